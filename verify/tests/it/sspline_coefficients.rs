//! S-spline coefficients (seed 000 eq 9, 16–18, 29): closed forms, published
//! poles, cross-method agreement, the f64 production accuracy contract, and
//! property tests of the defining identities.

use proptest::prelude::*;
use rug::Rational;
use splinelab::scalar::{Mp, Real};
use splinelab::sspline::beta2::{coefficients_closed_form, cubic_coefficients_closed_form};
use splinelab::sspline::euler_frobenius::poles;
use splinelab::sspline::node_values::node_values;
use splinelab::sspline::{
    CoefficientMethod, SplineFamily, SsplineError, TruncatedBasis, coefficients,
};
use splinelab_verify::assertions::assert_ulps_close;
use splinelab_verify::metrics::{relative_error, ulps_f64};
use splinelab_verify::sspline::componentwise_condition;

type M = Mp<192>;

fn max_rel(a: &[M], b: &[M]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, r)| relative_error(x, &r.to_float()))
        .fold(0.0, f64::max)
}

#[test]
fn every_method_matches_eq18_for_the_cubic() {
    let exact = cubic_coefficients_closed_form::<Mp<320>>(61);
    let exact: Vec<M> = exact.iter().map(|x| x.convert::<M>()).collect();
    for method in CoefficientMethod::INDEPENDENT {
        let c: Vec<M> = coefficients(&SplineFamily::Order(4), 61, method).unwrap();
        let bits = -max_rel(&c, &exact).log2();
        assert!(bits >= (M::BITS - 10) as f64, "{method:?}: {bits} bits");
    }
}

#[test]
fn beta2_family_matches_eq29_and_zero_tension_is_the_cubic() {
    for t in ["0", "1/2", "1", "5", "10", "50", "1000"] {
        let f = SplineFamily::parse_tension(t).unwrap();
        let b = Mp::<320>::from_rational(f.tension().unwrap());
        let exact: Vec<M> = coefficients_closed_form(&b, 40)
            .iter()
            .map(|x: &Mp<320>| x.convert::<M>())
            .collect();
        for method in CoefficientMethod::INDEPENDENT {
            let c: Vec<M> = coefficients(&f, 40, method).unwrap();
            let bits = -max_rel(&c, &exact).log2();
            assert!(
                bits >= (M::BITS - 10) as f64,
                "β2={t} {method:?}: {bits} bits"
            );
        }
    }
    let cubic: Vec<f64> =
        coefficients(&SplineFamily::Order(4), 30, CoefficientMethod::Production).unwrap();
    let beta0: Vec<f64> = coefficients(
        &SplineFamily::beta2(Rational::new()).unwrap(),
        30,
        CoefficientMethod::Production,
    )
    .unwrap();
    assert_eq!(cubic, beta0);
}

#[test]
fn f64_poles_match_mpfr_poles_and_published_values() {
    // Unser–Aldroubi–Eden 1993, Table I, degrees 2..9 (m = 3..10): the dominant pole.
    let published = [
        (3, "-0.171572875253809902"),
        (4, "-0.267949192431122706"),
        (5, "-0.361341225900220177"),
        (6, "-0.430575347099973792"),
        (7, "-0.488294589303044755"),
        (8, "-0.535280430796438165"),
        (9, "-0.574686909248765430"),
        (10, "-0.607997389168625779"),
    ];
    for (m, want) in published {
        let f = SplineFamily::Order(m);
        let xi64: Vec<f64> = poles(&f).unwrap();
        let xi: Vec<Mp<256>> = poles(&f).unwrap();
        let want = Mp::<256>::parse(want).unwrap();
        assert!(
            relative_error(xi.last().unwrap(), &want.to_float()) < 1e-17,
            "m={m}"
        );
        for (a, b) in xi64.iter().zip(&xi) {
            assert!(
                relative_error(a, &b.to_float()) < 64.0 * f64::EPSILON,
                "m={m}"
            );
        }
    }
}

