//! Cubic Catmull–Rom splines by the three-level interpolation pyramid of
//! Barry and Goldman (seed 002, "3次Catmull-Romスプライン" steps 1–3), with
//! uniform, centripetal and chordal knot spacing.

use super::{CurveError, check_points};
use crate::param_curve::{OutOfDomain, ParamCurve, ParamCurveDeriv};
use crate::scalar::Real;
use crate::validation::{at_least, finite};
use nalgebra::SVector;

/// Knot spacing `t_k = t_{k−1} + |P_k − P_{k−1}|^α` (seed 002).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Spacing {
    /// `α = 0`: `t_k = t_{k−1} + 1`.
    Uniform,
    /// `α = ½`: `t_k = t_{k−1} + √|P_k − P_{k−1}|`.
    Centripetal,
    /// `α = 1`: `t_k = t_{k−1} + |P_k − P_{k−1}|`.
    Chordal,
}

impl Spacing {
    /// All three, in order of `α`.
    pub const ALL: [Spacing; 3] = [Spacing::Uniform, Spacing::Centripetal, Spacing::Chordal];

    /// The exponent `α` as a display string.
    pub fn alpha(self) -> &'static str {
        match self {
            Spacing::Uniform => "0",
            Spacing::Centripetal => "1/2",
            Spacing::Chordal => "1",
        }
    }

    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Spacing::Uniform => "uniform",
            Spacing::Centripetal => "centripetal",
            Spacing::Chordal => "chordal",
        }
    }

    /// The knot interval `|d|^α` for a chord of length `len ≥ 0`
    /// (exactly 1 for uniform spacing, whatever `len`).
    fn interval<T: Real>(self, len: T) -> T {
        match self {
            Spacing::Uniform => T::one(),
            Spacing::Centripetal => len.sqrt(),
            Spacing::Chordal => len,
        }
    }
}

/// A cubic Catmull–Rom spline through points `P_0, …, P_{N−1}`.
///
/// - **Open** (`N ≥ 4`): segment `k`, `1 ≤ k ≤ N − 3`, runs from `P_k` to
///   `P_{k+1}` on `[t_k, t_{k+1}]` and is built from `P_{k−1}, …, P_{k+2}`
///   (seed 002's definition); `P_0` and `P_{N−1}` only shape the end tangents.
/// - **Closed** (`N ≥ 3`): indices are taken mod `N`, `N` segments, the
///   last from `P_{N−1}` back to `P_0`.
///
/// **Zero chords**: with centripetal or chordal spacing two equal consecutive
/// points give a zero knot interval and the pyramid would divide by zero;
/// the constructor returns [`CurveError::CoincidentPoints`]. Uniform spacing
/// has interval 1 regardless and accepts them (the segment between two equal
/// points is then a small loop or a point, as the cubic dictates).
#[derive(Clone, Debug, PartialEq)]
pub struct CatmullRom<T: Real, const D: usize> {
    points: Vec<SVector<T, D>>,
    spacing: Spacing,
    closed: bool,
    /// Knot intervals `Δ_k = |P_{k+1} − P_k|^α`, `k = 0..N−2` (open) or
    /// `0..N−1` cyclically (closed).
    intervals: Vec<T>,
    /// Global knots at the start of each segment and the end of the last.
    knots: Vec<T>,
}

/// `X = ((b − τ) A + (τ − a) B) / (b − a)` and its derivative
/// `X' = (B − A)/(b − a) + ((b − τ) A' + (τ − a) B')/(b − a)`.
#[allow(clippy::type_complexity)]
fn lerp_d<T: Real, const D: usize>(
    a: &T,
    b: &T,
    tau: &T,
    (pa, da): (&SVector<T, D>, &SVector<T, D>),
    (pb, db): (&SVector<T, D>, &SVector<T, D>),
) -> (SVector<T, D>, SVector<T, D>) {
    let len = b.clone() - a;
    let (wa, wb) = (b.clone() - tau, tau.clone() - a);
    let x = (pa * wa.clone() + pb * wb.clone()) / len.clone();
    let dx = ((pb - pa) + da * wa + db * wb) / len;
    (x, dx)
}

