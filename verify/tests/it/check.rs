//! `check`: the references against closed forms, exact rational solves and
//! scipy 1.17.1's committed outputs (verify/fixtures/scipy, made by
//! make_check_fixtures.py); injected errors found where they were put.

use ndarray::Array1;
use ndarray_npy::ReadNpyExt;
use rug::ops::Pow;
use rug::{Float, Rational};
use splinelab::scalar::{Mp, Real};
use splinelab::sspline::SplineFamily;
use splinelab::sspline::node_values::node_values_exact;
use splinelab_verify::check::bezier_eval::check_bezier_eval;
use splinelab_verify::check::bspline_eval::{BSplineEvalInput, check_bspline_eval};
use splinelab_verify::check::coeffs::check_coeffs;
use splinelab_verify::check::knot_insertion::check_knot_insertion;
use splinelab_verify::check::prefilter::{
    PrefilterInput, check_prefilter, family_of_degree, interpolation_coefficients,
};
use splinelab_verify::check::rational_bspline::RationalBSpline;
use splinelab_verify::check::{CheckError, EXACT_MODES, Mode, Region, UserFormat};
use splinelab_verify::exact::solve_rational;
use std::path::PathBuf;

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/scipy")
        .join(name)
}

fn npy_f64(name: &str) -> Vec<f64> {
    let f = std::fs::File::open(fixture(name)).unwrap();
    Array1::<f64>::read_npy(f).unwrap().to_vec()
}

fn npy_f32(name: &str) -> Vec<f64> {
    let f = std::fs::File::open(fixture(name)).unwrap();
    Array1::<f32>::read_npy(f)
        .unwrap()
        .iter()
        .map(|x| *x as f64)
        .collect()
}

fn input(degree: usize, mode: Mode, user: Vec<f64>, max_ulps: Option<f64>) -> PrefilterInput {
    PrefilterInput {
        samples: npy_f64("prefilter/samples.npy"),
        user,
        format: UserFormat::F64,
        family: family_of_degree(degree).unwrap(),
        mode,
        max_ulps,
    }
}

/// The f64 `k` ulps above `x` (by bit arithmetic, not by the code under test).
fn ulps_above(x: f64, k: u64) -> f64 {
    let b = x.to_bits();
    f64::from_bits(if x >= 0.0 { b + k } else { b - k })
}

#[test]
fn cubic_reference_is_the_closed_form_in_the_interior() {
    // c_i = √3 (√3 − 2)^|i|: an impulse in the middle of 201 samples; the
    // mirror ends perturb c near the centre by ρ^100 ≈ 1e−57.
    let n = 201;
    let mut s = vec![Mp::<256>::from_int(0); n];
    s[100] = Mp::from_int(1);
    let d = interpolation_coefficients(&s, &SplineFamily::Order(4), Mode::Mirror).unwrap();
    let r3 = Float::with_val(300, 3).sqrt();
    for i in 0..=30i32 {
        let c = Float::with_val(300, &r3 - 2u32).pow(i) * &r3;
        let got = d[(100 + i) as usize].to_float();
        let rel = Float::with_val(300, &got - &c).abs() / c.abs();
        assert!(rel < 1e-40, "i = {i}: relative difference {rel}");
    }
}

#[test]
fn coeffs_reference_meets_the_closed_forms() {
    // Cubic eq 18, and Beta2 eq 29: c_i = δ ξ^i / (2(ξ − 1/ξ)), ξ the root in
    // (−1, 0) of 2z² + (β2 + 8) z + 2, δ = β2 + 12; rounded once to f64.
    for (family, beta2) in [
        (SplineFamily::Order(4), Rational::from(0)),
        (
            SplineFamily::Beta2(Rational::from((1, 4))),
            Rational::from((1, 4)),
        ),
        (SplineFamily::Beta2(Rational::from(7)), Rational::from(7)),
    ] {
        let p = 400;
        let b = Float::with_val(p, &beta2) + 8u32;
        let disc = Float::with_val(p, &b * &b) - 16u32;
        let xi = (disc.sqrt() - &b) / 4u32;
        let delta = Float::with_val(p, &beta2) + 12u32;
        let kappa = delta / (Float::with_val(p, &xi - xi.clone().recip()) * 2u32);
        let user: Vec<f64> = (0..60)
            .map(|i| Float::with_val(p, &kappa * Float::with_val(p, xi.clone().pow(i))).to_f64())
            .collect();
        let s = check_coeffs(&family, &user, UserFormat::F64, Some(0.5)).unwrap();
        let w = s.worst.unwrap();
        assert!(
            w.ulps <= 0.5 + 1e-9,
            "{family}: {} ulps at {}",
            w.ulps,
            w.index
        );
        assert_eq!(s.verdict, "pass");
    }
}

