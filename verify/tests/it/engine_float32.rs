//! The float32 data route (issue 42): `f32` samples computed in `f64` as
//! scipy computes them, and results stored rounded once.
//!
//! - The samples are widened exactly as the engine reads them, so the
//!   `f64` interpolant of `f32` data is the `f64` interpolant of the
//!   widened data, bit for bit: coefficients and values, every mode,
//!   degrees 0 to 7, 1-D to 3-D, contiguous and strided inputs.
//! - `f32` results ([`Stored`]) are the `f64` results rounded once
//!   (`as f32`, round to nearest), bit for bit, on every evaluation path
//!   (scattered points, the separable grid, affine maps, derivatives).
//! - `f32` coefficients of an `f64` filter (`spline_filter_from_as`) are
//!   scipy's `spline_filter(output=float32)`: each axis filtered in `f64`
//!   from the previous axis' `f32` values and rounded once, checked
//!   against that algorithm written out lane by lane.

use splinelab::ndarray::{Array2, ArrayD, Axis, IxDyn};
use splinelab::ndimage::interpolant::PointRule;
use splinelab::ndimage::nd_prefilter::{spline_filter_from, spline_filter_from_as};
use splinelab::ndimage::samples::Stored;
use splinelab::prelude::*;
use splinelab_verify::rng::SplitMix64;

const SHAPES: [&[usize]; 5] = [&[23], &[1], &[9, 14], &[6, 1, 11], &[7, 8, 9]];

/// Samples of `shape` rounded to `f32` (normal noise scaled by 3, some
/// exact zeros and tiny values: zero crossings are where relative errors
/// grow).
fn data32(shape: &[usize], seed: u64) -> ArrayD<f32> {
    let total = shape.iter().product();
    let mut r = SplitMix64::new(seed);
    let v = (0..total)
        .map(|k| match k % 13 {
            4 => 0.0,
            9 => (r.range(-1.0, 1.0) * 1e-6) as f32,
            _ => (r.range(-3.0, 3.0)) as f32,
        })
        .collect();
    ArrayD::from_shape_vec(IxDyn(shape), v).unwrap()
}

/// `count` points in `[−2, ν + 1]` per axis, every 17th on a grid point.
fn points(count: usize, shape: &[usize], seed: u64) -> Array2<f64> {
    let mut r = SplitMix64::new(seed);
    Array2::from_shape_fn((count, shape.len()), |(k, a)| {
        let n = shape[a] as f64;
        if k % 17 == 3 {
            (r.unit() * n).floor()
        } else {
            r.range(-2.0, n + 1.0)
        }
    })
}

