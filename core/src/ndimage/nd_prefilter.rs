//! The prefilter of an N-dimensional array: [`LineFilter`] along one axis
//! (`scipy.ndimage.spline_filter1d`) or along every axis in turn
//! (`spline_filter`), the lines of an axis filtered in parallel (rayon).
//!
//! A line along the last axis is contiguous; the lines of a strided axis
//! (standard layout) are filtered many at once: strips of `w` neighbouring
//! lines stay where they lie, their rows read into a work buffer that stays
//! in L2 (row `i` holds sample `i` of each line) with the first pole's gain
//! and causal pass, and written back by the last anti-causal pass, every
//! step of the recursion a vector operation over a row
//! ([`LineFilter::apply_rows`]); the rows are prefetched ahead (each is a
//! short run on its own page). The contiguous axis transposes groups of 16
//! lines (32 in `f32`) into such rows. The row kernels are compiled for the
//! CPU's vector units and chosen at run time (`ndimage::lanes`). Other
//! layouts copy each line into a contiguous buffer.
//!
//! **Passes over memory.** Each pass reads and writes the array once. The
//! input's copy is fused into the first pass ([`spline_filter_from`]: the
//! first axis reads the input and writes the output, checking the samples
//! as it reads them), and the trailing axes of an array of three or more
//! dimensions run slab by slab (`a[i, …]` filtered along all of them by one
//! task while it stays in L2): a 2-D array takes two passes (was three:
//! copy, axis 0, axis 1), `256³` two (was four). Measured (one thread,
//! `python/bench/nd_prefilter_ab.py`, process time, min of 7 alternated
//! against the pass-per-axis build, a plain copy of the same bytes 7.0
//! ms, a shared 2-core machine): 4096² cubic 46.7 → 32.0 ms, quintic 52.2
//! → 41.7; 256³ cubic 51.2 → 32.5, quintic 60.5 → 41.4; `f32` 4096² 24.8 →
//! 17.8, 256³ 28.0 → 17.4; `spline_filter1d` of 4096² along axis 0 29.2 →
//! 15.1 (2.07 × the copy), along axis 1 25.9 → 18.6.
//! Quintic (and quartic) splines run their two poles as one pass down and
//! one up the rows (`line_filter::Cascade`) instead of two of each:
//! against the build of one pass per pole (same harness, min of 15, both
//! orientations of the harness, load 1.5): 4096² quintic 37.3 → 31.9 ms
//! (41.3 → 35.2 on the harness's other side), 256³ 43.8 → 37.5 (40.6 →
//! 37.4); cubic and `f32` unchanged. Two threads, wall clock
//! (`benches/peers/python_prefilter.py --rounds 5`): 4096² quintic 23.2 →
//! 20.0 ms (2.96 × the copy), 256³ 23.6 → 21.4 (3.03 ×); cubic 19.1, 18.0.
//! The first pass of an array larger than L3 (32 MiB, `lanes::STREAM_BYTES`)
//! writes `out` by streaming stores (`lanes::stream_row`: each row formed
//! in L1, then written whole lines at a time without being read for
//! ownership; the same values): the array is not read back before it is
//! overwritten. Measured (`python/bench/nd_prefilter_ab.py --rounds 9`,
//! one thread, process time, alternated against the build before, load
//! 7): 4096² cubic 32.5 → 31.2 ms, quintic 35.6 → 34.8, `f32` 18.3 →
//! 17.8; 256³ cubic 34.6 → 32.9, quintic 40.8 → 39.0, `f32` 18.3 → 17.3;
//! `spline_filter1d` along axis 0 16.5 → 15.2 (along axis 1, not
//! streamed: 21.0 → 20.9).
//! Every line gets the same operations whatever the pass, slab or group it
//! falls in (lines side by side are independent columns), so the result
//! does not depend on the route or the number of threads.
//!
//! Error per axis: that of the [`LineFilter`] route; over `D` axes the
//! truncated route's bound compounds to at most `((A + b)^D − A^D) · max|s|`
//! with `A = Σ|c_j|` the amplification (`1/|V(−1)|`) and `b` the per-axis
//! bound (≈ `D A^{D−1} b`).

use super::NdimageError;
use super::alloc::{try_array, try_to_owned};
use super::block_filter::BlockPrefilter;
use super::lanes;
use super::line_filter::{LineFilter, RowCheck};
use super::missing::{fill, fill_filter_mark, pattern};
use super::mode::Mode;
use super::nan_policy::{first_non_finite, write_nan};
use super::stash::Stash;
use crate::scalar::Real;
use ndarray::{
    Array, ArrayBase, ArrayView, ArrayView3, ArrayViewMut3, Axis, Data, DataMut, Dimension, Zip,
};
use rayon::prelude::*;

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

