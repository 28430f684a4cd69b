//! The engine's guarantees against independent references: truncated and
//! block-parallel routes within their certified bound of the exact filter,
//! derivatives against finite differences in 256-bit MPFR, and the
//! interpolation condition at high degree against exact node values in
//! 512-bit MPFR.

use splinelab::ndarray::{Array1, Array2};
use splinelab::prelude::*;
use splinelab::validation::NonFiniteValue;
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
                let routes = [Route::Truncated { tol }, Route::Convolution { tol }];
                for route in routes {
                    let f = LineFilter::<f64>::new(&SplineFamily::Order(d + 1), mode, 0.3, route)
                        .unwrap();
                    assert!(f.bound() < tol);
                    let mut got = s.clone();
                    f.apply(&mut got, &mut Vec::new());
                    let diff = max_diff(&got, &want);
                    // max|s_ext| ≤ 1; rounding of both routes ≤ 64 u A.
                    let allowed = f.bound() + 64.0 * f64::EPSILON * amp;
                    assert!(
                        diff <= allowed,
                        "d={d} {mode} {route:?}: {diff:e} > {allowed:e}"
                    );
                    // And the bound is not vacuous: the convolution's difference is
                    // of its order for loose tol (one line, the truncated route runs
                    // the exact recursion: its blocks are tested on long lines below).
                    if tol == 1e-4 && f.is_convolution() {
                        assert!(diff > f.bound() * 1e-4, "d={d} {mode}: {diff:e}");
                    }
                }
            }
        }
    }
}

/// The truncated route on one long line (`spline_filter1d` of a 1-D array,
/// which runs certified blocks on the pool) against the exact coefficients
/// computed in 128-bit MPFR: within `bound · max|s|` plus the f64 rounding
/// of the recursion (`64 u A`), for every mode; and at a loose tolerance the
/// difference is real (the blocks ran), of the order of the bound.
#[test]
fn truncated_blocks_match_mpfr_within_the_bound() {
    type W = Mp<128>;
    let s = signal(60_000, 23);
    let wide: Vec<W> = s.iter().map(|x| W::from_f64_exact(*x)).collect();
    for d in [3u32, 5] {
        let family = SplineFamily::Order(d + 1);
        for mode in Mode::ALL {
            let fw = LineFilter::<W>::new(&family, mode, 0.3, Route::Exact).unwrap();
            let mut want = wide.clone();
            fw.apply(&mut want, &mut Vec::new());
            let want: Vec<f64> = want.iter().map(|x| x.to_f64()).collect();
            let amp = fw.recursive().amplification().to_f64();
            for tol in [1e-4, 1e-12] {
                let f =
                    LineFilter::<f64>::new(&family, mode, 0.3, Route::Truncated { tol }).unwrap();
                let blocks = BlockPrefilter::from_line_filter(&f).unwrap();
                assert!(blocks.pays_off(s.len()) && f.bound() < tol);
                let mut got = Array1::from_vec(s.clone());
                spline_filter1d(&mut got, 0, &f).unwrap();
                let diff = max_diff(got.as_slice().unwrap(), &want);
                // max|s_ext| ≤ max(1, |cval|) = 1.
                let allowed = f.bound() + 64.0 * f64::EPSILON * amp;
                assert!(
                    diff <= allowed,
                    "d={d} {mode} tol={tol:e}: {diff:e} > {allowed:e}"
                );
                if tol == 1e-4 {
                    assert!(diff > f.bound() * 1e-3, "d={d} {mode}: {diff:e}");
                }
            }
        }
    }
}

