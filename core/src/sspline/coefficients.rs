//! The S-spline coefficients `c_0, …, c_{K−1}` (`c_{−i} = c_i`) solving
//! `Σ_i c_i β(j − i) = δ_{0j}` for all integers `j` (seed 000 eq 9, 17), by
//! three independent methods and a production route.
//!
//! In Laurent form, `Σ_i c_i z^i = 1/V(z)` with `V(z) = Σ_j β(j) z^j =
//! z^{−p} P(z)`, `P` the Euler–Frobenius polynomial. The methods:
//!
//! - [`CoefficientMethod::PartialFractions`] — poles and residues (eq 17,
//!   the κ of eq 12–13), see [`PoleExpansion`];
//! - [`CoefficientMethod::RecursiveFilter`] — `1/V(z) = g Π_r 1/((1 − ξ_r z⁻¹)(1 − ξ_r z))`
//!   applied to a unit impulse by causal and anti-causal first-order
//!   recursions (Unser–Aldroubi–Eden, *B-spline signal processing I*, IEEE
//!   Trans. SP 41 (1993)); uses the poles but not the κ;
//! - [`CoefficientMethod::ToeplitzSolve`] — the banded symmetric Toeplitz
//!   system `β(j − i)` on `[−N, N]` with right-hand side `e_0`, by band
//!   Gaussian elimination; uses neither poles nor κ (the poles only size `N`).
//!
//! [`CoefficientMethod::Production`] is the partial-fraction route in at
//! least 128 guard bits, rounded once to `T`: correctly rounded up to a
//! `2^{−120}` relative perturbation (so ≤ 1 ulp in `f64`, 0.5 ulp except in
//! near-tie cases). It exists because no pure-`f64` route can reach a few
//! ulps for large `i`: the pole itself carries a relative rounding error
//! `δ ≤ u`, and `ξ^i` amplifies it to `i·δ` (30 ulps at `i = 60`).

use super::euler_frobenius::{PoleExpansion, poles, polynomial};
use super::{SplineFamily, SsplineError};
use crate::scalar::{Mp, Real};

/// How to compute the coefficients; see the [module documentation](self).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CoefficientMethod {
    /// Poles and residues, `c_i = Σ_r κ_r ξ_r^i` (eq 17).
    PartialFractions,
    /// Causal/anti-causal recursive filter applied to a unit impulse.
    RecursiveFilter,
    /// Band Gaussian elimination of the symmetric Toeplitz system.
    ToeplitzSolve,
    /// Partial fractions in ≥ 128 guard bits, rounded once to `T`.
    Production,
}

impl CoefficientMethod {
    /// The three independent methods (without `Production`).
    pub const INDEPENDENT: [CoefficientMethod; 3] = [
        CoefficientMethod::PartialFractions,
        CoefficientMethod::RecursiveFilter,
        CoefficientMethod::ToeplitzSolve,
    ];

    /// Short name for tables and JSON.
    pub fn name(&self) -> &'static str {
        match self {
            CoefficientMethod::PartialFractions => "partial-fractions",
            CoefficientMethod::RecursiveFilter => "recursive-filter",
            CoefficientMethod::ToeplitzSolve => "toeplitz-solve",
            CoefficientMethod::Production => "production",
        }
    }
}

/// `c_0..c_{count−1}` of `family` in `T` by `method`.
///
/// Cost: partial fractions `O(p·count)` powers after the poles; filter
/// `O(p·N)`; Toeplitz `O(p²·N)`, with `N = count + (BITS+16)/log2(1/ρ)`
/// (`ρ` the dominant pole) chosen so that the truncation of the infinite
/// system is below `2^{−BITS−16}` relatively; production: partial fractions
/// at ≥ `BITS + 128` bits.
///
/// Error behaviour (relative, per coefficient, `u` the unit roundoff of `T`):
/// partial fractions and filter about `i·u` plus the pole error times `i`;
/// Toeplitz: componentwise small, `O(N u)` in the worst case, because the
/// B-spline collocation matrix is totally positive and `e_0` has an
/// alternating sign pattern (de Boor–Pinkus 1977; Higham, *Accuracy and
/// Stability*, 2nd ed., §9.6); production: ≤ 1 ulp. Measured figures for
/// every order are in the verify study `sspline`.
///
/// ```
/// use splinelab::sspline::{coefficients, CoefficientMethod, SplineFamily};
/// let c: Vec<f64> = coefficients(&SplineFamily::Order(4), 3, CoefficientMethod::Production).unwrap();
/// // eq 18: c_i = √3 (√3 − 2)^i
/// assert!((c[0] - 1.7320508075688772).abs() <= 2.3e-16);
/// assert!((c[2] - 0.12435565298214105).abs() <= 1.4e-17);
/// ```
///
/// ```
/// // In MPFR: the cubic's c_i against eq 18, c_i = √3 (√3 − 2)^i.
/// use splinelab::nalgebra::ComplexField;
/// use splinelab::scalar::{Mp, Real};
/// use splinelab::sspline::{coefficients, CoefficientMethod, SplineFamily};
/// type M = Mp<256>;
/// let c: Vec<M> = coefficients(&SplineFamily::Order(4), 4, CoefficientMethod::Production).unwrap();
/// let s3 = M::from_int(3).sqrt();
/// let mut want = s3.clone();
/// for ci in &c {
///     assert!(((ci.clone() - want.clone()) / want.clone()).to_f64().abs() < 1e-74);
///     want = want * (s3.clone() - M::from_int(2));
/// }
/// ```
pub fn coefficients<T: Real>(
    family: &SplineFamily,
    count: usize,
    method: CoefficientMethod,
) -> Result<Vec<T>, SsplineError> {
    family.validate()?;
    if count == 0 {
        return Err(SsplineError::ZeroCount);
    }
    match method {
        CoefficientMethod::PartialFractions => partial_fractions(family, count),
        CoefficientMethod::RecursiveFilter => recursive_filter(family, count),
        CoefficientMethod::ToeplitzSolve => toeplitz_solve(family, count),
        CoefficientMethod::Production => production(family, count),
    }
}

