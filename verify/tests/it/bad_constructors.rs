//! The bad-input sweep of the public constructors of `splinelab`: non-finite
//! numbers, empty and one-element inputs, duplicate points, non-monotone
//! knots, out-of-range parameters and sizes whose arithmetic overflows. Each
//! must return the typed error of its module (the variant is checked), never
//! panic (a panic is caught and counted as a failure) and never accept the
//! input. Run for `f64` and `Mp<128>`; the number of cases is printed.

use nalgebra::{Vector2, Vector3};
use rug::Rational;
use splinelab::bernstein::bezier::{BernsteinPoly, Bezier, BezierError};
use splinelab::bspline::de_boor::{BSpline, BSplineData, BSplineError};
use splinelab::bspline::knots::{KnotError, KnotVector};
use splinelab::bspline::nurbs::{NurbsCurve, NurbsSurface};
use splinelab::curves::CurveError;
use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
use splinelab::curves::global_cubic::{CubicEnds, control_points as cubic_control_points};
use splinelab::curves::hermite::Hermite;
use splinelab::curves::rational_bezier::RationalBezier;
use splinelab::curves::sspline_curve::SsplineCurve;
use splinelab::curves::sspline_surface::{Direction, SsplineSurface};
use splinelab::qi::circle_tangent::start_tangent;
use splinelab::qi::cubic_spline::{ClampedCubicSpline, Parameterization};
use splinelab::qi::tangent::unit_direction;
use splinelab::qi::{QiError, QiOptions, interpolate};
use splinelab::quadrature::{GaussLegendre, QuadratureError, choose_order};
use splinelab::scalar::prelude::*;
use splinelab::sspline::end_conditions::{EndCondition, EndRule};
use splinelab::sspline::{
    Criterion, MAX_HALF_WIDTH, SplineFamily, SsplineError, TruncatedBasis, TruncationAnalysis,
    WidthChooser, truncation_width,
};
use splinelab::surface_deformation::bv_solve::{
    BvBidiagonal, BvError, Factorised, Method1d, TensorSolver,
};
use splinelab::surface_deformation::inverse_mapping::{
    InverseMappingError, SampleGrid, control_points as patch_from_samples, deform_grid,
};
use splinelab::surface_deformation::patch::{Patch, PatchError, PatchGrid, Point3};
use splinelab::surface_deformation::vandermonde::{NodeFamily, VandermondeError};
use splinelab::validation::InputError;
use std::fmt::Display;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// The tally of one sweep.
#[derive(Default)]
struct Sweep {
    tried: usize,
    failures: Vec<String>,
}

impl Sweep {
    /// `f` must return an error for which `expected` holds; an `Ok`, another
    /// error or a panic is a failure.
    fn check<R, E: Display + std::fmt::Debug>(
        &mut self,
        what: &str,
        f: impl FnOnce() -> Result<R, E>,
        expected: impl Fn(&E) -> bool,
    ) {
        self.tried += 1;
        let why = match catch_unwind(AssertUnwindSafe(f)) {
            Err(p) => {
                let msg = p
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                format!("panicked: {msg}")
            }
            Ok(Ok(_)) => "accepted".into(),
            Ok(Err(e)) if !expected(&e) => format!("wrong error {e:?}"),
            Ok(Err(e)) if e.to_string().is_empty() => "empty message".into(),
            Ok(Err(_)) => return,
        };
        self.failures.push(format!("{what}: {why}"));
    }
}

/// `check` with the expected error as a pattern.
macro_rules! refuses {
    ($s:expr, $what:expr, $call:expr, $pat:pat) => {
        $s.check($what, || $call, |e| matches!(e, $pat))
    };
}

fn r<T: Real>(x: f64) -> T {
    T::from_f64_exact(x)
}

/// `a · b` overflows in `T` (f64 does; MPFR's exponent range does not).
fn overflows<T: Real>(a: f64, b: f64) -> bool {
    !(r::<T>(a) * r::<T>(b)).is_finite()
}

fn v2<T: Real>(x: f64, y: f64) -> Vector2<T> {
    Vector2::new(r(x), r(y))
}

fn v3<T: Real>(x: f64, y: f64, z: f64) -> Vector3<T> {
    Vector3::new(r(x), r(y), r(z))
}

fn reals<T: Real>(xs: &[f64]) -> Vec<T> {
    xs.iter().map(|&x| r(x)).collect()
}

fn line<T: Real>(n: usize) -> Vec<Vector2<T>> {
    (0..n).map(|k| v2(k as f64, (k * k) as f64)).collect()
}

/// `line(n)` with point `k` replaced by `(x, 0)`.
fn with_bad<T: Real>(n: usize, k: usize, x: f64) -> Vec<Vector2<T>> {
    let mut p = line(n);
    p[k] = v2(x, 0.0);
    p
}

const NON_FINITE: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

