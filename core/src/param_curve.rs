//! What a parametric curve or surface can do, as small capability traits
//! (after kurbo's `ParamCurve` family): [`ParamCurve`] (domain and point),
//! [`ParamCurveDeriv`] (first derivative), [`ParamSurface`] and
//! [`ParamSurfaceDeriv`]. Generic code — sampling, flattening, distance
//! measurements in `verify` — takes any of them. Two capabilities build on
//! them elsewhere: [`ParamCurveBezier`](crate::curves::bezier_pieces::ParamCurveBezier)
//! (a chain of Bézier pieces, what flattening with a proven bound needs) and
//! [`ParamCurveArclen`](crate::arclength::ParamCurveArclen) (arc length and its
//! inverse, for every curve with a derivative).
//!
//! Every curve and surface type of the crate implements them in its own
//! file, over its own scalar `T` (f64 or MPFR) and its own error type. The domain is
//! always in `T`. Outside its domain each type keeps its own documented
//! rule: polynomial pieces extrapolate (Bézier, Hermite), spline types
//! refuse with their error.
//!
//! | type | curve | derivative (and arc length) | Bézier pieces (flattening) |
//! |---|---|---|---|
//! | [`Bezier`](crate::bernstein::bezier::Bezier) | ✓ | ✓ (hodograph) | ✓ |
//! | [`Hermite`](crate::curves::hermite::Hermite) | ✓ | ✓ | ✓ |
//! | [`CatmullRom`](crate::curves::catmull_rom::CatmullRom) | ✓ | ✓ | ✓ |
//! | [`RationalBezier`](crate::curves::rational_bezier::RationalBezier) | ✓ | | ✓ |
//! | [`BSpline`](crate::bspline::de_boor::BSpline) | ✓ | ✓ | ✓ |
//! | [`NurbsCurve`](crate::bspline::nurbs::NurbsCurve) | ✓ | ✓ | ✓ |
//! | [`SsplineCurve`](crate::curves::sspline_curve::SsplineCurve) | ✓ | | ✓ |
//! | [`ClampedCubicSpline`](crate::qi::cubic_spline::ClampedCubicSpline) | ✓ | ✓ | |
//! | [`QiInterpolation`](crate::qi::interpolate::QiInterpolation) | ✓ | ✓ | |
//! | [`Patch`](crate::surface_deformation::patch::Patch), [`SsplineSurface`](crate::curves::sspline_surface::SsplineSurface), [`NurbsSurface`](crate::bspline::nurbs::NurbsSurface) | surface | [`Patch`](crate::surface_deformation::patch::Patch) |

use crate::scalar::Real;
use nalgebra::SVector;

/// A curve `t ↦ P(t)` in `D` dimensions on a closed parameter interval.
pub trait ParamCurve<T: Real, const D: usize> {
    /// Why an evaluation failed.
    type Error: std::error::Error;

    /// The parameter interval `[a, b]`.
    fn domain(&self) -> (T, T);

    /// The point `P(t)`.
    fn eval(&self, t: &T) -> Result<SVector<T, D>, Self::Error>;
}

/// A curve with a first derivative.
pub trait ParamCurveDeriv<T: Real, const D: usize>: ParamCurve<T, D> {
    /// `P'(t) = dP/dt` (with respect to the curve's own parameter).
    fn deriv(&self, t: &T) -> Result<SVector<T, D>, Self::Error>;

    /// The parameters strictly inside the domain, increasing, where the
    /// curve joins two pieces and its derivatives may jump (a spline's
    /// knots); empty for one smooth piece. Integration of `‖P'‖` splits
    /// there ([`crate::arclength`]).
    fn breakpoints(&self) -> Vec<T> {
        Vec::new()
    }
}

/// The values of `knots` strictly inside `(lo, hi)`, without repeats.
pub(crate) fn interior<T: Real>(knots: &[T], lo: &T, hi: &T) -> Vec<T> {
    let mut inside: Vec<T> = knots
        .iter()
        .filter(|k| *k > lo && *k < hi)
        .cloned()
        .collect();
    inside.dedup();
    inside
}

/// A surface `(u, v) ↦ S(u, v)` in `D` dimensions on a parameter rectangle.
pub trait ParamSurface<T: Real, const D: usize> {
    /// Why an evaluation failed.
    type Error: std::error::Error;

    /// The parameter rectangle `([a_u, b_u], [a_v, b_v])`.
    fn domain(&self) -> ((T, T), (T, T));

    /// The point `S(u, v)`.
    fn eval(&self, u: &T, v: &T) -> Result<SVector<T, D>, Self::Error>;
}

/// A surface with first partial derivatives.
pub trait ParamSurfaceDeriv<T: Real, const D: usize>: ParamSurface<T, D> {
    /// `(S_u, S_v)` at `(u, v)`.
    fn partials(&self, u: &T, v: &T) -> Result<(SVector<T, D>, SVector<T, D>), Self::Error>;
}

/// `count + 1` points at equally spaced parameters over the domain,
/// ends included (`count ≥ 1`). Cost: `count + 1` evaluations.
///
/// **Method**: parameters `a + (b − a)(k/count)`, the end `b` exactly, each
/// point by the curve's own `eval`. **Accuracy**: that of `eval` per point
/// (the parameter rounded in three operations). **Source**: seed 002 (uniform drawing).
///
/// ```
/// use nalgebra::Vector2;
/// use splinelab::bernstein::bezier::Bezier;
/// use splinelab::param_curve::sample;
/// let line = Bezier::new(vec![Vector2::new(0.0f64, 0.0), Vector2::new(2.0, 4.0)]).unwrap();
/// let pts = sample(&line, 4).unwrap();
/// assert_eq!(pts[2], Vector2::new(1.0, 2.0));
/// ```
pub fn sample<T: Real, const D: usize, C: ParamCurve<T, D>>(
    curve: &C,
    count: usize,
) -> Result<Vec<SVector<T, D>>, C::Error> {
    let (a, b) = curve.domain();
    let n = count.max(1);
    (0..=n)
        .map(|k| {
            // The ends exactly; interior points by one lerp.
            let t = if k == n {
                b.clone()
            } else {
                let s = T::from_int(k as i64) / T::from_int(n as i64);
                a.clone() + (b.clone() - &a) * s
            };
            curve.eval(&t)
        })
        .collect()
}

/// A parameter outside the domain of a type whose inherent evaluation has
/// no error of its own.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("parameter {t} is outside the domain [{lo}, {hi}]")]
pub struct OutOfDomain {
    /// The parameter (as f64).
    pub t: f64,
    /// Domain start.
    pub lo: f64,
    /// Domain end.
    pub hi: f64,
}

/// `Err` unless `lo ≤ t ≤ hi` (a NaN is outside).
pub(crate) fn check_domain<T: Real>(t: &T, lo: &T, hi: &T) -> Result<(), OutOfDomain> {
    if t >= lo && t <= hi {
        Ok(())
    } else {
        Err(OutOfDomain {
            t: t.to_f64(),
            lo: lo.to_f64(),
            hi: hi.to_f64(),
        })
    }
}

/// `(T(a), T(b))` of an `f64` domain (exact).
pub(crate) fn widen<T: Real>((a, b): (f64, f64)) -> (T, T) {
    (T::from_f64_exact(a), T::from_f64_exact(b))
}

pub(crate) fn unit<T: Real>() -> (T, T) {
    (T::zero(), T::one())
}