/// The interpolation conditions assembled and solved over the rationals,
/// written out independently of the banded solver.
fn exact_solution(s: &[i64], degree: usize, mode: Mode) -> Vec<Rational> {
    let v = node_values_exact(&SplineFamily::Order(degree as u32 + 1)).unwrap();
    let (n, q) = (s.len(), v.len() as i64 / 2);
    let mut a = vec![vec![Rational::new(); n]; n];
    for (j, row) in a.iter_mut().enumerate() {
        for o in -q..=q {
            let k = j as i64 + o;
            let e = match mode {
                Mode::Mirror if n == 1 => 0,
                Mode::Mirror => {
                    let m = k.rem_euclid(2 * n as i64 - 2);
                    if m >= n as i64 {
                        2 * n as i64 - 2 - m
                    } else {
                        m
                    }
                }
                Mode::Reflect => {
                    let m = k.rem_euclid(2 * n as i64);
                    if m >= n as i64 {
                        2 * n as i64 - 1 - m
                    } else {
                        m
                    }
                }
                Mode::GridWrap => k.rem_euclid(n as i64),
                Mode::Nearest | Mode::GridConstant => unreachable!("not an exact mode"),
            };
            row[e as usize] += &v[(o + q) as usize];
        }
    }
    let b: Vec<Rational> = s.iter().map(|x| Rational::from(*x)).collect();
    solve_rational(a, &b).unwrap()
}

