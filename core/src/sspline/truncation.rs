//! The truncated S-spline basis `S_n(x) = Σ_{|i|≤n} c_i β(x − i)` (seed 000
//! eq 10, 28) and the measures of its truncation error.
//!
//! Eq 10 writes the truncation as a restriction to `−n ≤ x ≤ n`; read
//! literally that would make the basis discontinuous, so here — as in the
//! digest — `n` bounds the *coefficient index*, and `S_n` is the spline
//! `Σ_{|i|≤n} c_i β(x − i)`, supported on `|x| < n + m/2`.
//!
//! Error measures for half-width `n`, all computed from the *tail*
//! `E(x) = S(x) − S_n(x) = Σ_{|i|>n} c_i β(x − i)` directly (no cancellation
//! against the untruncated spline), so that each has its own value right:
//!
//! - `|c_n|`, the paper's indicator;
//! - the knot interpolation error `max_j |S_n(j) − δ_{0j}| = max_j |E(j)|`;
//! - the uniform error `sup_x Σ_k |E(x − k)|`: the worst error of a curve
//!   `Σ_k P_k S(x − k)` with `|P_k| ≤ 1` (attained for `P_k = sign E(x−k)`);
//! - the analytic tail bound `2 Σ_r |κ_r| |ξ_r|^{n+1}/(1 − |ξ_r|) ≥ Σ_{|i|>n} |c_i|`.
//!
//! Always `knot ≤ uniform ≤ bound`.

use super::euler_frobenius::PoleExpansion;
use super::node_values::node_values;
use super::{CoefficientMethod, SplineFamily, SsplineError, coefficients};
use crate::scalar::Real;

/// The truncated S-spline basis `S_{0,m}` of half-width `n` (eq 10, 28).
#[derive(Debug, Clone, PartialEq)]
pub struct TruncatedBasis<T> {
    family: SplineFamily,
    c: Vec<T>,
}

impl<T: Real> TruncatedBasis<T> {
    /// The basis with the production coefficients
    /// ([`CoefficientMethod::Production`], ≤ 1 ulp) `c_0..c_n`.
    ///
    /// **Method**: [`coefficients()`] for `c_0..c_n`. **Source**: seed 000 eqs 10 and 28.
    ///
    /// ```
    /// use splinelab::sspline::{SplineFamily, TruncatedBasis};
    /// let s = TruncatedBasis::<f64>::new(&SplineFamily::Order(4), 12).unwrap();
    /// assert!((s.eval(&0.0) - 1.0).abs() < 1e-6 && s.eval(&3.0).abs() < 1e-6);
    /// ```
    ///
    /// ```
    /// // In MPFR: at half-width 40 the cubic's S_n interpolates δ_{0j} to within
    /// // its tail, ≈ 2 |κ| |ξ|^41 / (1 − |ξ|) < 1e-22 (ξ = √3 − 2).
    /// use splinelab::scalar::{Mp, Real};
    /// use splinelab::sspline::{SplineFamily, TruncatedBasis};
    /// type M = Mp<128>;
    /// let s = TruncatedBasis::<M>::new(&SplineFamily::Order(4), 40).unwrap();
    /// assert!((s.eval(&M::from_int(0)) - M::from_int(1)).to_f64().abs() < 1e-22);
    /// assert!(s.eval(&M::from_int(3)).to_f64().abs() < 1e-22);
    /// ```
    pub fn new(family: &SplineFamily, n: usize) -> Result<Self, SsplineError> {
        if n == 0 {
            return Err(SsplineError::ZeroWidth);
        }
        if n > super::MAX_HALF_WIDTH {
            return Err(SsplineError::WidthTooLarge(n));
        }
        let c = coefficients(family, n + 1, CoefficientMethod::Production)?;
        Ok(TruncatedBasis {
            family: family.clone(),
            c,
        })
    }

    /// The basis with given coefficients `c_0..c_n` (`n = c.len() − 1`).
    pub fn from_coefficients(family: &SplineFamily, c: Vec<T>) -> Result<Self, SsplineError> {
        family.validate()?;
        if c.is_empty() {
            return Err(SsplineError::ZeroCount);
        }
        Ok(TruncatedBasis {
            family: family.clone(),
            c,
        })
    }

    /// Half-width `n`.
    pub fn half_width(&self) -> usize {
        self.c.len() - 1
    }

    /// The coefficients `c_0..c_n`.
    pub fn coefficients(&self) -> &[T] {
        &self.c
    }

    /// The family of the underlying basis.
    pub fn family(&self) -> &SplineFamily {
        &self.family
    }

    /// `S_n(x)` is zero for `|x| ≥` this radius, `n + m/2`.
    pub fn support_radius(&self) -> f64 {
        self.half_width() as f64 + self.family.half_support()
    }