/// The finiteness and overflow checks ([`LineFilter::check_magnitude`]) in one pass over the samples:
/// `Ok(true)` where every sample is finite (and below the overflow limit),
/// `Ok(false)` where some is not (for [`filter_missing`] to handle by the
/// filter's [`NanPolicy`]).
fn scan_samples<T: Real + Send + Sync, S: Data<Elem = T>, D: Dimension>(
    a: &ArrayBase<S, D>,
    filter: &LineFilter<T>,
    axes: usize,
) -> Result<bool, NdimageError> {
    if a.is_empty() {
        return Err(NdimageError::Empty);
    }
    let (finite, max) = match a.as_slice_memory_order() {
        Some(s) => scan(s),
        None => {
            let mut scan = Scan::default();
            a.iter().for_each(|x| scan.add(std::slice::from_ref(x)));
            scan.result()
        }
    };
    if finite {
        filter.check_magnitude(max, axes)?;
    }
    Ok(finite)
}

/// `src`, which holds a non-finite sample, filtered along `axes` into
/// `out` by the filter's [`NanPolicy`] ([`super::nan_policy`]): refused
/// ([`NanPolicy::Raise`]); or the missing samples filled with 0, filtered by
/// the filter's route, and NaN written where the policy's pattern says — every
/// line through a missing sample along a filtered axis
/// ([`NanPolicy::Propagate`], scipy's), or the coefficients within the
/// certified half-width of one ([`NanPolicy::Local`]). The slow path, run
/// only where the one scan of the samples met a non-finite one: a mask, a
/// refill, the filter again.
///
/// **Accuracy**: outside the NaN pattern the finite route's values for the
/// filled samples; under `Local` within
/// [`local_bound`](super::missing::local_bound)` · max|finite s|` of the exact
/// coefficients of any filling in `[−max|s|, max|s|]`.
///
/// ```
/// use splinelab::prelude::*;
/// use splinelab::ndimage::nan_policy::NanPolicy;
/// use splinelab::ndimage::nd_prefilter::spline_filter_from;
/// let route = Route::Truncated { tol: 1e-12 };
/// let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, route).unwrap();
/// let mut s = ndarray::Array1::from_iter((0..80).map(|i| (i as f64 * 0.3).sin()));
/// s[40] = f64::NAN;
/// let mut out = ndarray::Array1::zeros(80);
/// // scipy's pattern: the whole line.
/// spline_filter_from(&s, &mut out, &[0], Some(&f)).unwrap();
/// assert!(out.iter().all(|x| x.is_nan()));
/// // Local: the 2n + 1 coefficients within the certified half-width.
/// let f = f.with_nan_policy(NanPolicy::Local).unwrap();
/// spline_filter_from(&s, &mut out, &[0], Some(&f)).unwrap();
/// let n = f.half_width().unwrap();
/// assert_eq!(out.iter().filter(|x| x.is_nan()).count(), 2 * n + 1);
/// assert!(out[40 - n].is_nan() && out[40 - n - 1].is_finite());
/// ```
pub fn filter_missing<T, S1, S2, D>(
    src: &ArrayBase<S1, D>,
    out: &mut ArrayBase<S2, D>,
    axes: &[usize],
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    S1: Data<Elem = T>,
    S2: DataMut<Elem = T>,
    D: Dimension,
{
    fill_filter_mark(src, out, axes, filter, |o| {
        filter_axes_unchecked(o, axes, filter)
    })
}

/// [`filter_missing`] in place.
fn filter_missing_in_place<T, S, D>(
    a: &mut ArrayBase<S, D>,
    axes: &[usize],
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    let src = try_to_owned(a, "a copy of the samples with missing ones")?;
    filter_missing(&src, a, axes, filter)
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

/// [`scan`] of one block ([`Scan`]).
pub(crate) fn scan_block<T: Real>(s: &[T]) -> (bool, f64) {
    let mut scan = Scan::default();
    scan.add(s);
    scan.result()
}

/// A running check of samples: whether all are finite, and their largest
/// magnitude (0 for scalars of more than 53 bits, which cannot overflow).
/// For f32/f64, eight independent lanes of `|x| ≤ MAX` (false for NaN and
/// ±∞) and of a comparison maximum, so the loop vectorises: a fold through
/// `f64::max` (NaN-aware, a serial chain) cost as much as the prefilter's
/// recursion itself. The passes that read an input array feed it the rows
/// they read, while they are in L1.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Scan {
    ok: [bool; LANES],
    max: [f64; LANES],
}

impl Default for Scan {
    fn default() -> Self {
        Scan {
            ok: [true; LANES],
            max: [0.0; LANES],
        }
    }
}

impl Scan {
    /// Takes in the values of `s`.
    #[inline(always)]
    pub(crate) fn add<T: Real>(&mut self, s: &[T]) {
        if const { !T::FITS_F64 } {
            self.ok[0] &= s.iter().all(|x| x.is_finite());
            return;
        }
        let (mut ok, mut max) = (self.ok, self.max);
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
        (self.ok, self.max) = (ok, max);
    }

    /// The scan of both parts.
    fn merge(mut self, other: Scan) -> Scan {
        for (a, b) in self.ok.iter_mut().zip(other.ok) {
            *a &= b;
        }
        for (a, b) in self.max.iter_mut().zip(other.max) {
            *a = if b > *a { b } else { *a };
        }
        self
    }

    /// Whether every value was finite, and the largest magnitude.
    pub(crate) fn result(&self) -> (bool, f64) {
        let m = self
            .max
            .iter()
            .fold(0.0f64, |m, &x| if x > m { x } else { m });
        (self.ok.iter().all(|&b| b), m)
    }
}

impl RowCheck for Scan {
    #[inline(always)]
    fn row<T: Real>(&mut self, row: &[T]) {
        self.add(row);
    }
}

/// Independent accumulators of [`Scan`]: two AVX registers of f64.
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
/// with `order` = degree and `mode`). Lines in parallel. Non-finite samples
/// by the filter's [`NanPolicy`] ([`filter_missing`]).
///
///
/// **Accuracy**: the [`LineFilter`] route's per line; scipy 1.17.1's output within 16 ulps
/// of max|value| (`verify/tests/it/engine_scipy.rs::spline_filter_matches_scipy`).
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
    if !scan_samples(a, filter, 1)? {
        return filter_missing_in_place(a, &[axis], filter);
    }
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

/// The lines of `axis` filtered in parallel: a standard-layout array of
/// more than one line in one pass ([`axis_pass`]), other layouts lane by
/// lane through a contiguous copy.
fn filter_lines<T, S, D>(a: &mut ArrayBase<S, D>, axis: usize, filter: &LineFilter<T>)
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    let shape = a.shape().to_vec();
    if a.len() > shape[axis]
        && let Some(data) = a.as_slice_mut()
    {
        axis_pass(
            data,
            None,
            &shape,
            axis,
            filter,
            On::Pool(&Stash::default()),
        );
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

/// The filter along `axes` in turn of checked samples. A standard-layout
/// array in passes ([`filter_run`]: the trailing axes slab by slab);
/// otherwise, or where one axis holds every element (one line: the
/// certified blocks' case), axis by axis ([`filter_axis_unchecked`]).
fn filter_axes_unchecked<T, S, D>(
    a: &mut ArrayBase<S, D>,
    axes: &[usize],
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    let shape = a.shape().to_vec();
    let one_line = axes.iter().any(|&k| a.len() == shape[k]);
    match a.as_slice_mut() {
        Some(data) if !one_line => {
            filter_run(
                data,
                None,
                &shape,
                axes,
                filter,
                On::Pool(&Stash::default()),
            );
            Ok(())
        }
        _ => axes
            .iter()
            .try_for_each(|&axis| filter_axis_unchecked(a, axis, filter)),
    }
}

/// The work buffers of one task: `rows` (a strip's or a group's rows)
/// and the filter's `scratch`.
struct Work<T> {
    rows: Vec<T>,
    scratch: Vec<T>,
}

impl<T> Default for Work<T> {
    fn default() -> Self {
        Work {
            rows: Vec::new(),
            scratch: Vec::new(),
        }
    }
}

/// Where the tasks of a pass run: on the pool, each taking work buffers
/// from the stash, or here, in turn, with the caller's buffers (inside a
/// task of the slab route, whose slab stays in that core's cache).
enum On<'a, T> {
    Pool(&'a Stash<Work<T>>),
    Here(&'a mut Work<T>),
}

impl<T: Send> On<'_, T> {
    /// The same place, for one more pass.
    fn again(&mut self) -> On<'_, T> {
        match self {
            On::Pool(stash) => On::Pool(stash),
            On::Here(work) => On::Here(work),
        }
    }

    /// `task` on every item, the scans merged.
    fn each<I: Send>(self, items: Vec<I>, task: impl Fn(I, &mut Work<T>) -> Scan + Sync) -> Scan {
        match self {
            On::Pool(stash) => items
                .into_par_iter()
                .map(|item| stash.with(|work| task(item, work)))
                .reduce(Scan::default, Scan::merge),
            On::Here(work) => items
                .into_iter()
                .fold(Scan::default(), |scan, item| scan.merge(task(item, work))),
        }
    }
}

/// Filters the standard-layout array `data` of `shape` along `axes` in
/// turn, the first pass reading the samples from `src` (the same shape)
/// when given: the copy fused into that pass, which also scans what it
/// reads (the [`Scan`] of `src` is returned; of nothing without `src`).
///
/// Where the remaining axes are at least two trailing ones (none is axis
/// 0) of an array of three or more dimensions, each slab `data[i, …]` is
/// filtered along all of them by one task while it stays in cache
/// ([`slab_pass`]): `256³` is read and written twice (axis 0, then the
/// slabs), not once per axis. Every line gets the operations it gets in
/// an axis-by-axis pass (lines side by side are independent columns), so
/// the same bits.
fn filter_run<T: Real + Send + Sync>(
    data: &mut [T],
    mut src: Option<&[T]>,
    shape: &[usize],
    axes: &[usize],
    filter: &LineFilter<T>,
    mut on: On<'_, T>,
) -> Scan {
    let mut scan = Scan::default();
    let mut rest = axes;
    while let Some((&axis, tail)) = rest.split_first() {
        if shape.len() >= 3 && rest.len() >= 2 && rest.iter().all(|&k| k >= 1) {
            return scan.merge(slab_pass(data, src, shape, rest, filter, on));
        }
        scan = scan.merge(axis_pass(data, src.take(), shape, axis, filter, on.again()));
        rest = tail;
    }
    scan
}

/// Bytes of a slab that one task filters along its axes (a core's L2):
/// larger slabs run in turn, each on the pool.
const SLAB_BYTES: usize = 1 << 20;

/// [`filter_run`] along `axes` (none is 0) slab by slab: on the pool, one
/// slab per task, where a slab fits [`SLAB_BYTES`]; otherwise in turn.
fn slab_pass<T: Real + Send + Sync>(
    data: &mut [T],
    src: Option<&[T]>,
    shape: &[usize],
    axes: &[usize],
    filter: &LineFilter<T>,
    on: On<'_, T>,
) -> Scan {
    let (sub, len) = (&shape[1..], shape[1..].iter().product::<usize>());
    let inner: Vec<usize> = axes.iter().map(|&k| k - 1).collect();
    let slabs = pieces(data, src, len);
    match on {
        On::Pool(stash) if len * std::mem::size_of::<T>() <= SLAB_BYTES => On::Pool(stash)
            .each(slabs, |(slab, s), work| {
                filter_run(slab, s, sub, &inner, filter, On::Here(work))
            }),
        mut on => slabs.into_iter().fold(Scan::default(), |scan, (slab, s)| {
            scan.merge(filter_run(slab, s, sub, &inner, filter, on.again()))
        }),
    }
}

/// `data` in pieces of `len`, each with the same piece of `src` if given.
fn pieces<'a, T>(
    data: &'a mut [T],
    src: Option<&'a [T]>,
    len: usize,
) -> Vec<(&'a mut [T], Option<&'a [T]>)> {
    match src {
        Some(s) => data.chunks_mut(len).zip(s.chunks(len).map(Some)).collect(),
        None => data.chunks_mut(len).map(|d| (d, None)).collect(),
    }
}

