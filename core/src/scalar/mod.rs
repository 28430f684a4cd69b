//! The scalar abstraction: one trait bound, [`Real`], for every algorithm in
//! splinelab, implemented for `f64` and for the MPFR type [`Mp`].
//!
//! `Real` extends nalgebra's [`RealField`] (so nalgebra's LU, QR and SVD run in
//! both precisions) with what a precision study needs: the unit roundoff,
//! lossless or correctly rounded conversions, exact rationals and decimal
//! output with a requested number of significant digits.

mod eft;
mod mp;
pub mod running_error;

pub use eft::{
    DekkerProduct, ErrorFree, FmaProduct, TwoProduct, fast_two_sum, fma_available, two_prod,
    two_sum,
};
pub use mp::Mp;

/// What generic numerical code needs in scope: the scalar trait, the MPFR
/// type, and the supertraits whose methods (`pi()`, `sqrt()`, `zero()`, …)
/// are called on concrete types.
pub mod prelude {
    pub use super::{Mp, Real};
    pub use nalgebra::{ComplexField, RealField};
    pub use num_traits::{One, Zero};
}

use nalgebra::RealField;
use rug::{Float, Rational};
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Sub, SubAssign};

/// A real scalar with a known, fixed binary precision.
///
/// Implemented for `f64` (53 bits), `f32` (24 bits, for single-precision
/// data) and [`Mp<BITS>`](Mp) (`BITS` bits). The
/// precision is part of the type: no global state decides how an operation
/// rounds, so two threads computing in `Mp<128>` and `Mp<256>` never interfere.
///
/// Beyond nalgebra's owned arithmetic, `Real` guarantees arithmetic with a
/// borrowed right operand (`x * &y`, `acc += &y`): for `f64` it is the same
/// instruction, for [`Mp`] it saves the allocation a `clone()` would make.
/// (A bound on `&Self op &Self` cannot be a supertrait in today's Rust: it is
/// not implied at use sites.) [`ErrorFree`] is the hook for error-free
/// transformations, so compensated algorithms run in every precision.
pub trait Real:
    RealField
    + ErrorFree
    + for<'a> Add<&'a Self, Output = Self>
    + for<'a> Sub<&'a Self, Output = Self>
    + for<'a> Mul<&'a Self, Output = Self>
    + for<'a> Div<&'a Self, Output = Self>
    + for<'a> AddAssign<&'a Self>
    + for<'a> SubAssign<&'a Self>
    + for<'a> MulAssign<&'a Self>
    + for<'a> DivAssign<&'a Self>
{
    /// Significand precision in bits (53 for `f64`).
    const BITS: u32;

    /// Whether the precision is at most f64's (`BITS ≤ 53`: f64, f32 and
    /// narrow MPFR types): the engine's fixed-size kernels serve only these
    /// (its vector and tile kernels further only f64 and f32, chosen by
    /// type). Derived from [`Real::BITS`]; branch on it as
    /// `if const { T::FITS_F64 }` so that the compiler drops those kernels
    /// from every wider instantiation before generating code: each MPFR
    /// precision in the CLI's ladder and the checks' agreement ladder
    /// otherwise compiles clones it never runs (issue 38: the first build).
    const FITS_F64: bool = Self::BITS <= 53;

    /// Short name of the type for tables and JSON (`"f64"`, `"mp256"`).
    fn type_name() -> String;

    /// Unit roundoff `u = 2^(−BITS)`: the relative error bound of one
    /// correctly rounded operation (round to nearest).
    fn unit_roundoff() -> Self {
        Self::from_f64_exact(1.0).scale_by_pow2(-(Self::BITS as i32))
    }

    /// `x · 2^k`, exact unless it overflows or underflows.
    fn scale_by_pow2(self, k: i32) -> Self;

    /// Converts an `f64`. Exact whenever `BITS ≥ 53` (always, for the types
    /// provided here at 53 bits or more); rounds to nearest otherwise.
    fn from_f64_exact(x: f64) -> Self;

    /// Converts to `f64`, correctly rounded (round to nearest, ties to even).
    fn to_f64(&self) -> f64;

    /// Converts an exact rational, correctly rounded to this precision.
    fn from_rational(q: &Rational) -> Self;

    /// The exact rational value, `None` for NaN or infinities.
    fn to_rational(&self) -> Option<Rational>;

    /// Converts an integer exactly (`|n| < 2^BITS`), correctly rounded
    /// otherwise. (Named `from_int` because num-traits' `FromPrimitive`,
    /// also a supertrait, already has an `Option`-returning `from_i64`.)
    fn from_int(n: i64) -> Self {
        Self::from_rational(&Rational::from(n))
    }

    /// The value as an MPFR float of the same precision (lossless).
    fn to_float(&self) -> Float;

    /// Converts an MPFR float of any precision, correctly rounded to nearest;
    /// NaN stays NaN and infinities stay infinite (beyond the type's range:
    /// infinite, as IEEE rounding does).
    fn from_float(x: &Float) -> Self;

    /// This value in another precision `U`, correctly rounded (one rounding,
    /// through the lossless [`Real::to_float`]); NaN and infinities are kept.
    ///
    /// ```
    /// use splinelab::scalar::{Mp, Real};
    /// let third = Mp::<256>::from_int(1) / Mp::<256>::from_int(3);
    /// assert_eq!(third.convert::<f64>(), 1.0 / 3.0);
    /// assert!(f64::NAN.convert::<Mp<128>>().to_f64().is_nan());
    /// ```
    fn convert<U: Real>(&self) -> U {
        U::from_float(&self.to_float())
    }

    /// Decimal string with `digits` significant digits, scientific notation
    /// (e.g. `"1.602462888e13"`), or `"NaN"`, `"inf"`, `"-inf"`.
    fn to_decimal(&self, digits: usize) -> String {
        decimal_string(&self.to_float(), digits)
    }

    /// The number of significant decimal digits that this precision carries:
    /// `⌈BITS · log10 2⌉ + 1`, enough to round-trip.
    fn decimal_digits() -> usize {
        (Self::BITS as f64 * std::f64::consts::LOG10_2).ceil() as usize + 1
    }
}

