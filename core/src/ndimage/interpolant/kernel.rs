//! Fixed-size evaluation kernels: [`Interpolant::eval_many`] and
//! [`Interpolant::resample_affine`] for 1 to 3 dimensions and degrees 0 to
//! 5 (scipy's range) at `f64`/`f32` precision, with the dimension `D` and
//! the order `M = degree + 1` known to the compiler.
//!
//! Degree 0 (`M = 1`, nearest sample): inside `[0, n − 1]` the sample
//! [`Mode::nearest_index`](crate::ndimage::mode::Mode::nearest_index)
//! picks is `⌊x⌋ + [x − ⌊x⌋ ≥ ½]`, which is [`cell_lanes`]`::<1>` (every
//! mode's fold is the identity there), weight 1; a point outside the grid
//! on some axis is not folded here (scipy folds order-0 points by its own
//! rule, which the coordinate fold of higher orders is not) but evaluated
//! by the general [`Interpolant::eval_in`], so the rounding stays
//! `nearest_index`'s bit for bit.
//!
//! Why: the general path ([`Interpolant::locate`],
//! [`Interpolant::tensor_sum`]) loops over run-time `ndim` and `m` with
//! slices of weights, so every point pays loop control, bounds checks and
//! a call per axis; here the weights of a point are `[[T; M]; D]` on the
//! stack, the closed-form weights (`weights.rs`) are inlined,
//! and each row of `M` coefficients is one bounds check. A point whose
//! coordinate lies inside `[0, n − 1]` is not folded (every mode's fold is
//! the identity there).
//!
//! **Same values**: the weights are those of every other path
//! ([`cell_weights_into`](super::cell_weights_into): closed forms for
//! degrees 1 to 5, `weights.rs`, in `f64`), and the sums are added in the
//! order of [`Interpolant::tensor_sum`], so in `f64` the results are those
//! of the general path and of [`Interpolant::eval`] bit for bit
//! (`verify/tests/it/engine_batch.rs::batch_equals_single_point_evaluation`).
//! In `f32` the weights are rounded once from `f64`, as there.

use super::batch::{BATCH, PointSource, prefetch};
use super::weights::closed_form;
use super::{Interpolant, Scratch};
use crate::ndimage::NdimageError;
use crate::scalar::Real;
use crate::sspline::bspline_uniform::centred_cell;
use multiversion::multiversion;

/// Below this magnitude [`cell_lanes`] rounds exactly (`1.5 · 2^52` added
/// and subtracted rounds to an integer while `|x| < 2^51`).
const LANE_CELL_LIMIT: f64 = (1u64 << 51) as f64;

/// [`centred_cell`] for order `M` as `(first, u)` with `first` an integer
/// in `f64`, the same values for `|x| < 2^51`, branch-free so that a loop
/// of them runs in SIMD lanes (no call to libm's `floor`, not inlined on
/// the x86-64 baseline): `⌊x⌋` is `x` rounded to an integer by adding and
/// subtracting `1.5 · 2^52`, less one where that exceeds `x`; then `t = x −
/// ⌊x⌋` is exact, and odd orders take the cell centred on the half-integer.
#[inline(always)]
fn cell_lanes<const M: usize>(x: f64) -> (f64, f64) {
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let r = (x + ROUND) - ROUND;
    let fl = if r > x { r - 1.0 } else { r };
    let t = x - fl;
    // first = ⌊x⌋ + ⌊M/2⌋ − M + 1 (+ 1 for an odd order past the half).
    let lead = (M / 2) as f64 + 1.0 - M as f64;
    if M.is_multiple_of(2) {
        (fl + lead, t)
    } else {
        let past = t >= 0.5;
        let first = fl + lead + if past { 1.0 } else { 0.0 };
        (first, if past { t - 0.5 } else { t + 0.5 })
    }
}

/// The most rows a batch may prefetch a whole batch ahead of its sums
/// ([`Interpolant::eval_fixed`]): 512 rows of at most 48 bytes stay within
/// the 48 KiB L1 of Zen 4 / 5 until they are read. Above it (3-D cubics:
/// 1024 rows) a batch is summed right after it is located: one batch ahead,
/// map_coordinates 128³ cubic took 65.5 ms against 60.5 (one thread,
/// min of 15 alternated), 2-D cubics and quintics gain.
const AHEAD_ROWS: usize = 512;

