//! The prefilter of one line of samples under a scipy boundary [`Mode`]:
//! the coefficients `D_k` with `Σ_i D_i β(j − i) = s_j` for every integer
//! `j`, the samples extended by the mode. The kernel the N-D engine runs on
//! every line of every axis.
//!
//! Three routes ([`Route`]):
//!
//! - **exact**: the recursive filter of [`RecursivePrefilter`] (a causal and
//!   an anti-causal first-order recursion per pole, after the gain, which is
//!   correctly rounded: [`RecursivePrefilter::gain`]). Initial values: the
//!   causal one sums the extended signal to the pole's horizon `K`
//!   (`|ξ|^K < 2^{−BITS−8}`) by Horner's rule from the far end
//!   (`causal_start`); the anti-causal one is the closed form of the
//!   mode — `ξ/(ξ² − 1)(c⁺_{ν−1} + ξ c⁺_{ν−2})` (mirror), `ξ/(ξ − 1) c⁺_{ν−1}`
//!   (reflect), `−ξ Σ_j ξ^j c⁺_{(ν−1+j) mod ν}` (grid-wrap, Horner's rule
//!   again) (Unser, Aldroubi and Eden 1993; Thévenaz, Blu and Unser 2000;
//!   the same closed forms as scipy's `ni_splines.c`, which sums the causal
//!   start over one period and divides by `1 − ξ^{period}`). Accuracy on
//!   lines of 2 to 40 samples, degrees 2–5, every mode, against the exact
//!   rational coefficients: worst 2.7 `ε · max|D|`, mean 0.9
//!   (`verify/tests/it/prefilter_rounding.rs`). `nearest` and `grid-constant` have no finite
//!   closed form: the line is padded by `P = max K + 2` extended samples on
//!   each side and filtered as `mirror`; the mirror of the padded line agrees
//!   with the true extension to distance `2P`, so the neglected influence is
//!   below `2^{−2·BITS}` relatively (scipy pads by 12, which leaves
//!   `ρ^{24} ≈ 1.6·10^{−9}` for quintics).
//! - **truncated** (`tol=`): certified to `Σ_{|j|>n} |c_j| · max|s|` of the
//!   exact result, computed the fastest way that keeps it: here (one line
//!   at a time, or lines side by side) the exact recursion itself; one long
//!   line in certified blocks (`block_filter`, chosen by the N-D and Python
//!   entry points).
//! - **convolution**: the S-spline convolution `D_k = Σ_{|j|≤n} c_{|j|} s_{k−j}`
//!   (seed 000 eq 10, 20) of half-width `n`, over the extended samples;
//!   against the exact result its error is at most
//!   `Σ_{|j|>n} |c_j| · max|s|`, the width chooser's guaranteed bound. Local
//!   (`D_k` reads `n` samples each side), as chunked filtering needs.

use super::NdimageError;
use super::lanes;
use super::mode::Mode;
use super::nan_policy::NanPolicy;
use super::samples::{Sample, Stored};
use crate::scalar::Real;
use crate::sspline::SplineFamily;
use crate::sspline::prefilter::{ConvolutionPrefilter, RecursivePrefilter};
use crate::sspline::width::certified_width;
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

/// How the coefficients are computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Route {
    /// The exact recursive filter.
    Exact,
    /// Coefficients within `bound · max|s|` of the exact ones per filtered
    /// axis (`bound = Σ_{|j|>W}|c_j| < tol`, `W` the width certified for
    /// `tol`), by the fastest route that keeps that bound: lines filtered
    /// side by side (every N-D axis, short lines) run the exact recursion
    /// (difference 0); one long line runs in certified blocks of overlap
    /// `W` whose recursions advance in vector lanes and on every thread
    /// ([`BlockPrefilter`](super::block_filter::BlockPrefilter), chosen by
    /// [`spline_filter1d`](super::nd_prefilter::spline_filter1d) and the
    /// Python package). Never slower than [`Route::Exact`].
    Truncated {
        /// The tolerance, `0 < tol < 1`.
        tol: f64,
    },
    /// The truncated convolution itself, `D_k = Σ_{|j|≤W} c_j s_{k−j}`
    /// (seed 000 eq 10) with `W` certified for `tol`: `2W + 1` taps per
    /// sample, slower than the recursion, but local — `D_k` reads only
    /// `s_{k−W} .. s_{k+W}`, which chunked filtering (the dask route) needs
    /// for a chunk to agree with the whole array. Error against the exact
    /// result at most `Σ_{|j|>W}|c_j| · max|s|`.
    Convolution {
        /// The tolerance, `0 < tol < 1`.
        tol: f64,
    },
}

/// The mode-aware prefilter of one line.
#[derive(Debug, Clone)]
pub struct LineFilter<T> {
    recursive: RecursivePrefilter<T>,
    cascade: Option<Box<Cascade<T>>>,
    convolution: Option<ConvolutionPrefilter<T>>,
    width: Option<usize>,
    bound: f64,
    mode: Mode,
    cval: T,
    nan_policy: NanPolicy,
}

impl<T: Real> LineFilter<T> {
    /// The filter of `family` under `mode` (`cval` used by `grid-constant`
    /// only), by `route`. Cost: one pole computation in MPFR (and for the
    /// truncated and convolution routes one width choice, `O(n)` MPFR
    /// coefficients).
    ///
    ///
    /// **Accuracy**: exact route as [`RecursivePrefilter`] (`O(u/|V(−1)|)` relative); truncated
    /// and convolution routes within their certified bound
    /// (`verify/tests/it/engine_properties.rs::truncated_route_stays_within_its_certified_bound`).
    /// **Source**: Unser, Aldroubi and Eden (1993) for the recursion, seed 000 eq 10 for the
    /// truncation.
    ///
    /// ```
    /// use splinelab::sspline::SplineFamily;
    /// use splinelab::ndimage::{mode::Mode, line_filter::{LineFilter, Route}};
    /// let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Reflect, 0.0, Route::Exact).unwrap();
    /// let mut c = vec![1.0, 4.0, 2.0, 0.0];
    /// f.apply(&mut c, &mut Vec::new());
    /// // Half-sample symmetric ends: s_{−1} = s_0, so (D_0 + 4 D_0 + D_1)/6 = s_0.
    /// assert!(((5.0 * c[0] + c[1]) / 6.0 - 1.0).abs() < 1e-15);
    /// ```
    pub fn new(
        family: &SplineFamily,
        mode: Mode,
        cval: f64,
        route: Route,
    ) -> Result<Self, NdimageError> {
        let recursive = RecursivePrefilter::new(family)?;
        let (convolution, width, bound) = match route {
            Route::Exact => (None, None, 0.0),
            Route::Truncated { tol } => {
                let (n, bound) = certified_width(family, tol)?;
                (None, Some(n), bound)
            }
            Route::Convolution { tol } => {
                let (n, bound) = certified_width(family, tol)?;
                (Some(ConvolutionPrefilter::new(family, n)?), Some(n), bound)
            }
        };
        let cascade = match (recursive.poles(), &convolution) {
            ([z1, z2], None) => Some(Box::new(Cascade::new(z1, z2, recursive.horizons()))),
            _ => None,
        };
        Ok(LineFilter {
            recursive,
            cascade,
            convolution,
            width,
            bound,
            mode,
            cval: T::from_f64_exact(cval),
            nan_policy: NanPolicy::default(),
        })
    }

