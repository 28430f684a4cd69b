//! One long 1-D signal prefiltered in parallel blocks, the paper's
//! locality put to work: the coefficient `D_k = Σ_j c_j s_{k−j}` depends on
//! the samples within `W` of `k` up to `Σ_{|j|>W} |c_j| · max|s|`.
//!
//! Each block `[a, b)` runs the exact recursive filter over the extended
//! samples `s_i`, `i ∈ [a − W, b + W)` (the mode's extension beyond the
//! ends), zero beyond that window (plus the filter's horizon of zeros, so
//! the cascade of passes stays exact to `2^{−BITS−8}`): it computes
//! `Σ_{|j|≤W…} c_j s_{k−j}` over the window, which contains every `j` with
//! `|j| ≤ W`. Hence, with `W` the certified width of a tolerance
//! ([`certified_width`]):
//!
//! `|D_block − D_exact| ≤ bound · max|s| + rounding`, `bound < tol`.
//!
//! The windows' recursions run along consecutive samples in vector lanes
//! (`ndimage::window_recursion`, a private module: the `V`-tap filter by
//! doubling and the recursion of stride `V`, no transposes), every causal
//! pass first and every anti-causal pass after; a window of
//! [`WINDOW_BYTES`] (1024 `f64`) plus its overlaps stays in L1 across the
//! passes, the samples are read once and the coefficients written once, in
//! order, and the next window's memory is fetched while one is filtered.
//!
//! Cost: `(1 + (2W + T)/B)` causal and `(1 + (W + T)/B)` anti-causal
//! passes of the sequential filter's work per pole for windows of `B`
//! samples (`T` the longest pole horizon), spread over the rayon pool in
//! [`TASKS`] tasks. Measured on the 2-core Zen 5 development machine under
//! a load of 4 to 5 (`python/bench/prefilter_ab.py --rounds 7`, one thread,
//! CPU time, min of 7 alternated with the transposed groups of 32 windows
//! this replaced): 10⁷ samples cubic 10.7 → 4.8 ms (1.22× a copy of the
//! same bytes), quintic 12.3 → 8.5 ms (2.1×), f32 cubic 7.3 → 2.5 ms;
//! 10⁶ cubic 0.82 → 0.41 ms (the exact filter 1.79 ms).
//!
//! The windows depend on the line's length only (never on the thread
//! count), and every CPU computes the same bits (the kernels' fused
//! multiply-adds in one order on every target).

use super::NdimageError;
use super::line_filter::{LineFilter, Route};
use super::missing::fill_filter_mark;
use super::mode::Mode;
use super::nan_policy::NanPolicy;
use super::stash::Stash;
use super::window_recursion::{Ahead, WindowRecursion, lanes};
use crate::scalar::Real;
use crate::sspline::SplineFamily;
#[cfg(doc)]
use crate::sspline::width::certified_width;
use ndarray::{ArrayView1, ArrayViewMut1};
use rayon::prelude::*;

/// The block-parallel prefilter (module documentation).
#[derive(Debug, Clone)]
pub struct BlockPrefilter<T> {
    filter: LineFilter<T>,
    overlap: usize,
    bound: f64,
    kernel: WindowRecursion<T>,
}

impl<T: Real + Send + Sync> BlockPrefilter<T> {
    /// Blocks overlapping by the certified width of `tol` for `family`.
    ///
    ///
    /// **Method**: the certified half-width `W` of `tol` ([`certified_width`], the pole tail
    /// bound `Σ_{|j|>W} |c_j| < tol`) and the exact recursive [`LineFilter`]. **Accuracy**:
    /// [`Self::bound`], tested in
    /// `verify/tests/it/engine_properties.rs::parallel_blocks_stay_within_the_bound_of_the_sequential_filter`.
    /// **Source**: seed 000 eq 10 (truncation) with the tail bound; the recursion of Unser,
    /// Aldroubi and Eden (1993).
    ///
    /// ```
    /// use splinelab::sspline::SplineFamily;
    /// use splinelab::ndimage::{mode::Mode, block_filter::BlockPrefilter};
    /// let f = BlockPrefilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, 1e-12).unwrap();
    /// assert!(f.bound() < 1e-12 && f.overlap() == 22);
    /// ```
    pub fn new(
        family: &SplineFamily,
        mode: Mode,
        cval: f64,
        tol: f64,
    ) -> Result<Self, NdimageError> {
        // The truncated route's filter runs the exact recursion on a line
        // (the blocks' own kernel) and knows its certified width.
        let filter = LineFilter::new(family, mode, cval, Route::Truncated { tol })?;
        Ok(BlockPrefilter {
            kernel: kernel(&filter),
            overlap: filter
                .half_width()
                .expect("the truncated route has a width"),
            bound: filter.bound(),
            filter,
        })
    }

