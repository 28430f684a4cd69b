//! Splines on rectilinear grids as scipy.interpolate builds them:
//! `RegularGridInterpolator` and `interpn` (methods `linear`, `slinear`,
//! `cubic`, `quintic`, `pchip`), `make_ndbspl`.
//!
//! The cubic and quintic splines are the **exact** not-a-knot
//! tensor-product interpolants — one banded solve per grid line along each
//! axis ([`GridSpline`]), where scipy solves the whole sparse system
//! iteratively to `atol = 1e-6` — with a bound on their rounding
//! ([`GridSpline::error_bound`]). Degree 1 is the multilinear interpolant,
//! evaluated on the samples themselves ([`tensor_eval`] with the samples as
//! coefficients); PCHIP is scipy's recursive construction, read locally
//! ([`pchip_eval`]).
//!
//! The objects, one per module: [`axis`] (nodes, not-a-knot knots, cells
//! and B-spline weights), [`banded_lu`] (the 1-D solves), [`grid_spline`]
//! (the coefficients and their error bound), [`multilinear`] (scipy's
//! `linear` and `nearest`, in scipy's operations), [`cardinal`] (certified
//! windows: the samples a value needs, for chunked data), [`evaluate`] (the tensor
//! product at points), [`pchip`], [`error`].
//!
//! Against [`crate::ndimage`] on a uniform grid: the same B-splines, but
//! not-a-knot ends (the spline's k-th derivative continuous across the
//! first and last `(k − 1)/2` interior nodes) where scipy.ndimage's modes
//! extend the samples (mirror, reflect, …) beyond the ends.

pub mod axis;
pub mod banded_lu;
pub mod cardinal;
pub mod error;
pub mod evaluate;
pub mod grid_spline;
pub mod layout;
pub mod multilinear;
pub mod pchip;
#[cfg(test)]
mod tests;

pub use axis::GridAxis;
pub use banded_lu::BandedLu;
pub use cardinal::{CardinalAxis, CardinalWeights, point_windows, windowed_value};
pub use error::GriddedError;
pub use evaluate::tensor_eval;
pub use grid_spline::GridSpline;
pub use layout::Layout;
pub use pchip::pchip_eval;

/// The highest (odd) degree of a grid spline (scipy's RGI stops at 5).
pub const MAX_GRID_DEGREE: usize = 15;
