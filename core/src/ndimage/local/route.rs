//! Which route a call takes, and with which half-width.
//!
//! **The default tolerance** ([`default_tol`]). The global route's exact
//! recursive prefilter first multiplies every sample by the gain `Λ`, one
//! rounding each: it filters `Λ s_k (1 + δ_k)`, `|δ_k| ≤ u = 2^{−BITS}`.
//! The rest of the filter is linear, and its ∞-norm over its input per unit
//! gain is the amplification `A = Σ_j |c_j| = 1/|V(−1)|`
//! ([`RecursivePrefilter::amplification`]), reached by a perturbation
//! alternating in sign (frequency π). That first rounding alone can
//! therefore move a coefficient by `u · A · max|s|` per axis, and every
//! later operation of the recursion (each pass a stable first-order
//! recursion that amplifies its own roundings by at most `1/(1 − |ξ|)`,
//! [`LineFilter`](crate::ndimage::line_filter::LineFilter)'s analysis)
//! adds to it: `u · A · max|s|` is a floor of the global route's a-priori
//! rounding error per axis. With `tol=None` the local route takes the
//! half-width certified for `tol = u·A/4` (at most 1/2), so its truncation
//! error, below `tol · max|s|` per axis, is under a quarter of that floor:
//! the answer is as accurate as the global route's. (Cubic, f64: `A = 3`,
//! `tol = 8.3e-17`, half-width 29; quintic `A = 7.5`, `tol = 2.1e-16`, half-width 45.)
//!
//! **The route by cost** ([`RouteCost`]). The local route computes, for each
//! tile of `t^D` cells that holds points, the coefficients of its box
//! (`t + d` per axis) from the samples `n` further out, axis by axis; the
//! global route prefilters all `N` samples along every axis once (and holds
//! a coefficient array of the input's size). The estimate of each in
//! nanoseconds: local `Σ_tiles (C_TAP (2n + 1) Σ_j e^{D−j} b^j + C_READ
//! e^D)` with `b = t + d`, `e = b + 2n`, for the tile edge `t` (a power of
//! two) that minimises it, plus `C_CALL` per call (its set-up); global
//! `N (C_GLOBAL D + C_COPY)`. Without a
//! prefilter (degrees 0, 1, `prefilter=False`) the local route reads each
//! point's `(d + 1)^D` support and the global route copies the array
//! (`C_COPY` per sample). Either way the local route first locates every
//! point (`C_LOCATE` each, `cval` points included), so where that alone
//! reaches the global cost nothing is located. The constants were measured on the 2-core
//! development machine (`python/bench/local_route.py`); the crossover they
//! give is quoted in the README.

use crate::ndimage::NdimageError;
use crate::ndimage::filter_cache;
use crate::ndimage::line_filter::Route;
use crate::ndimage::mode::Mode;
use crate::ndimage::nan_policy::NanPolicy;
use crate::scalar::Real;