    /// The blocks with `policy` for non-finite samples
    /// ([`LineFilter::with_nan_policy`]; default `Propagate`).
    pub fn with_nan_policy(mut self, policy: NanPolicy) -> Result<Self, NdimageError> {
        self.filter = self.filter.with_nan_policy(policy)?;
        Ok(self)
    }

    /// The blocks of `filter`'s route: overlap its certified half-width,
    /// its bound; `None` for the exact route (no width). Costs a clone of
    /// the poles and `O(p log V)` products of their powers, no MPFR (the
    /// filter already holds them).
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Truncated { tol: 1e-12 }).unwrap();
    /// let b = BlockPrefilter::from_line_filter(&f).unwrap();
    /// assert_eq!((b.overlap(), b.bound()), (f.half_width().unwrap(), f.bound()));
    /// ```
    pub fn from_line_filter(filter: &LineFilter<T>) -> Option<Self> {
        Some(BlockPrefilter {
            filter: filter.clone(),
            overlap: filter.half_width()?,
            bound: filter.bound(),
            kernel: kernel(filter),
        })
    }

    /// Whether blocks beat the sequential exact filter on a line of `len`
    /// samples: at least [`MIN_LINE`] (shorter lines run the exact
    /// recursion, which is within the bound too: difference 0).
    pub fn pays_off(&self, len: usize) -> bool {
        len >= MIN_LINE
    }

    /// [`Self::apply_into`] in about [`TASKS`] blocks (enough for four per
    /// thread on sixteen cores, so a slow thread does not hold the others
    /// up), each a whole number of windows and at least [`MIN_WINDOWS`]
    /// of them. The windows depend on the length only, so the result is the
    /// same bits whatever the thread count.
    ///
    /// **Method**, **accuracy** and **source**: as [`Self::apply_into`]
    /// (tested in `verify/tests/it/engine_properties.rs::truncated_route_stays_within_its_certified_bound`,
    /// against MPFR in `verify/tests/it/engine_properties.rs::truncated_blocks_match_mpfr_within_the_bound`).
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// let f = BlockPrefilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, 1e-12).unwrap();
    /// let s: Vec<f64> = (0..100_000).map(|i| (i as f64 * 0.01).sin()).collect();
    /// let mut out = vec![0.0; s.len()];
    /// f.apply_line_into(&s, &mut out).unwrap();
    /// let exact = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
    /// let mut want = s.clone();
    /// exact.apply(&mut want, &mut Vec::new());
    /// let diff = out.iter().zip(&want).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    /// assert!(diff <= f.bound() + 1e-14);
    /// ```
    pub fn apply_line_into(&self, s: &[T], out: &mut [T]) -> Result<(), NdimageError> {
        let window = window::<T>();
        let windows = s.len().div_ceil(TASKS).div_ceil(window).max(MIN_WINDOWS);
        self.apply_into(s, out, windows * window)
    }

    /// The overlap `W` on each side of a block.
    pub fn overlap(&self) -> usize {
        self.overlap
    }

    /// `Σ_{|j|>W} |c_j|`, rounded up: the guaranteed relative difference
    /// from the sequential exact result (before rounding).
    pub fn bound(&self) -> f64 {
        self.bound
    }

    /// The coefficients of `s`, blocks of `block` samples in parallel; each
    /// block is cut into windows of [`WINDOW_BYTES`] (the last one shorter),
    /// each filtered with its overlap of `W` extended samples each side. The
    /// bound holds for every window, whatever its size.
    pub fn apply(&self, s: &[T], block: usize) -> Result<Vec<T>, NdimageError> {
        let mut out = vec![T::zero(); s.len()];
        self.apply_into(s, &mut out, block)?;
        Ok(out)
    }

    /// [`Self::apply`] into the caller's buffer (`out.len() = s.len()`), so
    /// repeated calls neither allocate nor fault in fresh pages.
    ///
    ///
    /// **Method**: each window `[a − W, b + W)` filtered exactly by the recursion (the
    /// module documentation), in the order of `window_recursion`. **Accuracy**: within
    /// `bound · max|s|` plus rounding of the sequential exact result, tested in
    /// `verify/tests/it/engine_properties.rs::parallel_blocks_stay_within_the_bound_of_the_sequential_filter`.
    /// **Source**: seed 000 eq 10 and its tail bound (locality of the cardinal spline).
    ///
    /// ```
    /// use splinelab::sspline::SplineFamily;
    /// use splinelab::ndimage::{mode::Mode, block_filter::BlockPrefilter};
    /// let f = BlockPrefilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, 1e-12).unwrap();
    /// let s: Vec<f64> = (0..1000).map(|i| (i as f64 * 0.1).sin()).collect();
    /// let mut out = vec![0.0; s.len()];
    /// f.apply_into(&s, &mut out, 256).unwrap();
    /// assert_eq!(out, f.apply(&s, 256).unwrap());
    /// ```
    pub fn apply_into(&self, s: &[T], out: &mut [T], block: usize) -> Result<(), NdimageError> {
        if out.len() != s.len() {
            return Err(NdimageError::BufferLength {
                expected: s.len(),
                got: out.len(),
            });
        }
        if s.is_empty() {
            return Err(NdimageError::Empty);
        }
        let block = block.max(1);
        // Each window measures its samples (largest magnitude, and whether
        // its recursions stayed finite) in its first pass; the position of
        // a non-finite sample is searched only on failure.
        let stash = Stash::default();
        let (max, finite) = out
            .par_chunks_mut(block)
            .enumerate()
            .map(|(b, chunk)| stash.with(|bufs| self.filter_block(s, b * block, chunk, bufs)))
            .reduce(|| (0.0, true), |a, b| (a.0.max(b.0), a.1 && b.1));
        if finite {
            return self.filter.check_magnitude(max, 1);
        }
        if s.iter().any(|x| !x.is_finite()) {
            // The filter's policy: refused, or filled and marked.
            let (s, mut o) = (ArrayView1::from(s), ArrayViewMut1::from(out));
            return fill_filter_mark(&s, &mut o, &[0], &self.filter, |o| {
                let line = o.as_slice_mut().expect("a slice's view is contiguous");
                self.filter.apply(line, &mut Vec::new());
                Ok(())
            });
        }
        self.filter.check_magnitude(max, 1)?;
        // Finite data within the growth bound cannot overflow
        // (LineFilter::growth): the extension's constant is not finite.
        Err(NdimageError::Overflow {
            max,
            growth: self.filter.growth(),
            limit: max,
        })
    }

    /// One task of [`Self::apply_into`]: the block `chunk` of `out`
    /// (starting at sample `start`) window by window; the largest `|s|`
    /// over the windows and whether their recursions stayed finite.
    fn filter_block(
        &self,
        s: &[T],
        start: usize,
        chunk: &mut [T],
        bufs: &mut Buffers<T>,
    ) -> (f64, bool) {
        let step = window::<T>();
        let v = lanes::<T>();
        let w = self.overlap.next_multiple_of(v);
        let tail = self.filter.exact_pad().next_multiple_of(v);
        let base = chunk.as_ptr();
        let count = chunk.len().div_ceil(step);
        // A line larger than L3 (`lanes::STREAM_BYTES`) filtered with two
        // poles or more: each window's coefficients are formed in
        // `bufs.staged` (in L1) and written out by streaming stores
        // (`lanes::stream_row`, the same values), so the output is not read
        // for ownership; nothing of it prefetched. Measured (10⁷ f64,
        // `tol=1e-12`, `python/bench/prefilter_ab.py --rounds 21`, one
        // thread CPU / two threads wall, load 6): quintic 8.04 → 7.50 /
        // 4.33 → 3.81 ms; cubic (one pole: the staging copy is a third
        // more work per window) 4.67 → 5.20 / 2.65 → 2.94, so not there.
        let stream = std::mem::size_of_val(s) >= crate::ndimage::lanes::STREAM_BYTES
            && self.filter.recursive().poles().len() >= 2;
        if stream {
            bufs.staged.resize(step, T::zero());
        }
        let (mut max, mut finite) = (0.0f64, true);
        for (j, out) in chunk.chunks_mut(step).enumerate() {
            let a = start + j * step;
            let span = out.len().next_multiple_of(v) + 2 * w;
            let lo = a as i64 - w as i64;
            let src: &[T] = if lo >= 0 && lo as usize + span <= s.len() {
                // Interior window: read in place.
                &s[lo as usize..lo as usize + span]
            } else {
                self.extend(s, lo, span, &mut bufs.edge);
                &bufs.edge
            };
            // The next window of this block, fetched while this one runs.
            let ahead: Ahead<T> = (j + 1 < count).then(|| {
                let next = src.as_ptr().wrapping_add(step);
                match stream {
                    true => (next, bufs.staged.as_ptr()),
                    false => (next, base.wrapping_add((j + 1) * step)),
                }
            });
            let (m, ok) = if stream {
                let staged = &mut bufs.staged[..out.len()];
                let r = self
                    .kernel
                    .window(src, tail, w, staged, &mut bufs.work, ahead);
                crate::ndimage::lanes::stream_row(out, staged);
                r
            } else {
                self.kernel.window(src, tail, w, out, &mut bufs.work, ahead)
            };
            max = max.max(m);
            finite &= ok;
        }
        if stream {
            crate::ndimage::lanes::stream_fence();
        }
        (max, finite)
    }
}

