//! The curves of seed 002 (Takayama, *Curves*): cubic Hermite segments,
//! rational Bézier curves (exact circular arcs), Catmull–Rom splines by the
//! Barry–Goldman pyramid, and adaptive flattening of Bézier curves by
//! de Casteljau subdivision; and the curves and surfaces of seed 000 built on
//! the S-spline basis of [`sspline`](crate::sspline): [`sspline_curve`],
//! [`sspline_surface`], and the global cubic interpolant they are compared
//! with ([`global_cubic`]).
//!
//! All share one [`CurveError`]. The dependency runs one way: this module
//! uses `sspline`'s coefficients and [`SsplineError`]; `sspline` (basis,
//! coefficients, prefilter engine) never names a curve.
//!
//! Polynomial Bézier curves themselves ([`Bezier`](crate::bernstein::bezier::Bezier)),
//! tensor Bézier patches ([`Patch`](crate::surface_deformation::patch::Patch)) and
//! B-splines / NURBS ([`bspline`](crate::bspline)) live in their own modules
//! and are reused here, never re-implemented.
//!
//! All objects are generic over the scalar ([`Real`](crate::scalar::Real))
//! and the dimension `D` (2-D and 3-D points are `SVector<T, 2>` / `SVector<T, 3>`).

pub mod bezier_pieces;
pub mod catmull_rom;
pub mod flatten;
pub mod global_cubic;
pub mod greedy_flatten;
pub mod hermite;
pub mod rational_bezier;
pub mod sspline_curve;
pub mod sspline_surface;

use crate::bernstein::bezier::BezierError;
use crate::bspline::de_boor::BSplineError;
use crate::param_curve::OutOfDomain;
use crate::sspline::SsplineError;
use crate::validation::InputError;

/// Why a curve or surface of this module (seed 002's, or an S-spline curve
/// or surface) could not be built, evaluated or edited.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CurveError {
    /// Too few points, or a point, tangent or scalar input that is not finite.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A weight is zero, negative or not finite.
    #[error("weight {index} = {value} is not a positive finite number")]
    BadWeight {
        /// Position of the weight.
        index: usize,
        /// Its value (as f64).
        value: f64,
    },
    /// Points and weights have different counts.
    #[error("{points} points but {weights} weights")]
    LengthMismatch {
        /// Number of points.
        points: usize,
        /// Number of weights.
        weights: usize,
    },
    /// The denominator of a rational curve is not positive at this parameter.
    #[error("the weight function of the rational curve is not positive at t = {t}")]
    VanishingDenominator {
        /// The parameter (as f64).
        t: f64,
    },
    /// Two consecutive points coincide: the chordal/centripetal knot interval
    /// `|P_k − P_{k−1}|^α` is zero and the pyramid would divide by zero.
    #[error("points {index} and {next} coincide: zero chord under non-uniform knot spacing")]
    CoincidentPoints {
        /// First point of the zero chord.
        index: usize,
        /// Second point (the next one, cyclically for closed curves).
        next: usize,
    },
    /// A parameter is outside the curve's domain.
    #[error(transparent)]
    OutOfDomain(#[from] OutOfDomain),
    /// A value is outside its documented range.
    #[error("{name} = {value} is outside {range}")]
    OutOfRange {
        /// Which input.
        name: &'static str,
        /// Its value (as f64).
        value: f64,
        /// The accepted range.
        range: &'static str,
    },
    /// The flatness tolerance is below what the precision can honour.
    #[error("tolerance {tol:e} is below the rounding floor {floor:e} of this precision and curve")]
    ToleranceBelowRounding {
        /// The requested tolerance.
        tol: f64,
        /// The smallest honourable tolerance.
        floor: f64,
    },
    /// The wrong degree for a conversion.
    #[error("expected a Bézier curve of degree {expected}, got degree {got}")]
    Degree {
        /// Required degree.
        expected: usize,
        /// Given degree.
        got: usize,
    },
    /// Subdivision did not reach the tolerance within the depth limit.
    #[error("adaptive subdivision exceeded depth {0}")]
    DepthExceeded(usize),
    /// An error of the underlying Bézier code.
    #[error(transparent)]
    Bezier(#[from] BezierError),
    /// S-spline: more basis order than data points.
    #[error("order {order} exceeds the number of data points {points}")]
    OrderTooHigh {
        /// The spline order `m`.
        order: u32,
        /// Data points given.
        points: usize,
    },
    /// S-spline: an edited index is outside the data.
    #[error("point index {index} is outside 0..{len}")]
    IndexOutOfRange {
        /// The index given.
        index: usize,
        /// The number of points.
        len: usize,
    },
    /// S-spline: the operation needs a B-spline family (not Beta2).
    #[error("this operation needs a B-spline family, not {0}")]
    NotBSpline(String),
    /// S-spline: the end condition is not available here (tangents on
    /// surfaces).
    #[error("end condition not supported for surfaces: {0}")]
    Unsupported(&'static str),
    /// S-spline surface: the grid does not have `ν_u · ν_v` points.
    #[error("a {nu}×{nv} grid needs {} points, got {got}", *nu as u128 * *nv as u128)]
    GridSize {
        /// Points in `u`.
        nu: usize,
        /// Points in `v`.
        nv: usize,
        /// Points given.
        got: usize,
    },
    /// S-spline coefficient computation failed.
    #[error(transparent)]
    Sspline(#[from] SsplineError),
    /// The B-spline view of a curve could not be built.
    #[error(transparent)]
    BSpline(#[from] BSplineError),
}

/// Checks that every coordinate of every point is finite.
pub(crate) fn check_points<T: crate::scalar::Real, const D: usize>(
    points: &[nalgebra::SVector<T, D>],
) -> Result<(), CurveError> {
    Ok(crate::validation::finite_points("point", points)?)
}
