//! NURBS: non-uniform rational B-spline curves and tensor-product surfaces,
//! evaluated by the rational de Boor algorithm (seed 002 "BスプラインとNURBS":
//! non-uniform knots, weighted control points), with the exact circle and
//! cylinder.

use super::de_boor::{BSpline, BSplineError, check_structure, de_boor_window, find_span};
use super::knots::KnotVector;
use crate::bernstein::affine_step::AffineStep;
use crate::param_curve::{ParamCurve, ParamCurveDeriv, ParamSurface};
use crate::scalar::Real;
use crate::validation::{finite, finite_points};
use nalgebra::{SVector, Vector1, Vector2, Vector3};
use rug::Rational;

fn check_weights<T: Real>(weights: &[T]) -> Result<(), BSplineError> {
    match weights
        .iter()
        .position(|w| !(w.is_finite() && *w > T::zero()))
    {
        Some(index) => Err(BSplineError::BadWeight {
            index,
            value: weights[index].to_f64(),
        }),
        None => Ok(()),
    }
}

fn check_weight_count(points: usize, weights: usize) -> Result<(), BSplineError> {
    if points == weights {
        Ok(())
    } else {
        Err(BSplineError::WeightCount { points, weights })
    }
}

/// A homogeneous point `(w Q, w)`: the weight carried as one more
/// coordinate, so that one de Boor triangle (one `α` per step) serves the
/// numerator and the denominator of the rational form.
#[derive(Clone, Debug)]
struct Weighted<T: Real, const D: usize> {
    point: SVector<T, D>,
    weight: T,
}

impl<T: Real, const D: usize> Weighted<T, D> {
    fn new(point: &SVector<T, D>, weight: &T) -> Self {
        Weighted {
            point: point.clone(),
            weight: weight.clone(),
        }
    }

    /// The affine point `w Q / w`.
    fn project(self) -> SVector<T, D> {
        self.point / self.weight
    }
}

/// Coordinate by coordinate: the point's, then the weight's.
impl<T: Real, const D: usize> AffineStep<T> for Weighted<T, D> {
    fn affine_step(&mut self, r: &T, b: &Self, t: &T) {
        self.point.affine_step(r, &b.point, t);
        self.weight.affine_step(r, &b.weight, t);
    }
    fn scale_in_place(&mut self, r: &T) {
        self.point.scale_in_place(r);
        self.weight.scale_in_place(r);
    }
    fn accumulate(&mut self, b: &Self) {
        self.point.accumulate(&b.point);
        self.weight.accumulate(&b.weight);
    }
}

/// The homogeneous window `(w_j Q_j, w_j)`, `j ∈ lo..=hi`.
fn weighted_window<T: Real, const D: usize>(
    homogeneous: &[SVector<T, D>],
    weights: &[T],
    lo: usize,
    hi: usize,
) -> Vec<Weighted<T, D>> {
    homogeneous[lo..=hi]
        .iter()
        .zip(&weights[lo..=hi])
        .map(|(p, w)| Weighted::new(p, w))
        .collect()
}

/// Positive finite radius, else [`BSplineError::BadRadius`].
fn check_radius<T: Real>(r: &T) -> Result<(), BSplineError> {
    if r.is_finite() && *r > T::zero() {
        Ok(())
    } else {
        Err(BSplineError::BadRadius { value: r.to_f64() })
    }
}

/// A NURBS curve `P(t) = Σ N_{j,k}(t) w_j Q_j / Σ N_{j,k}(t) w_j`, stored as
/// the B-spline of the homogeneous points `w_j Q_j` plus the weights (all
/// finite and `> 0`, so the denominator is positive on the domain).
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsCurve<T: Real, const D: usize> {
    homogeneous: BSpline<T, D>,
    weights: Vec<T>,
}

impl<T: Real, const D: usize> NurbsCurve<T, D> {
    /// From affine control points, weights (`> 0`, finite) and knots;
    /// stores `w_j Q_j` (one rounding per coordinate). **Method**: the
    /// homogeneous form of Piegl & Tiller, *The NURBS Book*, §4.2.
    pub fn new(
        order: usize,
        points: Vec<SVector<T, D>>,
        weights: Vec<T>,
        knots: KnotVector<T>,
    ) -> Result<Self, BSplineError> {
        check_weights(&weights)?;
        check_weight_count(points.len(), weights.len())?;
        let h: Vec<_> = points
            .iter()
            .zip(&weights)
            .map(|(p, w)| p * w.clone())
            .collect();
        Self::from_homogeneous(order, h, weights, knots)
    }

