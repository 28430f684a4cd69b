//! Gauss–Legendre quadrature on `[0, 1]` with nodes and weights computed in
//! the working precision.
//!
//! An `m`-point Gauss–Legendre rule integrates polynomials of degree
//! `≤ 2m − 1` exactly; for a function analytic on a Bernstein ellipse with
//! parameter `ρ` its error is `O(ρ^(−2m))`, and for entire integrands (such as
//! the QI tangent, a composition of sin/cos with polynomials) it decays
//! faster than geometrically. The nodes are the roots of the Legendre
//! polynomial `P_m`, found by Newton's method on the three-term recurrence
//! (Golub–Welsch is not needed: Newton from Tricomi's initial guesses
//! converges quadratically for every root). The first iterations run in
//! `f64`, the last ones in `T`, so `Mp<1024>` rules are correct to the
//! working precision and not limited by `f64` tables.
//!
//! Reference: Abramowitz & Stegun 25.4.29 (weights), Tricomi's asymptotic
//! initial guess `x_i ≈ cos(π (i − ¼)/(m + ½))`.

use crate::scalar::Real;
use thiserror::Error;

/// What can go wrong when building or applying a rule.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum QuadratureError {
    /// A rule needs at least one node.
    #[error("a Gauss–Legendre rule needs at least one node")]
    ZeroOrder,
    /// More nodes than [`MAX_NODES`].
    #[error("a Gauss–Legendre rule of {0} nodes exceeds the limit of {MAX_NODES}")]
    TooManyNodes(usize),
    /// Tolerances must be positive and finite.
    #[error("quadrature tolerance must be positive and finite (got {0})")]
    InvalidTolerance(f64),
    /// Newton on the Legendre polynomial did not reach the working precision.
    #[error("Legendre root {index} of P_{order} did not converge")]
    RootNotConverged {
        /// Number of nodes of the rule.
        order: usize,
        /// Index of the root that failed.
        index: usize,
    },
    /// Doubling the order up to the limit never met the tolerance.
    #[error(
        "quadrature error estimate {estimate:e} still above tolerance {tol:e} at order {order}"
    )]
    ToleranceNotMet {
        /// Largest order tried.
        order: usize,
        /// Last error estimate `|Q_m − Q_2m|` (rounded to f64).
        estimate: f64,
        /// Requested tolerance (rounded to f64).
        tol: f64,
    },
}

/// Most nodes a rule may have: building one costs `O(m²)` operations
/// (`m/2` Newton solves on the `O(m)` recurrence), and the QI study's
/// doubling search stops at 2048.
pub const MAX_NODES: usize = 1 << 16;

/// An `m`-point Gauss–Legendre rule mapped to `[0, 1]`.
///
/// ```
/// use splinelab::quadrature::GaussLegendre;
/// // ∫₀¹ t⁵ dt = 1/6 exactly with 3 nodes (degree ≤ 2·3 − 1).
/// let rule = GaussLegendre::<f64>::new(3).unwrap();
/// let q = rule.integrate(|t| t.powi(5));
/// assert!((q - 1.0 / 6.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct GaussLegendre<T> {
    nodes: Vec<T>,
    weights: Vec<T>,
}

/// `(P_m(x), P'_m(x))` by the three-term recurrence
/// `(k+1) P_{k+1} = (2k+1) x P_k − k P_{k−1}` and
/// `P'_m = m (x P_m − P_{m−1}) / (x² − 1)` (not valid at `x = ±1`).
///
/// Cost `O(m)`; the recurrence is forward stable on `[−1, 1]`.
/// Tested through the rules built on it
/// (`quadrature.rs::tests::exact_on_polynomials_f64`, `exact_on_polynomials_mp`).
/// **Source**: Abramowitz & Stegun (1964), 22.7.10 and 22.8.5.
pub fn legendre<T: Real>(m: usize, x: &T) -> (T, T) {
    let mut p_prev = T::one();
    let mut p = x.clone();
    if m == 0 {
        return (T::one(), T::zero());
    }
    for k in 1..m {
        let kk = T::from_int(k as i64);
        let next = (T::from_int(2 * k as i64 + 1) * x.clone() * &p - kk.clone() * p_prev)
            / (kk + T::one());
        p_prev = std::mem::replace(&mut p, next);
    }
    let dp = T::from_int(m as i64) * (x.clone() * &p - p_prev) / (x.clone() * x - T::one());
    (p, dp)
}

