//! The deterministic inputs of the curves study: random dyadic points,
//! exact fractions, the circle study's arcs, the Catmull–Rom loop example
//! and the flattening test curves.

use crate::rng::SplitMix64;
use nalgebra::{SVector, Vector2};
use splinelab::scalar::prelude::*;

/// A random point with dyadic coordinates in `[−range, range]`.
pub(super) fn random_point<T: Real, const D: usize>(
    rng: &mut SplitMix64,
    range: f64,
) -> SVector<T, D> {
    SVector::from_fn(|_, _| T::from_f64_exact(rng.dyadic(range)))
}

/// `j / m` in `T` (correctly rounded).
pub fn frac<T: Real>(j: usize, m: usize) -> T {
    T::from_int(j as i64) / T::from_int(m as i64)
}

/// The arcs of the circle study: starts `kπ/7` (`k = 0..6`) and sweeps
/// `π/8, π/3, π/2, 2π/3, 5π/6, π` (up to 180°).
pub fn study_arcs<T: Real>() -> Vec<(T, T)> {
    let pi = T::pi();
    let sweeps = [(1, 8), (1, 3), (1, 2), (2, 3), (5, 6), (1, 1)];
    (0..7)
        .flat_map(|k| {
            let pi = pi.clone();
            sweeps
                .iter()
                .map(move |&(a, b)| (pi.clone() * frac::<T>(k, 7), pi.clone() * frac::<T>(a, b)))
        })
        .collect()
}

/// The classic counter-example for uniform Catmull–Rom: the middle segment
/// from `(0, 0)` to `(1, 0)` with far outer points `(−11, −6)` and
/// `(12, −6)`. Uniform tangents `(P_2 − P_0)/2 = (6, 3)` and
/// `(P_3 − P_1)/2 = (6, −3)` give Bézier inner points `(2, 1)` and
/// `(−1, 1)`, which cross: the segment loops. Centripetal spacing shrinks
/// the tangents by the knot ratio and cannot loop (Yuksel–Schaefer–Keyser,
/// *Parameterization and applications of Catmull–Rom curves*, CAD 2011).
pub fn loop_example<T: Real>() -> Vec<Vector2<T>> {
    [(-11, -6), (0, 0), (1, 0), (12, -6)]
        .iter()
        .map(|&(x, y)| Vector2::new(T::from_int(x), T::from_int(y)))
        .collect()
}

/// The Bézier curves of the flattening comparison: a cubic S-curve and a
/// degree-10 zig-zag, both with dyadic control points.
pub fn flatten_test_curves() -> Vec<(String, Vec<[f64; 2]>)> {
    let cubic = vec![[0.0, 0.0], [1.0, 2.0], [3.0, -1.0], [4.0, 1.0]];
    let deg10 = (0..=10)
        .map(|i| {
            [
                i as f64,
                if i % 2 == 0 {
                    0.0
                } else {
                    1.0 + i as f64 / 8.0
                },
            ]
        })
        .collect();
    vec![("cubic".into(), cubic), ("degree-10".into(), deg10)]
}