    /// The filter with `policy` for non-finite samples (default
    /// [`NanPolicy::Propagate`]), read by the N-D prefilters
    /// ([`spline_filter1d`](super::nd_prefilter::spline_filter1d),
    /// [`spline_filter`](super::nd_prefilter::spline_filter),
    /// [`spline_filter_from`](super::nd_prefilter::spline_filter_from)).
    /// [`NanPolicy::Local`] needs a certified half-width: refused
    /// ([`NdimageError::LocalNeedsTol`]) for [`Route::Exact`].
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// use splinelab::ndimage::nan_policy::NanPolicy;
    /// let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
    /// assert!(f.clone().with_nan_policy(NanPolicy::Local).is_err());
    /// let f = f.with_nan_policy(NanPolicy::Raise).unwrap();
    /// let mut a = ndarray::array![1.0, f64::NAN, 2.0];
    /// let e = spline_filter(&mut a, &f).unwrap_err();
    /// assert_eq!(e.to_string(), "sample 1 is not finite (nan)");
    /// ```
    pub fn with_nan_policy(mut self, policy: NanPolicy) -> Result<Self, NdimageError> {
        if policy == NanPolicy::Local && self.width.is_none() {
            return Err(NdimageError::LocalNeedsTol);
        }
        self.nan_policy = policy;
        Ok(self)
    }

    /// What the N-D prefilters do with non-finite samples.
    pub fn nan_policy(&self) -> NanPolicy {
        self.nan_policy
    }

    /// The constant beyond the ends of `grid-constant`.
    pub(crate) fn cval(&self) -> &T {
        &self.cval
    }

    /// The mode.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The recursive filter (poles, gain, horizons, conditioning).
    pub fn recursive(&self) -> &RecursivePrefilter<T> {
        &self.recursive
    }

    /// A bound on every value the filter forms along one axis, per unit of
    /// `max(max|s|, |cval|)`: `gain · Π_k (2/(1 − |z_k|))²` (each pole's
    /// causal pass grows by at most `1/(1 − |z|)`, its anti-causal pass by
    /// `2|z|/(1 − |z|)`; the truncated route's `Σ|c_j|` is below it too).
    /// Generous (cubic: 44.8), so that data below `MAX / growth` can never
    /// overflow. `O(p)`.
    pub fn growth(&self) -> f64 {
        growth_of(&self.recursive)
    }

    /// Refuses data of largest magnitude `max_abs` that the filter could
    /// overflow along `axes` axes: for scalars of at most 53 bits (f32,
    /// f64), `max(max_abs, |cval|) · growth^axes` must stay below the
    /// largest finite value ([`Self::growth`]; `cval` only under
    /// `grid-constant`, the one mode that extends by it); MPFR's exponent
    /// range makes overflow unreachable. `O(p)`; where `growth^axes` alone
    /// exceeds the range (a high degree), [`NdimageError::DegreeRange`]
    /// names a degree that fits, found by bisection over the degrees
    /// (`O(log d)` pole computations, on this error path only).
    ///
    /// **Method**: compares `max(max_abs, |cval|) · growth^axes` with the scalar's largest
    /// value. **Accuracy**: a sufficient bound (never refuses data that cannot overflow by more
    /// than the growth's slack; data just below the limit is exact,
    /// `verify/tests/it/engine_properties.rs::data_that_could_overflow_is_refused_and_data_below_the_limit_is_exact`).
    /// **Source**: the geometric-series bound of each first-order recursion `|c_k| ≤ max|s|/(1
    /// − |z|)` (Unser, Aldroubi and Eden 1993).
    pub fn check_magnitude(&self, max_abs: f64, axes: usize) -> Result<(), NdimageError> {
        if T::BITS > 53 {
            return Ok(());
        }
        let top = if T::BITS <= 24 {
            f32::MAX as f64
        } else {
            f64::MAX
        };
        self.check_magnitude_below(max_abs, axes, top)
    }

    /// [`Self::check_magnitude`] for coefficients stored as `O`
    /// ([`Stored`]): also refused where they could pass the largest value
    /// `O` holds (`f32` coefficients of an `f64` filter: the filter cannot
    /// overflow in `f64`, but its results would be ±∞ in `f32`).
    pub fn check_magnitude_for<O: Stored<T>>(
        &self,
        max_abs: f64,
        axes: usize,
    ) -> Result<(), NdimageError> {
        self.check_magnitude(max_abs, axes)?;
        match O::LARGEST {
            top if top.is_finite() => self.check_magnitude_below(max_abs, axes, top),
            _ => Ok(()),
        }
    }

    /// The check of [`Self::check_magnitude`] against `top`, the largest
    /// magnitude the results may take.
    fn check_magnitude_below(
        &self,
        max_abs: f64,
        axes: usize,
        top: f64,
    ) -> Result<(), NdimageError> {
        let growth = self.growth();
        let axes_i = i32::try_from(axes).unwrap_or(i32::MAX);
        let limit = top / growth.powi(axes_i);
        let max = match self.mode {
            Mode::GridConstant => max_abs.max(self.cval.to_f64().abs()),
            _ => max_abs,
        };
        if max <= limit {
            return Ok(());
        }
        if limit > 0.0 {
            return Err(NdimageError::Overflow { max, growth, limit });
        }
        // No data is safe at this degree: say which degree is.
        let SplineFamily::Order(order) = *self.recursive.family() else {
            return Err(NdimageError::Overflow { max, growth, limit });
        };
        let degree = order.saturating_sub(1);
        let fits = |d: u32| {
            SplineFamily::order(d + 1)
                .ok()
                .and_then(|f| RecursivePrefilter::<f64>::new(&f).ok())
                .is_some_and(|r| max.max(f64::MIN_POSITIVE) * growth_of(&r).powi(axes_i) <= top)
        };
        Err(NdimageError::DegreeRange {
            degree,
            axes,
            bits: T::BITS,
            fits: largest_true(2, degree, fits),
        })
    }

    /// The certified half-width `W` of `tol` (the convolution's half-width,
    /// the blocks' overlap), `None` for the exact route.
    pub fn half_width(&self) -> Option<usize> {
        self.width
    }

    /// Whether this is [`Route::Convolution`] (local: `D_k` reads only
    /// `s_{k−W} .. s_{k+W}`).
    pub fn is_convolution(&self) -> bool {
        self.convolution.is_some()
    }

    /// The truncated convolution of [`Route::Convolution`] (`None` for the
    /// other routes): the local route's per-axis pass.
    pub(crate) fn convolution(&self) -> Option<&ConvolutionPrefilter<T>> {
        self.convolution.as_ref()
    }

    /// For the truncated and convolution routes, `Σ_{|j|>W} |c_j|` (0 for
    /// the exact route): `|D − D_exact| ≤ bound · max|s|` on one line.
    pub fn bound(&self) -> f64 {
        self.bound
    }

    /// Samples beyond each end the exact route needs for `nearest` and
    /// `grid-constant`: the longest horizon plus 2.
    pub fn exact_pad(&self) -> usize {
        self.recursive.horizons().iter().copied().max().unwrap_or(0) + 2
    }

    /// The extended sample `s_i`.
    pub(crate) fn sample(&self, s: &[T], i: i64) -> T {
        match self.mode.fold(i, s.len()) {
            Some(k) => s[k].clone(),
            None => self.cval.clone(),
        }
    }

    /// Fills `ext` with `s_i`, `i = lo .. lo + ext.len()`.
    fn extend_into(&self, s: &[T], lo: i64, ext: &mut Vec<T>, len: usize) {
        ext.clear();
        ext.extend((0..len as i64).map(|j| self.sample(s, lo + j)));
    }

    /// Replaces the samples in `line` by their coefficients, in place
    /// (`scratch` is reused between calls). Cost: exact `9p + 1` flops per
    /// sample plus `O(pK)` (the two-step look-ahead of the causal and
    /// anti-causal passes spends 5 more flops per pole to halve the dependency
    /// chain); the truncated route runs the exact recursion (difference 0,
    /// within its bound); the convolution `2n + 1` flops per sample.
    pub fn apply(&self, line: &mut [T], scratch: &mut Vec<T>) {
        self.apply_padded(line, 0, scratch);
    }

