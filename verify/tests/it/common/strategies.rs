//! Shared proptest strategies: the inputs every property test draws from,
//! including the near-degenerate ones where numerical code breaks
//! (near-coincident points, near-multiple roots, values a few ulps apart).
//! One place, so that a new test gets the adversarial cases for free.

use proptest::prelude::*;
use rug::Rational;
use splinelab_verify::bezier_eval::product_of_roots;

/// Finite f64s spread over many binades (including tiny and huge ones).
pub fn finite_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        (-1e300f64..1e300),
        (-1.0f64..1.0),
        (any::<i32>(), -300i32..300).prop_map(|(m, e)| m as f64 * 2f64.powi(e)),
    ]
}

/// `len` values within `ulps` units in the last place of `base` (a signal
/// that is constant up to rounding: every difference cancels).
pub fn ulp_close_values(
    len: impl Into<prop::collection::SizeRange>,
    ulps: i64,
) -> impl Strategy<Value = Vec<f64>> {
    let len = len.into();
    (
        finite_f64().prop_filter("normal", |x| x.is_normal()),
        Just(len),
    )
        .prop_flat_map(move |(base, len)| {
            prop::collection::vec(-ulps..=ulps, len)
                .prop_map(move |d| d.into_iter().map(|k| nudge(base, k)).collect())
        })
}

/// `x` moved by `k` ulps (`k` steps of `next_up` / `next_down`).
pub fn nudge(x: f64, k: i64) -> f64 {
    (0..k.unsigned_abs()).fold(x, |y, _| if k > 0 { y.next_up() } else { y.next_down() })
}

/// Points of a `D`-dimensional integer grid `[-r, r]^D` (exact in every
/// precision, so references need no rounding argument).
pub fn grid_points<const D: usize>(
    r: i32,
    len: impl Into<prop::collection::SizeRange>,
) -> impl Strategy<Value = Vec<[i32; D]>> {
    prop::collection::vec(prop::array::uniform::<_, D>(-r..=r), len)
}

/// Grid points where some consecutive points are pulled to within a few
/// ulps of each other (near-coincident control or data points): each point is
/// a grid point, or its predecessor moved by at most 4 ulps per coordinate.
pub fn near_coincident_points<const D: usize>(
    r: i32,
    len: impl Into<prop::collection::SizeRange>,
) -> impl Strategy<Value = Vec<[f64; D]>> {
    let len = len.into();
    prop::collection::vec(
        (
            prop::array::uniform::<_, D>(-r..=r),
            any::<bool>(),
            prop::array::uniform::<_, D>(-4i64..=4),
        ),
        len,
    )
    .prop_map(|raw| {
        let mut out: Vec<[f64; D]> = Vec::with_capacity(raw.len());
        for (grid, collapse, ulps) in raw {
            let p = match out.last() {
                Some(prev) if collapse => std::array::from_fn(|i| nudge(prev[i], ulps[i])),
                _ => grid.map(f64::from),
            };
            out.push(p);
        }
        out
    })
}

/// Bernstein coefficients (rounded to f64) of `∏ (t − r_k)`, the roots on a
/// `1/64` grid of `[0, 1]` and possibly repeated: multiple and clustered
/// roots, where evaluation is ill-conditioned.
pub fn near_multiple_roots(max_roots: usize) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(0u32..=64, 1..=max_roots).prop_map(|r| {
        let q: Vec<Rational> = r.iter().map(|&k| Rational::from((k, 64))).collect();
        product_of_roots(&q).iter().map(Rational::to_f64).collect()
    })
}

/// A parameter `t`: uniform in `[0, 1]`, within `2^−e` (e < 45) of a
/// `1/64`-grid point (next to the roots of [`near_multiple_roots`]), or
/// extrapolated to `[−½, 1½]`.
pub fn parameter() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => 0.0f64..=1.0,
        3 => (0u32..=64, -1.0f64..1.0, 0i32..45)
            .prop_map(|(k, d, e)| (k as f64 / 64.0 + d * 2f64.powi(-e)).clamp(0.0, 1.0)),
        1 => -0.5f64..1.5,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;

    #[test]
    fn ulp_close_values_are_within_their_ulps() {
        let mut runner = TestRunner::deterministic();
        for _ in 0..200 {
            let v = ulp_close_values(2..8, 3)
                .new_tree(&mut runner)
                .unwrap()
                .current();
            let (lo, hi) = v
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            // At most 6 ulps apart (± 3 from one base), and not all equal in general.
            assert!(nudge(lo, 6) >= hi, "{v:?}");
        }
    }

    #[test]
    fn near_coincident_points_do_collapse() {
        let mut runner = TestRunner::deterministic();
        let mut close = 0;
        for _ in 0..100 {
            let p = near_coincident_points::<2>(8, 4..8)
                .new_tree(&mut runner)
                .unwrap()
                .current();
            close += p
                .windows(2)
                .filter(|w| (0..2).all(|i| (w[0][i] - w[1][i]).abs() <= 8.0 * f64::EPSILON * 8.0))
                .count();
        }
        assert!(close > 50, "{close}");
    }
}
