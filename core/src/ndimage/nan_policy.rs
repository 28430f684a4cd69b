//! What the engine does with samples that are not finite (NaN, ±∞: missing
//! data as scientists store it): [`NanPolicy`], and how far a missing
//! sample reaches under [`NanPolicy::Local`] ([`nan_reach`]).
//!
//! - [`NanPolicy::Propagate`] (the default, scipy.ndimage's behaviour): a
//!   non-finite sample makes every coefficient of every line through it
//!   along a filtered axis non-finite, as scipy's recursive filter does
//!   (its causal start sums the whole line, its recursions carry the value
//!   to both ends): after the prefilter along every axis (degree ≥ 2) one
//!   missing sample leaves no finite coefficient. Evaluation then carries
//!   a non-finite coefficient to every output whose window of `d + 1`
//!   coefficients per axis holds one, zero weights included (`0 · NaN` is
//!   NaN, as in scipy's C). Finite samples give the finite route's values.
//! - [`NanPolicy::Raise`]: refused, naming the first non-finite sample
//!   (flat index in logical order, and its value).
//! - [`NanPolicy::Local`] (needs a tolerance: [`Route::Truncated`](super::line_filter::Route::Truncated) or
//!   [`Route::Convolution`](super::line_filter::Route::Convolution)): the missing samples are filled with 0, the
//!   coefficients computed by the filter's route, and a coefficient is
//!   set to NaN when a missing sample lies within the certified half-width
//!   `n` of it along every filtered axis (after the mode's folding:
//!   [`Mode::fold`]). An output is then NaN exactly when its window holds
//!   such a coefficient, i.e. only within [`nan_reach`] samples of a
//!   missing one. Every other coefficient `D` differs from the exact
//!   coefficients `D*` of the samples with the missing ones filled by any
//!   values `v` with `|v| ≤ M = max|finite sample|` by at most
//!   `((A + b)^k − (A − b)^k) · M` over `k` filtered axes
//!   ([`local_bound`](super::missing::local_bound); `A = 1/|V(−1)|` the filter's amplification `Σ|c_j|`,
//!   `b = Σ_{|j|>n}|c_j|` the certified tail, [`LineFilter::bound`](super::line_filter::LineFilter::bound)): the
//!   fill enters `D` only through the taps beyond `n` on some axis (at most
//!   `A^k − (A − b)^k` of it), and the route's own truncation adds at most
//!   `(A + b)^k − A^k`. Interpolation weights are non-negative and sum to
//!   one, so outputs obey the same bound.
//!
//! The policy is carried by the [`LineFilter`](super::line_filter::LineFilter)
//! ([`LineFilter::with_nan_policy`](super::line_filter::LineFilter::with_nan_policy))
//! for the prefilters and by [`Options::nan_policy`](super::interpolant::Options)
//! for the interpolant. The check costs nothing where every sample is
//! finite: finiteness is part of the one scan of the samples every route
//! already makes (for the overflow bound); the masks, the refill and the
//! second filtering run only where a non-finite sample was found
//! ([`super::missing`]).
//!
//! Coordinates are not samples: a non-finite coordinate is refused under
//! every policy ([`NdimageError::NonFiniteCoordinate`]); scipy's own output
//! there comes from casting NaN to an integer in C (undefined behaviour),
//! which the Python drop-in reproduces.

use super::NdimageError;
use super::mode::Mode;
use super::samples::{Sample, Stored};
use crate::scalar::Real;
use crate::sspline::SplineFamily;
use crate::sspline::width::certified_width;
use crate::validation::NonFiniteValue;
use ndarray::{ArrayBase, ArrayD, Axis, Data, DataMut, Dimension, IxDyn, Zip};

/// What the engine does with non-finite samples (module documentation).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::VariantArray, strum::IntoStaticStr,
)]
#[strum(serialize_all = "lowercase")]
pub enum NanPolicy {
    /// scipy's pattern: a missing sample spreads along every filtered line.
    #[default]
    Propagate,
    /// Refused, naming the first non-finite sample.
    Raise,
    /// NaN only within the certified reach of a missing sample ([`nan_reach`]).
    Local,
}

crate::named_enum!(NanPolicy, "nan_policy");

/// The prefilter tolerance of [`NanPolicy::Local`] when the caller names
/// none: the CLI's `--nan-policy local` without `--tol` and the Python
/// package's `nan_policy="local"` default both read it, so the same call
/// gives the same NaN pattern and values from either. `local` needs a
/// finite reach, which the exact prefilter has not, so it always runs
/// truncated; at 1e-12 the truncation is below f64's rounding of
/// coefficients of order 1 and a cubic's reach is 24 ([`nan_reach`]).
pub const LOCAL_TOL: f64 = 1e-12;

