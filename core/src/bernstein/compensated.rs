//! Compensated de Casteljau evaluation (Jiang, Li, Cheng & Su, 2010): a fast
//! f64 kernel, and a bounded version in every precision.
//!
//! **Method** (Jiang, Li, Cheng & Su, *Accurate evaluation of a polynomial in
//! Bernstein form*, Comput. Math. Appl. 60 (2010), Algorithm `CompDeCasteljau`):
//! with the error-free transformations [`two_sum`] and [`two_prod`](crate::scalar::two_prod),
//! `1 − t = r + ρ` exactly, and each de Casteljau step
//! `(1 − t) b_i + t b_{i+1} = b_i' + w_i` exactly, where
//! `(s, π₁) = TwoProd(r, b_i)`, `(v, π₂) = TwoProd(t, b_{i+1})`,
//! `(b_i', σ) = TwoSum(s, v)` and `w_i = π₁ + π₂ + σ + ρ b_i`. The exact
//! error of the plain result therefore obeys the same de Casteljau recurrence
//! driven by the `w_i`; it is evaluated alongside in ordinary f64
//! (`ĉ_i' = w_i + r ĉ_i + t ĉ_{i+1}`) and added at the end.
//!
//! **Accuracy** (Theorem 4 of the paper), for `t ∈ [0, 1]` and no underflow:
//! `|res − p(t)| / |p(t)| ≤ u + 2γ_{3n}² cond_B(p, t)` — as accurate as de
//! Casteljau in doubled precision (106 bits) and then rounded to f64.
//!
//! **Known limitation**: near a multiple root where `|p(t)| ≲ u² Σ|b_i|B_i^n(t)`
//! the correction itself is pure rounding noise and the result can be exactly
//! 0 while `p(t) ≠ 0` (of order `u³`); the bound still holds since its second
//! term dominates.
//!
//! **Cost**: `n(n+1)/2` steps of two TwoProd, one TwoSum and the correction
//! (26 flops with FMA). TwoProd takes the fused multiply-add route when the
//! CPU has FMA — detected at run time, so the binary stays portable — and
//! Dekker's 17-flop product otherwise (see [`crate::scalar::TwoProduct`]);
//! both are exact, so the result is the same bits either way. Degrees ≤ 31
//! use stack buffers (no allocation). Measured ratios against plain de
//! Casteljau: `cargo bench -p splinelab-benches --bench bezier_eval`.

use super::bezier::{BernsteinPoly, BezierError, Evaluation, check_parameter, finite};
use crate::scalar::running_error::{RoundingModel, Running};
use crate::scalar::{DekkerProduct, FmaProduct, Real, TwoProduct, fma_available, two_sum};

const METHOD: &str = "compensated";

/// The compensated de Casteljau value of `p(t)` (see the module docs).
///
/// ```
/// use splinelab::bernstein::{bezier::BernsteinPoly, compensated::compensated_de_casteljau};
/// // (t − ½)³ = (−⅛, ⅛, −⅛, ⅛) in Bernstein form; near t = ½ plain de Casteljau
/// // loses all digits, the compensated value is exact here.
/// let p = BernsteinPoly::new(vec![-0.125, 0.125, -0.125, 0.125]).unwrap();
/// let t = 0.5 + 2f64.powi(-20);
/// assert_eq!(compensated_de_casteljau(&p, t), Ok(2f64.powi(-60)));
/// ```
pub fn compensated_de_casteljau(poly: &BernsteinPoly<f64>, t: f64) -> Result<f64, BezierError> {
    check_parameter(&t)?;
    finite(dispatch(poly.coeffs(), t), METHOD, poly.degree())
}

