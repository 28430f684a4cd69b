//! The local route: values of the spline interpolant at a few points of a
//! large array, reading only the samples their windows need.
//!
//! The S-spline's locality (seed 000): with the half-width `n` certified
//! for a tolerance ([`certified_width`](crate::sspline::width::certified_width)),
//! a coefficient depends only on the samples within `n` of it, up to
//! `Σ_{|j|>n}|c_j| · max|s|` per axis, and a value at a point only on the
//! `(d + 1)^D` coefficients of its window. The local route groups the points
//! into tiles ([`LocalPlan`]), reads each tile's samples with a margin of
//! `n` (folded at the array's edges exactly as each mode extends the
//! samples on the global route: [`Mode::fold`](super::mode::Mode::fold);
//! scipy's 12-sample padding of `nearest` / `grid-constant` at degrees 2–5
//! through [`LocalOptions::scipy_pad`]), prefilters the tile by the
//! truncated convolution of [`Route::Convolution`](super::line_filter::Route),
//! and evaluates its points with the global route's weights and sums
//! ([`cell_weights_into`](super::interpolant::cell_weights_into), the same
//! nesting). Degrees 0 and 1 and `prefilter=False` read only each point's
//! support. Every scipy mode (`constant` and `wrap` through a
//! [`PointRule`](super::interpolant::PointRule)), degrees 0–199, any
//! [`Real`](crate::scalar::Real) compute type, any sample type
//! ([`Sample`](super::samples::Sample)), partial derivatives.
//!
//! **Accuracy.** Against the global route's exact coefficients each
//! coefficient is within `((A + b)^D − A^D) · max|s|` (`A` the
//! amplification, `b` the certified per-axis bound, [`LocalSpec::bound`]),
//! plus the rounding of the two routes; values, a combination of
//! non-negative weights summing to one, within the same. With `tol=None`
//! the half-width is certified for [`default_tol`] (below the global
//! route's own rounding error, [`route`]'s documentation).
//!
//! **The same bits whatever the source or the chunking**: every
//! coefficient is computed by the same operations whichever tile holds it
//! ([`coef_box`]'s documentation), so an in-memory array, a memory map and
//! blocks fetched from an array-like give the same values, whatever the
//! tile size or the chunking.
//!
//! **Missing samples** ([`NanPolicy`](super::nan_policy::NanPolicy)): on
//! this route a missing sample reaches only the points whose windows read
//! it (a coefficient within `n` of it on every axis, a point whose window
//! holds such a coefficient) — also under `propagate`, where the global
//! route makes every coefficient of a line through it non-finite; samples
//! no window reads are never looked at (`raise` refuses only a missing
//! sample that is read).
//!
//! **Cost**: [`route`] (the rule that chooses between the two routes).

mod axis_map;
mod coef_box;
mod gather;
mod overlay;
mod plan;
pub mod route;
mod spec;
mod spline;
#[cfg(test)]
mod tests;
mod tile_cache;

pub use plan::{LocalPlan, LocalStats};
pub use route::{RouteCost, default_tol};
pub use spec::{LocalOptions, LocalSpec};
pub use spline::{Boxes, EAGER_TILES, LocalInterpolant, UpdateStats};

use super::NdimageError;
use super::interpolant::PointRule;
use super::samples::SampleSource;
use crate::scalar::Real;
use ndarray::ArrayView2;

/// scipy's `map_coordinates` on the local route: `∂^deriv f` (values for
/// `None`) of the spline `opts` of `source` at the rows of `points`
/// (`(k, ndim)`, the transpose of scipy's layout), under `rule`; with what
/// the call read.
///
/// ```
/// use splinelab::ndimage::local::{LocalOptions, map_coordinates_local};
/// use splinelab::ndimage::interpolant::PointRule;
/// use splinelab::prelude::*;
/// let data = ndarray::Array2::from_shape_fn((200, 300), |(i, j)| ((i * 7 + j * 3) % 11) as f64);
/// let at = ndarray::array![[10.25, 20.5], [150.0, 299.0]];
/// let opts = LocalOptions::new(3, Mode::Mirror);
/// let (v, stats) = map_coordinates_local(&data, at.view(), opts, PointRule::Fold, None).unwrap();
/// let f = Interpolant::new(&data, Options::new(3, Mode::Mirror)).unwrap();
/// for (k, p) in at.rows().into_iter().enumerate() {
///     assert!((v[k] - f.eval(&p.to_vec()).unwrap()).abs() < 1e-13);
/// }
/// assert!(stats.samples_read < data.len() / 4);
/// ```
pub fn map_coordinates_local<T, S>(
    source: &S,
    points: ArrayView2<'_, f64>,
    opts: LocalOptions,
    rule: PointRule,
    deriv: Option<&[u32]>,
) -> Result<(Vec<T>, LocalStats), NdimageError>
where
    T: Real + Send + Sync,
    S: SampleSource<T> + ?Sized,
{
    let spec = LocalSpec::<T>::new(source.shape(), opts)?;
    let plan = LocalPlan::new(&spec, points, rule, None)?;
    let mut out = vec![T::zero(); points.nrows()];
    let stats = plan.evaluate(&spec, source, deriv, &mut out)?;
    Ok((out, stats))
}