/// Whether every coordinate lies in `[0, high]` (a branch-free pass, in
/// lanes; a NaN does not).
#[inline(always)]
fn within(x: &[f64], high: f64) -> bool {
    x.iter().fold(true, |ok, &t| ok & (t >= 0.0) & (t <= high))
}

/// The cells ([`cell_lanes`]) and closed-form weights
/// ([`closed_form`](super::weights::closed_form)) of a batch of folded
/// coordinates on one axis: `first[j]`, `w[l][j] = β(x_j − first_j − l)`.
/// One branch-free loop over the points, compiled for AVX-512 and for
/// AVX2 + FMA besides the baseline and chosen at run time by the CPU's
/// features (`multiversion`): the points run in 8, 4 or 2 lanes. The
/// arithmetic is the same IEEE operations in every version (no
/// contraction into fused multiply-adds), so every version gives the same
/// bits. Coordinates of `2^51` or more are redone by the caller.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma"))]
pub(super) fn cells_and_weights<T: Real, const M: usize>(
    x: &[f64; BATCH],
    first: &mut [f64; BATCH],
    w: &mut [[T; BATCH]; M],
) {
    for j in 0..BATCH {
        let (f, u) = cell_lanes::<M>(x[j]);
        first[j] = f;
        let c = closed_form::<M>(u).expect("kernels serve orders 1 to 6");
        for l in 0..M {
            w[l][j] = T::from_f64_exact(c[l]);
        }
    }
}

/// The flat offsets `Σ_a (firsts[a][j] + pad) · strides[a]` of a batch's
/// windows into `bases`, in lanes, and whether every window starts inside
/// `[0, top_a]` on every axis (else `bases` is not to be used). Exact: the
/// cells are integers in `f64`, and the offsets integers below `2^53`.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma"))]
pub(super) fn bases_in_lanes<const D: usize>(
    firsts: &[[f64; BATCH]; D],
    pad: f64,
    top: &[f64; D],
    strides: &[f64; D],
    bases: &mut [usize; BATCH],
) -> bool {
    let mut inside = true;
    for (j, base) in bases.iter_mut().enumerate() {
        let mut flat = 0.0;
        for a in 0..D {
            let i0 = firsts[a][j] + pad;
            inside &= (i0 >= 0.0) & (i0 <= top[a]);
            flat += i0 * strides[a];
        }
        *base = flat as usize;
    }
    inside
}

/// The lanes of one batch on `D` axes: coordinates, folded coordinates,
/// first window indices (integers in `f64`), whether each point takes
/// `cval`, and the flat offsets of the windows.
struct Lanes<const D: usize> {
    xs: [[f64; BATCH]; D],
    folded: [[f64; BATCH]; D],
    firsts: [[f64; BATCH]; D],
    take_cval: [bool; BATCH],
    flat: [usize; BATCH],
}

impl<const D: usize> Lanes<D> {
    fn new() -> Self {
        Lanes {
            xs: [[0.0; BATCH]; D],
            folded: [[0.0; BATCH]; D],
            firsts: [[0.0; BATCH]; D],
            take_cval: [false; BATCH],
            flat: [0; BATCH],
        }
    }
}

/// A located batch: the weights `[axis][l][point]` and the flat offset of
/// each point's window (`None`: its value is already written).
struct Located<T, const D: usize, const M: usize> {
    ws: [[[T; BATCH]; M]; D],
    bases: [Option<usize>; BATCH],
}

impl<T: Real, const D: usize, const M: usize> Located<T, D, M> {
    fn new() -> Self {
        Located {
            ws: std::array::from_fn(|_| {
                std::array::from_fn(|_| std::array::from_fn(|_| T::zero()))
            }),
            bases: [None; BATCH],
        }
    }

    /// The tensor sums of the located points into `out` ([`sum_fixed`]).
    #[inline(always)]
    fn sum(&self, c: &[T], out: &mut [T], strides: &[usize]) {
        for (j, (o, base)) in out.iter_mut().zip(&self.bases).enumerate() {
            if let Some(base) = *base {
                *o = sum_fixed::<T, D, M>(c, base, &self.ws, j, strides);
            }
        }
    }
}

impl<T: Real + Send + Sync> Interpolant<T> {
    /// Whether a fixed-size kernel serves this interpolant: `f64`/`f32`
    /// precision, 1 to 3 dimensions, degree 0 to 5.
    pub(super) fn has_kernel(&self) -> bool {
        T::FITS_F64 && (1..=3).contains(&self.ndim()) && (1..=6).contains(&self.order)
    }

