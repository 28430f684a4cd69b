//! Cubic Hermite segments (seed 002): end values and derivatives hold, and
//! the Hermite form agrees with its Bézier form (P₁ = P₀ + P'(0)/3,
//! P₂ = P₃ − P'(1)/3) evaluated by de Casteljau — in f64 and MPFR.

use nalgebra::Vector3;
use proptest::prelude::*;
use splinelab::bernstein::bezier::Bezier;
use splinelab::curves::hermite::Hermite;
use splinelab::scalar::prelude::*;
use splinelab_verify::curves::{bounds, hermite_errors};

fn v<T: Real>(p: [f64; 3]) -> Vector3<T> {
    Vector3::new(
        T::from_f64_exact(p[0]),
        T::from_f64_exact(p[1]),
        T::from_f64_exact(p[2]),
    )
}

fn check<T: Real>(data: &[[f64; 3]; 4]) {
    let h = Hermite::new(v::<T>(data[0]), v(data[1]), v(data[2]), v(data[3])).unwrap();
    let e = hermite_errors(&h).unwrap();
    for (name, x) in [
        ("end values", e.end_values),
        ("end derivatives", e.end_derivatives),
        ("bezier agreement", e.bezier_agreement),
        ("conversion derivatives", e.conversion_derivatives),
    ] {
        assert!(
            x <= bounds::HERMITE,
            "{} {name}: {x} u > {} u",
            T::type_name(),
            bounds::HERMITE
        );
    }
}

fn coord() -> impl Strategy<Value = f64> {
    (-4096i32..=4096).prop_map(|j| j as f64 / 512.0)
}

fn point() -> impl Strategy<Value = [f64; 3]> {
    [coord(), coord(), coord()]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn end_values_derivatives_and_bezier_form_hold_in_f64(d in [point(), point(), point(), point()]) {
        check::<f64>(&d);
    }

    #[test]
    fn end_values_derivatives_and_bezier_form_hold_in_mp128(d in [point(), point(), point(), point()]) {
        check::<Mp<128>>(&d);
    }
}

#[test]
fn lecture_conversion_is_exact_on_dyadic_data() {
    // P'(0) = 3(P₁ − P₀) = (3, 6, 0), P'(1) = 3(P₃ − P₂) = (0, −3, 3).
    let b = Bezier::new(vec![
        v::<f64>([0.0, 0.0, 0.0]),
        v([1.0, 2.0, 0.0]),
        v([2.0, 3.0, -1.0]),
        v([2.0, 2.0, 0.0]),
    ])
    .unwrap();
    let h = Hermite::from_bezier(&b).unwrap();
    let (_, _, d0, d1) = h.ends();
    assert_eq!((*d0, *d1), (v([3.0, 6.0, 0.0]), v([0.0, -3.0, 3.0])));
    assert_eq!(h.to_bezier().unwrap(), b);
    // Power form at t = ½ against de Casteljau: both exact on these dyadics.
    assert_eq!(h.eval(&0.5), b.eval(&0.5).unwrap());
}