/// Newton's method for the `i`-th root (1-based, descending) of `P_m`,
/// started at `x0`, stopped when the correction no longer exceeds a few
/// units of the working precision. Returns the root and `P'_m` there.
fn legendre_root<T: Real>(m: usize, x0: T, index: usize) -> Result<(T, T), QuadratureError> {
    let tiny = T::unit_roundoff().scale_by_pow2(2);
    let mut x = x0;
    // Quadratic convergence: a handful of steps suffice from a good start;
    // the extra allowance covers the f64 → T hand-over for 4096-bit types.
    for _ in 0..64 {
        let (p, dp) = legendre(m, &x);
        let dx = p / dp.clone();
        x -= dx.clone();
        if dx.abs() <= tiny.clone() * x.clone().abs() + T::unit_roundoff() * tiny.clone() {
            // |dx| ≤ 4u|x| after quadratic convergence means the error of the
            // updated x is O(dx²) ≪ u: done. P'_m is re-evaluated at the final
            // x so that the weight matches the node.
            let (_, dp) = legendre(m, &x);
            return Ok((x, dp));
        }
    }
    Err(QuadratureError::RootNotConverged { order: m, index })
}

impl<T: Real> GaussLegendre<T> {
    /// Builds the `m`-point rule on `[0, 1]`: nodes `t_i = (1 + x_i)/2` and
    /// weights `w_i = 1 / ((1 − x_i²) P'_m(x_i)²)` (A&S 25.4.29 halved for
    /// the interval length), where `x_i` are the roots of `P_m`.
    ///
    /// Cost: `O(m²)` operations in `T` (Newton, `O(m)` per evaluation,
    /// about `log₂(BITS/53)` steps per root after an `f64` start).
    /// Accuracy: nodes and weights within a few ulps of `T` (checked in the
    /// tests by exactness on polynomials and by symmetry).
    /// Errors: `m = 0`, `m >` [`MAX_NODES`], a root that does not converge.
    /// Tests: `quadrature.rs::tests::exact_on_polynomials_f64`,
    /// `exact_on_polynomials_mp`, `mp_nodes_are_not_f64_limited`. **Source**:
    /// Gauss–Legendre by Newton on `P_m`, weights by Abramowitz & Stegun (1964), 25.4.29.
    ///
    /// ```
    /// // In MPFR: 3 nodes integrate t⁵ exactly, ∫₀¹ t⁵ dt = 1/6, to 256-bit rounding.
    /// use splinelab::quadrature::GaussLegendre;
    /// use splinelab::scalar::{Mp, Real};
    /// type M = Mp<256>;
    /// let rule = GaussLegendre::<M>::new(3).unwrap();
    /// let q = rule.integrate(|t| { let t2 = t.clone() * t.clone(); t2.clone() * t2 * t.clone() });
    /// assert!((q - M::from_int(1) / M::from_int(6)).to_f64().abs() < 1e-74);
    /// ```
    pub fn new(m: usize) -> Result<Self, QuadratureError> {
        if m == 0 {
            return Err(QuadratureError::ZeroOrder);
        }
        if m > MAX_NODES {
            return Err(QuadratureError::TooManyNodes(m));
        }
        let half = T::from_f64_exact(0.5);
        let mut nodes = vec![T::zero(); m];
        let mut weights = vec![T::zero(); m];
        for i in 1..=m.div_ceil(2) {
            let guess = (std::f64::consts::PI * (i as f64 - 0.25) / (m as f64 + 0.5)).cos();
            let (x64, _) = legendre_root::<f64>(m, guess, i)?;
            let (x, dp) = if m % 2 == 1 && i == m.div_ceil(2) {
                // The middle root of an odd-order polynomial is exactly 0.
                let zero = T::zero();
                let (_, dp) = legendre(m, &zero);
                (zero, dp)
            } else {
                legendre_root::<T>(m, T::from_f64_exact(x64), i)?
            };
            let w = T::one() / ((T::one() - x.clone() * &x) * dp.clone() * dp);
            // Roots come in ± pairs: x_i descending, store ascending on [0,1].
            nodes[i - 1] = half.clone() - half.clone() * x.clone();
            nodes[m - i] = half.clone() + half.clone() * x;
            weights[i - 1] = w.clone();
            weights[m - i] = w;
        }
        Ok(GaussLegendre { nodes, weights })
    }

