//! `check interp`: the reference against the interpolation property (exact
//! at the samples) and scipy 1.17.1's committed `map_coordinates` outputs
//! (verify/fixtures/scipy/interp, made by make_check_fixtures.py) in all
//! five modes — `nearest` and `grid-constant` in scipy's padded convention —
//! near the grid, far beyond it, at order 1 and with a non-zero `cval`;
//! injected errors found at their index and in their region.

use ndarray::{Array1, Array2};
use ndarray_npy::ReadNpyExt;
use rug::Rational;
use splinelab_verify::check::interp::{InterpInput, check_interp, check_interp_with_cval};
use splinelab_verify::check::{CheckError, CheckSummary, Mode, Region, UserFormat};
use std::path::PathBuf;

fn open(name: &str) -> std::fs::File {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("fixtures/scipy/interp");
    std::fs::File::open(p.join(name)).unwrap()
}

fn npy1(name: &str) -> Vec<f64> {
    Array1::<f64>::read_npy(open(name)).unwrap().to_vec()
}

fn npy2(name: &str) -> Array2<f64> {
    Array2::<f64>::read_npy(open(name)).unwrap()
}

/// The fixture case of `dims` axes: samples, shape, point-major
/// coordinates, at the points of `coords{dims}.npy` or `far{dims}.npy`.
fn case_at(dims: usize, points: &str) -> (Vec<f64>, Vec<usize>, Vec<f64>) {
    let coords = npy2(&format!("{points}{dims}.npy"));
    let points = coords.t().iter().copied().collect();
    if dims == 1 {
        (npy1("samples1.npy"), vec![200], points)
    } else {
        let s = npy2("samples2.npy");
        (s.iter().copied().collect(), s.shape().to_vec(), points)
    }
}

fn input(dims: usize, degree: usize, mode: Mode, user: Vec<f64>, max: Option<f64>) -> InterpInput {
    let (samples, shape, points) = case_at(dims, "coords");
    InterpInput {
        samples,
        shape,
        points,
        user,
        format: UserFormat::F64,
        degree,
        mode: mode.into(),
        max_ulps: max,
    }
}

fn scipy(dims: usize, degree: usize, mode: Mode) -> Vec<f64> {
    npy1(&format!("v{dims}_d{degree}_{}.npy", mode.name()))
}

#[test]
fn the_reference_interpolates_the_samples_exactly() {
    // f(j) = s_j at every grid point, whatever the mode and degree: the
    // samples themselves must check at (far) below one ulp.
    for (dims, degree) in [(1, 2), (1, 5), (2, 3)] {
        for mode in Mode::ALL {
            let mut inp = input(dims, degree, mode, vec![], None);
            let grid: Vec<Vec<f64>> = match dims {
                1 => (0..200).map(|i| vec![i as f64]).collect(),
                _ => (0..64)
                    .flat_map(|i| (0..64).map(move |j| vec![i as f64, j as f64]))
                    .collect(),
            };
            inp.points = grid.concat();
            inp.user = inp.samples.clone();
            let s = check_interp(&inp).unwrap();
            let w = s.worst.unwrap();
            assert!(w.ulps < 1e-6, "{dims}-D d{degree} {mode}: {}", w.ulps);
        }
    }
}

fn report(what: &str, s: &CheckSummary) {
    eprintln!(
        "{what}: bits {:?} median {:.3} max {:.3} scaled {:.3}",
        s.reference_bits,
        s.median_ulps,
        s.worst.as_ref().unwrap().ulps,
        s.max_ulps_scaled,
    );
}

/// The bounds scipy meets where its coordinate arithmetic is exact:
/// (median ulps, max ulps of max |f|). Measured (scipy 1.17.1): median ≤ 2.9
/// and max ≤ 12.5 ulps of max |f| for degrees 1–3; the quintic's larger
/// coefficients cancel in the sum: median ≈ 10.6, max ≈ 32 ulps of max |f|.
fn tight(degree: usize) -> (f64, f64) {
    if degree <= 3 {
        (3.0, 16.0)
    } else {
        (12.0, 40.0)
    }
}

