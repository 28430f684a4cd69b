//! Why a gridded spline was refused: [`GriddedError`].

use crate::ndimage::NdimageError;

/// Why a rectilinear-grid spline could not be built or evaluated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GriddedError {
    /// The spline degree is not odd, or above [`super::MAX_GRID_DEGREE`].
    #[error("degree {0} is not supported: the not-a-knot grid spline takes odd degrees 1..={max}", max = super::MAX_GRID_DEGREE)]
    Degree(usize),
    /// An axis has fewer nodes than the degree needs (`degree + 1`).
    #[error("axis {axis} has {got} points, but degree {degree} needs at least {need}")]
    TooFewPoints {
        /// The axis.
        axis: usize,
        /// Its number of nodes.
        got: usize,
        /// The degree asked for.
        degree: usize,
        /// `degree + 1`.
        need: usize,
    },
    /// Nodes not finite or not strictly ascending.
    #[error("the points of axis {axis} must be finite and strictly ascending (node {index})")]
    NotAscending {
        /// The axis.
        axis: usize,
        /// The first offending node.
        index: usize,
    },
    /// The values' shape does not match the grid (plus one trailing axis).
    #[error("values of shape {got:?} do not match the grid {grid:?} (plus one trailing axis)")]
    Shape {
        /// The grid's lengths.
        grid: Vec<usize>,
        /// The values' shape.
        got: Vec<usize>,
    },
    /// A point has the wrong number of coordinates, or `nu` the wrong length.
    #[error("expected {expected} coordinates per point, got {got}")]
    Dimension {
        /// Grid dimensions.
        expected: usize,
        /// Coordinates given.
        got: usize,
    },
    /// The 1-D collocation matrix of an axis is singular in working precision.
    #[error(
        "the collocation matrix of axis {axis} is singular in working precision (pivot {index})"
    )]
    Singular {
        /// The axis.
        axis: usize,
        /// The zero pivot's row.
        index: usize,
    },
    /// A work array or the coefficients could not be allocated (Python: `MemoryError`).
    #[error(transparent)]
    Alloc(#[from] NdimageError),
}
