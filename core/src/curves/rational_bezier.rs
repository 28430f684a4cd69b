//! Rational Bézier curves (seed 002, "有理ベジエ曲線"): each Bernstein weight
//! `λ_i(t) = B_i^n(t)` is multiplied by a weight `w_i` and renormalised,
//! `P(t) = Σ w_i B_i^n(t) P_i / Σ w_i B_i^n(t)` — no longer a polynomial, so
//! circular arcs become exact.

use super::{CurveError, check_points};
use crate::bernstein::bezier::{check_parameter, de_casteljau};
use crate::param_curve::{ParamCurve, unit};
use crate::scalar::Real;
use crate::validation::{at_least, finite, finite_vector};
use nalgebra::{SVector, Vector2};

/// A rational Bézier curve of degree `n`, stored in homogeneous form
/// `(H_i, w_i) = (w_i P_i, w_i)`, which is what the projective de Casteljau
/// algorithm runs on.
///
/// Invariants: `n + 1 ≥ 1` points, all coordinates finite, all weights
/// finite and `≥ 0`, the end weights `> 0`; so the weight function
/// `Σ w_i B_i^n(t)` is positive on `[0, 1]`. A zero *interior* weight is a
/// point at infinity (`H_i` is then a direction), which only
/// [`RationalBezier::from_homogeneous`] accepts — it is what makes the exact
/// 180° arc possible.
#[derive(Clone, Debug, PartialEq)]
pub struct RationalBezier<T: Real, const D: usize> {
    homogeneous: Vec<SVector<T, D>>,
    weights: Vec<T>,
}

fn check_weights<T: Real>(weights: &[T], interior_zero_ok: bool) -> Result<(), CurveError> {
    let n = weights.len().saturating_sub(1);
    for (index, w) in weights.iter().enumerate() {
        let zero_ok = interior_zero_ok && index != 0 && index != n;
        let ok = w.is_finite() && (*w > T::zero() || (zero_ok && w.is_zero()));
        if !ok {
            return Err(CurveError::BadWeight {
                index,
                value: w.to_f64(),
            });
        }
    }
    Ok(())
}

impl<T: Real, const D: usize> RationalBezier<T, D> {
    /// A curve from affine control points `P_i` and weights `w_i`, every
    /// weight finite and `> 0` (zero, negative or non-finite weights are a
    /// typed error). Stores `w_i P_i` (one rounding per coordinate).
    pub fn new(points: Vec<SVector<T, D>>, weights: Vec<T>) -> Result<Self, CurveError> {
        Self::check_lengths(points.len(), weights.len())?;
        check_points(&points)?;
        check_weights(&weights, false)?;
        let homogeneous = points
            .iter()
            .zip(&weights)
            .map(|(p, w)| p * w.clone())
            .collect();
        Self::from_homogeneous(homogeneous, weights)
    }

    /// A curve from homogeneous control points `H_i = w_i P_i` and weights.
    /// Weights must be finite and `≥ 0` with positive end weights; an
    /// interior zero weight makes `H_i` a point at infinity (a direction).
    /// Validation only: the homogeneous points are stored exactly. **Source**:
    /// seed 002 (rational Bézier); Piegl & Tiller, *The NURBS Book*, §1.5.
    pub fn from_homogeneous(
        homogeneous: Vec<SVector<T, D>>,
        weights: Vec<T>,
    ) -> Result<Self, CurveError> {
        Self::check_lengths(homogeneous.len(), weights.len())?;
        check_points(&homogeneous)?;
        check_weights(&weights, true)?;
        Ok(RationalBezier {
            homogeneous,
            weights,
        })
    }

    fn check_lengths(points: usize, weights: usize) -> Result<(), CurveError> {
        at_least("a rational Bézier curve", 1, points)?;
        if points != weights {
            return Err(CurveError::LengthMismatch { points, weights });
        }
        Ok(())
    }

    /// The degree `n`.
    pub fn degree(&self) -> usize {
        self.weights.len() - 1
    }

    /// The homogeneous points `H_i = w_i P_i`.
    pub fn homogeneous(&self) -> &[SVector<T, D>] {
        &self.homogeneous
    }

    /// The weights `w_i`.
    pub fn weights(&self) -> &[T] {
        &self.weights
    }

    /// The affine control point `P_i = H_i / w_i`, `None` for a point at
    /// infinity (`w_i = 0`) or `i > n`.
    pub fn point(&self, i: usize) -> Option<SVector<T, D>> {
        let w = self.weights.get(i)?;
        (!w.is_zero()).then(|| &self.homogeneous[i] / w.clone())
    }