    /// The coefficients `D_{−pad} .. D_{ν+pad−1}` of the samples in
    /// `out[pad .. pad + ν]` (the rest of `out` is overwritten): the
    /// coefficients beyond the ends that evaluation near the ends reads.
    ///
    /// **Method**: the line padded by `P = max K + 2` extended samples each side and filtered
    /// under the mirror rule (module documentation). **Accuracy**: the exact spline of the
    /// extended signal to `2^{−2·BITS}` relative
    /// (`verify/tests/it/engine_properties.rs::nearest_outside_the_grid_is_the_edge_extended_spline`).
    /// **Source**: scipy's padding of `nearest`/`grid-constant` (`ni_interpolation.c`), with
    /// the pad widened to the pole horizon.
    pub fn apply_padded(&self, out: &mut [T], pad: usize, scratch: &mut Vec<T>) {
        let len = out.len() - 2 * pad;
        if len == 0 {
            return;
        }
        if let Some(conv) = &self.convolution {
            let n = conv.half_width();
            let s = out[pad..pad + len].to_vec();
            self.extend_into(&s, -((pad + n) as i64), scratch, len + 2 * (pad + n));
            conv.apply_extended(scratch, out);
            return;
        }
        match self.mode {
            Mode::Mirror | Mode::Reflect | Mode::GridWrap => {
                self.symmetric(&mut out[pad..pad + len]);
                if pad > 0 {
                    let d = out[pad..pad + len].to_vec();
                    for (j, o) in out.iter_mut().enumerate() {
                        *o = self.sample(&d, j as i64 - pad as i64);
                    }
                }
            }
            Mode::Nearest | Mode::GridConstant => {
                let big = self.exact_pad() + pad;
                let s = out[pad..pad + len].to_vec();
                self.extend_into(&s, -(big as i64), scratch, len + 2 * big);
                self.run(scratch, Mode::Mirror);
                let off = big - pad;
                out.clone_from_slice(&scratch[off..off + len + 2 * pad]);
            }
        }
    }

    /// The exact filter for the three modes with closed-form initial values.
    fn symmetric(&self, c: &mut [T]) {
        self.run(c, self.mode);
    }

    fn run(&self, c: &mut [T], mode: Mode) {
        let r = &self.recursive;
        if c.len() == 1 {
            // Every symmetric extension of one sample is constant.
            c[0] = c[0].clone() * r.constant_response();
            return;
        }
        let gain = r.gain().clone();
        for x in c.iter_mut() {
            *x *= gain.clone();
        }
        for (z, &k) in r.poles().iter().zip(r.horizons()) {
            c[0] = causal_start(c, z, k, mode);
            causal(c, z.clone());
            let last = c.len() - 1;
            c[last] = anticausal_start(c, z, k, mode);
            anticausal(c, z.clone());
        }
    }
}

impl<T: Real> LineFilter<T> {
    /// Filters `w` lines at once, in place: `rows` holds `L × w` values,
    /// row `i` the sample `i` of every line (line `j` is the column
    /// `rows[j], rows[w + j], …`). The strided axes of an N-D array run
    /// through this: each step of the recursion is a contiguous vector
    /// operation over `w` lines (vectorised, cache friendly, no per-line
    /// copy). The recursion of [`Self::apply`] one step at a time (the
    /// single line uses a two-step look-ahead instead), so both agree to a
    /// few ulps of `max|s|`, not bitwise; `4p + 1` flops per sample. Two
    /// poles run as one pass down the rows and one up ([`Cascade`], lines
    /// of at least 3 samples under mirror, reflect and grid-wrap, and the
    /// padded lines of nearest and grid-constant): the same flops in
    /// another order, within the same bound.
    ///
    ///
    /// **Accuracy**: the doc example and
    /// `verify/tests/it/engine_scipy.rs::spline_filter_matches_scipy` (strided axes run here).
    /// **Source**: Unser, Aldroubi and Eden (1993), the causal/anti-causal recursion; initial
    /// values as Thévenaz, Blu and Unser (2000).
    ///
    /// ```
    /// use splinelab::sspline::SplineFamily;
    /// use splinelab::ndimage::{mode::Mode, line_filter::{LineFilter, Route}};
    /// let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
    /// let (a, b) = ([1.0, 4.0, 2.0, 0.0], [3.0, -1.0, 0.5, 2.0]);
    /// let mut rows: Vec<f64> = a.iter().zip(&b).flat_map(|(x, y)| [*x, *y]).collect();
    /// f.apply_lines(&mut rows, 2, &mut Vec::new());
    /// let mut c = a.to_vec();
    /// f.apply(&mut c, &mut Vec::new());
    /// assert!((0..4).all(|i| (rows[2 * i] - c[i]).abs() <= 4.0 * f64::EPSILON * 4.0));
    /// ```
    pub fn apply_lines(&self, rows: &mut [T], w: usize, scratch: &mut Vec<T>) {
        if w == 0 || rows.len() < w {
            return;
        }
        let len = rows.len() / w;
        if let Some(conv) = &self.convolution {
            let n = conv.half_width();
            self.extend_rows_into(rows, w, -(n as i64), len + 2 * n, scratch);
            convolve_rows(conv.coefficients(), scratch, rows, w);
            return;
        }
        match self.mode {
            Mode::Mirror | Mode::Reflect | Mode::GridWrap => self.run_rows(rows, w, self.mode),
            Mode::Nearest | Mode::GridConstant => {
                let big = self.exact_pad();
                self.extend_rows_into(rows, w, -(big as i64), len + 2 * big, scratch);
                self.run_rows(scratch, w, Mode::Mirror);
                rows.clone_from_slice(&scratch[big * w..(big + len) * w]);
            }
        }
    }

    /// [`Self::apply_lines`] on rows that stay where they lie: `rows[i]` is
    /// sample `i` of `w` lines (a strided axis of an array, read and written
    /// in place). For the modes with closed-form starts the first pole's
    /// gain and causal pass run while the rows are read into `buf`, and the
    /// last anti-causal pass writes the rows directly: the array is read and
    /// written once, and `buf` sees two passes per pole instead of five
    /// (copy in, gain, causal, anti-causal, copy out); two poles (degrees
    /// 4 and 5) run as one pass down and one up ([`Cascade`]), so `buf`
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
    fn fuses_rows(&self, n: usize) -> bool {
        let closed_form = matches!(self.mode, Mode::Mirror | Mode::Reflect | Mode::GridWrap);
        n >= 2 && !self.recursive.poles().is_empty() && self.convolution.is_none() && closed_form
    }

