//! The Euler–Frobenius polynomial `P(z) = V_1 z^d + V_2 z^{d−1} + … + V_{d+1}`
//! (seed 000 eq 16), its roots `ξ_r ∈ (−1, 0)` (the *poles* of the S-spline
//! coefficient sequence) and the weights `κ_r` of `c_i = Σ_r κ_r ξ_r^{|i|}`
//! (eq 17).
//!
//! `P` is palindromic with positive coefficients; its roots are real,
//! negative, simple and come in pairs `ξ, 1/ξ` (appendix b; Schoenberg,
//! *Cardinal Spline Interpolation*, 1973, lecture 2). With `d = 2p` there are
//! `p = ⌊(m−1)/2⌋` roots in (−1, 0).

use super::{SplineFamily, SsplineError, node_values::node_values};
use crate::roots::palindromic_inner_roots;
use crate::scalar::Real;

/// Coefficients of `P` (ascending powers; `P` is palindromic, so this is also
/// the descending list `V_1..V_{d+1}`), rounded to `T`.
pub fn polynomial<T: Real>(family: &SplineFamily) -> Result<Vec<T>, SsplineError> {
    node_values(family)
}

/// The `p` roots of `P` in (−1, 0), ordered from the one nearest 0 to the
/// dominant one nearest −1, computed in `T` by Laguerre's method with
/// implicit deflation of reciprocal pairs, every search starting at −1
/// ([`crate::roots::palindromic_inner_roots`]).
///
/// Cost `O(p·m)` per iteration, a few iterations per root. Accuracy: the
/// attainable accuracy of each root in `T` (measured: a few ulps in `f64`
/// up to order 24; at `BITS` bits, `BITS − 4` correct bits up to order 40 —
/// see the verify studies). The roots are checked to be distinct and inside
/// (−1, 0); anything else is an error, never a silent result.
///
/// Tests: `euler_frobenius.rs::tests::published_poles` and
/// `verify/tests/it/prefilter_every_order.rs`. **Source**: seed 000 eq 16; the
/// poles as in Unser, Aldroubi & Eden (1993).
///
/// ```
/// use splinelab::sspline::{SplineFamily, euler_frobenius::poles};
/// let xi: Vec<f64> = poles(&SplineFamily::Order(4)).unwrap();
/// assert!((xi[0] - (3f64.sqrt() - 2.0)).abs() < 1e-16);
/// ```
///
/// ```
/// // In MPFR: the quintic's two inner poles are roots, to 256-bit rounding,
/// // of its Euler–Frobenius polynomial z⁴ + 26z³ + 66z² + 26z + 1 (the
/// // samples 1, 26, 66, 26, 1 of 120 β₆), and lie in (−1, 0).
/// use splinelab::scalar::{Mp, Real};
/// use splinelab::sspline::{SplineFamily, euler_frobenius::poles};
/// type M = Mp<256>;
/// let xi: Vec<M> = poles(&SplineFamily::Order(6)).unwrap();
/// assert_eq!(xi.len(), 2);
/// for z in &xi {
///     let p = [1, 26, 66, 26, 1].iter().fold(M::from_int(0), |acc, &a| acc * z.clone() + M::from_int(a));
///     assert!(p.to_f64().abs() < 1e-70 && z.to_f64() < 0.0 && z.to_f64() > -1.0);
/// }
/// ```
pub fn poles<T: Real>(family: &SplineFamily) -> Result<Vec<T>, SsplineError> {
    let a = polynomial::<T>(family)?;
    let p = family.pole_count();
    let roots = palindromic_inner_roots(&a, p)?;
    let inside = roots
        .iter()
        .filter(|r| **r < T::zero() && **r > -T::one())
        .count();
    let distinct = roots.windows(2).all(|w| w[1] < w[0]);
    if inside != p || !distinct {
        return Err(SsplineError::PoleCount {
            family: family.to_string(),
            expected: p,
            found: if distinct { inside } else { 0 },
        });
    }
    Ok(roots)
}

/// The poles and their partial-fraction weights: `c_i = Σ_r κ_r ξ_r^{|i|}`.
#[derive(Debug, Clone, PartialEq)]
pub struct PoleExpansion<T> {
    /// Roots of `P` in (−1, 0), nearest 0 first.
    pub poles: Vec<T>,
    /// Weights `κ_r`, one per pole.
    pub kappas: Vec<T>,
    /// `c_0` when there is no pole (order 2: `c = δ`), else unused (0).
    pub constant: T,
}

