//! The engine's guarantees against independent references: truncated and
//! block-parallel routes within their certified bound of the exact filter,
//! derivatives against finite differences in 256-bit MPFR, and the
//! interpolation condition at high degree against exact node values in
//! 512-bit MPFR.

use splinelab::ndarray::{Array1, Array2};
use splinelab::prelude::*;
use splinelab_verify::rng::SplitMix64;

/// A fixed pseudo-random signal in [−1, 1).
fn signal(n: usize, seed: u64) -> Vec<f64> {
    SplitMix64::new(seed).signal(n)
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

fn exact(d: u32, mode: Mode, s: &[f64]) -> (Vec<f64>, f64) {
    let f = LineFilter::<f64>::new(&SplineFamily::Order(d + 1), mode, 0.3, Route::Exact).unwrap();
    let mut c = s.to_vec();
    f.apply(&mut c, &mut Vec::new());
    (c, f.recursive().amplification())
}

#[test]
fn truncated_route_stays_within_its_certified_bound() {
    let s = signal(3000, 7);
    for d in [3u32, 5, 9] {
        for mode in Mode::ALL {
            for tol in [1e-4, 1e-8, 1e-13] {
                let (want, amp) = exact(d, mode, &s);
                let f = LineFilter::<f64>::new(
                    &SplineFamily::Order(d + 1),
                    mode,
                    0.3,
                    Route::Truncated { tol },
                )
                .unwrap();
                assert!(f.bound() < tol);
                let mut got = s.clone();
                f.apply(&mut got, &mut Vec::new());
                let diff = max_diff(&got, &want);
                // max|s_ext| ≤ 1; rounding of both routes ≤ 64 u A.
                let allowed = f.bound() + 64.0 * f64::EPSILON * amp;
                assert!(
                    diff <= allowed,
                    "d={d} {mode} tol={tol:e}: {diff:e} > {allowed:e}"
                );
                // And the bound is not vacuous: the difference is of its order for loose tol.
                if tol == 1e-4 {
                    assert!(diff > f.bound() * 1e-4, "d={d} {mode}: {diff:e}");
                }
            }
        }
    }
}

#[test]
fn parallel_blocks_stay_within_the_bound_of_the_sequential_filter() {
    let s = signal(50_000, 11);
    for d in [3u32, 5] {
        for mode in [Mode::Mirror, Mode::Nearest, Mode::GridWrap] {
            for tol in [1e-6, 1e-12] {
                let (want, amp) = exact(d, mode, &s);
                let f = BlockPrefilter::<f64>::new(&SplineFamily::Order(d + 1), mode, 0.3, tol)
                    .unwrap();
                // Small windows; windows of WINDOW with a ragged last group.
                for block in [4096, 40_000] {
                    let got = f.apply(&s, block).unwrap();
                    let diff = max_diff(&got, &want);
                    let allowed = f.bound() + 64.0 * f64::EPSILON * amp;
                    assert!(
                        diff <= allowed,
                        "d={d} {mode} tol={tol:e} block={block}: {diff:e} > {allowed:e}"
                    );
                }
            }
        }
    }
}

#[test]
fn parallel_blocks_report_the_first_non_finite_sample() {
    let mut s = signal(50_000, 5);
    s[41_234] = f64::NAN;
    s[45_000] = f64::INFINITY;
    let f = BlockPrefilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, 1e-9).unwrap();
    let err = f.apply(&s, 4096).unwrap_err();
    assert_eq!(
        err.to_string(),
        PrefilterError::NonFinite(41_234).to_string()
    );
}

#[test]
fn derivatives_match_mpfr_finite_differences() {
    type W = Mp<256>;
    let s = signal(40, 3);
    let data = Array1::from(s.clone());
    let wide = data.mapv(W::from_f64_exact);
    for d in [2u32, 3, 5, 7] {
        let opts = Options::new(d, Mode::Mirror);
        let f: Interpolant<f64> = Interpolant::new(&data, opts).unwrap();
        let g: Interpolant<W> = Interpolant::new(&wide, opts).unwrap();
        let h = 2f64.powi(-24);
        for x in [3.25, 17.6, 20.0 + 1.0 / 3.0, 38.9] {
            // Central difference in 256 bits: error O(h²) ≈ 1e-14 of f'''.
            let fd = (g.eval(&[x + h]).unwrap() - g.eval(&[x - h]).unwrap())
                / W::from_f64_exact(2.0 * h);
            let d1 = f.eval_derivative(&[x], &[1]).unwrap();
            assert!(
                (d1 - fd.to_f64()).abs() < 1e-9,
                "d={d} x={x}: {d1} vs {}",
                fd.to_f64()
            );
            let d1w = g.eval_derivative(&[x], &[1]).unwrap();
            assert!((d1w - fd).to_f64().abs() < 1e-9);
            if d >= 3 {
                let fd2 = (g.eval_derivative(&[x + h], &[1]).unwrap()
                    - g.eval_derivative(&[x - h], &[1]).unwrap())
                    / W::from_f64_exact(2.0 * h);
                let d2 = f.eval_derivative(&[x], &[2]).unwrap();
                assert!((d2 - fd2.to_f64()).abs() < 1e-8, "d={d} x={x}: {d2}");
            }
        }
        assert!(f.eval_derivative(&[1.0], &[d + 1]).is_err());
    }
    // Mixed partial of a 2-D bilinear-in-each-axis reproduction: data x·y
    // on a periodic-free interior point: ∂²(xy)/∂x∂y = 1 for a cubic spline
    // away from the ends (mirror breaks linearity only near them).
    let grid = Array2::from_shape_fn((30, 30), |(i, j)| (i * j) as f64);
    let f: Interpolant<f64> = Interpolant::new(&grid, Options::new(3, Mode::Mirror)).unwrap();
    let v = f.eval_derivative(&[14.3, 15.7], &[1, 1]).unwrap();
    assert!((v - 1.0).abs() < 1e-5, "{v}");
}