impl<T: Real> BlockPrefilter<T> {
    /// `ext` = the extended samples `s_i`, `i ∈ [lo, lo + span)`: the part
    /// inside the line copied, the mode's extension computed only beyond
    /// the ends.
    fn extend(&self, s: &[T], lo: i64, span: usize, ext: &mut Vec<T>) {
        let hi = lo + span as i64;
        let (a, b) = (lo.clamp(0, s.len() as i64), hi.clamp(0, s.len() as i64));
        ext.clear();
        ext.extend((lo..a).map(|i| self.filter.sample(s, i)));
        ext.extend_from_slice(&s[a as usize..b.max(a) as usize]);
        ext.extend((b.max(a)..hi).map(|i| self.filter.sample(s, i)));
    }
}

/// The window kernel of `filter`'s poles and gain.
fn kernel<T: Real>(filter: &LineFilter<T>) -> WindowRecursion<T> {
    let r = filter.recursive();
    WindowRecursion::new(r.poles(), r.gain())
}

/// A task's work space: the window's passes, the extended samples of a
/// window at the line's ends, and a window's coefficients to stream.
struct Buffers<T> {
    work: Vec<T>,
    edge: Vec<T>,
    /// A window's coefficients before they are streamed out.
    staged: Vec<T>,
}

impl<T> Default for Buffers<T> {
    fn default() -> Self {
        Buffers {
            work: Vec::new(),
            edge: Vec::new(),
            staged: Vec::new(),
        }
    }
}

