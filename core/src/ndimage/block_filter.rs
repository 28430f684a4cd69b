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
//! Cost: `(1 + 2W/B)` times the sequential filter for blocks of `B`
//! samples, spread over the rayon pool; [`GROUP`] (32) blocks advance
//! together as the columns of one buffer, so the recursion runs as vector
//! operations (compiled for the CPU's widest vector unit, `ndimage::lanes`)
//! rather than one latency-bound chain.

use super::NdimageError;
use super::lanes;
use super::line_filter::{LineFilter, Route};
use super::mode::Mode;
use super::nd_prefilter::{Stash, scan_block};
use crate::scalar::Real;
use crate::sspline::SplineFamily;
use crate::sspline::width::certified_width;
use rayon::prelude::*;
use std::borrow::Cow;

/// The block-parallel prefilter (module documentation).
#[derive(Debug, Clone)]
pub struct BlockPrefilter<T> {
    filter: LineFilter<T>,
    overlap: usize,
    bound: f64,
}

impl<T: Real + Send + Sync> BlockPrefilter<T> {
    /// Blocks overlapping by the certified width of `tol` for `family`.
    ///
    ///
    /// **Method**: the certified half-width `W` of `tol` ([`certified_width`], the pole tail
    /// bound `Σ_{|j|>W} |c_j| < tol`) and the exact recursive [`LineFilter`]. **Accuracy**:
    /// [`Self::bound`], tested in
    /// `verify/tests/engine_properties.rs::parallel_blocks_stay_within_the_bound_of_the_sequential_filter`.
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
        let (overlap, bound) = certified_width(family, tol)?;
        Ok(BlockPrefilter {
            filter: LineFilter::new(family, mode, cval, Route::Exact)?,
            overlap,
            bound,
        })
    }

    /// The blocks of `filter`'s route: overlap its certified half-width,
    /// its bound; `None` for the exact route (no width). Costs a clone of
    /// the poles, no MPFR (the filter already holds them).
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
        })
    }

    /// Whether blocks beat the sequential exact filter on a line of `len`
    /// samples: at least [`GROUP`] windows whose blocks are 16 overlaps
    /// long (extra work `2W/B ≤ 1/8`); shorter lines run the exact
    /// recursion, which is within the bound too (difference 0).
    pub fn pays_off(&self, len: usize) -> bool {
        len >= self.min_block()
    }

    /// The smallest block [`Self::apply_line_into`] hands to one task.
    fn min_block(&self) -> usize {
        GROUP * 16 * (self.overlap + self.filter.exact_pad()).max(8)
    }

    /// [`Self::apply_into`] in [`TASKS`] blocks (enough for four per thread
    /// on sixteen cores, so a slow thread does not hold the others up), none
    /// below [`Self::pays_off`]'s size. The blocks depend on the length
    /// only, so the result is the same bits whatever the thread count.
    ///
    /// **Method**, **accuracy** and **source**: as [`Self::apply_into`]
    /// (tested in `verify/tests/engine_properties.rs::truncated_route_stays_within_its_certified_bound`,
    /// against MPFR in `verify/tests/engine_properties.rs::truncated_blocks_match_mpfr_within_the_bound`).
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
        let block = s.len().div_ceil(TASKS).max(self.min_block());
        self.apply_into(s, out, block)
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
    /// block is cut into windows of at most [`WINDOW`] samples (plus the
    /// overlap), filtered [`GROUP`] at a time in an L2-sized buffer. The bound
    /// holds for every window, whatever its size.
    pub fn apply(&self, s: &[T], block: usize) -> Result<Vec<T>, NdimageError> {
        let mut out = vec![T::zero(); s.len()];
        self.apply_into(s, &mut out, block)?;
        Ok(out)
    }

    /// [`Self::apply`] into the caller's buffer (`out.len() = s.len()`), so
    /// repeated calls neither allocate nor fault in fresh pages.
    ///
    ///
    /// **Method**: each block's window `[a − W, b + W)` filtered exactly by the recursion (the
    /// module documentation). **Accuracy**: within `bound · max|s|` plus rounding of the
    /// sequential exact result, tested in
    /// `verify/tests/engine_properties.rs::parallel_blocks_stay_within_the_bound_of_the_sequential_filter`.
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
        // Each group checks its own samples (finite, and their largest
        // magnitude for the overflow check) while they are on their way to
        // L2 (a separate pass over `s` first cost a fifth of the time at
        // 10⁶ samples); the position is searched only on failure.
        let stash = Stash::default();
        let max = out
            .par_chunks_mut(block)
            .enumerate()
            .map(|(b, chunk)| stash.with(|buf| self.filter_chunk(s, b * block, chunk, buf)))
            .try_reduce(|| 0.0, |a, b| Some(a.max(b)));
        match max {
            Some(max) => self.filter.check_magnitude(max, 1),
            None => {
                let i = s.iter().position(|x| !x.is_finite()).unwrap_or(0);
                Err(NdimageError::NonFinite(i))
            }
        }
    }

    /// One task of [`Self::apply_into`]: the block `chunk` of `out`
    /// (starting at sample `start`) in groups of [`GROUP`] windows; `max|s|`
    /// over the block, `None` if a sample is not finite.
    fn filter_chunk(
        &self,
        s: &[T],
        start: usize,
        chunk: &mut [T],
        buf: &mut Vec<Row<T>>,
    ) -> Option<f64> {
        let sub = chunk.len().div_ceil(GROUP).min(WINDOW);
        let mut max = 0.0f64;
        for (g, group) in chunk.chunks_mut(sub * GROUP).enumerate() {
            let a = start + g * sub * GROUP;
            let (finite, m) = scan_block(&s[a..a + group.len()]);
            if !finite {
                return None;
            }
            max = max.max(m);
            self.filter_group(s, a as i64, sub, group, buf);
        }
        Some(max)
    }

    /// Up to [`GROUP`] consecutive blocks of `out` (the first starting at
    /// sample `a`), filtered together as the columns of `buf`: column `j`
    /// holds window `j` (block `j` and `W` samples each side, extended by
    /// the mode; zeros for a missing block), with `exact_pad()` zeros each
    /// side when there are several poles. One pole needs no zeros: the
    /// anti-causal start `ξ/(ξ² − 1) c⁺_{L−1}` is the exact sum over the
    /// zero continuation. `buf` stays in L2 across the passes; the samples
    /// are loaded with the first causal pass in strips of [`STRIP`] rows,
    /// front to back, and the blocks stored whole after the last pass (perf,
    /// 10⁷ samples: storing each strip as the last anti-causal pass went,
    /// backwards, was three fifths of this function's time; forward, CPU
    /// time per call 23.2 → 20.2 ms, `engine_peer tol1d 3 10000000`).
    fn filter_group(&self, s: &[T], a: i64, block: usize, out: &mut [T], buf: &mut Vec<Row<T>>) {
        let w = self.overlap;
        let r = self.filter.recursive();
        let (poles, gain) = (r.poles(), r.gain());
        let pad = if poles.len() == 1 {
            0
        } else {
            self.filter.exact_pad()
        };
        let span = block + 2 * w;
        let zero: Row<T> = std::array::from_fn(|_| T::zero());
        buf.resize(span + 2 * pad, zero.clone());
        let srcs = self.windows(s, a, block, out.len());
        let (head, rest) = buf.split_at_mut(pad);
        let (mid, tail) = rest.split_at_mut(span);
        head.fill(zero.clone());
        tail.fill(zero.clone());
        // The first causal pass runs on each strip while it is in L1 (the
        // zeros above the window stay zeros: it starts at the window).
        let mut prev = zero.clone();
        for (k, strip) in mid.chunks_mut(STRIP).enumerate() {
            lanes::load_strip(strip, k * STRIP, &srcs, gain);
            lanes::causal_fixed(strip, &mut prev, &poles[0]);
        }
        lanes::causal_fixed(tail, &mut prev, &poles[0]);
        let (last, rest) = poles.split_last().expect("a spline has a pole");
        let top = buf.len() - 1;
        for (p, z) in rest.iter().enumerate() {
            if p > 0 {
                lanes::causal_fixed(buf, &mut zero.clone(), z);
            }
            let mut next = anticausal_start(buf, z);
            lanes::anticausal_fixed(&mut buf[..top], &mut next, z);
        }
        if !rest.is_empty() {
            lanes::causal_fixed(buf, &mut zero.clone(), last);
        }
        // The last anti-causal pass needs the rows of the blocks only.
        let mut next = anticausal_start(buf, last);
        let first = pad + w;
        lanes::anticausal_fixed(&mut buf[first..top], &mut next, last);
        // The blocks stored whole, a tile group of blocks at a time: long
        // runs per block (one long run per output page, not 64-row pieces
        // of 32 blocks in turn) are what the memory writes fastest (perf,
        // `engine_peer tol1d 3 10000000 20`, one thread, min of 4
        // alternated: strips of 64 rows 17.4 ms, of 256 15.7, whole 14.8).
        let mut outs: Vec<&mut [T]> = out.chunks_mut(block).collect();
        lanes::store_strip(&mut outs, &buf[first..first + block], 0);
    }

    /// The [`GROUP`] windows of a group, each `block + 2W` extended samples
    /// (zeros for a block beyond `out_len`).
    fn windows<'a>(&self, s: &'a [T], a: i64, block: usize, out_len: usize) -> Vec<Cow<'a, [T]>> {
        let w = self.overlap;
        let span = block + 2 * w;
        (0..GROUP)
            .map(|j| {
                let start = (j * block).min(out_len);
                let len = (out_len - start).min(block) + 2 * w;
                let lo = a + start as i64 - w as i64;
                if len == span && lo >= 0 && lo as usize + len <= s.len() {
                    // Interior window: read in place.
                    return Cow::Borrowed(&s[lo as usize..lo as usize + len]);
                }
                let mut v: Vec<T> = if len == 2 * w {
                    Vec::new()
                } else {
                    (0..len as i64)
                        .map(|i| self.filter.sample(s, lo + i))
                        .collect()
                };
                v.resize(span, T::zero());
                Cow::Owned(v)
            })
            .collect()
    }
}

