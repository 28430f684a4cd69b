//! The capability traits of `splinelab::param_curve`, checked through the
//! traits alone: every derivative a type reports is the limit of its own
//! points. In 256-bit MPFR the symmetric difference
//! `(P(t + h) − P(t − h)) / 2h` with `h = 2⁻⁶⁰` differs from `P'(t)` by
//! `h² |P'''| / 6 ≈ 10⁻³⁷` (truncation) plus `u |P| / h ≈ 10⁻⁵⁹` (rounding),
//! so agreement to `10⁻³⁰` (relative to `max(|P'|, 1)`) checks each
//! derivative against a second, independent route. Also: the domain ends
//! evaluate, and [`sample`] visits them.

use nalgebra::{Vector2, Vector3};
use splinelab::bernstein::bezier::Bezier;
use splinelab::bspline::de_boor::BSpline;
use splinelab::bspline::knots::KnotVector;
use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
use splinelab::curves::hermite::Hermite;
use splinelab::param_curve::{ParamCurveDeriv, ParamSurface, ParamSurfaceDeriv, sample};
use splinelab::qi::cubic_spline::{ClampedCubicSpline, Parameterization};
use splinelab::qi::{QiOptions, interpolate};
use splinelab::scalar::prelude::*;
use splinelab::surface_deformation::patch::Patch;

type M = Mp<256>;

fn m(x: f64) -> M {
    M::from_f64_exact(x)
}

fn h() -> M {
    m(1.0).scale_by_pow2(-60)
}

/// At 7 interior parameters (irrational fractions of the domain, away
/// from knots), `deriv` matches the symmetric difference of `eval`.
fn check_curve<const D: usize, C: ParamCurveDeriv<M, D>>(name: &str, c: &C)
where
    C::Error: std::fmt::Debug,
{
    let (a, b) = c.domain();
    for k in 1..=7 {
        let frac = m(k as f64 * 0.123_456_789_1);
        let t = a.clone() + (b.clone() - a.clone()) * frac;
        let fd = (c.eval(&(t.clone() + h())).unwrap() - c.eval(&(t.clone() - h())).unwrap())
            / (m(2.0) * h());
        let d = c.deriv(&t).unwrap();
        let scale = d.norm().max(m(1.0));
        let err = (fd - &d).norm() / scale;
        assert!(err < m(1e-30), "{name} at t = {t:?}: {err:?}");
    }
    let ends = sample(c, 5).unwrap();
    assert_eq!(ends.len(), 6);
    assert_eq!(
        ends[0],
        c.eval(&a).unwrap(),
        "{name}: sample starts at the domain start"
    );
    assert_eq!(
        ends[5],
        c.eval(&b).unwrap(),
        "{name}: sample ends at the domain end"
    );
}

fn v2(x: f64, y: f64) -> Vector2<M> {
    Vector2::new(m(x), m(y))
}

fn v3(x: f64, y: f64, z: f64) -> Vector3<M> {
    Vector3::new(m(x), m(y), m(z))
}

fn walk() -> Vec<Vector3<M>> {
    vec![
        v3(0.0, 0.0, 0.0),
        v3(1.0, 1.0, 0.5),
        v3(2.0, 0.5, 1.5),
        v3(3.0, 1.5, 2.0),
    ]
}

#[test]
fn curve_derivatives_are_the_limits_of_their_points() {
    let pts = vec![
        v2(0.0, 0.0),
        v2(1.2, 2.0),
        v2(-0.2, 2.0),
        v2(1.0, 0.0),
        v2(3.0, 1.0),
    ];
    check_curve("Bezier", &Bezier::new(pts.clone()).unwrap());
    check_curve(
        "Hermite",
        &Hermite::new(v2(0.0, 0.0), v2(1.0, 0.5), v2(0.0, 3.0), v2(2.0, -3.0)).unwrap(),
    );
    for spacing in [Spacing::Uniform, Spacing::Centripetal, Spacing::Chordal] {
        check_curve(
            &format!("CatmullRom {spacing:?}"),
            &CatmullRom::new(pts.clone(), spacing, false).unwrap(),
        );
    }
    let knots = KnotVector::clamped_uniform(4, pts.len()).unwrap();
    check_curve("BSpline", &BSpline::new(4, pts, knots).unwrap());
    let w = walk();
    let (t0, t1) = (v3(1.0, 0.0, 0.0), v3(0.0, 0.0, 1.0));
    for param in [Parameterization::ChordLength, Parameterization::Uniform] {
        check_curve(
            &format!("ClampedCubicSpline {param:?}"),
            &ClampedCubicSpline::new(&w, param, &t0, &t1).unwrap(),
        );
    }
    check_curve(
        "QiInterpolation",
        &interpolate(&w, &QiOptions::default()).unwrap(),
    );
}

#[test]
fn patch_partials_are_the_limits_of_its_points() {
    let control: Vec<Vector3<M>> = (0..16)
        .map(|k| v3((k / 4) as f64, (k % 4) as f64, ((k * 7) % 5) as f64 * 0.3))
        .collect();
    let p = Patch::new(3, control).unwrap();
    let ((a, _), (c, _)) = ParamSurface::domain(&p);
    assert_eq!((a, c), (m(0.0), m(0.0)));
    for (u, v) in [(0.3, 0.6), (0.71, 0.2), (0.5, 0.5)] {
        let (u, v) = (m(u), m(v));
        let (su, sv) = p.partials(&u, &v).unwrap();
        let at = |u: &M, v: &M| ParamSurface::eval(&p, u, v).unwrap();
        let fu = (at(&(u.clone() + h()), &v) - at(&(u.clone() - h()), &v)) / (m(2.0) * h());
        let fv = (at(&u, &(v.clone() + h())) - at(&u, &(v.clone() - h()))) / (m(2.0) * h());
        assert!((fu - su).norm() < m(1e-30));
        assert!((fv - sv).norm() < m(1e-30));
    }
}
