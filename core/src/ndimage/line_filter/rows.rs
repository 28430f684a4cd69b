//! The filter of lines side by side, `w` lines whose row `i` holds sample
//! `i` of each: the rows of a strided axis filtered where they lie
//! ([`LineFilter::apply_rows`], [`LineFilter::apply_rows_from`]: the first
//! pole's gain and causal pass fused with the read, the last anti-causal
//! pass with the write, [`Loaded`] what the first half leaves the second),
//! and the column passes behind [`LineFilter::apply_lines`], whose gain a
//! caller's load may take ([`LineFilter::load_gain`],
//! [`LineFilter::apply_lines_scaled`]). Which passes run is decided here;
//! the loops they run are in `row_kernels`, the two-pole pass in `cascade`.

use super::LineFilter;
use super::cascade::Anticausal2;
use super::recursion::{anticausal_start_rows, causal_start_of, causal_start_rows};
use super::row_kernels::{Anticausal, Causal, RowCheck, load_down, store_up};
use crate::ndimage::lanes;
use crate::ndimage::mode::Mode;
use crate::scalar::Real;

impl<T: Real> LineFilter<T> {
    /// [`Self::apply_lines`] on rows that stay where they lie: `rows[i]` is
    /// sample `i` of `w` lines (a strided axis of an array, read and written
    /// in place). For the modes with closed-form starts the first pole's
    /// gain and causal pass run while the rows are read into `buf`, and the
    /// last anti-causal pass writes the rows directly: the array is read and
    /// written once, and `buf` sees two passes per pole instead of five
    /// (copy in, gain, causal, anti-causal, copy out); two poles (degrees
    /// 4 and 5) run as one pass down and one up ([`Cascade`](super::cascade::Cascade)), so `buf`
    /// sees two passes in all. The same operations in
    /// the same order as [`Self::apply_lines`], so the same bits; other
    /// modes and routes copy the rows through `buf` into [`Self::apply_lines`].
    ///
    ///
    /// **Accuracy**: [`Self::apply_lines`]'s, bit for bit
    /// (`line_filter::tests::rows_in_place_equal_apply_lines_bit_for_bit`). **Source**: Unser,
    /// Aldroubi and Eden (1993), the causal/anti-causal recursion.
    pub(crate) fn apply_rows(&self, rows: &mut [&mut [T]], buf: &mut Vec<T>, scratch: &mut Vec<T>) {
        let loaded = self.load_rows(rows, buf, scratch, &mut ());
        self.store_rows(rows, buf, loaded, false);
    }

    /// [`Self::apply_rows`] reading the samples from `src` (rows of the
    /// same shape as `rows`) and writing the coefficients into `rows`: a
    /// copy fused into the filter. `seen` takes in every source row just
    /// before the filter reads it (then from L1: the caller's finiteness
    /// and magnitude check, [`RowCheck`]). The same bits as copying
    /// `src` into `rows` and calling [`Self::apply_rows`]. `stream`: the
    /// last pass writes `rows` by streaming stores (`lanes::stream_row`,
    /// the same values; for rows that the caller will not read again while
    /// they could still be in cache).
    pub(crate) fn apply_rows_from<R: AsRef<[T]>, F: RowCheck>(
        &self,
        src: &[R],
        rows: &mut [&mut [T]],
        buf: &mut Vec<T>,
        scratch: &mut Vec<T>,
        seen: &mut F,
        stream: bool,
    ) {
        let loaded = self.load_rows(src, buf, scratch, seen);
        self.store_rows(rows, buf, loaded, stream);
    }

    /// Whether [`Self::apply_rows`] fuses the first and last passes with
    /// the reads and writes of the rows (closed-form starts, a pole, at
    /// least two rows); otherwise the rows go through `buf` whole.
    pub(super) fn fuses_rows(&self, n: usize) -> bool {
        let closed_form = matches!(self.mode, Mode::Mirror | Mode::Reflect | Mode::GridWrap);
        n >= 2 && !self.recursive.poles().is_empty() && self.convolution.is_none() && closed_form
    }

    /// The reading half of [`Self::apply_rows`]: every pass but the last
    /// anti-causal one, from the rows `src` into `buf` (whose row `n − 1`
    /// receives that pass's start); the rows whole through
    /// [`Self::apply_lines`] where the passes do not fuse; two poles as one
    /// pass down ([`Cascade`](super::cascade::Cascade)). Returns what [`Self::store_rows`] has
    /// left to do.
    fn load_rows<R: AsRef<[T]>, F: RowCheck>(
        &self,
        src: &[R],
        buf: &mut Vec<T>,
        scratch: &mut Vec<T>,
        seen: &mut F,
    ) -> Loaded<T> {
        let w = src.first().map_or(0, |r| r.as_ref().len());
        let n = src.len();
        if w == 0 || !self.fuses_rows(n) {
            buf.clear();
            for r in src {
                seen.row(r.as_ref());
                buf.extend_from_slice(r.as_ref());
            }
            self.apply_lines(buf, w, scratch);
            return Loaded::Whole;
        }
        let (mode, r) = (self.mode, &self.recursive);
        if buf.len() < n * w {
            // Every value is written before it is read: no clearing pass
            // (and none when a longer buffer shrinks back).
            buf.resize(n * w, T::zero());
        }
        let buf = &mut buf[..n * w];
        if let Some(cascade) = self.cascade_for(n, mode) {
            return Loaded::Cascade(cascade.load(src, buf, r.gain(), mode, seen));
        }
        let mut acc = vec![T::zero(); w];
        let (z0, k0) = (&r.poles()[0], r.horizons()[0]);
        seen.row(src[0].as_ref());
        causal_start_of(src, Some(r.gain()), z0, k0, mode, &mut acc);
        buf[..w].clone_from_slice(&acc);
        let mut step = Causal {
            gain: r.gain(),
            z: z0,
        };
        load_down(src, buf, &mut step, seen);
        let last = r.poles().len() - 1;
        for (p, (z, &k)) in r.poles().iter().zip(r.horizons()).enumerate() {
            if p > 0 {
                causal_start_rows(buf, w, z, k, mode, &mut acc);
                buf[..w].clone_from_slice(&acc);
                lanes::causal_strided(buf, w, z);
            }
            anticausal_start_rows(buf, w, z, k, mode, &mut acc);
            buf[(n - 1) * w..].clone_from_slice(&acc);
            if p < last {
                lanes::anticausal_strided(buf, w, z);
            }
        }
        Loaded::Last
    }