    /// The points `start..start + out.len()` of `src` into `out` by the
    /// fixed-size kernel of this interpolant's dimension and order (call
    /// only when [`Self::has_kernel`]).
    pub(super) fn eval_kernel<S: PointSource>(
        &self,
        src: &S,
        start: usize,
        out: &mut [T],
    ) -> Result<(), NdimageError> {
        if const { !T::FITS_F64 } {
            // Never taken (`has_kernel`): keeps the 15 fixed-size clones
            // out of wider MPFR builds (`Real::FITS_F64`).
            return self.eval_chunk(src, start, out);
        }
        macro_rules! by_order {
            ($d:literal) => {
                match self.order {
                    1 => self.eval_fixed::<S, $d, 1>(src, start, out),
                    2 => self.eval_fixed::<S, $d, 2>(src, start, out),
                    3 => self.eval_fixed::<S, $d, 3>(src, start, out),
                    4 => self.eval_fixed::<S, $d, 4>(src, start, out),
                    5 => self.eval_fixed::<S, $d, 5>(src, start, out),
                    _ => self.eval_fixed::<S, $d, 6>(src, start, out),
                }
            };
        }
        match self.ndim() {
            1 => by_order!(1),
            2 => by_order!(2),
            _ => by_order!(3),
        }
    }

    /// [`Self::eval_kernel`] for dimension `D` and order `M`, in batches of
    /// [`BATCH`] points, two stages apart: each batch is located
    /// ([`Self::locate_batch`]: its rows prefetched) before the previous one
    /// is summed ([`Located::sum`]), so that a point's rows are on their way
    /// a whole batch before they are read (up to [`AHEAD_ROWS`] rows a
    /// batch; above, each batch is summed as soon as it is located). The
    /// sums are those of the points one by one (only their interleaving
    /// changes), so the same bits.
    fn eval_fixed<S: PointSource, const D: usize, const M: usize>(
        &self,
        src: &S,
        start: usize,
        out: &mut [T],
    ) -> Result<(), NdimageError> {
        let c = self.coeffs.as_slice().expect("standard layout");
        let mut lanes = Lanes::<D>::new();
        let (mut a, mut b) = (Located::<T, D, M>::new(), Located::<T, D, M>::new());
        let (mut current, mut previous) = (&mut a, &mut b);
        let mut pending: Option<&mut [T]> = None;
        let mut fallback = None;
        for (k, batch) in out.chunks_mut(BATCH).enumerate() {
            self.locate_batch(
                src,
                start + k * BATCH,
                batch,
                &mut lanes,
                current,
                &mut fallback,
            )?;
            if M.pow(D as u32 - 1) * BATCH > AHEAD_ROWS {
                current.sum(c, batch, &self.strides);
                continue;
            }
            if let Some(done) = pending.take() {
                previous.sum(c, done, &self.strides);
            }
            std::mem::swap(&mut current, &mut previous);
            pending = Some(batch);
        }
        if let Some(done) = pending {
            previous.sum(c, done, &self.strides);
        }
        Ok(())
    }