/// One pass along `axis` of the standard-layout array `data` of `shape`
/// (more than one line), reading from `src` when given (and scanning it):
/// strided axes by strips ([`strided_pass`]), the last by groups of lines
/// ([`last_pass`]).
fn axis_pass<T: Real + Send + Sync>(
    data: &mut [T],
    src: Option<&[T]>,
    shape: &[usize],
    axis: usize,
    filter: &LineFilter<T>,
    on: On<'_, T>,
) -> Scan {
    if axis + 1 < shape.len() {
        return strided_pass(data, src, shape, axis, filter, on);
    }
    let n = shape[axis];
    if std::mem::size_of::<T>() <= 4 {
        last_pass::<T, { 2 * lanes::LINES }>(data, src, n, filter, on)
    } else {
        last_pass::<T, { lanes::LINES }>(data, src, n, filter, on)
    }
}

/// Contiguous lines filtered `G` at a time: each group is transposed
/// into a buffer (row `i` = sample `i` of the group's lines) so that the
/// recursion, latency-bound on one line, runs as vector operations over
/// the group ([`LineFilter::apply_lines`]); a last group of fewer lines
/// the same way (its other columns zero). The lines are read whole
/// and written back whole, a tile group of lines at a time (tiles
/// transposed in registers, `lanes::load_strip` and `store_strip`). `G` is 16 lines of `f64`
/// (two AVX-512 registers, enough independent chains to hide the
/// recursion's latency) and 32 of `f32`: the same bytes per row, twice
/// the lanes.
fn last_pass<T: Real + Send + Sync, const G: usize>(
    data: &mut [T],
    src: Option<&[T]>,
    n: usize,
    filter: &LineFilter<T>,
    on: On<'_, T>,
) -> Scan {
    on.each(pieces(data, src, n * G), |(lines, src), work| {
        last_group::<T, G>(lines, src, n, filter, work)
    })
}

