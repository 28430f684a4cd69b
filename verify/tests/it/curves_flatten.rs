//! Adaptive flattening (seed 002, method 2): every curve point within the
//! tolerance of the polyline (dense samples), for cubic and higher degrees,
//! in f64 and MPFR; de Casteljau subdivision invariance; segment counts of
//! adaptive vs uniform sampling on closed forms.

use crate::common;
use common::strategies::{grid_points, near_coincident_points};
use nalgebra::Vector2;
use proptest::prelude::*;
use splinelab::bernstein::bezier::Bezier;
use splinelab::curves::flatten::{flatten, uniform_polyline, uniform_segments};
use splinelab::curves::greedy_flatten::flatten_greedy;
use splinelab::scalar::prelude::*;
use splinelab_verify::curves::{flatten_excess, flatten_test_curves, frac};
use splinelab_verify::flatten_reference::{deviation_in_mpfr, greedy_reference_segments};
use splinelab_verify::metrics::{dist_ref, in_u};

fn curve<T: Real>(pts: &[[i32; 2]]) -> Bezier<T, 2> {
    Bezier::new(
        pts.iter()
            .map(|p| Vector2::new(T::from_int(p[0] as i64), T::from_int(p[1] as i64)))
            .collect(),
    )
    .unwrap()
}

fn control() -> impl Strategy<Value = Vec<[i32; 2]>> {
    grid_points::<2>(16, 4..12)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn every_curve_point_is_within_tol_of_the_polyline_f64(p in control(), k in 1i32..=5) {
        // Judged in 256-bit MPFR, hundreds of chords per case: tolerances
        // stop at 1e-5 and 8 samples per chord keep the test to seconds.
        let tol = 10f64.powi(-k);
        let (excess, _) = flatten_excess(&curve::<f64>(&p), &tol, 8).unwrap();
        prop_assert!(excess <= 1.0, "deviation / tol = {excess}");
    }

    #[test]
    fn every_curve_point_is_within_tol_of_the_polyline_mp128(p in control(), k in 1u32..=4) {
        // Fewer, coarser cases than f64: MPFR subdivision is ~100× slower.
        let tol = Mp::<128>::from_int(1) / Mp::from_int(10i64.pow(k));
        let (excess, _) = flatten_excess(&curve::<Mp<128>>(&p), &tol, 6).unwrap();
        prop_assert!(excess <= 1.0, "deviation / tol = {excess}");
    }

    #[test]
    fn subdivision_halves_reproduce_the_curve(p in control(), t in 1usize..64, s in 0usize..=16) {
        // L(s) = P(t s), R(s) = P(t + (1 − t) s): the f64 halves against the
        // curve evaluated in MPFR 128, the MPFR-128 halves against MPFR 256.
        let (t, s) = (frac::<f64>(t, 64), frac::<f64>(s, 16));
        let (left_at, right_at) = (t * s, t + (1.0 - t) * s);
        let (l, r) = curve::<f64>(&p).subdivide(&t).unwrap();
        let c128 = curve::<Mp<128>>(&p);
        let reference = |c: &Bezier<Mp<128>, 2>, u: f64| c.eval(&Mp::<128>::from(u)).unwrap();
        let lift = |v: Vector2<f64>| Vector2::new(Mp::<128>::from(v.x), Mp::from(v.y));
        // t·s and t + (1 − t)s are exact in f64 (t = k/64, s = j/16).
        for (half, at) in [(&l, left_at), (&r, right_at)] {
            let got = lift(half.eval(&s).unwrap());
            prop_assert!(in_u::<f64>(&dist_ref(&got, &reference(&c128, at)), 16.0) <= 256.0);
        }
        let (tm, sm) = (Mp::<128>::from(t), Mp::<128>::from(s));
        let (lm, rm) = c128.subdivide(&tm).unwrap();
        let c256 = curve::<Mp<256>>(&p);
        for (half, at) in [(&lm, left_at), (&rm, right_at)] {
            let v = half.eval(&sm).unwrap();
            let got = Vector2::new(v.x.convert::<Mp<256>>(), v.y.convert());
            let want = c256.eval(&Mp::<256>::from(at)).unwrap();
            prop_assert!(in_u::<Mp<128>>(&dist_ref(&got, &want), 16.0) <= 256.0);
        }
    }
}

#[test]
fn uniform_count_is_the_smallest_passing_count() {
    // Degree 10 zig-zag: the returned m passes, m − 1 does not.
    let pts: Vec<[i32; 2]> = (0..=10)
        .map(|i| [i, if i % 2 == 0 { 0 } else { 1 }])
        .collect();
    let c = curve::<f64>(&pts);
    for tol in [1e-2, 1e-4] {
        // Judged in 256-bit MPFR, not by the sampled distance the count is
        // bisected on (same 32 samples per segment, so the same maximum up
        // to the f64 rounding of each distance).
        let judge = |poly| deviation_in_mpfr(&c, &poly, 32).unwrap();
        let m = uniform_segments(&c, &tol, 32).unwrap();
        assert!(judge(uniform_polyline(&c, m).unwrap()) <= tol * (1.0 + 1e-14));
        assert!(judge(uniform_polyline(&c, m - 1).unwrap()) > tol);
        assert!(judge(flatten(&c, &tol).unwrap()) <= tol);
    }
}