    /// From homogeneous points `w_j Q_j`, weights and knots. **Method**:
    /// validation only; stored exactly (no rounding). **Source**: Piegl &
    /// Tiller, *The NURBS Book*, §4.2.
    pub fn from_homogeneous(
        order: usize,
        homogeneous: Vec<SVector<T, D>>,
        weights: Vec<T>,
        knots: KnotVector<T>,
    ) -> Result<Self, BSplineError> {
        check_weights(&weights)?;
        check_weight_count(homogeneous.len(), weights.len())?;
        Ok(NurbsCurve {
            homogeneous: BSpline::new(order, homogeneous, knots)?,
            weights,
        })
    }

    /// The homogeneous B-spline `Σ N_j w_j Q_j` (order, knots, `w_j Q_j`).
    pub fn homogeneous(&self) -> &BSpline<T, D> {
        &self.homogeneous
    }

    /// The weights.
    pub fn weights(&self) -> &[T] {
        &self.weights
    }

    /// The parameter domain.
    pub fn domain(&self) -> (T, T) {
        self.homogeneous.domain()
    }

    /// `P(t)` by the rational de Boor algorithm: one de Boor triangle on the
    /// homogeneous points `(w_j Q_j, w_j)`, the weight carried as a
    /// coordinate, then one division (Piegl–Tiller §4.2).
    ///
    /// **Cost**: `(D + 1) k(k−1)/2` affine combinations. **Accuracy**: the
    /// weight sum has relative error `≤ γ_{3k}` (positive terms); each
    /// numerator coordinate `≤ γ_{3k} Σ N_j |w_j Q_j|`; so `P(t)` is within
    /// `≈ γ_{3k+1}(Σ N_j |w_j Q_j| / w(t) + |P(t)|)` per coordinate.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::bspline::nurbs::NurbsCurve;
    /// let c = NurbsCurve::circle(&Vector2::new(0.0f64, 0.0), &1.0).unwrap();
    /// let p = c.eval(&0.3).unwrap();
    /// assert!((p.norm() - 1.0).abs() < 4.0 * f64::EPSILON);
    /// ```
    pub fn eval(&self, t: &T) -> Result<SVector<T, D>, BSplineError> {
        let b = &self.homogeneous;
        let (k, knots) = (b.order(), b.knots().as_slice());
        let s = b.span(t)?;
        let lo = s + 1 - k;
        let window = weighted_window(b.points(), &self.weights, lo, s);
        Ok(de_boor_window(k, knots, window, s, t).project())
    }
}

/// The weight `√2/2` of the 90° corners of the NURBS circle, and the
/// 9-point circle's knots `0,0,0,¼,¼,½,½,¾,¾,1,1,1`.
fn circle_data<T: Real>() -> (T, KnotVector<T>) {
    let q = |n: i64| T::from_rational(&Rational::from((n, 4)));
    let knots = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4].map(q).to_vec();
    let s = T::from_int(2).sqrt() / T::from_int(2);
    (s, KnotVector::new(knots).expect("constant knots are valid"))
}

/// The 9-point circle of radius `r` about the origin: the affine control
/// points `r·d` on the circumscribed square (`d` its corners and edge
/// midpoints) and their weights (`√2/2` at the corners, 1 elsewhere).
fn circle_net<T: Real>(r: &T, corner: &T) -> Vec<(Vector2<T>, T)> {
    let dirs = [
        (1, 0),
        (1, 1),
        (0, 1),
        (-1, 1),
        (-1, 0),
        (-1, -1),
        (0, -1),
        (1, -1),
        (1, 0),
    ];
    dirs.iter()
        .enumerate()
        .map(|(j, &(x, y))| {
            let w = if j % 2 == 1 { corner.clone() } else { T::one() };
            (Vector2::new(T::from_int(x), T::from_int(y)) * r.clone(), w)
        })
        .collect()
}

impl<T: Real> NurbsCurve<T, 2> {
    /// The exact circle of radius `r` about `centre`: order 3, 9 control
    /// points on the circumscribed square, corner weights `√2/2`, knots
    /// `0,0,0,¼,¼,½,½,¾,¾,1,1,1` (Piegl–Tiller §7.5). Each quarter is the
    /// rational quadratic arc with `w = cos 45°`, so `|P(t) − c| = r` for all
    /// `t ∈ [0, 1]` in exact arithmetic. Errors for a non-finite centre or
    /// radius or `r ≤ 0`.
    pub fn circle(centre: &Vector2<T>, r: &T) -> Result<Self, BSplineError> {
        check_radius(r)?;
        let (s, knots) = circle_data::<T>();
        let (h, weights) = circle_net(r, &s)
            .into_iter()
            .map(|(p, w)| (p * w.clone() + centre * w.clone(), w))
            .unzip();
        Self::from_homogeneous(3, h, weights, knots)
    }
}