/// One group of [`last_pass`]: at most `G` lines of `n` samples, read
/// from `src` (and scanned) when given.
fn last_group<T: Real, const G: usize>(
    lines: &mut [T],
    src: Option<&[T]>,
    n: usize,
    filter: &LineFilter<T>,
    work: &mut Work<T>,
) -> Scan {
    let mut scan = Scan::default();
    let Work { rows, scratch } = work;
    let count = lines.len() / n;
    if rows.len() < n * G {
        rows.resize(n * G, T::zero());
    }
    let buf = rows[..n * G].as_chunks_mut::<G>().0;
    if count < G {
        // The columns of absent lines: zeros, not stale values.
        buf.iter_mut()
            .for_each(|r| r[count..].iter_mut().for_each(|x| *x = T::zero()));
    }
    // Whole lines at once (a tile group of lines at a time): long runs per
    // line read faster from memory than 64-row pieces of 16 lines in turn
    // (`engine_peer lines2d 3 4096 10`, one thread, min of 4 alternated:
    // 38.1 → 35.3 ms). The filter's gain applied as the rows are loaded
    // where it starts with it (× 1 otherwise: exact).
    let one = T::one();
    let gain = filter.load_gain(n);
    match src {
        Some(s) => {
            scan.add(s);
            lanes::load_strip(
                buf,
                0,
                &s.chunks(n).collect::<Vec<_>>(),
                gain.unwrap_or(&one),
            );
        }
        None => {
            let srcs: Vec<&[T]> = lines.chunks(n).collect();
            lanes::load_strip(buf, 0, &srcs, gain.unwrap_or(&one));
        }
    }
    match gain {
        Some(_) => filter.apply_lines_scaled(buf.as_flattened_mut(), G),
        None => filter.apply_lines(buf.as_flattened_mut(), G, scratch),
    }
    let mut outs: Vec<&mut [T]> = lines.chunks_mut(n).collect();
    lanes::store_strip(&mut outs, buf, 0);
    scan
}

