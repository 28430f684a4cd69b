//! Flattening over any curve of Bézier pieces (`ParamCurveBezier`): NURBS,
//! Catmull–Rom, S-spline and B-spline curves flattened by both methods
//! (greedy chords and subdivision), each polyline's largest distance from the
//! curve judged in 256-bit MPFR on the curve rebuilt exactly from the same
//! data (`deviation_of_curve_in_mpfr`), and required `≤ tol`.

use nalgebra::Vector2;
use splinelab::bspline::de_boor::BSpline;
use splinelab::bspline::knots::KnotVector;
use splinelab::bspline::nurbs::NurbsCurve;
use splinelab::curves::bezier_pieces::ParamCurveBezier;
use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
use splinelab::curves::flatten::{Polyline, flatten, max_deviation};
use splinelab::curves::greedy_flatten::flatten_greedy;
use splinelab::curves::sspline_curve::SsplineCurve;
use splinelab::param_curve::ParamCurve;
use splinelab::scalar::prelude::*;
use splinelab::sspline::{SplineFamily, end_conditions::EndCondition};
use splinelab_verify::flatten_reference::{
    deviation_of_curve_in_mpfr, lift256, nurbs_twin, nurbs_with_twin,
};

type M = Mp<256>;

/// MPFR samples per chord when judging.
const SAMPLES: usize = 16;

fn v(x: f64, y: f64) -> Vector2<f64> {
    Vector2::new(x, y)
}

fn lift_knots(k: &KnotVector<f64>) -> KnotVector<M> {
    KnotVector::new(k.as_slice().iter().map(|&x| M::from_f64_exact(x)).collect()).unwrap()
}

/// Chords judged in MPFR: all of them up to this many, else this many with
/// the largest f64 measure (a chord whose true deviation passed `tol` has an
/// f64 measure within rounding of it, far above the rest).
const JUDGED: usize = 100;

/// The largest MPFR-judged deviation over the [`JUDGED`] chords of `poly`
/// with the largest f64 measure; asserts the f64 measure of each is finite.
fn judged_worst<C, E>(curve: &C, exact: &E, poly: &Polyline<f64, 2>) -> f64
where
    C: ParamCurve<f64, 2>,
    C::Error: std::fmt::Debug,
    E: ParamCurve<M, 2>,
    E::Error: std::fmt::Debug,
{
    let chord = |j: usize| Polyline {
        params: poly.params[j..j + 2].to_vec(),
        points: poly.points[j..j + 2].to_vec(),
    };
    let mut measured: Vec<(f64, usize)> = (0..poly.segments())
        .map(|j| (max_deviation(curve, &chord(j), SAMPLES).unwrap(), j))
        .collect();
    measured.sort_by(|a, b| b.0.total_cmp(&a.0));
    measured
        .iter()
        .take(JUDGED)
        .map(|&(_, j)| deviation_of_curve_in_mpfr(exact, &chord(j), SAMPLES).unwrap())
        .fold(0.0, f64::max)
}

/// Both methods at each tolerance: the polyline's ends are the curve's, its
/// parameters cover the domain, and the MPFR-judged deviation is `≤ tol`.
/// Returns the segment counts (greedy, subdivision) at the last tolerance.
fn check<C, E>(name: &str, curve: &C, exact: &E, tols: &[f64]) -> (usize, usize)
where
    C: ParamCurveBezier<f64, 2>,
    C::Error: std::fmt::Debug,
    E: ParamCurve<M, 2>,
    E::Error: std::fmt::Debug,
{
    let (lo, hi) = curve.domain();
    let mut counts = (0, 0);
    for &tol in tols {
        let greedy = flatten_greedy(curve, &tol).unwrap();
        let sub = flatten(curve, &tol).unwrap();
        for (method, poly) in [("greedy", &greedy), ("subdivision", &sub)] {
            assert_eq!((poly.params[0], *poly.params.last().unwrap()), (lo, hi));
            assert!(
                poly.params.windows(2).all(|w| w[0] < w[1]),
                "{name} {method}"
            );
            let ends = [curve.eval(&lo).unwrap(), curve.eval(&hi).unwrap()];
            let got = [poly.points[0], *poly.points.last().unwrap()];
            for (g, e) in got.iter().zip(&ends) {
                assert!((g - e).norm() < 1e-14, "{name} {method}: end {g} vs {e}");
            }
            let judged = judged_worst(curve, exact, poly);
            assert!(
                judged <= tol,
                "{name} {method} tol {tol:e}: MPFR {judged:e}"
            );
        }
        counts = (greedy.segments(), sub.segments());
    }
    counts
}