/// max_j |Σ_i D_i β(j − i) − s_j| in 512 bits from the exact node
/// values, `D` extended by the mirror rule.
fn residual<T: Real>(d: &[T], s: &[f64], order: u32) -> f64 {
    splinelab_verify::interpolation_residual::residual(d, s, order, Mode::Mirror).unwrap()
}

fn coefficients<T: Real + Send + Sync>(s: &[f64], order: u32) -> Vec<T> {
    let f =
        LineFilter::<T>::new(&SplineFamily::Order(order), Mode::Mirror, 0.0, Route::Exact).unwrap();
    let mut c: Vec<T> = s.iter().map(|x| T::from_f64_exact(*x)).collect();
    f.apply(&mut c, &mut Vec::new());
    c
}

#[test]
fn high_degrees_satisfy_the_interpolation_condition() {
    let s = signal(48, 5);
    for degree in [7u32, 9, 15, 31, 57, 99] {
        let m = degree + 1;
        let c256 = coefficients::<Mp<256>>(&s, m);
        let d256 = c256.iter().fold(0.0f64, |a, x| a.max(x.to_f64().abs()));
        let r256 = residual(&c256, &s, m);
        // Relative to max|D| always; relative to max|s| (≤ 1) up to degree
        // 57 — at 99 the rounding of the coefficients themselves leaves
        // 3.9e-60 of max|s| (measured), just above 1e-60.
        assert!(
            r256 < 1e-60 * d256,
            "degree {degree}: 256-bit residual {r256:e}"
        );
        if degree <= 57 {
            assert!(r256 < 1e-60, "degree {degree}: 256-bit residual {r256:e}");
        }
        let c128 = coefficients::<Mp<128>>(&s, m);
        let dmax = c128.iter().fold(0.0f64, |a, x| a.max(x.to_f64().abs()));
        let r128 = residual(&c128, &s, m);
        assert!(
            r128 < 16.0 * 2f64.powi(-128) * dmax,
            "degree {degree}: 128-bit residual {r128:e}"
        );
        let f = RecursivePrefilter::<f64>::new(&SplineFamily::Order(m)).unwrap();
        if degree <= 31 {
            // Backward error: the rounding of coefficients of size max|D|
            // (up to 1/|V(−1)| · max|s|) alone leaves a residual ~ u max|D|.
            let c = coefficients::<f64>(&s, m);
            let dmax = c.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            let r64 = residual(&c, &s, m);
            assert!(
                r64 < 16.0 * f64::EPSILON * dmax,
                "degree {degree}: f64 residual {r64:e}, max|D| {dmax:e}"
            );
            assert!(RecursivePrefilter::<f64>::new_within(&SplineFamily::Order(m), 1e-8).is_ok());
        } else {
            // f64 cannot carry these coefficients meaningfully: refused.
            assert!(f.estimated_error() > 1e-8);
            assert!(RecursivePrefilter::<f64>::new_within(&SplineFamily::Order(m), 1e-8).is_err());
        }
    }
}

/// `grid-constant` far outside the grid: every window reads only the
/// constant, so the value is the one at a moderately far point (scipy:
/// `cval`'s spline), never a panic or an overflowed index — up to ±f64::MAX.
#[test]
fn grid_constant_far_points_read_the_constant_and_never_overflow() {
    let data = Array2::from_shape_fn((12, 9), |(i, j)| (i as f64 * 0.7).sin() + j as f64);
    for d in [1u32, 3, 5] {
        let f: Interpolant<f64> =
            Interpolant::new(&data, Options::new(d, Mode::GridConstant)).unwrap();
        let near = f.eval(&[-1e6, 4.5]).unwrap();
        for far in [-1e12, -1e19, -1e308, -f64::MAX] {
            assert_eq!(f.eval(&[far, 4.5]).unwrap(), near, "degree {d} at {far}");
        }
        let near = f.eval(&[3.25, 1e6]).unwrap();
        for far in [1e12, 1e19, 1e308, f64::MAX] {
            assert_eq!(f.eval(&[3.25, far]).unwrap(), near, "degree {d} at {far}");
        }
        // The batch path agrees.
        let pts = Array2::from_shape_vec((2, 2), vec![-1e308, 4.5, 3.25, 1e308]).unwrap();
        let mut out = [0.0; 2];
        f.eval_many(pts.view(), &mut out).unwrap();
        assert_eq!(out, [f.eval(&[-1e6, 4.5]).unwrap(), near]);
    }
}