    /// The points `start..start + out.len()` of `src` (at most [`BATCH`])
    /// located into `at`: folded, their cells and weights formed axis by
    /// axis with the points in SIMD lanes ([`cells_and_weights`]), the flat
    /// offsets of their windows (in lanes for a full batch inside the
    /// padded coefficients, [`bases_in_lanes`]; else point by point,
    /// [`Self::base_fixed`]) and their rows prefetched. A point that takes
    /// `cval`, or whose window leaves the padded coefficients
    /// (`grid-constant` far outside: the general [`Interpolant::eval_in`]),
    /// is written to `out` here and not located.
    fn locate_batch<S: PointSource, const D: usize, const M: usize>(
        &self,
        src: &S,
        start: usize,
        out: &mut [T],
        lanes: &mut Lanes<D>,
        at: &mut Located<T, D, M>,
        fallback: &mut Option<(Vec<T>, Vec<usize>, Vec<bool>)>,
    ) -> Result<(), NdimageError> {
        let c = self.coeffs.as_slice().expect("standard layout");
        let n = out.len();
        let Lanes {
            xs,
            folded,
            firsts,
            take_cval,
            flat,
        } = lanes;
        src.fill_lanes(start, xs, &mut take_cval[..n])?;
        let plain = !take_cval[..n].iter().any(|&cv| cv);
        let mut inside = plain;
        for (a, f) in folded.iter_mut().enumerate() {
            let high = (self.shape[a] - 1) as f64;
            if plain && within(&xs[a][..n], high) {
                // Every mode's fold is the identity inside the grid.
                *f = xs[a];
                continue;
            }
            inside = false;
            for j in 0..n {
                // A point that takes cval is not located (no fold); degree
                // 0 is not folded either ([`Self::base_fixed`] declines a
                // point outside, module documentation).
                f[j] = match (take_cval[j], M) {
                    (true, _) => 0.0,
                    (false, 1) => xs[a][j],
                    (false, _) => self.fold_fixed(xs[a][j], a),
                };
            }
        }
        for a in 0..D {
            cells_and_weights::<T, M>(&folded[a], &mut firsts[a], &mut at.ws[a]);
        }
        let (pad, top, strides) = self.lane_bounds::<D, M>();
        let lanes_serve = plain && (M > 1 || inside);
        if lanes_serve && n == BATCH && bases_in_lanes(firsts, pad, &top, &strides, flat) {
            for (base, &f) in at.bases.iter_mut().zip(flat.iter()) {
                self.prefetch_fixed::<D, M>(c, f);
                *base = Some(f);
            }
            return Ok(());
        }
        for (j, o) in out.iter_mut().enumerate() {
            at.bases[j] = None;
            if take_cval[j] {
                *o = self.cval.clone();
                continue;
            }
            at.bases[j] = self.base_fixed::<D, M>(folded, firsts, &mut at.ws, j);
            if let Some(base) = at.bases[j] {
                self.prefetch_fixed::<D, M>(c, base);
            } else {
                let x: [f64; D] = std::array::from_fn(|a| xs[a][j]);
                *o = self.eval_slow(&x, fallback);
            }
        }
        Ok(())
    }

    /// The pad, the last start of a window on each axis and the strides, in
    /// `f64` for [`bases_in_lanes`] (flat offsets are integers far below
    /// `2^53`).
    pub(super) fn lane_bounds<const D: usize, const M: usize>(&self) -> (f64, [f64; D], [f64; D]) {
        let top = std::array::from_fn(|a| (self.shape[a] + 2 * self.pad - M) as f64);
        let strides = std::array::from_fn(|a| self.strides[a] as f64);
        (self.pad as f64, top, strides)
    }

    /// The general single-point evaluation, its work space made on first use.
    pub(super) fn eval_slow(
        &self,
        x: &[f64],
        space: &mut Option<(Vec<T>, Vec<usize>, Vec<bool>)>,
    ) -> T {
        let (w, off, inside) = space.get_or_insert_with(|| self.scratch());
        let zero = [0; 3];
        let mut sc = Scratch { w, off, inside };
        self.eval_in(x, &zero[..x.len()], &mut sc)
    }

    /// The point at which axis `a` is evaluated: `x` itself inside `[0,
    /// n − 1]` (every mode's fold is the identity there), else
    /// [`Interpolant::coordinate`].
    #[inline(always)]
    fn fold_fixed(&self, x: f64, a: usize) -> f64 {
        if x >= 0.0 && x <= (self.shape[a] - 1) as f64 {
            x
        } else {
            self.coordinate(x, a)
        }
    }

    /// The flat offset of the first coefficient of point `j` of a batch
    /// (its cells in `firsts`), or `None` when its window leaves the padded
    /// coefficients, or at degree 0 (`M = 1`) when the point lies outside
    /// `[0, n − 1]` on some axis (module documentation). A coordinate of
    /// `2^51` or more in magnitude, beyond
    /// [`cells_and_weights`]' rounding, gets its cell and weights here from
    /// [`centred_cell`].
    #[inline(always)]
    pub(super) fn base_fixed<const D: usize, const M: usize>(
        &self,
        folded: &[[f64; BATCH]; D],
        firsts: &mut [[f64; BATCH]; D],
        ws: &mut [[[T; BATCH]; M]; D],
        j: usize,
    ) -> Option<usize> {
        let mut base = 0;
        for a in 0..D {
            let x = folded[a][j];
            if M == 1 && !(x >= 0.0 && x <= (self.shape[a] - 1) as f64) {
                return None;
            }
            if folded[a][j].abs() >= LANE_CELL_LIMIT {
                let (first, u) = centred_cell(M as u32, folded[a][j]);
                firsts[a][j] = first as f64;
                let f = closed_form::<M>(u).expect("kernels serve orders 1 to 6");
                for (l, v) in f.into_iter().enumerate() {
                    ws[a][l][j] = T::from_f64_exact(v);
                }
            }
            let i0 = firsts[a][j] as i64 + self.pad as i64;
            if i0 < 0 || i0 as usize + M > self.shape[a] + 2 * self.pad {
                return None;
            }
            base += i0 as usize * self.strides[a];
        }
        Some(base)
    }

