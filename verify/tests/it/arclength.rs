//! Arc length (`ParamCurveArclen`) against closed forms — a straight cubic
//! of uneven speed, circle arcs by rational quadratic NURBS, the parabola —
//! and against 256-bit MPFR references for curves without one (a cubic
//! Bézier, a centripetal Catmull–Rom spline, a free-form NURBS); the inverse
//! `inv_arclen` judged by the MPFR length up to the returned parameter.

use nalgebra::Vector2;
use rug::Float;
use rug::float::Constant;
use splinelab::arclength::{ArclenError, ParamCurveArclen};
use splinelab::bernstein::bezier::Bezier;
use splinelab::bspline::knots::KnotVector;
use splinelab::bspline::nurbs::NurbsCurve;
use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
use splinelab::scalar::prelude::*;
use splinelab_verify::flatten_reference::{lift256, nurbs_with_twin};

type M = Mp<256>;
const BITS: u32 = 256;

fn v(x: f64, y: f64) -> Vector2<f64> {
    Vector2::new(x, y)
}

/// `|got − want| ≤ tol`, `want` in MPFR.
fn close(got: f64, want: &Float, tol: f64, what: &str) {
    let err = (Float::with_val(BITS, got) - want).abs().to_f64();
    assert!(
        err <= tol,
        "{what}: {got} vs {want:.20}: error {err:e} > {tol:e}"
    );
}

/// The quarter-or-less circle arc of angle `theta` as a rational quadratic
/// NURBS: `(1, 0), (1, tan θ/2), (cos θ, sin θ)`, middle weight `cos θ/2`.
fn arc<T: Real>(theta: &T) -> NurbsCurve<T, 2> {
    let half = theta.clone().scale_by_pow2(-1);
    let pts = vec![
        Vector2::new(T::one(), T::zero()),
        Vector2::new(T::one(), half.clone().tan()),
        Vector2::new(theta.clone().cos(), theta.clone().sin()),
    ];
    let knots = KnotVector::new([0, 0, 0, 1, 1, 1].map(T::from_int).to_vec()).unwrap();
    NurbsCurve::new(3, pts, vec![T::one(), half.cos(), T::one()], knots).unwrap()
}

#[test]
fn a_straight_cubic_of_uneven_speed_has_its_chord_length() {
    // Control points at 0, 1, 4, 5 along (3, 4)/5: monotone, length 5.
    let c = Bezier::new(vec![v(0.0, 0.0), v(0.6, 0.8), v(2.4, 3.2), v(3.0, 4.0)]).unwrap();
    for acc in [1e-6, 1e-10, 1e-13] {
        close(
            c.arclen(&acc).unwrap(),
            &Float::with_val(BITS, 5),
            acc,
            "line",
        );
    }
    // Along the line the point at length s is s·(3, 4)/5.
    for s in [0.0, 0.7, 2.5, 4.9, 5.0] {
        let t = c.inv_arclen(&s, &1e-12).unwrap();
        let p = c.eval(&t).unwrap();
        assert!((p - v(0.6 * s, 0.8 * s)).norm() <= 2e-12, "s = {s}: {p}");
    }
}

#[test]
fn circle_arcs_by_rational_quadratic_nurbs_have_length_r_theta() {
    let pi = Float::with_val(BITS, Constant::Pi);
    for k in [1, 2, 3, 4] {
        // θ = kπ/8 (a single rational quadratic needs θ < π).
        let theta = Float::with_val(BITS, Float::with_val(BITS, &pi * k) / 8u32);
        let c = arc(&theta.to_f64());
        close(c.arclen(&1e-12).unwrap(), &theta, 1e-12, "arc f64");
        let exact = arc(&M::from_float(&theta));
        let got = exact.arclen(&M::from_f64_exact(1e-60)).unwrap().to_float();
        close(0.0, &(got - &theta), 1e-60, "arc MPFR");
    }
    // The 9-point full circle of radius 2: 4π; half of it lands at (−2, 0).
    let circle = NurbsCurve::circle(&v(0.0, 0.0), &2.0).unwrap();
    let four_pi = Float::with_val(BITS, &pi * 4);
    close(circle.arclen(&1e-12).unwrap(), &four_pi, 1e-12, "circle");
    let t = circle
        .inv_arclen(&(2.0 * std::f64::consts::PI), &1e-12)
        .unwrap();
    assert!((circle.eval(&t).unwrap() - v(-2.0, 0.0)).norm() < 1e-11);
}

