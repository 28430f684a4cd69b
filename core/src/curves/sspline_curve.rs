//! S-spline curves (seed 000 eq 20–23) held as uniform B-spline curves with
//! control points `D = c ⋆ P`, and their local update.
//!
//! `Q(u) = Σ_i P_i S_n(u − i)` with `S_n(x) = Σ_{|j|≤n} c_j β(x − j)` (eq 10, 20)
//! is the B-spline (or Beta2-spline) curve `Q(u) = Σ_k D_k β(u − k)` with
//!
//! `D_k = Σ_{j=−n}^{n} c_{|j|} P_{k−j}` (truncated discrete convolution),
//!
//! the data extended beyond the ends by the [`EndCondition`]. Eq 20 stops the
//! extension at `−n` and `ν − 1 + n`; here it is applied to every index the
//! basis reaches, which is the same rule without the extra cut.
//!
//! Moving one interior data point changes exactly the `2n + 1` control points
//! `D_{k−n..=k+n}` — the paper's local-modification claim.

use crate::bernstein::affine_step::AffineStep;
use crate::bspline::de_boor::BSpline;
use crate::bspline::knots::KnotVector;
use crate::param_curve::{OutOfDomain, ParamCurve, widen};
use crate::scalar::Real;
use crate::sspline::end_conditions::{EndCondition, EndRule};
use crate::sspline::{SplineFamily, TruncatedBasis};
use crate::validation::{at_least, finite_point_at, finite_points, finite_vector};
use nalgebra::SVector;

use super::CurveError;

/// One direction of an S-spline: basis family, coefficients `c_0..c_n`, end
/// rule, data count, and the range of control indices it needs.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Axis<T> {
    pub family: SplineFamily,
    pub c: Vec<T>,
    pub rule: EndRule,
    pub len: usize,
    /// Index `k` of the first control point.
    pub first: i64,
    /// Number of control points.
    pub count: usize,
}

impl<T: Real> Axis<T> {
    /// One direction: validates `len ≥ 2` and the order, then computes
    /// `c_0..c_n` by [`TruncatedBasis::new`] (production coefficients, ≤ 1 ulp
    /// each; `verify/tests/it/sspline_coefficients.rs`) and the control index
    /// range (integers, exact). **Source**: seed 000 eqs 10 and 20–23.
    pub fn new(
        family: &SplineFamily,
        n: usize,
        rule: EndRule,
        len: usize,
    ) -> Result<Self, CurveError> {
        at_least("an S-spline curve", 2, len)?;
        let m = family.spline_order();
        if m as usize > len {
            return Err(CurveError::OrderTooHigh {
                order: m,
                points: len,
            });
        }
        let c = TruncatedBasis::<T>::new(family, n)?.coefficients().to_vec();
        let h = m.div_ceil(2) as i64;
        let last = Self::last_knot(rule, len);
        Ok(Axis {
            family: family.clone(),
            c,
            rule,
            len,
            first: 1 - h,
            count: (last + 2 * h - 1) as usize,
        })
    }

    fn last_knot(rule: EndRule, len: usize) -> i64 {
        match rule {
            EndRule::Periodic => len as i64,
            _ => len as i64 - 1,
        }
    }

    pub fn half_width(&self) -> usize {
        self.c.len() - 1
    }

    /// Parameter domain `[0, ν − 1]` (`[0, ν]` periodic).
    pub fn domain(&self) -> (f64, f64) {
        (0.0, Self::last_knot(self.rule, self.len) as f64)
    }

    pub fn check_param(&self, u: &T) -> Result<(), CurveError> {
        let (lo, hi) = self.domain();
        let uf = u.to_f64();
        if !u.is_finite() || *u < T::zero() || *u > T::from_int(hi as i64) {
            return Err(CurveError::OutOfDomain(OutOfDomain { t: uf, lo, hi }));
        }
        Ok(())
    }

    /// Control positions `(slot, β(u − k))` with a non-zero-able basis value.
    /// **Method**: the family's basis window at `u` (the B-spline recurrence,
    /// error `O(m u)` per value, exact at rationals:
    /// `bspline_uniform.rs::tests::recursion_matches_truncated_powers_exactly_at_rationals`),
    /// clipped to the stored slots. **Source**: seed 000 eqs 7 and 31.
    pub fn window(&self, u: &T) -> Vec<(usize, T)> {
        let w = self.family.basis_window(u);
        w.values
            .into_iter()
            .enumerate()
            .filter_map(|(l, b)| {
                let slot = w.first + l as i64 - self.first;
                (0..self.count as i64)
                    .contains(&slot)
                    .then_some((slot as usize, b))
            })
            .collect()
    }

