//! The prefilter of an N-dimensional array: [`LineFilter`] along one axis
//! (`scipy.ndimage.spline_filter1d`) or along every axis in turn
//! (`spline_filter`), the lines of an axis filtered in parallel (rayon).
//!
//! A line along the last axis is contiguous and filtered in place. The
//! lines of a strided axis (standard layout) are filtered many at once:
//! strips of `w` neighbouring lines are copied into an L2-sized buffer whose
//! row `i` holds sample `i` of each line, and every step of the recursion is
//! a vector operation over a row ([`LineFilter::apply_lines`]); the
//! contiguous axis transposes groups of 16 lines (32 in `f32`) into such
//! rows. The row kernels are compiled for the CPU's vector units and
//! chosen at run time (`ndimage::lanes`). Other
//! layouts copy each strided line into a contiguous buffer. Error per axis: that of
//! the [`LineFilter`] route; over `D` axes the truncated route's bound
//! compounds to at most `((A + b)^D − A^D) · max|s|` with `A = Σ|c_j|` the
//! amplification (`1/|V(−1)|`) and `b` the per-axis bound (≈ `D A^{D−1} b`).

use super::NdimageError;
use super::block_filter::BlockPrefilter;
use super::lanes;
use super::line_filter::LineFilter;
use super::mode::Mode;
use crate::scalar::Real;
use ndarray::{
    Array, ArrayBase, ArrayViewMut2, ArrayViewMut3, Axis, Data, DataMut, Dimension, Zip,
};
use rayon::prelude::*;
use std::sync::Mutex;

/// Refuses samples that `filter` could overflow along `axes` axes
/// ([`LineFilter::check_magnitude`]). One pass on the pool, after [`check_finite`].
pub(crate) fn check_range<T: Real + Send + Sync, S: Data<Elem = T>, D: Dimension>(
    a: &ArrayBase<S, D>,
    filter: &LineFilter<T>,
    axes: usize,
) -> Result<(), NdimageError> {
    if T::BITS > 53 {
        return Ok(());
    }
    let max = match a.as_slice_memory_order() {
        Some(s) => scan(s).1,
        None => a.iter().fold(0.0f64, |m, x| m.max(x.to_f64().abs())),
    };
    filter.check_magnitude(max, axes)
}

/// The first non-finite element (in logical order), as an error.
pub(crate) fn check_finite<T: Real + Send + Sync, S: Data<Elem = T>, D: Dimension>(
    a: &ArrayBase<S, D>,
) -> Result<(), NdimageError> {
    if a.is_empty() {
        return Err(NdimageError::Empty);
    }
    if let Some(s) = a.as_slice_memory_order() {
        // Fast path: one vectorised pass on the pool; the position only on failure.
        if scan(s).0 {
            return Ok(());
        }
    }
    first_non_finite(a)
}

/// [`check_finite`] and [`check_range`] in one pass over the samples.
fn check_samples<T: Real + Send + Sync, S: Data<Elem = T>, D: Dimension>(
    a: &ArrayBase<S, D>,
    filter: &LineFilter<T>,
    axes: usize,
) -> Result<(), NdimageError> {
    if a.is_empty() {
        return Err(NdimageError::Empty);
    }
    let Some(s) = a.as_slice_memory_order() else {
        check_finite(a)?;
        return check_range(a, filter, axes);
    };
    match scan(s) {
        (true, max) => filter.check_magnitude(max, axes),
        (false, _) => first_non_finite(a),
    }
}

/// The error naming the first non-finite element of `a` in logical order
/// (`Ok` if there is none). Serial: runs only on failure.
fn first_non_finite<T: Real, S: Data<Elem = T>, D: Dimension>(
    a: &ArrayBase<S, D>,
) -> Result<(), NdimageError> {
    match a.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(NdimageError::NonFinite(i)),
        None => Ok(()),
    }
}

