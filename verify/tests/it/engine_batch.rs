//! Batch evaluation (`Interpolant::eval_many`: located in batches, rows
//! prefetched) against the single-point path (`Interpolant::eval`: the
//! recursive sum with per-index bounds), itself tested against scipy and
//! MPFR elsewhere; both take the same weights (closed forms for degrees 1
//! to 5, de Boor–Cox above). Counts that are
//! not multiples of the batch (64) or chunk (2048) sizes, points inside,
//! outside and far outside the grid (the `grid-constant` fallback), any
//! strides, 1 to 4 dimensions, degrees 0 to 7, every mode.

use splinelab::ndarray::{Array2, ArrayD, IxDyn};
use splinelab::ndimage::interpolant::PointRule;
use splinelab::prelude::*;
use splinelab_verify::rng::SplitMix64;

/// `count` points of `ndim` coordinates, mostly in `[−3, ν + 2]` per axis,
/// every 97th far outside (±1e6) and every 89th on a grid point.
fn points(count: usize, shape: &[usize], seed: u64) -> Array2<f64> {
    let mut r = SplitMix64::new(seed);
    Array2::from_shape_fn((count, shape.len()), |(k, a)| {
        let n = shape[a] as f64;
        match () {
            _ if k % 97 == 5 => {
                if r.unit() < 0.5 {
                    -1e6
                } else {
                    1e6 + 0.25
                }
            }
            _ if k % 89 == 3 => (r.unit() * n).floor(),
            _ => r.range(-3.0, n + 2.0),
        }
    })
}

fn data(shape: &[usize], seed: u64) -> ArrayD<f64> {
    let total = shape.iter().product();
    ArrayD::from_shape_vec(IxDyn(shape), SplitMix64::new(seed).signal(total)).unwrap()
}

/// Worst `|batch − single|` over the points, and the largest coefficient.
fn compare<T: Real + Send + Sync>(f: &Interpolant<T>, pts: &Array2<f64>) -> (f64, f64) {
    let mut out = vec![T::zero(); pts.nrows()];
    f.eval_many(pts.view(), &mut out).unwrap();
    let worst = pts
        .rows()
        .into_iter()
        .zip(&out)
        .map(|(p, v)| {
            let single = f.eval(p.as_slice().unwrap()).unwrap();
            (v.clone() - single).to_f64().abs()
        })
        .fold(0.0f64, f64::max);
    let cmax = f
        .coefficients()
        .iter()
        .fold(0.0f64, |m, c| m.max(c.to_f64().abs()));
    (worst, cmax)
}

#[test]
fn batch_equals_single_point_evaluation() {
    let cases: [(&[usize], &[u32], usize); 4] = [
        (&[37], &[0, 1, 2, 3, 4, 5, 7], 4133),
        (&[23, 17], &[0, 1, 2, 3, 5, 7], 2113),
        (&[9, 11, 7], &[0, 1, 3, 5], 1061),
        (&[5, 6, 4, 5], &[2, 3], 233),
    ];
    for (shape, degrees, count) in cases {
        let a = data(shape, shape.len() as u64);
        let pts = points(count, shape, 11 + shape.len() as u64);
        for &d in degrees {
            for mode in Mode::ALL {
                let mut opts = Options::new(d, mode);
                opts.cval = 0.375;
                let f = Interpolant::new(&a, opts).unwrap();
                let (worst, cmax) = compare(&f, &pts);
                // Every degree: the same weights (closed forms for degrees
                // 1 to 5 on both paths) and the same sums, bit for bit.
                assert!(
                    worst == 0.0,
                    "{shape:?} degree {d} {mode:?}: batch differs by {worst:e} (max|c| {cmax:e})"
                );
            }
        }
    }
}

#[test]
fn batch_ignores_the_layout_of_the_points() {
    let shape = [40, 33];
    let f = Interpolant::new(&data(&shape, 3), Options::new(3, Mode::Reflect)).unwrap();
    let pts = points(3001, &shape, 5);
    // The transpose of an (ndim, count) array, as `map_coordinates` passes it.
    let by_axis = pts.t().as_standard_layout().into_owned();
    let (mut a, mut b) = (vec![0.0; 3001], vec![0.0; 3001]);
    f.eval_many(pts.view(), &mut a).unwrap();
    f.eval_many(by_axis.t(), &mut b).unwrap();
    assert_eq!(a, b);
}