/// The production contract: c_i in f64 within 2 ulps for orders 2..24 and
/// i ≤ 60, against the recursive filter in 512-bit MPFR (a method that shares
/// no code with the partial-fraction production route beyond the poles).
#[test]
fn production_f64_is_within_two_ulps_up_to_order_24() {
    for m in 2..=24 {
        let f = SplineFamily::Order(m);
        let reference: Vec<Mp<512>> =
            coefficients(&f, 61, CoefficientMethod::RecursiveFilter).unwrap();
        let c: Vec<f64> = coefficients(&f, 61, CoefficientMethod::Production).unwrap();
        for (i, (x, r)) in c.iter().zip(&reference).enumerate() {
            assert_ulps_close(*x, &r.to_float(), 2.0, &format!("order {m} c_{i}"));
        }
    }
}

/// In MPFR the three methods agree to BITS − 10 bits up to order 10, and to
/// within 2^10 · u · cond_i (the componentwise condition number of c_i under
/// relative perturbations of the node values) up to order 40.
#[test]
fn methods_agree_in_mpfr_up_to_order_40() {
    for m in (2..=12).chain([16, 20, 24, 32, 40]) {
        let f = SplineFamily::Order(m);
        let count = 61;
        let cond = componentwise_condition(&f, count).unwrap();
        let runs: Vec<Vec<M>> = CoefficientMethod::INDEPENDENT
            .iter()
            .map(|meth| coefficients(&f, count, *meth).unwrap())
            .collect();
        let u = M::unit_roundoff().to_f64();
        for (a, b) in [(0, 1), (0, 2), (1, 2)] {
            for i in 0..count {
                let r = relative_error(&runs[a][i], &runs[b][i].to_float());
                assert!(
                    r <= 1024.0 * u * cond[i],
                    "m={m} i={i} methods {a},{b}: {r:e} cond {}",
                    cond[i]
                );
                if m <= 10 {
                    assert!(r <= 1024.0 * u, "m={m} i={i} methods {a},{b}: {r:e}");
                }
            }
        }
    }
}

