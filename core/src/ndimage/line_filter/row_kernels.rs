//! The row kernels of the strided passes: the walkers that run one pass
//! down ([`load_down`]) or up ([`store_up`], [`store_up_streamed`]) the
//! rows of a strip, forming each row by a step ([`DownStep`], [`UpStep`]:
//! the one-pole steps [`Causal`] and [`Anticausal`] here, the cascade's in
//! `cascade`) while the rows ahead are prefetched ([`rows_ahead`],
//! [`prefetch_starts`]); what a pass does with each row it reads
//! ([`RowCheck`]); and the truncated convolution of every column
//! ([`convolve_rows`]). Each is compiled in vector clones (`multiversion`)
//! with its step inlined. Apart from `rows`, which decides the passes a
//! strip runs, because they are the inner loops that the rows, the cascade
//! and the blocks share.

use crate::ndimage::lanes;
use crate::ndimage::mode::Mode;
use crate::scalar::Real;
use multiversion::{multiversion, target::match_target};

/// What a pass that reads an input does with each row it reads, while the
/// row is in L1 (the N-D prefilter's finiteness and magnitude check; `()`:
/// nothing). Inlined into the row kernels' vector clones.
pub(crate) trait RowCheck {
    /// Takes in one row of samples.
    fn row<T: Real>(&mut self, row: &[T]);
}

impl RowCheck for () {
    #[inline(always)]
    fn row<T: Real>(&mut self, _: &[T]) {}
}

/// Asks the cache for the rows `s_{−j}`, `j < count`, of `rows` (folded
/// by `mode`) that a causal start sums: each is a run on its own page,
/// read before the pass's own prefetching ([`rows_ahead`]) begins, and
/// one request after another leaves each miss waiting on the last.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(super) fn prefetch_starts<T: Real, R: AsRef<[T]>>(rows: &[R], mode: Mode, count: usize) {
    for j in 0..count.min(rows.len()) {
        let row = rows[mode.fold(-(j as i64), rows.len()).unwrap_or(0)].as_ref();
        match_target! {
            "x86_64+avx2" => lanes::prefetch(row),
            _ => { let _ = row; }
        }
    }
}

/// One row of a pass down a strip ([`load_down`]): row `i` of the work
/// buffer from the samples of row `i` and the buffer's row `i − 1`.
/// Inlined into the walker's vector clones (as [`RowCheck`]).
pub(super) trait DownStep<T> {
    /// `x` (buffer row `i`) from `s` (sample row `i`) and `prev`.
    fn row(&mut self, x: &mut [T], s: &[T], prev: &[T]);
}

/// The first pole's gain and causal pass: `x = g·s + ξ prev`, the
/// operations of [`lanes::scale`] then [`lanes::causal_strided`].
pub(super) struct Causal<'a, T> {
    pub(super) gain: &'a T,
    pub(super) z: &'a T,
}

impl<T: Real> DownStep<T> for Causal<'_, T> {
    #[inline(always)]
    fn row(&mut self, x: &mut [T], s: &[T], prev: &[T]) {
        let (g, z) = (self.gain, self.z);
        for ((x, s), p) in x.iter_mut().zip(s).zip(prev) {
            *x = g.clone() * s + z.clone() * p;
        }
    }
}

/// A pass down the rows `rows` into `buf` (row 0 of `buf` already holds
/// the pass's start), `step` forming each row, the rows prefetched
/// [`rows_ahead`]; `seen` takes in each row (from row 1) before it is read.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(super) fn load_down<T: Real, R: AsRef<[T]>, F: RowCheck, S: DownStep<T>>(
    rows: &[R],
    buf: &mut [T],
    step: &mut S,
    seen: &mut F,
) {
    let w = buf.len() / rows.len();
    let ahead = rows_ahead::<T>(w);
    for (i, src) in rows.iter().enumerate().skip(1) {
        if let Some(later) = rows.get(i + ahead) {
            match_target! {
                "x86_64+avx2" => lanes::prefetch(later.as_ref()),
                _ => { let _ = later; }
            }
        }
        let src = src.as_ref();
        seen.row(src);
        let (done, rest) = buf.split_at_mut(i * w);
        step.row(&mut rest[..w], src, &done[(i - 1) * w..]);
    }
}

/// One row of a pass up a strip ([`store_up`]): output row `i` from the
/// output row `i + 1` and the buffer's row `i`.
pub(super) trait UpStep<T> {
    /// `o` (output row `i`) from `next` (row `i + 1`) and `c` (buffer row `i`).
    fn row(&mut self, o: &mut [T], next: &[T], c: &[T]);
}