fn knots<T: Real>(s: &mut Sweep) {
    use KnotError::*;
    refuses!(
        s,
        "KnotVector::new([])",
        KnotVector::<T>::new(vec![]),
        TooFew(0)
    );
    refuses!(
        s,
        "KnotVector::new([0])",
        KnotVector::<T>::new(reals(&[0.0])),
        TooFew(1)
    );
    for x in NON_FINITE {
        refuses!(
            s,
            &format!("KnotVector::new([0, {x}, 1])"),
            KnotVector::<T>::new(reals(&[0.0, x, 1.0])),
            Input(InputError::NonFiniteAt { index: 1, .. })
        );
    }
    refuses!(
        s,
        "KnotVector decreasing",
        KnotVector::<T>::new(reals(&[1.0, 0.0])),
        Decreasing { index: 1 }
    );
    refuses!(
        s,
        "KnotVector non-monotone",
        KnotVector::<T>::new(reals(&[0.0, 1.0, 0.5, 2.0])),
        Decreasing { index: 2 }
    );
    refuses!(
        s,
        "KnotVector::uniform(1)",
        KnotVector::<T>::uniform(1),
        TooFew(1)
    );
    refuses!(
        s,
        "KnotVector::clamped_uniform(0, 3)",
        KnotVector::<T>::clamped_uniform(0, 3),
        TooFew(_)
    );
    refuses!(
        s,
        "KnotVector::clamped_uniform(4, 3)",
        KnotVector::<T>::clamped_uniform(4, 3),
        TooFew(_)
    );
    refuses!(
        s,
        "KnotVector::clamped_uniform(MAX, MAX)",
        KnotVector::<T>::clamped_uniform(usize::MAX, usize::MAX),
        TooMany { .. }
    );
    refuses!(
        s,
        "KnotVector::clamped_uniform(2, MAX)",
        KnotVector::<T>::clamped_uniform(2, usize::MAX),
        TooMany { .. }
    );
}

fn bsplines<T: Real>(s: &mut Sweep) {
    use BSplineError::*;
    let k = |n: usize| KnotVector::<T>::uniform(n).unwrap();
    refuses!(
        s,
        "BSpline order 0",
        BSpline::new(0, line::<T>(3), k(3)),
        ZeroOrder
    );
    refuses!(
        s,
        "BSpline no points",
        BSpline::new(2, line::<T>(0), k(2)),
        Input(InputError::TooFewPoints { .. })
    );
    refuses!(
        s,
        "BSpline one point, order 2",
        BSpline::new(2, line::<T>(1), k(3)),
        Input(InputError::TooFewPoints { .. })
    );
    refuses!(
        s,
        "BSpline knot count",
        BSpline::new(2, line::<T>(3), k(4)),
        KnotCount { .. }
    );
    let flat = || KnotVector::<T>::new(reals(&[1.0; 5])).unwrap();
    refuses!(
        s,
        "BSpline empty domain",
        BSpline::new(2, line::<T>(3), flat()),
        EmptyDomain
    );
    for x in NON_FINITE {
        refuses!(
            s,
            &format!("BSpline point {x}"),
            BSpline::new(2, with_bad::<T>(3, 1, x), k(5)),
            Input(InputError::NonFiniteAt { index: 1, .. })
        );
    }
    let data = BSplineData {
        order: 2,
        knots: reals::<T>(&[0.0, 1.0, 2.0, 3.0]),
        points: vec![reals(&[0.0, 0.0]), reals(&[1.0, 1.0, 1.0])],
    };
    refuses!(
        s,
        "BSpline from data of mixed dimension",
        BSpline::<T, 2>::try_from(data),
        Dimension { .. }
    );
}