/// Bytes per row of a strip at least: each row of a strip is a separate
/// run in memory, and runs shorter than this read slowly (measured,
/// `spline_filter1d` 4096² along axis 0, one thread: 64 lines of f64 15.5
/// ms, 32 lines 31.0 ms, 16 lines 58.9 ms).
const ROW_BYTES: usize = 512;

/// Bytes of a strip's work buffer where rows are long enough: a quarter
/// of L2, so that the buffer stays there between the causal and the
/// anti-causal pass (measured, 256³ along axis 0, one thread: 256 KiB
/// 17.3 ms, 512 KiB 18.1 ms, 2 MiB 24.5 ms).
const STRIP_BYTES: usize = 256 << 10;

/// Lines per strip for an axis of `n` samples: the strip of `n × w`
/// values within [`STRIP_BYTES`], unless rows would be shorter than
/// [`ROW_BYTES`]; a multiple of 8 (a cache line of f64) up to 1024.
fn strip_width<T>(n: usize) -> usize {
    let size = std::mem::size_of::<T>().max(1);
    let w = (STRIP_BYTES / (n.max(1) * size)).max(ROW_BYTES / size);
    (w / 8 * 8).clamp(8, 1024)
}

/// The filter along a strided `axis` of a standard-layout array: seen as
/// `(outer, n, inner)`, the `inner` lines are cut in strips of `w`
/// (a task each); each strip's `n × w` blocks are filtered where they lie,
/// their rows through the work buffer ([`LineFilter::apply_rows`]: the
/// array read and written once), or read from `src` and written into
/// `data` ([`LineFilter::apply_rows_from`], scanned as they are read).
fn strided_pass<T: Real + Send + Sync>(
    data: &mut [T],
    src: Option<&[T]>,
    shape: &[usize],
    axis: usize,
    filter: &LineFilter<T>,
    on: On<'_, T>,
) -> Scan {
    let n = shape[axis];
    let dims = (
        shape[..axis].iter().product::<usize>(),
        n,
        shape[axis + 1..].iter().product::<usize>(),
    );
    let w = strip_width::<T>(n);
    // A pass from `src` into `data` writes what it does not read again:
    // into an array larger than L3, by streaming stores.
    let stream = src.is_some() && std::mem::size_of_val(data) >= lanes::STREAM_BYTES;
    let mut v = ArrayViewMut3::from_shape(dims, data).expect("standard layout");
    let strips: Vec<ArrayViewMut3<'_, T>> = v.axis_chunks_iter_mut(Axis(2), w).collect();
    let from = src.map(|s| ArrayView3::from_shape(dims, s).expect("the same shape"));
    let froms: Vec<Option<ArrayView3<'_, T>>> = match &from {
        Some(s) => s.axis_chunks_iter(Axis(2), w).map(Some).collect(),
        None => strips.iter().map(|_| None).collect(),
    };
    on.each(
        strips.into_iter().zip(froms).collect(),
        |(strip, from), work| filter_strip(strip, from, filter, work, stream),
    )
}