/// Values per task of the scans and copies: 256 KiB of `f64` (the pool's
/// overhead per task is then well below the time to stream it).
const SCAN_BLOCK: usize = 1 << 15;

/// Whether every value of `s` is finite, and `max|s|` (0 for scalars of
/// more than 53 bits, which cannot overflow): one pass on the pool.
fn scan<T: Real + Send + Sync>(s: &[T]) -> (bool, f64) {
    s.par_chunks(SCAN_BLOCK)
        .map(scan_block)
        .reduce(|| (true, 0.0), |a, b| (a.0 & b.0, a.1.max(b.1)))
}

/// [`scan`] of one block. For f32/f64, eight independent lanes of
/// `|x| ≤ MAX` (false for NaN and ±∞) and of a comparison maximum, so the
/// loop vectorises: a fold through `f64::max` (NaN-aware, a serial chain)
/// cost as much as the prefilter's recursion itself.
pub(crate) fn scan_block<T: Real>(s: &[T]) -> (bool, f64) {
    if T::BITS > 53 {
        return (s.iter().all(|x| x.is_finite()), 0.0);
    }
    let (mut ok, mut max) = ([true; LANES], [0.0f64; LANES]);
    let mut chunks = s.chunks_exact(LANES);
    for c in &mut chunks {
        for ((ok, m), x) in ok.iter_mut().zip(max.iter_mut()).zip(c) {
            let a = x.to_f64().abs();
            *ok &= a <= f64::MAX;
            *m = if a > *m { a } else { *m };
        }
    }
    for x in chunks.remainder() {
        let a = x.to_f64().abs();
        ok[0] &= a <= f64::MAX;
        max[0] = if a > max[0] { a } else { max[0] };
    }
    let m = max.iter().fold(0.0f64, |m, &x| if x > m { x } else { m });
    (ok.iter().all(|&b| b), m)
}

/// Independent accumulators of [`scan_block`]: two AVX registers of f64.
const LANES: usize = 8;

/// Copies `src` into `dst` on the pool, scanning each block ([`scan`])
/// while it is in L1: the copy, the finiteness and the magnitude check in
/// one pass (and the first touch of `dst`'s pages on the thread that
/// will filter them).
fn copy_scan<T: Real + Send + Sync>(src: &[T], dst: &mut [T]) -> (bool, f64) {
    dst.par_chunks_mut(SCAN_BLOCK)
        .zip(src.par_chunks(SCAN_BLOCK))
        .map(|(d, s)| {
            d.clone_from_slice(s);
            scan_block(d)
        })
        .reduce(|| (true, 0.0), |a, b| (a.0 & b.0, a.1.max(b.1)))
}

fn check_axis<D: Dimension>(dim: &D, axis: usize) -> Result<(), NdimageError> {
    if axis < dim.ndim() {
        Ok(())
    } else {
        Err(NdimageError::Axis {
            axis,
            ndim: dim.ndim(),
        })
    }
}

/// Replaces `a` by its coefficients along `axis` (scipy's `spline_filter1d`
/// with `order` = degree and `mode`). Lines in parallel.
///
///
/// **Accuracy**: the [`LineFilter`] route's per line; scipy 1.17.1's output within 16 ulps
/// of max|value| (`verify/tests/engine_scipy.rs::spline_filter_matches_scipy`).
///
/// ```
/// use splinelab::prelude::*;
/// let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
/// let mut a = ndarray::array![[1.0, 2.0, 0.0], [3.0, 1.0, 5.0]];
/// spline_filter1d(&mut a, 1, &f).unwrap();
/// // Mirror ends: (4 D_0 + 2 D_1)/6 = s_0 on every row.
/// assert!(((4.0 * a[[1, 0]] + 2.0 * a[[1, 1]]) / 6.0 - 3.0).abs() < 1e-15);
/// ```
pub fn spline_filter1d<T, S, D>(
    a: &mut ArrayBase<S, D>,
    axis: usize,
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    check_axis(&a.raw_dim(), axis)?;
    check_samples(a, filter, 1)?;
    filter_axis_unchecked(a, axis, filter)
}