/// Nanoseconds per convolution tap (a multiply and two adds) on the local
/// route (the taps swept over whole rows: vectorised).
pub const C_TAP: f64 = 0.25;
/// Nanoseconds per sample read and extended into a tile's work array (a
/// memory map's page faults included: a tile's rows lie on pages of their
/// own). With [`C_TAP`], a quarter of the first estimate since the box is
/// read row by row (1000 random cubic points of a 16000² memory map: 24 ms
/// measured, 23 ms estimated; 1000 quintic ones at `tol=1e-12`: 35 ms, 38 ms).
pub const C_READ: f64 = 5.0;
/// Nanoseconds per sample and axis of the global route's prefilter.
pub const C_GLOBAL: f64 = 4.0;
/// Nanoseconds per sample of the global route's copy (padding, conversion).
pub const C_COPY: f64 = 1.5;
/// Nanoseconds per sample read by a point of degree 0 or 1 evaluated in
/// place ([`map_samples_in_place`](crate::ndimage::interpolant::map_samples_in_place)),
/// beyond what the padded route's kernels spend on it. Measured (issue 50,
/// sixth session, `threads=1`, the 2-core machine, random points inside,
/// the slope between two counts): in place 7.8 / 20.7 ns a point of degree
/// 0 / 1 on 128² against 5.0 / 6.0 through the padded copy, 10.8 / 29.5
/// on 16³–64³ against 6.5 / 9.2: 2.6–4.4 ns a sample read (the in-place
/// loop of points inside at compile-time axes; it was 16.5 ns a point of
/// degree 0 before, when this was 8).
pub const C_IN_PLACE_TAP: f64 = 4.0;
/// Nanoseconds per point of the local route's bookkeeping (cell, grouping).
/// Measured (issue 42, `LocalPlan::new` alone, random points on a 2048²
/// array, the loaded 2-core machine): 0.5 µs a point at 10⁴ points, 0.63
/// µs at 10⁵, 1.9 µs at 10⁶ (its hash sets and sort leave the caches).
/// With 150 ns, the figure before, 10⁶ points on a 4096² array were
/// grouped and priced (2.4 s) before the global route (0.35 s) was taken.
pub const C_POINT: f64 = 1000.0;
/// Nanoseconds per point of locating it (its cell, whether it is a `cval`
/// point), every point, before anything is priced: the local route's
/// floor at many points. Measured (issue 42, `local_map_f64` declining 10⁴
/// linear points on a 250 × 150 array, the loaded 2-core machine): 57 ns a
/// point, spec included, where the global route's extra cost is 56 µs; it
/// is what reproject's 7875 such calls spent deciding.
pub const C_LOCATE: f64 = 50.0;

/// Nanoseconds of the local route's set-up per call, whatever its points:
/// the spec (its filter kept between calls, `filter_cache`), the plan's
/// arrays and the pricing of the tile edges, and the Python package's
/// call into it. Measured (issue 50, `python/bench/small_calls.py`'s
/// machine): `splinelab._local.try_map` forced at one point outside an 8²
/// array under `'constant'` (nothing evaluated): 1.2 µs linear, 1.5 µs
/// cubic (the engine's part 0.8 and 1.1 µs).
pub const C_CALL: f64 = 1500.0;

/// The tolerance of the local route under `tol=None` for a spline of
/// `degree ≥ 2` computed in `T` (module documentation): `u · A / 4`, at
/// most 1/2.
///
/// ```
/// use splinelab::ndimage::local::default_tol;
/// let t = default_tol::<f64>(3).unwrap();
/// assert!((t - 0.75 * 2f64.powi(-53)).abs() < 1e-30);
/// ```
pub fn default_tol<T: Real>(degree: u32) -> Result<f64, NdimageError> {
    // The exact filter kept between calls ([`filter_cache`]): its poles,
    // hence `A`, are computed in MPFR once.
    let exact = filter_cache::line_filter::<T>(
        degree,
        Mode::Mirror,
        0.0,
        Route::Exact,
        NanPolicy::Propagate,
    )?;
    let a = exact.recursive().amplification();
    let u = (-(T::BITS as f64)).exp2();
    Ok((u * a / 4.0).min(0.5))
}

/// The estimated cost of each route for one call (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RouteCost {
    /// Local route, nanoseconds (estimate).
    pub local_ns: f64,
    /// Global route, nanoseconds (estimate).
    pub global_ns: f64,
    /// The tile edge the local route would use.
    pub tile: usize,
    /// Tiles it would compute.
    pub tiles: usize,
}

impl RouteCost {
    /// Whether the local route is the cheaper.
    pub fn prefer_local(&self) -> bool {
        self.local_ns < self.global_ns
    }
}

/// The local cost of one tile of edge `t` (module documentation).
pub fn tile_ns(ndim: usize, degree: u32, n: usize, t: usize) -> f64 {
    let b = (t + degree as usize) as f64;
    let e = b + 2.0 * n as f64;
    let d = ndim as i32;
    let outputs: f64 = (1..=d).map(|j| e.powi(d - j) * b.powi(j)).sum();
    C_TAP * (2 * n + 1) as f64 * outputs + C_READ * e.powi(d)
}