    /// The reading half of [`Self::apply_rows`]: every pass but the last
    /// anti-causal one, from the rows `src` into `buf` (whose row `n − 1`
    /// receives that pass's start); the rows whole through
    /// [`Self::apply_lines`] where the passes do not fuse; two poles as one
    /// pass down ([`Cascade`]). Returns what [`Self::store_rows`] has
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
    /// pass (or both poles' of a [`Cascade`]) from `buf` into `rows`, or
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
    fn extend_rows_into(&self, rows: &[T], w: usize, lo: i64, count: usize, ext: &mut Vec<T>) {
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
    fn run_rows(&self, c: &mut [T], w: usize, mode: Mode) {
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

impl<T: Real> LineFilter<T> {
    /// The [`Cascade`] of a filter of two poles, for lines of `n ≥ 3`
    /// samples under a mode with closed-form starts (`None` otherwise:
    /// the poles' passes in turn).
    fn cascade_for(&self, n: usize, mode: Mode) -> Option<&Cascade<T>> {
        let closed_form = matches!(mode, Mode::Mirror | Mode::Reflect | Mode::GridWrap);
        self.cascade.as_deref().filter(|_| n >= 3 && closed_form)
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
    /// Both causal passes of a [`Cascade`]; the value is the first pole's
    /// anti-causal start `u_{n−1}` of each line.
    Cascade(Vec<T>),
}

/// The two poles `ξ₁, ξ₂` of a degree-4 or degree-5 spline as one pass
/// down the lines and one pass up, instead of down, up, down, up: the four
/// first-order filters are linear and shift-invariant on the extended
/// (infinite) signal, so they commute, and `A₂A₁C₂C₁ s` is the spline's
/// coefficients (up to the gain) like `A₂C₂A₁C₁ s`. Down,
/// `y_k = x_k + ξ₁ y_{k−1}`, `w_k = y_k + ξ₂ w_{k−1}`; up,
/// `u_k = ξ₁ (u_{k+1} − w_k)`, `c_k = ξ₂ (c_{k+1} − u_k)`. A strided
/// axis then reads and writes its work buffer twice instead of four
/// times, and the two chains of each pass are independent work for the
/// vector units.
///
/// **Starts.** `y_0 = Σ_{k<R} ξ₁^k x_{−k}` and
/// `w_0 = Σ_{k<R} h_k x_{−k}` with `h_k = Σ_{i+j=k} ξ₁^i ξ₂^j` (the two
/// causal filters' joint impulse response, `h_k = ξ₂ h_{k−1} + ξ₁^k`),
/// the samples extended by the mode, the reach `R` the larger horizon and
/// on until `|h_k|` is below the larger pole's `|ξ|^K`: both by Horner's
/// rule, the two recursions run from `x_{−R+1}` (state 0) up to `x_0`, so
/// each rounding is damped on its way to the start (as
/// [`causal_start`]). At the end the coefficients
/// `c` are symmetric like the samples; with `P = ξ₁ξ₂`, `Q = ξ₁ + ξ₂`,
/// inverting both anti-causal filters gives
/// `P w_k = P c_{k+2} − Q c_{k+1} + c_k`, and for `k = n−1, n−2, n−3`
/// (mirror: `c_{n−1+j} = c_{n−1−j}`) three equations in `c_{n−1}, c_{n−2},
/// c_{n−3}`; reflect (`c_{n−1+j} = c_{n−j}`) two in `c_{n−1}, c_{n−2}`.
/// Their solution (Cramer's rule, once per filter) gives `c_{n−1}`, and
/// `u_{n−1} = c_n − c_{n−1}/ξ₂` (the second anti-causal filter inverted):
/// each a fixed combination of the last three (two) `w`. The determinants
/// are `(1 − ξ₁²)(1 − ξ₂²)(1 − P)`-like products of factors in `(0, 2)`
/// (mirror: `(1 − P)((1 + P)² − Q²)`, reflect: `(1 − P)(1 − ξ₁)(1 − ξ₂)`),
/// never small. Grid-wrap: the periodic sums `u_{n−1} = −Σ_m ξ₁^{m+1}
/// w_{n−1+m}` and `c_{n−1} = P Σ_m h_m w_{n−1+m}` (indices mod `n`,
/// `m < R`), by Horner's rule as the starts. The
/// one-pole closed forms (Unser, Aldroubi and Eden 1993) are the same
/// derivation with one filter.
///
/// **Cost**: `4` flops per sample and pole as before, plus `O(K)` rows of
/// starts. **Accuracy**: another order of the same operations: a few `u`
/// of `A · max|s|` per axis like the passes in turn (tested against 128-bit
/// MPFR in `nd_prefilter`'s and `engine_lanes`' tests; the rows of
/// [`LineFilter::apply_rows`] and [`LineFilter::apply_lines`] run the
/// same operations, bit for bit).
#[derive(Debug, Clone)]
struct Cascade<T> {
    z: [T; 2],
    /// The reach `R` of the starts (terms of `h`).
    reach: usize,
    /// Mirror: the weights of `w_{n−1}, w_{n−2}, w_{n−3}` in `u_{n−1}`
    /// and in `c_{n−1}`.
    mirror: [[T; 3]; 2],
    /// Reflect: the same for `w_{n−1}, w_{n−2}`.
    reflect: [[T; 2]; 2],
    /// `P = ξ₁ξ₂` (grid-wrap's `c_{n−1}`).
    p: T,
}

impl<T: Real> Cascade<T> {
    /// The cascade of the poles `z1` (the smaller) and `z2` with their
    /// horizons. `O(K)`.
    fn new(z1: &T, z2: &T, horizons: &[usize]) -> Self {
        let kmax = horizons.iter().copied().max().unwrap_or(0);
        let big = z1.to_f64().abs().max(z2.to_f64().abs());
        let tail = big.powi(kmax as i32);
        let mut h = vec![T::one()];
        let mut z1k = T::one();
        while h.len() < kmax.max(1) || (h[h.len() - 1].to_f64().abs() > tail && h.len() < 4 * kmax)
        {
            z1k *= z1.clone();
            let next = z2.clone() * &h[h.len() - 1] + &z1k;
            h.push(next);
        }
        let (one, zero) = (T::one(), T::zero());
        let p = z1.clone() * z2;
        let q = z1.clone() + z2;
        // `u_{n−1} = c_n − c_{n−1}/ξ₂` from the weights of `c_{n−1}` (a)
        // and of `c_n` (b): each times `P`, the equations' right side.
        let weights = |a: &T, b: &T| {
            let (a, b) = (p.clone() * a, p.clone() * b);
            (b - a.clone() / z2, a)
        };
        let m = [
            [one.clone(), -q.clone(), p.clone()],
            [-q.clone(), one.clone() + &p, zero.clone()],
            [p.clone(), -q.clone(), one.clone()],
        ];
        let inv = inverse3(&m);
        let mirror: [(T, T); 3] = std::array::from_fn(|j| weights(&inv[0][j], &inv[1][j]));
        // Reflect: c_n = c_{n−1}.
        let m = [[one.clone() - &q, p.clone()], [p.clone() - &q, one.clone()]];
        let inv = inverse2(&m);
        let reflect: [(T, T); 2] = std::array::from_fn(|j| weights(&inv[0][j], &inv[0][j]));
        Cascade {
            z: [z1.clone(), z2.clone()],
            reach: h.len(),
            mirror: [mirror.clone().map(|(u, _)| u), mirror.map(|(_, c)| c)],
            reflect: [reflect.clone().map(|(u, _)| u), reflect.map(|(_, c)| c)],
            p,
        }
    }

    /// The starts `y_0` and `w_0` of every column of `rows` (times `gain`
    /// first, if given) into `y` and `w0`.
    fn starts<R: AsRef<[T]>>(
        &self,
        rows: &[R],
        gain: Option<&T>,
        mode: Mode,
        y: &mut [T],
        w0: &mut [T],
    ) {
        y.fill(T::zero());
        w0.fill(T::zero());
        for k in (0..self.reach).rev() {
            let i = mode.fold(-(k as i64), rows.len()).unwrap_or(0);
            horner2_row(y, w0, &self.z, rows[i].as_ref(), gain);
        }
    }

    /// The anti-causal starts `u_{n−1}` and `c_{n−1}` of every column of
    /// the causal values `c` (`n × w`) into `u` and `last`.
    fn ends(&self, c: &[T], w: usize, mode: Mode, u: &mut [T], last: &mut [T]) {
        let n = c.len() / w;
        let row = |i: usize| &c[i * w..(i + 1) * w];
        u.fill(T::zero());
        last.fill(T::zero());
        // Mirror and reflect: fixed weights of the last three (two) rows.
        let weights: Option<(&[T], &[T])> = match mode {
            Mode::Mirror => Some((&self.mirror[0], &self.mirror[1])),
            Mode::Reflect => Some((&self.reflect[0], &self.reflect[1])),
            _ => None,
        };
        match weights {
            Some((for_u, for_last)) => {
                for (j, (fu, fc)) in for_u.iter().zip(for_last).enumerate() {
                    add_scaled(u, fu, row(n - 1 - j));
                    add_scaled(last, fc, row(n - 1 - j));
                }
            }
            None => {
                for m in (0..self.reach).rev() {
                    horner2_row(u, last, &self.z, row((n - 1 + m) % n), None);
                }
                let (mz, p) = (-self.z[0].clone(), &self.p);
                for (u, c) in u.iter_mut().zip(last.iter_mut()) {
                    *u = mz.clone() * &*u;
                    *c = p.clone() * &*c;
                }
            }
        }
    }

    /// Both poles down and up every column of `c` (`n × w`, `n ≥ 3`,
    /// already scaled by the gain), in place.
    #[inline(never)]
    fn rows(&self, c: &mut [T], w: usize, mode: Mode) {
        let n = c.len() / w;
        let (mut y, mut acc) = (vec![T::zero(); w], vec![T::zero(); w]);
        let rows: Vec<&[T]> = c.chunks(w).collect();
        self.starts(&rows, None, mode, &mut y, &mut acc);
        c[..w].clone_from_slice(&acc);
        lanes::causal2_strided(c, w, &mut y, &self.z[0], &self.z[1]);
        self.ends(c, w, mode, &mut y, &mut acc);
        c[(n - 1) * w..].clone_from_slice(&acc);
        lanes::anticausal2_strided(c, w, &mut y, &self.z[0], &self.z[1]);
    }

    /// The causal half of [`Self::rows`] reading the samples `src` (times
    /// `gain`) into `buf`, `seen` taking in each row; returns `u_{n−1}`,
    /// and `buf`'s last row holds `c_{n−1}` ([`Anticausal2`] does
    /// the rest). The same operations as [`Self::rows`] on the scaled rows.
    #[inline(never)]
    fn load<R: AsRef<[T]>, F: RowCheck>(
        &self,
        src: &[R],
        buf: &mut [T],
        gain: &T,
        mode: Mode,
        seen: &mut F,
    ) -> Vec<T> {
        let n = src.len();
        let w = buf.len() / n;
        let (mut y, mut acc) = (vec![T::zero(); w], vec![T::zero(); w]);
        prefetch_starts(src, mode, self.reach);
        seen.row(src[0].as_ref());
        self.starts(src, Some(gain), mode, &mut y, &mut acc);
        buf[..w].clone_from_slice(&acc);
        let mut step = Causal2 {
            gain,
            z: [&self.z[0], &self.z[1]],
            y: &mut y,
        };
        load_down(src, buf, &mut step, seen);
        self.ends(buf, w, mode, &mut y, &mut acc);
        buf[(n - 1) * w..].clone_from_slice(&acc);
        y
    }
}

/// The inverse of a 3 × 3 matrix (Cramer's rule: the adjugate over the
/// determinant).
fn inverse3<T: Real>(m: &[[T; 3]; 3]) -> [[T; 3]; 3] {
    let cof = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        m[r0][c0].clone() * &m[r1][c1] - m[r0][c1].clone() * &m[r1][c0]
    };
    let det = (0..3).fold(T::zero(), |d, j| d + m[0][j].clone() * cof(0, j));
    std::array::from_fn(|i| std::array::from_fn(|j| cof(j, i) / &det))
}

/// The inverse of a 2 × 2 matrix.
fn inverse2<T: Real>(m: &[[T; 2]; 2]) -> [[T; 2]; 2] {
    let det = m[0][0].clone() * &m[1][1] - m[0][1].clone() * &m[1][0];
    [
        [m[1][1].clone() / &det, -m[0][1].clone() / &det],
        [-m[1][0].clone() / &det, m[0][0].clone() / &det],
    ]
}

/// Asks the cache for the rows `s_{−j}`, `j < count`, of `rows` (folded
/// by `mode`) that a causal start sums: each is a run on its own page,
/// read before the pass's own prefetching ([`rows_ahead`]) begins, and
/// one request after another leaves each miss waiting on the last.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn prefetch_starts<T: Real, R: AsRef<[T]>>(rows: &[R], mode: Mode, count: usize) {
    for j in 0..count.min(rows.len()) {
        let row = rows[mode.fold(-(j as i64), rows.len()).unwrap_or(0)].as_ref();
        match_target! {
            "x86_64+avx2" => lanes::prefetch(row),
            _ => { let _ = row; }
        }
    }
}

/// `acc += f · row` for a row of `w` values.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn add_scaled<T: Real>(acc: &mut [T], f: &T, row: &[T]) {
    for (a, x) in acc.iter_mut().zip(row) {
        *a += f.clone() * x;
    }
}

/// One Horner step of both starts of a [`Cascade`]: `y = row + ξ₁ y`,
/// `w = y + ξ₂ w` (the row times a gain `g` first, if given, as
/// [`lanes::scale`] does).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn horner2_row<T: Real>(y: &mut [T], w: &mut [T], z: &[T; 2], row: &[T], gain: Option<&T>) {
    let [z1, z2] = z;
    for ((y, w), x) in y.iter_mut().zip(w.iter_mut()).zip(row) {
        let x = match gain {
            Some(g) => g.clone() * x,
            None => x.clone(),
        };
        *y = x + z1.clone() * &*y;
        *w = y.clone() + z2.clone() * &*w;
    }
}