/// The last anti-causal pass: `o = ξ (next − c)`, the operations of
/// [`lanes::anticausal_strided`].
pub(super) struct Anticausal<'a, T> {
    pub(super) z: &'a T,
}

impl<T: Real> UpStep<T> for Anticausal<'_, T> {
    #[inline(always)]
    fn row(&mut self, o: &mut [T], next: &[T], c: &[T]) {
        for ((o, nx), c) in o.iter_mut().zip(next).zip(c) {
            *o = self.z.clone() * (nx.clone() - c.clone());
        }
    }
}

/// A pass up writing `rows` from the values in `buf`: row `n − 1` copied
/// (it holds the pass's start), then `step` on each row from `n − 2`
/// down to 0, the rows prefetched [`rows_ahead`]; by streaming stores
/// where `stream` ([`store_up_streamed`]).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(super) fn store_up<T: Real, S: UpStep<T>>(
    rows: &mut [&mut [T]],
    buf: &[T],
    step: &mut S,
    stream: bool,
) {
    let n = rows.len();
    let w = buf.len() / n;
    if stream {
        return store_up_streamed(rows, buf, step);
    }
    rows[n - 1].clone_from_slice(&buf[(n - 1) * w..]);
    let ahead = rows_ahead::<T>(w);
    for i in (0..n - 1).rev() {
        if let Some(later) = i.checked_sub(ahead) {
            match_target! {
                "x86_64+avx2" => lanes::prefetch(&rows[later][..]),
                _ => { let _ = later; }
            }
        }
        let (lo, hi) = rows.split_at_mut(i + 1);
        step.row(&mut lo[i][..], &hi[0][..], &buf[i * w..(i + 1) * w]);
    }
}

/// [`store_up`] by streaming stores: each row formed in `cur` from the
/// row after it, kept in `next` (both in L1: the rows written are not read
/// back), then written whole lines at a time without reading them first
/// ([`lanes::stream_row`]); nothing prefetched (the rows' old contents are
/// not wanted). The same operations on the same values, so the same bits.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn store_up_streamed<T: Real, S: UpStep<T>>(rows: &mut [&mut [T]], buf: &[T], step: &mut S) {
    let n = rows.len();
    let w = buf.len() / n;
    let mut next = buf[(n - 1) * w..].to_vec();
    let mut cur = next.clone();
    lanes::stream_row(rows[n - 1], &next);
    for i in (0..n - 1).rev() {
        step.row(&mut cur, &next, &buf[i * w..(i + 1) * w]);
        lanes::stream_row(rows[i], &cur);
        std::mem::swap(&mut cur, &mut next);
    }
    lanes::stream_fence();
}

/// Rows ahead that [`load_down`] and [`store_up`] ask the cache
/// for ([`lanes::prefetch`]): about [`PREFETCH_BYTES`] ahead, one row at least.
pub(super) fn rows_ahead<T>(w: usize) -> usize {
    (PREFETCH_BYTES / (w * std::mem::size_of::<T>()).max(1)).max(1)
}

/// How far ahead the strided passes prefetch their rows (measured, one
/// thread, `spline_filter1d` along axis 0 of 256³ / 4096²: 2 KiB 15.9 /
/// 15.7 ms, 4 KiB 14.4 / 16.3, 8 KiB 14.6 / 17.4, 16 KiB 15.2 / 16.6;
/// without prefetching 4096² took 30.5 ms).
pub(super) const PREFETCH_BYTES: usize = 4 << 10;

/// The truncated convolution of every column: `ext` holds the extended
/// rows `−n .. L + n`, `out` receives rows `0 .. L`; per value the
/// operations of `ConvolutionPrefilter::apply_extended`.
pub(crate) fn convolve_rows<T: Real>(taps: &[T], ext: &[T], out: &mut [T], w: usize) {
    let n = taps.len() - 1;
    for (k, o) in out.chunks_mut(w).enumerate() {
        for (o, x) in o.iter_mut().zip(&ext[(k + n) * w..]) {
            *o = taps[0].clone() * x;
        }
        for (j, cj) in taps.iter().enumerate().skip(1) {
            let (l, r) = (&ext[(k + n - j) * w..], &ext[(k + n + j) * w..]);
            for ((o, l), r) in o.iter_mut().zip(l).zip(r) {
                *o += cj.clone() * (l.clone() + r);
            }
        }
    }
}