fn nurbs<T: Real>(s: &mut Sweep) {
    use BSplineError::*;
    let k = |n: usize| KnotVector::<T>::uniform(n).unwrap();
    for w in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        refuses!(
            s,
            &format!("NurbsCurve weight {w}"),
            NurbsCurve::new(2, line::<T>(3), reals(&[1.0, w, 1.0]), k(5)),
            BadWeight { index: 1, .. }
        );
    }
    refuses!(
        s,
        "NurbsCurve NaN point",
        NurbsCurve::new(2, with_bad::<T>(3, 2, f64::NAN), reals(&[1.0; 3]), k(5)),
        Input(InputError::NonFiniteAt { index: 2, .. })
    );
    refuses!(
        s,
        "NurbsCurve fewer weights",
        NurbsCurve::new(2, line::<T>(4), reals(&[1.0; 3]), k(5)),
        WeightCount { .. }
    );
    refuses!(
        s,
        "NurbsCurve more weights",
        NurbsCurve::new(2, line::<T>(3), reals(&[1.0; 4]), k(5)),
        WeightCount { .. }
    );
    refuses!(
        s,
        "NurbsCurve no points",
        NurbsCurve::new(2, line::<T>(0), vec![], k(2)),
        Input(InputError::TooFewPoints { .. })
    );
    if overflows::<T>(1e300, 1e300) {
        refuses!(
            s,
            "NurbsCurve w·P overflows",
            NurbsCurve::new(
                2,
                with_bad::<T>(3, 1, 1e300),
                reals(&[1.0, 1e300, 1.0]),
                k(5)
            ),
            Input(InputError::NonFiniteAt { index: 1, .. })
        );
    }
    refuses!(
        s,
        "NurbsCurve::from_homogeneous fewer weights",
        NurbsCurve::from_homogeneous(2, line::<T>(4), reals(&[1.0; 3]), k(6)),
        WeightCount { .. }
    );
    for rad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        refuses!(
            s,
            &format!("NurbsCurve::circle r = {rad}"),
            NurbsCurve::circle(&v2::<T>(0.0, 0.0), &r(rad)),
            BadRadius { .. }
        );
    }
    refuses!(
        s,
        "NurbsCurve::circle NaN centre",
        NurbsCurve::circle(&v2::<T>(f64::NAN, 0.0), &r(1.0)),
        Input(InputError::NonFiniteAt { .. })
    );
    let surface = |counts: (usize, usize), points: Vec<Vector2<T>>, w: Vec<T>| {
        NurbsSurface::new((2, 2), counts, points, w, (k(4), k(4)))
    };
    refuses!(
        s,
        "NurbsSurface net size",
        surface((2, 2), line(3), reals(&[1.0; 4])),
        NetSize { .. }
    );
    refuses!(
        s,
        "NurbsSurface NaN point",
        surface((2, 2), with_bad(4, 3, f64::NAN), reals(&[1.0; 4])),
        Input(InputError::NonFiniteAt { index: 3, .. })
    );
    refuses!(
        s,
        "NurbsSurface zero weight",
        surface((2, 2), line(4), reals(&[1.0, 0.0, 1.0, 1.0])),
        BadWeight { index: 1, .. }
    );
    refuses!(
        s,
        "NurbsSurface counts overflow",
        surface((usize::MAX, 2), line(4), reals(&[1.0; 4])),
        KnotCount { .. }
    );
    for rad in [f64::NAN, 0.0, -1.0] {
        refuses!(
            s,
            &format!("NurbsSurface::cylinder radius {rad}"),
            NurbsSurface::<T, 3>::cylinder(&r(rad), &r(1.0)),
            BadRadius { .. }
        );
    }
    refuses!(
        s,
        "NurbsSurface::cylinder infinite height",
        NurbsSurface::<T, 3>::cylinder(&r(1.0), &r(f64::INFINITY)),
        Input(InputError::NonFinite { name: "height" })
    );
}

fn beziers<T: Real>(s: &mut Sweep) {
    refuses!(
        s,
        "Bezier::new([])",
        Bezier::<T, 2>::new(vec![]),
        BezierError::Input(InputError::TooFewPoints {
            needed: 1,
            got: 0,
            ..
        })
    );
    for x in NON_FINITE {
        refuses!(
            s,
            &format!("Bezier point {x}"),
            Bezier::new(with_bad::<T>(3, 0, x)),
            BezierError::Input(InputError::NonFiniteAt {
                what: "control point",
                index: 0
            })
        );
        refuses!(
            s,
            &format!("BernsteinPoly {x}"),
            BernsteinPoly::<T>::new(reals(&[1.0, x])),
            BezierError::Input(InputError::NonFiniteAt {
                what: "coefficient",
                index: 1
            })
        );
        refuses!(
            s,
            &format!("BernsteinPoly::from_f64 {x}"),
            BernsteinPoly::<T>::from_f64(&[x]),
            BezierError::Input(InputError::NonFiniteAt {
                what: "coefficient",
                index: 0
            })
        );
    }
    refuses!(
        s,
        "BernsteinPoly::new([])",
        BernsteinPoly::<T>::new(vec![]),
        BezierError::Input(InputError::TooFewPoints {
            needed: 1,
            got: 0,
            ..
        })
    );
    let quadratic = Bezier::new(line::<T>(3)).unwrap();
    rational_and_hermite::<T>(s, &quadratic);
}

fn rational_and_hermite<T: Real>(s: &mut Sweep, quadratic: &Bezier<T, 2>) {
    use CurveError::*;
    let rb = |p: Vec<Vector2<T>>, w: &[f64]| RationalBezier::new(p, reals(w));
    refuses!(
        s,
        "RationalBezier empty",
        rb(vec![], &[]),
        Input(InputError::TooFewPoints { .. })
    );
    refuses!(
        s,
        "RationalBezier fewer weights",
        rb(line(3), &[1.0, 1.0]),
        LengthMismatch { .. }
    );
    refuses!(
        s,
        "RationalBezier NaN point",
        rb(with_bad(3, 1, f64::NAN), &[1.0; 3]),
        Input(InputError::NonFiniteAt { index: 1, .. })
    );
    for w in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        refuses!(
            s,
            &format!("RationalBezier weight {w}"),
            rb(line(3), &[1.0, w, 1.0]),
            BadWeight { index: 1, .. }
        );
    }
    refuses!(
        s,
        "RationalBezier::from_homogeneous end weight 0",
        RationalBezier::from_homogeneous(line::<T>(3), reals(&[0.0, 1.0, 1.0])),
        BadWeight { index: 0, .. }
    );
    let p = || v2::<T>(0.0, 0.0);
    for x in NON_FINITE {
        let bad = v2::<T>(x, 0.0);
        refuses!(
            s,
            &format!("Hermite p1 {x}"),
            Hermite::new(p(), bad.clone(), p(), p()),
            Input(InputError::NonFiniteAt { index: 1, .. })
        );
        refuses!(
            s,
            &format!("Hermite d1 {x}"),
            Hermite::new(p(), p(), p(), bad),
            Input(InputError::NonFiniteAt { index: 3, .. })
        );
    }
    refuses!(
        s,
        "Hermite::from_bezier(quadratic)",
        Hermite::from_bezier(quadratic),
        Degree {
            expected: 3,
            got: 2
        }
    );
}