/// One strip of [`strided_pass`] (`outer × n × w`), block by block;
/// `stream`: its rows written by streaming stores.
fn filter_strip<T: Real>(
    mut strip: ArrayViewMut3<'_, T>,
    from: Option<ArrayView3<'_, T>>,
    filter: &LineFilter<T>,
    work: &mut Work<T>,
    stream: bool,
) -> Scan {
    let mut scan = Scan::default();
    let Work { rows: buf, scratch } = work;
    for (k, mut block) in strip.outer_iter_mut().enumerate() {
        let mut rows: Vec<&mut [T]> = block
            .axis_iter_mut(Axis(0))
            .map(|r| r.into_slice().expect("a row of a standard-layout strip"))
            .collect();
        match &from {
            Some(s) => {
                let block = s.index_axis(Axis(0), k);
                let src: Vec<&[T]> = block
                    .axis_iter(Axis(0))
                    .map(|r| r.to_slice().expect("a row of a standard-layout strip"))
                    .collect();
                filter.apply_rows_from(&src, &mut rows, buf, scratch, &mut scan, stream);
            }
            None => filter.apply_rows(&mut rows, buf, scratch),
        }
    }
    scan
}

/// Replaces `a` by its coefficients along every axis (scipy's
/// `spline_filter`): the tensor-product interpolation coefficients; non-finite
/// samples by the filter's [`NanPolicy`] ([`filter_missing`]). A
/// standard-layout array of three or more dimensions is filtered along
/// axis 0, then slab by slab along the others (module documentation).
///
/// **Accuracy**: per axis the [`LineFilter`] route's; the truncated route compounds to `((A
/// + b)^D − A^D) max|s|` (module documentation); scipy agreement in
/// `verify/tests/it/engine_scipy.rs::spline_filter_matches_scipy`.
pub fn spline_filter<T, S, D>(
    a: &mut ArrayBase<S, D>,
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    S: DataMut<Elem = T>,
    D: Dimension,
{
    let axes: Vec<usize> = (0..a.ndim()).collect();
    if !scan_samples(a, filter, a.ndim())? {
        return filter_missing_in_place(a, &axes, filter);
    }
    filter_axes_unchecked(a, &axes, filter)
}

/// `src` filtered along `axes` in turn (every axis: [`spline_filter`];
/// one: [`spline_filter1d`]) into `out`. Where both are in standard
/// layout the first pass reads `src` and writes `out` (the copy fused into
/// it), checking the samples as it reads them (finite, and below the
/// overflow limit [`LineFilter::check_magnitude`]); on failure `out`
/// holds unspecified values and the error says why. A non-finite sample
/// found there is handled by the filter's [`NanPolicy`] ([`filter_missing`],
/// which reads `src` again: only then). Otherwise (other
/// layouts, one line, no axes) `src` is copied and checked in one pass on
/// the pool first (the first touch of `out`'s pages included), then
/// filtered in place. `filter` `None`: the copy only (degrees 0 and 1).
///
/// **Method**, **accuracy** and **source**: those of [`spline_filter`]
/// (scipy agreement in `verify/tests/it/engine_scipy.rs::spline_filter_matches_scipy`;
/// equal to the in-place call in
/// `verify/tests/it/engine_properties.rs::filtering_a_copy_equals_filtering_in_place`).
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
    let shape = out.shape().to_vec();
    let one_line = axes.iter().any(|&k| src.len() == shape[k]);
    if let (Some(f), Some(s), Some(d), false, false) = (
        filter,
        src.as_slice(),
        out.as_slice_mut(),
        one_line,
        axes.is_empty(),
    ) {
        let stash = Stash::default();
        return match filter_run(d, Some(s), &shape, axes, f, On::Pool(&stash)).result() {
            (true, max) => f.check_magnitude(max, axes.len()),
            (false, _) => filter_missing(src, out, axes, f),
        };
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
    let finite = match scanned {
        Some((true, max)) => filter.check_magnitude(max, axes.len()).map(|()| true)?,
        Some((false, _)) => false,
        None => scan_samples(src, filter, axes.len())?,
    };
    if !finite {
        return filter_missing(src, out, axes, filter);
    }
    filter_axes_unchecked(out, axes, filter)
}

/// The coefficients of `a` along every axis including `pad` coefficients
/// beyond each end of each axis (what evaluation near the ends reads): the
/// result has shape `a.shape()[k] + 2·pad` and element `[i + pad]` is
/// `D_i`, `i ∈ [−pad, ν + pad)`.
///
/// **Method**: [`padded_extension`] then the exact prefilter along every axis
/// ([`LineFilter::apply_padded`]); non-finite samples by the filter's
/// [`NanPolicy`] as in [`filter_missing`] (`Propagate`: every coefficient,
/// `Local`: the folded certified half-width on the padded layout). **Accuracy**: as [`LineFilter::apply_padded`]
/// (`verify/tests/it/engine_properties.rs::nearest_outside_the_grid_is_the_edge_extended_spline`).
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
    let run = |a: ArrayView<'_, T, D>| {
        pad_lanes(&a, pad, |buf| {
            filter.apply_padded(buf, pad, &mut Vec::new())
        })
    };
    if scan_samples(a, filter, a.ndim())? {
        return run(a.view());
    }
    // The missing-sample path of every route (`missing`), on the padded
    // layout: the output grows by `pad`, so it is filled into a copy.
    let mut filled = try_to_owned(a, "the samples with missing ones filled")?;
    let mask = fill(a, &mut filled, a.ndim(), filter)?;
    let mut c = run(filled.view())?;
    let axes: Vec<usize> = (0..a.ndim()).collect();
    write_nan(&mut c, &pattern(&mask, &axes, filter, pad));
    Ok(c)
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
    pad_lanes(a, pad, |buf| {
        let s = buf[pad..buf.len() - pad].to_vec();
        for (j, o) in buf.iter_mut().enumerate() {
            *o = match mode.fold(j as i64 - pad as i64, s.len()) {
                Some(k) => s[k].clone(),
                None => cval.clone(),
            };
        }
    })
}

