//! Why the N-D engine refused a request or failed: [`NdimageError`].

use super::mode::Mode;
use crate::sspline::prefilter::PrefilterError;
use crate::validation::NonFiniteValue;

/// Why a prefilter, interpolation or resampling request of the engine was
/// refused or failed. The 1-D prefilters' own failures (an ill-conditioned
/// scalar, an unsupported end rule, the poles) arrive as
/// [`NdimageError::Prefilter`]; empty and non-finite data keep their own
/// variants whichever layer finds them.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NdimageError {
    /// No samples.
    #[error("the signal is empty")]
    Empty,
    /// A sample is NaN or infinite under
    /// [`NanPolicy::Raise`](super::nan_policy::NanPolicy::Raise): the first
    /// one, its flat index in the array's logical order and its value.
    #[error("sample {index} is not finite ({value})")]
    NonFinite {
        /// Flat index in logical (C) order.
        index: usize,
        /// What it holds.
        value: NonFiniteValue,
    },
    /// [`NanPolicy::Local`](super::nan_policy::NanPolicy::Local) without a
    /// tolerance: the exact recursive prefilter carries a missing sample
    /// along the whole line, so no finite reach exists.
    #[error(
        "nan_policy \"local\" needs a tolerance (tol): the exact prefilter (tol=None) spreads a missing \
         sample along its whole line, so there is no finite reach; give tol (e.g. 1e-12) or use \"propagate\""
    )]
    LocalNeedsTol,
    /// Samples so large that the coefficients could overflow the scalar.
    #[error(
        "samples up to {max:e} could overflow: the filter forms values up to {growth:e} × max|s| per axis; \
         scale the data below {limit:e}, use a lower degree, or compute in MPFR (the command \
         line's --prec BITS, an Mp scalar in Rust)"
    )]
    Overflow {
        /// The largest |sample| (or |cval|).
        max: f64,
        /// The filter's growth bound ([`crate::ndimage::line_filter::LineFilter::growth`]).
        growth: f64,
        /// The largest safe |sample|.
        limit: f64,
    },
    /// A degree whose filter's growth bound alone exceeds the scalar's
    /// range along `axes` axes (no data is safe): `fits` a lower degree that
    /// the data fits, if any; MPFR has the range for any degree.
    #[error("{}", describe_degree_range(*degree, *axes, *bits, *fits))]
    DegreeRange {
        /// The degree asked for.
        degree: u32,
        /// The axes filtered.
        axes: usize,
        /// The scalar's significand bits (24: f32, 53: f64).
        bits: u32,
        /// A degree whose filter the data fits (the largest such, as found by bisection).
        fits: Option<u32>,
    },
    /// A point has the wrong number of coordinates.
    #[error("a point has {got} coordinates, the array has {expected} dimensions")]
    PointDimension {
        /// Dimensions of the interpolant.
        expected: usize,
        /// Coordinates given.
        got: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("coordinate {0} is not finite")]
    NonFiniteCoordinate(usize),
    /// A derivative above the degree was asked for.
    #[error("derivative order {order} exceeds the degree {degree}")]
    DerivativeTooHigh {
        /// The derivative order asked for.
        order: u32,
        /// The spline degree.
        degree: u32,
    },
    /// An output buffer of the wrong length.
    #[error("output buffer holds {got} values, {expected} are needed")]
    BufferLength {
        /// Values needed.
        expected: usize,
        /// Buffer length.
        got: usize,
    },
    /// An axis outside the array.
    #[error("axis {axis} is out of range for an array of {ndim} dimensions")]
    Axis {
        /// The axis.
        axis: usize,
        /// Dimensions of the array.
        ndim: usize,
    },
    /// A box of samples asked of a [`SampleSource`](super::samples::SampleSource)
    /// that does not lie inside the array.
    #[error("the box {lo:?}..{hi:?} is not inside an array of shape {shape:?}")]
    BoxOutside {
        /// First index of the box on each axis.
        lo: Vec<usize>,
        /// One past the last index on each axis.
        hi: Vec<usize>,
        /// The array's shape.
        shape: Vec<usize>,
    },
    /// A box of samples that no fetched block holds
    /// ([`Blocks`](super::samples::Blocks)).
    #[error("the box {lo:?}..{hi:?} was not fetched")]
    NotFetched {
        /// First index of the box on each axis.
        lo: Vec<usize>,
        /// One past the last index on each axis.
        hi: Vec<usize>,
    },
    /// A work array or a result that cannot be allocated (the allocator
    /// refused, or its size overflows): Python's `MemoryError`.
    #[error("cannot allocate {bytes} bytes for {what}")]
    OutOfMemory {
        /// The bytes asked for (`usize::MAX` where the size overflows).
        bytes: usize,
        /// What the memory was for.
        what: &'static str,
    },
    /// A degree outside `0..=199` (degree 0: nearest, 1: linear).
    #[error("degree {0} is outside the supported range 0..=199")]
    Degree(u32),
    /// The 1-D prefilter failed (ill-conditioned scalar, end rule, poles).
    #[error(transparent)]
    Prefilter(PrefilterError),
    /// A tile cache budget below one tile of coefficients
    /// ([`LocalInterpolant`](super::local::LocalInterpolant)).
    #[error(
        "cache_bytes={budget} is too small for one tile of coefficients: the smallest that works is {smallest}"
    )]
    CacheTooSmall {
        /// The budget asked for.
        budget: usize,
        /// One tile's bytes.
        smallest: usize,
    },
    /// A sample source of another shape than the spline's.
    #[error("the samples have shape {got:?}, the spline was built for {expected:?}")]
    SourceShape {
        /// The spline's shape.
        expected: Vec<usize>,
        /// The source's shape.
        got: Vec<usize>,
    },
    /// An index outside the array (numpy's words).
    #[error("index {index} is out of bounds for axis {axis} with size {len}")]
    IndexOutside {
        /// The index.
        index: usize,
        /// The axis.
        axis: usize,
        /// The axis' length.
        len: usize,
    },
    /// A prefilter asked for under a mode that is not one of the
    /// symmetric ones the coefficients are computed with (scipy's filter
    /// rules: mirror, reflect, grid-wrap).
    #[error("the prefilter's mode {0} is not one of mirror, reflect, grid-wrap")]
    FilterMode(Mode),
}

fn describe_degree_range(degree: u32, axes: usize, bits: u32, fits: Option<u32>) -> String {
    let scalar = if bits <= 24 { "float32" } else { "float64" };
    let plural = if axes == 1 { "axis" } else { "axes" };
    let lower = match fits {
        Some(d) => format!("degree {d} and below fit {scalar} for this data"),
        None => format!("no degree above 1 fits {scalar} for this data"),
    };
    format!(
        "degree {degree} cannot be filtered in {scalar} along {axes} {plural}: the bound on its \
         filter's growth exceeds {scalar}'s range whatever the data; {lower}, and MPFR fits every \
         degree (the command line's --prec BITS, an Mp scalar in Rust)"
    )
}

impl From<PrefilterError> for NdimageError {
    /// Empty and non-finite data keep the engine's own variants, so a caller
    /// matches one variant whichever layer found the sample.
    fn from(e: PrefilterError) -> Self {
        match e {
            PrefilterError::Empty => NdimageError::Empty,
            PrefilterError::NonFinite { index, value } => NdimageError::NonFinite { index, value },
            other => NdimageError::Prefilter(other),
        }
    }
}

impl From<crate::sspline::SsplineError> for NdimageError {
    fn from(e: crate::sspline::SsplineError) -> Self {
        NdimageError::Prefilter(PrefilterError::Sspline(e))
    }
}