/// One Horner step of a start, `acc = row + ξ · acc` for a row of `w`
/// values, or `acc = g · row + ξ · acc` with a gain `g` (the row scaled
/// first, as [`lanes::scale`] does).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn horner_row<T: Real>(acc: &mut [T], z: &T, row: &[T], gain: Option<&T>) {
    match gain {
        Some(g) => {
            for (a, x) in acc.iter_mut().zip(row) {
                *a = g.clone() * x + z.clone() * &*a;
            }
        }
        None => {
            for (a, x) in acc.iter_mut().zip(row) {
                *a = x.clone() + z.clone() * &*a;
            }
        }
    }
}

/// [`causal_start`] of every column of `c` (`L × w`), into `acc`.
fn causal_start_rows<T: Real>(c: &[T], w: usize, z: &T, horizon: usize, mode: Mode, acc: &mut [T]) {
    let rows: Vec<&[T]> = c.chunks(w).collect();
    causal_start_of(&rows, None, z, horizon, mode, acc);
}

/// [`causal_start`] of every column of `rows` (times `gain` first, if
/// given), into `acc`.
fn causal_start_of<T: Real, R: AsRef<[T]>>(
    rows: &[R],
    gain: Option<&T>,
    z: &T,
    horizon: usize,
    mode: Mode,
    acc: &mut [T],
) {
    acc.fill(T::zero());
    for j in (0..horizon.max(1)).rev() {
        let i = mode.fold(-(j as i64), rows.len()).unwrap_or(0);
        horner_row(acc, z, rows[i].as_ref(), gain);
    }
}

/// One row of a pass down a strip ([`load_down`]): row `i` of the work
/// buffer from the samples of row `i` and the buffer's row `i − 1`.
/// Inlined into the walker's vector clones (as [`RowCheck`]).
trait DownStep<T> {
    /// `x` (buffer row `i`) from `s` (sample row `i`) and `prev`.
    fn row(&mut self, x: &mut [T], s: &[T], prev: &[T]);
}

/// The first pole's gain and causal pass: `x = g·s + ξ prev`, the
/// operations of [`lanes::scale`] then [`lanes::causal_strided`].
struct Causal<'a, T> {
    gain: &'a T,
    z: &'a T,
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

/// [`Cascade`]'s pass down: `y = g·s + ξ₁ y`, `x = y + ξ₂ prev`, the
/// operations of [`lanes::causal2_strided`] on scaled rows (`y`: the
/// first pole's row, carried).
struct Causal2<'a, T> {
    gain: &'a T,
    z: [&'a T; 2],
    y: &'a mut [T],
}

impl<T: Real> DownStep<T> for Causal2<'_, T> {
    #[inline(always)]
    fn row(&mut self, x: &mut [T], s: &[T], prev: &[T]) {
        let (g, [z1, z2]) = (self.gain, self.z);
        for (((x, s), p), y) in x.iter_mut().zip(s).zip(prev).zip(self.y.iter_mut()) {
            *y = g.clone() * s + z1.clone() * &*y;
            *x = y.clone() + z2.clone() * p;
        }
    }
}