/// A NURBS tensor-product surface
/// `S(u, v) = Σ_i Σ_j N_i(u) N_j(v) w_ij P_ij / Σ_i Σ_j N_i(u) N_j(v) w_ij`,
/// net `P_ij` row-major (`i` along `u`, `n_u` rows of `n_v` points).
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface<T: Real, const D: usize> {
    orders: (usize, usize),
    counts: (usize, usize),
    homogeneous: Vec<SVector<T, D>>,
    weights: Vec<T>,
    knots_u: KnotVector<T>,
    knots_v: KnotVector<T>,
}

impl<T: Real, const D: usize> NurbsSurface<T, D> {
    /// Validates both directions like a [`BSpline`] (orders, counts, knots,
    /// non-empty domains), the net size, finite points and weights `> 0`.
    /// Stores `w_ij P_ij`: one rounding per coordinate (the product by the
    /// weight), computed by the homogeneous rule of Piegl & Tiller, *The
    /// NURBS Book*, §4.4 (NURBS surfaces).
    pub fn new(
        orders: (usize, usize),
        counts: (usize, usize),
        points: Vec<SVector<T, D>>,
        weights: Vec<T>,
        knots: (KnotVector<T>, KnotVector<T>),
    ) -> Result<Self, BSplineError> {
        let (nu, nv) = counts;
        check_structure(orders.0, nu, &knots.0)?;
        check_structure(orders.1, nv, &knots.1)?;
        for got in [points.len(), weights.len()] {
            if nu.checked_mul(nv) != Some(got) {
                return Err(BSplineError::NetSize { nu, nv, got });
            }
        }
        finite_points("control point", &points)?;
        check_weights(&weights)?;
        let homogeneous = points
            .iter()
            .zip(&weights)
            .map(|(p, w)| p * w.clone())
            .collect();
        Ok(NurbsSurface {
            orders,
            counts,
            homogeneous,
            weights,
            knots_u: knots.0,
            knots_v: knots.1,
        })
    }

    /// The parameter rectangle `([t_{k_u−1}, t_{n_u}], [t_{k_v−1}, t_{n_v}])`.
    pub fn domains(&self) -> ((T, T), (T, T)) {
        let ((ku, kv), (nu, nv)) = (self.orders, self.counts);
        let (a, b) = (self.knots_u.as_slice(), self.knots_v.as_slice());
        (
            (a[ku - 1].clone(), a[nu].clone()),
            (b[kv - 1].clone(), b[nv].clone()),
        )
    }

    /// `S(u, v)` by rational de Boor as curves of curves: for each of the
    /// `k_u` rows active at `u`, one de Boor triangle in `v` on `(w P, w)`
    /// (the weight carried as a coordinate); then de Boor in `u` on those
    /// `k_u` homogeneous values; then one division.
    ///
    /// **Cost**: `(D + 1)(k_u k_v(k_v − 1) + k_u(k_u − 1))/2` affine
    /// combinations. **Accuracy**: as [`NurbsCurve::eval`] with `γ_{3(k_u + k_v)}`.
    pub fn eval(&self, u: &T, v: &T) -> Result<SVector<T, D>, BSplineError> {
        let ((ku, kv), (nu, nv)) = (self.orders, self.counts);
        let su = find_span(ku, nu, &self.knots_u, u)?;
        let sv = find_span(kv, nv, &self.knots_v, v)?;
        let (kus, kvs) = (self.knots_u.as_slice(), self.knots_v.as_slice());
        let rows: Vec<_> = (su + 1 - ku..=su)
            .map(|i| {
                let lo = i * nv + sv + 1 - kv;
                let window = weighted_window(&self.homogeneous, &self.weights, lo, i * nv + sv);
                de_boor_window(kv, kvs, window, sv, v)
            })
            .collect();
        Ok(de_boor_window(ku, kus, rows, su, u).project())
    }
}

