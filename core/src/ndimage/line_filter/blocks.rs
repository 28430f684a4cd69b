//! A strip filtered in blocks of [`BLOCK_ROWS`] rows, with work memory
//! independent of its length ([`LineFilter::filter_in_blocks`]): where the
//! rows are read and written ([`BlockIo`]; a strided strip's rows,
//! [`StripRows`]), the work buffers ([`RowBlocks`]), and the reads and
//! writes that widen, scale and round the rows ([`rows_as_compute`],
//! [`read_rows_scaled`], [`write_rows`]). The operations of
//! [`LineFilter::apply_rows`] on the same values, so the same bits.

use super::LineFilter;
use super::recursion::{anticausal_start_rows, causal_start_of};
use super::row_kernels::{RowCheck, rows_ahead};
use crate::ndimage::lanes;
use crate::ndimage::mode::Mode;
use crate::ndimage::samples::{Sample, Stored};
use crate::scalar::Real;
use multiversion::{multiversion, target::match_target};

/// Rows of one block of [`LineFilter::filter_in_blocks`]: 128 rows of a
/// strip 64 `f64` wide are 64 KiB, in L2 from their recomputation to the
/// pass up.
const BLOCK_ROWS: usize = 128;

/// Where [`LineFilter::filter_in_blocks`] reads the rows it filters (`n`
/// rows of `w` values: one value of each of `w` lines side by side) and
/// writes the results: the rows of a strided strip, or a group of
/// contiguous lines transposed.
pub(crate) trait BlockIo<T> {
    /// `(n, w)`.
    fn shape(&self) -> (usize, usize);
    /// Rows `lo .. hi` read into `rows` (`(hi − lo) × w`) as `T`, times
    /// `gain` (each value `gain · s` rounded once, as [`lanes::scale`]);
    /// `first`: the first read of these rows (the caller's checks take in
    /// the samples as they are).
    fn read_into(&mut self, lo: usize, hi: usize, rows: &mut [T], gain: &T, first: bool);
    /// Rows `lo ..` written from `block` (rows of `w` values).
    fn write(&mut self, lo: usize, block: &[T]);
    /// After the last write.
    fn finish(&mut self) {}
}

/// The work buffers of [`LineFilter::filter_in_blocks`]: `O((B + n/B) · w)`
/// values for `n` rows of `w` and blocks of `B` rows, not `n · w`.
pub(crate) struct RowBlocks<T> {
    /// One block's causal values after the row before it, and room for
    /// the row after it (`(B + 2) × w`).
    block: Vec<T>,
    /// The causal value of each block's last row (the next block's start).
    marks: Vec<T>,
    /// The cascade's first-pole state at each block's last row.
    states: Vec<T>,
    /// The causal start (row 0) and the cascade's first-pole start.
    start: Vec<T>,
    y0: Vec<T>,
    /// The cascade's first-pole state carried down (`y`) and up (`u`).
    y: Vec<T>,
    u: Vec<T>,
    /// The anti-causal start `c_{n−1}`, then the row after a block.
    next: Vec<T>,
}

impl<T> Default for RowBlocks<T> {
    fn default() -> Self {
        RowBlocks {
            block: Vec::new(),
            marks: Vec::new(),
            states: Vec::new(),
            start: Vec::new(),
            y0: Vec::new(),
            y: Vec::new(),
            u: Vec::new(),
            next: Vec::new(),
        }
    }
}

impl<T: Real> RowBlocks<T> {
    /// Every buffer sized for rows of `w` and `count` blocks.
    fn prepare(&mut self, w: usize, count: usize) {
        let rows = |v: &mut Vec<T>, k: usize| v.resize(k * w, T::zero());
        rows(&mut self.block, BLOCK_ROWS + 2);
        rows(&mut self.marks, count);
        rows(&mut self.states, count);
        for v in [
            &mut self.start,
            &mut self.y0,
            &mut self.y,
            &mut self.u,
            &mut self.next,
        ] {
            rows(v, 1);
        }
    }
}

/// The blocks `[lo, hi)` of `n` rows: `⌈n/B⌉` of nearly equal length
/// (each at least `B/2` rows where `n ≥ B`).
fn block_spans(n: usize) -> Vec<(usize, usize)> {
    let count = n.div_ceil(BLOCK_ROWS).max(1);
    (0..count)
        .map(|k| (k * n / count, (k + 1) * n / count))
        .collect()
}

