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
use super::alloc::try_padded_zeros;
use super::alloc::try_to_owned;
use super::block_filter::BlockPrefilter;
use super::lanes;
use super::line_filter::{BlockIo, LineFilter, RowBlocks, RowCheck, StripRows, rows_as_compute};
use super::missing::{fill, fill_filter_mark, pattern};
use super::mode::Mode;
use super::nan_policy::{first_non_finite, write_nan};
use super::samples::{Sample, Stored};
use super::stash::Stash;
use crate::scalar::Real;
use ndarray::{
    Array, ArrayBase, ArrayView3, ArrayViewMut3, Axis, Data, DataMut, Dimension, Slice, Zip,
};
use rayon::prelude::*;

/// The first non-finite element (in logical order) of samples read into
/// `T`, as an error.
pub(crate) fn check_finite<T, E, S, D>(a: &ArrayBase<S, D>) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    S: Data<Elem = E>,
    D: Dimension,
{
    if a.is_empty() {
        return Err(NdimageError::Empty);
    }
    if let Some(s) = a.as_slice_memory_order() {
        // Fast path: one vectorised pass on the pool; the position only on failure.
        if scan::<T, E>(s).0 {
            return Ok(());
        }
    }
    first_non_finite::<T, _, _, _>(a)
}

/// The finiteness and overflow checks ([`LineFilter::check_magnitude_for`]
/// coefficients stored as `O`) in one pass over the samples: `Ok(true)`
/// where every sample is finite (and below the overflow limit),
/// `Ok(false)` where some is not (for [`filter_missing`] to handle by the
/// filter's [`NanPolicy`]).
fn scan_samples<T, E, O, S, D>(
    a: &ArrayBase<S, D>,
    filter: &LineFilter<T>,
    axes: usize,
) -> Result<bool, NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Stored<T>,
    S: Data<Elem = E>,
    D: Dimension,
{
    if a.is_empty() {
        return Err(NdimageError::Empty);
    }
    let (finite, max) = match a.as_slice_memory_order() {
        Some(s) => scan::<T, E>(s),
        None => {
            let mut scan = Scan::default();
            a.iter()
                .for_each(|x| scan.add(std::slice::from_ref(&x.widen())));
            scan.result()
        }
    };
    if finite {
        filter.check_magnitude_for::<O>(max, axes)?;
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
pub fn filter_missing<T, E, O, S1, S2, D>(
    src: &ArrayBase<S1, D>,
    out: &mut ArrayBase<S2, D>,
    axes: &[usize],
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
    S1: Data<Elem = E>,
    S2: DataMut<Elem = O>,
    D: Dimension,
{
    fill_filter_mark(src, out, axes, filter, |o| {
        filter_axes_unchecked(o, axes, filter)
    })
}

/// [`filter_missing`] in place.
fn filter_missing_in_place<T, O, S, D>(
    a: &mut ArrayBase<S, D>,
    axes: &[usize],
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    O: Sample<T> + Stored<T>,
    S: DataMut<Elem = O>,
    D: Dimension,
{
    let src = try_to_owned(a, "a copy of the samples with missing ones")?;
    filter_missing(&src, a, axes, filter)
}

/// Values per task of the scans and copies: 256 KiB of `f64` (the pool's
/// overhead per task is then well below the time to stream it).
const SCAN_BLOCK: usize = 1 << 15;

/// Whether every value of `s` (read into `T`) is finite, and `max|s|` (0
/// for scalars of more than 53 bits, which cannot overflow): one pass on
/// the pool.
fn scan<T: Real + Send + Sync, E: Sample<T>>(s: &[E]) -> (bool, f64) {
    s.par_chunks(SCAN_BLOCK)
        .map(|b| {
            let mut scan = Scan::default();
            scan.add_samples(b);
            scan.result()
        })
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

    /// Takes in the values of samples `s` read into `T` (themselves where
    /// they are of type `T`; otherwise widened a short run at a time).
    fn add_samples<T: Real, E: Sample<T>>(&mut self, s: &[E]) {
        if let Some(t) = E::as_compute(s) {
            return self.add(t);
        }
        const RUN: usize = 256;
        let mut buf = vec![T::zero(); s.len().min(RUN)];
        for c in s.chunks(RUN) {
            E::widen_into(c, &mut buf);
            self.add(&buf[..c.len()]);
        }
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

/// Copies `src` into `dst` on the pool (widened into `T`), scanning each
/// block ([`scan`]) while it is in L1: the copy, the finiteness and the
/// magnitude check in one pass (and the first touch of `dst`'s pages on
/// the thread that will filter them).
fn copy_scan<T: Real + Send + Sync, E: Sample<T>>(src: &[E], dst: &mut [T]) -> (bool, f64) {
    dst.par_chunks_mut(SCAN_BLOCK)
        .zip(src.par_chunks(SCAN_BLOCK))
        .map(|(d, s)| {
            E::widen_into(s, d);
            scan_block(d)
        })
        .reduce(|| (true, 0.0), |a, b| (a.0 & b.0, a.1.max(b.1)))
}

/// Whether `O` is the compute type `T` itself (its buffers are `T`'s).
fn is_compute<T, O: Stored<T>>() -> bool {
    O::as_compute_mut(&mut []).is_some()
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
/// by the filter's [`NanPolicy`] ([`filter_missing`]). The elements of `a`
/// may be of another type than the filter's `T` ([`Sample`] and
/// [`Stored`]: `f32` storage filtered in `f64`): each line is read into `T`,
/// filtered, and stored rounded once, as scipy filters a float32 array
/// into a float32 output (float64 line buffers).
///
/// **Accuracy**: the [`LineFilter`] route's per line; scipy 1.17.1's output within 16 ulps
/// of max|value| (`verify/tests/it/engine_scipy.rs::spline_filter_matches_scipy`).
///
/// ```
/// use splinelab::prelude::*;
/// let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
/// let mut a: ndarray::Array2<f64> = ndarray::array![[1.0, 2.0, 0.0], [3.0, 1.0, 5.0]];
/// spline_filter1d(&mut a, 1, &f).unwrap();
/// // Mirror ends: (4 D_0 + 2 D_1)/6 = s_0 on every row.
/// assert!(((4.0 * a[[1, 0]] + 2.0 * a[[1, 1]]) / 6.0 - 3.0).abs() < 1e-15);
/// ```
pub fn spline_filter1d<T, O, S, D>(
    a: &mut ArrayBase<S, D>,
    axis: usize,
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    O: Sample<T> + Stored<T>,
    S: DataMut<Elem = O>,
    D: Dimension,
{
    check_axis(&a.raw_dim(), axis)?;
    if !scan_samples::<T, O, O, _, _>(a, filter, 1)? {
        return filter_missing_in_place(a, &[axis], filter);
    }
    filter_axis_unchecked(a, axis, filter)
}

/// [`spline_filter1d`] on checked input. A single long line under
/// [`Route::Truncated`](super::line_filter::Route::Truncated) runs in
/// certified blocks on the pool ([`BlockPrefilter::apply_line_into`]);
/// everything else by lines.
fn filter_axis_unchecked<T, O, S, D>(
    a: &mut ArrayBase<S, D>,
    axis: usize,
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    O: Sample<T> + Stored<T>,
    S: DataMut<Elem = O>,
    D: Dimension,
{
    let blocks = BlockPrefilter::from_line_filter(filter).filter(|b| b.pays_off(a.len()));
    if let (Some(b), true) = (blocks, a.len() == a.shape()[axis])
        && let Some(line) = a.as_slice_memory_order_mut().and_then(O::as_compute_mut)
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
/// lane through a contiguous copy (in `T`, stored back as `O`).
fn filter_lines<T, O, S, D>(a: &mut ArrayBase<S, D>, axis: usize, filter: &LineFilter<T>)
where
    T: Real + Send + Sync,
    O: Sample<T> + Stored<T>,
    S: DataMut<Elem = O>,
    D: Dimension,
{
    let shape = a.shape().to_vec();
    if a.len() > shape[axis]
        && let Some(data) = a.as_slice_mut()
    {
        axis_pass::<T, O, O>(
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
        match lane.as_slice_mut().and_then(O::as_compute_mut) {
            Some(line) => filter.apply(line, &mut scratch),
            None => {
                let mut line: Vec<T> = lane.iter().map(Sample::widen).collect();
                filter.apply(&mut line, &mut scratch);
                for (d, s) in lane.iter_mut().zip(&line) {
                    *d = O::store(s);
                }
            }
        }
    });
}

/// The filter along `axes` in turn of checked samples. A standard-layout
/// array in passes ([`filter_run`]: the trailing axes slab by slab);
/// otherwise, or where one axis holds every element (one line: the
/// certified blocks' case), axis by axis ([`filter_axis_unchecked`]).
fn filter_axes_unchecked<T, O, S, D>(
    a: &mut ArrayBase<S, D>,
    axes: &[usize],
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    O: Sample<T> + Stored<T>,
    S: DataMut<Elem = O>,
    D: Dimension,
{
    let shape = a.shape().to_vec();
    let one_line = axes.iter().any(|&k| a.len() == shape[k]);
    match a.as_slice_mut() {
        Some(data) if !one_line => {
            filter_run::<T, O, O>(
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

/// The work buffers of one task: `rows` (a strip's or a group's rows),
/// the filter's `scratch`, and `wide` (a block read into `T` where the
/// array's elements are of another type).
struct Work<T> {
    rows: Vec<T>,
    scratch: Vec<T>,
    wide: Vec<T>,
    blocks: RowBlocks<T>,
}

impl<T> Default for Work<T> {
    fn default() -> Self {
        Work {
            rows: Vec::new(),
            scratch: Vec::new(),
            wide: Vec::new(),
            blocks: RowBlocks::default(),
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
            // One task (a small array's one group): no parallel iterator
            // to set up around it.
            On::Pool(stash) if items.len() == 1 => {
                stash.with(|work| On::Here(work).each(items, task))
            }
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
/// Samples of another type than `T` are widened block by block as the
/// pass reads them, and results of another type are stored rounded once
/// at the end of each pass ([`Sample`], [`Stored`]: the same operations
/// in `T` on every line, through a work block that stays in cache).
///
/// Where the remaining axes are at least two trailing ones (none is axis
/// 0) of an array of three or more dimensions, each slab `data[i, …]` is
/// filtered along all of them by one task while it stays in cache
/// ([`slab_pass`]): `256³` is read and written twice (axis 0, then the
/// slabs), not once per axis. Every line gets the operations it gets in
/// an axis-by-axis pass (lines side by side are independent columns), so
/// the same bits.
fn filter_run<T, E, O>(
    data: &mut [O],
    mut src: Option<&[E]>,
    shape: &[usize],
    axes: &[usize],
    filter: &LineFilter<T>,
    mut on: On<'_, T>,
) -> Scan
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
{
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
fn slab_pass<T, E, O>(
    data: &mut [O],
    src: Option<&[E]>,
    shape: &[usize],
    axes: &[usize],
    filter: &LineFilter<T>,
    on: On<'_, T>,
) -> Scan
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
{
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
fn pieces<'a, O, E>(
    data: &'a mut [O],
    src: Option<&'a [E]>,
    len: usize,
) -> Vec<(&'a mut [O], Option<&'a [E]>)> {
    match src {
        Some(s) => data.chunks_mut(len).zip(s.chunks(len).map(Some)).collect(),
        None => data.chunks_mut(len).map(|d| (d, None)).collect(),
    }
}

/// One pass along `axis` of the standard-layout array `data` of `shape`
/// (more than one line), reading from `src` when given (and scanning it):
/// strided axes by strips ([`strided_pass`]), the last by groups of lines
/// ([`last_pass`]).
fn axis_pass<T, E, O>(
    data: &mut [O],
    src: Option<&[E]>,
    shape: &[usize],
    axis: usize,
    filter: &LineFilter<T>,
    on: On<'_, T>,
) -> Scan
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
{
    if axis + 1 < shape.len() {
        return strided_pass(data, src, shape, axis, filter, on);
    }
    let n = shape[axis];
    if std::mem::size_of::<T>() <= 4 {
        last_pass::<T, E, O, { 2 * lanes::LINES }>(data, src, n, filter, on)
    } else {
        last_pass::<T, E, O, { lanes::LINES }>(data, src, n, filter, on)
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
fn last_pass<T, E, O, const G: usize>(
    data: &mut [O],
    src: Option<&[E]>,
    n: usize,
    filter: &LineFilter<T>,
    on: On<'_, T>,
) -> Scan
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
{
    on.each(pieces(data, src, n * G), |(lines, src), work| {
        last_group_as::<T, E, O, G>(lines, src, n, filter, work)
    })
}

/// One group of [`last_pass`] whatever the element types: lines and
/// samples of type `T` go straight to [`last_group`]; samples of another
/// type are widened into the lines first (where those are `T`'s), or the
/// group goes through the task's `wide` block in `T` and is stored rounded
/// once (where they are not).
fn last_group_as<T: Real, E: Sample<T>, O: Sample<T> + Stored<T>, const G: usize>(
    lines: &mut [O],
    src: Option<&[E]>,
    n: usize,
    filter: &LineFilter<T>,
    work: &mut Work<T>,
) -> Scan {
    if let Some(scan) = last_group_in_blocks::<T, E, O, G>(lines, src, n, filter, work) {
        return scan;
    }
    if let Some(t) = O::as_compute_mut(lines) {
        let Some(s) = src else {
            return last_group::<T, G>(t, None, n, filter, work);
        };
        if let Some(s) = E::as_compute(s) {
            return last_group::<T, G>(t, Some(s), n, filter, work);
        }
        // Widened into the lines, scanned there while in cache, then
        // filtered in place.
        E::widen_into(s, t);
        let mut scan = Scan::default();
        scan.add(t);
        return scan.merge(last_group::<T, G>(t, None, n, filter, work));
    }
    let mut wide = std::mem::take(&mut work.wide);
    wide.resize(lines.len(), T::zero());
    let mut scan = Scan::default();
    match src {
        Some(s) => {
            E::widen_into(s, &mut wide);
            scan.add(&wide);
        }
        None => O::widen_into(lines, &mut wide),
    }
    last_group::<T, G>(&mut wide, None, n, filter, work);
    O::store_from(&wide, lines);
    work.wide = wide;
    scan
}

/// Bytes of a group's whole buffers (`n × G` in `T`, twice where the
/// lines are of another type) from which [`last_pass`] filters it in
/// blocks of rows ([`LineFilter::filter_in_blocks`]): the blocks read the
/// group twice (the second time from L2), which at 4096 samples of `f64`
/// lines (512 KiB) made `spline_filter1d` along the last axis 1.3–1.8×
/// slower on one thread (4096² f64 and f32, alternated, min of 5:
/// 39.0–40.7 → 54.1–70.3 ms), so below 1 MiB a thread the whole buffer
/// stays; `f32` coefficients of an `f64` filter (two buffers, 1 MiB at
/// 4096) run in blocks as fast (`spline_filter(output=float32)` 84–120 →
/// 77–101 ms).
const GROUP_BLOCKS_FROM: usize = 1 << 20;

/// One group of [`last_pass`] in blocks of rows where its whole buffers
/// would reach [`GROUP_BLOCKS_FROM`]: the work
/// memory of [`LineFilter::filter_in_blocks`] instead, the same bits.
/// `None`: not taken.
fn last_group_in_blocks<T: Real, E: Sample<T>, O: Sample<T> + Stored<T>, const G: usize>(
    lines: &mut [O],
    src: Option<&[E]>,
    n: usize,
    filter: &LineFilter<T>,
    work: &mut Work<T>,
) -> Option<Scan> {
    // The whole route holds the group in `T` (and again, widened, where
    // the lines are not `T`'s).
    let copies = if is_compute::<T, O>() { 1 } else { 2 };
    if n * G * std::mem::size_of::<T>() * copies < GROUP_BLOCKS_FROM || !filter.runs_in_blocks(n) {
        return None;
    }
    let mut scan = Scan::default();
    let pieces = std::mem::take(&mut work.wide);
    let (done, pieces) = match src {
        Some(_) => {
            let seen = &mut scan;
            let mut io = GroupLines::<T, E, O, Scan, G> {
                src,
                lines,
                n,
                seen,
                pieces,
            };
            (
                filter.filter_in_blocks(&mut io, &mut work.blocks),
                io.pieces,
            )
        }
        None => {
            let seen = &mut ();
            let mut io = GroupLines::<T, O, O, (), G> {
                src: None,
                lines,
                n,
                seen,
                pieces,
            };
            (
                filter.filter_in_blocks(&mut io, &mut work.blocks),
                io.pieces,
            )
        }
    };
    work.wide = pieces;
    done.then_some(scan)
}

/// A group of at most `G` contiguous lines of `n` samples as the rows of
/// [`LineFilter::filter_in_blocks`]: row `i` holds sample `i` of each line
/// times the gain (transposed in tiles, [`lanes::load_strip`], as
/// [`last_group`] loads them; the columns of absent lines zero). Read from
/// `src` (`seen` taking in each piece on its first read) or in place from
/// `lines`, widened into `pieces` where of another type than `T`; written
/// back into `lines` ([`lanes::store_strip`]), rounded once where they are
/// not `T`'s.
struct GroupLines<'a, T, E, O, F, const G: usize> {
    src: Option<&'a [E]>,
    lines: &'a mut [O],
    n: usize,
    seen: &'a mut F,
    pieces: Vec<T>,
}

impl<T, E, O, F, const G: usize> BlockIo<T> for GroupLines<'_, T, E, O, F, G>
where
    T: Real,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
    F: RowCheck,
{
    fn shape(&self) -> (usize, usize) {
        (self.n, G)
    }

    fn read_into(&mut self, lo: usize, hi: usize, rows: &mut [T], gain: &T, first: bool) {
        let (n, rows) = (self.n, rows.as_chunks_mut::<G>().0);
        let seen = first.then_some(&mut *self.seen);
        match self.src {
            Some(s) => load_pieces(s, n, (lo, hi), rows, gain, &mut self.pieces, seen),
            None => load_pieces(self.lines, n, (lo, hi), rows, gain, &mut self.pieces, seen),
        }
    }

    fn write(&mut self, lo: usize, block: &[T]) {
        let rows = block.as_chunks::<G>().0;
        let (n, len) = (self.n, rows.len());
        if is_compute::<T, O>() {
            let mut outs: Vec<&mut [T]> = self
                .lines
                .chunks_mut(n)
                .filter_map(O::as_compute_mut)
                .collect();
            return lanes::store_strip(&mut outs, rows, lo);
        }
        let count = self.lines.len() / n.max(1);
        self.pieces.resize(count * len, T::zero());
        let mut outs: Vec<&mut [T]> = self.pieces.chunks_mut(len.max(1)).collect();
        lanes::store_strip(&mut outs, rows, 0);
        for (line, p) in self.lines.chunks_mut(n).zip(self.pieces.chunks(len.max(1))) {
            O::store_from(p, &mut line[lo..lo + len]);
        }
    }
}

/// The pieces `lo .. hi` of the contiguous `lines` of `n` samples into
/// `rows` (column `j` = line `j`, the columns of absent lines zero) times
/// `gain` ([`lanes::load_strip`]), read into `T` through `wide` where they
/// are of another type; `seen` takes in each piece as it is.
fn load_pieces<T: Real, S: Sample<T>, F: RowCheck, const G: usize>(
    lines: &[S],
    n: usize,
    (lo, hi): (usize, usize),
    rows: &mut [[T; G]],
    gain: &T,
    wide: &mut Vec<T>,
    seen: Option<&mut F>,
) {
    let pieces: Vec<&[S]> = lines.chunks(n.max(1)).map(|l| &l[lo..hi]).collect();
    let pieces = rows_as_compute(&pieces, wide);
    if pieces.len() < G {
        rows.iter_mut()
            .for_each(|r| r[pieces.len()..].iter_mut().for_each(|x| *x = T::zero()));
    }
    if let Some(seen) = seen {
        pieces.iter().for_each(|p| seen.row(p));
    }
    lanes::load_strip(rows, 0, &pieces, gain);
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
    let Work { rows, scratch, .. } = work;
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
    // The group's lines in arrays of `G` (no allocation: a small array is
    // one group, and a call's few allocations are much of its time).
    let mut srcs: [&[T]; G] = [&[]; G];
    let read = src.unwrap_or(&*lines);
    if let Some(s) = src {
        scan.add(s);
    }
    for (r, line) in srcs.iter_mut().zip(read.chunks(n)) {
        *r = line;
    }
    lanes::load_strip(buf, 0, &srcs[..count], gain.unwrap_or(&one));
    match gain {
        Some(_) => filter.apply_lines_scaled(buf.as_flattened_mut(), G),
        None => filter.apply_lines(buf.as_flattened_mut(), G, scratch),
    }
    let mut outs: [&mut [T]; G] = std::array::from_fn(|_| <&mut [T]>::default());
    for (o, line) in outs.iter_mut().zip(lines.chunks_mut(n)) {
        *o = line;
    }
    lanes::store_strip(&mut outs[..count], buf, 0);
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

/// Bytes of a strip's whole work buffer (`n × w`) above which
/// [`filter_strip`] filters it in blocks of rows
/// ([`LineFilter::filter_in_blocks`]): a strip of 64 lines of `f64` is
/// 2 MiB at 4096 samples, a buffer a thread that put the prefilter's peak
/// memory 4 MiB above scipy's on two threads (4096² float32,
/// `python/bench/float32.py memory`: spline_filter 132.5 → 129.6 MiB,
/// scipy 128.2); the blocks' second read of the strip comes from L3 and
/// their buffers stay in L2, as fast as the whole buffer (one thread, 4096²,
/// alternated, min of 5: `spline_filter1d` along axis 0 61–75 → 59–77 ms).
const STRIP_BLOCKS_FROM: usize = 256 << 10;

/// [`STRIP_BLOCKS_FROM`] for a filter of one pole; 4 MiB for two (the
/// cascade of degrees 4 and 5, twice the arithmetic per sample, whose
/// recomputation in the blocks showed: quintic `spline_filter` of 4096²
/// float32, one thread, alternated, min of 5: f64 68–92 → 102–137 ms,
/// `compute="float32"` 46–58 → 65–73 ms), so that a quintic strip of 64
/// lines keeps its whole buffer up to 8192 samples.
fn strip_blocks_from<T: Real>(filter: &LineFilter<T>) -> usize {
    if filter.recursive().poles().len() > 1 {
        4 << 20
    } else {
        STRIP_BLOCKS_FROM
    }
}

/// The filter along a strided `axis` of a standard-layout array: seen as
/// `(outer, n, inner)`, the `inner` lines are cut in strips of `w`
/// (a task each); each strip's `n × w` blocks are filtered where they lie,
/// their rows through the work buffer ([`LineFilter::apply_rows`]: the
/// array read and written once), or read from `src` and written into
/// `data` ([`LineFilter::apply_rows_from`], scanned as they are read).
fn strided_pass<T, E, O>(
    data: &mut [O],
    src: Option<&[E]>,
    shape: &[usize],
    axis: usize,
    filter: &LineFilter<T>,
    on: On<'_, T>,
) -> Scan
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
{
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
    let strips: Vec<ArrayViewMut3<'_, O>> = v.axis_chunks_iter_mut(Axis(2), w).collect();
    let from = src.map(|s| ArrayView3::from_shape(dims, s).expect("the same shape"));
    let froms: Vec<Option<ArrayView3<'_, E>>> = match &from {
        Some(s) => s.axis_chunks_iter(Axis(2), w).map(Some).collect(),
        None => strips.iter().map(|_| None).collect(),
    };
    on.each(
        strips.into_iter().zip(froms).collect(),
        |(strip, from), work| filter_strip(strip, from, filter, work, stream),
    )
}

/// One strip of [`strided_pass`] (`outer × n × w`), block by block;
/// `stream`: its rows written by streaming stores. Rows and samples of
/// type `T` are filtered where they lie; samples of another type are
/// widened into the rows first (rows of type `T`), or the block goes
/// through the task's `wide` block in `T` and is stored rounded once.
fn filter_strip<T: Real, E: Sample<T>, O: Sample<T> + Stored<T>>(
    mut strip: ArrayViewMut3<'_, O>,
    from: Option<ArrayView3<'_, E>>,
    filter: &LineFilter<T>,
    work: &mut Work<T>,
    stream: bool,
) -> Scan {
    let mut scan = Scan::default();
    let Work {
        rows: buf,
        scratch,
        wide,
        blocks,
    } = work;
    for (k, mut block) in strip.outer_iter_mut().enumerate() {
        let mut rows: Vec<&mut [O]> = block
            .axis_iter_mut(Axis(0))
            .map(|r| r.into_slice().expect("a row of a standard-layout strip"))
            .collect();
        let src_block = from.as_ref().map(|s| s.index_axis(Axis(0), k));
        let src: Option<Vec<&[E]>> = src_block.as_ref().map(|b| {
            b.axis_iter(Axis(0))
                .map(|r| r.to_slice().expect("a row of a standard-layout strip"))
                .collect()
        });
        let (n, w) = (rows.len(), rows.first().map_or(0, |r| r.len()));
        if n * w * std::mem::size_of::<T>() > strip_blocks_from(filter) && filter.runs_in_blocks(n)
        {
            // Long lines: blocks of rows, work memory independent of `n`
            // (the same bits). Rows filtered in place are not scanned.
            let done = match &src {
                Some(s) => {
                    let seen = &mut scan;
                    let io = &mut StripRows {
                        src: Some(s),
                        rows: &mut rows,
                        seen,
                        stream,
                    };
                    filter.filter_in_blocks(io, blocks)
                }
                None => {
                    let seen = &mut ();
                    let io = &mut StripRows::<O, O, ()> {
                        src: None,
                        rows: &mut rows,
                        seen,
                        stream: false,
                    };
                    filter.filter_in_blocks(io, blocks)
                }
            };
            if done {
                continue;
            }
        }
        if is_compute::<T, O>() {
            let mut rows: Vec<&mut [T]> = rows.into_iter().filter_map(O::as_compute_mut).collect();
            let Some(src) = src else {
                filter.apply_rows(&mut rows, buf, scratch);
                continue;
            };
            match src
                .iter()
                .map(|r| E::as_compute(r))
                .collect::<Option<Vec<&[T]>>>()
            {
                Some(s) => filter.apply_rows_from(&s, &mut rows, buf, scratch, &mut scan, stream),
                None => {
                    for (r, s) in rows.iter_mut().zip(&src) {
                        E::widen_into(s, r);
                        scan.add(r);
                    }
                    filter.apply_rows(&mut rows, buf, scratch);
                }
            }
            continue;
        }
        wide.resize(n * w, T::zero());
        let block_t = &mut wide[..n * w];
        match &src {
            Some(src) => {
                for (t, s) in block_t.chunks_mut(w).zip(src) {
                    E::widen_into(s, t);
                }
                scan.add(block_t);
            }
            None => {
                for (t, r) in block_t.chunks_mut(w).zip(&rows) {
                    O::widen_into(r, t);
                }
            }
        }
        let mut rows_t: Vec<&mut [T]> = block_t.chunks_mut(w).collect();
        filter.apply_rows(&mut rows_t, buf, scratch);
        for (r, t) in rows.iter_mut().zip(wide[..n * w].chunks(w)) {
            O::store_from(t, r);
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
pub fn spline_filter<T, O, S, D>(
    a: &mut ArrayBase<S, D>,
    filter: &LineFilter<T>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    O: Sample<T> + Stored<T>,
    S: DataMut<Elem = O>,
    D: Dimension,
{
    let axes: Vec<usize> = (0..a.ndim()).collect();
    if !scan_samples::<T, O, O, _, _>(a, filter, a.ndim())? {
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
/// **Element types.** `src` may hold any [`Sample`] type of the compute
/// type `T` (`f32` samples of an `f64` filter: widened exactly as the
/// first pass reads them, a block at a time, no widened copy of the
/// input), and `out` any type that is both read and stored ([`Stored`]:
/// `f32` coefficients of an `f64` filter are rounded once at the end of
/// each axis' pass, scipy's float64 line buffers written into a float32
/// output).
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
pub fn spline_filter_from<T, E, S1, S2, D>(
    src: &ArrayBase<S1, D>,
    out: &mut ArrayBase<S2, D>,
    axes: &[usize],
    filter: Option<&LineFilter<T>>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    S1: Data<Elem = E>,
    S2: DataMut<Elem = T>,
    D: Dimension,
{
    spline_filter_from_as(src, out, axes, filter)
}

/// [`spline_filter_from`] into coefficients of any type `O` the compute
/// type is stored into and read back from ([`Stored`], [`Sample`]): `f32`
/// coefficients of an `f64` filter, each axis' pass read into `f64`
/// blocks and stored rounded once at its end, as scipy's `spline_filter`
/// computes a float32 `output` (float64 line buffers, the output rounded
/// after every axis); no `f64` array of the output's size.
///
/// ```
/// use splinelab::prelude::*;
/// use splinelab::ndimage::nd_prefilter::spline_filter_from_as;
/// let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
/// let a = ndarray::array![0.1f32, 0.7, 0.2, 0.9];
/// let mut out = ndarray::Array1::<f32>::zeros(4);
/// spline_filter_from_as(&a, &mut out, &[0], Some(&f)).unwrap();
/// let mut wide = a.mapv(f64::from);
/// spline_filter1d(&mut wide, 0, &f).unwrap();
/// assert_eq!(out, wide.mapv(|x| x as f32));
/// ```
pub fn spline_filter_from_as<T, E, O, S1, S2, D>(
    src: &ArrayBase<S1, D>,
    out: &mut ArrayBase<S2, D>,
    axes: &[usize],
    filter: Option<&LineFilter<T>>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
    S1: Data<Elem = E>,
    S2: DataMut<Elem = O>,
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
            (true, max) => f.check_magnitude_for::<O>(max, axes.len()),
            (false, _) => filter_missing(src, out, axes, f),
        };
    }
    if !is_compute::<T, O>() {
        // Results of another type than `T` (f32 coefficients of an f64
        // filter): the first axis lane by lane from `src`, so that the
        // samples are not rounded into `out` before they are filtered.
        return filter_lanes_from(src, out, axes, filter);
    }
    let scanned = match (
        src.as_slice(),
        out.as_slice_mut().and_then(O::as_compute_mut),
    ) {
        (Some(s), Some(d)) => Some(copy_scan(s, d)),
        _ => {
            store_samples(src, out);
            None
        }
    };
    let Some(filter) = filter else {
        return Ok(());
    };
    let finite = match scanned {
        Some((true, max)) => filter
            .check_magnitude_for::<O>(max, axes.len())
            .map(|()| true)?,
        Some((false, _)) => false,
        None => scan_samples::<T, E, O, _, _>(src, filter, axes.len())?,
    };
    if !finite {
        return filter_missing(src, out, axes, filter);
    }
    filter_axes_unchecked(out, axes, filter)
}

/// `out[i] = src[i]` read into `T` and stored as `O`, on the pool.
fn store_samples<T, E, O, S1, S2, D>(src: &ArrayBase<S1, D>, out: &mut ArrayBase<S2, D>)
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Stored<T>,
    S1: Data<Elem = E>,
    S2: DataMut<Elem = O>,
    D: Dimension,
{
    Zip::from(out)
        .and(src)
        .par_for_each(|d, s| *d = O::store(&s.widen()));
}

/// [`spline_filter_from`] where `out` is not of the compute type and the
/// fused pass does not serve (other layouts, one line, no axes): `src`
/// checked, then filtered along the first axis lane by lane (each lane
/// read into `T`, filtered, stored once) and along the others in place;
/// no axes or no filter: `src` stored into `out`.
fn filter_lanes_from<T, E, O, S1, S2, D>(
    src: &ArrayBase<S1, D>,
    out: &mut ArrayBase<S2, D>,
    axes: &[usize],
    filter: Option<&LineFilter<T>>,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
    S1: Data<Elem = E>,
    S2: DataMut<Elem = O>,
    D: Dimension,
{
    let (Some(f), Some((&first, rest))) = (filter, axes.split_first()) else {
        store_samples(src, out);
        return Ok(());
    };
    if !scan_samples::<T, E, O, _, _>(src, f, axes.len())? {
        return filter_missing(src, out, axes, f);
    }
    Zip::from(out.lanes_mut(Axis(first)))
        .and(src.lanes(Axis(first)))
        .par_for_each(|mut o, s| {
            let mut line: Vec<T> = s.iter().map(Sample::widen).collect();
            f.apply(&mut line, &mut Vec::new());
            for (d, v) in o.iter_mut().zip(&line) {
                *d = O::store(v);
            }
        });
    filter_axes_unchecked(out, rest, f)
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
pub fn padded_coefficients<T, E, S, D>(
    a: &ArrayBase<S, D>,
    filter: &LineFilter<T>,
    pad: usize,
) -> Result<Array<T, D>, NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    S: Data<Elem = E>,
    D: Dimension,
{
    let mut c = padded_array::<T, D>(a.raw_dim(), pad)?;
    let mut inner = interior_mut(&mut c, pad);
    // The missing-sample path of every route (`missing`), on the padded
    // layout: the samples with their missing ones filled, then the policy's
    // pattern grown by `pad`.
    let mask = if scan_samples::<T, E, T, _, _>(a, filter, a.ndim())? {
        store_samples(a, &mut inner);
        None
    } else {
        Some(fill(a, &mut inner, a.ndim(), filter)?)
    };
    pad_lanes(&mut c, a.shape(), pad, |buf| {
        filter.apply_padded(buf, pad, &mut Vec::new())
    });
    if let Some(mask) = mask {
        let axes: Vec<usize> = (0..a.ndim()).collect();
        write_nan(&mut c, &pattern(&mask, &axes, filter, pad));
    }
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
    check_finite::<T, _, _, _>(a)?;
    let cval = T::from_f64_exact(cval);
    let mut c = padded_array::<T, D>(a.raw_dim(), pad)?;
    interior_mut(&mut c, pad).assign(a);
    pad_lanes(&mut c, a.shape(), pad, |buf| {
        let s = buf[pad..buf.len() - pad].to_vec();
        for (j, o) in buf.iter_mut().enumerate() {
            *o = match mode.fold(j as i64 - pad as i64, s.len()) {
                Some(k) => s[k].clone(),
                None => cval.clone(),
            };
        }
    });
    Ok(c)
}

/// A zero array of `dim` grown by `pad` on both sides of every axis, in
/// standard layout, allocated fallibly ([`try_padded_zeros`]).
fn padded_array<T: Real, D: Dimension>(
    mut dim: D,
    pad: usize,
) -> Result<Array<T, D>, NdimageError> {
    let (padded, v) = try_padded_zeros(dim.slice(), pad, "padded coefficients")?;
    dim.slice_mut().copy_from_slice(&padded);
    let (expected, got) = (dim.size(), v.len());
    Array::from_shape_vec(dim, v).map_err(|_| NdimageError::BufferLength { expected, got })
}

/// The elements of the padded array `c` away from its pads.
fn interior_mut<T, D: Dimension>(
    c: &mut Array<T, D>,
    pad: usize,
) -> ndarray::ArrayViewMut<'_, T, D> {
    c.slice_each_axis_mut(|ax| Slice::from(pad..ax.len - pad))
}

/// The padded array `c` (of the interior `shape`, grown by `pad` per side)
/// filled lane by lane from its interior, axis by axis: along axis `k`
/// every lane over the whole extent of the axes before it (filled by then)
/// and the interior of those after it, copied into a buffer (its samples in
/// the middle, `pad` slots each side), passed to `fill` and stored whole.
/// In place: one array.
fn pad_lanes<T, D>(
    c: &mut Array<T, D>,
    shape: &[usize],
    pad: usize,
    fill: impl Fn(&mut Vec<T>) + Sync,
) where
    T: Real + Send + Sync,
    D: Dimension,
{
    for axis in 0..shape.len() {
        let mut part = c.slice_each_axis_mut(|ax| {
            let k = ax.axis.index();
            if k > axis {
                Slice::from(pad..pad + shape[k])
            } else {
                Slice::from(..)
            }
        });
        Zip::from(part.lanes_mut(Axis(axis))).par_for_each(|mut lane| {
            let mut buf: Vec<T> = lane.to_vec();
            fill(&mut buf);
            for (d, s) in lane.iter_mut().zip(buf) {
                *d = s;
            }
        });
    }
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

    /// `a` filtered along `axes` in turn, each lane alone through the
    /// whole-line buffer ([`LineFilter::apply_lines`] of one column) in
    /// `T`, and stored as `O` after each axis: the route the blocks replace.
    fn lane_by_lane<T: Real, O: Sample<T> + Stored<T>>(
        a: &ArrayD<O>,
        axes: &[usize],
        f: &LineFilter<T>,
    ) -> ArrayD<O> {
        let mut out = a.clone();
        for &axis in axes {
            for mut lane in out.lanes_mut(Axis(axis)) {
                let src: Vec<O> = lane.to_vec();
                let mut line = vec![T::zero(); src.len()];
                O::widen_into(&src, &mut line);
                f.apply_lines(&mut line, 1, &mut Vec::new());
                let mut stored = src;
                O::store_from(&line, &mut stored);
                lane.iter_mut().zip(stored).for_each(|(d, s)| *d = s);
            }
        }
        out
    }

    /// Lines long enough for blocks of rows (a strided strip of 2100 ×
    /// 64 above [`STRIP_BLOCKS_FROM`] for one pole, two poles' strips in
    /// `line_filter`'s tests; a group of 3 contiguous lines of 8300 above
    /// [`GROUP_BLOCKS_FROM`]) give the bits of each lane filtered alone
    /// through the whole buffer: degrees 2–5 (one pole; two: the cascade), mirror and
    /// reflect, in place and from a copy, f64 and f32 compute, f32 samples
    /// and coefficients of an f64 filter.
    #[test]
    fn long_lines_in_blocks_equal_the_whole_line_bit_for_bit() {
        fn check<T: Real + Send + Sync, O: Sample<T> + Stored<T>>(
            a: &ArrayD<O>,
            f: &LineFilter<T>,
            what: &str,
        ) {
            let bits = |x: &ArrayD<O>| {
                x.iter()
                    .map(|v| v.widen().to_f64().to_bits())
                    .collect::<Vec<_>>()
            };
            for axes in [&[0usize][..], &[1], &[0, 1]] {
                assert!(f.runs_in_blocks(2100));
                let want = lane_by_lane(a, axes, f);
                let mut got = a.clone();
                for &axis in axes {
                    spline_filter1d(&mut got, axis, f).unwrap();
                }
                assert_eq!(bits(&got), bits(&want), "{what} in place {axes:?}");
                let mut got = ArrayD::from_elem(IxDyn(a.shape()), a.iter().next().unwrap().clone());
                spline_filter_from_as(a, &mut got, axes, Some(f)).unwrap();
                assert_eq!(bits(&got), bits(&want), "{what} from a copy {axes:?}");
            }
        }
        for degree in [2u32, 3, 4, 5] {
            let family = SplineFamily::Order(degree + 1);
            for mode in [Mode::Mirror, Mode::Reflect] {
                let f64s = LineFilter::<f64>::new(&family, mode, 0.0, Route::Exact).unwrap();
                let f32s = LineFilter::<f32>::new(&family, mode, 0.0, Route::Exact).unwrap();
                for shape in [[2100usize, 70], [3, 8300]] {
                    let what = format!("degree {degree} {mode:?} {shape:?}");
                    check(&samples::<f64>(&shape, 5), &f64s, &format!("f64 {what}"));
                    check(&samples::<f32>(&shape, 5), &f32s, &format!("f32 {what}"));
                    check::<f64, f32>(
                        &samples::<f32>(&shape, 5),
                        &f64s,
                        &format!("f32 in f64 {what}"),
                    );
                }
            }
        }
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