    /// Prefetch the `M^{D−1}` rows of a located point.
    #[inline(always)]
    fn prefetch_fixed<const D: usize, const M: usize>(&self, c: &[T], base: usize) {
        match D {
            1 => prefetch(c, base, M),
            2 => (0..M).for_each(|l0| prefetch(c, base + l0 * self.strides[0], M)),
            _ => {
                for l0 in 0..M {
                    for l1 in 0..M {
                        prefetch(c, base + l0 * self.strides[0] + l1 * self.strides[1], M);
                    }
                }
            }
        }
    }
}

/// `Σ_l w[l][j] · row[l]` over one row of `M` coefficients, from zero
/// (`w` by order index, point `j` of the batch).
#[inline(always)]
fn dot<T: Real, const M: usize>(w: &[[T; BATCH]; M], j: usize, row: &[T]) -> T {
    let row: &[T; M] = row[..M].try_into().expect("M coefficients");
    let mut sum = T::zero();
    for l in 0..M {
        sum += w[l][j].clone() * &row[l];
    }
    sum
}

/// The tensor sum of located point `j` of a batch (weights `w[axis][l][j]`),
/// in the order of [`Interpolant::tensor_sum`]: rows of the last axis
/// dotted, then weighted by the middle axis, then by the first.
#[inline(always)]
pub(super) fn sum_fixed<T: Real, const D: usize, const M: usize>(
    c: &[T],
    base: usize,
    w: &[[[T; BATCH]; M]; D],
    j: usize,
    strides: &[usize],
) -> T {
    // A slice, so that the arms of the other dimensions index it without
    // constant out-of-bounds indices.
    let w: &[[[T; BATCH]; M]] = w;
    match D {
        1 => dot(&w[0], j, &c[base..]),
        2 => {
            let mut sum = T::zero();
            for l0 in 0..M {
                let at = base + l0 * strides[0];
                sum += w[0][l0][j].clone() * dot(&w[1], j, &c[at..]);
            }
            sum
        }
        _ => {
            let mut sum = T::zero();
            for l0 in 0..M {
                let mut plane = T::zero();
                for l1 in 0..M {
                    let at = base + l0 * strides[0] + l1 * strides[1];
                    plane += w[1][l1][j].clone() * dot(&w[2], j, &c[at..]);
                }
                sum += w[0][l0][j].clone() * plane;
            }
            sum
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The branch-free cell of the lanes equals [`centred_cell`] (floor by
    /// libm) for every order, at integers, half-integers, their floating
    /// neighbours, negative and tiny coordinates and up to just below
    /// [`LANE_CELL_LIMIT`].
    #[test]
    fn lane_cells_equal_centred_cells() {
        let mut xs = vec![0.0, -0.0, 1e-300, -1e-300, 0.5, -0.5, 2.5, -3.5, 7.0, -7.0];
        for x in [0.5f64, 1.0, 2.5, 1e6 + 0.5, 1e15, (LANE_CELL_LIMIT) - 1.5] {
            for s in [1.0, -1.0] {
                let x = s * x;
                xs.extend([
                    x,
                    f64::from_bits(x.to_bits() + 1),
                    f64::from_bits(x.to_bits() - 1),
                ]);
            }
        }
        fn check<const M: usize>(xs: &[f64]) {
            for &x in xs {
                let (first, u) = centred_cell(M as u32, x);
                let (lane_first, lane_u) = cell_lanes::<M>(x);
                assert_eq!(
                    (first as f64, u),
                    (lane_first, lane_u),
                    "order {M} at {x:e}"
                );
            }
        }
        check::<1>(&xs);
        check::<2>(&xs);
        check::<3>(&xs);
        check::<4>(&xs);
        check::<5>(&xs);
        check::<6>(&xs);
    }
}

/// Degree 0 through the fixed kernels against the rule it must keep:
/// the sample [`Mode::nearest_index`](crate::ndimage::mode::Mode::nearest_index)
/// names, read from the samples themselves (not the padded coefficients),
/// `cval` where it names none.
#[cfg(test)]
mod degree_0 {
    use crate::ndimage::interpolant::{Interpolant, Options, PointRule};
    use crate::ndimage::mode::Mode;
    use ndarray::{Array2, ArrayD, Dimension, IxDyn};
    use proptest::prelude::*;

    const CVAL: f64 = 0.625;

    /// `x` moved by `steps` representable values (up for positive).
    fn nudge(mut x: f64, steps: i32) -> f64 {
        for _ in 0..steps.unsigned_abs() {
            x = if steps > 0 {
                x.next_up()
            } else {
                x.next_down()
            };
        }
        x
    }

    /// The value scipy's order 0 gives at `x` (outside points by the mode's
    /// own rule, `nearest_index`), from the samples.
    fn nearest(data: &ArrayD<f64>, mode: Mode, x: &[f64]) -> f64 {
        let k: Option<Vec<usize>> = x
            .iter()
            .zip(data.shape())
            .map(|(&t, &n)| mode.nearest_index(t, n))
            .collect();
        k.map_or(CVAL, |k| data[IxDyn(&k)])
    }

    fn data(shape: &[usize]) -> ArrayD<f64> {
        ArrayD::from_shape_fn(IxDyn(shape), |ix| {
            let k = ix.slice().iter().fold(5, |k, &i| k * 31 + i * 7);
            (k % 97) as f64 / 8.0 - 6.0
        })
    }

    fn interpolant(data: &ArrayD<f64>, mode: Mode) -> Interpolant<f64> {
        let mut opts = Options::new(0, mode);
        opts.cval = CVAL;
        Interpolant::new(data, opts).unwrap()
    }

    proptest! {
        /// Points at half-integers and a few ulps beside them (the ties and
        /// their neighbours), inside and outside the grid, 1 to 3
        /// dimensions, every mode: `eval_many` (batches of 64, lanes and
        /// single points) equals the rule exactly.
        #[test]
        fn eval_many_takes_the_nearest_index_sample(
            shape in proptest::collection::vec(1usize..8, 1..=3),
            mode in proptest::sample::select(Mode::ALL.to_vec()),
            ticks in proptest::collection::vec((-14i32..30, -2i32..=2), 3..600),
        ) {
            let d = shape.len();
            let a = data(&shape);
            let f = interpolant(&a, mode);
            let count = ticks.len() / d;
            let pts = Array2::from_shape_fn((count, d), |(p, h)| {
                let (k, s) = ticks[p * d + h];
                nudge(f64::from(k) * 0.5, s)
            });
            let mut out = vec![0.0; count];
            f.eval_many(pts.view(), &mut out).unwrap();
            for (p, got) in out.iter().enumerate() {
                let x = pts.row(p).to_vec();
                prop_assert_eq!(*got, nearest(&a, mode, &x), "{:?} {:?} at {:?}", shape, mode, x);
            }
        }

        /// The affine route (runs inside the grid, the batch path or `cval`
        /// outside) with half-integer steps from a half-integer offset, a
        /// few ulps off: every output equals the rule (scipy's `constant`,
        /// `CvalOutside`: `cval` outside `[0, n − 1]`).
        #[test]
        fn affine_runs_take_the_nearest_index_sample(
            n0 in 1usize..12,
            n1 in 1usize..12,
            mode in proptest::sample::select(Mode::ALL.to_vec()),
            off in (-10i32..10, -10i32..10, -2i32..=2),
            flip in any::<bool>(),
            cval_outside in any::<bool>(),
        ) {
            let a = data(&[n0, n1]);
            let f = interpolant(&a, mode);
            let s = if flip { -0.5 } else { 0.5 };
            let matrix = [0.5, 0.0, 0.0, s];
            let offset = [nudge(f64::from(off.0) * 0.5, off.2), f64::from(off.1) * 0.5];
            let (rule, shape) = (
                if cval_outside { PointRule::CvalOutside } else { PointRule::Fold },
                [2 * n0 + 9, 2 * n1 + 70],
            );
            let mut out = vec![0.0; shape[0] * shape[1]];
            f.resample_affine(&matrix, &offset, &shape, 0.0, rule, &mut out).unwrap();
            for (k, got) in out.iter().enumerate() {
                let (i, j) = (k / shape[1], k % shape[1]);
                let x = [offset[0] + i as f64 * 0.5, offset[1] + j as f64 * s];
                let outside = x.iter().zip([n0, n1]).any(|(&t, n)| t < 0.0 || t > (n - 1) as f64);
                let want = if cval_outside && outside { CVAL } else { nearest(&a, mode, &x) };
                prop_assert_eq!(*got, want, "{:?} at {:?}", mode, x);
            }
        }
    }
}