/// A pass down the rows `rows` into `buf` (row 0 of `buf` already holds
/// the pass's start), `step` forming each row, the rows prefetched
/// [`rows_ahead`]; `seen` takes in each row (from row 1) before it is read.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn load_down<T: Real, R: AsRef<[T]>, F: RowCheck, S: DownStep<T>>(
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
trait UpStep<T> {
    /// `o` (output row `i`) from `next` (row `i + 1`) and `c` (buffer row `i`).
    fn row(&mut self, o: &mut [T], next: &[T], c: &[T]);
}

/// The last anti-causal pass: `o = ξ (next − c)`, the operations of
/// [`lanes::anticausal_strided`].
struct Anticausal<'a, T> {
    z: &'a T,
}

impl<T: Real> UpStep<T> for Anticausal<'_, T> {
    #[inline(always)]
    fn row(&mut self, o: &mut [T], next: &[T], c: &[T]) {
        for ((o, nx), c) in o.iter_mut().zip(next).zip(c) {
            *o = self.z.clone() * (nx.clone() - c.clone());
        }
    }
}

/// [`Cascade`]'s pass up: `u = ξ₁ (u − c)`, `o = ξ₂ (next − u)`, the
/// operations of [`lanes::anticausal2_strided`] (`u`: the first pole's
/// row, carried).
struct Anticausal2<'a, T> {
    z: [&'a T; 2],
    u: &'a mut [T],
}

impl<T: Real> UpStep<T> for Anticausal2<'_, T> {
    #[inline(always)]
    fn row(&mut self, o: &mut [T], next: &[T], c: &[T]) {
        let [z1, z2] = self.z;
        for (((o, nx), c), u) in o.iter_mut().zip(next).zip(c).zip(self.u.iter_mut()) {
            *u = z1.clone() * (u.clone() - c.clone());
            *o = z2.clone() * (nx.clone() - u.clone());
        }
    }
}

/// A pass up writing `rows` from the values in `buf`: row `n − 1` copied
/// (it holds the pass's start), then `step` on each row from `n − 2`
/// down to 0, the rows prefetched [`rows_ahead`]; by streaming stores
/// where `stream` ([`store_up_streamed`]).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn store_up<T: Real, S: UpStep<T>>(rows: &mut [&mut [T]], buf: &[T], step: &mut S, stream: bool) {
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
fn rows_ahead<T>(w: usize) -> usize {
    (PREFETCH_BYTES / (w * std::mem::size_of::<T>()).max(1)).max(1)
}

/// How far ahead the strided passes prefetch their rows (measured, one
/// thread, `spline_filter1d` along axis 0 of 256³ / 4096²: 2 KiB 15.9 /
/// 15.7 ms, 4 KiB 14.4 / 16.3, 8 KiB 14.6 / 17.4, 16 KiB 15.2 / 16.6;
/// without prefetching 4096² took 30.5 ms).
const PREFETCH_BYTES: usize = 4 << 10;

/// [`anticausal_start`] of every column, into `acc`.
fn anticausal_start_rows<T: Real>(
    c: &[T],
    w: usize,
    z: &T,
    horizon: usize,
    mode: Mode,
    acc: &mut [T],
) {
    let n = c.len() / w;
    let last = &c[(n - 1) * w..];
    match mode {
        Mode::Reflect => {
            let f = z.clone() / (z.clone() - T::one());
            for (a, x) in acc.iter_mut().zip(last) {
                *a = f.clone() * x;
            }
        }
        Mode::GridWrap => {
            acc.fill(T::zero());
            for j in (0..horizon.max(1)).rev() {
                let i = (n - 1 + j) % n;
                horner_row(acc, z, &c[i * w..(i + 1) * w], None);
            }
            let mz = -z.clone();
            for a in acc.iter_mut() {
                *a = mz.clone() * a.clone();
            }
        }
        _ => {
            let f = z.clone() / (z.clone() * z - T::one());
            let before = &c[(n - 2) * w..(n - 1) * w];
            for ((a, x), y) in acc.iter_mut().zip(last).zip(before) {
                *a = f.clone() * (x.clone() + z.clone() * y.clone());
            }
        }
    }
}

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

/// `c⁺_k = c_k + ξ c⁺_{k−1}`, `k ≥ 1`, run two steps at a time:
/// `c⁺_k = (c_k + ξ c_{k−1}) + ξ² c⁺_{k−2}`. One step is a dependent
/// multiply-add (the loop is bound by its latency, not by arithmetic);
/// with the look-ahead, two interleaved chains advance at once, the
/// `ξ c_{k−1}` terms being independent work. Rounding: one more operation
/// per sample and the rounded `ξ²`, each a relative `u` on terms the
/// recursion damps by `1/(1 − ξ²)`: the same few ulps.
#[inline]
pub(crate) fn causal<T: Real>(c: &mut [T], z: T) {
    if c.len() < 2 {
        return;
    }
    let z2 = z.clone() * &z;
    let mut older = c[0].clone();
    let mut s_prev = c[1].clone();
    c[1] += z.clone() * &older;
    let mut prev = c[1].clone();
    for x in c[2..].iter_mut() {
        let s = x.clone();
        *x = (s.clone() + z.clone() * s_prev) + z2.clone() * older;
        older = prev;
        prev = x.clone();
        s_prev = s;
    }
}

/// `c⁻_k = ξ (c⁻_{k+1} − c⁺_k)`, `k < ν − 1`, two steps at a time as in
/// [`causal`]: `c⁻_k = ξ² c⁻_{k+2} − (ξ² c⁺_{k+1} + ξ c⁺_k)`.
#[inline]
pub(crate) fn anticausal<T: Real>(c: &mut [T], z: T) {
    let n = c.len();
    if n < 2 {
        return;
    }
    let z2 = z.clone() * &z;
    let mut later = c[n - 1].clone();
    let mut s_next = c[n - 2].clone();
    c[n - 2] = z.clone() * (later.clone() - &s_next);
    let mut next = c[n - 2].clone();
    for x in c[..n - 2].iter_mut().rev() {
        let s = x.clone();
        *x = z2.clone() * later - (z2.clone() * s_next + z.clone() * &s);
        later = next;
        next = x.clone();
        s_next = s;
    }
}

/// `c⁺_0 = Σ_{j<K} ξ^j s_{−j}`, the samples extended by `mode` (symmetric
/// or periodic), truncated at the horizon `K` and evaluated by Horner's
/// rule from the far end, `a ← s_{−j} + ξ a` for `j = K − 1, …, 0`: each
/// rounding is damped by `ξ^j` on its way to `c⁺_0`, so the sum carries
/// about `u |c⁺_0| / (1 − |ξ|)`, as one step of the recursion does. (Summed
/// from `j = 0` with running powers, every one of the `≈ K` additions rounds
/// at the full size of the sum: for a line shorter than the horizon,
/// folded back and forth, that was the largest error of the filter after
/// the gain's; `verify/tests/it/prefilter_rounding.rs` pins it.)
fn causal_start<T: Real>(c: &[T], z: &T, horizon: usize, mode: Mode) -> T {
    let n = c.len();
    let mut sum = T::zero();
    for j in (0..horizon.max(1)).rev() {
        let i = mode.fold(-(j as i64), n).unwrap_or(0);
        sum = c[i].clone() + z.clone() * sum;
    }
    sum
}

/// `c⁻_{ν−1}` of the mode (module documentation); grid-wrap's periodic sum
/// `−ξ Σ_{j<K} ξ^j c⁺_{(ν−1+j) mod ν}` by Horner's rule as [`causal_start`].
fn anticausal_start<T: Real>(c: &[T], z: &T, horizon: usize, mode: Mode) -> T {
    let n = c.len();
    let z = z.clone();
    match mode {
        Mode::Reflect => z.clone() / (z - T::one()) * c[n - 1].clone(),
        Mode::GridWrap => {
            let mut sum = T::zero();
            for j in (0..horizon.max(1)).rev() {
                sum = c[(n - 1 + j) % n].clone() + z.clone() * sum;
            }
            -z * sum
        }
        _ => z.clone() / (z.clone() * &z - T::one()) * (c[n - 1].clone() + z * c[n - 2].clone()),
    }
}