/// [`spline_filter1d`] on checked input. A single long line under
/// [`Route::Truncated`](super::line_filter::Route::Truncated) runs in
/// certified blocks on the pool ([`BlockPrefilter::apply_line_into`]);
/// everything else by lines.
fn filter_axis_unchecked<T, S, D>(
    a: &mut ArrayBase<S, D>,
    axis: usize,
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    let blocks = BlockPrefilter::from_line_filter(filter).filter(|b| b.pays_off(a.len()));
    if let (Some(b), true) = (blocks, a.len() == a.shape()[axis])
        && let Some(line) = a.as_slice_memory_order_mut()
    {
        // One line, in place: the blocks read a copy of the samples.
        let s: Vec<T> = line.par_iter().cloned().collect();
        return b.apply_line_into(&s, line);
    }
    filter_lines(a, axis, filter);
    Ok(())
}

/// The lines of `axis` filtered in parallel (many at once where the
/// layout allows).
fn filter_lines<T, S, D>(a: &mut ArrayBase<S, D>, axis: usize, filter: &LineFilter<T>)
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    if a.is_standard_layout() && a.len() > a.shape()[axis] {
        if axis + 1 < a.ndim() {
            filter_strided_axis(a, axis, filter);
        } else {
            filter_last_axis(a, filter);
        }
        return;
    }
    Zip::from(a.lanes_mut(Axis(axis))).par_for_each(|mut lane| {
        let mut scratch = Vec::new();
        match lane.as_slice_mut() {
            Some(line) => filter.apply(line, &mut scratch),
            None => {
                let mut line = lane.to_vec();
                filter.apply(&mut line, &mut scratch);
                for (d, s) in lane.iter_mut().zip(line) {
                    *d = s;
                }
            }
        }
    });
}

/// Contiguous lines filtered `G` at a time: each group is transposed
/// into a buffer (row `i` = sample `i` of the group's lines) so that the
/// recursion, latency-bound on one line, runs as vector operations over
/// the group ([`LineFilter::apply_lines`]); lines left over run alone. The
/// lines are read whole (tiles transposed in registers, `lanes::load_strip`)
/// and written back in strips of [`STRIP`] rows, front to back. `G` is 16 lines of `f64`
/// (two AVX-512 registers, enough independent chains to hide the
/// recursion's latency) and 32 of `f32`: the same bytes per row, twice
/// the lanes.
fn filter_last_axis<T, S, D>(a: &mut ArrayBase<S, D>, filter: &LineFilter<T>)
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    if std::mem::size_of::<T>() <= 4 {
        filter_last_axis_in::<T, S, D, { 2 * lanes::LINES }>(a, filter)
    } else {
        filter_last_axis_in::<T, S, D, { lanes::LINES }>(a, filter)
    }
}

/// [`filter_last_axis`] in groups of `G` lines.
fn filter_last_axis_in<T, S, D, const G: usize>(a: &mut ArrayBase<S, D>, filter: &LineFilter<T>)
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    let n = a.shape()[a.ndim() - 1];
    let data = a.as_slice_mut().expect("standard layout");
    let stash = Stash::default();
    let one = T::one();
    data.par_chunks_mut(n * G).for_each(|lines| {
        stash.with(|(buf, scratch): &mut (Vec<[T; G]>, Vec<T>)| {
            if lines.len() < n * G {
                for line in lines.chunks_mut(n) {
                    filter.apply(line, scratch);
                }
                return;
            }
            buf.resize(n, std::array::from_fn(|_| T::zero()));
            let srcs: Vec<&[T]> = lines.chunks(n).collect();
            // Whole lines at once (a tile group of lines at a time): long
            // runs per line read faster from memory than 64-row pieces of
            // 16 lines in turn (`engine_peer lines2d 3 4096 10`, one
            // thread, min of 4 alternated: 38.1 → 35.3 ms). × 1: exact,
            // the gain is applied by the filter.
            lanes::load_strip(buf, 0, &srcs, &one);
            filter.apply_lines(buf.as_flattened_mut(), G, scratch);
            let mut outs: Vec<&mut [T]> = lines.chunks_mut(n).collect();
            for (k, strip) in buf.chunks(STRIP).enumerate() {
                lanes::store_strip(&mut outs, strip, k * STRIP);
            }
        })
    });
}

