//! The slow path of a prefilter whose samples hold a missing (non-finite)
//! one, by the filter's [`NanPolicy`]: fill, filter by the route, mark the
//! policy's pattern; and the bound [`NanPolicy::Local`] certifies outside
//! its reach ([`local_bound`]). Apart from [`super::nan_policy`] (the
//! policy, its reach and masks), which the [`LineFilter`] carries, so that
//! the filter and the policy do not name each other.

use super::NdimageError;
use super::line_filter::LineFilter;
use super::mode::Mode;
use super::nan_policy::{
    NanPolicy, dilate, fill_missing, first_non_finite, max_finite, missing, spread, write_nan,
};
use super::samples::{Sample, Stored};
use crate::scalar::Real;
use ndarray::{ArrayBase, ArrayD, Data, DataMut, Dimension};

/// The bound of [`NanPolicy::Local`] per unit of `max|finite sample|`
/// outside the reach, over `axes` filtered axes: `(A + b)^k − (A − b)^k`
/// with `A` the amplification and `b` the certified tail of `filter`
/// (module documentation); `0` for the exact route, where nothing is
/// certified.
///
/// ```
/// use splinelab::prelude::*;
/// use splinelab::ndimage::missing::local_bound;
/// let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Truncated { tol: 1e-12 }).unwrap();
/// let (b, a) = (f.bound(), f.recursive().amplification());
/// assert!((local_bound(&f, 1) - 2.0 * b).abs() <= 1e-30);
/// assert!(local_bound(&f, 2) <= 4.0 * a * b * (1.0 + 1e-12) && local_bound(&f, 2) > 0.0);
/// ```
pub fn local_bound<T: Real>(filter: &LineFilter<T>, axes: usize) -> f64 {
    let b = filter.bound();
    if b == 0.0 || axes == 0 {
        return 0.0;
    }
    let a = filter.recursive().amplification().to_f64();
    // (A + b)^k − (A − b)^k = 2 Σ_{odd j} C(k, j) A^{k−j} b^j, summed without
    // cancellation.
    let k = axes as i32;
    let mut sum = 0.0;
    let mut binom = 1.0;
    for j in 1..=k {
        binom = binom * f64::from(k - j + 1) / f64::from(j);
        if j % 2 == 1 {
            sum += 2.0 * binom * a.powi(k - j) * b.powi(j);
        }
    }
    sum
}

/// Whether the constant `grid-constant` extends with is missing.
pub(crate) fn cval_missing<T: Real>(filter: &LineFilter<T>) -> bool {
    filter.mode() == Mode::GridConstant && !filter.cval().is_finite()
}

/// The slow path of a prefilter whose samples `src` hold a non-finite one,
/// by the filter's policy: refused ([`NanPolicy::Raise`]); or the missing
/// samples filled with 0 into `out`, filtered along `axes` by `run` (the
/// caller's route: the N-D prefilter's axes, or one long line), and NaN
/// written where the policy's pattern says ([`spread`] for scipy's,
/// [`dilate`] by the certified half-width for [`NanPolicy::Local`]).
/// Kept here, not in a route, so that every route reaches it without the
/// routes naming each other.
pub(crate) fn fill_filter_mark<T, E, O, S1, S2, D>(
    src: &ArrayBase<S1, D>,
    out: &mut ArrayBase<S2, D>,
    axes: &[usize],
    filter: &LineFilter<T>,
    run: impl FnOnce(&mut ArrayBase<S2, D>) -> Result<(), NdimageError>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Stored<T>,
    S1: Data<Elem = E>,
    S2: DataMut<Elem = O>,
    D: Dimension,
{
    let mask = fill(src, out, axes.len(), filter)?;
    run(out)?;
    write_nan(out, &pattern(&mask, axes, filter, 0));
    Ok(())
}

/// The first half of [`fill_filter_mark`]: refused by
/// [`NanPolicy::Raise`] (naming the first missing sample), the finite
/// samples' magnitude checked for `axes` filtered axes, then `src` into
/// `out` with its missing samples 0 (read into `T`, stored as `O`);
/// returns their mask.
pub(crate) fn fill<T, E, O, S1, S2, D>(
    src: &ArrayBase<S1, D>,
    out: &mut ArrayBase<S2, D>,
    axes: usize,
    filter: &LineFilter<T>,
) -> Result<ArrayD<bool>, NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Stored<T>,
    S1: Data<Elem = E>,
    S2: DataMut<Elem = O>,
    D: Dimension,
{
    if filter.nan_policy() == NanPolicy::Raise {
        first_non_finite::<T, _, _, _>(src)?;
    }
    filter.check_magnitude_for::<O>(max_finite::<T, _, _, _>(src), axes)?;
    fill_missing(src, out);
    Ok(missing::<T, _, _, _>(src))
}

/// The second half: where the coefficients along `axes` of samples whose
/// missing ones are `mask` are NaN by the filter's policy, on the layout
/// grown by `pad` beyond each end of every axis in `axes` (0: the grid;
/// more: [`padded_coefficients`](super::nd_prefilter::padded_coefficients),
/// which filters every axis). Where a missing sample's reach is finite,
/// `mask` dilated by it, folded by the mode ([`dilate`]): 0 without poles
/// (degrees 0 and 1: the coefficients are the samples, as scipy copies
/// them), the certified half-width under [`NanPolicy::Local`]. Otherwise
/// scipy's lines ([`spread`]), which are constant along `axes`, so a
/// padded layout extends them by their edges.
pub(crate) fn pattern<T: Real>(
    mask: &ArrayD<bool>,
    axes: &[usize],
    filter: &LineFilter<T>,
    pad: usize,
) -> ArrayD<bool> {
    let reach = match filter.nan_policy() {
        _ if filter.recursive().poles().is_empty() => Some(0),
        NanPolicy::Local => filter.half_width(),
        _ => None,
    };
    match reach {
        Some(0) if pad == 0 => mask.clone(),
        Some(n) => dilate(mask, axes, n, filter.mode(), cval_missing(filter), pad),
        None if pad == 0 => spread(mask, axes),
        None => dilate(&spread(mask, axes), axes, 0, Mode::Nearest, false, pad),
    }
}