#[test]
fn batch_in_mpfr_and_f32_equals_single_point_evaluation() {
    let shape = [12, 9];
    let pts = points(517, &shape, 9);
    let a = data(&shape, 4);
    let a128 = a.mapv(Mp::<128>::from_f64_exact);
    let f = Interpolant::new(&a128, Options::new(3, Mode::GridConstant)).unwrap();
    // Above 53 bits the cubic weights come from de Boor as in `eval`.
    assert_eq!(compare(&f, &pts).0, 0.0);
    let a32 = a.mapv(|v| v as f32);
    let f = Interpolant::new(&a32, Options::new(3, Mode::Mirror)).unwrap();
    let (worst, cmax) = compare(&f, &pts);
    assert!(worst <= 8.0 * f64::from(f32::EPSILON) * cmax, "{worst:e}");
}

#[test]
fn batch_rejects_bad_input_with_typed_errors() {
    let f = Interpolant::new(&data(&[10, 10], 1), Options::new(3, Mode::Mirror)).unwrap();
    let mut pts = points(100, &[10, 10], 2);
    let mut out = vec![0.0; 100];
    assert!(matches!(
        f.eval_many(pts.view(), &mut out[..99]),
        Err(NdimageError::BufferLength {
            expected: 100,
            got: 99
        })
    ));
    assert!(matches!(
        f.eval_many(pts.t(), &mut out[..2]),
        Err(NdimageError::PointDimension {
            expected: 2,
            got: 100
        })
    ));
    pts[[70, 1]] = f64::NAN;
    assert!(matches!(
        f.eval_many(pts.view(), &mut out),
        Err(NdimageError::NonFiniteCoordinate(141))
    ));
}

/// The cubic batch path computes exactly its documented arithmetic: weights
/// `v³/6, 2/3 − u²(2 − u)/2, 2/3 − v²(2 − v)/2, u³/6` of `u = x − ⌊x⌋`,
/// `Σ_{l0} w0[l0] · (Σ_{l1} w1[l1] · D[i0 + l0, i1 + l1])` from zero, in
/// that order, with `i = ⌊x⌋ − 1`: bit for bit, at points whose window lies
/// inside the grid.
#[test]
fn cubic_batch_is_its_documented_sum_bit_for_bit() {
    let shape = [30, 26];
    let f = Interpolant::new(&data(&shape, 8), Options::new(3, Mode::Mirror)).unwrap();
    let d = f.coefficients();
    let mut r = SplitMix64::new(21);
    let pts = Array2::from_shape_fn((2500, 2), |(_, a)| r.range(1.0, shape[a] as f64 - 2.0));
    let mut out = vec![0.0; pts.nrows()];
    f.eval_many(pts.view(), &mut out).unwrap();
    let weights = |x: f64| {
        let u = x - x.floor();
        let v = 1.0 - u;
        let (u2, v2) = (u * u, v * v);
        let w = [
            v2 * v / 6.0,
            2.0 / 3.0 - 0.5 * u2 * (2.0 - u),
            2.0 / 3.0 - 0.5 * v2 * (2.0 - v),
            u2 * u / 6.0,
        ];
        (x.floor() as usize - 1, w)
    };
    for (p, got) in pts.rows().into_iter().zip(&out) {
        let ((i0, w0), (i1, w1)) = (weights(p[0]), weights(p[1]));
        let mut sum = 0.0;
        for l0 in 0..4 {
            let mut dot = 0.0;
            for l1 in 0..4 {
                dot += w1[l1] * d[[i0 + l0, i1 + l1]];
            }
            sum += w0[l0] * dot;
        }
        assert_eq!(got.to_bits(), sum.to_bits(), "at {p}");
    }
}

