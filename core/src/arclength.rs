//! Arc length of a curve with a derivative, and its inverse: the capability
//! [`ParamCurveArclen`] (after kurbo's trait of that name: `arclen(accuracy)`
//! and `inv_arclen(s, accuracy)`), implemented for every
//! [`ParamCurveDeriv`] — Bézier, Hermite, Catmull–Rom, B-spline, NURBS,
//! clamped cubic and QI curves.
//!
//! **Method**: `L(t_0, t_1) = ∫ ‖P'(t)‖₂ dt` by adaptive Gauss–Legendre
//! quadrature: on each interval of width `h` an 8-point rule is compared with
//! the same rule on the two halves, and the halves' sum is accepted when the
//! two differ by at most `rate · h`, `rate = accuracy / (2 (b − a))` over the
//! domain `[a, b]`; otherwise each half is refined in turn. The accepted
//! pieces' estimates sum to at most `accuracy / 2` over the whole domain (and
//! over any part of it), the halves being far more accurate than the whole
//! for a smooth speed. The curve's breakpoints
//! ([`ParamCurveDeriv::breakpoints`]: spline knots) split the integral first,
//! so that the speed is smooth on every part; other kinks (cusps where
//! `P' = 0`) are found by the refinement itself.
//!
//! [`inv_arclen`](ParamCurveArclen::inv_arclen) finds `t` with
//! `L(a, t) = s` by Newton's method `t ← t + (s − L)/‖P'(t)‖` safeguarded by
//! bisection on a bracket, each step adding the length of the step's
//! interval to the running length.
//!
//! **Accuracy**: the estimate is not a bound; measured against closed forms
//! (line, circle arc by a rational quadratic NURBS, parabola) and 256-bit
//! MPFR references in `verify/tests/it/arclength.rs`, the error stays below
//! `accuracy` (and far below it for smooth curves).
//!
//! **Source**: adaptive quadrature by interval halving (Gander & Gautschi,
//! *Adaptive quadrature — revisited*, BIT 40, 2000); the Gauss–Legendre rule
//! of [`crate::quadrature`]; the interface of kurbo's `ParamCurveArclen`.

use crate::param_curve::ParamCurveDeriv;
use crate::quadrature::GaussLegendre;
use crate::scalar::Real;

/// Nodes of the Gauss–Legendre rule (exact for speeds of degree ≤ 15).
const NODES: usize = 8;

/// Deepest interval halving (`2⁻⁶⁰` of the domain).
pub const MAX_DEPTH: usize = 60;

/// Most Newton/bisection steps of `inv_arclen`.
const MAX_STEPS: usize = 200;

/// Why an arc length could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ArclenError<E: std::error::Error + 'static> {
    /// The curve's own evaluation failed.
    #[error(transparent)]
    Curve(E),
    /// The accuracy or the length asked for is not a usable number.
    #[error("{name} = {value} is outside {range}")]
    OutOfRange {
        /// Which input.
        name: &'static str,
        /// Its value (as f64).
        value: f64,
        /// The accepted range.
        range: &'static str,
    },
    /// The refinement reached [`MAX_DEPTH`] (an accuracy below what the
    /// precision can resolve, or a speed that is not integrable).
    #[error("arc length did not reach the accuracy within {0} halvings")]
    NotConverged(usize),
}