#[test]
fn high_orders_work_in_mpfr() {
    for m in [60, 100] {
        let f = SplineFamily::Order(m);
        let a: Vec<Mp<256>> = coefficients(&f, 10, CoefficientMethod::PartialFractions).unwrap();
        let b: Vec<Mp<256>> = coefficients(&f, 10, CoefficientMethod::RecursiveFilter).unwrap();
        for (x, y) in a.iter().zip(&b) {
            assert!(relative_error(x, &y.to_float()) < 1e-40, "m={m}");
        }
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let c = |f: SplineFamily, k| coefficients::<f64>(&f, k, CoefficientMethod::Production);
    assert_eq!(
        c(SplineFamily::Order(1), 3),
        Err(SsplineError::OrderOutOfRange(1))
    );
    assert_eq!(
        c(SplineFamily::Order(201), 3),
        Err(SsplineError::OrderOutOfRange(201))
    );
    assert_eq!(c(SplineFamily::Order(4), 0), Err(SsplineError::ZeroCount));
    assert!(matches!(
        c(SplineFamily::Beta2(Rational::from(-1)), 3),
        Err(SsplineError::InvalidTension(_))
    ));
    assert!(SplineFamily::beta2_from_f64(f64::NAN).is_err());
    assert!(matches!(
        coefficients::<f64>(
            &SplineFamily::Order(190),
            3,
            CoefficientMethod::PartialFractions
        ),
        Err(SsplineError::PrecisionTooLow { .. })
    ));
}

fn family_strategy() -> impl Strategy<Value = SplineFamily> {
    prop_oneof![
        (2u32..=24).prop_map(SplineFamily::Order),
        (0i64..=400).prop_map(|k| SplineFamily::Beta2(Rational::from((k, 8)))),
    ]
}

/// `Σ_i c_i β(j − i) = δ_{0j}` at every node whose stencil lies inside the
/// computed range, with a residual at the rounding level of `Σ|c_i| β(j−i)`.
fn check_interpolation<T: Real>(
    f: &SplineFamily,
    method: CoefficientMethod,
) -> Result<(), TestCaseError> {
    let count = 40;
    let c: Vec<T> = coefficients(f, count, method).unwrap();
    let v: Vec<T> = node_values(f).unwrap();
    let p = (v.len() / 2) as i64;
    let ci = |i: i64| c[i.unsigned_abs() as usize].clone();
    for j in 0..(count as i64 - p) {
        let mut s = if j == 0 { -T::one() } else { T::zero() };
        let mut scale = T::zero();
        for d in -p..=p {
            let t = ci(j - d) * v[(p + d) as usize].clone();
            scale += t.clone().abs();
            s += t;
        }
        let tol = T::unit_roundoff() * T::from_int(64 * (2 * p + 1) * count as i64) * scale;
        prop_assert!(
            s.clone().abs() <= tol,
            "{f} j={j}: residual {:e}",
            s.to_f64()
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn coefficients_interpolate_at_every_node(f in family_strategy(), k in 0usize..3) {
        let method = CoefficientMethod::INDEPENDENT[k];
        check_interpolation::<f64>(&f, CoefficientMethod::Production)?;
        check_interpolation::<Mp<160>>(&f, method)?;
    }

    /// c_i = c_{−i} and β even make S_n even; x and −x fall in mirrored
    /// knot cells, so the two evaluations round differently, by at most the
    /// evaluation error `O(m² u)` (the basis values are ≤ 1 and Σ|c_i|β ≤ 2).
    #[test]
    fn truncated_basis_is_even(f in family_strategy(), n in 1usize..30, x in 0.0f64..40.0) {
        let m2 = f.spline_order().pow(2) as f64;
        let s = TruncatedBasis::<f64>::new(&f, n).unwrap();
        prop_assert!((s.eval(&x) - s.eval(&-x)).abs() <= 16.0 * m2 * f64::EPSILON);
        let s = TruncatedBasis::<Mp<128>>::new(&f, n).unwrap();
        let d = s.eval(&Mp::from_f64_exact(x)) - s.eval(&Mp::from_f64_exact(-x));
        prop_assert!(d.to_f64().abs() <= 16.0 * m2 * Mp::<128>::unit_roundoff().to_f64());
    }

    /// Σ_k S_n(x − k) = Σ_{|i|≤n} c_i, which is 1 up to the tail: for the
    /// closely truncated basis the sum is 1 within the tail bound + rounding.
    #[test]
    fn translates_sum_to_one(f in family_strategy(), x in 0.0f64..1.0) {
        let n = splinelab::sspline::f64_saturation_width(&f).unwrap();
        let s = TruncatedBasis::<f64>::new(&f, n).unwrap();
        let r = s.support_radius().ceil() as i64;
        let sum: f64 = (-r..=r).map(|k| s.eval(&(x - k as f64))).sum();
        let abs_sum: f64 = (-r..=r).map(|k| s.eval(&(x - k as f64)).abs()).sum();
        prop_assert!((sum - 1.0).abs() <= 4.0 * (2 * r + 1) as f64 * f64::EPSILON * abs_sum, "{}: {}", f, sum);
    }
}

#[test]
fn ulp_metric_sanity_for_the_reference() {
    // The 2-ulp contract is measured with the shared metric; check it on a
    // value whose distance is known exactly.
    let r = Mp::<512>::from_f64_exact(0.5);
    assert_eq!(ulps_f64(0.5 + 2.0 * f64::EPSILON / 2.0, &r.to_float()), 2.0);
}

/// `P(x)` exactly, `P` with the exact node values as coefficients.
fn euler_frobenius_at(family: &SplineFamily, x: f64) -> Rational {
    let a = splinelab::sspline::node_values::node_values_exact(family).unwrap();
    let x = Rational::from_f64(x).unwrap();
    a.iter().rev().fold(Rational::new(), |acc, c| acc * &x + c)
}

/// The f64 poles are correctly rounded (to within one ulp): `P` changes
/// sign, in exact rational arithmetic, between the neighbours of each
/// returned pole — including orders where Laguerre in f64 itself fails.
#[test]
fn rounded_poles_bracket_the_exact_roots_up_to_high_orders() {
    use splinelab::sspline::coefficients::poles_rounded;
    for m in [4u32, 7, 12, 40, 100, 130, 150] {
        let f = SplineFamily::Order(m);
        let xi: Vec<f64> = poles_rounded(&f).unwrap();
        assert_eq!(xi.len(), f.pole_count());
        for x in xi {
            let (lo, hi) = (
                euler_frobenius_at(&f, x.next_down()),
                euler_frobenius_at(&f, x.next_up()),
            );
            assert!(
                lo.cmp0() != hi.cmp0(),
                "order {m}: no sign change of P around {x:e}"
            );
        }
    }
}
