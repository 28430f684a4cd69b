//! Line filters kept between calls. Building a [`LineFilter`] computes its
//! poles in MPFR, and for a tolerance its certified width (and for the
//! convolution its weights), about 0.1 ms each: as long as filtering 10⁴
//! samples, and far longer than a whole call on a small array (issue 50:
//! `map_coordinates` of 25 points on 43² costs scipy 24 µs). Every caller
//! that builds one per call (the interpolant, the local route's spec, the
//! Python package's filters) asks [`line_filter`] instead: keyed by the
//! scalar type, degree, mode, `cval`, route and NaN policy; at most
//! [`CAPACITY`] kept (cleared when full). A filter is immutable once built,
//! so a kept one is the same filter bit for bit.

use super::NdimageError;
use super::line_filter::{LineFilter, Route};
use super::mode::Mode;
use super::nan_policy::NanPolicy;
use crate::scalar::Real;
use crate::sspline::SplineFamily;
use std::any::{Any, TypeId};
use std::cell::RefCell;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// Filters kept at once: a program that tries many settings keeps the
/// last ones, not one filter per setting ever asked for.
pub const CAPACITY: usize = 64;

type Key = (TypeId, u32, Mode, u64, Option<(bool, u64)>, NanPolicy);
type Filters = HashMap<Key, Arc<dyn Any + Send + Sync>>;

static FILTERS: OnceLock<Mutex<Filters>> = OnceLock::new();

thread_local! {
    /// The filter this thread was given last (a kept one: the same filter
    /// as the map's for its key, which a clearing of the map leaves valid).
    static LAST: RefCell<Option<(Key, Arc<dyn Any + Send + Sync>)>> = const { RefCell::new(None) };
}

/// The filter of B-spline degree `degree` under `mode` (`cval` for
/// `grid-constant`), by `route`, with `nan_policy`
/// ([`LineFilter::new`], [`LineFilter::with_nan_policy`]), built on the
/// first call and shared after it. Errors as those two.
///
/// ```
/// use splinelab::ndimage::filter_cache::line_filter;
/// use splinelab::prelude::*;
/// use splinelab::ndimage::nan_policy::NanPolicy;
/// let a = line_filter::<f64>(3, Mode::Mirror, 0.0, Route::Exact, NanPolicy::Propagate).unwrap();
/// let b = line_filter::<f64>(3, Mode::Mirror, 0.0, Route::Exact, NanPolicy::Propagate).unwrap();
/// assert!(std::sync::Arc::ptr_eq(&a, &b));
/// ```
pub fn line_filter<T: Real>(
    degree: u32,
    mode: Mode,
    cval: f64,
    route: Route,
    nan_policy: NanPolicy,
) -> Result<Arc<LineFilter<T>>, NdimageError> {
    let tol = match route {
        Route::Exact => None,
        Route::Truncated { tol } => Some((false, tol.to_bits())),
        Route::Convolution { tol } => Some((true, tol.to_bits())),
    };
    let key = (
        TypeId::of::<T>(),
        degree,
        mode,
        cval.to_bits(),
        tol,
        nan_policy,
    );
    // The thread's last filter first: a loop of small calls asks for the
    // same one each time, and the lock and the hash were a few per cent of
    // such a call (issue 50).
    let last = LAST.with_borrow(|l| {
        l.as_ref()
            .filter(|(k, _)| *k == key)
            .map(|(_, f)| f.clone())
    });
    if let Some(f) = last.and_then(|f| f.downcast::<LineFilter<T>>().ok()) {
        return Ok(f);
    }
    let filters = FILTERS.get_or_init(|| Mutex::new(HashMap::new()));
    let hit = filters
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .get(&key)
        .cloned();
    if let Some(f) = hit {
        LAST.set(Some((key, f.clone())));
        if let Ok(f) = f.downcast::<LineFilter<T>>() {
            return Ok(f);
        }
    }
    // Degree → order and its limit in their one home (`spline_order`).
    let family = SplineFamily::order(super::spline_order(degree)?)?;
    let f = Arc::new(LineFilter::new(&family, mode, cval, route)?.with_nan_policy(nan_policy)?);
    let mut map = filters.lock().unwrap_or_else(|p| p.into_inner());
    if map.len() >= CAPACITY {
        map.clear();
    }
    map.insert(key, f.clone());
    LAST.set(Some((key, f.clone())));
    Ok(f)
}
