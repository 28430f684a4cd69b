//! Error-free transformations of f64 arithmetic.
//!
//! Each returns `(s, e)` with `s` the rounded result and `e` the rounding
//! error, so that `s + e` equals the exact result (no overflow assumed).
//! References: Knuth TAOCP vol. 2 §4.2.2 (TwoSum), Dekker 1971 (FastTwoSum),
//! Ogita–Rump–Oishi, *Accurate sum and dot product*, SIAM J. Sci. Comput. 26
//! (2005) (TwoProd via fused multiply-add).

/// TwoSum (Knuth): `a + b = s + e` exactly, for any finite `a`, `b` whose sum
/// does not overflow. 6 flops, no branch.
///
/// ```
/// use splinelab::scalar::two_sum;
/// let (s, e) = two_sum(1.0, 1e-20);
/// assert_eq!((s, e), (1.0, 1e-20));
/// ```
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// FastTwoSum (Dekker): `a + b = s + e` exactly, provided `|a| ≥ |b|` (or
/// `a == 0`). 3 flops. Callers that cannot guarantee the ordering use
/// [`two_sum`].
///
/// ```
/// use splinelab::scalar::fast_two_sum;
/// // 2 + ε/4 is not representable: it rounds to 2, and the error is ε/4.
/// let (s, e) = fast_two_sum(2.0, f64::EPSILON / 4.0);
/// assert_eq!((s, e), (2.0, f64::EPSILON / 4.0));
/// ```
pub fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let e = b - (s - a);
    (s, e)
}

/// TwoProd: `a · b = p + e` exactly. Exact unless `a·b` overflows or `e`
/// underflows (needs `e_a + e_b ≥ −1022 + 53`).
///
/// With FMA compiled in (`target_feature = "fma"`) this is the fused
/// multiply-add route [`FmaProduct`] (`e = fma(a, b, −p)`, 2 flops);
/// otherwise Dekker's product [`DekkerProduct`] (17 flops), because an
/// un-inlined `f64::mul_add` is a library call that costs more than Dekker's
/// 17 inlined flops. Hot loops instead pick the route once at run time
/// ([`fma_available`]) and run a kernel generic over [`TwoProduct`] compiled
/// with FMA enabled (see `bernstein::compensated`). Both routes are exact
/// under the conditions above, so they return the same bits.
///
/// ```
/// use splinelab::scalar::two_prod;
/// let x = 1.0 + f64::EPSILON;
/// let (p, e) = two_prod(x, x); // (1+ε)² = 1 + 2ε + ε²
/// assert_eq!(p, 1.0 + 2.0 * f64::EPSILON);
/// assert_eq!(e, f64::EPSILON * f64::EPSILON);
/// ```
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    if cfg!(target_feature = "fma") {
        FmaProduct::two_prod(a, b)
    } else {
        DekkerProduct::two_prod(a, b)
    }
}

/// Whether this CPU executes `f64::mul_add` as one hardware instruction.
///
/// Compile-time when the build already targets FMA; otherwise a run-time
/// CPUID check on x86-64 (cached by `std`), always true on AArch64 (FMA is
/// part of the base ISA), false elsewhere (where `mul_add` would be a slow
/// correctly rounded software routine). **Method**: `cfg!`/CPUID as above;
/// no arithmetic. It only chooses the route: both [`FmaProduct`] and
/// [`DekkerProduct`] give the exact `two_prod` (`verify/tests/it/scalar.rs::two_prod_is_exact_on_ties`).
/// **Source**: Ogita, Rump & Oishi (2005), TwoProduct with and without FMA.
pub fn fma_available() -> bool {
    #[cfg(target_feature = "fma")]
    {
        true
    }
    #[cfg(all(
        not(target_feature = "fma"),
        any(target_arch = "x86", target_arch = "x86_64")
    ))]
    {
        std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(all(
        not(target_feature = "fma"),
        not(any(target_arch = "x86", target_arch = "x86_64"))
    ))]
    {
        cfg!(target_arch = "aarch64")
    }
}

/// One exact product route: `a · b = p + e` with `p = fl(a · b)`.
pub trait TwoProduct {
    /// `(p, e)` with `p = fl(a·b)` and `p + e = a·b` exactly (same
    /// conditions as [`two_prod`]).
    fn two_prod(a: f64, b: f64) -> (f64, f64);
}

/// TwoProd by fused multiply-add: `e = fma(a, b, −p)` (Ogita–Rump–Oishi
/// 2005, Algorithm 3.5), 2 flops. Exact on every platform (`f64::mul_add`
/// rounds once), fast only where [`fma_available`].
pub struct FmaProduct;

impl TwoProduct for FmaProduct {
    #[inline(always)]
    fn two_prod(a: f64, b: f64) -> (f64, f64) {
        let p = a * b;
        (p, a.mul_add(b, -p))
    }
}