/// One row of the group buffer: sample `i` of each of the [`GROUP`] windows.
type Row<T> = [T; GROUP];

/// `c⁻_{L−1} = ξ/(ξ² − 1) c⁺_{L−1}`, the last row of `buf` replaced by
/// it and returned: the anti-causal start over a zero continuation.
fn anticausal_start<T: Real>(buf: &mut [Row<T>], z: &T) -> Row<T> {
    let f = z.clone() / (z.clone() * z - T::one());
    let last = buf.last_mut().expect("a window has a sample");
    for x in last.iter_mut() {
        *x = f.clone() * x.clone();
    }
    last.clone()
}

/// Blocks filtered together ([`BlockPrefilter::filter_group`]): the
/// recursion of one block is a chain of dependent multiply-adds; 32
/// independent chains side by side (four AVX-512 registers of `f64`, two of
/// `f32`) keep the vector units busy while each step waits for the last
/// (measured, `engine_peer tol1d 3 10000000`, CPU time on one thread with
/// the vector kernels: 8 → 32 blocks, 24.5 → 23.2 ms; the strips below took
/// it to 20.2 ms).
pub const GROUP: usize = 32;

/// Rows of the group buffer per strip (`64 × 256` bytes in `f64`: L1).
const STRIP: usize = 64;

/// Blocks of [`BlockPrefilter::apply_line_into`] on a long line.
pub const TASKS: usize = 64;

/// Largest window, in samples: [`GROUP`] windows and their overlaps
/// (`32 × 8 × 1024` bytes in `f64`) stay in L2 across the passes.
pub const WINDOW: usize = 1024;