/// Arc length and its inverse (module doc), for every curve with a derivative.
///
/// ```
/// use nalgebra::Vector2;
/// use splinelab::arclength::ParamCurveArclen;
/// use splinelab::bernstein::bezier::Bezier;
/// // A straight cubic from (0, 0) to (3, 4) with uneven speed (control
/// // points at 0, 1, 4, 5 along the line): length 5.
/// let c = Bezier::new(vec![Vector2::new(0.0f64, 0.0), Vector2::new(0.6, 0.8),
///                          Vector2::new(2.4, 3.2), Vector2::new(3.0, 4.0)]).unwrap();
/// assert!((c.arclen(&1e-12).unwrap() - 5.0).abs() < 1e-12);
/// ```
///
/// ```
/// // In MPFR: the parabola (t, t²) on [0, 1] has length √5/2 + asinh(2)/4.
/// use nalgebra::Vector2;
/// use splinelab::arclength::ParamCurveArclen;
/// use splinelab::bernstein::bezier::Bezier;
/// use splinelab::scalar::{Mp, Real};
/// type M = Mp<256>;
/// let v = |x: f64, y: f64| Vector2::new(M::from_f64_exact(x), M::from_f64_exact(y));
/// let c = Bezier::new(vec![v(0.0, 0.0), v(0.5, 0.0), v(1.0, 1.0)]).unwrap();
/// let (five, two) = (rug::Float::with_val(256, 5), rug::Float::with_val(256, 2));
/// let exact: rug::Float = five.sqrt() / 2u32 + two.asinh() / 4u32;
/// let got: rug::Float = c.arclen(&M::from_f64_exact(1e-60)).unwrap().to_float();
/// assert!((got - exact).abs().to_f64() < 1e-60);
/// ```
pub trait ParamCurveArclen<T: Real, const D: usize>: ParamCurveDeriv<T, D> {
    /// The length of the curve over its domain, to within `accuracy`.
    /// **Errors**: `accuracy` not finite or `≤ 0`; the curve's evaluation;
    /// [`ArclenError::NotConverged`].
    fn arclen(&self, accuracy: &T) -> Result<T, ArclenError<Self::Error>>
    where
        Self::Error: 'static,
    {
        let (a, b) = self.domain();
        self.arclen_between(&a, &b, accuracy)
    }

    /// The length of the curve between the parameters `t0 ≤ t1` of its
    /// domain, to within `accuracy`.
    fn arclen_between(&self, t0: &T, t1: &T, accuracy: &T) -> Result<T, ArclenError<Self::Error>>
    where
        Self::Error: 'static,
    {
        let rate = rate_of(self, accuracy)?;
        let rule = rule::<T, Self::Error>()?;
        integrate(self, &rule, t0, t1, &rate)
    }

    /// The parameter `t` at which the length from the domain start is `s`
    /// (`0 ≤ s ≤` the curve's length), to within `accuracy` of arc length:
    /// `|L(a, t) − s| ≤ accuracy`. Lengths within `accuracy` past either end
    /// give that end. **Errors**: `s` or `accuracy` not finite, `s`
    /// outside `[−accuracy, L + accuracy]`, as [`ParamCurveArclen::arclen`].
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::arclength::ParamCurveArclen;
    /// use splinelab::bernstein::bezier::Bezier;
    /// use splinelab::param_curve::ParamCurve;
    /// // The straight cubic of uneven speed: 2.5 along it is the point (1.5, 2).
    /// let c = Bezier::new(vec![Vector2::new(0.0f64, 0.0), Vector2::new(2.4, 3.2),
    ///                          Vector2::new(0.3, 0.4), Vector2::new(3.0, 4.0)]).unwrap();
    /// let t = c.inv_arclen(&2.5, &1e-12).unwrap();
    /// assert!((c.eval(&t).unwrap() - Vector2::new(1.5, 2.0)).norm() < 1e-11);
    /// ```
    fn inv_arclen(&self, s: &T, accuracy: &T) -> Result<T, ArclenError<Self::Error>>
    where
        Self::Error: 'static,
    {
        let rate = rate_of(self, accuracy)?;
        let rule = rule::<T, Self::Error>()?;
        let (a, b) = self.domain();
        let total = integrate(self, &rule, &a, &b, &rate)?;
        if !s.is_finite() || *s < -accuracy.clone() || *s > total.clone() + accuracy {
            return Err(ArclenError::OutOfRange {
                name: "arc length",
                value: s.to_f64(),
                range: "[0, the curve's length]",
            });
        }
        let half = accuracy.clone().scale_by_pow2(-1);
        if *s <= half {
            return Ok(a);
        }
        if total.clone() - s <= half {
            return Ok(b);
        }
        // Bracket [lo, hi] with L(lo) ≤ s ≤ L(hi); `len_lo` the running length.
        let (mut lo, mut hi) = (a.clone(), b);
        let mut len_lo = T::zero();
        // First guess: proportional to the length.
        let mut t = a.clone() + (hi.clone() - a) * (s.clone() / total);
        for _ in 0..MAX_STEPS {
            let len_t = len_lo.clone() + integrate(self, &rule, &lo, &t, &rate)?;
            let miss = s.clone() - &len_t;
            if miss.clone().abs() <= half {
                return Ok(t);
            }
            if miss > T::zero() {
                (lo, len_lo) = (t.clone(), len_t);
            } else {
                hi = t.clone();
            }
            let speed = self.deriv(&t).map_err(ArclenError::Curve)?.norm();
            let newton = t.clone() + miss / speed.clone();
            t = if speed > T::zero() && newton > lo && newton < hi {
                newton
            } else {
                (lo.clone() + &hi).scale_by_pow2(-1)
            };
        }
        Err(ArclenError::NotConverged(MAX_STEPS))
    }
}