/// [`spline_filter_from`] (copy, checks and filter on the pool) gives what
/// filtering a copy in place gives, bit for bit, exact and truncated, 2-D
/// and 3-D, a single axis or every axis; and the same errors.
#[test]
fn filtering_a_copy_equals_filtering_in_place() {
    use splinelab::ndarray::Array3;
    use splinelab::ndimage::nd_prefilter::spline_filter_from;
    let plane = Array2::from_shape_vec((37, 53), signal(37 * 53, 2)).unwrap();
    let cube = Array3::from_shape_vec((9, 17, 13), signal(9 * 17 * 13, 4)).unwrap();
    for route in [Route::Exact, Route::Truncated { tol: 1e-9 }] {
        let f = LineFilter::<f64>::new(&SplineFamily::Order(6), Mode::Nearest, 0.0, route).unwrap();
        let mut want = plane.clone();
        spline_filter(&mut want, &f).unwrap();
        let mut got = Array2::zeros(plane.raw_dim());
        spline_filter_from(&plane, &mut got, &[0, 1], Some(&f)).unwrap();
        assert_eq!(got, want, "{route:?}");
        let mut want = cube.clone();
        spline_filter1d(&mut want, 1, &f).unwrap();
        let mut got = Array3::zeros(cube.raw_dim());
        spline_filter_from(&cube, &mut got, &[1], Some(&f)).unwrap();
        assert_eq!(got, want, "{route:?}");
        // A transposed (non-contiguous) source goes the strided way.
        let mut want = plane.t().as_standard_layout().into_owned();
        spline_filter(&mut want, &f).unwrap();
        let mut got = Array2::zeros(want.raw_dim());
        spline_filter_from(&plane.t(), &mut got, &[0, 1], Some(&f)).unwrap();
        assert_eq!(got, want, "{route:?} transposed");
    }
    let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact)
        .unwrap()
        .with_nan_policy(NanPolicy::Raise)
        .unwrap();
    let mut bad = plane.clone();
    bad[[20, 7]] = f64::NAN;
    let mut out = Array2::zeros(bad.raw_dim());
    let err = spline_filter_from(&bad, &mut out, &[0, 1], Some(&f)).unwrap_err();
    assert_eq!(
        err,
        NdimageError::NonFinite {
            index: 20 * 53 + 7,
            value: NonFiniteValue::Nan
        }
    );
    assert_eq!(spline_filter(&mut bad, &f).unwrap_err(), err);
    let big = Array2::from_elem((3, 3), 1e308);
    let mut out = Array2::zeros((3, 3));
    let err = spline_filter_from(&big, &mut out, &[0, 1], Some(&f)).unwrap_err();
    assert!(
        matches!(err, NdimageError::Overflow { max, .. } if max == 1e308),
        "{err}"
    );
    let mut short = Array2::zeros((3, 4));
    assert!(matches!(
        spline_filter_from(&big, &mut short, &[0], Some(&f)),
        Err(NdimageError::BufferLength { .. })
    ));
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

/// A quintic line larger than L3 (over 32 MiB: `lanes::STREAM_BYTES`),
/// whose blocks write their coefficients by streaming stores (two poles
/// or more), into an output
/// that starts off a cache line (as numpy's do): within the certified
/// bound of the sequential exact filter, as the cached stores are.
#[test]
fn streamed_blocks_stay_within_the_bound_of_the_sequential_filter() {
    let s = signal(4_500_000, 13);
    let (want, amp) = exact(5, Mode::Mirror, &s);
    let f = BlockPrefilter::<f64>::new(&SplineFamily::Order(6), Mode::Mirror, 0.3, 1e-12).unwrap();
    for off in [0, 1, 3] {
        let mut out = vec![f64::NAN; s.len() + off];
        f.apply_line_into(&s, &mut out[off..]).unwrap();
        let diff = max_diff(&out[off..], &want);
        let allowed = f.bound() + 64.0 * f64::EPSILON * amp;
        assert!(diff <= allowed, "offset {off}: {diff:e} > {allowed:e}");
    }
}

#[test]
fn parallel_blocks_report_the_first_non_finite_sample() {
    let mut s = signal(50_000, 5);
    s[41_234] = f64::NAN;
    s[45_000] = f64::INFINITY;
    let f = BlockPrefilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, 1e-9)
        .unwrap()
        .with_nan_policy(NanPolicy::Raise)
        .unwrap();
    let err = f.apply(&s, 4096).unwrap_err();
    assert_eq!(err.to_string(), "sample 41234 is not finite (nan)");
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
        // The normwise relative residual (backward error, Rigal–Gaches)
        // max|s − B D| / (‖B‖∞ max|D|), ‖B‖∞ = 1 (the B-splines sum to 1),
        // below 1e-60 at every degree; relative to max|s| (≤ 1) up to degree
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