/// `rows` read as `T`: the rows themselves where they are of type `T`,
/// otherwise widened into `wide` (exactly: [`Sample::widen_into`]).
pub(crate) fn rows_as_compute<'a, T: Real, S: Sample<T>, R: AsRef<[S]>>(
    rows: &'a [R],
    wide: &'a mut Vec<T>,
) -> Vec<&'a [T]> {
    if let Some(direct) = rows
        .iter()
        .map(|r| S::as_compute(r.as_ref()))
        .collect::<Option<Vec<&[T]>>>()
    {
        return direct;
    }
    let w = rows.first().map_or(0, |r| r.as_ref().len()).max(1);
    wide.resize(rows.len() * w, T::zero());
    for (t, r) in wide.chunks_mut(w).zip(rows) {
        S::widen_into(r.as_ref(), t);
    }
    wide.chunks(w).take(rows.len()).collect()
}

/// The rows `src[lo ..]` read into `dst` (rows of `w`, as many as it
/// holds) as `T` (exactly: [`Sample::widen_into`]) times `gain`, `seen`
/// taking in each as read; later rows asked of the cache
/// [`rows_ahead`] (each row of a strip is a run on its own page, which the
/// hardware does not prefetch: [`PREFETCH_BYTES`](super::row_kernels::PREFETCH_BYTES)).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn read_rows_scaled<T: Real, S: Sample<T>, R: AsRef<[S]>, F: RowCheck>(
    src: &[R],
    lo: usize,
    dst: &mut [T],
    gain: &T,
    mut seen: Option<&mut F>,
) {
    let w = src.first().map_or(1, |r| r.as_ref().len()).max(1);
    let ahead = rows_ahead::<T>(w);
    for (i, d) in (lo..).zip(dst.chunks_mut(w)) {
        if let Some(later) = src.get(i + ahead) {
            match_target! {
                "x86_64+avx2" => lanes::prefetch(later.as_ref()),
                _ => { let _ = later; }
            }
        }
        let s = src[i].as_ref();
        match S::as_compute(s) {
            Some(s) => {
                if let Some(seen) = seen.as_deref_mut() {
                    seen.row(s);
                }
                for (d, s) in d.iter_mut().zip(s) {
                    *d = gain.clone() * s;
                }
            }
            None => {
                S::widen_into(s, d);
                if let Some(seen) = seen.as_deref_mut() {
                    seen.row(d);
                }
                for d in d.iter_mut() {
                    *d *= gain.clone();
                }
            }
        }
    }
}

/// `rows[j] = block`'s row `j` ([`store_row`]), the rows after asked of
/// the cache [`rows_ahead`] where not written by streaming stores.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn write_rows<T: Real, O: Stored<T>>(rows: &mut [&mut [O]], block: &[T], stream: bool) {
    let w = rows.first().map_or(1, |r| r.len()).max(1);
    let ahead = rows_ahead::<T>(w);
    let count = block.len() / w;
    for j in 0..count.min(rows.len()) {
        if let Some(later) = rows.get(j + ahead).filter(|_| !stream && j + ahead < count) {
            match_target! {
                "x86_64+avx2" => lanes::prefetch(&later[..]),
                _ => { let _ = later; }
            }
        }
        store_row(rows[j], &block[j * w..(j + 1) * w], stream);
    }
}

/// `row = v`, stored as `O` (rounded once where `O` is not `T`); by a
/// streaming store where `stream`.
fn store_row<T: Real, O: Stored<T>>(row: &mut [O], v: &[T], stream: bool) {
    match O::as_compute_mut(row) {
        Some(t) if stream => lanes::stream_row(t, v),
        Some(t) => t.clone_from_slice(v),
        None => O::store_from(v, row),
    }
}

/// The rows of a strided strip as a [`BlockIo`]: read from `src` (rows
/// of samples, `seen` taking in each on its first read) or, without it,
/// from `rows` in place; written into `rows` (by streaming stores where
/// `stream`).
pub(crate) struct StripRows<'a, 'r, E, O, F> {
    pub src: Option<&'a [&'a [E]]>,
    pub rows: &'a mut [&'r mut [O]],
    pub seen: &'a mut F,
    pub stream: bool,
}