#[test]
fn reference_matches_exact_rational_solves() {
    let s = [3, -1, 4, 1, -5, 9, 2, -6, 5, 3, -5, 8, 9, -7, 9, 3, 2, 3];
    for degree in 2..=5 {
        for mode in EXACT_MODES {
            for len in [5, 11, s.len()] {
                let exact = exact_solution(&s[..len], degree, mode);
                let x: Vec<Mp<256>> = s[..len].iter().map(|v| Mp::from_int(*v)).collect();
                let got = interpolation_coefficients(&x, &family_of_degree(degree).unwrap(), mode)
                    .unwrap();
                for (g, e) in got.iter().zip(&exact) {
                    let diff =
                        Float::with_val(256, &Rational::from(&g.to_rational().unwrap() - e)).abs();
                    let scale = Float::with_val(256, e).abs();
                    assert!(
                        diff <= scale * 1e-70,
                        "degree {degree} {mode:?} n {len}: {g} vs {}",
                        e.to_f64()
                    );
                }
                // The exact solution rounded to f64 passes at half an ulp.
                let user: Vec<f64> = exact
                    .iter()
                    .map(|q| Float::with_val(53, q).to_f64())
                    .collect();
                let mut inp = input(degree, mode, user, Some(0.5 + 1e-9));
                inp.samples = s[..len].iter().map(|v| *v as f64).collect();
                assert_eq!(check_prefilter(&inp).unwrap().verdict, "pass");
            }
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
    /// Any integer samples, lengths down to 1 (where the band folds onto
    /// itself), every degree scipy has and every mode: the banded MPFR solve
    /// equals the exact rational solve to 2^−230.
    #[test]
    fn banded_reference_equals_the_exact_solve(
        s in proptest::collection::vec(-1000i64..1000, 1..30),
        degree in 2usize..=5,
        m in 0usize..3,
    ) {
        let mode = EXACT_MODES[m];
        let exact = exact_solution(&s, degree, mode);
        let x: Vec<Mp<256>> = s.iter().map(|v| Mp::from_int(*v)).collect();
        let got = interpolation_coefficients(&x, &family_of_degree(degree).unwrap(), mode).unwrap();
        let scale = exact.iter().map(|e| Float::with_val(256, e).abs()).fold(Float::with_val(256, 1e-300), |a, b| a.max(&b));
        for (g, e) in got.iter().zip(&exact) {
            let diff = Float::with_val(256, &Rational::from(&g.to_rational().unwrap() - e)).abs();
            proptest::prop_assert!(diff <= Float::with_val(256, &scale * 1e-69));
        }
    }
}

#[test]
fn scipy_prefilter_is_within_a_few_ulps_of_its_scale() {
    // Every scipy mode: nearest and grid-constant as scipy's spline_filter1d
    // treats them (reflect and mirror rules, `scipy_filter_rule`).
    for degree in 2..=5 {
        for mode in Mode::ALL {
            let user = npy_f64(&format!("prefilter/d{degree}_{}.npy", mode.name()));
            let s = check_prefilter(&input(degree, mode, user, None)).unwrap();
            assert_eq!(s.reference_bits, Some(192));
            // Median at most an ulp; the largest error measured against the
            // coefficients' scale max |D| at most a few ulps.
            assert!(s.median_ulps < 1.0, "d{degree} {mode:?}: {}", s.median_ulps);
            assert!(
                s.max_ulps_scaled < 4.0,
                "d{degree} {mode:?}: {}",
                s.max_ulps_scaled
            );
            assert!(s.max_ulps_scaled > 0.0);
        }
    }
}

#[test]
fn nearest_and_grid_constant_follow_scipys_filter_rules() {
    // scipy's nearest output (half-sample rule) passes as nearest and fails,
    // at the ends only, when checked as grid-constant (whole-sample rule).
    let user = npy_f64("prefilter/d3_nearest.npy");
    let mirror = npy_f64("prefilter/d3_mirror.npy");
    assert_ne!(user[0], mirror[0]);
    let s = check_prefilter(&input(3, Mode::Nearest, user.clone(), None)).unwrap();
    assert!(s.max_ulps_scaled < 4.0, "{}", s.max_ulps_scaled);
    let wrong = check_prefilter(&input(3, Mode::GridConstant, user, None)).unwrap();
    assert!(wrong.max_ulps_scaled > 1e6, "{}", wrong.max_ulps_scaled);
    assert_eq!(wrong.worst.unwrap().region, Some(Region::Boundary));
}

#[test]
fn an_injected_1000_ulp_error_is_found_where_it_was_put() {
    for (degree, mode) in [(2, Mode::Mirror), (3, Mode::Reflect), (5, Mode::GridWrap)] {
        let scipy = npy_f64(&format!("prefilter/d{degree}_{}.npy", mode.name()));
        let clean = check_prefilter(&input(degree, mode, scipy.clone(), None)).unwrap();
        for (index, region) in [(1, Region::Boundary), (100, Region::Interior)] {
            let mut user = scipy.clone();
            user[index] = ulps_above(scipy[index], 1000);
            let own = clean.elements[index].ulps;
            let s = check_prefilter(&input(degree, mode, user, Some(500.0 + own))).unwrap();
            let w = s.worst.unwrap();
            assert_eq!(
                (w.index, w.region),
                (index, Some(region)),
                "d{degree} {mode:?}"
            );
            assert!((w.ulps - 1000.0).abs() <= own + 1.0, "{} vs {own}", w.ulps);
            assert_eq!((s.failed, s.verdict.as_str()), (1, "fail"));
        }
    }
}

#[test]
fn f32_data_is_judged_in_f32_ulps() {
    let samples = npy_f32("prefilter/samples_f32.npy");
    let user = npy_f32("prefilter/d3_mirror_f32.npy");
    let mut inp = input(3, Mode::Mirror, user, Some(1.0));
    inp.samples = samples;
    inp.format = UserFormat::F32;
    let s = check_prefilter(&inp).unwrap();
    // scipy filters in double and rounds once to float32: ≤ ½ f32 ulp.
    let w = s.worst.clone().unwrap();
    assert!(w.ulps <= 0.5 + 1e-6 && w.ulps > 0.1, "{}", w.ulps);
    assert_eq!(s.verdict, "pass");
    // The same values in f64 ulps are ~2^29 times larger.
    inp.format = UserFormat::F64;
    let s64 = check_prefilter(&inp).unwrap();
    assert!(s64.worst.unwrap().ulps > 1e7);
}

#[test]
fn non_finite_user_values_fail_without_a_crash() {
    let mut user = npy_f64("prefilter/d3_mirror.npy");
    user[7] = f64::NAN;
    user[150] = f64::INFINITY;
    let s = check_prefilter(&input(3, Mode::Mirror, user, None)).unwrap();
    assert_eq!((s.non_finite, s.verdict.as_str()), (2, "fail"));
    assert_eq!(s.worst.unwrap().index, 7);
}

#[derive(serde::Deserialize)]
struct Spline {
    t: Vec<f64>,
    c: Vec<f64>,
    k: usize,
}

fn insertion_case(name: &str) -> (RationalBSpline, RationalBSpline) {
    let text = std::fs::read_to_string(fixture("knot_insertion.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let case = &v["cases"][name];
    let spline = |k: &str| {
        let s: Spline = serde_json::from_value(case[k].clone()).unwrap();
        RationalBSpline::from_f64(&s.t, &s.c, s.k).unwrap()
    };
    (spline("before"), spline("after"))
}

#[test]
fn knot_insertion_fails_scipy_right_end_and_passes_correct_ones() {
    let (b, a) = insertion_case("right_end_3");
    let s = check_knot_insertion(&b, &a, UserFormat::F64, None).unwrap();
    assert_eq!(s.verdict, "fail");
    assert!(!s.identical && s.max_deviation > 0.1, "{}", s.max_deviation);
    for name in ["interior_1.5", "at_knot_2"] {
        let (b, a) = insertion_case(name);
        let s = check_knot_insertion(&b, &a, UserFormat::F64, None).unwrap();
        assert_eq!(s.verdict, "pass", "{name}: {}", s.max_deviation_ulps);
        assert!(s.max_deviation < 1e-15);
    }
    // A spline against itself is identical, exactly.
    let s = check_knot_insertion(&b, &b, UserFormat::F64, Some(0.0)).unwrap();
    assert!(s.identical && s.max_deviation == 0.0 && s.verdict == "pass");
}

#[test]
fn scipy_bspline_values_are_within_a_few_ulps() {
    let text = std::fs::read_to_string(fixture("bspline_eval.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let f = |k: &str| -> Vec<f64> { serde_json::from_value(v[k].clone()).unwrap() };
    let inp = BSplineEvalInput {
        t: f("t"),
        c: f("c"),
        k: 3,
        extrapolate: true,
        x: f("x"),
        user: f("values"),
        format: UserFormat::F64,
        max_ulps: Some(64.0),
    };
    let s = check_bspline_eval(&inp).unwrap();
    assert_eq!(s.verdict, "pass", "{:?}", s.worst);
    assert!(s.median_ulps <= 2.0);
    // Without extrapolation the outside values must be NaN: scipy's are not.
    let s = check_bspline_eval(&BSplineEvalInput {
        extrapolate: false,
        ..inp
    })
    .unwrap();
    assert_eq!(s.verdict, "fail");
}

#[test]
fn bezier_values_against_exact_de_casteljau() {
    // (1 − t)² + 2·3 t(1 − t) − t² at dyadic t is exact in f64.
    let b = [1.0, 3.0, -1.0];
    let t: Vec<f64> = (0..=16).map(|i| i as f64 / 16.0).collect();
    let mut user: Vec<f64> = t
        .iter()
        .map(|t| (1.0 - t) * (1.0 - t) + 6.0 * t * (1.0 - t) - t * t)
        .collect();
    let s = check_bezier_eval(&b, &t, &user, UserFormat::F64, Some(0.0)).unwrap();
    assert_eq!((s.verdict.as_str(), s.worst.unwrap().ulps), ("pass", 0.0));
    user[5] = ulps_above(user[5], 3);
    let s = check_bezier_eval(&b, &t, &user, UserFormat::F64, Some(2.0)).unwrap();
    let w = s.worst.unwrap();
    assert_eq!((w.index, w.ulps, s.failed), (5, 3.0, 1));
}

#[test]
fn bad_input_is_a_typed_error() {
    let mut inp = input(3, Mode::Mirror, vec![0.0; 5], None);
    assert!(matches!(
        check_prefilter(&inp),
        Err(CheckError::LengthMismatch {
            expected: 200,
            got: 5,
            ..
        })
    ));
    inp.user = vec![0.0; 200];
    inp.samples[3] = f64::NAN;
    assert!(matches!(
        check_prefilter(&inp),
        Err(CheckError::NonFiniteInput { index: 3, .. })
    ));
    assert!(matches!(
        family_of_degree(0),
        Err(CheckError::DegreeOutOfRange { .. })
    ));
    assert!(matches!(
        family_of_degree(16),
        Err(CheckError::DegreeOutOfRange { .. })
    ));
    assert!(check_bezier_eval(&[], &[0.5], &[1.0], UserFormat::F64, None).is_err());
    assert!(RationalBSpline::from_f64(&[0.0, 1.0, 2.0], &[1.0, 2.0], 1).is_err());
}