fn partial_fractions<T: Real>(family: &SplineFamily, count: usize) -> Result<Vec<T>, SsplineError> {
    let e = PoleExpansion::<T>::new(family)?;
    Ok((0..count).map(|i| e.coefficient(i)).collect())
}

/// Half-size `N` of the finite window `[−N, N]`: the neglected part is below
/// `2^{−BITS−16}` relative to `c_{count−1}`.
fn window_half_size<T: Real>(poles: &[T], count: usize) -> usize {
    let rho = poles.iter().map(|x| x.to_f64().abs()).fold(0.0, f64::max);
    if rho == 0.0 {
        return count;
    }
    let extra = (T::BITS as f64 + 16.0) / (-rho.log2());
    count + extra.ceil() as usize + 2
}

fn recursive_filter<T: Real>(family: &SplineFamily, count: usize) -> Result<Vec<T>, SsplineError> {
    let v = polynomial::<T>(family)?;
    let xi = poles::<T>(family)?;
    let n = window_half_size(&xi, count);
    // 1/V(z) = (Π_r (−ξ_r) / V_1) · Π_r 1/((1 − ξ_r z⁻¹)(1 − ξ_r z)).
    let gain = xi
        .iter()
        .fold(T::one() / v[0].clone(), |g, x| g * -x.clone());
    let mut s = vec![T::zero(); 2 * n + 1];
    s[n] = gain;
    for x in &xi {
        for k in 1..s.len() {
            let prev = s[k - 1].clone();
            s[k] += x.clone() * prev;
        }
        for k in (0..s.len() - 1).rev() {
            let next = s[k + 1].clone();
            s[k] += x.clone() * next;
        }
    }
    Ok(s[n..n + count].to_vec())
}

fn toeplitz_solve<T: Real>(family: &SplineFamily, count: usize) -> Result<Vec<T>, SsplineError> {
    let v = polynomial::<T>(family)?;
    let xi = poles::<T>(family)?;
    let n = window_half_size(&xi, count);
    let x = solve_band_toeplitz(&v, 2 * n + 1, n);
    Ok(x[n..n + count].to_vec())
}

/// Solves `A x = e_centre` with `A_{jk} = v[p + k − j]` (band half-width `p`,
/// `v.len() = 2p + 1`, symmetric positive definite) of size `size`, by
/// Gaussian elimination without pivoting in band storage: `O(size·p²)`.
fn solve_band_toeplitz<T: Real>(v: &[T], size: usize, centre: usize) -> Vec<T> {
    let p = v.len() / 2;
    let w = 2 * p + 1;
    let mut a: Vec<T> = (0..size).flat_map(|_| v.iter().cloned()).collect();
    let mut b = vec![T::zero(); size];
    b[centre] = T::one();
    for k in 0..size {
        let last = (k + p).min(size - 1);
        let pivot = a[k * w + p].clone();
        for i in k + 1..=last {
            let l = a[i * w + p + k - i].clone() / &pivot;
            for j in k + 1..=last {
                let akj = a[k * w + p + j - k].clone();
                a[i * w + p + j - i] -= l.clone() * akj;
            }
            let bk = b[k].clone();
            b[i] -= l * bk;
        }
    }
    let mut x = vec![T::zero(); size];
    for k in (0..size).rev() {
        let last = (k + p).min(size - 1);
        let mut s = b[k].clone();
        for j in k + 1..=last {
            s -= a[k * w + p + j - k].clone() * &x[j];
        }
        x[k] = s / a[k * w + p].clone();
    }
    x
}

