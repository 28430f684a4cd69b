//! Boehm knot insertion (seed 003 eq 3–6), multiple insertion and global
//! refinement, on the [`BSpline`] curve of [`super::de_boor`].
//!
//! Inserting `u` with `t_i ≤ u ≤ t_{i+1}`, `t_i < t_{i+1}` (span `i`):
//!
//! `Q'_j = (1 − α_j) Q_{j−1} + α_j Q_j`, with `α_j = 1` for `j ≤ i − k + 1`,
//! `α_j = (u − t_j)/(t_{j+k−1} − t_j)` for `i − k + 2 ≤ j ≤ i`, `α_j = 0`
//! for `j ≥ i + 1` (eq 5–6; the OCR's numerator `t_i − t'_j` is `u − t_j`),
//! and the knot vector gains `u` after `t_i` (eq 3). The curve is unchanged
//! (Boehm 1980) and only `k − 1` points move.
//!
//! The kernel [`insert_raw`] is generic over any ordered field — `f64`,
//! [`crate::scalar::Mp`] and exact `rug::Rational` — so the invariance can be
//! checked exactly. Each new point is the affine combination
//! `Q_{j−1} + α_j (Q_j − Q_{j−1})` with `α_j ∈ [0, 1]`: error
//! `≤ 3u max(|Q_{j−1}|, |Q_j|)` per coordinate and insertion, without growth
//! from one insertion to the next beyond that additive amount.

use super::de_boor::{BSpline, BSplineError};
use crate::scalar::Real;
use nalgebra::SVector;
use std::ops::{Add, Div, Mul, Sub};

/// Why a knot could not be inserted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InsertionError {
    /// `u` is outside the curve's domain `[t_{k−1}, t_{n+1}]` or not finite.
    #[error("knot {u} is outside the domain [{lo}, {hi}]")]
    OutOfDomain {
        /// The knot (as f64).
        u: f64,
        /// Domain start.
        lo: f64,
        /// Domain end.
        hi: f64,
    },
    /// `u` already has multiplicity `k`.
    #[error("knot {u} already has multiplicity {order} (the order)")]
    FullMultiplicity {
        /// The knot (as f64).
        u: f64,
        /// The order.
        order: usize,
    },
    /// Rebuilding the curve failed (cannot happen for valid input).
    #[error(transparent)]
    BSpline(#[from] BSplineError),
}

/// One Boehm insertion of `u` into a B-spline of order `k` with knots
/// `t_0..t_{n+k}` and points `Q_0..Q_n`, over any ordered field `F`.
///
/// Returns `None` when `u` is outside `[t_{k−1}, t_{n+1}]`, that domain is
/// empty, or `u` already has multiplicity `k`. The span is the last `i`,
/// `k − 1 ≤ i ≤ n`, with `t_i ≤ u` and `t_i < t_{i+1}`. **Cost** `O(n)` for
/// the copies, `k − 1` affine combinations.
/// **Method**: Boehm's rule `Q'_j = (1 − α_j) Q_{j−1} + α_j Q_j`,
/// `α_j = (u − t_j)/(t_{j+k−1} − t_j)`. **Accuracy**: exact over the rationals
/// (`verify/tests/it/knot_insertion.rs::insertion_is_exactly_invariant_in_rationals`);
/// the curve moves by at most 4 ulps in f64 (`insertion_is_invariant_to_4_ulps_in_f64`).
pub fn insert_raw<F, P>(order: usize, knots: &[F], points: &[P], u: &F) -> Option<(Vec<F>, Vec<P>)>
where
    F: Clone + PartialOrd + Sub<Output = F> + Div<Output = F>,
    P: Clone + Add<Output = P> + Sub<Output = P> + Mul<F, Output = P>,
{
    let (k, n) = (order, points.len().checked_sub(1)?);
    if k == 0 || knots.len() != n + 1 + k || !(knots[k - 1] <= *u && *u <= knots[n + 1]) {
        return None;
    }
    if knots.iter().filter(|t| *t == u).count() >= k {
        return None;
    }
    let i = (k - 1..=n)
        .rev()
        .find(|&i| knots[i] <= *u && knots[i] < knots[i + 1])?;
    let mut q = Vec::with_capacity(n + 2);
    q.extend_from_slice(&points[..=(i + 1 - k)]);
    for j in i + 2 - k..=i {
        let alpha = (u.clone() - knots[j].clone()) / (knots[j + k - 1].clone() - knots[j].clone());
        let d = points[j].clone() - points[j - 1].clone();
        q.push(points[j - 1].clone() + d * alpha);
    }
    q.extend_from_slice(&points[i..]);
    let mut t = Vec::with_capacity(knots.len() + 1);
    t.extend_from_slice(&knots[..=i]);
    t.push(u.clone());
    t.extend_from_slice(&knots[i + 1..]);
    Some((t, q))
}