/// The compensated triangle on the fastest exact TwoProd route of this CPU,
/// chosen at run time: FMA where [`fma_available`], Dekker's product elsewhere.
fn dispatch(coeffs: &[f64], t: f64) -> f64 {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "fma")))]
    if fma_available() {
        // SAFETY: the one precondition of calling a `#[target_feature]`
        // function is that the CPU supports the feature; `fma_available`
        // has just checked it with CPUID.
        #[allow(unsafe_code)]
        return unsafe { compensated_fma(coeffs, t) };
    }
    if cfg!(target_feature = "fma") || (fma_available() && !cfg!(target_arch = "x86_64")) {
        compensated_with::<FmaProduct>(coeffs, t)
    } else {
        compensated_with::<DekkerProduct>(coeffs, t)
    }
}

/// [`compensated_with::<FmaProduct>`] compiled with FMA enabled, so that
/// `mul_add` is one instruction instead of a library call.
#[cfg(all(target_arch = "x86_64", not(target_feature = "fma")))]
#[target_feature(enable = "fma")]
fn compensated_fma(coeffs: &[f64], t: f64) -> f64 {
    compensated_with::<FmaProduct>(coeffs, t)
}

/// Degrees up to this one run on stack buffers (no allocation).
const STACK_DEGREE: usize = 31;

/// The compensated triangle with a chosen TwoProd route `P` (both routes are
/// exact, so they return the same bits); `coeffs` non-empty. Public so that
/// tests and benches can run each route; [`compensated_de_casteljau`] picks
/// the fast one.
#[inline(always)]
pub fn compensated_with<P: TwoProduct>(coeffs: &[f64], t: f64) -> f64 {
    let n = coeffs.len() - 1;
    if n <= STACK_DEGREE {
        let (mut b, mut c) = ([0.0; STACK_DEGREE + 1], [0.0; STACK_DEGREE + 1]);
        b[..=n].copy_from_slice(coeffs);
        triangle::<P>(&mut b[..=n], &mut c[..=n], t)
    } else {
        triangle::<P>(&mut coeffs.to_vec(), &mut vec![0.0; n + 1], t)
    }
}

/// The recurrence of the module doc on `b` (coefficients, overwritten) and
/// `c` (zeroed corrections); returns `b_0 + ĉ_0`.
#[inline(always)]
fn triangle<P: TwoProduct>(b: &mut [f64], c: &mut [f64], t: f64) -> f64 {
    let n = b.len() - 1;
    let (r, rho) = two_sum(1.0, -t);
    for j in 1..=n {
        for i in 0..=n - j {
            let (s, pi1) = P::two_prod(r, b[i]);
            let (v, pi2) = P::two_prod(t, b[i + 1]);
            let (sum, sigma) = two_sum(s, v);
            let w = pi1 + pi2 + sigma + rho * b[i];
            c[i] = w + r * c[i] + t * c[i + 1];
            b[i] = sum;
        }
    }
    b[0] + c[0]
}