    /// The writing half of [`Self::apply_rows`]: the last anti-causal
    /// pass (or both poles' of a [`Cascade`](super::cascade::Cascade)) from `buf` into `rows`, or
    /// `buf`'s rows copied.
    fn store_rows(&self, rows: &mut [&mut [T]], buf: &[T], loaded: Loaded<T>, stream: bool) {
        let w = rows.first().map_or(0, |r| r.len());
        if w == 0 {
            return;
        }
        let buf = &buf[..rows.len() * w];
        let poles = self.recursive.poles();
        match (loaded, poles) {
            (Loaded::Whole, _) => {
                for (r, src) in rows.iter_mut().zip(buf.chunks(w)) {
                    r.clone_from_slice(src);
                }
            }
            (Loaded::Cascade(mut u), [z1, z2]) => {
                let mut step = Anticausal2 {
                    z: [z1, z2],
                    u: &mut u,
                };
                store_up(rows, buf, &mut step, stream);
            }
            (_, poles) => {
                let z = poles.last().expect("fused rows have a pole");
                store_up(rows, buf, &mut Anticausal { z }, stream);
            }
        }
    }

    /// Fills `ext` with the extended rows `lo .. lo + count` of `rows`.
    pub(super) fn extend_rows_into(
        &self,
        rows: &[T],
        w: usize,
        lo: i64,
        count: usize,
        ext: &mut Vec<T>,
    ) {
        let len = rows.len() / w;
        ext.clear();
        for j in 0..count as i64 {
            match self.mode.fold(lo + j, len) {
                Some(k) => ext.extend_from_slice(&rows[k * w..(k + 1) * w]),
                None => ext.extend(std::iter::repeat_n(self.cval.clone(), w)),
            }
        }
    }

    /// [`Self::run`] on every column of `c` (`L × w`).
    pub(super) fn run_rows(&self, c: &mut [T], w: usize, mode: Mode) {
        let r = &self.recursive;
        let len = c.len() / w;
        if len == 1 {
            let k = r.constant_response();
            for x in c.iter_mut() {
                *x = x.clone() * &k;
            }
            return;
        }
        lanes::scale(c, r.gain());
        self.poles_rows(c, w, mode);
    }

    /// The gain by which [`Self::apply_lines_scaled`] wants its rows
    /// multiplied (the first step of [`Self::apply_lines`], left to the
    /// caller's load of the rows), for `len` rows; `None` where
    /// [`Self::apply_lines`] starts otherwise (one row, a mode without
    /// closed-form starts, the convolution), and the caller loads the rows
    /// as they are and calls it.
    pub(crate) fn load_gain(&self, len: usize) -> Option<&T> {
        let closed_form = matches!(self.mode, Mode::Mirror | Mode::Reflect | Mode::GridWrap);
        (len >= 2 && closed_form && self.convolution.is_none()).then(|| self.recursive.gain())
    }

    /// [`Self::apply_lines`] on rows already multiplied by
    /// [`Self::load_gain`] (`Some`): the same operations, so the same bits
    /// (the product `gain · s` is the same whichever side loads it).
    pub(crate) fn apply_lines_scaled(&self, rows: &mut [T], w: usize) {
        self.poles_rows(rows, w, self.mode);
    }

    /// Every pole's causal and anti-causal pass down and up the columns of
    /// `c` (`L × w`, `L ≥ 2`, already scaled by the gain).
    fn poles_rows(&self, c: &mut [T], w: usize, mode: Mode) {
        let r = &self.recursive;
        let len = c.len() / w;
        if let Some(cascade) = self.cascade_for(len, mode) {
            return cascade.rows(c, w, mode);
        }
        let mut acc = vec![T::zero(); w];
        for (z, &k) in r.poles().iter().zip(r.horizons()) {
            causal_start_rows(c, w, z, k, mode, &mut acc);
            c[..w].clone_from_slice(&acc);
            lanes::causal_strided(c, w, z);
            anticausal_start_rows(c, w, z, k, mode, &mut acc);
            c[(len - 1) * w..].clone_from_slice(&acc);
            lanes::anticausal_strided(c, w, z);
        }
    }
}

/// What [`LineFilter::load_rows`] left in the work buffer for
/// [`LineFilter::store_rows`].
enum Loaded<T> {
    /// The finished coefficients (the rows went through
    /// [`LineFilter::apply_lines`]).
    Whole,
    /// Every pass but the last pole's anti-causal one.
    Last,
    /// Both causal passes of a [`Cascade`](super::cascade::Cascade); the value is the first pole's
    /// anti-causal start `u_{n−1}` of each line.
    Cascade(Vec<T>),
}
