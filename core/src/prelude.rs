//! Everything a user of the interpolation engine needs in scope:
//! `use splinelab::prelude::*;`.

pub use crate::ndimage::NdimageError;
pub use crate::ndimage::block_filter::BlockPrefilter;
pub use crate::ndimage::interpolant::{Interpolant, Options, map_coordinates};
pub use crate::ndimage::line_filter::{LineFilter, Route};
pub use crate::ndimage::mode::Mode;
pub use crate::ndimage::nan_policy::{LOCAL_TOL, NanPolicy, nan_reach};
pub use crate::ndimage::nd_prefilter::{spline_filter, spline_filter1d};
pub use crate::scalar::{Mp, Real};
pub use crate::sspline::SplineFamily;
pub use crate::sspline::prefilter::{PrefilterError, RecursivePrefilter};
pub use crate::sspline::width::certified_width;