impl<T: Real> PoleExpansion<T> {
    /// The expansion of `family` in `T`: poles by [`poles`], weights by
    /// residues of `1/V(z)`, `V(z) = z^{−p} P(z)`:
    /// `c_i = (1/2πi)∮ z^{i+p−1}/P(z) dz = Σ_r ξ_r^{i+p−1}/P'(ξ_r)` for
    /// `i ≥ 0`, so `κ_r = ξ_r^{p−1}/P'(ξ_r)` with
    /// `P'(ξ_r) = V_1 (ξ_r − 1/ξ_r) Π_{s≠r} (ξ_r − ξ_s)(ξ_r − 1/ξ_s)` (product
    /// form: each factor has a few `u` relative error, no cancellation from
    /// Horner). Equivalent to solving eq 12–13. Cost `O(p²)` after the poles.
    /// A vanishing difference (repeated root, appendix c) is reported as an
    /// error, never divided by.
    pub fn new(family: &SplineFamily) -> Result<Self, SsplineError> {
        let v = polynomial::<T>(family)?;
        let poles = poles::<T>(family)?;
        let p = poles.len();
        if p == 0 {
            return Ok(PoleExpansion {
                poles,
                kappas: vec![],
                constant: T::one() / v[0].clone(),
            });
        }
        let mut kappas = Vec::with_capacity(p);
        for (r, xr) in poles.iter().enumerate() {
            let mut deriv = v[0].clone() * (xr.clone() - xr.clone().recip());
            for (_, xs) in poles.iter().enumerate().filter(|(s, _)| *s != r) {
                deriv *= (xr.clone() - xs) * (xr.clone() - xs.clone().recip());
            }
            if deriv.is_zero() || !deriv.is_finite() {
                return Err(SsplineError::PoleCount {
                    family: family.to_string(),
                    expected: p,
                    found: 0,
                });
            }
            kappas.push(xr.clone().powi(p as i32 - 1) / deriv);
        }
        Ok(PoleExpansion {
            poles,
            kappas,
            constant: T::zero(),
        })
    }

    /// The magnitude of the dominant pole, `ρ = max_r |ξ_r|` (0 without
    /// poles): `|c_i| = O(ρ^i)`.
    pub fn decay_rate(&self) -> T {
        self.poles
            .iter()
            .map(|x| x.clone().abs())
            .fold(T::zero(), |a, b| if b > a { b } else { a })
    }

    /// `c_i = Σ_r κ_r ξ_r^i` for `i ≥ 0` (eq 17), one MPFR-correctly-rounded
    /// power per pole (`powi`). Relative error about `(i + 2p) u` plus the
    /// error of the poles amplified by `i`.
    pub fn coefficient(&self, i: usize) -> T {
        if self.poles.is_empty() {
            return if i == 0 {
                self.constant.clone()
            } else {
                T::zero()
            };
        }
        self.poles
            .iter()
            .zip(&self.kappas)
            .fold(T::zero(), |acc, (x, k)| {
                acc + k.clone() * x.clone().powi(i as i32)
            })
    }

    /// The analytic tail bound `Σ_{|i|>n} |c_i| ≤ 2 Σ_r |κ_r| |ξ_r|^{n+1}/(1 − |ξ_r|)`
    /// (geometric series of eq 17 with the triangle inequality).
    pub fn tail_bound(&self, n: usize) -> T {
        self.poles
            .iter()
            .zip(&self.kappas)
            .fold(T::zero(), |acc, (x, k)| {
                let a = x.clone().abs();
                acc + k.clone().abs() * a.clone().powi(n as i32 + 1) / (T::one() - a)
            })
            * T::from_int(2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    use nalgebra::ComplexField;

    #[test]
    fn published_poles() {
        type M = Mp<256>;
        let sq = |k: i64| M::from_int(k).sqrt();
        let rel = |a: &M, b: &M| ((a.clone() - b) / b.clone()).abs().to_f64();
        // Closed forms (Unser–Aldroubi–Eden 1993, Table I; degree n = m − 1).
        let quartic = (M::from_int(664) - sq(438976)).sqrt() + sq(304) - M::from_int(19);
        let quartic2 = (M::from_int(664) + sq(438976)).sqrt() - sq(304) - M::from_int(19);
        let cases = [
            (3, vec![sq(8) - M::from_int(3)]),
            (4, vec![sq(3) - M::from_int(2)]),
            (5, vec![quartic2, quartic]),
        ];
        for (m, want) in cases {
            let got = poles::<M>(&SplineFamily::Order(m)).unwrap();
            for (g, w) in got.iter().zip(&want) {
                assert!(rel(g, w) < 1e-72, "m={m}: {g:?} vs {w:?}");
            }
        }
        // Published decimals (same table): quartic, and degree 9 (m = 10).
        let q = poles::<M>(&SplineFamily::Order(5)).unwrap();
        assert!(
            rel(
                &q[0],
                &M::parse("-0.013725429297339121360331226939").unwrap()
            ) < 1e-27
        );
        assert!(rel(&q[1], &M::parse("-0.361341225900220177092212841").unwrap()) < 1e-27);
        let published = [
            "-0.00212130690318082",
            "-0.0432226085404818",
            "-0.201750520193153",
            "-0.607997389168626",
        ];
        let got = poles::<M>(&SplineFamily::Order(10)).unwrap();
        for (g, w) in got.iter().zip(published) {
            assert!(rel(g, &M::parse(w).unwrap()) < 1e-13, "{g:?} vs {w}");
        }
    }
}