    /// `S_n(x) = Σ_{|i|≤n} c_{|i|} β(x − i)`: one basis window (`O(m²)`) and
    /// `m` products. Error: a sum of `m` terms of alternating sign, about
    /// `m u Σ_i |c_i| β(x − i)` absolute.
    /// **Source**: seed 000 eq 10.
    pub fn eval(&self, x: &T) -> T {
        let w = self.family.basis_window(x);
        let n = self.half_width() as i64;
        w.values
            .iter()
            .enumerate()
            .map(|(l, b)| (w.first + l as i64, b))
            .filter(|(i, _)| i.abs() <= n)
            .fold(T::zero(), |acc, (i, b)| {
                acc + self.c[i.unsigned_abs() as usize].clone() * b
            })
    }
}

/// The four truncation error measures at one half-width (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct TruncationErrors<T> {
    /// Half-width `n`.
    pub n: usize,
    /// `|c_n|`.
    pub coeff: T,
    /// `max_j |S_n(j) − δ_{0j}|`.
    pub knot: T,
    /// `sup_x Σ_k |S(x − k) − S_n(x − k)|`.
    pub uniform: T,
    /// `2 Σ_r |κ_r| |ξ_r|^{n+1}/(1 − |ξ_r|)`.
    pub bound: T,
}

/// Everything needed to measure truncation errors of one family for all
/// half-widths up to `max_n`: the pole expansion and `c_0..c_K` with
/// `K = max_n + L`, `L` chosen so that `ρ^L ≤ 2^{−64}` (`ρ` the dominant
/// pole): the neglected coefficients change each measure by less than
/// `2^{−60}` of its value.
#[derive(Debug, Clone)]
pub struct TruncationAnalysis<T> {
    family: SplineFamily,
    expansion: PoleExpansion<T>,
    c: Vec<T>,
    c64: Vec<f64>,
    nodes: Vec<T>,
    max_n: usize,
}

impl<T: Real> TruncationAnalysis<T> {
    /// Precomputes the pole expansion `c_k = Σ_r κ_r ξ_r^{|k|}` (for the
    /// tail bound) and `c_0..c_K` by [`coefficients()`] (production method).
    /// **Cost**: one pole computation and `K` coefficients. **Accuracy**:
    /// the neglected tail `k > K` changes each measure by `< 2^{−60}` of it;
    /// the knot measure agrees with direct evaluation to `1e-14` relative
    /// (`verify/tests/it/sspline_truncation.rs::knot_error_matches_direct_evaluation`).
    /// **Source**: seed 000 eqs 10 and 28 (truncation at half-width `n`).
    pub fn new(family: &SplineFamily, max_n: usize) -> Result<Self, SsplineError> {
        if max_n > super::MAX_HALF_WIDTH {
            return Err(SsplineError::WidthTooLarge(max_n));
        }
        let expansion = PoleExpansion::<T>::new(family)?;
        let rho = expansion.decay_rate().to_f64();
        let extra = if rho > 0.0 {
            (64.0 / -rho.log2()).ceil() as usize
        } else {
            0
        };
        let k = max_n + extra + family.spline_order() as usize + 1;
        let c = coefficients(family, k + 1, CoefficientMethod::Production)?;
        let c64 = c.iter().map(|x: &T| x.to_f64()).collect();
        Ok(TruncationAnalysis {
            family: family.clone(),
            expansion,
            c,
            c64,
            nodes: node_values(family)?,
            max_n,
        })
    }

    /// The largest half-width this analysis measures.
    pub fn max_n(&self) -> usize {
        self.max_n
    }

    /// The pole expansion (poles and κ).
    pub fn expansion(&self) -> &PoleExpansion<T> {
        &self.expansion
    }

    /// Tail coefficient `c_{|i|}` for `n < |i| ≤ K`, else 0.
    fn tail(&self, n: usize, i: i64) -> Option<&T> {
        let a = i.unsigned_abs() as usize;
        (a > n && a < self.c.len()).then(|| &self.c[a])
    }

    /// `|c_n|`.
    pub fn coeff_error(&self, n: usize) -> T {
        self.c[n.min(self.c.len() - 1)].clone().abs()
    }

    /// `max_{j ≥ 0} |Σ_{|i|>n} c_i β(j − i)|`. Since `E(j) = δ_{0j} − S_n(j)`
    /// vanishes for `|j| > n + p`, only `n − p < j ≤ n + p` can be non-zero:
    /// `O(p²)`.
    /// **Method**: the tail sums `Σ_{|i|>n} c_i β(j − i)` at the `2p` knots,
    /// in `T`. **Accuracy**: agrees with direct evaluation to `1e-14` relative
    /// (`verify/tests/it/sspline_truncation.rs::knot_error_matches_direct_evaluation`).
    /// **Source**: seed 000 eq 28.
    pub fn knot_error(&self, n: usize) -> T {
        let p = (self.nodes.len() / 2) as i64;
        let n_i = n as i64;
        let mut best = T::zero();
        for j in (n_i + 1 - p).max(0)..=n_i + p {
            let mut e = T::zero();
            for d in -p..=p {
                if let Some(c) = self.tail(n, j - d) {
                    e += c.clone() * self.nodes[(p + d) as usize].clone();
                }
            }
            let e = e.abs();
            if e > best {
                best = e;
            }
        }
        best
    }

