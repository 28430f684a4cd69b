//! Quaternion-integral (QI) curves and G2 interpolation of 3D points
//! (Miura–Sakiyama, seed 004).
//!
//! A QI segment is `C(t) = P + l ∫₀ᵗ q(τ) v_x q(τ)⁻¹ dτ`, `0 ≤ t ≤ 1` (eq 2),
//! with `q = cos β + v̂ sin β`, `v̂ = (0, 0, cos α, sin α)` (eq 3–4) and `α, β`
//! quadratic Bernstein polynomials (eq 12–13). The curve has unit speed in
//! `s = l t`, so `l` is its arc length, and its tangent is the closed form
//! [`tangent::tangent`] `T(α, β) = (cos 2β, sin α sin 2β, −cos α sin 2β)`.
//!
//! [`interpolate::interpolate`] solves the paper's G2 system (eq 18–22) for
//! `n` segments through `n + 1` points by Newton's method with the exact
//! Jacobian of the discretised system (derivatives under the integral sign,
//! evaluated by the same Gauss–Legendre rule), optionally damped.
//!
//! Modules: [`quaternion`] (the paper's `q`, the rotation), [`tangent`]
//! (closed form, partial derivatives, the `(α, β)` chart and its branches),
//! [`segment`] (one segment: position, curvature), [`circle_tangent`] (end
//! conditions), [`cubic_spline`] (comparison spline and starting guess),
//! [`g2_system`] (residual and Jacobian), [`newton`] (the solver),
//! [`interpolate`](mod@interpolate) (the whole procedure).

pub mod circle_tangent;
pub mod cubic_spline;
pub mod g2_system;
pub mod interpolate;
pub mod newton;
pub mod quaternion;
pub mod segment;
pub mod tangent;

use crate::quadrature::QuadratureError;
use crate::scalar::Real;
use crate::validation::InputError;
use thiserror::Error;

pub use interpolate::{QiInterpolation, QiOptions, interpolate};
pub use newton::{Iteration, NewtonFailure};
pub use segment::QiSegment;

/// Why a QI construction or interpolation failed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum QiError {
    /// Too few points (the G2 system needs 3: two segments' worth of end
    /// conditions come from circles through three points), or a point with a
    /// NaN or infinite coordinate.
    #[error(transparent)]
    Input(#[from] InputError),
    /// Consecutive points coincide (chord length zero at working precision).
    #[error("points {index} and {next} coincide", next = index + 1)]
    CoincidentPoints {
        /// Index of the first of the two points.
        index: usize,
    },
    /// A tangent direction is zero, NaN or infinite.
    #[error("the {which} tangent is zero or not finite")]
    InvalidTangent {
        /// `"start"`, `"end"` or `"direction"`.
        which: &'static str,
    },
    /// An option is out of range.
    #[error("invalid option {name}: {why}")]
    InvalidOption {
        /// Option name.
        name: &'static str,
        /// What is wrong with it.
        why: String,
    },
    /// The quadrature could not reach the requested tolerance.
    #[error(transparent)]
    Quadrature(#[from] QuadratureError),
    /// Newton's method failed; the residual history (2-norms, rounded to
    /// f64, one per iterate starting with the initial guess) is kept.
    #[error(
        "Newton failed ({reason}) after {iterations} iterations, last residual {last:e}",
        iterations = residuals.len().saturating_sub(1),
        last = residuals.last().copied().unwrap_or(f64::NAN)
    )]
    NotConverged {
        /// Why it stopped.
        reason: NewtonFailure,
        /// `‖F(x_k)‖₂` for every iterate `k = 0, 1, …`.
        residuals: Vec<f64>,
        /// `‖Δx_k‖₂` of every step taken.
        steps: Vec<f64>,
    },
}

/// `x` is finite and `> 0` (false for NaN: the tests on user input must
/// reject NaN, which a negated `x <= 0` would let through).
pub(crate) fn finite_positive<T: Real>(x: &T) -> bool {
    x.is_finite() && *x > T::zero()
}