/// [`compensated_de_casteljau`] with a rigorous running error bound, in any
/// precision: the error-free transformations come from the scalar's
/// [`ErrorFree`](crate::scalar::ErrorFree) hook, so in `Mp<BITS>` the result is as accurate as de
/// Casteljau at `2·BITS` bits (the paper's theorem holds for any binary
/// precision with round to nearest).
///
/// **Bound**: the correction `ĉ` approximates the exact error `C` of the plain
/// result, which satisfies `C_i' = w_i + (1 − t) C_i + t C_{i+1}` exactly;
/// `ĉ` is computed in [`Running`] arithmetic with `1 − t = r ± |ρ|` and the
/// exact `π₁, π₂, σ` (each `± η` for a possibly underflowed residual,
/// [`underflow_floor`](crate::scalar::ErrorFree::underflow_floor)), so its radius `ν` bounds `|ĉ − C|`; then
/// `|res − p(t)| ≤ u|res| + ν`. The bound is of order
/// `u|p(t)| + n u² Σ|b_i|B_i^n(t)`, i.e. it follows the accuracy actually
/// achieved. Valid for any finite `t` (extrapolation is flagged).
/// **Cost**: about 3× [`compensated_de_casteljau`] in f64.
///
/// ```
/// use splinelab::bernstein::{bezier::BernsteinPoly, compensated::compensated_de_casteljau_bounded};
/// use splinelab::scalar::{Mp, Real};
/// // (t − ½)³ near its triple root, in 64-bit MPFR: the plain 64-bit value
/// // has no correct digit, the compensated one is exact.
/// let c = [-0.125, 0.125, -0.125, 0.125].map(Mp::<64>::from_f64_exact).to_vec();
/// let p = BernsteinPoly::new(c).unwrap();
/// let t = Mp::<64>::from_f64_exact(0.5 + 2f64.powi(-30));
/// let e = compensated_de_casteljau_bounded(&p, &t).unwrap();
/// assert_eq!(e.value.to_f64(), 2f64.powi(-90));
/// ```
pub fn compensated_de_casteljau_bounded<T: Real>(
    poly: &BernsteinPoly<T>,
    t: &T,
) -> Result<Evaluation<T>, BezierError> {
    let extrapolated = check_parameter(t)?;
    let n = poly.degree();
    let m = RoundingModel::<T>::new();
    let residual = |x: T| Running {
        value: x,
        radius: T::underflow_floor(),
    };
    let (r, rho) = T::two_sum(&T::one(), &-t.clone());
    let one_minus_t = Running {
        value: r.clone(),
        radius: rho.clone().abs(),
    };
    let tr = Running::exact(t.clone());
    let rho_r = Running::exact(rho);
    let mut b = poly.coeffs().to_vec();
    let mut c = vec![Running::exact(T::zero()); n + 1];
    for j in 1..=n {
        for i in 0..=n - j {
            let (s, pi1) = T::two_prod(&r, &b[i]);
            let (v, pi2) = T::two_prod(t, &b[i + 1]);
            let (sum, sigma) = T::two_sum(&s, &v);
            let w = m.add(
                &m.add(&residual(pi1), &residual(pi2)),
                &Running::exact(sigma),
            );
            let w = m.add(&w, &m.mul(&rho_r, &Running::exact(b[i].clone())));
            // Same operation order as the unbounded routine: (w + r ĉ_i) + t ĉ_{i+1}.
            let partial = m.add(&w, &m.mul(&one_minus_t, &c[i]));
            c[i] = m.add(&partial, &m.mul(&tr, &c[i + 1]));
            b[i] = sum;
        }
    }
    let res = m.add(&Running::exact(b[0].clone()), &c[0]);
    Evaluation::finish(res, extrapolated, METHOD, n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Rational;

    /// Exact value of (t − ½)ⁿ at a dyadic t.
    fn exact_power(t: f64, n: u32) -> Rational {
        use rug::ops::Pow;
        (Rational::from_f64(t).unwrap() - Rational::from((1, 2))).pow(n as i32)
    }

    fn half_power(n: usize) -> BernsteinPoly<f64> {
        // (t − ½)ⁿ = Σ (−½)ⁿ⁻ⁱ (½)ⁱ B_iⁿ(t).
        let c = (0..=n)
            .map(|i| if (n - i).is_multiple_of(2) { 1.0 } else { -1.0 } * 0.5f64.powi(n as i32));
        BernsteinPoly::new(c.collect()).unwrap()
    }

    #[test]
    fn running_bound_encloses_exact_value_near_multiple_root() {
        let p = half_power(9);
        for k in 1..200 {
            let t = 0.5 + (k as f64 - 100.0) * 1e-4;
            let e = compensated_de_casteljau_bounded(&p, &t).unwrap();
            assert_eq!(e.value, compensated_de_casteljau(&p, t).unwrap());
            let err = (Rational::from_f64(e.value).unwrap() - exact_power(t, 9)).abs();
            assert!(err <= Rational::from_f64(e.bound).unwrap(), "t = {t}");
        }
    }
}
