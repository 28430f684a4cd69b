//! de Casteljau evaluation and subdivision, written once over the scalar and
//! run in f64 and in MPFR, against exact rational references.

use nalgebra::Vector2;
use proptest::prelude::*;
use rug::Rational;
use splinelab::bernstein::bezier::{BernsteinPoly, Bezier};
use splinelab::scalar::prelude::*;
use splinelab_verify::bezier_eval::ExactPoly;

/// `γ_k` for the unit roundoff of `T`, exactly.
fn gamma_t<T: Real>(k: usize) -> Rational {
    let ku = Rational::from(k as u64) * (Rational::from(1) >> T::BITS);
    &ku / (Rational::from(1) - &ku)
}

fn exact_coords<T: Real>(c: &Bezier<T, 2>, k: usize) -> ExactPoly {
    let q: Vec<Rational> = c
        .points()
        .iter()
        .map(|p| p[k].to_rational().unwrap())
        .collect();
    ExactPoly::new(&q)
}

/// Subdivision consistency: the halves at `t` reproduce the curve,
/// `L(s) = P(ts)` and `R(s) = P(t + (1 − t)s)`, up to the rounding of the
/// new control points (each a de Casteljau value: within `γ_{3n} max|P_i|`).
fn subdivision_reproduces_curve<T: Real>(pts: &[(f64, f64)], t: f64) -> Result<(), TestCaseError> {
    let curve = Bezier::<T, 2>::new(
        pts.iter()
            .map(|&(x, y)| Vector2::new(T::from_f64_exact(x), T::from_f64_exact(y)))
            .collect(),
    )
    .unwrap();
    let n = curve.degree();
    let (left, right) = curve.subdivide(&T::from_f64_exact(t)).unwrap();
    let tq = Rational::from_f64(t).unwrap();
    for k in 0..2 {
        let max = pts
            .iter()
            .map(|p| if k == 0 { p.0.abs() } else { p.1.abs() })
            .fold(0.0, f64::max);
        let tol = gamma_t::<T>(3 * n) * Rational::from_f64(max).unwrap();
        let (p, l, r) = (
            exact_coords(&curve, k),
            exact_coords(&left, k),
            exact_coords(&right, k),
        );
        for j in 0..=8 {
            let s = Rational::from((j, 8));
            let on_left = Rational::from(&tq * &s);
            let on_right = &tq + (Rational::from(1) - &tq) * &s;
            let dl = (l.value(&s) - p.value(&on_left)).abs();
            let dr = (r.value(&s) - p.value(&on_right)).abs();
            prop_assert!(dl <= tol, "left half off by {} at s={s}", dl.to_f64());
            prop_assert!(dr <= tol, "right half off by {} at s={s}", dr.to_f64());
        }
    }
    // The split point is shared and equals P(t) as evaluated.
    prop_assert_eq!(left.points()[n].clone(), right.points()[0].clone());
    prop_assert_eq!(
        left.points()[n].clone(),
        curve.eval(&T::from_f64_exact(t)).unwrap()
    );
    Ok(())
}

/// de Casteljau and its running bound against the exact value, with the
/// a-priori bound `γ_{3n} Σ|b_i|B_i^n(t)` of the precision `T`.
fn de_casteljau_within_bounds<T: Real>(c: &[f64], t: f64) -> Result<(), TestCaseError> {
    let poly = BernsteinPoly::<T>::from_f64(c).unwrap();
    let exact = ExactPoly::from_f64(c);
    let tq = Rational::from_f64(t).unwrap();
    let e = poly.de_casteljau_bounded(&T::from_f64_exact(t)).unwrap();
    prop_assert_eq!(
        e.value.clone(),
        poly.de_casteljau(&T::from_f64_exact(t)).unwrap()
    );
    let err = (e.value.to_rational().unwrap() - exact.value(&tq)).abs();
    prop_assert!(err <= e.bound.to_rational().unwrap());
    prop_assert!(err <= gamma_t::<T>(3 * poly.degree()) * exact.abs_sum(&tq));
    Ok(())
}

fn points() -> impl Strategy<Value = Vec<(f64, f64)>> {
    prop::collection::vec((-10.0f64..10.0, -10.0f64..10.0), 1..=10)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn subdivision_consistency_f64(p in points(), t in 0.0f64..=1.0) {
        subdivision_reproduces_curve::<f64>(&p, t)?;
    }

    #[test]
    fn subdivision_consistency_mp128(p in points(), t in 0.0f64..=1.0) {
        subdivision_reproduces_curve::<Mp<128>>(&p, t)?;
    }

    #[test]
    fn de_casteljau_bounds_f64(c in prop::collection::vec(-1.0f64..1.0, 1..=16), t in 0.0f64..=1.0) {
        de_casteljau_within_bounds::<f64>(&c, t)?;
    }

    #[test]
    fn de_casteljau_bounds_mp106(c in prop::collection::vec(-1.0f64..1.0, 1..=16), t in 0.0f64..=1.0) {
        de_casteljau_within_bounds::<Mp<106>>(&c, t)?;
    }
}