fn bits64(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn bits32(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn rounded(v: &[f64]) -> Vec<u32> {
    v.iter()
        .map(|&x| <f32 as Stored<f64>>::store(&x).to_bits())
        .collect()
}

/// The `f64` interpolant of `f32` samples is that of the widened samples,
/// bit for bit (coefficients and values); its `f32` values are its `f64`
/// values rounded once.
#[test]
fn float32_data_through_the_f64_route_equals_the_widened_data() {
    for (s, shape) in SHAPES.iter().enumerate() {
        let a = data32(shape, 40 + s as u64);
        let wide = a.mapv(f64::from);
        let pts = points(700, shape, 7 + s as u64);
        for mode in Mode::ALL {
            for degree in 0..=7 {
                let opts = Options {
                    cval: 0.375,
                    ..Options::new(degree, mode)
                };
                let f = Interpolant::<f64>::from_samples(&a, opts).unwrap();
                let g = Interpolant::<f64>::new(&wide, opts).unwrap();
                let what = format!("{shape:?} {mode} degree {degree}");
                let (cf, cg): (Vec<f64>, Vec<f64>) = (
                    f.coefficients().iter().copied().collect(),
                    g.coefficients().iter().copied().collect(),
                );
                assert_eq!(bits64(&cf), bits64(&cg), "coefficients {what}");
                for rule in [PointRule::Fold, PointRule::CvalOutside] {
                    let (mut vf, mut vg) = (vec![0.0f64; 700], vec![0.0f64; 700]);
                    f.eval_many_with(pts.view(), rule, &mut vf).unwrap();
                    g.eval_many_with(pts.view(), rule, &mut vg).unwrap();
                    assert_eq!(bits64(&vf), bits64(&vg), "values {what} {rule:?}");
                    let mut v32 = vec![0.0f32; 700];
                    f.eval_many_with_as(pts.view(), rule, &mut v32).unwrap();
                    assert_eq!(bits32(&v32), rounded(&vf), "stored {what} {rule:?}");
                }
                // Given coefficients (prefilter=False) widened as they are copied.
                let h = Interpolant::<f64>::from_coefficients_of(&a, opts).unwrap();
                let k = Interpolant::<f64>::from_coefficients_with(&wide, opts).unwrap();
                let (mut vh, mut vk) = (vec![0.0f64; 700], vec![0.0f64; 700]);
                h.eval_many(pts.view(), &mut vh).unwrap();
                k.eval_many(pts.view(), &mut vk).unwrap();
                assert_eq!(bits64(&vh), bits64(&vk), "given {what}");
            }
        }
    }
}

/// Strided and transposed `f32` views read as their contiguous copies.
#[test]
fn strided_float32_views_read_as_their_copies() {
    let a = data32(&[12, 17], 3);
    let t = a.t();
    let every_other = a.slice_each_axis(|_| splinelab::ndarray::Slice::new(0, None, 2));
    for view in [t.view(), every_other.view()] {
        let copy = view.to_owned();
        for mode in [Mode::Mirror, Mode::Nearest, Mode::GridWrap] {
            let opts = Options::new(3, mode);
            let f = Interpolant::<f64>::from_samples(&view, opts).unwrap();
            let g = Interpolant::<f64>::new(&copy.mapv(f64::from), opts).unwrap();
            let (cf, cg): (Vec<f64>, Vec<f64>) = (
                f.coefficients().iter().copied().collect(),
                g.coefficients().iter().copied().collect(),
            );
            assert_eq!(bits64(&cf), bits64(&cg), "{mode} {:?}", view.strides());
        }
    }
}

/// The separable grid, affine maps and derivatives store `f32` values
/// that are the `f64` ones rounded once; a 1-D grid longer than one
/// gathering piece (2048) and 3-D rows.
#[test]
fn every_evaluation_path_stores_the_f64_value_rounded_once() {
    for shape in [&[4000usize][..], &[9, 14], &[6, 7, 8]] {
        let a = data32(shape, 5);
        for (mode, degree) in [
            (Mode::Mirror, 3),
            (Mode::Reflect, 5),
            (Mode::GridConstant, 1),
            (Mode::Nearest, 2),
        ] {
            let f = Interpolant::<f64>::from_samples(&a, Options::new(degree, mode)).unwrap();
            let axes: Vec<Vec<f64>> = shape
                .iter()
                .map(|&n| {
                    (0..(n * 3 / 2).max(2))
                        .map(|k| -1.3 + k as f64 * 0.71)
                        .collect()
                })
                .collect();
            let refs: Vec<&[f64]> = axes.iter().map(Vec::as_slice).collect();
            let count: usize = axes.iter().map(Vec::len).product();
            for deriv in [vec![0; shape.len()], {
                let mut d = vec![0; shape.len()];
                d[0] = 1;
                d
            }] {
                let (mut w, mut n) = (vec![0.0f64; count], vec![0.0f32; count]);
                f.resample_grid(&refs, &deriv, &mut w).unwrap();
                f.resample_grid_as(&refs, &deriv, &mut n).unwrap();
                assert_eq!(bits32(&n), rounded(&w), "grid {shape:?} {mode} {deriv:?}");
            }
            let nd = shape.len();
            let matrix: Vec<f64> = (0..nd * nd)
                .map(|i| if i % (nd + 1) == 0 { 0.93 } else { 0.11 })
                .collect();
            let offset: Vec<f64> = (0..nd).map(|h| 0.4 - h as f64).collect();
            let total: usize = shape.iter().product();
            for rule in [PointRule::Fold, PointRule::CvalOutside] {
                let (mut w, mut n) = (vec![0.0f64; total], vec![0.0f32; total]);
                f.resample_affine(&matrix, &offset, shape, 0.0, rule, &mut w)
                    .unwrap();
                f.resample_affine_as(&matrix, &offset, shape, 0.0, rule, &mut n)
                    .unwrap();
                assert_eq!(bits32(&n), rounded(&w), "affine {shape:?} {mode} {rule:?}");
            }
            if degree >= 1 {
                let pts = points(2500, shape, 9);
                let mut deriv = vec![0; nd];
                deriv[nd - 1] = 1;
                let (mut w, mut n) = (vec![0.0f64; 2500], vec![0.0f32; 2500]);
                f.eval_derivatives(pts.view(), &deriv, &mut w).unwrap();
                f.eval_derivatives(pts.view(), &deriv, &mut n).unwrap();
                assert_eq!(bits32(&n), rounded(&w), "derivatives {shape:?} {mode}");
                for (k, p) in pts.rows().into_iter().enumerate().step_by(97) {
                    let one = f.eval_derivative(p.as_slice().unwrap(), &deriv).unwrap();
                    assert_eq!(one.to_bits(), w[k].to_bits(), "{shape:?} {mode} at {p}");
                }
            }
        }
    }
}

/// scipy's `spline_filter(float32 input, output=float32)`: along each axis
/// in turn, the array read into f64, filtered along that axis (the f64
/// engine's own passes: the same operations on every line), rounded once
/// to f32. `lanes`: the first axis lane by lane ([`LineFilter::apply`]),
/// as the engine filters a source it cannot read by rows (a strided one).
fn per_axis_reference(
    a: &ArrayD<f32>,
    axes: &[usize],
    f: &LineFilter<f64>,
    lanes: bool,
) -> ArrayD<f32> {
    let mut cur = a.clone();
    for (k, &axis) in axes.iter().enumerate() {
        let mut wide = cur.mapv(f64::from);
        if lanes && k == 0 {
            for mut lane in wide.lanes_mut(Axis(axis)) {
                let mut line = lane.to_vec();
                f.apply(&mut line, &mut Vec::new());
                lane.iter_mut().zip(&line).for_each(|(d, &v)| *d = v);
            }
        } else {
            spline_filter1d(&mut wide, axis, f).unwrap();
        }
        cur = wide.mapv(|v| v as f32);
    }
    cur
}

/// `spline_filter_from_as` into f32 equals the per-axis reference, bit for
/// bit (fused pass, strips, groups of lines, slabs, one line, a strided
/// source); into f64 it equals the filter of the widened samples.
#[test]
fn float32_coefficients_are_rounded_after_every_axis_as_scipy() {
    let shapes: [&[usize]; 6] = [
        &[40],
        &[9, 17],
        &[33, 5],
        &[6, 40, 40],
        &[3, 5, 4, 19],
        &[1, 30],
    ];
    for (s, shape) in shapes.iter().enumerate() {
        let a = data32(shape, 60 + s as u64);
        let wide = a.mapv(f64::from);
        let all: Vec<usize> = (0..shape.len()).collect();
        for degree in [2u32, 3, 5] {
            for mode in [Mode::Mirror, Mode::Reflect, Mode::GridWrap] {
                let f = LineFilter::<f64>::new(
                    &SplineFamily::Order(degree + 1),
                    mode,
                    0.0,
                    Route::Exact,
                )
                .unwrap();
                for axes in [all.clone(), vec![shape.len() - 1], vec![0]] {
                    let what = format!("{shape:?} {degree} {mode} {axes:?}");
                    let mut got = ArrayD::<f32>::zeros(IxDyn(shape));
                    spline_filter_from_as(&a, &mut got, &axes, Some(&f)).unwrap();
                    let want = per_axis_reference(&a, &axes, &f, false);
                    let g: Vec<f32> = got.iter().copied().collect();
                    let w: Vec<f32> = want.iter().copied().collect();
                    assert_eq!(bits32(&g), bits32(&w), "f32 output {what}");
                    // The same from a transposed (strided) source.
                    let t = a.t();
                    let mut got_t = ArrayD::<f32>::zeros(IxDyn(t.shape()));
                    let axes_t: Vec<usize> = axes.iter().map(|&k| shape.len() - 1 - k).collect();
                    spline_filter_from_as(&t, &mut got_t, &axes_t, Some(&f)).unwrap();
                    let want_t =
                        per_axis_reference(&t.as_standard_layout().to_owned(), &axes_t, &f, true);
                    assert_eq!(got_t, want_t, "strided {what}");
                    // f64 coefficients of f32 samples: the widened samples' ones.
                    let mut c = ArrayD::<f64>::zeros(IxDyn(shape));
                    let mut d = ArrayD::<f64>::zeros(IxDyn(shape));
                    spline_filter_from(&a, &mut c, &axes, Some(&f)).unwrap();
                    spline_filter_from(&wide, &mut d, &axes, Some(&f)).unwrap();
                    let (c, d): (Vec<f64>, Vec<f64>) =
                        (c.iter().copied().collect(), d.iter().copied().collect());
                    assert_eq!(bits64(&c), bits64(&d), "f64 output {what}");
                }
            }
        }
    }
}

/// f32 storage filtered in f64 in place (`spline_filter` on an f32 array
/// with an f64 filter) is the same per-axis algorithm; a NaN sample
/// follows the filter's policy on that path too.
#[test]
fn float32_arrays_filter_in_place_in_f64() {
    let a = data32(&[7, 30, 9], 77);
    let f =
        LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
    let mut got = a.clone();
    spline_filter(&mut got, &f).unwrap();
    assert_eq!(got, per_axis_reference(&a, &[0, 1, 2], &f, false));
    let mut one = a.clone();
    spline_filter1d(&mut one, 1, &f).unwrap();
    assert_eq!(one, per_axis_reference(&a, &[1], &f, false));
    let mut bad = a.clone();
    bad[[3, 4, 5]] = f32::NAN;
    let mut out = ArrayD::<f32>::zeros(IxDyn(&[7, 30, 9]));
    spline_filter_from_as(&bad, &mut out, &[0, 1, 2], Some(&f)).unwrap();
    assert!(
        out.iter().all(|x| x.is_nan()),
        "scipy's pattern: every coefficient"
    );
    let raise = f.clone().with_nan_policy(NanPolicy::Raise).unwrap();
    let err = spline_filter_from_as(&bad, &mut out, &[0, 1, 2], Some(&raise)).unwrap_err();
    assert!(
        matches!(err, NdimageError::NonFinite { index, .. } if index == (3 * 30 + 4) * 9 + 5),
        "{err}"
    );
}
