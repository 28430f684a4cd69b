//! What the local route computes: [`LocalOptions`] (the caller's request,
//! scipy's words) and [`LocalSpec`] (the request resolved for one shape:
//! the truncated convolution of the certified half-width, each axis' index
//! maps, the coordinate rules).

use super::axis_map::AxisMap;
use super::route::default_tol;
use crate::ndimage::filter_cache;
use crate::ndimage::interpolant::Options;
use crate::ndimage::line_filter::{LineFilter, Route};
use crate::ndimage::mode::Mode;
use crate::ndimage::nan_policy::NanPolicy;
use crate::ndimage::{NdimageError, spline_order};
use crate::scalar::Real;
use std::sync::Arc;

/// How to build the local route of a spline: the global route's
/// [`Options`] (degree, mode, `cval`, NaN policy, and the tolerance in its
/// route: the one carrier of `tol`) plus what the Python drop-in maps
/// scipy's modes and `prefilter` onto.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalOptions {
    /// Degree `0..=199`, the engine's boundary mode (scipy's `constant` and
    /// `wrap` are the mirror spline with a
    /// [`PointRule`](crate::ndimage::interpolant::PointRule)), the constant
    /// of `grid-constant`, what non-finite samples do (module documentation
    /// of [`crate::ndimage::local`]: a missing sample reaches only the
    /// points whose windows read it), and the truncation tolerance: the
    /// local route always runs the truncated convolution, of the `tol` of
    /// [`Route::Truncated`] or [`Route::Convolution`]; [`Route::Exact`]
    /// asks for [`default_tol`] (below the global route's own rounding
    /// error). [`LocalOptions::tol`] reads it.
    pub options: Options,
    /// `false`: the array holds the coefficients (scipy's `prefilter=False`).
    pub prefilter: bool,
    /// scipy's padding of `nearest` / `grid-constant` at degrees 2–5 (12 in
    /// scipy's `map_coordinates`; 0: the exact extension). Used only with a
    /// prefilter and those two modes.
    pub scipy_pad: usize,
}

impl LocalOptions {
    /// Degree and mode, `cval = 0`, default tolerance, scipy's NaN
    /// propagation, a prefilter, the exact extension.
    pub fn new(degree: u32, mode: Mode) -> Self {
        LocalOptions {
            options: Options::new(degree, mode),
            prefilter: true,
            scipy_pad: 0,
        }
    }

    /// The tolerance asked for: that of a truncated route, `None` for
    /// [`Route::Exact`] (the default, [`default_tol`]).
    ///
    /// ```
    /// use splinelab::ndimage::local::LocalOptions;
    /// use splinelab::prelude::*;
    /// let mut o = LocalOptions::new(3, Mode::Mirror);
    /// assert_eq!(o.tol(), None);
    /// o.options.route = Route::Truncated { tol: 1e-9 };
    /// assert_eq!(o.tol(), Some(1e-9));
    /// ```
    pub fn tol(&self) -> Option<f64> {
        match self.options.route {
            Route::Exact => None,
            Route::Truncated { tol } | Route::Convolution { tol } => Some(tol),
        }
    }
}

/// [`LocalOptions`] resolved for one array shape.
#[derive(Debug, Clone)]
pub struct LocalSpec<T> {
    pub(crate) order: u32,
    pub(crate) shape: Vec<usize>,
    pub(crate) axes: Vec<AxisMap>,
    /// The truncated convolution ([`Route::Convolution`]); `None`: the
    /// coefficients are the samples (degrees 0 and 1, `prefilter=False`).
    pub(crate) filter: Option<Arc<LineFilter<T>>>,
    pub(crate) cval: T,
    pub(crate) nan_policy: NanPolicy,
    tol: Option<f64>,
}

impl<T: Real> LocalSpec<T> {
    /// The local route of `opts` on an array of `shape` (every axis at
    /// least one sample). Cost: for a prefilter one pole computation and
    /// one width choice in MPFR (about 0.1 ms each), as
    /// [`LineFilter::new`].
    ///
    /// ```
    /// use splinelab::ndimage::local::{LocalOptions, LocalSpec};
    /// use splinelab::prelude::*;
    /// let s = LocalSpec::<f64>::new(&[100, 100], LocalOptions::new(3, Mode::Mirror)).unwrap();
    /// // The default tolerance is below f64's rounding of the global route.
    /// assert!(s.bound() < 1e-16 && s.half_width() > 20);
    /// ```
    pub fn new(shape: &[usize], opts: LocalOptions) -> Result<Self, NdimageError> {
        if shape.is_empty() || shape.contains(&0) {
            return Err(NdimageError::Empty);
        }
        let requested = opts.tol();
        let (opts, prefilter, scipy_pad) = (opts.options, opts.prefilter, opts.scipy_pad);
        let order = spline_order(opts.degree)?;
        let filtered = prefilter && opts.degree >= 2;
        let (filter, tol) = if filtered {
            let tol = match requested {
                Some(t) => t,
                None => default_tol::<T>(opts.degree)?,
            };
            let route = Route::Convolution { tol };
            let f = filter_cache::line_filter(
                opts.degree,
                opts.mode,
                opts.cval,
                route,
                opts.nan_policy,
            )?;
            (Some(f), Some(tol))
        } else {
            (None, None)
        };
        let half = order as usize / 2;
        let padded =
            filtered && scipy_pad > 0 && matches!(opts.mode, Mode::Nearest | Mode::GridConstant);
        let clamp = match &filter {
            // The global route clamps beyond the exact pad; every
            // coefficient of a window beyond `n + ⌊m/2⌋ + 1` is the end one.
            Some(f) if opts.mode == Mode::Nearest => {
                let n = f.half_width().unwrap_or(0);
                Some(f.exact_pad().max(n + half + 1) as f64)
            }
            // Given coefficients: scipy leaves the point, the window reads
            // the end coefficient beyond `⌊m/2⌋ + 1`.
            None if opts.mode == Mode::Nearest && order > 2 => Some((half + 1) as f64),
            _ => None,
        };
        let axes = shape
            .iter()
            .map(|&len| {
                if padded {
                    AxisMap::scipy_padded(opts.mode, len, scipy_pad, half)
                } else {
                    AxisMap::engine(opts.mode, len, clamp)
                }
            })
            .collect();
        Ok(LocalSpec {
            order,
            shape: shape.to_vec(),
            axes,
            filter,
            cval: T::from_f64_exact(opts.cval),
            nan_policy: opts.nan_policy,
            tol,
        })
    }

    /// Number of dimensions.
    pub fn ndim(&self) -> usize {
        self.shape.len()
    }

    /// The array's shape.
    pub fn shape(&self) -> &[usize] {
        &self.shape
    }

    /// The spline degree.
    pub fn degree(&self) -> u32 {
        self.order - 1
    }

    /// The certified half-width `n` of the convolution (0 without a prefilter).
    pub fn half_width(&self) -> usize {
        self.filter
            .as_ref()
            .and_then(|f| f.half_width())
            .unwrap_or(0)
    }

    /// `Σ_{|j|>n} |c_j|`, the per-axis truncation bound (0 without a prefilter).
    pub fn bound(&self) -> f64 {
        self.filter.as_ref().map_or(0.0, |f| f.bound())
    }

    /// The tolerance the half-width was certified for (`None` without a prefilter).
    pub fn tol(&self) -> Option<f64> {
        self.tol
    }

    /// The filter's amplification `A = Σ|c_j|` (1 without a prefilter).
    pub fn amplification(&self) -> f64 {
        self.filter
            .as_ref()
            .map_or(1.0, |f| f.recursive().amplification())
    }
}