/// Where scipy rounds the coordinate it evaluates at — `x + 12` for the
/// padded modes, the fold for points far outside — its error grows by
/// `|f'| · ulp(x)/2`: measured up to 218 ulps of max |f| (1-D d2 nearest),
/// medians up to 5.1 (2-D); [`scipy_padded_error_is_its_rounding_of_x_plus_12`]
/// shows that this rounding is the whole excess.
const ROUNDED: (f64, f64) = (6.0, 256.0);

fn assert_scipy_bounds(what: &str, s: &CheckSummary, (median, scaled): (f64, f64)) {
    report(what, s);
    assert!(s.max_ulps_scaled < scaled, "{what}: {}", s.max_ulps_scaled);
    assert!(s.median_ulps < median, "{what}: {}", s.median_ulps);
    assert_eq!(s.non_finite, 0);
}

/// The bounds for `mode` at the fixtures' points: [`tight`] unless scipy
/// rounds `x + 12` ([`ROUNDED`]).
fn bounds(mode: Mode, degree: usize) -> (f64, f64) {
    let (median, scaled) = tight(degree);
    match mode {
        Mode::Nearest | Mode::GridConstant if degree > 1 => (median.max(ROUNDED.0), ROUNDED.1),
        _ => (median, scaled),
    }
}

#[test]
fn scipy_map_coordinates_is_within_a_few_ulps() {
    let cases = [(1, 2), (1, 3), (1, 5), (2, 3)];
    for (dims, degree) in cases {
        for mode in Mode::ALL {
            let s =
                check_interp(&input(dims, degree, mode, scipy(dims, degree, mode), None)).unwrap();
            let what = format!("{dims}-D d{degree} {mode}");
            assert_scipy_bounds(&what, &s, bounds(mode, degree));
        }
    }
}

#[test]
fn scipy_far_beyond_the_grid_and_its_padding_is_within_a_few_ulps() {
    // Points up to 30 samples out: beyond the 12 samples scipy pads, where
    // nearest takes the padded edge coefficient and grid-constant cval;
    // scipy folds them for the other modes, rounding (grid-wrap: 46 ulps of
    // max |f| measured in 1-D, median 4.5 in 2-D).
    for dims in [1, 2] {
        for mode in Mode::ALL {
            let (samples, shape, points) = case_at(dims, "far");
            let inp = InterpInput {
                samples,
                shape,
                points,
                user: npy1(&format!("f{dims}_d3_{}.npy", mode.name())),
                ..input(dims, 3, mode, vec![], None)
            };
            let s = check_interp(&inp).unwrap();
            assert_scipy_bounds(&format!("far {dims}-D {mode}"), &s, ROUNDED);
        }
    }
}

#[test]
fn scipy_order_1_and_a_nonzero_cval_are_followed() {
    // Order 1: scipy neither prefilters nor pads; linear interpolation of the
    // edge-extended (nearest) or cval-extended (grid-constant) samples.
    for mode in [Mode::Nearest, Mode::GridConstant] {
        let s = check_interp(&input(1, 1, mode, scipy(1, 1, mode), None)).unwrap();
        assert_scipy_bounds(&format!("d1 {mode}"), &s, tight(1));
    }
    // grid-constant with cval = 0.75 (the script's CVAL): padded with it and
    // worth it beyond the padding; judged with cval 0 it is far off.
    let v = npy1("v1_d3_grid-constant_cval.npy");
    let inp = input(1, 3, Mode::GridConstant, v, None);
    let s = check_interp_with_cval(&inp, 0.75).unwrap();
    assert_scipy_bounds(
        "d3 grid-constant cval 0.75",
        &s,
        bounds(Mode::GridConstant, 3),
    );
    let wrong = check_interp(&inp).unwrap();
    assert!(wrong.worst.unwrap().ulps > 1e12);
}