#[test]
fn cubic_counts_scale_like_the_inverse_square_root_of_tol() {
    // Both methods converge with order 2: 100× smaller tol needs ≈ 10× more
    // segments (between 5× and 20× allowing for the discrete counts).
    let c = curve::<f64>(&[[0, 0], [1, 2], [3, -1], [4, 1]]);
    for f in [
        |c: &Bezier<f64, 2>, t: f64| flatten(c, &t).unwrap().segments(),
        |c: &Bezier<f64, 2>, t: f64| uniform_segments(c, &t, 32).unwrap(),
    ] {
        let (a, b) = (f(&c, 1e-4), f(&c, 1e-6));
        assert!((5 * a..=20 * a).contains(&b), "{a} → {b}");
    }
}

// ---- near-optimal flattening (greedy chords under a proven bound) ---------

/// The test cubic (a near-cusp) and the study's curves.
fn greedy_test_curves() -> Vec<(String, Bezier<f64, 2>)> {
    let mut v = vec![(
        "near-cusp cubic".to_string(),
        Bezier::new(
            [[0.0, 0.0], [1.2, 2.0], [-0.2, 2.0], [1.0, 0.0]]
                .iter()
                .map(|p| Vector2::new(p[0], p[1]))
                .collect(),
        )
        .unwrap(),
    )];
    for (name, pts) in flatten_test_curves() {
        let c = Bezier::new(pts.iter().map(|p| Vector2::new(p[0], p[1])).collect()).unwrap();
        v.push((name, c));
    }
    v
}

/// On every test curve and tolerance 1e-2..1e-5: the greedy polyline is
/// within tol judged in 256-bit MPFR, never has more chords than uniform
/// sampling, and has at most 10% more than the greedy optimum under a
/// sampled true-distance check (`greedy_reference_segments`), or one more
/// chord where 10% is less than one (measured: 10 vs 9 on the near-cusp cubic
/// at 1e-2; 29 vs 27 at 1e-3 and 278 vs 269 at 1e-5).
#[test]
fn greedy_flattening_is_within_tol_below_uniform_and_near_the_optimum() {
    for (name, c) in greedy_test_curves() {
        for tol in [1e-2, 1e-3, 1e-4, 1e-5] {
            let poly = flatten_greedy(&c, &tol).unwrap();
            let got = poly.segments();
            let dev = deviation_in_mpfr(&c, &poly, 16).unwrap();
            assert!(dev <= tol, "{name} tol {tol:e}: deviation {dev:e}");
            let uniform = uniform_segments(&c, &tol, 64).unwrap();
            assert!(
                got <= uniform,
                "{name} tol {tol:e}: {got} > uniform {uniform}"
            );
            let optimum = greedy_reference_segments(&c, tol, 64).unwrap();
            assert!(
                got as f64 <= (1.1 * optimum as f64).max(optimum as f64 + 1.0),
                "{name} tol {tol:e}: {got} vs greedy optimum {optimum}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Random curves of degree 3..11 (near-degenerate ones included: repeated
    /// and collinear integer control points): every curve point within tol of
    /// the greedy polyline, judged in 256-bit MPFR, and never more chords
    /// than the seed's subdivision.
    #[test]
    fn greedy_polyline_is_within_tol_in_mpfr(p in control(), k in 1i32..=4) {
        let tol = 10f64.powi(-k);
        let c = curve::<f64>(&p);
        let poly = flatten_greedy(&c, &tol).unwrap();
        let dev = deviation_in_mpfr(&c, &poly, 6).unwrap();
        prop_assert!(dev <= tol, "deviation {dev:e} > tol {tol:e}");
        prop_assert!(poly.segments() <= flatten(&c, &tol).unwrap().segments());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Near-coincident control points (a cusp-like or degenerate control
    /// polygon): greedy flattening still keeps every point within tol,
    /// judged in 256-bit MPFR.
    #[test]
    fn greedy_flattening_holds_with_near_coincident_control_points(
        p in near_coincident_points::<2>(8, 4..9),
        k in 2i32..=4,
    ) {
        let tol = 10f64.powi(-k);
        let c = Bezier::new(p.iter().map(|q| Vector2::new(q[0], q[1])).collect()).unwrap();
        let poly = flatten_greedy(&c, &tol).unwrap();
        let dev = deviation_in_mpfr(&c, &poly, 16).unwrap();
        prop_assert!(dev <= tol, "deviation {dev:e} > tol {tol:e}");
    }
}