fn catmull_rom<T: Real>(s: &mut Sweep) {
    use CurveError::*;
    for spacing in Spacing::ALL {
        refuses!(
            s,
            &format!("CatmullRom {spacing:?} open, 3 points"),
            CatmullRom::new(line::<T>(3), spacing, false),
            Input(InputError::TooFewPoints { .. })
        );
        refuses!(
            s,
            &format!("CatmullRom {spacing:?} closed, 2 points"),
            CatmullRom::new(line::<T>(2), spacing, true),
            Input(InputError::TooFewPoints { .. })
        );
        refuses!(
            s,
            &format!("CatmullRom {spacing:?} empty"),
            CatmullRom::new(line::<T>(0), spacing, false),
            Input(InputError::TooFewPoints { .. })
        );
        refuses!(
            s,
            &format!("CatmullRom {spacing:?} NaN"),
            CatmullRom::new(with_bad::<T>(5, 2, f64::NAN), spacing, false),
            Input(InputError::NonFiniteAt { index: 2, .. })
        );
    }
    for spacing in [Spacing::Centripetal, Spacing::Chordal] {
        let mut dup = line::<T>(5);
        dup[2] = dup[1].clone();
        refuses!(
            s,
            &format!("CatmullRom {spacing:?} duplicate"),
            CatmullRom::new(dup, spacing, false),
            CoincidentPoints { index: 1, next: 2 }
        );
        let mut closed = line::<T>(4);
        closed[3] = closed[0].clone();
        refuses!(
            s,
            &format!("CatmullRom {spacing:?} closed, last = first"),
            CatmullRom::new(closed, spacing, true),
            CoincidentPoints { index: 3, next: 0 }
        );
        if overflows::<T>(1.7e308, 2.0) {
            let far = vec![
                v2::<T>(-1.7e308, 0.0),
                v2(1.7e308, 0.0),
                v2(0.0, 1.0),
                v2(1.0, 1.0),
            ];
            refuses!(
                s,
                &format!("CatmullRom {spacing:?} chord overflows"),
                CatmullRom::new(far, spacing, false),
                Input(InputError::NonFinite { .. })
            );
        }
    }
}