impl<T, E, O, F> BlockIo<T> for StripRows<'_, '_, E, O, F>
where
    T: Real,
    E: Sample<T>,
    O: Sample<T> + Stored<T>,
    F: RowCheck,
{
    fn shape(&self) -> (usize, usize) {
        (self.rows.len(), self.rows.first().map_or(0, |r| r.len()))
    }

    fn read_into(&mut self, lo: usize, _hi: usize, rows: &mut [T], gain: &T, first: bool) {
        // `rows` holds rows `lo .. hi`; the rows after are prefetched.
        let seen = first.then_some(&mut *self.seen);
        match self.src {
            Some(s) => read_rows_scaled(s, lo, rows, gain, seen),
            None => read_rows_scaled(self.rows, lo, rows, gain, seen),
        }
    }

    fn write(&mut self, lo: usize, block: &[T]) {
        write_rows(&mut self.rows[lo..], block, self.stream);
    }

    fn finish(&mut self) {
        if self.stream {
            lanes::stream_fence();
        }
    }
}

impl<T: Real> LineFilter<T> {
    /// Whether [`Self::filter_in_blocks`] runs on `n` rows: mirror or
    /// reflect starts (closed forms reading the first and the last rows),
    /// one pole or a [`Cascade`](super::cascade::Cascade), starts within a block, at least two
    /// blocks.
    pub(crate) fn runs_in_blocks(&self, n: usize) -> bool {
        let r = &self.recursive;
        let poles = match r.poles().len() {
            1 => true,
            2 => self.cascade_for(n, self.mode).is_some(),
            _ => false,
        };
        let starts = r.horizons().iter().all(|&k| k < BLOCK_ROWS)
            && self.cascade.as_deref().is_none_or(|c| c.reach < BLOCK_ROWS);
        matches!(self.mode, Mode::Mirror | Mode::Reflect)
            && n >= 2 * BLOCK_ROWS
            && self.fuses_rows(n)
            && poles
            && starts
    }

    /// The filter down the `n` rows of `io` (each column a line) with work
    /// memory independent of `n`: the rows in blocks of [`BLOCK_ROWS`]. A
    /// pass down the blocks keeps only each block's last causal row (and
    /// the cascade's first-pole state); the pass up then recomputes each
    /// block's causal values from the row before it, reading its rows a
    /// second time, runs the anti-causal step up the block and writes it.
    /// The rows are read times the gain ([`BlockIo::read_into`]) and
    /// filtered as [`Self::apply_lines_scaled`] filters its rows, the
    /// operations of [`Self::apply_rows`] too, on the same values, so the
    /// same bits (tested); the mirror and reflect starts read only the first rows
    /// (down) and the last three (up), which the first and last blocks
    /// hold. Returns `false`, with nothing done, where the filter or `n`
    /// does not allow blocks ([`Self::runs_in_blocks`]).
    ///
    /// **Cost**: the rows are read twice and written once (the whole
    /// buffer: read and written once each); work memory `(B + 2⌈n/B⌉ + 7)
    /// · w` values ([`RowBlocks`]).
    pub(crate) fn filter_in_blocks<B: BlockIo<T>>(
        &self,
        io: &mut B,
        work: &mut RowBlocks<T>,
    ) -> bool {
        let (n, w) = io.shape();
        if w == 0 || !self.runs_in_blocks(n) {
            return false;
        }
        let gain = self.recursive.gain();
        let spans = block_spans(n);
        work.prepare(w, spans.len());
        for (k, &span) in spans.iter().enumerate() {
            self.causal_block(io, k, span, gain, work, true);
        }
        let last_len = spans.last().map_or(0, |&(lo, hi)| hi - lo + 1);
        self.block_ends(n, last_len, w, work);
        let mut next = std::mem::take(&mut work.next);
        for (k, &span) in spans.iter().enumerate().rev() {
            let last = k + 1 == spans.len();
            if !last {
                self.causal_block(io, k, span, gain, work, false);
            }
            self.anticausal_block(io, span, last, work, &mut next);
        }
        work.next = next;
        io.finish();
        true
    }

