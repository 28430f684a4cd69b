//! S-splines (sampling splines) of Kuriyama–Kawai–Omura (seed 000): cardinal
//! interpolating splines built on uniform B-splines or on the Beta2-spline,
//! their coefficients, their truncation and the choice of truncation width.
//!
//! The cardinal spline `S(x) = Σ_{i∈ℤ} c_i β(x − i)` with `S(j) = δ_{0j}`
//! (eq 8–9) is built on the *centred* basis function `β` of a
//! [`SplineFamily`]. Its coefficients decay geometrically,
//! `c_i = Σ_r κ_r ξ_r^{|i|}` (eq 17), with `ξ_r` the roots in (−1, 0) of the
//! Euler–Frobenius polynomial (eq 16). The objects, one per module:
//!
//! - [`family`]: the family of basis functions (B-spline order `m`, or the
//!   cubic Beta2-spline with tension `β2`) and its validation;
//! - [`basis_window`]: the values of a basis's translates at one point, as
//!   the families evaluate them;
//! - [`bspline_uniform`]: the uniform B-spline `N_{0,m}` (eq 31) and its
//!   centred form;
//! - [`beta2`]: the Beta2-spline segments (eq 36) and the closed forms
//!   (eq 29, 38, 40; cubic eq 18);
//! - [`node_values`]: the exact node values `V_j` (eq 11, 19, 37);
//! - [`euler_frobenius`]: the polynomial (eq 16), its poles `ξ_r` and the
//!   partial-fraction weights `κ_r`;
//! - [`coefficients`](mod@coefficients): `c_i` by three independent methods;
//! - [`truncation`]: the truncated basis `S_n` (eq 10, 28) and the error
//!   measures of truncation;
//! - [`width`]: the truncation-width chooser;
//! - [`end_conditions`]: the free, periodic and end-tangent ends (eq 21–23)
//!   and the end rules of the 1-D prefilters;
//! - [`prefilter`]: the full build of interpolation coefficients from samples
//!   (exact recursive filter and truncated convolution), the two 1-D
//!   prefilters the N-D engine calls.
//!
//! The scipy.ndimage-style engine built on these (modes, N-D prefilter,
//! blocks, interpolant) is [`crate::ndimage`]; it depends on this module,
//! never the reverse.

pub mod basis_window;
pub mod beta2;
pub mod bspline_uniform;
pub mod coefficients;
pub mod end_conditions;
pub mod euler_frobenius;
pub mod family;
pub mod node_values;
pub mod prefilter;
pub mod truncation;
pub mod width;

pub use basis_window::BasisWindow;
pub use coefficients::{CoefficientMethod, coefficients};
pub use family::SplineFamily;
pub use truncation::{TruncatedBasis, TruncationAnalysis, TruncationErrors};
pub use width::{
    Criterion, WidthChoice, WidthChooser, check_tol, f64_saturation_width, truncation_width,
};

use crate::roots::RootsError;

/// Largest B-spline order accepted (the exact node values and the pole
/// computation have been exercised up to here in MPFR).
pub const MAX_ORDER: u32 = 200;

/// Largest truncation half-width accepted (2^20): beyond every width a
/// tolerance above 2^{−10^6} needs (the MPFR ladder's top), and it keeps the
/// coefficient tables and the per-point cost `O(n)` bounded.
pub const MAX_HALF_WIDTH: usize = 1 << 20;

/// Why an S-spline computation was refused or failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SsplineError {
    /// B-spline order outside `2..=200`.
    #[error("order {0} is outside the supported range 2..=200")]
    OrderOutOfRange(u32),
    /// Tension β2 negative, NaN, infinite or unparsable.
    #[error("tension β2 = {0} is invalid: it must be a finite number ≥ 0")]
    InvalidTension(String),
    /// Tolerance not in the open interval (0, 1).
    #[error("tolerance {0} is invalid: it must satisfy 0 < tol < 1")]
    InvalidTolerance(f64),
    /// A coefficient count of zero was requested.
    #[error("the number of coefficients must be at least 1")]
    ZeroCount,
    /// A truncation half-width of zero was requested.
    #[error("the truncation half-width n must be at least 1")]
    ZeroWidth,
    /// A truncation half-width above [`MAX_HALF_WIDTH`] was requested.
    #[error("the truncation half-width n = {0} exceeds the maximum {MAX_HALF_WIDTH}")]
    WidthTooLarge(usize),
    /// The node values underflow or cannot be represented in the scalar.
    #[error("node values of {family} are not representable as normal numbers in {scalar}")]
    PrecisionTooLow {
        /// The family, as text.
        family: String,
        /// The scalar type name.
        scalar: String,
    },
    /// The Euler–Frobenius root finder failed.
    #[error("pole computation failed: {0}")]
    Roots(#[from] RootsError),
    /// The poles found are not the expected number of distinct values in (−1, 0).
    #[error("expected {expected} distinct poles in (−1, 0) for {family}, found {found}")]
    PoleCount {
        /// The family, as text.
        family: String,
        /// Poles expected.
        expected: usize,
        /// Valid poles found.
        found: usize,
    },
    /// A result of the guarded computation is NaN or infinite (it is never
    /// rounded to a number).
    #[error("a coefficient or pole of {family} is not finite ({value})")]
    NonFinite {
        /// The family.
        family: String,
        /// The offending value as text.
        value: String,
    },
    /// The precision asked for plus the guard bits exceeds the widest
    /// compiled guarded precision.
    #[error(
        "{bits} bits with {guard} guard bits and {cancelled} bits of cancellation exceed the widest guarded precision {widest}"
    )]
    GuardTooWide {
        /// The target precision.
        bits: u32,
        /// Guard bits required.
        guard: u32,
        /// Bits lost to cancellation at this order.
        cancelled: u32,
        /// The widest compiled guarded precision.
        widest: u32,
    },
    /// The width search passed its limit without meeting the tolerance.
    #[error("no half-width up to {limit} meets tolerance {tol}")]
    WidthNotFound {
        /// Largest half-width examined.
        limit: usize,
        /// The tolerance.
        tol: f64,
    },
}