    /// `P(t)` by the projective de Casteljau algorithm: de Casteljau on the
    /// homogeneous points `H_i` and on the weights `w_i`, then one division,
    /// `P(t) = H(t) / w(t)` (seed 002; Farin, *Curves and Surfaces for CAGD*, §13.1).
    ///
    /// **Cost**: `(D + 1) n(n+1)/2` affine combinations and `D` divisions.
    /// **Accuracy** (`t ∈ [0, 1]`): `w(t)` has relative error `≤ γ_{3n}`
    /// (all terms positive); each coordinate of `H(t)` has absolute error
    /// `≤ γ_{3n} Σ |H_i| B_i^n(t)`; so `P(t)` is within
    /// `≈ γ_{3n+1} (Σ |H_i| B_i^n(t) / w(t) + |P(t)|)` per coordinate.
    /// Any finite `t` is accepted; outside `[0, 1]` a non-positive weight
    /// function is a typed error.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::curves::rational_bezier::RationalBezier;
    /// // Quarter circle: P1 = (1, 1) with weight cos 45°; at t = ½ the point (√½, √½).
    /// let w = 0.5f64.sqrt();
    /// let c = RationalBezier::new(
    ///     vec![Vector2::new(1.0, 0.0), Vector2::new(1.0, 1.0), Vector2::new(0.0, 1.0)],
    ///     vec![1.0, w, 1.0]).unwrap();
    /// let p = c.eval(&0.5).unwrap();
    /// assert!((p.norm() - 1.0).abs() < 4.0 * f64::EPSILON);
    /// ```
    pub fn eval(&self, t: &T) -> Result<SVector<T, D>, CurveError> {
        check_parameter(t)?;
        let h = de_casteljau(&self.homogeneous, t)?;
        let w = de_casteljau(&self.weights, t)?;
        if !(w > T::zero() && w.is_finite()) {
            return Err(CurveError::VanishingDenominator { t: t.to_f64() });
        }
        let p = h / w;
        finite_vector("P(t)", &p)?;
        Ok(p)
    }

    /// Degree elevation `n → n + 1` of the homogeneous curve:
    /// `H'_i = (i/(n+1)) H_{i−1} + (1 − i/(n+1)) H_i` and the same for the
    /// weights, `i = 0..n+1` (Farin §13.6). The rational curve is unchanged.
    ///
    /// **Cost**: `O(nD)`. **Accuracy**: each new coordinate is within
    /// `3u` relative of the exact convex combination of the stored values.
    /// Measured in `verify/tests/it/curves_rational.rs::degree_elevation_keeps_the_curve`.
    /// **Source**: Piegl & Tiller, *The NURBS Book*, §5.5 (degree elevation).
    pub fn elevate(&self) -> Self {
        let n1 = self.weights.len(); // n + 1
        let lerp = |i: usize, a: &dyn Fn(usize) -> SVector<T, D>| -> SVector<T, D> {
            if i == 0 {
                return a(0);
            }
            if i == n1 {
                return a(n1 - 1);
            }
            let s = T::from_int(i as i64) / T::from_int(n1 as i64);
            a(i - 1) * s.clone() + a(i) * (T::one() - s)
        };
        let h = |i: usize| self.homogeneous[i].clone();
        let w = |i: usize| SVector::<T, D>::repeat(self.weights[i].clone());
        let homogeneous = (0..=n1).map(|i| lerp(i, &h)).collect();
        let weights = (0..=n1).map(|i| lerp(i, &w)[0].clone()).collect();
        RationalBezier {
            homogeneous,
            weights,
        }
    }
}