    /// Block `k` (`span` of the rows) down into `work.block`: row 0 the
    /// previous block's last causal row (block 0: the start, computed on
    /// the `first` pass), then the block's rows times the gain, filtered in
    /// place as [`Self::apply_lines_scaled`] filters its rows. Keeps the
    /// block's last row and state for the blocks after it.
    fn causal_block<B: BlockIo<T>>(
        &self,
        io: &mut B,
        k: usize,
        (lo, hi): (usize, usize),
        gain: &T,
        work: &mut RowBlocks<T>,
        first: bool,
    ) {
        let (n, w) = io.shape();
        let RowBlocks {
            block,
            marks,
            states,
            start,
            y0,
            y,
            ..
        } = work;
        let mode = self.mode;
        let cascade = self.cascade_for(n, mode);
        // A block after the first starts from the previous block's last
        // row (row 0, not read).
        let skip = usize::from(k > 0);
        let region = &mut block[..(hi - lo + skip) * w];
        io.read_into(lo, hi, &mut region[skip * w..], gain, first);
        if k == 0 {
            if first {
                // The starts read rows `fold(−j)`, `j` below the horizon:
                // the first block's (a mirror or reflect fold of `−j` is
                // the same in the block as in the line).
                let rows: Vec<&[T]> = region.chunks(w).collect();
                match cascade {
                    Some(c) => c.starts(&rows, None, mode, y0, start),
                    None => {
                        let (z, h) = (&self.recursive.poles()[0], self.recursive.horizons()[0]);
                        causal_start_of(&rows, None, z, h, mode, start);
                    }
                }
            }
            region[..w].clone_from_slice(start);
            y.clone_from_slice(y0);
        } else {
            region[..w].clone_from_slice(&marks[(k - 1) * w..k * w]);
            y.clone_from_slice(&states[(k - 1) * w..k * w]);
        }
        match cascade {
            Some(c) => lanes::causal2_strided(region, w, y, &c.z[0], &c.z[1]),
            None => lanes::causal_strided(region, w, &self.recursive.poles()[0]),
        }
        let tail = region.len() - w;
        marks[k * w..(k + 1) * w].clone_from_slice(&region[tail..]);
        states[k * w..(k + 1) * w].clone_from_slice(y);
    }

    /// The anti-causal starts from the last block (`len` rows in
    /// `work.block`, the last three the line's; `n`: the line's length):
    /// `c_{n−1}` into `work.next` and that block's last row, and (cascade)
    /// `u_{n−1}` into `work.u`.
    fn block_ends(&self, n: usize, len: usize, w: usize, work: &mut RowBlocks<T>) {
        let (r, mode) = (&self.recursive, self.mode);
        let region = &mut work.block[..len * w];
        match self.cascade_for(n, mode) {
            Some(c) => c.ends(region, w, mode, &mut work.u, &mut work.next),
            None => {
                let (z, h) = (&r.poles()[0], r.horizons()[0]);
                anticausal_start_rows(region, w, z, h, mode, &mut work.next);
            }
        }
        region[(len - 1) * w..].clone_from_slice(&work.next);
    }

    /// Block `span` up, in `work.block`: its causal values and after them
    /// the row after the block (`next`; the `last` block's last row is the
    /// anti-causal start itself), filtered up in place as
    /// [`Self::apply_lines_scaled`] does; then written to `io`, and `next`
    /// set to its first row.
    fn anticausal_block<B: BlockIo<T>>(
        &self,
        io: &mut B,
        (lo, hi): (usize, usize),
        last: bool,
        work: &mut RowBlocks<T>,
        next: &mut [T],
    ) {
        let (n, w) = io.shape();
        let RowBlocks { block, u, .. } = work;
        // The block holds rows `lo − 1 (or 0) .. hi`: rows `lo .. hi` from
        // `skip`, then room for the row after them.
        let skip = usize::from(lo > 0);
        let len = hi - lo;
        let end = if last { skip + len } else { skip + len + 1 };
        if !last {
            block[(skip + len) * w..end * w].clone_from_slice(next);
        }
        let rows = &mut block[skip * w..end * w];
        match self.cascade_for(n, self.mode) {
            Some(c) => lanes::anticausal2_strided(rows, w, u, &c.z[0], &c.z[1]),
            None => lanes::anticausal_strided(rows, w, &self.recursive.poles()[0]),
        }
        next.clone_from_slice(&rows[..w]);
        io.write(lo, &rows[..len * w]);
    }
}
