//! What a parametric curve or surface can do, as small capability traits
//! (after kurbo's `ParamCurve` family): [`ParamCurve`] (domain and point),
//! [`ParamCurveDeriv`] (first derivative), [`ParamSurface`] and
//! [`ParamSurfaceDeriv`]. Generic code — sampling, flattening, distance
//! measurements in `verify` — takes any of them.
//!
//! Every curve and surface type of the crate implements them here, over
//! its own scalar `T` (f64 or MPFR) and its own error type. The domain is
//! always in `T`. Outside its domain each type keeps its own documented
//! rule: polynomial pieces extrapolate (Bézier, Hermite), spline types
//! refuse with their error.
//!
//! | type | curve | derivative |
//! |---|---|---|
//! | [`Bezier`] | ✓ | ✓ (hodograph) |
//! | [`Hermite`] | ✓ | ✓ |
//! | [`CatmullRom`] | ✓ | ✓ |
//! | [`RationalBezier`] | ✓ | |
//! | [`BSpline`] | ✓ | ✓ |
//! | [`NurbsCurve`] | ✓ | |
//! | [`SsplineCurve`] | ✓ | |
//! | [`ClampedCubicSpline`] | ✓ | ✓ |
//! | [`QiInterpolation`] | ✓ | ✓ |
//! | [`Patch`], [`SsplineSurface`], [`NurbsSurface`] | surface | [`Patch`] |