impl<T: Real, const D: usize> BSpline<T, D> {
    /// Inserts the knot `u` once by Boehm's rule (module doc, seed 003
    /// eq 3–6); the curve is unchanged. Errors (the curve untouched): `u`
    /// outside the domain, not finite, or already of multiplicity `k`.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::bspline::{de_boor::BSpline, knots::KnotVector};
    /// let q = vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 2.0), Vector2::new(3.0, 2.0), Vector2::new(4.0, 0.0)];
    /// let c = BSpline::new(3, q, KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap()).unwrap();
    /// let r = c.insert_knot(&0.25).unwrap();
    /// assert_eq!(r.points().len(), 5);
    /// assert!((r.eval(&0.7).unwrap() - c.eval(&0.7).unwrap()).norm() < 1e-15);
    /// ```
    ///
    /// ```
    /// // In MPFR: inserting 1/3 keeps the curve to 160-bit rounding.
    /// use nalgebra::Vector2;
    /// use splinelab::bspline::{de_boor::BSpline, knots::KnotVector};
    /// use splinelab::scalar::{Mp, Real};
    /// type M = Mp<160>;
    /// let v = |x: i64, y: i64| Vector2::new(M::from_int(x), M::from_int(y));
    /// let knots = KnotVector::new([0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0].map(M::from_f64_exact).to_vec()).unwrap();
    /// let c = BSpline::new(3, vec![v(0, 0), v(1, 2), v(3, 2), v(4, 0)], knots).unwrap();
    /// let r = c.insert_knot(&(M::from_int(1) / M::from_int(3))).unwrap();
    /// let t = M::from_f64_exact(0.7);
    /// assert!((r.eval(&t).unwrap() - c.eval(&t).unwrap()).norm().to_f64() < 1e-45);
    /// ```
    pub fn insert_knot(&self, u: &T) -> Result<Self, InsertionError> {
        let mut c = self.clone();
        c.insert_knot_in_place(u)?;
        Ok(c)
    }

    /// Inserts the knot `u` once by Boehm's rule, in place: the same points
    /// and knots as [`BSpline::insert_knot`], bit for bit.
    ///
    /// **Cost**: `O(log m)` for the span and the multiplicity (binary
    /// searches of the sorted knots), `k − 1` affine combinations, and one
    /// move of the points and one of the knots after the span (`Vec::insert`;
    /// amortised `O(1)` reallocation, none after [`BSpline::reserve`]). No
    /// re-validation: the new knot lands in sorted position and the new
    /// points are convex combinations of finite ones.
    /// **Errors** (the curve untouched): as [`BSpline::insert_knot`].
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::bspline::{de_boor::BSpline, knots::KnotVector};
    /// let q = vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 2.0), Vector2::new(3.0, 2.0), Vector2::new(4.0, 0.0)];
    /// let c = BSpline::new(3, q, KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap()).unwrap();
    /// let mut r = c.clone();
    /// r.insert_knot_in_place(&0.25).unwrap();
    /// assert_eq!(r.knots().as_slice(), &[0.0, 0.0, 0.0, 0.25, 0.5, 1.0, 1.0, 1.0]);
    /// assert!((r.eval(&0.7).unwrap() - c.eval(&0.7).unwrap()).norm() < 1e-15);
    /// ```
    pub fn insert_knot_in_place(&mut self, u: &T) -> Result<(), InsertionError> {
        let (k, n) = (self.order(), self.points().len() - 1);
        let (lo, hi) = self.domain();
        if !u.is_finite() || *u < lo || *u > hi {
            return Err(InsertionError::OutOfDomain {
                u: u.to_f64(),
                lo: lo.to_f64(),
                hi: hi.to_f64(),
            });
        }
        if self.knots().multiplicity(u) >= k {
            return Err(InsertionError::FullMultiplicity {
                u: u.to_f64(),
                order: k,
            });
        }
        // The validated curve has a non-empty domain containing u.
        let i = self
            .knots()
            .span(k - 1, n, u)
            .ok_or(BSplineError::EmptyDomain)?;
        let t = self.knots().as_slice();
        let fresh: Vec<SVector<T, D>> = (i + 2 - k..=i)
            .map(|j| {
                let alpha = (u.clone() - &t[j]) / (t[j + k - 1].clone() - &t[j]);
                let q = self.points();
                &q[j - 1] + (&q[j] - &q[j - 1]) * alpha
            })
            .collect();
        let (points, knots) = self.parts_mut();
        // Q_i moves one place right; Q_{i+2−k..=i} become the new points.
        points.insert(i, points[i].clone());
        points[i + 2 - k..=i].clone_from_slice(&fresh);
        knots.insert_sorted(i + 1, u.clone());
        Ok(())
    }

    /// Reserves room for `additional` more control points and knots, so that
    /// that many [`BSpline::insert_knot_in_place`] calls never reallocate.
    pub fn reserve(&mut self, additional: usize) {
        let (points, knots) = self.parts_mut();
        points.reserve(additional);
        knots.reserve(additional);
    }

    /// Inserts `u` `times` times (multiple insertion: repeated Boehm steps,
    /// `O(times·(n + k))`). Fails, leaving `self` untouched, if the
    /// multiplicity would exceed `k`.
    pub fn insert_knot_times(&self, u: &T, times: usize) -> Result<Self, InsertionError> {
        let mut c = self.clone();
        c.reserve(times);
        for _ in 0..times {
            c.insert_knot_in_place(u)?;
        }
        Ok(c)
    }

    /// Global refinement (seed 003 §4, "increase the control points
    /// everywhere"): inserts the midpoint of every non-empty knot span of the
    /// domain. `s` spans give `s` new points. **Cost** `O(s·(n + k))` by
    /// successive in-place insertions (each moves the tail once).
    /// **Accuracy**: as [`insert_raw`] per insertion; the curve is kept
    /// (`verify/tests/it/knot_insertion.rs::global_refinement_doubles_spans_and_keeps_the_curve`).
    pub fn refine_midpoints(&self) -> Result<Self, InsertionError> {
        let (k, n) = (self.order(), self.points().len() - 1);
        let t = self.knots().as_slice();
        let mids: Vec<T> = (k - 1..=n)
            .filter(|&i| t[i] < t[i + 1])
            .map(|i| (t[i].clone() + &t[i + 1]).scale_by_pow2(-1))
            .collect();
        let mut c = self.clone();
        c.reserve(mids.len());
        for m in &mids {
            c.insert_knot_in_place(m)?;
        }
        Ok(c)
    }
}