impl<T: Real, const D: usize> CatmullRom<T, D> {
    /// Builds the spline; typed errors for too few points, non-finite
    /// points, zero chords under centripetal/chordal spacing and chords
    /// that overflow the precision. **Method**: knots by accumulated chord
    /// lengths `|P_{i+1} − P_i|^α` (`α = 0, ½, 1`); each rounded a few times.
    /// **Source**: seed 002; the parametrisations of Yuksel et al. (2011).
    pub fn new(
        points: Vec<SVector<T, D>>,
        spacing: Spacing,
        closed: bool,
    ) -> Result<Self, CurveError> {
        if closed {
            at_least("a closed Catmull–Rom spline", 3, points.len())?;
        } else {
            at_least("an open Catmull–Rom spline", 4, points.len())?;
        }
        check_points(&points)?;
        let n = points.len();
        let chords = if closed { n } else { n - 1 };
        let mut intervals = Vec::with_capacity(chords);
        for k in 0..chords {
            let next = (k + 1) % n;
            let len = (&points[next] - &points[k]).norm();
            let d = spacing.interval(len);
            // Finite points whose distance overflows the precision.
            finite("knot interval (chord length)", &d)?;
            if d <= T::zero() {
                return Err(CurveError::CoincidentPoints { index: k, next });
            }
            intervals.push(d);
        }
        let (first, segs) = if closed { (0, n) } else { (1, n - 3) };
        let mut knots = vec![T::zero()];
        for s in 0..segs {
            let last = knots[s].clone();
            knots.push(last + intervals[first + s].clone());
        }
        Ok(CatmullRom {
            points,
            spacing,
            closed,
            intervals,
            knots,
        })
    }

    /// The interpolated points `P_k`.
    pub fn points(&self) -> &[SVector<T, D>] {
        &self.points
    }

    /// The knot spacing.
    pub fn spacing(&self) -> Spacing {
        self.spacing
    }

    /// Whether the spline is closed.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Number of cubic segments (`N − 3` open, `N` closed).
    pub fn segment_count(&self) -> usize {
        self.knots.len() - 1
    }

    /// Global knots: segment `s` runs over `[knots[s], knots[s+1]]`, the
    /// first knot is 0. (For an open spline, segment `s` is seed 002's
    /// segment `k = s + 1`.)
    pub fn knots(&self) -> &[T] {
        &self.knots
    }

    /// Indices of the four points and the three local knot intervals of segment `s`.
    fn segment_data(&self, s: usize) -> ([usize; 4], [T; 3]) {
        let n = self.points.len();
        let k = if self.closed { s } else { s + 1 };
        let idx = [(k + n - 1) % n, k % n, (k + 1) % n, (k + 2) % n];
        let m = self.intervals.len();
        let iv = |j: usize| self.intervals[j % m].clone();
        (idx, [iv(k + m - 1), iv(k), iv(k + 1)])
    }