#[test]
fn an_injected_1000_ulp_error_is_found_at_its_point() {
    let cases = [
        (1, 3, Mode::Mirror),
        (2, 3, Mode::GridWrap),
        (1, 5, Mode::Nearest),
        (2, 3, Mode::Nearest),
        (1, 3, Mode::GridConstant),
        (2, 3, Mode::GridConstant),
    ];
    for (dims, degree, mode) in cases {
        let clean = check_interp(&input(dims, degree, mode, scipy(dims, degree, mode), None))
            .unwrap()
            .elements;
        // scipy's values, except the few (near-zero values) whose own error is
        // over 16 ulps, which take the rounded reference: the injected error
        // must then be the only element over --max-ulps 100.
        let base: Vec<f64> = clean
            .iter()
            .map(|e| if e.ulps <= 16.0 { e.value } else { e.reference })
            .collect();
        for region in [Region::Boundary, Region::Interior] {
            let k = clean.iter().position(|e| e.region == Some(region)).unwrap();
            let mut user = base.clone();
            let b = user[k].to_bits();
            user[k] = f64::from_bits(if user[k] >= 0.0 { b + 1000 } else { b - 1000 });
            let own = clean[k].ulps.min(16.0);
            let s = check_interp(&input(dims, degree, mode, user, Some(100.0))).unwrap();
            let w = s.worst.unwrap();
            assert_eq!((w.index, w.region), (k, Some(region)), "{dims}-D {mode}");
            assert!((w.ulps - 1000.0).abs() <= own + 1.0, "{} vs {own}", w.ulps);
            assert_eq!(
                (s.failed, s.verdict.as_str()),
                (1, "fail"),
                "{dims}-D {mode}"
            );
        }
    }
}

#[test]
fn scipy_padded_error_is_its_rounding_of_x_plus_12() {
    // scipy evaluates nearest/grid-constant at fl(x + 12); the reference at
    // the exact x + 12. Judged at y = fl(x + 12) − 12 (exact in f64 here,
    // checked in rationals), scipy's values are within the bounds of the
    // other modes: its larger errors at x are that rounding, nothing else.
    for (dims, degree) in [(1, 2), (1, 3), (1, 5), (2, 3)] {
        for mode in [Mode::Nearest, Mode::GridConstant] {
            let mut inp = input(dims, degree, mode, scipy(dims, degree, mode), None);
            for x in inp.points.iter_mut() {
                let y = *x + 12.0;
                let z = y - 12.0;
                assert_eq!(
                    Rational::from_f64(z).unwrap(),
                    Rational::from_f64(y).unwrap() - 12
                );
                *x = z;
            }
            let s = check_interp(&inp).unwrap();
            let what = format!("at fl(x + 12) {dims}-D d{degree} {mode}");
            assert_scipy_bounds(&what, &s, tight(degree));
        }
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let v = scipy(1, 3, Mode::Mirror);
    let mut short = input(1, 3, Mode::Mirror, v.clone(), None);
    short.user.pop();
    assert!(matches!(
        check_interp(&short),
        Err(CheckError::LengthMismatch { .. })
    ));
    // Any number of axes is accepted; the shape must hold the samples.
    let mut three = input(1, 3, Mode::Mirror, v.clone(), None);
    three.shape = vec![2, 4, 5];
    assert!(matches!(
        check_interp(&three),
        Err(CheckError::LengthMismatch { .. })
    ));
    let mut scalar = input(1, 3, Mode::Mirror, v.clone(), None);
    scalar.shape = vec![];
    assert!(matches!(check_interp(&scalar), Err(CheckError::Invalid(_))));
    let mut nan = input(1, 3, Mode::Mirror, v.clone(), None);
    nan.points[3] = f64::NAN;
    assert!(matches!(
        check_interp(&nan),
        Err(CheckError::NonFiniteInput { .. })
    ));
    let mut far = input(1, 3, Mode::Nearest, v.clone(), None);
    far.points[5] = 1e300;
    assert!(matches!(check_interp(&far), Err(CheckError::Invalid(_))));
    let cval = input(1, 3, Mode::GridConstant, v.clone(), None);
    assert!(matches!(
        check_interp_with_cval(&cval, f64::INFINITY),
        Err(CheckError::NonFiniteInput { .. })
    ));
    let deg = input(1, 16, Mode::Mirror, v, None);
    assert!(matches!(
        check_interp(&deg),
        Err(CheckError::DegreeOutOfRange { .. })
    ));
}