/// Every lane of `a`, axis by axis, copied into the middle of a buffer
/// with `pad` slots each side, passed to `fill` and stored whole; the
/// arrays allocated fallibly ([`NdimageError::OutOfMemory`]).
fn pad_lanes<T, S, D>(
    a: &ArrayBase<S, D>,
    pad: usize,
    fill: impl Fn(&mut Vec<T>) + Sync,
) -> Result<Array<T, D>, NdimageError>
where
    T: Real + Send + Sync,
    S: Data<Elem = T>,
    D: Dimension,
{
    const WHAT: &str = "the padded spline coefficients";
    let mut cur = try_to_owned(a, WHAT)?;
    for axis in 0..a.ndim() {
        let mut dim = cur.raw_dim();
        dim[axis] = dim[axis].saturating_add(2 * pad);
        let mut next = try_array(dim, T::zero(), WHAT)?;
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
    Ok(cur)
}

#[cfg(test)]
mod tests {
    //! The slab route and the fused copy against the axis-by-axis passes
    //! (bit for bit: the same operations on every line), and the N-D
    //! result against 128-bit MPFR computed line by line along each axis
    //! with the one-line filter (an independent order of operations).
    use super::*;
    use crate::ndimage::line_filter::Route;
    use crate::ndimage::nan_policy::NanPolicy;
    use crate::scalar::Mp;
    use crate::sspline::SplineFamily;
    use crate::validation::NonFiniteValue;
    use ndarray::{ArrayD, IxDyn};

    /// Arrays of 3 and 4 dimensions: slabs, sub-slabs, an axis of one
    /// sample, and line counts per slab that are no multiple of the
    /// contiguous axis's groups (16 and 32 lines).
    const SHAPES: [&[usize]; 6] = [
        &[9, 17, 13],
        &[40, 3, 33],
        &[2, 1, 5],
        &[3, 5, 4, 19],
        &[4, 2, 33, 3],
        &[6, 40, 40],
    ];

    /// Deterministic samples in [−1, 1) (a Weyl sequence).
    fn samples<T: Real>(shape: &[usize], seed: u64) -> ArrayD<T> {
        let n: usize = shape.iter().product();
        let v = (0..n as u64)
            .map(|i| {
                let x = (i + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ seed;
                T::from_f64_exact((x >> 11) as f64 / (1u64 << 52) as f64 - 1.0)
            })
            .collect();
        ArrayD::from_shape_vec(IxDyn(shape), v).expect("shape")
    }

    fn same_bits<T: Real>(a: &ArrayD<T>, b: &ArrayD<T>) -> bool {
        a.iter()
            .zip(b)
            .all(|(x, y)| x.to_f64().to_bits() == y.to_f64().to_bits())
    }

    fn slabs_equal_axis_by_axis<T: Real + Send + Sync>() {
        for shape in SHAPES {
            let a = samples::<T>(shape, 7);
            let axes: Vec<usize> = (0..shape.len()).collect();
            for degree in [2u32, 3, 4, 5] {
                let family = SplineFamily::Order(degree + 1);
                for mode in Mode::ALL {
                    let f = LineFilter::<T>::new(&family, mode, 0.25, Route::Exact).unwrap();
                    let mut want = a.clone();
                    for &axis in &axes {
                        spline_filter1d(&mut want, axis, &f).unwrap();
                    }
                    let mut got = a.clone();
                    spline_filter(&mut got, &f).unwrap();
                    assert!(
                        same_bits(&got, &want),
                        "in place {shape:?} {degree} {mode:?}"
                    );
                    let mut got = ArrayD::from_elem(IxDyn(shape), T::zero());
                    spline_filter_from(&a, &mut got, &axes, Some(&f)).unwrap();
                    assert!(same_bits(&got, &want), "fused {shape:?} {degree} {mode:?}");
                    // The trailing axes alone, read from `a` slab by slab.
                    let mut want = a.clone();
                    for &axis in &axes[1..] {
                        spline_filter1d(&mut want, axis, &f).unwrap();
                    }
                    let mut got = ArrayD::from_elem(IxDyn(shape), T::zero());
                    spline_filter_from(&a, &mut got, &axes[1..], Some(&f)).unwrap();
                    assert!(
                        same_bits(&got, &want),
                        "trailing {shape:?} {degree} {mode:?}"
                    );
                }
            }
        }
    }

    /// [`spline_filter`] (slabs) and [`spline_filter_from`] (the copy fused
    /// into the first pass, then slabs) give the bits of one pass per axis
    /// over the whole array ([`spline_filter1d`] axis after axis), in f64
    /// and f32, every mode, degrees 2 to 5 (4 and 5: the two poles'
    /// cascade).
    #[test]
    fn slabs_and_fused_copy_equal_axis_by_axis_bit_for_bit() {
        slabs_equal_axis_by_axis::<f64>();
        slabs_equal_axis_by_axis::<f32>();
    }

    /// The N-D coefficients in `T` against the exact ones: 128-bit MPFR,
    /// each lane of each axis filtered alone by the one-line recursion.
    /// Each axis adds at most `64 u A` of rounding per unit of its input
    /// (`A = 1/|V(−1)|`, `u` the unit roundoff) and amplifies what came
    /// before by `A`, so over `D` axes `|D − D_exact| ≤ 64 u D A^D` (max|s|
    /// = 1).
    fn matches_mpfr<T: Real + Send + Sync>() {
        type W = Mp<128>;
        let u = 2f64.powi(-(T::BITS as i32));
        for shape in [&SHAPES[0], &SHAPES[3]] {
            let a = samples::<T>(shape, 11);
            let axes: Vec<usize> = (0..shape.len()).collect();
            for degree in [3u32, 4, 5] {
                let family = SplineFamily::Order(degree + 1);
                for mode in [Mode::Mirror, Mode::Reflect, Mode::Nearest, Mode::GridWrap] {
                    let f = LineFilter::<T>::new(&family, mode, 0.0, Route::Exact).unwrap();
                    let mut got = ArrayD::from_elem(IxDyn(shape), T::zero());
                    spline_filter_from(&a, &mut got, &axes, Some(&f)).unwrap();
                    let wide = LineFilter::<W>::new(&family, mode, 0.0, Route::Exact).unwrap();
                    let mut want = a.mapv(|x| W::from_f64_exact(x.to_f64()));
                    for &axis in &axes {
                        for mut lane in want.lanes_mut(Axis(axis)) {
                            let mut line = lane.to_vec();
                            wide.apply(&mut line, &mut Vec::new());
                            lane.iter_mut().zip(line).for_each(|(d, s)| *d = s);
                        }
                    }
                    let amp = wide.recursive().amplification().to_f64();
                    let allowed = 64.0 * u * axes.len() as f64 * amp.powi(axes.len() as i32);
                    let diff = got
                        .iter()
                        .zip(&want)
                        .fold(0.0f64, |m, (x, y)| m.max((x.to_f64() - y.to_f64()).abs()));
                    assert!(
                        diff <= allowed,
                        "{} bits {shape:?} d={degree} {mode:?}: {diff:e} > {allowed:e}",
                        T::BITS
                    );
                }
            }
        }
    }

    #[test]
    fn nd_coefficients_match_mpfr_line_by_line() {
        matches_mpfr::<f64>();
        matches_mpfr::<f32>();
    }

    /// A non-finite sample or one above the overflow limit, read by the
    /// fused first pass (strided or contiguous, or by the slabs), is
    /// reported as the copying route reports it.
    #[test]
    fn the_fused_pass_reports_bad_samples() {
        let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact)
            .unwrap();
        let shape = [6, 7, 9];
        let at = [4, 2, 5];
        let flat = (at[0] * 7 + at[1]) * 9 + at[2];
        for axes in [&[0usize, 1, 2][..], &[2], &[1, 2]] {
            for bad in [f64::NAN, f64::INFINITY] {
                let mut a = samples::<f64>(&shape, 3);
                a[IxDyn(&at)] = bad;
                let mut out = ArrayD::from_elem(IxDyn(&shape), 0.0);
                let raise = f.clone().with_nan_policy(NanPolicy::Raise).unwrap();
                let err = spline_filter_from(&a, &mut out, axes, Some(&raise)).unwrap_err();
                let value = NonFiniteValue::of(&bad).unwrap();
                assert_eq!(
                    err,
                    NdimageError::NonFinite { index: flat, value },
                    "{axes:?}"
                );
            }
            let mut a = samples::<f64>(&shape, 3);
            a[IxDyn(&at)] = 1e307;
            let mut out = ArrayD::from_elem(IxDyn(&shape), 0.0);
            let err = spline_filter_from(&a, &mut out, axes, Some(&f)).unwrap_err();
            assert!(
                matches!(err, NdimageError::Overflow { max, .. } if max == 1e307),
                "{axes:?}: {err}"
            );
        }
    }
}