    /// The point and derivative (with respect to the global knot parameter)
    /// of segment `s` at local coordinate `u ∈ [0, 1]` (`t = t_s + u Δ_s`).
    ///
    /// **Method** (seed 002 steps 1–3, Barry–Goldman pyramid) on local knots
    /// `s_0 = −Δ_{k−1}, s_1 = 0, s_2 = Δ_k, s_3 = Δ_k + Δ_{k+1}` (shifted so
    /// that the segment starts at 0 and no large knot values cancel):
    /// `L_{i,i+1}` linear through `P_i, P_{i+1}`; `Q_{k}` the lerp of
    /// `L_{k−1,k}`, `L_{k,k+1}` over `[s_0, s_2]`, `Q_{k+1}` over `[s_1, s_3]`;
    /// `C` the lerp of the two over `[s_1, s_2]`. Derivatives follow each lerp
    /// by the product rule (seed 002's `x'_k(t)` formula).
    ///
    /// **Cost**: 6 lerps with derivative, `O(D)` each. **Accuracy**: every
    /// lerp weight lies in `[0, 1]` for `τ ∈ [s_1, s_2]`, except the outer
    /// weights of levels 1–2 which are bounded by the knot ratios; the error is
    /// `O(u · max|P|)` times those ratios. A typed error for `u ∉ [0, 1]` or
    /// `s` out of range.
    pub fn eval_segment(
        &self,
        s: usize,
        u: &T,
    ) -> Result<(SVector<T, D>, SVector<T, D>), CurveError> {
        if s >= self.segment_count() {
            return Err(CurveError::OutOfRange {
                name: "segment",
                value: s as f64,
                range: "0..segment_count()",
            });
        }
        if !u.is_finite() || *u < T::zero() || *u > T::one() {
            return Err(CurveError::OutOfDomain(OutOfDomain {
                t: u.to_f64(),
                lo: 0.0,
                hi: 1.0,
            }));
        }
        let (idx, [d0, d1, d2]) = self.segment_data(s);
        let p = idx.map(|i| &self.points[i]);
        let z = SVector::<T, D>::zeros();
        let k = [-d0, T::zero(), d1.clone(), d1.clone() + d2];
        let tau = u.clone() * d1;
        let l01 = lerp_d(&k[0], &k[1], &tau, (p[0], &z), (p[1], &z));
        let l12 = lerp_d(&k[1], &k[2], &tau, (p[1], &z), (p[2], &z));
        let l23 = lerp_d(&k[2], &k[3], &tau, (p[2], &z), (p[3], &z));
        let q0 = lerp_d(&k[0], &k[2], &tau, (&l01.0, &l01.1), (&l12.0, &l12.1));
        let q1 = lerp_d(&k[1], &k[3], &tau, (&l12.0, &l12.1), (&l23.0, &l23.1));
        Ok(lerp_d(&k[1], &k[2], &tau, (&q0.0, &q0.1), (&q1.0, &q1.1)))
    }