use crate::bernstein::bezier::{Bezier, BezierError};
use crate::bspline::de_boor::{BSpline, BSplineError};
use crate::bspline::nurbs::{NurbsCurve, NurbsSurface};
use crate::curves::CurveError;
use crate::curves::catmull_rom::CatmullRom;
use crate::curves::hermite::Hermite;
use crate::curves::rational_bezier::RationalBezier;
use crate::qi::cubic_spline::ClampedCubicSpline;
use crate::qi::interpolate::QiInterpolation;
use crate::scalar::Real;
use crate::sspline::curve::{CurveError as SsplineCurveError, SsplineCurve};
use crate::sspline::surface::SsplineSurface;
use crate::surface_deformation::patch::{Patch, PatchError};
use nalgebra::SVector;
use std::convert::Infallible;

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
                a.clone() + (b.clone() - a.clone()) * s
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
fn check_domain<T: Real>(t: &T, lo: &T, hi: &T) -> Result<(), OutOfDomain> {
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
fn widen<T: Real>((a, b): (f64, f64)) -> (T, T) {
    (T::from_f64_exact(a), T::from_f64_exact(b))
}

fn unit<T: Real>() -> (T, T) {
    (T::zero(), T::one())
}

impl<T: Real, const D: usize> ParamCurve<T, D> for Bezier<T, D> {
    type Error = BezierError;
    fn domain(&self) -> (T, T) {
        unit()
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, BezierError> {
        Bezier::eval(self, t)
    }
}

impl<T: Real, const D: usize> ParamCurveDeriv<T, D> for Bezier<T, D> {
    /// The hodograph `n Σ (P_{i+1} − P_i) B_i^{n−1}(t)` by de Casteljau;
    /// zero for a point (degree 0).
    fn deriv(&self, t: &T) -> Result<SVector<T, D>, BezierError> {
        let p = self.points();
        let n = p.len() - 1;
        if n == 0 {
            return Ok(SVector::zeros());
        }
        let diff: Vec<_> = p.windows(2).map(|w| &w[1] - &w[0]).collect();
        Ok(crate::bernstein::bezier::de_casteljau(&diff, t)? * T::from_int(n as i64))
    }
}

impl<T: Real, const D: usize> ParamCurve<T, D> for Hermite<T, D> {
    type Error = Infallible;
    fn domain(&self) -> (T, T) {
        unit()
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, Infallible> {
        Ok(Hermite::eval(self, t))
    }
}

impl<T: Real, const D: usize> ParamCurveDeriv<T, D> for Hermite<T, D> {
    fn deriv(&self, t: &T) -> Result<SVector<T, D>, Infallible> {
        Ok(Hermite::derivative(self, t))
    }
}

impl<T: Real, const D: usize> ParamCurve<T, D> for CatmullRom<T, D> {
    type Error = CurveError;
    fn domain(&self) -> (T, T) {
        let k = self.knots();
        (k[0].clone(), k[k.len() - 1].clone())
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, CurveError> {
        CatmullRom::eval(self, t).map(|(p, _)| p)
    }
}

impl<T: Real, const D: usize> ParamCurveDeriv<T, D> for CatmullRom<T, D> {
    fn deriv(&self, t: &T) -> Result<SVector<T, D>, CurveError> {
        CatmullRom::eval(self, t).map(|(_, d)| d)
    }
}

impl<T: Real, const D: usize> ParamCurve<T, D> for RationalBezier<T, D> {
    type Error = CurveError;
    fn domain(&self) -> (T, T) {
        unit()
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, CurveError> {
        RationalBezier::eval(self, t)
    }
}

impl<T: Real, const D: usize> ParamCurve<T, D> for BSpline<T, D> {
    type Error = BSplineError;
    fn domain(&self) -> (T, T) {
        BSpline::domain(self)
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, BSplineError> {
        BSpline::eval(self, t)
    }
}

impl<T: Real, const D: usize> ParamCurveDeriv<T, D> for BSpline<T, D> {
    fn deriv(&self, t: &T) -> Result<SVector<T, D>, BSplineError> {
        self.eval_derivative(t, 1)
    }
}

impl<T: Real, const D: usize> ParamCurve<T, D> for NurbsCurve<T, D> {
    type Error = BSplineError;
    fn domain(&self) -> (T, T) {
        NurbsCurve::domain(self)
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, BSplineError> {
        NurbsCurve::eval(self, t)
    }
}

impl<T: Real, const D: usize> ParamCurve<T, D> for SsplineCurve<T, D> {
    type Error = SsplineCurveError;
    fn domain(&self) -> (T, T) {
        widen(SsplineCurve::domain(self))
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, SsplineCurveError> {
        SsplineCurve::eval(self, t)
    }
}

/// The piece `i` and local `τ ∈ [0, 1]` of the global parameter `t` on the
/// knots `k` (the last piece takes `t = k_last`).
fn piece<T: Real>(k: &[T], t: &T) -> Result<(usize, T), OutOfDomain> {
    let last = k.len() - 1;
    check_domain(t, &k[0], &k[last])?;
    let i = k
        .partition_point(|x| x <= t)
        .saturating_sub(1)
        .min(last - 1);
    let tau = (t.clone() - k[i].clone()) / (k[i + 1].clone() - k[i].clone());
    Ok((i, tau))
}

impl<T: Real> ParamCurve<T, 3> for ClampedCubicSpline<T> {
    type Error = OutOfDomain;
    fn domain(&self) -> (T, T) {
        let k = self.knots();
        (k[0].clone(), k[k.len() - 1].clone())
    }
    fn eval(&self, t: &T) -> Result<SVector<T, 3>, OutOfDomain> {
        let (i, tau) = piece(self.knots(), t)?;
        let [p, _, _] = self.jet(i, &tau);
        Ok(p)
    }
}

impl<T: Real> ParamCurveDeriv<T, 3> for ClampedCubicSpline<T> {
    fn deriv(&self, t: &T) -> Result<SVector<T, 3>, OutOfDomain> {
        let (i, tau) = piece(self.knots(), t)?;
        let [_, d, _] = self.jet(i, &tau);
        Ok(d)
    }
}

/// The QI curve on `[0, n]`: segment `i` on `[i, i + 1]`.
impl<T: Real> ParamCurve<T, 3> for QiInterpolation<T> {
    type Error = OutOfDomain;
    fn domain(&self) -> (T, T) {
        (T::zero(), T::from_int(self.segments.len() as i64))
    }
    fn eval(&self, t: &T) -> Result<SVector<T, 3>, OutOfDomain> {
        let (i, tau) = self.segment_at(t)?;
        Ok(self.point(i, &tau))
    }
}

impl<T: Real> ParamCurveDeriv<T, 3> for QiInterpolation<T> {
    /// `l_i T_i(τ)`: each segment has speed `l_i` in its local parameter.
    fn deriv(&self, t: &T) -> Result<SVector<T, 3>, OutOfDomain> {
        let (i, tau) = self.segment_at(t)?;
        let s = &self.segments[i];
        Ok(s.tangent_at(&tau) * s.length.clone())
    }
}

impl<T: Real> QiInterpolation<T> {
    fn segment_at(&self, t: &T) -> Result<(usize, T), OutOfDomain> {
        let (lo, hi) = ParamCurve::domain(self);
        check_domain(t, &lo, &hi)?;
        let i = (t.clone().floor().to_f64() as usize).min(self.segments.len() - 1);
        Ok((i, t.clone() - T::from_int(i as i64)))
    }
}

impl<T: Real> ParamSurface<T, 3> for Patch<T> {
    type Error = PatchError;
    fn domain(&self) -> ((T, T), (T, T)) {
        (unit(), unit())
    }
    fn eval(&self, u: &T, v: &T) -> Result<SVector<T, 3>, PatchError> {
        Patch::eval(self, u, v)
    }
}

impl<T: Real> ParamSurfaceDeriv<T, 3> for Patch<T> {
    fn partials(&self, u: &T, v: &T) -> Result<(SVector<T, 3>, SVector<T, 3>), PatchError> {
        self.derivatives(u, v)
    }
}

impl<T: Real, const D: usize> ParamSurface<T, D> for SsplineSurface<T, D> {
    type Error = SsplineCurveError;
    fn domain(&self) -> ((T, T), (T, T)) {
        let (u, v) = SsplineSurface::domain(self);
        (widen(u), widen(v))
    }
    fn eval(&self, u: &T, v: &T) -> Result<SVector<T, D>, SsplineCurveError> {
        SsplineSurface::eval(self, u, v)
    }
}

impl<T: Real, const D: usize> ParamSurface<T, D> for NurbsSurface<T, D> {
    type Error = BSplineError;
    fn domain(&self) -> ((T, T), (T, T)) {
        self.domains()
    }
    fn eval(&self, u: &T, v: &T) -> Result<SVector<T, D>, BSplineError> {
        NurbsSurface::eval(self, u, v)
    }
}
