//! The N-D engine against scipy.ndimage 1.17.1 on committed fixtures
//! (verify/fixtures/scipy, made by make_fixtures.py there): spline_filter1d
//! (1-D, and along axis 0 of a 2-D array), spline_filter (2-D, 3-D) and
//! map_coordinates (1-D, 2-D, 3-D, points inside and outside the grid) for
//! degrees ≤ 5 and every shared mode. Agreement is asserted to a few ulps of
//! the largest reference value.
//!
//! Two scipy defects found on the way, both checked against a 256-bit MPFR
//! twin of our filter and by the closed-form residual below: scipy's
//! `reflect` prefilter is wrong on short lines (relative errors `≈ ρ^{2ν}`:
//! 1e-11 for cubics at ν = 9, 1e-7 for quintics), so `reflect` on axes
//! shorter than 20 is compared with the MPFR twin instead; and scipy's
//! map_coordinates loses up to ~70 ulps on `nearest` / `grid-constant`
//! (its padding shifts the coordinates by the pad, `x + pad` rounds) and
//! ~30 on `grid-wrap` quintics, where ours stays within 13 ulps of MPFR —
//! hence the wider tolerance for map_coordinates.

use splinelab::ndarray::{Array2, ArrayD};
use splinelab::prelude::*;
use splinelab_verify::metrics::ulps_of_max;
use std::path::PathBuf;

const CVAL: f64 = 0.7;
/// Allowed difference, in units of `ε · max|reference|`.
const ULPS: f64 = 8.0;
/// For given coefficients: both sides round a sum of `(d + 1)^D` terms
/// (216 for 3-D quintics; worst seen 9.1).
const SUM_ULPS: f64 = 16.0;
/// The same for map_coordinates (scipy's own error, module docs).
const MAP_ULPS: f64 = 96.0;