impl<T: Real> NurbsSurface<T, 3> {
    /// The exact cylinder `x² + y² = r²`, `0 ≤ z ≤ height`: the NURBS circle
    /// (order 3, 9 points) in `u` times a straight line (order 2, knots
    /// `0,0,1,1`) in `v`; `S(u, v)` has `z = v · height` and distance `r`
    /// from the `z` axis. Errors as [`NurbsCurve::circle`], or for a
    /// non-finite height. **Accuracy**: exact in the representation; the
    /// radial error of evaluated points is `≤ 8u` in f64 (`≤ 256u` in MPFR)
    /// (`verify/tests/it/curves_rational.rs::nurbs_circle_and_cylinder_are_exact`).
    /// **Source**: Piegl & Tiller, *The NURBS Book*, §7.5 (circle) and §8.3
    /// (extruded surfaces).
    ///
    /// ```
    /// // In MPFR: a point of the cylinder r = 2, height 3 is at distance 2 from
    /// // the axis to 128-bit rounding, and z = v · height.
    /// use splinelab::bspline::nurbs::NurbsSurface;
    /// use splinelab::scalar::{Mp, Real};
    /// type M = Mp<128>;
    /// let s = NurbsSurface::<M, 3>::cylinder(&M::from_int(2), &M::from_int(3)).unwrap();
    /// let p = s.eval(&M::from_f64_exact(0.3), &M::from_f64_exact(0.5)).unwrap();
    /// let r2 = p[0].clone() * p[0].clone() + p[1].clone() * p[1].clone();
    /// assert!((r2 - M::from_int(4)).to_f64().abs() < 1e-35);
    /// assert!((p[2].clone() - M::from_f64_exact(1.5)).to_f64().abs() < 1e-35);
    /// ```
    pub fn cylinder(r: &T, height: &T) -> Result<Self, BSplineError> {
        check_radius(r)?;
        finite("height", height)?;
        // The circle's net, each point once at z = 0 and once at z = height.
        let (s, knots_u) = circle_data::<T>();
        let mut points = Vec::with_capacity(18);
        let mut weights = Vec::with_capacity(18);
        for (p, w) in circle_net(r, &s) {
            for z in [T::zero(), height.clone()] {
                points.push(Vector3::new(p.x.clone(), p.y.clone(), z));
                weights.push(w.clone());
            }
        }
        let knots_v = KnotVector::new(vec![T::zero(), T::zero(), T::one(), T::one()])?;
        Self::new((3, 2), (9, 2), points, weights, (knots_u, knots_v))
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

impl<T: Real, const D: usize> ParamCurveDeriv<T, D> for NurbsCurve<T, D> {
    /// `P' = (H' − w' P) / w` from the homogeneous B-spline `H = Σ N_j w_j Q_j`
    /// and the weight function `w = Σ N_j w_j`, each with its derivative by de
    /// Boor (Piegl & Tiller, *The NURBS Book*, §4.3, eq 4.8). **Accuracy**:
    /// that of the de Boor derivatives divided by `w > 0`; the NURBS circle's
    /// speed is checked against its closed form in `verify/tests/it/arclength.rs`.
    fn deriv(&self, t: &T) -> Result<SVector<T, D>, BSplineError> {
        let h = &self.homogeneous;
        let w = BSpline::new(
            h.order(),
            self.weights
                .iter()
                .map(|x| Vector1::new(x.clone()))
                .collect(),
            h.knots().clone(),
        )?;
        let (wt, wd) = (w.eval(t)?[0].clone(), w.eval_derivative(t, 1)?[0].clone());
        let p = h.eval(t)? / wt.clone();
        Ok((h.eval_derivative(t, 1)? - p * wd) / wt)
    }
    fn breakpoints(&self) -> Vec<T> {
        self.homogeneous.breakpoints()
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_is_exact_at_dyadic_parameters_and_weights_are_checked() {
        let c = NurbsCurve::circle(&Vector2::new(0.0f64, 0.0), &1.0).unwrap();
        assert_eq!(c.eval(&0.0).unwrap(), Vector2::new(1.0, 0.0));
        assert_eq!(c.eval(&0.25).unwrap(), Vector2::new(0.0, 1.0));
        assert_eq!(c.eval(&1.0).unwrap(), Vector2::new(1.0, 0.0));
        let k = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0]).unwrap();
        let pts = vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)];
        for w in [0.0, -1.0, f64::NAN] {
            assert!(matches!(
                NurbsCurve::new(2, pts.clone(), vec![1.0, w], k.clone()),
                Err(BSplineError::BadWeight { index: 1, .. })
            ));
        }
    }

    #[test]
    fn a_bad_radius_is_named_as_such() {
        let o = Vector2::new(0.0f64, 0.0);
        for r in [0.0, -2.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                NurbsCurve::circle(&o, &r),
                Err(BSplineError::BadRadius { .. })
            ));
            assert!(matches!(
                NurbsSurface::cylinder(&r, &1.0),
                Err(BSplineError::BadRadius { .. })
            ));
        }
    }
}