/// Samples per window (the coefficients one window writes) for `T`:
/// [`WINDOW_BYTES`] of them, a multiple of the vector lanes.
fn window<T: 'static>() -> usize {
    (WINDOW_BYTES / std::mem::size_of::<T>().max(1)).next_multiple_of(lanes::<T>())
}

/// Bytes of the samples one window writes: 1024 `f64`, 2048 `f32`. With
/// the overlaps the window's work buffer stays in L1 (48 KiB on Zen 5)
/// beside the next window's prefetched samples and coefficients. Measured
/// (prototype, 10⁷ samples cubic, one thread, min of 9): windows of 512,
/// 1024, 2048, 4096 `f64` streamed in 5.2, 4.9, 5.7, 6.0 ms (in cache:
/// 3.7, 3.7, 3.7, 3.6 ms): longer windows fetch further ahead than L1 holds.
pub const WINDOW_BYTES: usize = 8 << 10;

/// Fewest windows of a task.
pub const MIN_WINDOWS: usize = 4;

/// Shortest line that [`BlockPrefilter::pays_off`]: the block route's
/// fixed costs (the pool's hand-over, the two end windows) outweigh its
/// speed below it. Measured (Python `spline_filter1d(x, 3, tol=…,
/// threads=1)`, CPU µs, min of 200 × 3 alternated, before the end windows
/// copied their inside part): 8192 samples f64 exact 16.6, blocks 20.8;
/// 16384: exact 29.2, blocks 22.8 (f32 the same within a µs or two).
pub const MIN_LINE: usize = 12 << 10;

/// Blocks of [`BlockPrefilter::apply_line_into`] on a long line.
pub const TASKS: usize = 64;