/// Dekker's TwoProd (Dekker 1971): Veltkamp splitting into 26-bit halves,
/// whose pairwise products are exact, 17 flops. Exact under the conditions of
/// [`two_prod`] provided `|a|, |b| < 2^995` so that the split cannot overflow.
pub struct DekkerProduct;

impl TwoProduct for DekkerProduct {
    #[inline(always)]
    fn two_prod(a: f64, b: f64) -> (f64, f64) {
        let p = a * b;
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, al * bl - (((p - ah * bh) - al * bh) - ah * bl))
    }
}

/// Veltkamp's split `a = hi + lo` with `hi`, `lo` of at most 26 significant
/// bits each (factor `2^27 + 1`), so their pairwise products are exact.
#[inline(always)]
fn split(a: f64) -> (f64, f64) {
    const FACTOR: f64 = 134_217_729.0; // 2^27 + 1
    let c = FACTOR * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// Error-free transformations in a type's own arithmetic: the hook through
/// which compensated algorithms (e.g. `bernstein::compensated`) run in every
/// precision instead of f64 only.
///
/// For every implementation, `two_sum` and `two_prod` return `(r, e)` with `r`
/// the correctly rounded result and `r + e` the exact one, barring overflow
/// and, for `two_prod`, a residual below the underflow threshold (then `e` is
/// off by at most [`ErrorFree::underflow_floor`]).
pub trait ErrorFree: Sized {
    /// `a + b = s + e` exactly (Knuth's TwoSum for binary floating point
    /// with round to nearest).
    fn two_sum(a: &Self, b: &Self) -> (Self, Self);
    /// `a · b = p + e` exactly, `p = fl(a · b)`.
    fn two_prod(a: &Self, b: &Self) -> (Self, Self);
    /// Largest absolute error of an underflowed `two_prod` residual: the
    /// smallest positive normal number (0 for MPFR, whose exponent range
    /// makes underflow unreachable here).
    fn underflow_floor() -> Self;
}

impl ErrorFree for f64 {
    fn two_sum(a: &f64, b: &f64) -> (f64, f64) {
        two_sum(*a, *b)
    }
    fn two_prod(a: &f64, b: &f64) -> (f64, f64) {
        two_prod(*a, *b)
    }
    fn underflow_floor() -> f64 {
        f64::MIN_POSITIVE
    }
}

impl ErrorFree for f32 {
    fn two_sum(a: &f32, b: &f32) -> (f32, f32) {
        let s = a + b;
        let bb = s - a;
        (s, (a - (s - bb)) + (b - bb))
    }
    /// The 48-bit product of two f32 is exact in f64, and its residual after
    /// rounding to f32 has at most 24 significant bits: both steps are exact.
    fn two_prod(a: &f32, b: &f32) -> (f32, f32) {
        let exact = f64::from(*a) * f64::from(*b);
        let p = exact as f32;
        (p, (exact - f64::from(p)) as f32)
    }
    fn underflow_floor() -> f32 {
        f32::MIN_POSITIVE
    }
}

#[cfg(test)]
mod tests {
    use crate::scalar::{Mp, Real};
    use rug::Rational;

    /// `r + e` equals the exact rational result.
    fn exact<T: Real>(r: &T, e: &T) -> Rational {
        r.to_rational().unwrap() + e.to_rational().unwrap()
    }

    fn check<T: Real>(a: f64, b: f64) {
        let (x, y) = (T::from_f64_exact(a), T::from_f64_exact(b));
        let (qa, qb) = (x.to_rational().unwrap(), y.to_rational().unwrap());
        let (s, e) = T::two_sum(&x, &y);
        assert_eq!(
            exact(&s, &e),
            Rational::from(&qa + &qb),
            "{} two_sum",
            T::type_name()
        );
        assert_eq!(s, x.clone() + &y);
        let (p, e) = T::two_prod(&x, &y);
        assert_eq!(
            exact(&p, &e),
            Rational::from(&qa * &qb),
            "{} two_prod",
            T::type_name()
        );
        assert_eq!(p, x * &y);
    }

    #[test]
    fn every_precision_transforms_without_error() {
        let pairs = [
            (1.0 + f64::EPSILON, 1.0 - f64::EPSILON / 2.0),
            (1e16, 1.0 + 3.0 * f64::EPSILON),
            (-0.1, 0.3),
            (3.0_f64.sqrt(), -(2.0_f64.sqrt())),
            (1.0 / 3.0, 7.0 / 11.0),
        ];
        for (a, b) in pairs {
            check::<f64>(a, b);
            check::<f32>(a, b);
            check::<Mp<64>>(a, b);
            check::<Mp<256>>(a, b);
        }
    }
}