/// The local route's cost before anything is priced: its set-up
/// ([`C_CALL`]) and locating `points` points ([`C_LOCATE`] each).
pub fn locate_ns(points: usize) -> f64 {
    C_CALL + points as f64 * C_LOCATE
}

/// The local route's floor for `points` points (`ndim` axes, `degree`,
/// `half_width` the prefilter's certified half-width, `None` without a
/// prefilter), from the count alone: [`locate_ns`], and where there is a
/// point at least one box evaluated, the cheapest (a tile of edge 1, or
/// without a prefilter one point's support) with its [`C_POINT`]. The
/// local route is priced at least one box whenever it has a point, also
/// where every point takes `cval` (a call whose points all lie outside
/// under `'constant'` takes the global route where the array costs less
/// than that box: small arrays only). Where the floor reaches the global
/// route's cost ([`global_ns`]) the global route is taken without a look
/// at the points; the Python package evaluates the same formula from these
/// constants before calling the engine (`splinelab._local.may_be_local`).
///
/// ```
/// use splinelab::ndimage::local::route::{C_CALL, C_LOCATE, floor_ns};
/// assert_eq!(floor_ns(2, 3, Some(29), 0), C_CALL);
/// assert!(floor_ns(2, 3, Some(29), 1) > 20_000.0 + C_CALL + C_LOCATE);
/// ```
pub fn floor_ns(ndim: usize, degree: u32, half_width: Option<usize>, points: usize) -> f64 {
    let first_box = match half_width {
        _ if points == 0 => return locate_ns(0),
        Some(n) => tile_ns(ndim, degree, n, 1),
        None => C_READ * (f64::from(degree) + 1.0).powi(ndim as i32),
    };
    locate_ns(points) + C_POINT + first_box
}

/// Whether the local route may cost less than the global one for `points`
/// points on `samples` samples of `ndim` axes, from the count alone: its
/// floor ([`floor_ns`]; `filtered`: with a prefilter, whose certified
/// half-width `half_width` gives, asked only where locating the points
/// alone does not already reach the global cost) below the global route's
/// ([`global_ns`]). A `half_width` of `None` (unknown) counts as "may".
/// The first test of `LocalPlan::new_if_local`, and the one-step common
/// call's route decision in the Python bindings.
///
/// ```
/// use splinelab::ndimage::local::route::may_be_local;
/// assert!(!may_be_local(64, 2, 3, 1, true, || unreachable!()));
/// assert!(may_be_local(4096 * 4096, 2, 3, 10, true, || Some(29)));
/// ```
pub fn may_be_local(
    samples: usize,
    ndim: usize,
    degree: u32,
    points: usize,
    filtered: bool,
    half_width: impl FnOnce() -> Option<usize>,
) -> bool {
    let global = global_ns(samples, ndim, filtered);
    if locate_ns(points) >= global {
        return false;
    }
    let n = match filtered {
        true => match half_width() {
            Some(n) => Some(n),
            None => return true,
        },
        false => None,
    };
    floor_ns(ndim, degree, n, points) < global
}

/// Whether `points` points of degree 0 or 1 (`taps = (d + 1)^ndim` samples
/// each) on `samples` samples cost less read in place than through the
/// padded copy: `points · taps · C_IN_PLACE_TAP < samples · C_COPY`. A
/// few points on an array of any size are read in place (nothing
/// proportional to it); many points on a small one take the copy, whose
/// kernels prefetch.
///
/// ```
/// use splinelab::ndimage::local::route::in_place_pays;
/// assert!(in_place_pays(32 * 32 * 32, 25, 8.0));
/// assert!(!in_place_pays(128 * 128, 8192, 1.0));
/// ```
pub fn in_place_pays(samples: usize, points: usize, taps: f64) -> bool {
    points as f64 * taps * C_IN_PLACE_TAP < samples as f64 * C_COPY
}

/// The global route's cost on `samples` samples of `ndim` axes, with a
/// prefilter or without.
pub fn global_ns(samples: usize, ndim: usize, prefilter: bool) -> f64 {
    let filter = if prefilter {
        C_GLOBAL * ndim as f64
    } else {
        0.0
    };
    samples as f64 * (filter + C_COPY)
}