/// Points inside `[0, ν − 1]` on every axis fill whole batches, which the
/// fixed-size kernels locate in SIMD lanes (no fold, offsets in lanes, rows
/// prefetched a batch ahead); every 150th point lies just outside, so that
/// some batches take the point-by-point path. Both equal `eval` bit for
/// bit: 1 to 3 dimensions, degrees 1 to 5, every mode, under the point
/// rules of scipy's `constant` and `wrap` as well, counts that are not
/// multiples of the batch or chunk sizes, points read by rows and by
/// columns.
#[test]
fn batches_inside_the_grid_equal_single_point_evaluation() {
    let cases: [(&[usize], usize); 3] = [(&[61], 4500), (&[29, 23], 4211), (&[11, 9, 13], 2113)];
    for (shape, count) in cases {
        let a = data(shape, 30 + shape.len() as u64);
        let mut r = SplitMix64::new(7 + shape.len() as u64);
        let pts = Array2::from_shape_fn((count, shape.len()), |(k, ax)| {
            let n = shape[ax] as f64;
            if k % 150 == 77 {
                -0.25
            } else {
                r.range(0.0, n - 1.0)
            }
        });
        let by_axis = pts.t().as_standard_layout().into_owned();
        for degree in 1..=5 {
            for mode in Mode::ALL {
                let mut opts = Options::new(degree, mode);
                opts.cval = -0.75;
                let f = Interpolant::new(&a, opts).unwrap();
                let (mut rows, mut cols) = (vec![0.0; count], vec![0.0; count]);
                f.eval_many(pts.view(), &mut rows).unwrap();
                f.eval_many(by_axis.t(), &mut cols).unwrap();
                for (k, p) in pts.rows().into_iter().enumerate() {
                    let want = f.eval(p.as_slice().unwrap()).unwrap();
                    assert_eq!(
                        rows[k].to_bits(),
                        want.to_bits(),
                        "{shape:?} {mode:?} {degree} at {p}"
                    );
                    assert_eq!(
                        cols[k].to_bits(),
                        want.to_bits(),
                        "{shape:?} {mode:?} {degree} at {p}"
                    );
                }
                // scipy's 'constant': cval outside, the same values inside.
                f.eval_many_with(by_axis.t(), PointRule::CvalOutside, &mut cols)
                    .unwrap();
                for (k, p) in pts.rows().into_iter().enumerate() {
                    let want = if k % 150 == 77 { -0.75 } else { rows[k] };
                    assert_eq!(
                        cols[k].to_bits(),
                        want.to_bits(),
                        "{shape:?} {mode:?} {degree} at {p}"
                    );
                }
            }
        }
    }
}

/// A non-finite coordinate is refused whichever batch or chunk meets it
/// first, and the error names the first one in row-major order: NaN and
/// ±inf, on the fixed-size kernels (degree 3) and the general path
/// (degree 7), under every point rule (a NaN is not "outside" for scipy's
/// `constant`: it is refused).
#[test]
fn the_first_non_finite_coordinate_is_named_whichever_chunk_meets_it() {
    let shape = [40, 30];
    let a = data(&shape, 12);
    let count = 9000;
    for degree in [3, 7] {
        let f = Interpolant::new(&a, Options::new(degree, Mode::Mirror)).unwrap();
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for rule in [
                PointRule::Fold,
                PointRule::CvalOutside,
                PointRule::WrapPeriodNMinus1,
            ] {
                for (first, later) in [
                    ((4100, 1), (8000, 0)),
                    ((63, 0), (64, 1)),
                    ((8999, 1), (8999, 1)),
                ] {
                    let mut pts = points(count, &shape, 4);
                    pts[later] = bad;
                    pts[first] = bad;
                    let by_axis = pts.t().as_standard_layout().into_owned();
                    let mut out = vec![0.0; count];
                    let want = first.0 * 2 + first.1;
                    for view in [pts.view(), by_axis.t()] {
                        match f.eval_many_with(view, rule, &mut out) {
                            Err(NdimageError::NonFiniteCoordinate(k)) => {
                                assert_eq!(k, want, "degree {degree} {bad} {rule:?}")
                            }
                            other => panic!("degree {degree} {bad} {rule:?}: {other:?}"),
                        }
                    }
                }
            }
        }
    }
}
