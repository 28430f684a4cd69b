//! Accuracy of the resampling routes against independent references:
//! degrees beyond scipy's (7, 11) in `f64` against the same spline in
//! 256-bit MPFR, and coordinates beyond `2^53` against exact integer folding.

use super::PointRule;
use crate::prelude::*;
use crate::scalar::Mp;
use ndarray::{Array2, Array3};

/// Samples with values in `[−1, 1]` from an integer hash (exact, no libm).
fn samples(shape: (usize, usize)) -> Array2<f64> {
    Array2::from_shape_fn(shape, |(i, j)| {
        ((i * 131 + j * 97 + 11) * 7919 % 257) as f64 / 128.0 - 1.0
    })
}

/// The f64 separable (zoom-like grid) and affine (rotation) resamplings at
/// degrees 7 and 11 against the 256-bit interpolant of the same samples
/// evaluated pointwise: within `32 u · max|D|` (`u = 2^−53`), the rounding
/// of the prefilter and of the `(d + 1)²` non-negative-weight terms
/// (measured: 3.6 u · max|D| at most, reflect degree 7).
#[test]
fn high_degree_resampling_matches_mpfr() {
    let data = samples((25, 26));
    let mp = data.mapv(Mp::<256>::from_f64_exact);
    let rows: Vec<f64> = (0..7).map(|k| -3.25 + k as f64 * 4.71).collect();
    let cols: Vec<f64> = (0..6).map(|k| -2.5 + k as f64 * 5.37).collect();
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    let matrix = [c, s, -s, c];
    let offset = [4.0, -3.5];
    for degree in [7, 11] {
        for mode in [Mode::Mirror, Mode::Reflect, Mode::Nearest] {
            let f = Interpolant::<f64>::new(&data, Options::new(degree, mode)).unwrap();
            let g = Interpolant::<Mp<256>>::new(&mp, Options::new(degree, mode)).unwrap();
            let dmax = g
                .coefficients()
                .iter()
                .fold(0.0f64, |m, v| m.max(v.to_f64().abs()));
            let tol = 32.0 * f64::EPSILON / 2.0 * dmax;
            let mut grid = vec![0.0; rows.len() * cols.len()];
            f.resample_grid(&[&rows, &cols], &[0, 0], &mut grid)
                .unwrap();
            let mut turned = vec![0.0; 8 * 9];
            f.resample_affine(&matrix, &offset, &[8, 9], 0.0, PointRule::Fold, &mut turned)
                .unwrap();
            let mut worst = 0.0f64;
            for (k, v) in grid.iter().enumerate() {
                let x = [rows[k / cols.len()], cols[k % cols.len()]];
                worst = worst.max((v - g.eval(&x).unwrap().to_f64()).abs());
            }
            for (k, v) in turned.iter().enumerate() {
                let (i, j) = ((k / 9) as f64, (k % 9) as f64);
                let x = [
                    offset[0] + i * matrix[0] + j * matrix[1],
                    offset[1] + i * matrix[2] + j * matrix[3],
                ];
                worst = worst.max((v - g.eval(&x).unwrap().to_f64()).abs());
            }
            assert!(worst <= tol, "degree {degree} {mode}: {worst:e} > {tol:e}");
        }
    }
}

/// The sample index that `mode` folds the integer coordinate `x` to, in
/// exact integer arithmetic (`None`: outside, `cval`).
fn folded_index(mode: Mode, x: i128, n: i128) -> Option<usize> {
    let i = match mode {
        Mode::Mirror => {
            let r = x.rem_euclid(2 * n - 2);
            if r < n { r } else { 2 * n - 2 - r }
        }
        Mode::Reflect => {
            let r = x.rem_euclid(2 * n);
            if r < n { r } else { 2 * n - 1 - r }
        }
        Mode::GridWrap => x.rem_euclid(n),
        Mode::Nearest => x.clamp(0, n - 1),
        Mode::GridConstant => return (0..n).contains(&x).then_some(x as usize),
    };
    Some(i as usize)
}