/// The reference of `nearest` at `W`'s precision: the samples padded by
/// `pad` copies of their end samples on every side, interpolated under
/// `mirror` (whose ends then lie `pad` samples away, influence
/// `≤ ρ^{2·pad}`), evaluated at `x + pad` (exact for the dyadic points
/// used). A second route to the edge-extended spline: no nearest-specific
/// code runs. Beyond `pad/2` outside the spline is constant to `ρ^{pad/2}`:
/// points are clamped there.
fn nearest_reference<W: Real + Send + Sync, D: splinelab::ndarray::Dimension>(
    data: &splinelab::ndarray::Array<f64, D>,
    d: u32,
    pad: usize,
) -> impl Fn(&[f64], &[u32]) -> f64 {
    let shape = data.shape().to_vec();
    let big: Vec<usize> = shape.iter().map(|n| n + 2 * pad).collect();
    let padded = splinelab::ndarray::ArrayD::from_shape_fn(big, |i| {
        let at: Vec<usize> = (0..shape.len())
            .map(|a| i[a].saturating_sub(pad).min(shape[a] - 1))
            .collect();
        W::from_f64_exact(data.view().into_dyn()[at.as_slice()])
    });
    let f: Interpolant<W> = Interpolant::new(&padded, Options::new(d, Mode::Mirror)).unwrap();
    let h = pad as f64 / 2.0;
    move |x, deriv| {
        let at: Vec<f64> = (0..shape.len())
            .map(|a| x[a].clamp(-h, shape[a] as f64 - 1.0 + h) + pad as f64)
            .collect();
        f.eval_derivative(&at, deriv).unwrap().to_f64()
    }
}

/// `nearest` evaluates the spline of the edge-extended signal outside the
/// grid too (scipy's map_coordinates approximates it by padding 12 edge
/// samples; it used to return the end sample), values and first
/// derivatives, near the grid and far away (up to ±1e300): 2-D in f64
/// against a 128-bit reference, the batch path too; 1-D in 256-bit MPFR
/// against a 256-bit reference.
#[test]
fn nearest_outside_the_grid_is_the_edge_extended_spline() {
    type W = splinelab::scalar::Mp<256>;
    let data = Array2::from_shape_fn((9, 7), |(i, j)| ((i * 7 + j * 3) % 11) as f64 - 4.0);
    // Dyadic points, so that `x + pad` is exact in the reference.
    let pts = [
        [-3.3125, 2.5],
        [-0.40625, -1.6875],
        [4.0, 8.59375],
        [10.203125, 6.5],
        [-25.0, 3.125],
        [1e6, -1e300],
        [3.5, 1e12],
    ];
    let line = Array1::from_vec(vec![1.0, 5.0, 2.0, 7.0, 3.0, 9.0, 4.0, 0.0, 6.0]);
    let line_hi = line.mapv(W::from_f64_exact);
    for d in [2u32, 3, 5, 9] {
        let f: Interpolant<f64> = Interpolant::new(&data, Options::new(d, Mode::Nearest)).unwrap();
        let g = Interpolant::new(&line_hi, Options::new(d, Mode::Nearest)).unwrap();
        let reference = nearest_reference::<splinelab::scalar::Mp<128>, _>(&data, d, 160);
        let reference_hi = nearest_reference::<W, _>(&line, d, 800);
        for x in &pts {
            for deriv in [[0, 0], [1, 0], [0, 1]] {
                let want = reference(x, &deriv);
                let got = f.eval_derivative(x, &deriv).unwrap();
                // f64: a few ulps of max|D| (max|s| = 6, amplification ≤ 20).
                assert!(
                    (got - want).abs() < 1e-12,
                    "degree {d} at {x:?} d{deriv:?}: {got} vs {want}"
                );
            }
            for deriv in [0, 1] {
                let want = reference_hi(&x[..1], &[deriv]);
                let hi = g.eval_derivative(&x[..1], &[deriv]).unwrap().to_f64();
                assert!(
                    (hi - want).abs() <= 1e-60,
                    "MPFR degree {d} at {} d{deriv}: {hi} vs {want}",
                    x[0]
                );
            }
        }
        // Next to the ends the spline is not the end sample (it was clamped).
        let edge = f.eval(&[-0.5, 3.0]).unwrap();
        assert!((edge - data[(0, 3)]).abs() > 1e-3, "degree {d}: {edge}");
        let flat = Array2::from_shape_vec((pts.len(), 2), pts.concat()).unwrap();
        let mut out = vec![0.0; pts.len()];
        f.eval_many(flat.view(), &mut out).unwrap();
        for (x, v) in pts.iter().zip(&out) {
            assert!((v - f.eval(x).unwrap()).abs() < 1e-12, "batch at {x:?}");
        }
    }
}