/// How many samples along each axis a missing sample reaches under
/// [`NanPolicy::Local`] for a spline of `degree` and the prefilter's
/// tolerance `tol`: `r = n + ⌊d/2⌋ + 1`, with `n` the half-width certified
/// for `tol` (`Σ_{|j|>n}|c_j| < tol`, [`certified_width`], the
/// [`LineFilter::half_width`](super::line_filter::LineFilter::half_width) of the same tolerance; `n = 0` for degrees 0
/// and 1, which have no prefilter) and `⌊d/2⌋ + 1` the spline's own
/// window: an output at `x` reads the `d + 1` coefficients `i` with
/// `|x − i| ≤ (d + 1)/2`.
///
/// A coefficient is NaN when a missing sample `j` lies within `n` of it
/// (`|i − j| ≤ n` along every axis, after the mode's folding), so an output
/// at `x` can be NaN only where `|x_a − j_a| ≤ r` on every axis `a` for
/// some missing `j` (folded): the radius a chunked computation's overlap
/// must cover. **Cost**: one width search, `O(n)` MPFR terms (the
/// [`LineFilter`](super::line_filter::LineFilter) of the same tolerance makes it too). **Bound** outside
/// the reach: [`local_bound`](super::missing::local_bound). **Source**: the tail bound of seed 000
/// (`Σ_{|i|>n}|c_i| ≤ 2 Σ_r |κ_r||ξ_r|^{n+1}/(1 − |ξ_r|)`), the B-spline's
/// support `(d + 1)` (seed 000 eq 31).
///
/// ```
/// use splinelab::ndimage::nan_policy::nan_reach;
/// // Cubic at 1e-12: the certified half-width 22 plus the window 2.
/// assert_eq!(nan_reach(3, 1e-12).unwrap(), 22 + 2);
/// assert_eq!(nan_reach(1, 1e-12).unwrap(), 1);
/// assert!(nan_reach(3, 0.0).is_err());
/// ```
pub fn nan_reach(degree: u32, tol: f64) -> Result<usize, NdimageError> {
    let window = degree as usize / 2 + 1;
    if degree < 2 {
        crate::sspline::width::check_tol(tol)?;
        return Ok(window);
    }
    let (n, _) = certified_width(&SplineFamily::order(super::spline_order(degree)?)?, tol)?;
    Ok(n + window)
}

/// Where `a` (read into `T`) is not finite, in logical order (a copy of
/// its shape).
pub(crate) fn missing<T, E, S, D>(a: &ArrayBase<S, D>) -> ArrayD<bool>
where
    T: Real,
    E: Sample<T>,
    S: Data<Elem = E>,
    D: Dimension,
{
    let mut m = ArrayD::from_elem(IxDyn(a.shape()), false);
    Zip::from(&mut m)
        .and(&a.view().into_dyn())
        .par_for_each(|m, x| *m = !x.widen().is_finite());
    m
}

/// The largest finite `|x|` of `a` (for the overflow bound where some
/// samples are missing).
pub(crate) fn max_finite<T, E, S, D>(a: &ArrayBase<S, D>) -> f64
where
    T: Real,
    E: Sample<T>,
    S: Data<Elem = E>,
    D: Dimension,
{
    a.iter()
        .map(Sample::widen)
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.to_f64().abs()))
}

/// Writes `src` (read into `T`) into `out` with its non-finite samples
/// replaced by 0.
pub(crate) fn fill_missing<T, E, O, S1, S2, D>(src: &ArrayBase<S1, D>, out: &mut ArrayBase<S2, D>)
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Stored<T>,
    S1: Data<Elem = E>,
    S2: DataMut<Elem = O>,
    D: Dimension,
{
    Zip::from(out).and(src).par_for_each(|o, s| {
        let x = s.widen();
        *o = O::store(&if x.is_finite() { x } else { T::zero() });
    });
}

/// NaN wherever `mask` holds (`out` of the mask's shape).
pub(crate) fn write_nan<T, O, S, D>(out: &mut ArrayBase<S, D>, mask: &ArrayD<bool>)
where
    T: Real + Send + Sync,
    O: Stored<T>,
    S: DataMut<Elem = O>,
    D: Dimension,
{
    let nan = O::store(&T::from_f64_exact(f64::NAN));
    Zip::from(out.view_mut().into_dyn())
        .and(mask)
        .par_for_each(|o, &m| {
            if m {
                *o = nan.clone();
            }
        });
}