impl<T: Real> RationalBezier<T, 2> {
    /// The exact circular arc of radius `r` about `centre` from angle `start`
    /// through the counter-clockwise `sweep`, `0 < sweep ≤ π`, as a quadratic
    /// rational Bézier curve with middle weight `w_1 = cos(sweep/2)`.
    ///
    /// **Formula**: with `h = sweep/2` and `m = start + h`, the middle control
    /// point is `P_1 = c + (r / cos h)(cos m, sin m)` (the intersection of the
    /// end tangents), so its homogeneous form is
    /// `H_1 = cos h · c + r (cos m, sin m)` — finite even for the 180° arc,
    /// where `w_1 = 0` and `P_1` is at infinity. The ends are
    /// `c + r(cos a, sin a)` for `a = start`, `start + sweep`.
    ///
    /// **Accuracy**: control data within a few ulps (one `cos`/`sin` each);
    /// measured distance from the centre within 4 ulps of `r` in f64 for
    /// `c = 0`, `r = 1`, plus `u·(|start + sweep/2| + |start + sweep|)·r`
    /// for the rounding of the two angles formed (up to ~19u near 3π; see
    /// `verify/tests/it/curves_rational.rs`).
    /// **Source**: seed 002 (rational Bézier, exact circular arcs); Piegl &
    /// Tiller, *The NURBS Book*, §7.3; the test is
    /// `verify/tests/it/curves_rational.rs::arcs_up_to_180_degrees_are_on_the_circle_f64`.
    ///
    /// ```
    /// // In MPFR: the 120° arc of radius 3 about (1, 2); every point at distance 3.
    /// use nalgebra::Vector2;
    /// use splinelab::curves::rational_bezier::RationalBezier;
    /// use splinelab::nalgebra::RealField;
    /// use splinelab::scalar::{Mp, Real};
    /// type M = Mp<200>;
    /// let sweep = M::two_pi() / M::from_int(3);
    /// let c = RationalBezier::circular_arc(&Vector2::new(M::from_int(1), M::from_int(2)), &M::from_int(3), &M::from_int(0), &sweep).unwrap();
    /// for k in 0..=8 {
    ///     let d = c.eval(&(M::from_int(k) / M::from_int(8))).unwrap() - Vector2::new(M::from_int(1), M::from_int(2));
    ///     assert!((d.norm_squared() - M::from_int(9)).to_f64().abs() < 1e-55);
    /// }
    /// ```
    pub fn circular_arc(
        centre: &Vector2<T>,
        r: &T,
        start: &T,
        sweep: &T,
    ) -> Result<Self, CurveError> {
        for (name, x) in [
            ("centre.x", &centre.x),
            ("centre.y", &centre.y),
            ("radius", r),
            ("start", start),
            ("sweep", sweep),
        ] {
            finite(name, x)?;
        }
        if *r <= T::zero() {
            return Err(CurveError::OutOfRange {
                name: "radius",
                value: r.to_f64(),
                range: "(0, ∞)",
            });
        }
        if *sweep <= T::zero() || *sweep > T::pi() {
            return Err(CurveError::OutOfRange {
                name: "sweep",
                value: sweep.to_f64(),
                range: "(0, π]",
            });
        }
        let h = sweep.clone() / T::from_int(2);
        let on_circle = |a: T| Vector2::new(a.clone().cos(), a.sin()) * r.clone();
        let w1 = h.clone().cos().max(T::zero());
        let h0 = centre + on_circle(start.clone());
        let h1 = centre * w1.clone() + on_circle(start.clone() + h);
        let h2 = centre + on_circle(start.clone() + sweep);
        Self::from_homogeneous(vec![h0, h1, h2], vec![T::one(), w1, T::one()])
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

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    #[test]
    fn zero_negative_and_non_finite_weights_are_errors() {
        let p = vec![
            Vector2::new(0.0f64, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(2.0, 0.0),
        ];
        for (w, index) in [(0.0, 1), (-1.0, 1), (f64::NAN, 1), (f64::INFINITY, 1)] {
            assert!(matches!(
                RationalBezier::new(p.clone(), vec![1.0, w, 1.0]),
                Err(CurveError::BadWeight { index: i, .. }) if i == index
            ));
        }
        // A zero end weight is refused even in homogeneous form.
        assert!(matches!(
            RationalBezier::from_homogeneous(p.clone(), vec![0.0, 1.0, 1.0]),
            Err(CurveError::BadWeight { index: 0, .. })
        ));
        assert_eq!(
            RationalBezier::new(p.clone(), vec![1.0, 1.0]),
            Err(CurveError::LengthMismatch {
                points: 3,
                weights: 2
            })
        );
        assert!(matches!(
            RationalBezier::circular_arc(&Vector2::zeros(), &1.0, &0.0, &4.0),
            Err(CurveError::OutOfRange { name: "sweep", .. })
        ));
    }

    #[test]
    fn unit_weights_reproduce_the_polynomial_curve() {
        let p = vec![
            Vector2::new(0.0f64, 0.0),
            Vector2::new(1.0, 2.0),
            Vector2::new(2.0, 0.0),
        ];
        let c = RationalBezier::new(p, vec![1.0; 3]).unwrap();
        assert_eq!(c.eval(&0.5).unwrap(), Vector2::new(1.0, 1.0));
    }
}