fn qi<T: Real>(s: &mut Sweep) {
    use QiError::*;
    let helix = |n: usize| -> Vec<Vector3<T>> {
        (0..n)
            .map(|k| {
                let t = k as f64 * 0.6;
                v3(t.cos(), t.sin(), 0.3 * t)
            })
            .collect()
    };
    let z = Vector3::<T>::zeros();
    let d = v3::<T>(1.0, 0.0, 0.0);
    for param in [Parameterization::Uniform, Parameterization::ChordLength] {
        refuses!(
            s,
            &format!("ClampedCubicSpline {param:?} 1 point"),
            ClampedCubicSpline::new(&helix(1), param, &d, &d),
            Input(InputError::TooFewPoints { got: 1, .. })
        );
        for x in NON_FINITE {
            let mut p = helix(4);
            p[2].y = r(x);
            refuses!(
                s,
                &format!("ClampedCubicSpline {param:?} point {x}"),
                ClampedCubicSpline::new(&p, param, &d, &d),
                Input(InputError::NonFiniteAt { index: 2, .. })
            );
            refuses!(
                s,
                &format!("ClampedCubicSpline {param:?} slope {x}"),
                ClampedCubicSpline::new(&helix(4), param, &d, &v3(0.0, x, 0.0)),
                InvalidTangent { .. }
            );
        }
    }
    let mut dup = helix(4);
    dup[2] = dup[1].clone();
    refuses!(
        s,
        "ClampedCubicSpline chord duplicate",
        ClampedCubicSpline::new(&dup, Parameterization::ChordLength, &d, &d),
        CoincidentPoints { index: 1 }
    );
    let opts = QiOptions::<T>::default;
    for n in 0..3 {
        refuses!(
            s,
            &format!("interpolate {n} points"),
            interpolate(&helix(n), &opts()),
            Input(InputError::TooFewPoints { .. })
        );
    }
    for x in NON_FINITE {
        let mut p = helix(4);
        p[3].z = r(x);
        refuses!(
            s,
            &format!("interpolate point {x}"),
            interpolate(&p, &opts()),
            Input(InputError::NonFiniteAt { index: 3, .. })
        );
        let o = QiOptions {
            start_tangent: Some(v3(x, 1.0, 0.0)),
            ..opts()
        };
        refuses!(
            s,
            &format!("interpolate start tangent {x}"),
            interpolate(&helix(4), &o),
            InvalidTangent { .. }
        );
        let tols = [
            (
                "tol",
                QiOptions {
                    tol: r(x),
                    ..opts()
                },
            ),
            (
                "quad_tol",
                QiOptions {
                    quad_tol: r(x),
                    ..opts()
                },
            ),
        ];
        for (name, o) in tols {
            let what = format!("interpolate {name} {x}");
            refuses!(s, &what, interpolate(&helix(4), &o), InvalidOption { .. });
        }
    }
    refuses!(
        s,
        "interpolate duplicate points",
        interpolate(&dup, &opts()),
        CoincidentPoints { index: 1 }
    );
    refuses!(
        s,
        "interpolate zero end tangent",
        interpolate(
            &helix(4),
            &QiOptions {
                end_tangent: Some(z.clone()),
                ..opts()
            }
        ),
        InvalidTangent { .. }
    );
    refuses!(
        s,
        "interpolate tol -1",
        interpolate(
            &helix(4),
            &QiOptions {
                tol: r(-1.0),
                ..opts()
            }
        ),
        InvalidOption { .. }
    );
    for (lo, hi) in [(0, 16), (16, 16), (usize::MAX, usize::MAX)] {
        let o = QiOptions {
            min_quad_order: lo,
            max_quad_order: hi,
            ..opts()
        };
        refuses!(
            s,
            &format!("interpolate quad orders {lo}..{hi}"),
            interpolate(&helix(4), &o),
            InvalidOption { .. }
        );
    }
    refuses!(
        s,
        "unit_direction(0)",
        unit_direction(&z, "start"),
        InvalidTangent { .. }
    );
    refuses!(
        s,
        "unit_direction(NaN)",
        unit_direction(&v3::<T>(f64::NAN, 0.0, 0.0), "start"),
        InvalidTangent { .. }
    );
    let h = helix(3);
    refuses!(
        s,
        "start_tangent duplicate",
        start_tangent(&h[0], &h[0], &h[1]),
        InvalidTangent { .. }
    );
    use QuadratureError::*;
    refuses!(
        s,
        "GaussLegendre::new(0)",
        GaussLegendre::<T>::new(0),
        ZeroOrder
    );
    refuses!(
        s,
        "GaussLegendre::new(MAX)",
        GaussLegendre::<T>::new(usize::MAX),
        TooManyNodes(_)
    );
    refuses!(
        s,
        "choose_order tol NaN",
        choose_order::<T>(2, 8, &r(f64::NAN), |_, _| T::zero()),
        InvalidTolerance(_)
    );
    refuses!(
        s,
        "choose_order from MAX/2",
        choose_order::<T>(usize::MAX / 2 + 1, usize::MAX, &r(1e-3), |_, _| T::one()),
        TooManyNodes(_)
    );
}

fn families(s: &mut Sweep) {
    use SsplineError::*;
    for m in [0, 1, 201, u32::MAX] {
        refuses!(
            s,
            &format!("SplineFamily::order({m})"),
            SplineFamily::order(m),
            OrderOutOfRange(_)
        );
    }
    refuses!(
        s,
        "SplineFamily::beta2(-1/3)",
        SplineFamily::beta2(Rational::from((-1, 3))),
        InvalidTension(_)
    );
    for b in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1.0, -5e-324] {
        refuses!(
            s,
            &format!("SplineFamily::beta2_from_f64({b})"),
            SplineFamily::beta2_from_f64(b),
            InvalidTension(_)
        );
    }
    for text in ["", "nan", "inf", "-1", "1/0", "0/0", "1e99999999999", "x"] {
        refuses!(
            s,
            &format!("SplineFamily::parse_tension({text:?})"),
            SplineFamily::parse_tension(text),
            InvalidTension(_)
        );
    }
    let cubic = SplineFamily::Order(4);
    for tol in [f64::NAN, f64::INFINITY, 0.0, -1e-3, 1.0, 2.0] {
        for c in Criterion::all() {
            refuses!(
                s,
                &format!("truncation_width(tol {tol}, {c:?})"),
                truncation_width(&cubic, tol, c),
                InvalidTolerance(_)
            );
        }
        refuses!(
            s,
            &format!("WidthChooser::new(tol {tol})"),
            WidthChooser::new(&cubic, tol),
            InvalidTolerance(_)
        );
    }
    refuses!(
        s,
        "truncation_width(order 1)",
        truncation_width(&SplineFamily::Order(1), 1e-3, Criterion::Coeff),
        OrderOutOfRange(1)
    );
    refuses!(
        s,
        "WidthChooser::new(beta2 -1)",
        WidthChooser::new(&SplineFamily::Beta2(Rational::from(-1)), 1e-3),
        InvalidTension(_)
    );
}