/// Data the filter could overflow is a typed error, not a silent inf/NaN
/// (f64 `[1e308, −1e308, …]` gave `[inf, −inf, …]`, a 3×3 array of 1e308
/// NaNs): the limit is `MAX / growth^axes` with the growth bound
/// `gain · Π(2/(1 − |z|))²`; just below it the coefficients are finite and
/// satisfy the interpolation condition (checked against the exact values
/// scaled down by a power of two, which the filter commutes with exactly).
#[test]
fn data_that_could_overflow_is_refused_and_data_below_the_limit_is_exact() {
    let f =
        LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
    // The cubic's bound in closed form: 6 · (2/(1 − (2 − √3)))².
    let g = 6.0 * (2.0 / (1.0 - (2.0 - 3f64.sqrt()))).powi(2);
    assert!((f.growth() - g).abs() < 1e-12 * g, "{} vs {g}", f.growth());
    let mut big = Array1::from_vec(vec![1e308, -1e308, 1e308, 0.0, 1.0]);
    let e = spline_filter1d(&mut big, 0, &f).unwrap_err();
    assert!(
        matches!(e, NdimageError::Overflow { max, .. } if max == 1e308),
        "{e}"
    );
    let mut grid = Array2::from_elem((3, 3), 1e308);
    assert!(matches!(
        spline_filter(&mut grid, &f),
        Err(NdimageError::Overflow { .. })
    ));
    assert!(Interpolant::<f64>::new(&grid, Options::new(3, Mode::Mirror)).is_err());
    // Just below the limit (a power of two): finite, and exactly 2^k times
    // the coefficients of the unit-scale data.
    let k = (f64::MAX / g).log2().floor() as i32;
    let s = signal(40, 3);
    let mut scaled = Array1::from_iter(s.iter().map(|x| x * 2f64.powi(k)));
    spline_filter1d(&mut scaled, 0, &f).unwrap();
    let mut unit = Array1::from_vec(s.clone());
    spline_filter1d(&mut unit, 0, &f).unwrap();
    for (a, b) in scaled.iter().zip(&unit) {
        assert!(a.is_finite() && *a == b * 2f64.powi(k), "{a} vs {b}·2^{k}");
    }
    // f32: the limit is f32::MAX / growth; MPFR never refuses.
    let f32f =
        LineFilter::<f32>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
    let mut x32 = Array1::from_vec(vec![1e37f32, -1e37, 2.0]);
    assert!(matches!(
        spline_filter1d(&mut x32, 0, &f32f),
        Err(NdimageError::Overflow { .. })
    ));
    type W = splinelab::scalar::Mp<64>;
    let fw =
        LineFilter::<W>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
    let mut xw = Array1::from_vec(vec![W::from_f64_exact(1e308); 5]);
    spline_filter1d(&mut xw, 0, &fw).unwrap();
    assert!((xw[2].to_f64() - 1e308).abs() < 1e295);
}