/// Rows per strip of [`filter_last_axis`]'s transposition.
const STRIP: usize = 64;

/// Work buffers shared by the tasks of one pass, each task taking one
/// and putting it back: a fresh multi-megabyte `Vec` per task is a fresh
/// mapping whose pages the kernel zeroes (perf: `clear_page` was 38% of
/// spline_filter 4096² on one thread).
pub(crate) struct Stash<B>(Mutex<Vec<B>>);

impl<B> Default for Stash<B> {
    fn default() -> Self {
        Stash(Mutex::new(Vec::new()))
    }
}

impl<B: Default> Stash<B> {
    /// `f` on a buffer (new, or left by an earlier task).
    pub(crate) fn with<R>(&self, f: impl FnOnce(&mut B) -> R) -> R {
        let lock = || self.0.lock().unwrap_or_else(|p| p.into_inner());
        let mut buf = lock().pop().unwrap_or_default();
        let r = f(&mut buf);
        lock().push(buf);
        r
    }
}

/// Bytes of one strip's work buffer (measured: wider strips read longer
/// contiguous runs of each row, which the prefetcher needs more than the
/// buffer needs L2).
const STRIP_BYTES: usize = 2 << 20;

/// Lines per strip for an axis of `n` samples: a multiple of 8 (a cache
/// line of f64) between 8 and 1024, the strip of `n × w` values within
/// [`STRIP_BYTES`].
fn strip_width<T>(n: usize) -> usize {
    let w = STRIP_BYTES / (n.max(1) * std::mem::size_of::<T>().max(1));
    (w / 8 * 8).clamp(8, 1024)
}

/// The filter along a strided `axis` of a standard-layout array: seen as
/// `(outer, n, inner)`, the `inner` lines are cut in strips of `w`
/// (in parallel); each strip's `n × w` block is copied to a buffer (row `i`
/// = sample `i` of `w` lines, contiguous), filtered by
/// [`LineFilter::apply_lines`] and copied back.
fn filter_strided_axis<T, S, D>(a: &mut ArrayBase<S, D>, axis: usize, filter: &LineFilter<T>)
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    let shape = a.shape().to_vec();
    let n = shape[axis];
    let outer: usize = shape[..axis].iter().product();
    let inner: usize = shape[axis + 1..].iter().product();
    let data = a.as_slice_mut().expect("standard layout");
    let mut v = ArrayViewMut3::from_shape((outer, n, inner), data).expect("shape");
    let stash = Stash::default();
    v.axis_chunks_iter_mut(Axis(2), strip_width::<T>(n))
        .into_par_iter()
        .for_each(|mut strip| {
            stash.with(|(buf, scratch): &mut (Vec<T>, Vec<T>)| {
                filter_strip(&mut strip, filter, buf, scratch)
            })
        });
}

/// One strip of [`filter_strided_axis`] (`outer × n × w`): each `n × w`
/// block filtered where it lies, its rows through `buf`
/// ([`LineFilter::apply_rows`]: the array read and written once).
fn filter_strip<T: Real>(
    strip: &mut ArrayViewMut3<'_, T>,
    filter: &LineFilter<T>,
    buf: &mut Vec<T>,
    scratch: &mut Vec<T>,
) {
    for mut block in strip.outer_iter_mut() {
        let n = block.nrows();
        let mut rows: Vec<&mut [T]> = block
            .axis_iter_mut(Axis(0))
            .filter_map(|r| r.into_slice())
            .collect();
        if rows.len() == n {
            filter.apply_rows(&mut rows, buf, scratch);
        } else {
            // Not contiguous rows (not a standard-layout strip): copied.
            drop(rows);
            filter_block_copied(&mut block, filter, buf, scratch);
        }
    }
}

