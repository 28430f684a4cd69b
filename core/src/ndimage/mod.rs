//! The N-dimensional interpolation engine in scipy.ndimage's terms: boundary
//! modes, the prefilter of a line and of an array, the parallel block
//! prefilter, and the tensor-product interpolant with batch evaluation.
//!
//! It is built on seed 000's mathematics in [`crate::sspline`] (the
//! B-spline family, its poles, the recursive and truncated 1-D prefilters,
//! the certified truncation width); the dependency runs one way, `ndimage →
//! sspline`. Its formulas, with their sources, are rows of
//! [`crate::equations`] (Unser–Aldroubi–Eden 1993 and Thévenaz–Blu–Unser
//! 2000 for the recursive filter's initial values, scipy's `ni_splines.c` and
//! `ni_interpolation.c` for the modes and the padding). The objects, one per
//! module:
//!
//! - [`mode`]: the boundary modes (scipy's names), how they extend samples
//!   and fold points;
//! - [`line_filter`]: the prefilter of one line under a mode, exact
//!   (recursive) or truncated (certified convolution), and its growth bound;
//!   [`filter_cache`]: those filters kept between calls (their poles and
//!   widths are computed in MPFR);
//! - [`nd_prefilter`]: `spline_filter1d` / `spline_filter` over an
//!   `ndarray`, lines in parallel, strided axes in vector strips;
//! - [`block_filter`]: one long line in parallel blocks whose overlap is the
//!   certified width;
//! - [`interpolant`]: the interpolant built once and evaluated at points,
//!   with derivatives, one point or many (`interpolant::batch`);
//! - [`local`]: the local route, a few points of a large array from the
//!   samples their windows need (tiles prefiltered by the certified
//!   truncated convolution);
//! - [`nan_policy`]: what non-finite samples (missing data) do —
//!   scipy's propagation, refusal, or a certified local reach;
//! - [`missing`]: the prefilter's path where samples are missing (fill,
//!   filter, mark) and `local`'s bound;
//! - [`samples`]: the element types samples are read from and results
//!   stored into (widened into the compute type, rounded once on the way
//!   out), and sources read a box at a time;
//! - [`alloc`]: work arrays allocated fallibly ([`NdimageError::OutOfMemory`]);
//! - [`error`]: [`NdimageError`], why a request was refused.
//!
//! ```
//! // One code, two precisions: the cubic interpolant of the same samples in
//! // f64 and in 256-bit MPFR agree to f64's rounding at an off-grid point.
//! use splinelab::prelude::*;
//! use ndarray::array;
//! let s = array![1.0, 5.0, 2.0, 7.0, 3.0];
//! let f = Interpolant::new(&s, Options::new(3, Mode::Mirror)).unwrap();
//! let sm = s.mapv(Mp::<256>::from_f64_exact);
//! let fm = Interpolant::new(&sm, Options::new(3, Mode::Mirror)).unwrap();
//! let x = [1.3];
//! let (v, vm) = (f.eval(&x).unwrap(), fm.eval(&x).unwrap());
//! assert!((v - vm.to_f64()).abs() < 1e-14);
//! ```

pub mod alloc;
pub mod block_filter;
pub mod error;
pub mod filter_cache;
pub mod interpolant;
mod lanes;
pub mod line_filter;
pub mod local;
pub mod missing;
pub mod mode;
pub mod nan_policy;
pub mod nd_prefilter;
pub mod samples;
mod stash;
mod window_recursion;

pub use error::NdimageError;

/// The B-spline order `m = degree + 1` of a spline of `degree` (scipy's
/// `order`), refused with [`NdimageError::Degree`] at and above
/// [`MAX_ORDER`](crate::sspline::MAX_ORDER), the first order whose poles
/// are not computed: the one home of that conversion and its limit (the
/// interpolant, the local route's spec and `nan_reach` ask here).
///
/// ```
/// use splinelab::ndimage::{NdimageError, spline_order};
/// assert_eq!(spline_order(3).unwrap(), 4);
/// assert!(matches!(spline_order(200), Err(NdimageError::Degree(200))));
/// ```
pub fn spline_order(degree: u32) -> Result<u32, NdimageError> {
    if degree >= crate::sspline::MAX_ORDER {
        return Err(NdimageError::Degree(degree));
    }
    Ok(degree + 1)
}