    /// Control slots whose value depends on data point `k`, as sorted,
    /// merged, inclusive ranges; with each preimage `i` of `k`.
    /// **Method**: the preimages of `k` under the end rule's fold, each
    /// widened by `±n`; integer arithmetic, exact (checked by
    /// `verify/tests/it/sspline_curve.rs::interior_edit_touches_2n_plus_1_points`).
    /// **Source**: seed 000 §3 (local update).
    pub fn affected(&self, k: usize) -> (Vec<i64>, Vec<(usize, usize)>) {
        let n = self.half_width() as i64;
        let (lo, hi) = (self.first - n, self.first + self.count as i64 - 1 + n);
        let pre = self.rule.preimages(k, self.len, lo, hi);
        let mut ranges: Vec<(usize, usize)> = Vec::new();
        for &i in &pre {
            let a = (i - n - self.first).max(0) as usize;
            let b = (i + n - self.first).min(self.count as i64 - 1);
            if b < a as i64 {
                continue;
            }
            let b = b as usize;
            match ranges.last_mut() {
                Some(last) if a <= last.1 + 1 => last.1 = last.1.max(b),
                _ => ranges.push((a, b)),
            }
        }
        (pre, ranges)
    }

    /// Uniform knots of the B-spline view: `β(x − k)` has knots
    /// `k − m/2 + 0..=m`, exact in binary.
    pub fn knots(&self) -> Result<KnotVector<T>, CurveError> {
        let m = self.family.spline_order() as i64;
        let start = 2 * self.first - m;
        let t = (0..self.count as i64 + m)
            .map(|j| T::from_int(start + 2 * j).scale_by_pow2(-1))
            .collect();
        Ok(KnotVector::new(t).map_err(crate::bspline::de_boor::BSplineError::from)?)
    }
}

/// `D_slot = Σ_{j=−n}^{n} c_{|j|} get(k − j)` with `k = first + slot`: the one
/// summation order used by full builds and local updates alike (so that they
/// agree bitwise).
pub(crate) fn convolve_at<T: Real, V>(axis: &Axis<T>, slot: usize, get: impl Fn(i64) -> V) -> V
where
    V: AffineStep<T>,
{
    let n = axis.half_width() as i64;
    let k = axis.first + slot as i64;
    let mut acc = get(k - n);
    acc.scale_in_place(&axis.c[n as usize]);
    for j in (-n..n).rev() {
        // `get` hands over an owned point: scale it in place, add it.
        let mut term = get(k - j);
        term.scale_in_place(&axis.c[j.unsigned_abs() as usize]);
        acc.accumulate(&term);
    }
    acc
}

/// An S-spline curve through `P_0..P_{ν−1}` in `D` dimensions (eq 20).
#[derive(Debug, Clone, PartialEq)]
pub struct SsplineCurve<T: Real, const D: usize> {
    axis: Axis<T>,
    end: EndCondition<T, D>,
    data: Vec<SVector<T, D>>,
    control: Vec<SVector<T, D>>,
}

impl<T: Real, const D: usize> SsplineCurve<T, D> {
    /// Builds the curve of `family` with half-width `n ≥ 1` through `data`.
    ///
    /// **Method**: `c_0..c_n` by [`TruncatedBasis::new`] (≤ 1 ulp each), then
    /// `D_k = Σ_{|j|≤n} c_{|j|} P_{k−j}` for the `ν + 2⌈m/2⌉ − 2` control points
    /// the domain needs (one more when periodic). **Cost** `O(ν (2n + 1) D)`
    /// after the coefficients. **Error**: each `D_k` has the error of a dot
    /// product of length `2n + 1`, `≤ γ_{2n+1} Σ_j |c_j| |P_{k−j}|`; the curve
    /// differs from the untruncated S-spline by at most the uniform
    /// truncation error of `n` times `max |P|` (see [`crate::sspline::truncation`]).
    /// Measured: the curve interpolates its data and equals the de Boor
    /// evaluation of its B-spline view
    /// (`verify/tests/it/sspline_curve.rs::interpolates_and_matches_de_boor`).
    /// **Source**: seed 000 eqs 10 and 20–23.
    ///
    /// Errors: fewer than 2 points, order `> ν`, non-finite data or tangents,
    /// `n = 0`; the caller's data are only read.
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::curves::sspline_curve::SsplineCurve;
    /// use splinelab::sspline::{SplineFamily, end_conditions::EndCondition};
    /// let p: Vec<Vector2<f64>> = (0..8).map(|i| Vector2::new(i as f64, (i * i % 5) as f64)).collect();
    /// let q = SsplineCurve::new(&SplineFamily::Order(4), 20, &p, EndCondition::Free).unwrap();
    /// assert!((q.eval(&3.0).unwrap() - p[3]).norm() < 1e-9);
    /// ```
    pub fn new(
        family: &SplineFamily,
        n: usize,
        data: &[SVector<T, D>],
        end: EndCondition<T, D>,
    ) -> Result<Self, CurveError> {
        let axis = Axis::new(family, n, end.rule(), data.len())?;
        finite_points("data point", data)?;
        if let EndCondition::Tangents { start, end } = &end {
            finite_vector("the start tangent", start)?;
            finite_vector("the end tangent", end)?;
        }
        let mut curve = SsplineCurve {
            axis,
            end,
            data: data.to_vec(),
            control: Vec::new(),
        };
        curve.control = (0..curve.axis.count)
            .map(|s| curve.control_point(s))
            .collect();
        Ok(curve)
    }