fn read(name: &str) -> ArrayD<f64> {
    let path: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "fixtures",
        "scipy",
        &format!("{name}.npy"),
    ]
    .iter()
    .collect();
    ndarray_npy::read_npy(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// max |a − b| / (ε max|b|).
fn ulps(a: &[f64], b: &[f64]) -> f64 {
    ulps_of_max(a, b)
}

fn filter(d: u32, mode: Mode) -> LineFilter<f64> {
    LineFilter::new(&SplineFamily::Order(d + 1), mode, CVAL, Route::Exact).unwrap()
}

fn check(what: &str, got: &[f64], want: &ArrayD<f64>, worst: &mut f64, tol: f64) {
    let want: Vec<f64> = want.iter().copied().collect();
    let u = ulps(got, &want);
    assert!(u <= tol, "{what}: {u:.1} ulps of max|ref|");
    *worst = worst.max(u);
}

/// The reflect prefilter of `x` in 256-bit MPFR (one axis or all), rounded.
fn twin(x: &ArrayD<f64>, d: u32, axis: Option<usize>) -> ArrayD<f64> {
    type W = splinelab::scalar::Mp<256>;
    let f = LineFilter::<W>::new(
        &SplineFamily::Order(d + 1),
        Mode::Reflect,
        0.0,
        Route::Exact,
    )
    .unwrap();
    let mut w = x.mapv(W::from_f64_exact);
    match axis {
        Some(a) => spline_filter1d(&mut w, a, &f).unwrap(),
        None => spline_filter(&mut w, &f).unwrap(),
    }
    w.mapv(|v| v.to_f64())
}

/// Independent check of the reflect rule on a short line (where scipy
/// fails): the cubic interpolation condition `(D_{j−1} + 4D_j + D_{j+1})/6 = s_j`
/// with `D_{−1} = D_0`, `D_ν = D_{ν−1}`, in exact rational arithmetic.
#[test]
fn reflect_short_line_satisfies_the_cubic_condition() {
    use rug::Rational;
    let s = [0.3, -0.9, 0.25, 0.8, -0.4, 0.55, 0.1, -0.7, 0.6];
    let mut d = s.to_vec();
    filter(3, Mode::Reflect).apply(&mut d, &mut Vec::new());
    let q = |x: f64| Rational::from_f64(x).unwrap();
    for j in 0..s.len() {
        let l = d[j.saturating_sub(1)];
        let r = d[(j + 1).min(s.len() - 1)];
        let res: Rational = (q(l) + q(d[j]) * 4u32 + q(r)) / 6u32 - q(s[j]);
        let r = res.to_f64();
        assert!(r.abs() < 4.0 * f64::EPSILON, "j={j}: {r}");
    }
}

#[test]
fn spline_filter_matches_scipy() {
    let mut worst = 0.0f64;
    for mode in Mode::ALL {
        for d in 2..=5u32 {
            let f = filter(d, mode);
            let mut x1 = read("x1");
            spline_filter1d(&mut x1, 0, &f).unwrap();
            check(
                &format!("f1 {mode} {d}"),
                x1.as_slice().unwrap(),
                &read(&format!("f1_{mode}_{d}")),
                &mut worst,
                ULPS,
            );
            let mut x2 = read("x2");
            spline_filter1d(&mut x2, 0, &f).unwrap();
            let x2: Vec<f64> = x2.iter().copied().collect();
            let short = mode == Mode::Reflect;
            let want = |fixture: &str, input: &str, axis: Option<usize>| {
                if short {
                    twin(&read(input), d, axis)
                } else {
                    read(&format!("{fixture}_{mode}_{d}"))
                }
            };
            check(
                &format!("g2 {mode} {d}"),
                &x2,
                &want("g2", "x2", Some(0)),
                &mut worst,
                ULPS,
            );
            for k in [2, 3] {
                let mut x = read(&format!("x{k}"));
                spline_filter(&mut x, &f).unwrap();
                let x: Vec<f64> = x.iter().copied().collect();
                check(
                    &format!("f{k} {mode} {d}"),
                    &x,
                    &want(&format!("f{k}"), &format!("x{k}"), None),
                    &mut worst,
                    ULPS,
                );
            }
        }
    }
    eprintln!("spline_filter: worst {worst:.2} ulps of max|c|");
}

#[test]
fn map_coordinates_matches_scipy() {
    let mut worst = 0.0f64;
    for mode in Mode::ALL {
        for k in 1..=3 {
            let x = read(&format!("x{k}"));
            let p = read(&format!("p{k}_{mode}"));
            let p: Array2<f64> = p.into_dimensionality().unwrap();
            for d in 1..=5u32 {
                let opts = Options {
                    cval: CVAL,
                    ..Options::new(d, mode)
                };
                let got: Vec<f64> = map_coordinates(&x, p.t(), opts).unwrap();
                if mode == Mode::Reflect && k > 1 && d > 1 {
                    // scipy's reflect prefilter is wrong on these short axes.
                    continue;
                }
                check(
                    &format!("m{k} {mode} {d}"),
                    &got,
                    &read(&format!("m{k}_{mode}_{d}")),
                    &mut worst,
                    MAP_ULPS,
                );
                // The same through eval_many, points as rows.
                let f = Interpolant::new(&x, opts).unwrap();
                let mut out = vec![0.0; p.nrows()];
                f.eval_many(p.view(), &mut out).unwrap();
                assert_eq!(out, got);
            }
        }
    }
    eprintln!("map_coordinates: worst {worst:.2} ulps of max|value|");
}

/// scipy's `map_coordinates(x, q, order=d, mode, cval, prefilter=False)`:
/// `x` taken as coefficients ([`Interpolant::from_coefficients`]), degrees
/// 0..=5, points up to 3 samples outside and on half-integers (the ties of
/// degree 0). Degrees 0 and 1 have no prefilter, so [`Interpolant::new`]
/// must give the same values.
#[test]
fn given_coefficients_and_degrees_0_and_1_match_scipy() {
    let mut worst = 0.0f64;
    for mode in Mode::ALL {
        for k in 1..=3 {
            let x = read(&format!("x{k}"));
            let q: Array2<f64> = read(&format!("q{k}")).into_dimensionality().unwrap();
            for d in 0..=5u32 {
                let want = read(&format!("n{k}_{mode}_{d}"));
                let f = Interpolant::from_coefficients(&x, d, mode, CVAL).unwrap();
                let mut got = vec![0.0; q.nrows()];
                f.eval_many(q.view(), &mut got).unwrap();
                let one: Vec<f64> = q
                    .rows()
                    .into_iter()
                    .map(|p| f.eval(p.as_slice().unwrap()).unwrap())
                    .collect();
                // Single points (de Boor weights; eval_many's cubic weights are
                // closed forms): the same to rounding.
                check(
                    &format!("n{k} {mode} {d} eval"),
                    &one,
                    &want,
                    &mut worst,
                    SUM_ULPS,
                );
                if d == 0 {
                    // The nearest sample: exactly scipy's pick, ties included.
                    let want: Vec<f64> = want.iter().copied().collect();
                    assert_eq!(got, want, "n{k} {mode} 0");
                }
                check(
                    &format!("n{k} {mode} {d}"),
                    &got,
                    &want,
                    &mut worst,
                    SUM_ULPS,
                );
                if d <= 1 {
                    let opts = Options {
                        cval: CVAL,
                        ..Options::new(d, mode)
                    };
                    let samples: Vec<f64> = map_coordinates(&x, q.t(), opts).unwrap();
                    assert_eq!(samples, got, "n{k} {mode} {d}: new vs given");
                }
            }
        }
    }
    eprintln!("prefilter=False: worst {worst:.2} ulps of max|value|");
}

/// `nearest` and `grid-constant` with points outside the grid (up to 30
/// samples beyond the ends) against scipy's map_coordinates, on the check
/// fixtures (verify/fixtures/scipy/interp, made by make_check_fixtures.py).
/// scipy pads only 12 samples before its filter (with the reflect or
/// mirror rule at the padded ends), so it differs from the exact spline of
/// the extended signal by about `ρ^{24−δ}` of the data `δ ≤ 12` samples
/// outside (`ρ` the largest pole: at the ends 1.9e-14 for cubics, 1.6e-9
/// for quintics) and extends its coefficient at `−12` beyond, plus its
/// rounding of `x + 12` (up to ~70 ulps); the engine must agree within
/// that. Before the fix, `nearest` returned the end sample outside the
/// grid (0.16 away from scipy on a random signal).
#[test]
fn padded_modes_outside_the_grid_match_scipy_within_its_padding_error() {
    // |largest pole|: 3 − 2√2, 2 − √3, and the quintic's.
    let rho = |d: u32| -> f64 {
        match d {
            2 => 0.171_572_875_253_809_9,
            3 => 0.267_949_192_431_122_7,
            _ => 0.430_575_347_099_973_8,
        }
    };
    let cases = [
        ("samples1", "coords1", "v1", [2u32, 3, 5].as_slice()),
        ("samples1", "far1", "f1", &[3]),
        ("samples2", "coords2", "v2", &[3]),
        ("samples2", "far2", "f2", &[3]),
    ];
    for (samples, coords, prefix, degrees) in cases {
        let s = read(&format!("interp/{samples}"));
        let at = read(&format!("interp/{coords}"));
        let smax = s.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for &d in degrees {
            for mode in [Mode::Nearest, Mode::GridConstant] {
                let f: Interpolant<f64> = Interpolant::new(&s, Options::new(d, mode)).unwrap();
                let want = read(&format!("interp/{prefix}_d{d}_{}", mode.name()));
                let k = at.shape()[1];
                for (j, w) in want.iter().enumerate() {
                    let x: Vec<f64> = (0..s.ndim()).map(|a| at[[a, j]]).collect();
                    // Samples outside the grid (capped at scipy's pad).
                    let out = (0..s.ndim())
                        .map(|a| (-x[a]).max(x[a] - (s.shape()[a] - 1) as f64))
                        .fold(0.0f64, f64::max)
                        .min(12.0);
                    let tol = (128.0 * f64::EPSILON).max(4.0 * rho(d).powf(24.0 - out)) * smax;
                    let err = (f.eval(&x).unwrap() - w).abs();
                    assert!(
                        err <= tol,
                        "{prefix} degree {d} {mode} at {x:?} (of {k}): {err:e} > {tol:e}"
                    );
                }
            }
        }
    }
}