    /// Number of nodes `m`.
    pub fn order(&self) -> usize {
        self.nodes.len()
    }

    /// Nodes on `[0, 1]`, ascending.
    pub fn nodes(&self) -> &[T] {
        &self.nodes
    }

    /// Weights, summing to 1.
    pub fn weights(&self) -> &[T] {
        &self.weights
    }

    /// `Σ w_i f(t_i) ≈ ∫₀¹ f(t) dt`. Cost: `m` evaluations of `f`.
    pub fn integrate(&self, mut f: impl FnMut(&T) -> T) -> T {
        self.nodes
            .iter()
            .zip(&self.weights)
            .fold(T::zero(), |acc, (t, w)| acc + w.clone() * f(t))
    }

    /// `∫_a^b f ≈ (b − a) Σ w_i f(a + (b − a) t_i)`.
    pub fn integrate_on(&self, a: &T, b: &T, mut f: impl FnMut(&T) -> T) -> T {
        let len = b.clone() - a;
        let s = self.integrate(|t| f(&(a.clone() + len.clone() * t.clone())));
        len * s
    }
}

/// Chooses a rule by doubling: tries `m = m0, 2 m0, 4 m0, …` up to `m_max`
/// and accepts the first `m` whose error estimate `diff(Q_m, Q_2m) ≤ tol`,
/// where `diff` compares what the caller computes with two rules (for a
/// scalar integral, `|Q_m − Q_2m|`; for several, their maximum).
///
/// Returns the accepted rule `Q_m` and the estimate. Because `Q_2m` is far
/// more accurate than `Q_m` for smooth integrands, the estimate bounds the
/// error of `Q_m` up to a factor close to 1 in the asymptotic regime.
/// Cost: the rules up to `2m` plus two evaluations of the caller's
/// integrals per doubling.
/// **Accuracy**: the estimate is shown to bound the true error in
/// `quadrature.rs::tests::doubling_estimate_bounds_true_error`. **Source**:
/// standard practice, not from the seeds (used for seed 004's arc-length
/// and G2 integrals).
pub fn choose_order<T: Real>(
    m0: usize,
    m_max: usize,
    tol: &T,
    mut diff: impl FnMut(&GaussLegendre<T>, &GaussLegendre<T>) -> T,
) -> Result<(GaussLegendre<T>, T), QuadratureError> {
    if !(tol.is_finite() && *tol > T::zero()) {
        return Err(QuadratureError::InvalidTolerance(tol.to_f64()));
    }
    let mut m = m0.max(1);
    let mut low = GaussLegendre::new(m)?;
    loop {
        let high = GaussLegendre::new(m.saturating_mul(2))?;
        let est = diff(&low, &high);
        if est.is_finite() && est <= *tol {
            return Ok((low, est));
        }
        if 2 * m > m_max {
            return Err(QuadratureError::ToleranceNotMet {
                order: 2 * m,
                estimate: est.to_f64(),
                tol: tol.to_f64(),
            });
        }
        m *= 2;
        low = high;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    #[allow(unused_imports)]
    use crate::scalar::prelude::*;
    use rug::Rational;

    /// Exact ∫₀¹ t^k = 1/(k+1): every degree up to 2m − 1 must be exact
    /// to a few ulps.
    fn exact_on_monomials<T: Real>(m: usize, ulps: i32) {
        let rule = GaussLegendre::<T>::new(m).unwrap();
        for k in 0..2 * m {
            let q = rule.integrate(|t| t.clone().powi(k as i32));
            let exact = T::from_rational(&Rational::from((1, k as i64 + 1)));
            let err = (q.clone() - &exact).abs();
            let bound = T::unit_roundoff().scale_by_pow2(ulps) * T::from_int(m as i64);
            assert!(
                err <= bound,
                "m={m} k={k}: {} vs {}",
                q.to_decimal(30),
                exact.to_decimal(30)
            );
        }
    }

    #[test]
    fn exact_on_polynomials_f64() {
        for m in [1, 2, 3, 5, 8, 13] {
            exact_on_monomials::<f64>(m, 4);
        }
    }

    #[test]
    fn exact_on_polynomials_mp() {
        for m in [1, 4, 7, 16] {
            exact_on_monomials::<Mp<256>>(m, 4);
        }
    }

    /// Degree 2m is not exact: the 2-point rule (nodes ½ ± 1/(2√3), weights
    /// ½) gives 7/36 for ∫₀¹ t⁴ = 1/5 (closed form by hand).
    #[test]
    fn two_point_rule_on_t4_is_off_by_closed_form() {
        let rule = GaussLegendre::<Mp<128>>::new(2).unwrap();
        let q = rule.integrate(|t| t.clone().powi(4));
        let want = Mp::<128>::from_rational(&Rational::from((7, 36)));
        assert!((q - want).abs() < Mp::<128>::unit_roundoff().scale_by_pow2(3));
    }

    /// Nodes computed in Mp<256> agree with the f64 nodes to f64 accuracy,
    /// and the f64 rule is not accidentally used for the Mp one: the Mp
    /// weights sum to 1 to 256-bit accuracy.
    #[test]
    fn mp_nodes_are_not_f64_limited() {
        let m = 20;
        let r64 = GaussLegendre::<f64>::new(m).unwrap();
        let rmp = GaussLegendre::<Mp<256>>::new(m).unwrap();
        for (a, b) in r64.nodes().iter().zip(rmp.nodes()) {
            assert!((a - b.to_f64()).abs() < 4e-16);
        }
        let s = rmp
            .weights()
            .iter()
            .fold(Mp::<256>::from_int(0), |a, w| a + w);
        assert!((s - Mp::from_int(1)).abs() < Mp::<256>::unit_roundoff().scale_by_pow2(6));
        // ∫₀¹ e^t = e − 1 to 256 bits with 40 nodes (entire integrand).
        let r = GaussLegendre::<Mp<256>>::new(40).unwrap();
        let q = r.integrate(|t| t.clone().exp());
        let exact = <Mp<256> as nalgebra::RealField>::e() - Mp::from_int(1);
        assert!((q - exact).abs() < Mp::<256>::unit_roundoff().scale_by_pow2(8));
    }

    /// Error of a low rule measured against a higher-order rule computed in
    /// higher precision: the doubling estimate must bound the true error.
    #[test]
    fn doubling_estimate_bounds_true_error() {
        let f = |t: &Mp<512>| (t.clone() * Mp::from_int(7)).cos();
        let exact = (Mp::<512>::from_int(7)).sin() / Mp::from_int(7);
        let tol = Mp::<512>::from_f64_exact(1e-40);
        let (rule, est) = choose_order(4, 1024, &tol, |a, b| {
            (a.integrate(|t| f(t)) - b.integrate(|t| f(t))).abs()
        })
        .unwrap();
        let err = (rule.integrate(|t| f(t)) - exact).abs();
        assert!(est <= tol);
        assert!(err <= est.clone() * Mp::from_int(2), "err {err} est {est}");
    }

    #[test]
    fn bad_arguments_are_errors() {
        assert_eq!(
            GaussLegendre::<f64>::new(0).unwrap_err(),
            QuadratureError::ZeroOrder
        );
        let e = choose_order::<f64>(4, 64, &f64::NAN, |_, _| 0.0).unwrap_err();
        assert!(matches!(e, QuadratureError::InvalidTolerance(_)));
        let e = choose_order::<f64>(4, 16, &1e-300, |_, _| 1.0).unwrap_err();
        assert!(matches!(e, QuadratureError::ToleranceNotMet { .. }));
    }
}