    fn control_point(&self, slot: usize) -> SVector<T, D> {
        convolve_at(&self.axis, slot, |i| self.end.extended(&self.data, i))
    }

    /// The data points.
    pub fn data(&self) -> &[SVector<T, D>] {
        &self.data
    }

    /// The control points `D_k`, `k = first_index()..`.
    pub fn control_points(&self) -> &[SVector<T, D>] {
        &self.control
    }

    /// Index `k` of the first control point.
    pub fn first_index(&self) -> i64 {
        self.axis.first
    }

    /// The truncation half-width `n`.
    pub fn half_width(&self) -> usize {
        self.axis.half_width()
    }

    /// The coefficients `c_0..c_n`.
    pub fn coefficients(&self) -> &[T] {
        &self.axis.c
    }

    /// The parameter domain: `[0, ν − 1]`, or `[0, ν]` when periodic.
    pub fn domain(&self) -> (f64, f64) {
        self.axis.domain()
    }

    /// `Q(u) = Σ_k D_k β(u − k)`: one basis window (`O(m²)`, de Boor–Cox or
    /// eq 36) and `m` axpys. Error `≤ γ_{3m} Σ_k |D_k| β(u − k)`.
    ///
    /// ```
    /// // In MPFR at half-width 60: the cubic S-spline curve passes through its data
    /// // to within its truncation tail (|√3 − 2|^61 < 1e-34).
    /// use nalgebra::Vector2;
    /// use splinelab::curves::sspline_curve::SsplineCurve;
    /// use splinelab::scalar::{Mp, Real};
    /// use splinelab::sspline::{SplineFamily, end_conditions::EndCondition};
    /// type M = Mp<160>;
    /// let p: Vec<Vector2<M>> = (0..8).map(|i| Vector2::new(M::from_int(i), M::from_int(i * i % 5))).collect();
    /// let q = SsplineCurve::new(&SplineFamily::Order(4), 60, &p, EndCondition::Free).unwrap();
    /// for i in 0..8 {
    ///     assert!((q.eval(&M::from_int(i)).unwrap() - p[i as usize].clone()).norm().to_f64() < 1e-30);
    /// }
    /// ```
    pub fn eval(&self, u: &T) -> Result<SVector<T, D>, CurveError> {
        self.axis.check_param(u)?;
        Ok(self
            .axis
            .window(u)
            .into_iter()
            .fold(SVector::zeros(), |acc, (s, b)| acc + &self.control[s] * b))
    }

    /// The curve as a [`BSpline`] of order `m` on the uniform knots
    /// `k − m/2 + ℤ` (B-spline families only): evaluation and derivatives are
    /// then de Boor's. Its domain contains `[0, ν − 1]`.
    pub fn to_bspline(&self) -> Result<BSpline<T, D>, CurveError> {
        match self.axis.family {
            SplineFamily::Order(m) => Ok(BSpline::new(
                m as usize,
                self.control.clone(),
                self.axis.knots()?,
            )?),
            ref f => Err(CurveError::NotBSpline(f.to_string())),
        }
    }