fn ssplines<T: Real>(s: &mut Sweep) {
    use CurveError::*;
    let cubic = SplineFamily::Order(4);
    let free = || EndCondition::<T, 2>::Free;
    refuses!(
        s,
        "SsplineCurve 0 points",
        SsplineCurve::new(&cubic, 8, &line::<T>(0), free()),
        Input(InputError::TooFewPoints { got: 0, .. })
    );
    refuses!(
        s,
        "SsplineCurve 1 point",
        SsplineCurve::new(&cubic, 8, &line::<T>(1), free()),
        Input(InputError::TooFewPoints { got: 1, .. })
    );
    refuses!(
        s,
        "SsplineCurve order above points",
        SsplineCurve::new(&SplineFamily::Order(6), 8, &line::<T>(4), free()),
        OrderTooHigh { .. }
    );
    refuses!(
        s,
        "SsplineCurve n = 0",
        SsplineCurve::new(&cubic, 0, &line::<T>(6), free()),
        Sspline(SsplineError::ZeroWidth)
    );
    refuses!(
        s,
        "SsplineCurve bad family",
        SsplineCurve::new(&SplineFamily::Order(1), 8, &line::<T>(6), free()),
        Sspline(_)
    );
    for x in NON_FINITE {
        refuses!(
            s,
            &format!("SsplineCurve point {x}"),
            SsplineCurve::new(&cubic, 8, &with_bad::<T>(6, 4, x), free()),
            Input(InputError::NonFiniteAt { index: 4, .. })
        );
        let t = EndCondition::Tangents {
            start: v2::<T>(0.0, x),
            end: v2(1.0, 0.0),
        };
        refuses!(
            s,
            &format!("SsplineCurve tangent {x}"),
            SsplineCurve::new(&cubic, 8, &line::<T>(6), t),
            Input(InputError::NonFinite { .. })
        );
        refuses!(
            s,
            &format!("global_cubic point {x}"),
            cubic_control_points(&with_bad::<T>(5, 0, x), &CubicEnds::Natural),
            Input(InputError::NonFiniteAt { index: 0, .. })
        );
        let c = CubicEnds::Clamped {
            start: v2::<T>(x, 0.0),
            end: v2(0.0, 0.0),
        };
        refuses!(
            s,
            &format!("global_cubic tangent {x}"),
            cubic_control_points(&line::<T>(5), &c),
            Input(InputError::NonFinite { .. })
        );
    }
    refuses!(
        s,
        "global_cubic 1 point",
        cubic_control_points(&line::<T>(1), &CubicEnds::Natural),
        Input(InputError::TooFewPoints { got: 1, .. })
    );
    refuses!(
        s,
        "global_cubic 0 points",
        cubic_control_points(&line::<T>(0), &CubicEnds::Natural),
        Input(InputError::TooFewPoints { got: 0, .. })
    );
    let dir = |rule| Direction {
        family: cubic.clone(),
        n: 8,
        rule,
    };
    let (f, p) = (dir(EndRule::Free), dir(EndRule::Periodic));
    refuses!(
        s,
        "SsplineSurface reflect",
        SsplineSurface::new(&dir(EndRule::Reflect), &f, 4, 4, &line::<T>(16)),
        Unsupported(_)
    );
    refuses!(
        s,
        "SsplineSurface 1 × 4",
        SsplineSurface::new(&f, &p, 1, 4, &line::<T>(4)),
        Input(InputError::TooFewPoints { got: 1, .. })
    );
    refuses!(
        s,
        "SsplineSurface grid size",
        SsplineSurface::new(&f, &f, 4, 4, &line::<T>(15)),
        GridSize { .. }
    );
    refuses!(
        s,
        "SsplineSurface NaN",
        SsplineSurface::new(&f, &f, 4, 4, &with_bad::<T>(16, 7, f64::NAN)),
        Input(InputError::NonFiniteAt { index: 7, .. })
    );
    refuses!(
        s,
        "TruncatedBasis::new(n = 0)",
        TruncatedBasis::<T>::new(&cubic, 0),
        SsplineError::ZeroWidth
    );
    for n in [MAX_HALF_WIDTH + 1, usize::MAX] {
        refuses!(
            s,
            &format!("TruncatedBasis::new(n = {n})"),
            TruncatedBasis::<T>::new(&cubic, n),
            SsplineError::WidthTooLarge(_)
        );
        refuses!(
            s,
            &format!("TruncationAnalysis::new(max_n = {n})"),
            TruncationAnalysis::<T>::new(&cubic, n),
            SsplineError::WidthTooLarge(_)
        );
        refuses!(
            s,
            &format!("SsplineCurve n = {n}"),
            SsplineCurve::new(&cubic, n, &line::<T>(6), free()),
            Sspline(SsplineError::WidthTooLarge(_))
        );
    }
    for (nu, nv) in [
        (1 << 33, 1 << 33),
        (usize::MAX, 2),
        (usize::MAX, usize::MAX),
    ] {
        refuses!(
            s,
            &format!("SsplineSurface {nu} × {nv}"),
            SsplineSurface::new(&f, &f, nu, nv, &line::<T>(4)),
            GridSize { .. }
        );
    }
}