/// [`NanPolicy::Propagate`]'s pattern after filtering `axes` (scipy's
/// recursive filter carries a value along its whole line): an element is
/// non-finite when a missing one shares its coordinates on every other axis.
pub(crate) fn spread(mask: &ArrayD<bool>, axes: &[usize]) -> ArrayD<bool> {
    let mut any = mask.clone();
    for &axis in axes {
        if any.shape()[axis] > 1 {
            let folded = any.fold_axis(Axis(axis), false, |&a, &b| a | b);
            any = folded.insert_axis(Axis(axis));
        }
    }
    any.broadcast(mask.shape())
        .expect("the folded axes have length 1")
        .to_owned()
}

/// [`NanPolicy::Local`]'s pattern: `mask` dilated along each of `axes` in
/// turn by `n` samples, folded by `mode` (`outside`: whether the constant
/// beyond the ends of `grid-constant` is missing), each axis grown by
/// `pad` positions beyond each end (the layout of padded coefficients;
/// 0 for coefficients on the grid).
pub(crate) fn dilate(
    mask: &ArrayD<bool>,
    axes: &[usize],
    n: usize,
    mode: Mode,
    outside: bool,
    pad: usize,
) -> ArrayD<bool> {
    let mut cur = mask.clone();
    for &axis in axes {
        let mut shape = cur.shape().to_vec();
        shape[axis] += 2 * pad;
        let mut next = ArrayD::from_elem(IxDyn(&shape), false);
        Zip::from(cur.lanes(Axis(axis)))
            .and(next.lanes_mut(Axis(axis)))
            .par_for_each(|src, mut dst| {
                let src = src.to_vec();
                let len = src.len();
                let at = |i: i64| mode.fold(i, len).map_or(outside, |j| src[j]);
                // Prefix counts of the extended mask over [−pad − n, ν + pad + n).
                let lo = -(pad as i64) - n as i64;
                let mut prefix = Vec::with_capacity(dst.len() + 2 * n + 1);
                prefix.push(0usize);
                for i in lo..lo + (dst.len() + 2 * n) as i64 {
                    prefix.push(prefix.last().copied().unwrap_or(0) + usize::from(at(i)));
                }
                for (p, d) in dst.iter_mut().enumerate() {
                    *d = prefix[p + 2 * n + 1] > prefix[p];
                }
            });
        cur = next;
    }
    cur
}

/// The error naming the first non-finite element of `a` (read into `T`) in
/// logical order (`Ok` if there is none). Serial: runs only on failure.
pub(crate) fn first_non_finite<T, E, S, D>(a: &ArrayBase<S, D>) -> Result<(), NdimageError>
where
    T: Real,
    E: Sample<T>,
    S: Data<Elem = E>,
    D: Dimension,
{
    match a
        .iter()
        .enumerate()
        .find_map(|(i, x)| Some((i, NonFiniteValue::of(&x.widen())?)))
    {
        Some((index, value)) => Err(NdimageError::NonFinite { index, value }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dilation against its definition, position by position: `dst[p]`
    /// is set iff some missing `j = fold(p − pad + k)`, `|k| ≤ n`.
    #[test]
    fn dilation_is_the_folded_window_definition() {
        for mode in Mode::ALL {
            for len in [1usize, 2, 5, 9] {
                for pad in [0usize, 3] {
                    for n in [0usize, 1, 4, 11] {
                        for at in 0..len {
                            let mut m = ArrayD::from_elem(IxDyn(&[len]), false);
                            m[[at]] = true;
                            let got = dilate(&m, &[0], n, mode, false, pad);
                            for p in 0..len + 2 * pad {
                                let q = p as i64 - pad as i64;
                                let want = (-(n as i64)..=n as i64)
                                    .any(|k| mode.fold(q + k, len) == Some(at));
                                assert_eq!(
                                    got[[p]],
                                    want,
                                    "{mode} len {len} pad {pad} n {n} at {at} p {p}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// Names and parsing, and the error that lists the three choices.
    #[test]
    fn names_parse_and_unknown_lists_the_choices() {
        for p in NanPolicy::all() {
            assert_eq!(p.name().parse::<NanPolicy>(), Ok(p));
        }
        assert_eq!(NanPolicy::default(), NanPolicy::Propagate);
        assert_eq!(
            "omit".parse::<NanPolicy>().unwrap_err(),
            "unknown nan_policy 'omit' (expected one of propagate, raise, local)"
        );
    }
}