/// Formats an MPFR float with `digits` significant decimal digits.
pub fn decimal_string(x: &Float, digits: usize) -> String {
    if x.is_nan() {
        return "NaN".into();
    }
    if x.is_infinite() {
        return if x.is_sign_negative() { "-inf" } else { "inf" }.into();
    }
    x.to_string_radix(10, Some(digits.max(1)))
}

impl Real for f64 {
    const BITS: u32 = 53;

    fn type_name() -> String {
        "f64".into()
    }

    fn scale_by_pow2(self, k: i32) -> Self {
        // Split the exponent so that 2^k itself never overflows.
        let half = k / 2;
        self * 2f64.powi(half) * 2f64.powi(k - half)
    }

    fn from_f64_exact(x: f64) -> Self {
        x
    }

    /// `n as f64`: exact for `|n| ≤ 2^53`, round to nearest beyond — the
    /// same value as the default route through a rational, without MPFR.
    fn from_int(n: i64) -> Self {
        n as f64
    }

    fn to_f64(&self) -> f64 {
        *self
    }

    fn from_rational(q: &Rational) -> Self {
        // `Rational::to_f64` truncates; go through a correctly rounded 53-bit
        // MPFR value instead. Exact exponent range of f64 is kept by MPFR's
        // wider range, so only subnormal results can double-round.
        Float::with_val(53, q).to_f64()
    }

    fn to_rational(&self) -> Option<Rational> {
        Rational::from_f64(*self)
    }

    fn to_float(&self) -> Float {
        Float::with_val(53, *self)
    }

    fn from_float(x: &Float) -> Self {
        x.to_f64()
    }
}

impl Real for f32 {
    const BITS: u32 = 24;

    fn type_name() -> String {
        "f32".into()
    }

    fn scale_by_pow2(self, k: i32) -> Self {
        let half = k / 2;
        self * 2f32.powi(half) * 2f32.powi(k - half)
    }

    /// Rounds to nearest (`f64 → f32` is a correctly rounded conversion).
    fn from_f64_exact(x: f64) -> Self {
        x as f32
    }

    /// `n as f32` (round to nearest, exact for `|n| ≤ 2^24`).
    fn from_int(n: i64) -> Self {
        n as f32
    }

    fn to_f64(&self) -> f64 {
        *self as f64
    }

    fn from_rational(q: &Rational) -> Self {
        Float::with_val(24, q).to_f32()
    }

    fn to_rational(&self) -> Option<Rational> {
        Rational::from_f32(*self)
    }

    fn to_float(&self) -> Float {
        Float::with_val(24, *self)
    }

    fn from_float(x: &Float) -> Self {
        x.to_f32()
    }
}