impl<T: Real, const D: usize, C: ParamCurveDeriv<T, D> + ?Sized> ParamCurveArclen<T, D> for C {}

/// The accepted error per unit parameter, `accuracy / (2 (b − a))`.
fn rate_of<T: Real, const D: usize, C: ParamCurveDeriv<T, D> + ?Sized>(
    curve: &C,
    accuracy: &T,
) -> Result<T, ArclenError<C::Error>> {
    if !accuracy.is_finite() || *accuracy <= T::zero() {
        return Err(ArclenError::OutOfRange {
            name: "accuracy",
            value: accuracy.to_f64(),
            range: "(0, ∞)",
        });
    }
    let (a, b) = curve.domain();
    let width = (b - a).max(T::unit_roundoff());
    Ok(accuracy.clone() / (width * T::from_int(2)))
}

fn rule<T: Real, E: std::error::Error + 'static>() -> Result<GaussLegendre<T>, ArclenError<E>> {
    GaussLegendre::new(NODES).map_err(|_| ArclenError::NotConverged(0))
}

/// The rule on `[t0, t1]` applied to the speed `‖P'‖`.
fn gauss<T: Real, const D: usize, C: ParamCurveDeriv<T, D> + ?Sized>(
    curve: &C,
    rule: &GaussLegendre<T>,
    t0: &T,
    t1: &T,
) -> Result<T, ArclenError<C::Error>> {
    let h = t1.clone() - t0;
    let mut sum = T::zero();
    for (x, w) in rule.nodes().iter().zip(rule.weights()) {
        let t = t0.clone() + h.clone() * x.clone();
        sum += w.clone() * curve.deriv(&t).map_err(ArclenError::Curve)?.norm();
    }
    Ok(sum * h)
}

/// `L(t0, t1)`: adaptive halving (module doc, [`refine`]) between the
/// curve's breakpoints inside `(t0, t1)` (where the speed may have a kink
/// that halving would chase).
fn integrate<T: Real, const D: usize, C: ParamCurveDeriv<T, D> + ?Sized>(
    curve: &C,
    rule: &GaussLegendre<T>,
    t0: &T,
    t1: &T,
    rate: &T,
) -> Result<T, ArclenError<C::Error>> {
    let mut cuts = vec![t0.clone()];
    cuts.extend(curve.breakpoints().into_iter().filter(|b| b > t0 && b < t1));
    cuts.push(t1.clone());
    let mut sum = T::zero();
    for w in cuts.windows(2) {
        if w[1] > w[0] {
            let whole = gauss(curve, rule, &w[0], &w[1])?;
            sum += refine(curve, rule, &w[0], &w[1], whole, rate, 0)?;
        }
    }
    Ok(sum)
}

/// The halves of `[t0, t1]` against `whole`, the rule on all of it.
fn refine<T: Real, const D: usize, C: ParamCurveDeriv<T, D> + ?Sized>(
    curve: &C,
    rule: &GaussLegendre<T>,
    t0: &T,
    t1: &T,
    whole: T,
    rate: &T,
    depth: usize,
) -> Result<T, ArclenError<C::Error>> {
    let mid = (t0.clone() + t1).scale_by_pow2(-1);
    let left = gauss(curve, rule, t0, &mid)?;
    let right = gauss(curve, rule, &mid, t1)?;
    let halves = left.clone() + &right;
    if (whole - halves.clone()).abs() <= rate.clone() * (t1.clone() - t0) {
        return Ok(halves);
    }
    if depth >= MAX_DEPTH || mid <= *t0 || mid >= *t1 {
        return Err(ArclenError::NotConverged(MAX_DEPTH));
    }
    Ok(refine(curve, rule, t0, &mid, left, rate, depth + 1)?
        + refine(curve, rule, &mid, t1, right, rate, depth + 1)?)
}