#[test]
fn the_parabola_has_its_closed_form_length() {
    // (t, t²) on [0, 1]: ∫ √(1 + 4t²) = √5/2 + asinh(2)/4.
    let exact = Float::with_val(BITS, 5).sqrt() / 2 + Float::with_val(BITS, 2).asinh() / 4;
    let c = Bezier::new(vec![v(0.0, 0.0), v(0.5, 0.0), v(1.0, 1.0)]).unwrap();
    for acc in [1e-8, 1e-12, 1e-14] {
        close(c.arclen(&acc).unwrap(), &exact, acc, "parabola f64");
    }
    let m = Bezier::new(vec![
        lift256(&v(0.0, 0.0)),
        lift256(&v(0.5, 0.0)),
        lift256(&v(1.0, 1.0)),
    ])
    .unwrap();
    let got = m.arclen(&M::from_f64_exact(1e-70)).unwrap().to_float();
    close(0.0, &(got - &exact), 1e-70, "parabola MPFR");
}

/// The f64 length to 1e-12 against the same curve's 256-bit length to
/// 1e-30, and `inv_arclen` judged by the MPFR length up to its parameter.
fn against_mpfr<C, E>(name: &str, curve: &C, exact: &E)
where
    C: ParamCurveArclen<f64, 2>,
    C::Error: std::fmt::Debug + 'static,
    E: ParamCurveArclen<M, 2>,
    E::Error: std::fmt::Debug + 'static,
{
    let fine = M::from_f64_exact(1e-30);
    let reference = exact.arclen(&fine).unwrap().to_float();
    let total = curve.arclen(&1e-12).unwrap();
    close(total, &reference, 1e-12, name);
    let (a, _) = exact.domain();
    for frac in [0.1, 0.5, 0.93] {
        let s = frac * total;
        let t = curve.inv_arclen(&s, &1e-10).unwrap();
        let at = exact
            .arclen_between(&a, &M::from_f64_exact(t), &fine)
            .unwrap()
            .to_float();
        close(s, &at, 1e-10, &format!("{name}: inverse at {frac}"));
    }
}

#[test]
fn curves_without_a_closed_form_match_mpfr() {
    let pts = [v(0.0, 0.0), v(1.0, 2.5), v(3.0, -1.0), v(4.0, 1.0)];
    let bezier = Bezier::new(pts.to_vec()).unwrap();
    let exact = Bezier::new(pts.iter().map(lift256).collect()).unwrap();
    against_mpfr("cubic Bézier", &bezier, &exact);

    // A centripetal Catmull–Rom spline: C¹ only, so the speed has kinks at
    // the knots; the MPFR twin uses the exact chord-length knots.
    let cr = [
        v(0.0, 0.0),
        v(1.0, 1.0),
        v(1.2, 3.0),
        v(4.0, 2.0),
        v(5.0, 0.0),
        v(6.5, 1.0),
    ];
    let c = CatmullRom::new(cr.to_vec(), Spacing::Centripetal, false).unwrap();
    let exact = CatmullRom::new(
        cr.iter().map(lift256).collect(),
        Spacing::Centripetal,
        false,
    )
    .unwrap();
    // The knots differ by f64 rounding: compare at that scale.
    let reference = exact.arclen(&M::from_f64_exact(1e-30)).unwrap().to_float();
    close(c.arclen(&1e-12).unwrap(), &reference, 1e-12, "Catmull–Rom");

    // A free-form cubic NURBS and its exact 256-bit twin.
    let xy = [(0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 2.5), (6.0, 0.0)];
    let q: Vec<_> = xy.iter().map(|&(x, y)| v(x, y)).collect();
    let w = [1.0, 3.0, 0.5, 2.0, 1.0];
    let knots = [0.0, 0.0, 0.0, 0.0, 1.5, 3.0, 3.0, 3.0, 3.0];
    let (nurbs, exact) = nurbs_with_twin(4, &q, &w, &knots).unwrap();
    against_mpfr("NURBS", &nurbs, &exact);
}

#[test]
fn bad_accuracy_and_lengths_are_typed_errors() {
    let c = Bezier::new(vec![v(0.0, 0.0), v(3.0, 4.0)]).unwrap();
    for acc in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            c.arclen(&acc),
            Err(ArclenError::OutOfRange {
                name: "accuracy",
                ..
            })
        ));
    }
    for s in [-1.0, 5.1, f64::NAN] {
        assert!(matches!(
            c.inv_arclen(&s, &1e-9),
            Err(ArclenError::OutOfRange {
                name: "arc length",
                ..
            })
        ));
    }
    assert_eq!(c.inv_arclen(&5.0, &1e-9).unwrap(), 1.0);
}