fn patches<T: Real>(s: &mut Sweep) {
    use PatchError::*;
    let net = |n: usize| -> Vec<Point3<T>> {
        (0..n)
            .map(|k| v3((k / 2) as f64, (k % 2) as f64, 0.0))
            .collect()
    };
    refuses!(
        s,
        "Patch degree 0",
        Patch::new(0, net(1)),
        Input(InputError::DegreeTooSmall { min: 1, got: 0, .. })
    );
    refuses!(
        s,
        "Patch empty",
        Patch::new(1, net(0)),
        WrongPointCount { .. }
    );
    refuses!(
        s,
        "Patch 3 points",
        Patch::new(1, net(3)),
        WrongPointCount { .. }
    );
    refuses!(
        s,
        "Patch degree MAX",
        Patch::new(usize::MAX, net(4)),
        WrongPointCount { .. }
    );
    for x in NON_FINITE {
        let mut p = net(4);
        p[3].x = r(x);
        refuses!(
            s,
            &format!("Patch point {x}"),
            Patch::new(1, p),
            Input(InputError::NonFiniteAt { index: 3, .. })
        );
    }
    let one = || Patch::new(1, net(4)).unwrap();
    refuses!(
        s,
        "PatchGrid 0 × 1",
        PatchGrid::<T>::new(0, 1, vec![]),
        EmptyGrid { .. }
    );
    refuses!(
        s,
        "PatchGrid 1 × 2 with 1 patch",
        PatchGrid::new(1, 2, vec![one()]),
        GridSize { .. }
    );
    refuses!(
        s,
        "PatchGrid MAX × 2",
        PatchGrid::new(usize::MAX, 2, vec![one()]),
        GridSize { .. }
    );
    let quad = Patch::new(2, net(9)).unwrap();
    refuses!(
        s,
        "PatchGrid mixed degrees",
        PatchGrid::new(1, 2, vec![one(), quad]),
        DegreeMismatch { .. }
    );
    refuses!(
        s,
        "PatchGrid::planar NaN size",
        PatchGrid::planar(1, 1, 1, &r::<T>(f64::NAN)),
        Input(InputError::NonFiniteAt { .. })
    );
    refuses!(
        s,
        "PatchGrid::planar 0 × 1",
        PatchGrid::planar(0, 1, 1, &r::<T>(1.0)),
        EmptyGrid { .. }
    );
    refuses!(
        s,
        "PatchGrid::planar MAX × MAX",
        PatchGrid::planar(usize::MAX, usize::MAX, 1, &r::<T>(1.0)),
        TooManyPatches { .. }
    );
}

fn samples<T: Real>(s: &mut Sweep) {
    use BvError::*;
    use InverseMappingError as I;
    let grid = |u: &[f64], v: &[f64]| SampleGrid::<T>::new(reals(u), reals(v));
    refuses!(
        s,
        "SampleGrid empty",
        grid(&[], &[]),
        I::Nodes(Input(InputError::TooFewPoints { got: 0, .. }))
    );
    refuses!(
        s,
        "SampleGrid one node",
        grid(&[0.5], &[0.5]),
        I::GridShape { .. }
    );
    refuses!(
        s,
        "SampleGrid duplicate",
        grid(&[0.5, 0.5], &[0.0, 1.0]),
        I::Nodes(RepeatedNode { .. })
    );
    refuses!(
        s,
        "SampleGrid decreasing",
        grid(&[0.0, 1.0], &[1.0, 0.0]),
        I::Nodes(NodesNotIncreasing { .. })
    );
    refuses!(
        s,
        "SampleGrid outside [0, 1]",
        grid(&[0.0, 1.5], &[0.0, 1.0]),
        I::Nodes(NodeOutOfRange { .. })
    );
    refuses!(
        s,
        "SampleGrid lengths",
        grid(&[0.0, 1.0], &[0.0, 0.5, 1.0]),
        I::GridShape { .. }
    );
    for x in NON_FINITE {
        refuses!(
            s,
            &format!("SampleGrid node {x}"),
            grid(&[0.0, x], &[0.0, 1.0]),
            I::Nodes(Input(InputError::NonFiniteAt {
                what: "node",
                index: 1
            }))
        );
        refuses!(
            s,
            &format!("BvBidiagonal node {x}"),
            BvBidiagonal::<T>::new(&reals(&[0.0, x])),
            Input(InputError::NonFiniteAt {
                what: "node",
                index: 1
            })
        );
    }
    for family in NodeFamily::all() {
        refuses!(
            s,
            &format!("SampleGrid::from_family({family}, 0)"),
            SampleGrid::<T>::from_family(family, 0),
            I::Family(VandermondeError::Input(InputError::DegreeTooSmall {
                min: 1,
                got: 0,
                ..
            }))
        );
        refuses!(
            s,
            &format!("NodeFamily::nodes({family}, MAX)"),
            family.nodes::<T>(usize::MAX),
            VandermondeError::DegreeTooLarge(_)
        );
    }
    refuses!(
        s,
        "BvBidiagonal empty",
        BvBidiagonal::<T>::new(&[]),
        Input(InputError::TooFewPoints { got: 0, .. })
    );
    refuses!(
        s,
        "BvBidiagonal duplicate",
        BvBidiagonal::<T>::new(&reals(&[0.2, 0.2])),
        RepeatedNode { .. }
    );
    for m in [Method1d::Gepp, Method1d::MarcoMartinez] {
        refuses!(
            s,
            &format!("Factorised {m:?} duplicate"),
            Factorised::<T>::new(&reals(&[0.0, 0.3, 0.3]), m),
            RepeatedNode { .. }
        );
    }
    let g = SampleGrid::<T>::from_family(NodeFamily::Equispaced, 1).unwrap();
    let pts =
        |n: usize, bad: f64| -> Vec<Point3<T>> { (0..n).map(|k| v3(k as f64, bad, 0.0)).collect() };
    let solver = TensorSolver::KroneckerMarcoMartinez;
    refuses!(
        s,
        "control_points 3 samples",
        patch_from_samples(&g, &pts(3, 0.0), solver),
        I::Count { .. }
    );
    refuses!(
        s,
        "control_points NaN sample",
        patch_from_samples(&g, &pts(4, f64::NAN), solver),
        I::Input(InputError::NonFiniteAt { .. })
    );
    let surface = PatchGrid::planar(1, 1, 1, &r::<T>(1.0)).unwrap();
    refuses!(
        s,
        "deform_grid no flows",
        deform_grid(&surface, &g, &[], solver),
        I::PatchCount { .. }
    );
    refuses!(
        s,
        "deform_grid NaN flow",
        deform_grid(&surface, &g, &[pts(4, f64::INFINITY)], solver),
        I::Input(InputError::NonFiniteAt { .. })
    );
}