    /// `F(x) = Σ_k |E(x − k)|` in the scalar `S` from the coefficients `c`
    /// (`c_0..c_K` in `S`): one basis window and `O((K − n)·m)` products.
    fn curve_error_in<S: Real>(&self, c: &[S], n: usize, x: &S) -> S {
        let w = self.family.basis_window(x);
        let len = w.values.len() as i64;
        let kk = c.len() as i64;
        let tail = |i: i64| {
            let a = i.unsigned_abs() as usize;
            (a > n && a < c.len()).then(|| &c[a])
        };
        let mut total = S::zero();
        for k in (w.first - kk)..=(w.first + len - 1 + kk) {
            // All indices first + l − k inside [−n, n]: no tail term.
            if w.first - k >= -(n as i64) && w.first + len - 1 - k <= n as i64 {
                continue;
            }
            let mut e = S::zero();
            for (l, b) in w.values.iter().enumerate() {
                if let Some(ci) = tail(w.first + l as i64 - k) {
                    e += ci.clone() * b;
                }
            }
            total += e.abs();
        }
        total
    }

    fn curve_error_at(&self, n: usize, x: &T) -> T {
        self.curve_error_in(&self.c, n, x)
    }

    fn curve_error_f64(&self, n: usize, x: f64) -> f64 {
        self.curve_error_in(&self.c64, n, &x)
    }

    /// `sup_x Σ_k |E(x − k)|`. The function is even and 1-periodic, so
    /// `x ∈ [0, ½]`. The maximiser is *located* in `f64` (17 grid points,
    /// then 40 golden-section steps around the best one, bracket
    /// `≈ 2·10⁻¹⁰`); the value is then evaluated in `T` at the located point
    /// and at the best grid point, and the larger is returned. The sup lies
    /// at a smooth maximum or at a kink (a sign change of some `E(x − k)`), so
    /// the located value is a lower bound within about `10⁻⁹` relative of the
    /// sup (checked against dense sampling in the tests); the value itself
    /// carries the full accuracy of `T`.
    /// Test: `verify/tests/it/sspline_truncation.rs::uniform_error_is_the_sup_of_dense_samples`.
    /// **Source**: seed 000 eq 28 (the uniform truncation error).
    pub fn uniform_error(&self, n: usize) -> T {
        const GRID: i32 = 16;
        let at = |j: i32| j as f64 / (2 * GRID) as f64;
        let (best_j, _) = (0..=GRID)
            .map(|j| (j, self.curve_error_f64(n, at(j))))
            .fold((0, -1.0), |b, v| if v.1 > b.1 { v } else { b });
        let lo = at((best_j - 1).max(0));
        let hi = at((best_j + 1).min(GRID));
        let x_star = self.golden_argmax(n, lo, hi);
        let f_star = self.curve_error_at(n, &T::from_f64_exact(x_star));
        let f_grid = self.curve_error_at(n, &T::from_f64_exact(at(best_j)));
        if f_star > f_grid { f_star } else { f_grid }
    }

    fn golden_argmax(&self, n: usize, mut a: f64, mut b: f64) -> f64 {
        let g = (5f64.sqrt() - 1.0) / 2.0;
        let mut x1 = b - g * (b - a);
        let mut x2 = a + g * (b - a);
        let mut f1 = self.curve_error_f64(n, x1);
        let mut f2 = self.curve_error_f64(n, x2);
        for _ in 0..40 {
            if f1 < f2 {
                a = x1;
                x1 = x2;
                f1 = f2;
                x2 = a + g * (b - a);
                f2 = self.curve_error_f64(n, x2);
            } else {
                b = x2;
                x2 = x1;
                f2 = f1;
                x1 = b - g * (b - a);
                f1 = self.curve_error_f64(n, x1);
            }
        }
        if f1 > f2 { x1 } else { x2 }
    }

    /// `Σ_k |E(x − k)|` at one point (the curve error for the worst data at
    /// that parameter), exposed for studies and tests.
    pub fn curve_error(&self, n: usize, x: &T) -> T {
        self.curve_error_at(n, x)
    }

    /// The analytic tail bound (see [`PoleExpansion::tail_bound`]).
    pub fn tail_bound(&self, n: usize) -> T {
        self.expansion.tail_bound(n)
    }

    /// All four measures at `n` (`1 ≤ n ≤ max_n`).
    pub fn errors(&self, n: usize) -> TruncationErrors<T> {
        TruncationErrors {
            n,
            coeff: self.coeff_error(n),
            knot: self.knot_error(n),
            uniform: self.uniform_error(n),
            bound: self.tail_bound(n),
        }
    }
}