/// One `n × w` block through `buf`: copied in, [`LineFilter::apply_lines`], copied back.
fn filter_block_copied<T: Real>(
    block: &mut ArrayViewMut2<'_, T>,
    filter: &LineFilter<T>,
    buf: &mut Vec<T>,
    scratch: &mut Vec<T>,
) {
    buf.clear();
    buf.extend(block.iter().cloned());
    filter.apply_lines(buf, block.ncols(), scratch);
    block
        .iter_mut()
        .zip(buf.iter())
        .for_each(|(d, s)| *d = s.clone());
}

/// Replaces `a` by its coefficients along every axis (scipy's
/// `spline_filter`): the tensor-product interpolation coefficients.
///
/// **Accuracy**: per axis the [`LineFilter`] route's; the truncated route compounds to `((A
/// + b)^D − A^D) max|s|` (module documentation); scipy agreement in
/// `verify/tests/engine_scipy.rs::spline_filter_matches_scipy`.
pub fn spline_filter<T, S, D>(
    a: &mut ArrayBase<S, D>,
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    check_samples(a, filter, a.ndim())?;
    (0..a.ndim()).try_for_each(|axis| filter_axis_unchecked(a, axis, filter))
}

/// `src` copied into `out` and filtered along `axes` in turn (every axis:
/// [`spline_filter`]; one: [`spline_filter1d`]): the copy, the finiteness
/// and the magnitude checks are one pass on the pool (the first touch of
/// `out`'s pages included), so no step runs on one thread. `filter` `None`:
/// the copy only (degrees 0 and 1).
///
/// **Method**, **accuracy** and **source**: those of [`spline_filter`]
/// (scipy agreement in `verify/tests/engine_scipy.rs::spline_filter_matches_scipy`;
/// equal to the in-place call in
/// `verify/tests/engine_properties.rs::filtering_a_copy_equals_filtering_in_place`).
///
/// ```
/// use splinelab::prelude::*;
/// use splinelab::ndimage::nd_prefilter::spline_filter_from;
/// let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
/// let a = ndarray::array![[1.0, 2.0, 0.0], [3.0, 1.0, 5.0]];
/// let mut out = ndarray::Array2::zeros((2, 3));
/// spline_filter_from(&a, &mut out, &[0, 1], Some(&f)).unwrap();
/// let mut b = a.clone();
/// spline_filter(&mut b, &f).unwrap();
/// assert_eq!(out, b);
/// ```
pub fn spline_filter_from<T, S1, S2, D>(
    src: &ArrayBase<S1, D>,
    out: &mut ArrayBase<S2, D>,
    axes: &[usize],
    filter: Option<&LineFilter<T>>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    S1: Data<Elem = T>,
    S2: DataMut<Elem = T>,
    D: Dimension,
{
    if src.shape() != out.shape() {
        return Err(NdimageError::BufferLength {
            expected: src.len(),
            got: out.len(),
        });
    }
    for &axis in axes {
        check_axis(&out.raw_dim(), axis)?;
    }
    if src.is_empty() {
        return Err(NdimageError::Empty);
    }
    let scanned = match (src.as_slice(), out.as_slice_mut()) {
        (Some(s), Some(d)) => Some(copy_scan(s, d)),
        _ => {
            Zip::from(&mut *out)
                .and(src)
                .par_for_each(|d, s| *d = s.clone());
            None
        }
    };
    let Some(filter) = filter else {
        return Ok(());
    };
    match scanned {
        Some((true, max)) => filter.check_magnitude(max, axes.len())?,
        Some((false, _)) => first_non_finite(src)?,
        None => check_samples(src, filter, axes.len())?,
    }
    axes.iter()
        .try_for_each(|&axis| filter_axis_unchecked(out, axis, filter))
}

/// The coefficients of `a` along every axis including `pad` coefficients
/// beyond each end of each axis (what evaluation near the ends reads): the
/// result has shape `a.shape()[k] + 2·pad` and element `[i + pad]` is
/// `D_i`, `i ∈ [−pad, ν + pad)`.
///
/// **Method**: [`padded_extension`] then the exact prefilter along every axis
/// ([`LineFilter::apply_padded`]). **Accuracy**: as [`LineFilter::apply_padded`]
/// (`verify/tests/engine_properties.rs::nearest_outside_the_grid_is_the_edge_extended_spline`).
/// **Source**: scipy's `_prepad_for_spline_filter` convention, the pad widened to the pole
/// horizon.
pub fn padded_coefficients<T, S, D>(
    a: &ArrayBase<S, D>,
    filter: &LineFilter<T>,
    pad: usize,
) -> Result<Array<T, D>, NdimageError>
where
    T: Real + Send + Sync,
    S: Data<Elem = T>,
    D: Dimension,
{
    check_finite(a)?;
    check_range(a, filter, a.ndim())?;
    Ok(pad_lanes(a, pad, |buf| {
        filter.apply_padded(buf, pad, &mut Vec::new())
    }))
}

/// `a` extended by `pad` values beyond each end of each axis as `mode`
/// extends samples (`cval` for `grid-constant`), unfiltered: the layout of
/// [`padded_coefficients`] for coefficients the caller already has (scipy's
/// `prefilter=False`) and for degrees 0 and 1, whose coefficients are the
/// samples.
///
/// **Accuracy**: exact (copies). **Source**: scipy's extension rules per mode
/// (`ni_support.c`, `NI_ExtendLine`).
pub fn padded_extension<T, S, D>(
    a: &ArrayBase<S, D>,
    mode: Mode,
    cval: f64,
    pad: usize,
) -> Result<Array<T, D>, NdimageError>
where
    T: Real + Send + Sync,
    S: Data<Elem = T>,
    D: Dimension,
{
    check_finite(a)?;
    let cval = T::from_f64_exact(cval);
    Ok(pad_lanes(a, pad, |buf| {
        let s = buf[pad..buf.len() - pad].to_vec();
        for (j, o) in buf.iter_mut().enumerate() {
            *o = match mode.fold(j as i64 - pad as i64, s.len()) {
                Some(k) => s[k].clone(),
                None => cval.clone(),
            };
        }
    }))
}

/// Every lane of `a`, axis by axis, copied into the middle of a buffer
/// with `pad` slots each side, passed to `fill` and stored whole.
fn pad_lanes<T, S, D>(
    a: &ArrayBase<S, D>,
    pad: usize,
    fill: impl Fn(&mut Vec<T>) + Sync,
) -> Array<T, D>
where
    T: Real + Send + Sync,
    S: Data<Elem = T>,
    D: Dimension,
{
    let mut cur = a.to_owned();
    for axis in 0..a.ndim() {
        let mut dim = cur.raw_dim();
        dim[axis] += 2 * pad;
        let mut next = Array::from_elem(dim, T::zero());
        Zip::from(cur.lanes(Axis(axis)))
            .and(next.lanes_mut(Axis(axis)))
            .par_for_each(|src, mut dst| {
                let mut buf: Vec<T> = Vec::with_capacity(src.len() + 2 * pad);
                buf.resize(pad, T::zero());
                buf.extend(src.iter().cloned());
                buf.resize(src.len() + 2 * pad, T::zero());
                fill(&mut buf);
                for (d, s) in dst.iter_mut().zip(buf) {
                    *d = s;
                }
            });
        cur = next;
    }
    cur
}
