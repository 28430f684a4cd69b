//! Batch evaluation of a [`BSpline`] into a caller's buffer — the operation
//! `scipy.interpolate.BSpline.__call__` performs on an array of parameters.
//!
//! **Method**: every parameter is checked first (finite, inside the domain),
//! so a bad one is a typed error and nothing is half-written; then each point
//! is de Boor's triangle of [`BSpline::eval`] on one reused window buffer.
//! The span is found in `O(1)` when the parameter lies in the previous
//! point's span or the next one (sorted or slowly varying input), and by
//! binary search otherwise. The values are the same bits as
//! [`BSpline::eval`]: the same span and the same operations.
//!
//! **Cost**: `O(m + m·k²·D)` for `m` parameters (plus `O(log n)` per span
//! change by search), no allocation beyond one `k`-point window.

use super::de_boor::{BSpline, BSplineError, de_boor_in_place};
use crate::scalar::Real;
use nalgebra::SVector;

impl<T: Real, const D: usize> BSpline<T, D> {
    /// `out[j] = P(ts[j])` for every `j` (module doc).
    ///
    /// **Errors** (`out` untouched): `out.len() ≠ ts.len()`, or the first
    /// parameter that is not finite or lies outside the domain.
    ///
    /// **Method**: per parameter, span search then de Boor's algorithm, as
    /// [`BSpline::eval`](super::de_boor::BSpline::eval). **Accuracy**: equal bit
    /// for bit to pointwise evaluation
    /// (`verify/tests/it/curves_bspline.rs::batch_evaluation_equals_pointwise_eval`).
    /// **Source**: de Boor, *A Practical Guide to Splines*; seed 003 eqs 1–2.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::bspline::{de_boor::BSpline, knots::KnotVector};
    /// let q = vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 2.0), Vector2::new(3.0, 2.0), Vector2::new(4.0, 0.0)];
    /// let c = BSpline::new(3, q, KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap()).unwrap();
    /// let ts = [0.0, 0.3, 0.5, 0.9, 1.0];
    /// let mut out = vec![Vector2::zeros(); ts.len()];
    /// c.eval_into(&ts, &mut out).unwrap();
    /// for (t, p) in ts.iter().zip(&out) {
    ///     assert_eq!(*p, c.eval(t).unwrap());
    /// }
    /// assert!(c.eval_into(&[0.5, 2.0], &mut out[..2]).is_err());
    /// ```
    pub fn eval_into(&self, ts: &[T], out: &mut [SVector<T, D>]) -> Result<(), BSplineError> {
        if out.len() != ts.len() {
            return Err(BSplineError::OutputLength {
                params: ts.len(),
                got: out.len(),
            });
        }
        let (lo, hi) = self.domain();
        if let Some(t) = ts.iter().find(|t| !t.is_finite() || **t < lo || **t > hi) {
            // The same error `eval` gives for it.
            return Err(self.span(t).expect_err("outside the domain"));
        }
        let k = self.order();
        let knots = self.knots().as_slice();
        let points = self.points();
        let last = points.len() - 1;
        let mut window = points[..k].to_vec();
        let mut span = k - 1;
        for (t, o) in ts.iter().zip(out.iter_mut()) {
            span = self.span_near(span, last, t)?;
            window.clone_from_slice(&points[span + 1 - k..=span]);
            de_boor_in_place(k, knots, &mut window, span, t);
            *o = window[k - 1].clone();
        }
        Ok(())
    }

    /// The span of `t` (inside the domain), tried first at `hint` and
    /// `hint + 1`, the same as [`BSpline::span`] returns.
    #[inline]
    fn span_near(&self, hint: usize, last: usize, t: &T) -> Result<usize, BSplineError> {
        let knots = self.knots().as_slice();
        for s in [hint, hint + 1] {
            // Interior of span s, or the right end of the domain in the last span.
            if s <= last
                && knots[s] <= *t
                && (*t < knots[s + 1] || (s == last && *t == knots[s + 1]))
                && knots[s] < knots[s + 1]
            {
                return Ok(s);
            }
        }
        self.span(t)
    }
}