    /// Point and derivative at global parameter `t ∈ [0, knots[last]]`
    /// (the segment containing `t`; at an interior knot, the segment that
    /// starts there). See [`CatmullRom::eval_segment`].
    ///
    /// **Method**: binary search for the segment, then the segment's cubic by
    /// [`CatmullRom::eval_segment`]. **Accuracy**: the uniform segment matches the
    /// classical matrix form (`catmull_rom.rs::tests::uniform_segment_matches_the_classical_matrix_form`).
    /// **Source**: seed 002 (Catmull–Rom, uniform / centripetal / chordal).
    ///
    /// ```
    /// use nalgebra::Vector2;
    /// use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
    /// let pts = vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 1.0),
    ///                Vector2::new(2.0, 1.0), Vector2::new(3.0, 0.0)];
    /// let c = CatmullRom::new(pts, Spacing::Centripetal, false).unwrap();
    /// let end = *c.knots().last().unwrap();
    /// assert_eq!(c.eval(&0.0).unwrap().0, Vector2::new(1.0, 1.0));
    /// assert!((c.eval(&end).unwrap().0 - Vector2::new(2.0, 1.0)).norm() < 1e-15);
    /// ```
    ///
    /// ```
    /// // In MPFR with chordal spacing: the spline passes through the inner points
    /// // and the segment ends to 128-bit rounding.
    /// use nalgebra::Vector2;
    /// use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
    /// use splinelab::scalar::{Mp, Real};
    /// type M = Mp<128>;
    /// let v = |x: i64, y: i64| Vector2::new(M::from_int(x), M::from_int(y));
    /// let c = CatmullRom::new(vec![v(0, 0), v(1, 1), v(3, 1), v(4, 0), v(5, 2)], Spacing::Chordal, false).unwrap();
    /// for (k, want) in [v(1, 1), v(3, 1), v(4, 0)].iter().enumerate() {
    ///     let p = c.eval(&c.knots()[k]).unwrap().0;
    ///     assert!((p - want.clone()).norm().to_f64() < 1e-36);
    /// }
    /// ```
    pub fn eval(&self, t: &T) -> Result<(SVector<T, D>, SVector<T, D>), CurveError> {
        let hi = self.knots[self.knots.len() - 1].clone();
        if !t.is_finite() || *t < T::zero() || *t > hi {
            return Err(CurveError::OutOfDomain(OutOfDomain {
                t: t.to_f64(),
                lo: 0.0,
                hi: hi.to_f64(),
            }));
        }
        // Last knot ≤ t, clamped to the last segment.
        let s = self
            .knots
            .partition_point(|k| k <= t)
            .saturating_sub(1)
            .min(self.segment_count() - 1);
        let (a, b) = (&self.knots[s], &self.knots[s + 1]);
        let u = ((t.clone() - a) / (b.clone() - a)).clamp(T::zero(), T::one());
        self.eval_segment(s, &u)
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
    fn breakpoints(&self) -> Vec<T> {
        let k = self.knots();
        crate::param_curve::interior(k, &k[0], &k[k.len() - 1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validation::InputError;
    use nalgebra::Vector2;

    #[test]
    fn zero_chords_and_too_few_points_are_typed_errors() {
        let p = |x: f64, y: f64| Vector2::new(x, y);
        let pts = vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 0.0), p(2.0, 1.0)];
        for s in [Spacing::Centripetal, Spacing::Chordal] {
            assert_eq!(
                CatmullRom::new(pts.clone(), s, false),
                Err(CurveError::CoincidentPoints { index: 1, next: 2 })
            );
        }
        // Uniform spacing accepts the repeated point (documented treatment).
        assert!(CatmullRom::new(pts.clone(), Spacing::Uniform, false).is_ok());
        // Closed: the wrap-around chord P_{N−1} → P_0 counts too.
        let ring = vec![p(0.0, 0.0), p(1.0, 0.0), p(0.0, 0.0)];
        assert_eq!(
            CatmullRom::new(ring, Spacing::Chordal, true),
            Err(CurveError::CoincidentPoints { index: 2, next: 0 })
        );
        assert!(matches!(
            CatmullRom::new(pts[..3].to_vec(), Spacing::Uniform, false),
            Err(CurveError::Input(InputError::TooFewPoints {
                needed: 4,
                got: 3,
                ..
            }))
        ));
        let bad = vec![p(0.0, 0.0), p(f64::INFINITY, 0.0), p(1.0, 1.0)];
        assert_eq!(
            CatmullRom::new(bad, Spacing::Uniform, true),
            Err(CurveError::Input(InputError::NonFiniteAt {
                what: "point",
                index: 1
            }))
        );
    }

    #[test]
    fn uniform_segment_matches_the_classical_matrix_form() {
        // Uniform Catmull–Rom: P(u) = ½[(2P1) + (−P0 + P2)u + (2P0 − 5P1 + 4P2 − P3)u² + (−P0 + 3P1 − 3P2 + P3)u³].
        let pts = [0.0, 1.0, 4.0, 2.0].map(|y| Vector2::new(y, -y));
        let c = CatmullRom::new(pts.to_vec(), Spacing::Uniform, false).unwrap();
        let u = 0.375f64;
        let [p0, p1, p2, p3] = pts;
        let want = (p1 * 2.0
            + (p2 - p0) * u
            + (p0 * 2.0 - p1 * 5.0 + p2 * 4.0 - p3) * (u * u)
            + (p1 * 3.0 - p0 - p2 * 3.0 + p3) * (u * u * u))
            * 0.5;
        assert!((c.eval_segment(0, &u).unwrap().0 - want).norm() < 1e-15);
    }
}