    /// Moves data point `k` to `p` and recomputes only the control points
    /// that depend on it — `D_{k−n..=k+n}` for an interior point, more near a
    /// free or reflected end that owns several extended indices.
    ///
    /// **Cost** `(2n + 1)²` multiply-adds per coordinate for an interior
    /// point (each affected `D_l` is recomputed as a sum of `2n + 1` terms),
    /// independent of `ν`. **Result**: bitwise identical to a full rebuild
    /// with the moved point (same summation order). Returns the number of
    /// control points recomputed. On error nothing is changed.
    /// Tested in `verify/tests/it/sspline_curve.rs::local_edit_equals_rebuild_f64`.
    /// **Source**: seed 000 §3 (local update).
    pub fn move_point(&mut self, k: usize, p: SVector<T, D>) -> Result<usize, CurveError> {
        self.check_edit(k, &p)?;
        self.data[k] = p;
        let (_, ranges) = self.axis.affected(k);
        let mut count = 0;
        for (a, b) in ranges {
            for s in a..=b {
                self.control[s] = self.control_point(s);
            }
            count += b - a + 1;
        }
        Ok(count)
    }

    /// Moves data point `k` to `p` by adding `c_{|l−i|} (p − P_k)` to each
    /// affected `D_l` (`i` every extended index owned by `k`) — the
    /// paper's update. **Cost** `2n + 1` axpys for an interior point.
    /// **Result**: equal to a full rebuild up to rounding, `≤ (2n + 2) u
    /// Σ|c| max|P|` per edit (errors accumulate over successive edits).
    pub fn shift_point(&mut self, k: usize, p: SVector<T, D>) -> Result<usize, CurveError> {
        self.check_edit(k, &p)?;
        let delta = &p - &self.data[k];
        self.data[k] = p;
        let (pre, _) = self.axis.affected(k);
        let (n, last) = (self.half_width() as i64, self.axis.count as i64 - 1);
        let mut count = 0;
        for i in pre {
            let s0 = i - self.axis.first;
            for s in (s0 - n).max(0)..=(s0 + n).min(last) {
                let c = &self.axis.c[(s - s0).unsigned_abs() as usize];
                self.control[s as usize] += &delta * c.clone();
                count += 1;
            }
        }
        Ok(count)
    }

    fn check_edit(&self, k: usize, p: &SVector<T, D>) -> Result<(), CurveError> {
        if k >= self.data.len() {
            return Err(CurveError::IndexOutOfRange {
                index: k,
                len: self.data.len(),
            });
        }
        Ok(finite_point_at("data point", k, p)?)
    }
}

impl<T: Real, const D: usize> ParamCurve<T, D> for SsplineCurve<T, D> {
    type Error = CurveError;
    fn domain(&self) -> (T, T) {
        widen(SsplineCurve::domain(self))
    }
    fn eval(&self, t: &T) -> Result<SVector<T, D>, CurveError> {
        SsplineCurve::eval(self, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bernstein::affine_step::tests::values;
    use crate::scalar::Mp;
    use nalgebra::Vector3;

    /// `convolve_at` equals the cloning form it replaced
    /// (`acc = acc + P·c`, same order), bit for bit, in f64 and MPFR.
    fn convolution_same_as_cloning_form<T: Real>() {
        let v: Vec<T> = values(420).into_iter().map(T::from_f64_exact).collect();
        let pts: Vec<Vector3<T>> = v
            .chunks_exact(3)
            .map(|w| Vector3::new(w[0].clone(), w[1].clone(), w[2].clone()))
            .collect();
        let get = |i: i64| pts[i.rem_euclid(pts.len() as i64) as usize].clone();
        for (m, n) in [(4, 3), (6, 11)] {
            let family = SplineFamily::Order(m);
            let mut axis = Axis::<T>::new(&family, n, EndRule::Periodic, pts.len()).unwrap();
            // Full-precision coefficients, so that every product rounds.
            axis.c = v[..=n].to_vec();
            for slot in 0..axis.count {
                let k = axis.first + slot as i64;
                let mut old = get(k - n as i64) * axis.c[n].clone();
                for j in (-(n as i64)..n as i64).rev() {
                    // The old owned-operand expression, spelled as it was.
                    #[allow(clippy::assign_op_pattern)]
                    {
                        old = old + get(k - j) * axis.c[j.unsigned_abs() as usize].clone();
                    }
                }
                assert_eq!(convolve_at(&axis, slot, get), old, "m={m} slot={slot}");
            }
        }
    }

    #[test]
    fn in_place_convolution_is_bitwise_the_cloning_form() {
        convolution_same_as_cloning_form::<f64>();
        convolution_same_as_cloning_form::<Mp<24>>();
        convolution_same_as_cloning_form::<Mp<113>>();
    }
}
