//! The scalar layer against published constants and exact rationals.

use proptest::prelude::*;
use rug::{Float, Rational};
use splinelab::scalar::prelude::*;
use splinelab::scalar::{DekkerProduct, FmaProduct, TwoProduct, fast_two_sum, two_prod, two_sum};

// Published decimal expansions (OEIS A000796, A002193, A001113), 61 digits.
const PI_60: &str = "3.141592653589793238462643383279502884197169399375105820974944";
const SQRT2_60: &str = "1.414213562373095048801688724209698078569671875376948073176679";
const E_60: &str = "2.718281828459045235360287471352662497757247093699959574966967";

/// Asserts that `x` agrees with the published expansion to 60 significant
/// digits: |x − published| < 10^(−59) (|x| is in [1, 10)).
fn assert_60_digits(x: &Mp<256>, published: &str) {
    let p = Float::with_val(400, Float::parse(published).unwrap());
    let diff = Float::with_val(400, x.as_float() - &p).abs();
    assert!(
        diff < Float::with_val(64, 1e-59),
        "{x} vs {published}: diff {diff}"
    );
}

#[test]
fn mpfr_constants_match_published_values_to_60_digits() {
    assert_60_digits(&Mp::<256>::pi(), PI_60);
    assert_60_digits(&Mp::<256>::from_int(2).sqrt(), SQRT2_60);
    assert_60_digits(&Mp::<256>::e(), E_60);
}

#[test]
fn mp_arithmetic_is_correctly_rounded_against_rationals() {
    // 1/3 + 1/7 at 100 bits: the exact sum is 10/21; one rounding of the
    // exact 1/3 and 1/7 each, then of the sum: error ≤ 2u relative.
    type M = Mp<100>;
    let third = M::from_rational(&Rational::from((1, 3)));
    let seventh = M::from_rational(&Rational::from((1, 7)));
    let sum = (third + seventh).to_rational().unwrap();
    let exact = Rational::from((10, 21));
    let rel = ((sum - &exact) / exact).abs();
    let u = Rational::from((1, 1)) >> 100u32;
    assert!(rel <= Rational::from(3) * u);
}

#[test]
fn f64_round_trip_is_lossless_and_decimal_output_has_the_digits_requested() {
    let x = 0.1f64;
    let m = Mp::<128>::from_f64_exact(x);
    assert_eq!(m.to_rational().unwrap(), Rational::from_f64(x).unwrap());
    assert_eq!(m.to_f64(), x);
    // 0.1 in binary is 0.1000000000000000055511151231257827...
    assert_eq!(m.to_decimal(20), "1.0000000000000000555e-1");
    assert_eq!(f64::from_rational(&Rational::from((1, 3))), 1.0 / 3.0);
}

#[test]
fn default_epsilon_is_the_machine_epsilon_of_the_precision() {
    use approx::AbsDiffEq;
    let eps = <Mp<256> as AbsDiffEq>::default_epsilon();
    assert_eq!(eps.to_rational().unwrap(), Rational::from(1) >> 255u32);
    assert_eq!(
        Mp::<256>::unit_roundoff().to_rational().unwrap(),
        Rational::from(1) >> 256u32
    );
}

fn exact(x: f64) -> Rational {
    Rational::from_f64(x).unwrap()
}

use crate::common;
use common::strategies::finite_f64;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn two_sum_is_exact(a in finite_f64(), b in finite_f64()) {
        let (s, e) = two_sum(a, b);
        prop_assume!(s.is_finite());
        prop_assert_eq!(exact(s) + exact(e), exact(a) + exact(b));
    }

    #[test]
    fn two_sum_is_exact_on_near_cancellation(a in finite_f64(), k in 0i32..60, d in -4i64..4) {
        // b ≈ −a(1 − 2^−k) shifted by a few ulps: heavy cancellation.
        let b = -a * (1.0 - 2f64.powi(-k)) + d as f64 * f64::EPSILON * a;
        let (s, e) = two_sum(a, b);
        prop_assume!(s.is_finite());
        prop_assert_eq!(exact(s) + exact(e), exact(a) + exact(b));
    }

    #[test]
    fn fast_two_sum_is_exact_when_ordered(a in finite_f64(), b in finite_f64()) {
        let (a, b) = if a.abs() >= b.abs() { (a, b) } else { (b, a) };
        let (s, e) = fast_two_sum(a, b);
        prop_assume!(s.is_finite());
        prop_assert_eq!(exact(s) + exact(e), exact(a) + exact(b));
    }

    #[test]
    fn two_prod_is_exact(m1 in any::<i64>(), m2 in any::<i64>(), e1 in -400i32..400, e2 in -400i32..400) {
        // Exponents kept where the error term cannot underflow.
        let (a, b) = (m1 as f64 * 2f64.powi(e1), m2 as f64 * 2f64.powi(e2));
        let (p, e) = two_prod(a, b);
        prop_assert_eq!(exact(p) + exact(e), exact(a) * exact(b));
    }

    #[test]
    fn f64_from_int_is_correctly_rounded(n in any::<i64>()) {
        // The fast `as` conversion against MPFR's correctly rounded one.
        let exact = Float::with_val(53, n).to_f64();
        prop_assert_eq!(f64::from_int(n).to_bits(), exact.to_bits());
    }

    #[test]
    fn fma_and_dekker_routes_are_both_exact(m1 in any::<i64>(), m2 in any::<i64>(), e1 in -400i32..400, e2 in -400i32..400) {
        // The run-time dispatch may take either route: each must be exact on
        // its own (FmaProduct is exact everywhere; fast only with hardware FMA).
        let (a, b) = (m1 as f64 * 2f64.powi(e1), m2 as f64 * 2f64.powi(e2));
        for (p, e) in [FmaProduct::two_prod(a, b), DekkerProduct::two_prod(a, b)] {
            prop_assert_eq!(exact(p) + exact(e), exact(a) * exact(b));
        }
    }

    #[test]
    fn two_prod_is_exact_on_ties(k in 1u32..52) {
        // (1 + 2^−k)² has a 2k-bit significand: exact only through the error term.
        let a = 1.0 + 2f64.powi(-(k as i32));
        let (p, e) = two_prod(a, a);
        prop_assert_eq!(exact(p) + exact(e), exact(a) * exact(a));
    }
}
