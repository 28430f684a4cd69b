//! `check`: verifies a user's own numbers (prefilter coefficients, B-spline
//! and Bézier values, knot insertions, condition numbers) against references
//! computed from the user's exact inputs, independently of the splinelab
//! routines a user might be comparing against.
//!
//! One file per KIND ([`prefilter`], [`interp`], [`coeffs`], [`cond`], [`bspline_eval`],
//! [`bezier_eval`], [`knot_insertion`]) and the shared
//! pieces: the user's number format ([`format`]), the per-element errors and
//! their summary ([`summary`]), and the `p / p + 64` agreement driver that
//! certifies an MPFR reference ([`agreement`]), and the error a
//! backward-stable computation would make ([`stable_bound`]), from which the
//! default verdict comes; the interpolation conditions of the modes and
//! their solution in any precision ([`interpolation_conditions`]), which the
//! `prefilter` and `interp` references and the stable bound share. Exact kinds (Bézier, B-spline
//! values, knot insertion) use rational arithmetic and need no ladder.

pub mod agreement;
pub mod banded;
pub mod bezier_eval;
pub mod bspline_eval;
pub mod coeffs;
pub mod cond;
pub mod format;
pub mod grid_spline;
pub mod interp;
pub mod interpolation_conditions;
pub mod knot_insertion;
pub mod outcome;
pub mod prefilter;
pub mod rational_bspline;
pub mod stable_bound;
pub mod summary;

pub use agreement::{Certified, LADDER};
pub use format::UserFormat;
pub use interpolation_conditions::{EXACT_MODES, Mode, ParseMode};
pub use outcome::Outcome;
pub use stable_bound::BOUND_FACTOR;
pub use summary::{
    BoundBasis, CheckSummary, ElementError, Region, RegionSummary, Worst, WorstExcess,
};

use splinelab::sspline::SsplineError;

/// Why a check could not be run (bad input or an exhausted precision ladder).
/// A user value that is wrong, even NaN, is never an error: it is a failed
/// element of the result.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CheckError {
    /// Two inputs that must have the same length do not.
    #[error("{what}: expected {expected} values, got {got}")]
    LengthMismatch {
        /// Which input.
        what: String,
        /// The length implied by the other inputs.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// An input that must not be empty is.
    #[error("{0} is empty")]
    Empty(String),
    /// An input (not a user result) is NaN or infinite.
    #[error("{what}[{index}] is not finite ({value})")]
    NonFiniteInput {
        /// Which input.
        what: String,
        /// Its index.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A degree outside the supported range.
    #[error("degree {degree} is outside the supported range {min}..={max}")]
    DegreeOutOfRange {
        /// The degree given.
        degree: usize,
        /// Smallest accepted.
        min: usize,
        /// Largest accepted.
        max: usize,
    },
    /// The inputs do not describe a valid object (knots decreasing, …).
    #[error("invalid input: {0}")]
    Invalid(String),
    /// The S-spline family was refused.
    #[error("{0}")]
    Spline(#[from] SsplineError),
    /// Even the largest precision of the ladder did not reproduce itself.
    #[error("the reference did not agree between {low} and {high} bits: not certified")]
    NotCertified {
        /// The lower precision tried last.
        low: u32,
        /// The higher one.
        high: u32,
    },
    /// The work exceeds the check's budget.
    #[error("too large: {0}")]
    TooLarge(String),
}

/// Refuses a NaN or infinite input value.
pub fn require_finite(what: &str, xs: &[f64]) -> Result<(), CheckError> {
    match xs.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(CheckError::NonFiniteInput {
            what: what.into(),
            index,
            value: xs[index],
        }),
        None => Ok(()),
    }
}

/// Refuses two lengths that disagree.
pub fn require_len(what: &str, expected: usize, got: usize) -> Result<(), CheckError> {
    if expected == got {
        Ok(())
    } else {
        Err(CheckError::LengthMismatch {
            what: what.into(),
            expected,
            got,
        })
    }
}
