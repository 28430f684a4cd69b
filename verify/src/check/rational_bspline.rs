//! Exact rational evaluation of a B-spline in scipy's `BSpline(t, c, k,
//! extrapolate)` convention: the ground truth of `bspline-eval` and
//! `knot-insertion`, independent of core's de Boor.

use super::CheckError;
use rug::Rational;

/// A scalar B-spline with exact rational knots and coefficients.
#[derive(Debug, Clone, PartialEq)]
pub struct RationalBSpline {
    t: Vec<Rational>,
    c: Vec<Rational>,
    k: usize,
}

/// Largest degree accepted.
pub const MAX_DEGREE: usize = 30;

impl RationalBSpline {
    /// The spline with the exact values of the f64 inputs. Refused: a degree
    /// above [`MAX_DEGREE`], non-finite or decreasing knots, `len(c) ≠
    /// len(t) − k − 1`, fewer than `k + 1` coefficients, an empty base
    /// interval `t[k] = t[n]`.
    pub fn from_f64(t: &[f64], c: &[f64], k: usize) -> Result<Self, CheckError> {
        if k > MAX_DEGREE {
            return Err(CheckError::DegreeOutOfRange {
                degree: k,
                min: 0,
                max: MAX_DEGREE,
            });
        }
        super::require_finite("knots", t)?;
        super::require_finite("coefficients", c)?;
        if t.len() < 2 * k + 2 {
            return Err(CheckError::Invalid(format!(
                "{} knots are too few for degree {k} (need ≥ {})",
                t.len(),
                2 * k + 2
            )));
        }
        super::require_len("coefficients (len(t) − k − 1)", t.len() - k - 1, c.len())?;
        if let Some(i) = t.windows(2).position(|w| w[1] < w[0]) {
            return Err(CheckError::Invalid(format!(
                "knots decrease at index {}",
                i + 1
            )));
        }
        let n = c.len();
        if t[k] >= t[n] {
            return Err(CheckError::Invalid(format!(
                "empty base interval t[{k}] = t[{n}]"
            )));
        }
        let q = |x: &f64| Rational::from_f64(*x).expect("finite");
        Ok(RationalBSpline {
            t: t.iter().map(q).collect(),
            c: c.iter().map(q).collect(),
            k,
        })
    }

    /// Degree `k`.
    pub fn degree(&self) -> usize {
        self.k
    }

    /// The knots.
    pub fn knots(&self) -> &[Rational] {
        &self.t
    }

    /// The coefficients.
    pub fn coefficients(&self) -> &[Rational] {
        &self.c
    }

    /// The base interval `[t[k], t[n]]`.
    pub fn base_interval(&self) -> (Rational, Rational) {
        (self.t[self.k].clone(), self.t[self.c.len()].clone())
    }

    /// `true` when `x` lies in the base interval.
    pub fn in_base(&self, x: &Rational) -> bool {
        let (a, b) = self.base_interval();
        *x >= a && *x <= b
    }

    /// scipy's interval: the largest `l ∈ [k, n − 1]` with `t[l] ≤ x`
    /// (`k` when none), so the last piece is closed on the right and
    /// extrapolation continues the end pieces. It can be empty
    /// (`t[l] = t[l+1]`, a knot of multiplicity above `k + 1` at the right
    /// end): scipy evaluates there all the same, and so does [`Self::eval`].
    fn interval(&self, x: &Rational) -> usize {
        let n = self.c.len();
        let l = self.t[..n].partition_point(|ti| ti <= x);
        l.saturating_sub(1).clamp(self.k, n - 1)
    }

    /// The value at `x` in exact arithmetic, by the Cox–de Boor recursion
    /// for the `k + 1` basis functions of scipy's interval `l`, with scipy's
    /// convention that a term over a zero-length knot span is 0 (so the
    /// value is scipy's own definition, including at an empty interval).
    /// `O(k²)` rational operations; extrapolates from the end pieces.
    pub fn eval(&self, x: &Rational) -> Rational {
        let (l, h) = self.basis(x);
        h.iter()
            .zip(&self.c[l - self.k..=l])
            .fold(Rational::new(), |s, (b, c)| s + Rational::from(b * c))
    }

    /// `Σ_j |c_j| |B_j(x)|` exactly (the scale of a stable evaluation's
    /// error, [`stable_bound`](super::stable_bound)); `O(k²)`.
    pub fn abs_eval(&self, x: &Rational) -> Rational {
        let (l, h) = self.basis(x);
        h.iter()
            .zip(&self.c[l - self.k..=l])
            .fold(Rational::new(), |s, (b, c)| s + Rational::from(b * c).abs())
    }

    /// scipy's interval `l` at `x` and the `k + 1` basis values
    /// `B_{l−k..=l}(x)` there (the recursion of [`Self::eval`]).
    fn basis(&self, x: &Rational) -> (usize, Vec<Rational>) {
        let (k, l) = (self.k, self.interval(x));
        let mut h = vec![Rational::from(1)];
        for j in 1..=k {
            let prev = std::mem::replace(&mut h, vec![Rational::new(); j + 1]);
            for n in 1..=j {
                let (xb, xa) = (&self.t[l + n], &self.t[l + n - j]);
                if xb == xa {
                    continue;
                }
                let w: Rational = &prev[n - 1] / Rational::from(xb - xa);
                h[n - 1] += &w * Rational::from(xb - x);
                h[n] = w * Rational::from(x - xa);
            }
        }
        (l, h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamped_quadratic_is_the_bernstein_form_and_extrapolates() {
        // Clamped quadratic on [0, 1]: c0 (1−x)² + 2 c1 x(1−x) + c2 x².
        let s = RationalBSpline::from_f64(&[0., 0., 0., 1., 1., 1.], &[1., 3., 2.], 2).unwrap();
        let x = Rational::from((1, 3));
        let want = Rational::from((4, 9)) + Rational::from((2 * 3 * 2, 9)) + Rational::from((2, 9));
        assert_eq!(s.eval(&x), want);
        // Outside: the same polynomial continued, at x = 2: 1 − 12 + 8.
        assert_eq!(s.eval(&Rational::from(2)), Rational::from(-3));
        assert!(RationalBSpline::from_f64(&[0., 1., 0.5, 1.], &[1., 1.], 1).is_err());
    }
}