fn sweep<T: Real>() -> Sweep {
    let mut s = Sweep::default();
    knots::<T>(&mut s);
    bsplines::<T>(&mut s);
    nurbs::<T>(&mut s);
    beziers::<T>(&mut s);
    catmull_rom::<T>(&mut s);
    qi::<T>(&mut s);
    ssplines::<T>(&mut s);
    patches::<T>(&mut s);
    samples::<T>(&mut s);
    s
}

fn assert_clean(name: &str, s: &Sweep) {
    println!("{name}: bad-constructor cases tried: {}", s.tried);
    assert!(
        s.failures.is_empty(),
        "{name}: {} of {} cases failed:\n{}",
        s.failures.len(),
        s.tried,
        s.failures.join("\n")
    );
}

#[test]
fn every_constructor_refuses_bad_input_in_f64() {
    assert_clean("f64", &sweep::<f64>());
}

#[test]
fn every_constructor_refuses_bad_input_in_mp128() {
    assert_clean("Mp<128>", &sweep::<Mp<128>>());
}

#[test]
fn the_scalar_free_constructors_refuse_bad_input() {
    let mut s = Sweep::default();
    families(&mut s);
    assert_clean("families and widths", &s);
}

/// The inputs the sweep breaks are accepted when intact, so each case fails
/// for its own defect.
#[test]
fn the_intact_inputs_are_accepted() {
    let k = |n: usize| KnotVector::<f64>::uniform(n).unwrap();
    assert!(BSpline::new(2, line::<f64>(3), k(5)).is_ok());
    assert!(NurbsCurve::new(2, line::<f64>(3), reals(&[1.0; 3]), k(5)).is_ok());
    assert!(
        NurbsSurface::new(
            (2, 2),
            (2, 2),
            line::<f64>(4),
            reals(&[1.0; 4]),
            (k(4), k(4))
        )
        .is_ok()
    );
    assert!(CatmullRom::new(line::<f64>(5), Spacing::Chordal, false).is_ok());
    assert!(
        SsplineCurve::new(
            &SplineFamily::Order(4),
            8,
            &line::<f64>(6),
            EndCondition::Free
        )
        .is_ok()
    );
    let free = Direction {
        family: SplineFamily::Order(4),
        n: 8,
        rule: EndRule::Free,
    };
    assert!(SsplineSurface::new(&free, &free, 4, 4, &line::<f64>(16)).is_ok());
    assert!(KnotVector::<f64>::clamped_uniform(4, 6).is_ok());
    assert!(GaussLegendre::<f64>::new(5).is_ok());
    assert!(SampleGrid::<f64>::new(reals(&[0.0, 1.0]), reals(&[0.0, 1.0])).is_ok());
    assert!(PatchGrid::planar(2, 3, 2, &1.0f64).is_ok());
    assert!(truncation_width(&SplineFamily::Order(4), 1e-3, Criterion::Uniform).is_ok());
}