fn production<T: Real>(family: &SplineFamily, count: usize) -> Result<Vec<T>, SsplineError> {
    rounded_from_wide(family, &Coefficients(count))
}

/// The poles `ξ_r` computed with at least 128 guard bits beyond the
/// cancellation of high orders and rounded once to `T`: correctly rounded
/// up to a `2^{−120}` relative perturbation. [`poles`] in `T` itself loses
/// `≈ 0.65 m` bits and stops converging in `f64` above order ~120.
pub fn poles_rounded<T: Real>(family: &SplineFamily) -> Result<Vec<T>, SsplineError> {
    rounded_from_wide(family, &Poles)
}

/// A list of reals computable in any precision.
trait WideComputation {
    fn run<W: Real>(&self, family: &SplineFamily) -> Result<Vec<W>, SsplineError>;
}

struct Coefficients(usize);

impl WideComputation for Coefficients {
    fn run<W: Real>(&self, family: &SplineFamily) -> Result<Vec<W>, SsplineError> {
        partial_fractions(family, self.0)
    }
}

struct Poles;

impl WideComputation for Poles {
    fn run<W: Real>(&self, family: &SplineFamily) -> Result<Vec<W>, SsplineError> {
        poles(family)
    }
}

/// Guard bits carried beyond the target precision and the cancellation.
pub const GUARD_BITS: u32 = 128;

/// Runs `c` with ≥ [`GUARD_BITS`] guard bits and rounds once to `T`.
/// Evaluating the Euler–Frobenius polynomial near its dominant root (≈ −1)
/// cancels about 0.65 bits per order (`|V(−1)| ≈ (2/π)^m`), so the working
/// precision covers that loss on top of the guard bits.
///
/// The working precision is the first rung `W ≥ BITS + cancellation + 128`
/// of one list (`guarded_rungs!` below); past the last rung the call is an
/// error ([`SsplineError::GuardTooWide`]), never a silent loss of guard
/// bits. Cost: at most about 2× the bits of `T` plus 512.
fn rounded_from_wide<T: Real, C: WideComputation>(
    family: &SplineFamily,
    c: &C,
) -> Result<Vec<T>, SsplineError> {
    let cancelled = (0.7 * family.spline_order() as f64) as u32;
    let need = T::BITS.saturating_add(cancelled).saturating_add(GUARD_BITS);
    /// The guarded precisions, increasing: the first three keep the working
    /// precisions of the f64 and 128/256-bit paths; then `2^k + 512`.
    macro_rules! guarded_rungs {
        ($($w:literal),+) => {
            $(
                if need <= $w {
                    return round(family, c.run::<Mp<$w>>(family)?);
                }
            )+
            return Err(SsplineError::GuardTooWide {
                bits: T::BITS,
                guard: GUARD_BITS,
                cancelled,
                widest: *[$($w),+].last().unwrap_or(&0),
            })
        };
    }
    guarded_rungs!(
        192, 384, 1088, 2560, 4608, 8704, 16896, 33280, 66048, 131_584, 262_656, 524_800, 1_049_088
    );
}

/// Rounds each wide value once to `T`; a NaN or infinity is an error (it
/// has no rational value to round).
fn round<T: Real, W: Real>(family: &SplineFamily, wide: Vec<W>) -> Result<Vec<T>, SsplineError> {
    wide.iter()
        .map(|c| {
            if c.is_finite() {
                Ok(c.convert())
            } else {
                Err(SsplineError::NonFinite {
                    family: family.to_string(),
                    value: c.to_float().to_string(),
                })
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Past 960 bits of target + cancellation the ladder used to run in `T`
    /// itself, losing the guard bits: at 1024 bits and order 200 the
    /// production coefficients must match partial fractions in 2048 bits
    /// rounded once to 1024 bits.
    #[test]
    fn production_keeps_guard_bits_at_high_precision_and_order() {
        let family = SplineFamily::Order(200);
        let got: Vec<Mp<1024>> = coefficients(&family, 3, CoefficientMethod::Production).unwrap();
        let wide: Vec<Mp<2048>> = partial_fractions(&family, 3).unwrap();
        for (g, w) in got.iter().zip(&wide) {
            let w: Mp<1024> = w.convert();
            let rel = ((g.clone() - &w) / w).to_float().abs();
            assert!(rel < rug::Float::with_val(64, 1) >> 1000u32, "{rel}");
        }
    }

    #[test]
    fn non_finite_wide_values_are_errors_not_zeros() {
        let family = SplineFamily::Order(4);
        let nan = Mp::<192>::from_f64_exact(f64::NAN);
        let inf = Mp::<192>::from_f64_exact(f64::INFINITY);
        for bad in [nan, inf] {
            let r: Result<Vec<f64>, _> = round(&family, vec![Mp::<192>::from_int(1), bad]);
            assert!(matches!(r, Err(SsplineError::NonFinite { .. })), "{r:?}");
        }
    }
}