/// Coordinates beyond `2^53` are integers; every route folds them exactly,
/// so the value is the sample at the exactly folded index (the
/// interpolation condition), `cval` for `grid-constant`: pointwise, batch
/// (the fixed-size kernels), separable and affine with a huge offset.
#[test]
fn coordinates_beyond_2_pow_53_fold_exactly() {
    let data = samples((7, 9));
    let huge = [
        2f64.powi(53) + 2.0,
        -(2f64.powi(60)) - 4096.0,
        3.0 * 2f64.powi(70),
        -(2f64.powi(62)),
        1e300,
    ];
    for mode in Mode::ALL {
        for degree in [1, 3, 5, 8] {
            let mut opts = Options::new(degree, mode);
            opts.cval = 0.625;
            let f = Interpolant::<f64>::new(&data, opts).unwrap();
            for &x0 in &huge {
                let x1 = 4.0;
                let want = match folded_index(mode, x0 as i128, 7) {
                    Some(i) => data[[i, 4]],
                    None => 0.625,
                };
                if x0.abs() > 1e30 && matches!(mode, Mode::Mirror | Mode::Reflect | Mode::GridWrap)
                {
                    // 1e300 as an i128 saturates: its fold is checked below
                    // against the f64 remainder (exact) instead.
                    let p = match mode {
                        Mode::Mirror => 12.0,
                        Mode::Reflect => 14.0,
                        _ => 7.0,
                    };
                    let r = x0.rem_euclid(p) as i128;
                    let want = data[[folded_index(mode, r, 7).unwrap(), 4]];
                    assert!(
                        (f.eval(&[x0, x1]).unwrap() - want).abs() < 1e-13,
                        "{mode} {degree} {x0:e}"
                    );
                    continue;
                }
                let one = f.eval(&[x0, x1]).unwrap();
                let mut many = [0.0];
                f.eval_many(ndarray::array![[x0, x1]].view(), &mut many)
                    .unwrap();
                let mut grid = [0.0];
                f.resample_grid(&[&[x0], &[x1]], &[0, 0], &mut grid)
                    .unwrap();
                let mut affine = [0.0];
                f.resample_affine(
                    &[1.0, 0.0, 0.0, 1.0],
                    &[x0, x1],
                    &[1, 1],
                    0.0,
                    PointRule::Fold,
                    &mut affine,
                )
                .unwrap();
                for (route, v) in [
                    ("eval", one),
                    ("eval_many", many[0]),
                    ("grid", grid[0]),
                    ("affine", affine[0]),
                ] {
                    assert!(
                        (v - want).abs() < 1e-13,
                        "{mode} degree {degree} x {x0:e} {route}: {v} vs {want}"
                    );
                }
            }
        }
    }
}

/// A 3-D degree-7 evaluation (order 8: beyond the fixed-size kernels) in
/// f64 against 256-bit MPFR at scattered points.
#[test]
fn degree_7_in_3d_matches_mpfr() {
    let data = Array3::from_shape_fn((9, 8, 10), |(i, j, k)| {
        ((i * 31 + j * 17 + k * 5 + 3) * 7919 % 263) as f64 / 131.0 - 1.0
    });
    let mp = data.mapv(Mp::<256>::from_f64_exact);
    let f = Interpolant::<f64>::new(&data, Options::new(7, Mode::Mirror)).unwrap();
    let g = Interpolant::<Mp<256>>::new(&mp, Options::new(7, Mode::Mirror)).unwrap();
    let pts = Array2::from_shape_fn((300, 3), |(k, a)| {
        ((k * (7 + a) + 3 * a) % 113) as f64 * 0.1 - 1.3
    });
    let mut out = vec![0.0; 300];
    f.eval_many(pts.view(), &mut out).unwrap();
    let dmax = g
        .coefficients()
        .iter()
        .fold(0.0f64, |m, v| m.max(v.to_f64().abs()));
    for (p, v) in pts.rows().into_iter().zip(&out) {
        let r = g.eval(p.as_slice().unwrap()).unwrap().to_f64();
        assert!(
            (v - r).abs() <= 256.0 * f64::EPSILON * dmax,
            "{p}: {v} vs {r}"
        );
    }
}