#[test]
fn nurbs_circle_and_a_free_form_nurbs_flatten_within_tol() {
    // The exact circle: the chord of angle θ on the unit circle deviates by
    // its sagitta 1 − cos(θ/2); tol = 1e-6 needs θ ≤ 2 acos(1 − 1e-6), i.e.
    // at least 2π / 2.83e-3 ≈ 2221 chords of the optimum.
    let circle = NurbsCurve::circle(&v(0.0, 0.0), &1.0).unwrap();
    let exact = nurbs_twin(&circle).unwrap();
    let (greedy, sub) = check("circle", &circle, &exact, &[1e-3, 1e-6, 1e-10]);
    let sagitta_count = 2.0 * std::f64::consts::PI / (2.0 * (1.0 - 1e-10f64).acos());
    assert!(
        greedy as f64 >= sagitta_count.floor(),
        "{greedy} < {sagitta_count}"
    );
    assert!(sub >= greedy, "{sub} < {greedy}");

    // A cubic NURBS with uneven weights on an unclamped knot vector.
    let q = [
        v(0.0, 0.0),
        v(1.0, 3.0),
        v(2.5, -1.0),
        v(4.0, 2.0),
        v(5.0, 0.0),
        v(7.0, 1.5),
    ];
    let w = [1.0, 3.0, 0.5, 2.0, 1.0, 0.75];
    let knots = [0.0, 0.5, 1.0, 2.0, 2.5, 4.0, 4.25, 5.0, 6.0, 7.0];
    let (free, exact) = nurbs_with_twin(4, &q, &w, &knots).unwrap();
    check("free-form NURBS", &free, &exact, &[1e-2, 1e-6, 1e-10]);
}

#[test]
fn catmull_rom_splines_flatten_within_tol() {
    let pts = vec![
        v(0.0, 0.0),
        v(1.0, 2.0),
        v(1.5, 2.1),
        v(4.0, -1.0),
        v(5.0, 0.5),
        v(5.2, 3.0),
    ];
    for spacing in [Spacing::Uniform, Spacing::Centripetal, Spacing::Chordal] {
        // Closed once: the wrap-around segment is one more cubic.
        let closings: &[bool] = if spacing == Spacing::Centripetal {
            &[false, true]
        } else {
            &[false]
        };
        for &closed in closings {
            let c = CatmullRom::new(pts.clone(), spacing, closed).unwrap();
            let exact =
                CatmullRom::new(pts.iter().map(lift256).collect(), spacing, closed).unwrap();
            let name = format!("{} closed={closed}", spacing.name());
            check(&name, &c, &exact, &[1e-3, 1e-9]);
        }
    }
}

#[test]
fn sspline_and_bspline_curves_flatten_within_tol() {
    let data: Vec<_> = (0..9)
        .map(|i| v(i as f64, ((i * i * 7) % 5) as f64 - 2.0))
        .collect();
    for order in [3, 4, 5] {
        let s =
            SsplineCurve::new(&SplineFamily::Order(order), 20, &data, EndCondition::Free).unwrap();
        // The curve's own B-spline view, lifted exactly: the same curve in MPFR.
        let b = s.to_bspline().unwrap();
        let exact = BSpline::new(
            b.order(),
            b.points().iter().map(lift256).collect(),
            lift_knots(b.knots()),
        )
        .unwrap();
        let (greedy, _) = check(
            &format!("S-spline order {order}"),
            &s,
            &exact,
            &[1e-3, 1e-9],
        );
        // One S-spline piece per unit span at least.
        assert!(greedy >= 8, "{greedy}");
        check(&format!("its B-spline, order {order}"), &b, &exact, &[1e-6]);
    }
}

#[test]
fn a_bezier_curve_flattens_as_before_through_the_pieces() {
    // The one-piece path is the old Bézier path: parameters on [0, 1] and the
    // subdivision's dyadic parameters exactly (P(t) = (2t, 4t(1 − t)), flat at
    // depth 6 everywhere at 1e-3: `flatten`'s own closed-form test).
    let c = splinelab::bernstein::bezier::Bezier::new(vec![v(0.0, 0.0), v(1.0, 2.0), v(2.0, 0.0)])
        .unwrap();
    let poly: Polyline<f64, 2> = flatten(&c, &1e-3).unwrap();
    assert!(poly.params.iter().all(|t| (t * 64.0).fract() == 0.0));
}