/// [`LineFilter::growth`] of a recursive filter.
fn growth_of<T: Real>(r: &RecursivePrefilter<T>) -> f64 {
    r.poles().iter().fold(r.gain().to_f64().abs(), |g, z| {
        g * (2.0 / (1.0 - z.to_f64().abs())).powi(2)
    })
}

/// The largest `d` in `lo..hi` with `holds(d)`, by bisection (assuming
/// `holds` is true up to some degree and false above it, as the growth of
/// the filters rises with the degree; what is returned holds in any case),
/// `None` where `holds(lo)` is false.
fn largest_true(lo: u32, hi: u32, holds: impl Fn(u32) -> bool) -> Option<u32> {
    if lo >= hi || !holds(lo) {
        return None;
    }
    let (mut good, mut bad) = (lo, hi);
    while bad - good > 1 {
        let mid = good + (bad - good) / 2;
        if holds(mid) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    Some(good)
}

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
/// hardware does not prefetch: [`PREFETCH_BYTES`]).
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
    /// one pole or a [`Cascade`], starts within a block, at least two
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

#[cfg(test)]
mod tests {
    use super::*;

    fn exact(order: u32, mode: Mode, cval: f64) -> LineFilter<f64> {
        LineFilter::new(&SplineFamily::Order(order), mode, cval, Route::Exact).unwrap()
    }

    /// Degree 199's growth bound overflows f64 along two axes whatever the
    /// data: the refusal names the degree 199, the axes, and a degree the
    /// data fits — one whose check passes while the next one's does not —
    /// and the MPFR route; never "scale the data below 0e0".
    #[test]
    fn a_degree_beyond_the_range_names_one_that_fits() {
        let e = exact(200, Mode::Mirror, 0.0)
            .check_magnitude(0.5, 2)
            .unwrap_err();
        let NdimageError::DegreeRange {
            degree: 199,
            axes: 2,
            bits: 53,
            fits: Some(d),
        } = e
        else {
            panic!("{e}");
        };
        assert!(
            exact(d + 1, Mode::Mirror, 0.0)
                .check_magnitude(0.5, 2)
                .is_ok()
        );
        assert!(
            exact(d + 2, Mode::Mirror, 0.0)
                .check_magnitude(0.5, 2)
                .is_err()
        );
        let message = e.to_string();
        assert!(
            message.contains(&format!("degree {d} and below fit float64"))
                && message.contains("--prec")
        );
        assert!(!message.contains("0e0"), "{message}");
    }

    /// `cval` counts towards the overflow check only under `grid-constant`,
    /// the one mode whose extension holds it (scipy's 'constant' filters
    /// with the mirror rule and puts `cval` outside, even infinite).
    #[test]
    fn cval_counts_only_where_the_mode_extends_by_it() {
        for mode in [Mode::Mirror, Mode::Reflect, Mode::GridWrap, Mode::Nearest] {
            assert!(
                exact(4, mode, f64::INFINITY)
                    .check_magnitude(1.0, 1)
                    .is_ok(),
                "{mode}"
            );
        }
        let e = exact(4, Mode::GridConstant, 1e308)
            .check_magnitude(1.0, 1)
            .unwrap_err();
        assert!(
            matches!(e, NdimageError::Overflow { max, .. } if max == 1e308),
            "{e}"
        );
    }

    /// The two poles' passes as one pass down and one up ([`Cascade`]:
    /// its starts derived from the symmetry of the result) against 128-bit
    /// MPFR running the one-line recursion pole after pole, column by
    /// column: degrees 4 and 5, every mode, lines of 3 samples (the
    /// fewest the cascade takes) to 41 and 300 (beyond every horizon),
    /// in f64 and f32, through [`LineFilter::apply_lines`] and
    /// [`LineFilter::apply_rows_from`]. Within `64 u A` of `max|s| = 1`
    /// (`A = 1/|V(−1)|`, the per-axis bound of `nd_prefilter`'s tests).
    #[test]
    fn cascade_of_two_poles_matches_mpfr_at_every_length() {
        cascade_matches_mpfr::<f64>();
        cascade_matches_mpfr::<f32>();
    }

    fn cascade_matches_mpfr<T: Real>() {
        use crate::scalar::Mp;
        type W = Mp<128>;
        let u = 2f64.powi(-(T::BITS as i32));
        let w = 5;
        for degree in [4u32, 5] {
            let family = SplineFamily::Order(degree + 1);
            for mode in Mode::ALL {
                let f = LineFilter::<T>::new(&family, mode, 0.25, Route::Exact).unwrap();
                assert!(f.cascade.is_some(), "degree {degree} has two poles");
                let wide = LineFilter::<W>::new(&family, mode, 0.25, Route::Exact).unwrap();
                let allowed = 64.0 * u * wide.recursive().amplification().to_f64();
                for n in (3..=41).chain([300]) {
                    let data: Vec<T> = (0..n * w)
                        .map(|i| T::from_f64_exact(((i * 7919) % 211) as f64 / 105.5 - 1.0))
                        .collect();
                    let mut lines = data.clone();
                    f.apply_lines(&mut lines, w, &mut Vec::new());
                    let mut rows = vec![T::zero(); n * w];
                    let src: Vec<&[T]> = data.chunks(w).collect();
                    let mut outs: Vec<&mut [T]> = rows.chunks_mut(w).collect();
                    f.apply_rows_from(
                        &src,
                        &mut outs,
                        &mut Vec::new(),
                        &mut Vec::new(),
                        &mut (),
                        n % 2 == 1,
                    );
                    for j in 0..w {
                        let mut line: Vec<W> = (0..n)
                            .map(|i| W::from_f64_exact(data[i * w + j].to_f64()))
                            .collect();
                        wide.apply(&mut line, &mut Vec::new());
                        for (i, want) in line.iter().enumerate() {
                            let want = want.to_f64();
                            for (route, got) in [("lines", &lines), ("rows", &rows)] {
                                let diff = (got[i * w + j].to_f64() - want).abs();
                                assert!(
                                    diff <= allowed,
                                    "{} bits degree {degree} {mode:?} n {n} {route} [{i}]: \
                                     {diff:e} > {allowed:e}",
                                    T::BITS
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// `apply_rows` (rows read and written in place, passes fused) against
    /// `apply_lines` (rows copied, one pass per operation): every mode and
    /// route, one to three poles, lines of 1 to 40 samples (shorter and
    /// longer than the horizons), rows of 1, 3 and 8 lines.
    #[test]
    fn rows_in_place_equal_apply_lines_bit_for_bit() {
        let modes = Mode::ALL;
        for degree in [1u32, 2, 3, 5, 7] {
            let family = SplineFamily::Order(degree + 1);
            for mode in modes {
                for route in [
                    Route::Exact,
                    Route::Truncated { tol: 1e-9 },
                    Route::Convolution { tol: 1e-9 },
                ] {
                    let f = LineFilter::<f64>::new(&family, mode, 0.5, route).unwrap();
                    for (n, w) in [(1, 3), (2, 1), (3, 8), (7, 3), (40, 8)] {
                        let data: Vec<f64> = (0..n * w)
                            .map(|i| ((i * 7919) % 211) as f64 / 97.0 - 1.0)
                            .collect();
                        let mut want = data.clone();
                        f.apply_lines(&mut want, w, &mut Vec::new());
                        let mut got = data.clone();
                        let mut rows: Vec<&mut [f64]> = got.chunks_mut(w).collect();
                        f.apply_rows(&mut rows, &mut Vec::new(), &mut Vec::new());
                        assert!(
                            got.iter()
                                .zip(&want)
                                .all(|(a, b)| a.to_bits() == b.to_bits()),
                            "degree {degree} {mode:?} {route:?} n {n} w {w}"
                        );
                    }
                }
            }
        }
    }

    /// Rows filtered in blocks ([`LineFilter::filter_in_blocks`])
    /// equal the whole-strip buffer ([`LineFilter::apply_rows`],
    /// `apply_rows_from`) bit for bit: degrees 2–5 (one pole; two: the
    /// cascade), mirror and reflect, f64 and f32, lines of 256 to 1001 rows
    /// (blocks of unequal length, a last block of ≥ 3 rows), rows of 1 to
    /// 17 values, in place and from a copy (scanned rows: the same maxima);
    /// f32 samples and rows of an f64 filter equal the rows widened,
    /// filtered in f64 and rounded once.
    #[test]
    fn rows_in_blocks_equal_the_whole_buffer_bit_for_bit() {
        rows_in_blocks::<f64>();
        rows_in_blocks::<f32>();
        for degree in [2u32, 3, 5] {
            let f = LineFilter::<f64>::new(
                &SplineFamily::Order(degree + 1),
                Mode::Mirror,
                0.0,
                Route::Exact,
            )
            .unwrap();
            let (n, w) = (700, 9);
            let data: Vec<f32> = (0..n * w)
                .map(|i| ((i * 7919) % 211) as f32 / 97.0 - 1.0)
                .collect();
            let mut wide: Vec<f64> = data.iter().map(|&x| x as f64).collect();
            let mut rows: Vec<&mut [f64]> = wide.chunks_mut(w).collect();
            f.apply_rows(&mut rows, &mut Vec::new(), &mut Vec::new());
            let want: Vec<f32> = wide.iter().map(|&x| x as f32).collect();
            // From f32 samples into f32 rows, and in place in f32 rows.
            let mut got = vec![0f32; n * w];
            let src: Vec<&[f32]> = data.chunks(w).collect();
            let mut rows: Vec<&mut [f32]> = got.chunks_mut(w).collect();
            assert!(blocks(
                &f,
                Some(&src),
                &mut rows,
                &mut RowBlocks::default(),
                &mut (),
                false
            ));
            assert_eq!(got, want, "degree {degree} from f32");
            let mut got = data.clone();
            let mut rows: Vec<&mut [f32]> = got.chunks_mut(w).collect();
            assert!(blocks::<_, f32, f32, ()>(
                &f,
                None,
                &mut rows,
                &mut RowBlocks::default(),
                &mut (),
                false
            ));
            assert_eq!(got, want, "degree {degree} in place f32");
        }
    }

    fn rows_in_blocks<T: Real>() {
        for degree in [2u32, 3, 4, 5] {
            let family = SplineFamily::Order(degree + 1);
            for mode in [Mode::Mirror, Mode::Reflect] {
                let f = LineFilter::<T>::new(&family, mode, 0.0, Route::Exact).unwrap();
                for (n, w) in [(256, 1), (257, 17), (300, 8), (1001, 5)] {
                    let data: Vec<T> = (0..n * w)
                        .map(|i| T::from_f64_exact(((i * 7919) % 211) as f64 / 97.0 - 1.0))
                        .collect();
                    let mut want = data.clone();
                    let mut rows: Vec<&mut [T]> = want.chunks_mut(w).collect();
                    f.apply_rows(&mut rows, &mut Vec::new(), &mut Vec::new());
                    let bits = |v: &[T]| v.iter().map(|x| x.to_f64().to_bits()).collect::<Vec<_>>();
                    let mut got = data.clone();
                    let mut rows: Vec<&mut [T]> = got.chunks_mut(w).collect();
                    let mut work = RowBlocks::default();
                    assert!(blocks::<_, T, T, ()>(
                        &f,
                        None,
                        &mut rows,
                        &mut work,
                        &mut (),
                        false
                    ));
                    assert_eq!(
                        bits(&got),
                        bits(&want),
                        "degree {degree} {mode:?} n {n} w {w} in place"
                    );
                    for stream in [false, true] {
                        let mut got = vec![T::zero(); n * w];
                        let src: Vec<&[T]> = data.chunks(w).collect();
                        let mut rows: Vec<&mut [T]> = got.chunks_mut(w).collect();
                        let mut seen = MaxSeen::default();
                        assert!(blocks(
                            &f,
                            Some(&src),
                            &mut rows,
                            &mut work,
                            &mut seen,
                            stream
                        ));
                        assert_eq!(
                            bits(&got),
                            bits(&want),
                            "degree {degree} {mode:?} n {n} w {w} from src"
                        );
                        assert_eq!(seen.rows, n, "each sample row seen once");
                    }
                }
                // Too few rows for blocks: refused, nothing written.
                let mut short = vec![T::one(); 100];
                let mut rows: Vec<&mut [T]> = short.chunks_mut(1).collect();
                assert!(!blocks::<_, T, T, ()>(
                    &f,
                    None,
                    &mut rows,
                    &mut RowBlocks::default(),
                    &mut (),
                    false
                ));
                assert!(short.iter().all(|x| *x == T::one()));
            }
        }
    }

    /// [`LineFilter::filter_in_blocks`] on the rows of a strip.
    fn blocks<T: Real, E: Sample<T>, O: Sample<T> + Stored<T>, F: RowCheck>(
        f: &LineFilter<T>,
        src: Option<&[&[E]]>,
        rows: &mut [&mut [O]],
        work: &mut RowBlocks<T>,
        seen: &mut F,
        stream: bool,
    ) -> bool {
        f.filter_in_blocks(
            &mut StripRows {
                src,
                rows,
                seen,
                stream,
            },
            work,
        )
    }

    /// Counts the rows a pass takes in.
    #[derive(Default)]
    struct MaxSeen {
        rows: usize,
    }

    impl RowCheck for MaxSeen {
        fn row<U: Real>(&mut self, _: &[U]) {
            self.rows += 1;
        }
    }

    /// The rows written by streaming stores (`apply_rows_from` with
    /// `stream`) equal [`LineFilter::apply_lines`] bit for bit: f64 and
    /// f32, degrees 3 and 5 (one pole; two: the cascade) and 2, every mode,
    /// rows of 1 to 70 values (heads, whole 64-byte lines and tails) at
    /// offsets that leave them unaligned, 2 to 40 rows.
    #[test]
    fn streamed_rows_equal_apply_lines_bit_for_bit() {
        streamed_rows::<f64>();
        streamed_rows::<f32>();
    }

    fn streamed_rows<T: Real>() {
        for degree in [2u32, 3, 5] {
            let family = SplineFamily::Order(degree + 1);
            for mode in Mode::ALL {
                let f = LineFilter::<T>::new(&family, mode, 0.5, Route::Exact).unwrap();
                for (n, w, off) in [(2, 1, 0), (3, 17, 1), (7, 8, 3), (40, 24, 2), (40, 70, 5)] {
                    let data: Vec<T> = (0..n * w)
                        .map(|i| T::from_f64_exact(((i * 7919) % 211) as f64 / 97.0 - 1.0))
                        .collect();
                    let mut want = data.clone();
                    f.apply_lines(&mut want, w, &mut Vec::new());
                    let mut out = vec![T::zero(); off + n * w];
                    let mut rows: Vec<&mut [T]> = out[off..].chunks_mut(w).collect();
                    let src: Vec<&[T]> = data.chunks(w).collect();
                    f.apply_rows_from(
                        &src,
                        &mut rows,
                        &mut Vec::new(),
                        &mut Vec::new(),
                        &mut (),
                        true,
                    );
                    let bits = |x: &T| x.to_f64().to_bits();
                    assert!(
                        out[off..]
                            .iter()
                            .zip(&want)
                            .all(|(a, b)| bits(a) == bits(b)),
                        "{} bits degree {degree} {mode:?} n {n} w {w}",
                        T::BITS
                    );
                }
            }
        }
    }
}
