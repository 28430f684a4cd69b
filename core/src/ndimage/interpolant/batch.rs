//! Batch evaluation of an [`Interpolant`] at many points
//! ([`Interpolant::eval_many`]): the same sums as [`Interpolant::eval`]
//! (weights of degrees 1 to 5 in closed form, see [`cell_weights_into`]), arranged so
//! that the coefficient reads of many points overlap.
//!
//! Why: for a grid of a few megabytes and scattered points each point reads
//! `m^{D−1}` rows of `m` coefficients that are in no cache, so the time per
//! point is memory latency, not arithmetic. The points are taken in batches:
//! first every point of the batch is located (cell, weights, flat offset)
//! and its rows are prefetched, then the sums run on rows that are already
//! on their way (the fixed-size kernels of `kernel.rs` sum a batch only
//! after the next one is located, so every point's rows have a batch's
//! time to arrive). The points are checked finite batch by batch as they
//! are read (no separate pass over them). Results are bit-identical to the
//! unbatched order (the prefetch is only a hint).

use super::{Interpolant, PointRule, Scratch, cell_weights_into};
use crate::ndimage::NdimageError;
use crate::ndimage::samples::Stored;
use crate::scalar::Real;
use crate::sspline::bspline_uniform::centred_cell;
use ndarray::{ArrayView2, Axis, s};
use rayon::prelude::*;

/// Points per parallel task (one work space each).
pub(super) const CHUNK: usize = 2048;
/// Points located (and prefetched) before their sums are formed: 64
/// measured fastest of 16, 32, 64 and 128 on map_coordinates (figures in
/// the commit that set it; `python/bench/map_coordinates.py` remeasures).
pub(super) const BATCH: usize = 64;

/// Where the points of a batch evaluation come from: an array of points
/// ([`Interpolant::eval_many`]) or points generated where they are
/// evaluated ([`Interpolant::resample_affine`]).
pub(super) trait PointSource: Sync {
    /// The coordinates of points `start..start + take_cval.len()` into
    /// `xs` (`ndim` per point, in order), and whether each takes `cval`
    /// without evaluation; an error for a non-finite coordinate.
    fn fill(
        &self,
        start: usize,
        xs: &mut [f64],
        take_cval: &mut [bool],
    ) -> Result<(), NdimageError>;

    /// [`Self::fill`] by axis into SIMD lanes: coordinate `a` of point
    /// `start + j` into `xs[a][j]` (`D ≤ 3` axes, `take_cval.len()` points),
    /// for the fixed-size kernels. By default [`Self::fill`], transposed.
    fn fill_lanes<const D: usize>(
        &self,
        start: usize,
        xs: &mut [[f64; BATCH]; D],
        take_cval: &mut [bool],
    ) -> Result<(), NdimageError> {
        let n = take_cval.len();
        let mut flat = [0.0; BATCH * 3];
        self.fill(start, &mut flat[..n * D], take_cval)?;
        for (j, x) in flat[..n * D].chunks_exact(D).enumerate() {
            for (a, &v) in x.iter().enumerate() {
                xs[a][j] = v;
            }
        }
        Ok(())
    }
}

/// The rows of a `(count, ndim)` array (any strides), each checked finite
/// as it is read, and what happens to a row outside the grid
/// ([`PointRule::CvalOutside`]: `cval`; [`PointRule::Fold`]: nothing;
/// [`PointRule::WrapPeriodNMinus1`]: folded by scipy's `wrap`).
struct Rows<'a> {
    points: ArrayView2<'a, f64>,
    /// Each axis' column as a slice where it is contiguous: map_coordinates'
    /// points are the transpose of a C-order `(ndim, count)` array, whose
    /// columns are (a row-major walk of the view would step across them).
    columns: Vec<Option<&'a [f64]>>,
    rule: PointRule,
    shape: &'a [usize],
}

impl<'a> Rows<'a> {
    fn new(points: ArrayView2<'a, f64>, rule: PointRule, shape: &'a [usize]) -> Self {
        let columns = (0..points.ncols())
            .map(|a| points.index_axis_move(Axis(1), a).to_slice())
            .collect();
        Rows {
            points,
            columns,
            rule,
            shape,
        }
    }

    /// Coordinate `a` of points `start..start + n`, in order, to `put`.
    #[inline(always)]
    fn column(&self, a: usize, start: usize, n: usize, put: impl FnMut((usize, &f64))) {
        match self.columns[a] {
            Some(col) => col[start..start + n].iter().enumerate().for_each(put),
            None => self
                .points
                .slice(s![start..start + n, a])
                .iter()
                .enumerate()
                .for_each(put),
        }
    }
}

/// Whether every value is finite (a branch-free pass, in lanes).
#[inline(always)]
fn all_finite(x: &[f64]) -> bool {
    x.iter().fold(true, |ok, t| ok & t.is_finite())
}

/// The error of a non-finite coordinate among points from `start` on (its
/// flat index is named by [`Interpolant::eval_many_with`], which knows
/// every point).
fn non_finite(start: usize, ndim: usize) -> NdimageError {
    NdimageError::NonFiniteCoordinate(start * ndim)
}

impl PointSource for Rows<'_> {
    fn fill(
        &self,
        start: usize,
        xs: &mut [f64],
        take_cval: &mut [bool],
    ) -> Result<(), NdimageError> {
        let n = take_cval.len();
        let ndim = self.shape.len();
        for a in 0..ndim {
            self.column(a, start, n, |(j, &v)| xs[j * ndim + a] = v);
        }
        if !all_finite(xs) {
            return Err(non_finite(start, ndim));
        }
        for (x, cv) in xs.chunks_exact_mut(ndim).zip(take_cval.iter_mut()) {
            *cv = self.rule.apply(x, self.shape);
        }
        Ok(())
    }

    /// The columns copied into the lanes (the next batch's prefetched),
    /// checked and ruled in lanes (scipy's `wrap` point by point).
    fn fill_lanes<const D: usize>(
        &self,
        start: usize,
        xs: &mut [[f64; BATCH]; D],
        take_cval: &mut [bool],
    ) -> Result<(), NdimageError> {
        let n = take_cval.len();
        for (a, x) in xs.iter_mut().enumerate() {
            match self.columns[a] {
                Some(col) => {
                    x[..n].copy_from_slice(&col[start..start + n]);
                    // The next batch's coordinates, so that they stream in
                    // while this batch is summed.
                    let next = (start + n).min(col.len());
                    prefetch_lines(col, next, BATCH.min(col.len() - next));
                }
                None => self.column(a, start, n, |(j, &v)| x[j] = v),
            }
        }
        if !xs.iter().all(|x| all_finite(&x[..n])) {
            return Err(non_finite(start, D));
        }
        take_cval.fill(false);
        match self.rule {
            PointRule::Fold => {}
            PointRule::CvalOutside => {
                for (x, &len) in xs.iter().zip(self.shape) {
                    let high = (len - 1) as f64;
                    for (cv, &t) in take_cval.iter_mut().zip(&x[..n]) {
                        *cv |= (t < 0.0) | (t > high);
                    }
                }
            }
            PointRule::WrapPeriodNMinus1 => {
                for j in 0..n {
                    let mut p: [f64; D] = std::array::from_fn(|a| xs[a][j]);
                    take_cval[j] = self.rule.apply(&mut p, self.shape);
                    for (x, v) in xs.iter_mut().zip(p) {
                        x[j] = v;
                    }
                }
            }
        }
        Ok(())
    }
}

impl<T: Real + Send + Sync> Interpolant<T> {
    /// `out[k] = f(points[k, ..])` for `points` of shape `(count, ndim)`
    /// (any strides), in parallel over chunks of 2048 points, one work space
    /// per chunk: no allocation per point. Every coordinate must be finite
    /// (else the error names the first flat index). Cost per point as
    /// [`Interpolant::eval`]; the coefficient rows of 64 points are
    /// prefetched before they are summed (module documentation); 1 to 3
    /// dimensions of degree 1 to 5 in `f64`/`f32` by fixed-size kernels
    /// (`kernel.rs`). Results of another type than `T`:
    /// [`Self::eval_many_with_as`].
    pub fn eval_many(
        &self,
        points: ArrayView2<'_, f64>,
        out: &mut [T],
    ) -> Result<(), NdimageError> {
        self.eval_many_with_as(points, PointRule::Fold, out)
    }

    /// [`Self::eval_many`] with a [`PointRule`] applied to each point first:
    /// scipy's `map_coordinates(mode="constant")` is
    /// [`PointRule::CvalOutside`] on the `mirror` interpolant (`cval` at
    /// every point outside `[0, n − 1]` on some axis, decided in the
    /// parallel evaluation rather than by a pass over the points after it).
    /// Same values as [`Self::eval_many`] at the points the rule leaves
    /// (`batch.rs::tests::cval_outside_rows_take_cval_and_equal_eval_many_inside`).
    pub fn eval_many_with(
        &self,
        points: ArrayView2<'_, f64>,
        rule: PointRule,
        out: &mut [T],
    ) -> Result<(), NdimageError> {
        self.eval_many_with_as(points, rule, out)
    }

    /// [`Self::eval_many_with`] into results of any type `O` the compute
    /// type stores into ([`Stored`]: `f32` results of an `f64`
    /// interpolant, each rounded once from its `f64` value, as scipy
    /// stores a float32 output): the values are computed a chunk of 2048
    /// at a time into a buffer of `T` and stored from it (no `T` copy of
    /// `out`); the same values as [`Self::eval_many_with`] rounded once
    /// (`verify/tests/it/engine_float32.rs`).
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// use splinelab::ndimage::interpolant::PointRule;
    /// let data = ndarray::array![0.1f32, 0.7, 0.2, 0.9, 0.4];
    /// let f = Interpolant::<f64>::from_samples(&data, Options::new(3, Mode::Mirror)).unwrap();
    /// let at = ndarray::array![[1.3], [2.71]];
    /// let (mut wide, mut narrow) = ([0.0f64; 2], [0.0f32; 2]);
    /// f.eval_many(at.view(), &mut wide).unwrap();
    /// f.eval_many_with_as(at.view(), PointRule::Fold, &mut narrow).unwrap();
    /// assert_eq!(narrow, [wide[0] as f32, wide[1] as f32]);
    /// ```
    pub fn eval_many_with_as<O: Stored<T>>(
        &self,
        points: ArrayView2<'_, f64>,
        rule: PointRule,
        out: &mut [O],
    ) -> Result<(), NdimageError> {
        check_points(points, self.ndim(), out.len())?;
        // Each batch checks its points as it reads them; the first
        // non-finite one is named only when one is met.
        let rows = Rows::new(points, rule, &self.shape);
        self.eval_source(&rows, out)
            .map_err(|e| name_non_finite(e, points))
    }

    /// The points of `src` into `out` (one per element), in parallel over
    /// chunks of [`CHUNK`] points ([`store_chunks`]).
    pub(super) fn eval_source<S: PointSource, O: Stored<T>>(
        &self,
        src: &S,
        out: &mut [O],
    ) -> Result<(), NdimageError> {
        store_chunks(out, |start, chunk| {
            if self.has_kernel() {
                self.eval_kernel(src, start, chunk)
            } else {
                self.eval_chunk(src, start, chunk)
            }
        })
    }

    /// `∂^deriv f` at each row of `points` (`(count, ndim)`, any strides)
    /// into `out` ([`Stored`]), in parallel over chunks of [`CHUNK`]
    /// points: [`Self::eval_derivative`] per point (a non-finite coordinate
    /// is named by its flat index, as [`Self::eval_many`] names it).
    pub fn eval_derivatives<O: Stored<T>>(
        &self,
        points: ArrayView2<'_, f64>,
        deriv: &[u32],
        out: &mut [O],
    ) -> Result<(), NdimageError> {
        let ndim = self.ndim();
        if points.ncols() != ndim || deriv.len() != ndim {
            return Err(NdimageError::PointDimension {
                expected: ndim,
                got: if points.ncols() != ndim {
                    points.ncols()
                } else {
                    deriv.len()
                },
            });
        }
        if out.len() != points.nrows() {
            return Err(NdimageError::BufferLength {
                expected: points.nrows(),
                got: out.len(),
            });
        }
        store_chunks(out, |start, chunk| {
            let mut x = vec![0.0; ndim];
            for (j, o) in chunk.iter_mut().enumerate() {
                let k = start + j;
                x.iter_mut().zip(points.row(k)).for_each(|(x, &p)| *x = p);
                *o = self.eval_derivative(&x, deriv).map_err(|e| match e {
                    NdimageError::NonFiniteCoordinate(i) => {
                        NdimageError::NonFiniteCoordinate(k * ndim + i)
                    }
                    e => e,
                })?;
            }
            Ok(())
        })
    }

    /// The points `start..start + out.len()` of `src` on the general path,
    /// sequentially, in batches.
    pub(super) fn eval_chunk<S: PointSource>(
        &self,
        src: &S,
        start: usize,
        out: &mut [T],
    ) -> Result<(), NdimageError> {
        let n = self.ndim();
        let zero = vec![0; n];
        let (mut w, mut off, mut inside) = self.scratch();
        let mut sc = Scratch {
            w: &mut w,
            off: &mut off,
            inside: &mut inside,
        };
        let k = sc.w.len();
        let mut xs = vec![0.0; BATCH * n];
        let mut take_cval = [false; BATCH];
        let mut ws = vec![T::zero(); BATCH * k];
        let mut bases = [None; BATCH];
        let c = self.coeffs.as_slice().expect("standard layout");
        for (b, batch) in out.chunks_mut(BATCH).enumerate() {
            src.fill(
                start + b * BATCH,
                &mut xs[..batch.len() * n],
                &mut take_cval[..batch.len()],
            )?;
            for (j, o) in batch.iter_mut().enumerate() {
                bases[j] = None;
                if take_cval[j] {
                    *o = self.cval.clone();
                    continue;
                }
                let x = &xs[j * n..(j + 1) * n];
                bases[j] = self.locate(x, &mut ws[j * k..(j + 1) * k]);
                match bases[j] {
                    Some(base) => self.prefetch_rows(c, base),
                    None => *o = self.eval_in(x, &zero, &mut sc),
                }
            }
            for (j, o) in batch.iter_mut().enumerate() {
                if let Some(base) = bases[j] {
                    *o = self.tensor_sum(c, base, &ws[j * k..(j + 1) * k], &mut sc);
                }
            }
        }
        Ok(())
    }

    /// Prefetch the rows a located point reads (1 to 3 dimensions; beyond,
    /// nothing): `m^{D−1}` runs of `m` coefficients from `base`.
    fn prefetch_rows(&self, c: &[T], base: usize) {
        let m = self.order as usize;
        match self.ndim() {
            1 => prefetch(c, base, m),
            2 => (0..m).for_each(|l0| prefetch(c, base + l0 * self.strides[0], m)),
            3 => {
                for l0 in 0..m {
                    for l1 in 0..m {
                        let at = base + l0 * self.strides[0] + l1 * self.strides[1];
                        prefetch(c, at, m);
                    }
                }
            }
            _ => {}
        }
    }

    /// The weights of `x` on every axis into `w` (`ndim × m`) and the flat
    /// offset of its first coefficient, when every coefficient the point
    /// reads lies inside the padded array (always, except `grid-constant`
    /// far outside); `None` otherwise. Weights by [`cell_weights_into`].
    fn locate(&self, x: &[f64], w: &mut [T]) -> Option<usize> {
        let m = self.order as usize;
        let mut base = 0;
        for a in 0..self.ndim() {
            if m == 1 {
                let k = self.mode.nearest_index(x[a], self.shape[a])?;
                base += (k + self.pad) * self.strides[a];
                w[a] = T::one();
                continue;
            }
            let xa = self.coordinate(x[a], a);
            let (first, u) = centred_cell(self.order, xa);
            let i0 = first + self.pad as i64;
            if i0 < 0 || i0 as usize + m > self.shape[a] + 2 * self.pad {
                return None;
            }
            base += i0 as usize * self.strides[a];
            cell_weights_into(self.order, 0, u, &mut w[a * m..(a + 1) * m]);
        }
        Some(base)
    }

    /// `Σ_l Π_a w_a[l_a] · c[base + Σ_a l_a s_a]` for a located point: for 1
    /// to 3 dimensions plain nested loops over contiguous runs of `m`
    /// coefficients, else the nested [`Self::accumulate`]. Same sums in the
    /// same order as [`Self::accumulate`].
    fn tensor_sum(&self, c: &[T], base: usize, w: &[T], sc: &mut Scratch<T>) -> T {
        let m = self.order as usize;
        // Σ_l w[l] · row[l] over one contiguous run of the last axis.
        let dot = |wl: &[T], row: &[T]| {
            let mut sum = T::zero();
            for (wv, cv) in wl.iter().zip(row) {
                sum += wv.clone() * cv;
            }
            sum
        };
        match self.ndim() {
            1 => dot(&w[..m], &c[base..base + m]),
            2 if m == 4 => self.sum_2d::<4>(c, base, w),
            2 if m == 6 => self.sum_2d::<6>(c, base, w),
            2 => {
                let s0 = self.strides[0];
                let mut sum = T::zero();
                for (l0, w0) in w[..m].iter().enumerate() {
                    let at = base + l0 * s0;
                    sum += w0.clone() * dot(&w[m..2 * m], &c[at..at + m]);
                }
                sum
            }
            3 => {
                let (s0, s1) = (self.strides[0], self.strides[1]);
                let mut sum = T::zero();
                for (l0, w0) in w[..m].iter().enumerate() {
                    let mut plane = T::zero();
                    for (l1, w1) in w[m..2 * m].iter().enumerate() {
                        let at = base + l0 * s0 + l1 * s1;
                        plane += w1.clone() * dot(&w[2 * m..3 * m], &c[at..at + m]);
                    }
                    sum += w0.clone() * plane;
                }
                sum
            }
            _ => {
                for (k, o) in sc.off.iter_mut().enumerate() {
                    *o = (k % m) * self.strides[k / m];
                }
                sc.w.clone_from_slice(w);
                sc.inside.fill(true);
                self.accumulate(&c[base..], sc, 0, 0, true)
            }
        }
    }
}

impl<T: Real + Send + Sync> Interpolant<T> {
    /// The 2-D case of [`Self::tensor_sum`] for a compile-time order `M`
    /// (loops unrolled, one bounds check per row): the same products added
    /// in the same order, from zero, so the same bits.
    fn sum_2d<const M: usize>(&self, c: &[T], base: usize, w: &[T]) -> T {
        let (w0, w1) = w.split_at(M);
        let w1: &[T; M] = w1[..M].try_into().expect("M weights");
        let mut sum = T::zero();
        for (l0, w0) in w0.iter().enumerate() {
            let at = base + l0 * self.strides[0];
            let row: &[T; M] = c[at..at + M].try_into().expect("M coefficients");
            let mut dot = T::zero();
            for l in 0..M {
                dot += w1[l].clone() * &row[l];
            }
            sum += w0.clone() * dot;
        }
        sum
    }
}

/// `out` filled on the pool in chunks of [`CHUNK`]: `eval(start, values)`
/// computes the values of outputs `start..start + values.len()` in `T`,
/// into the chunk itself where `O` is `T`, else into a buffer of one chunk
/// that is then stored ([`Stored::store_from`]: each value rounded once).
pub(super) fn store_chunks<T, O>(
    out: &mut [O],
    eval: impl Fn(usize, &mut [T]) -> Result<(), NdimageError> + Sync,
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    O: Stored<T>,
{
    out.par_chunks_mut(CHUNK)
        .enumerate()
        .try_for_each(|(c, chunk)| {
            if let Some(values) = O::as_compute_mut(chunk) {
                return eval(c * CHUNK, values);
            }
            let mut values = vec![T::zero(); chunk.len()];
            eval(c * CHUNK, &mut values)?;
            O::store_from(&values, chunk);
            Ok(())
        })
}

/// Points `(count, ndim)` of an array of `ndim` axes, and `out` of one
/// value per point: else the error a batch evaluation gives.
pub(super) fn check_points(
    points: ArrayView2<'_, f64>,
    ndim: usize,
    out: usize,
) -> Result<(), NdimageError> {
    if ndim == 0 {
        // A 0-d array has no axis to place a point on.
        return Err(NdimageError::Axis { axis: 0, ndim: 0 });
    }
    if points.ncols() != ndim {
        return Err(NdimageError::PointDimension {
            expected: ndim,
            got: points.ncols(),
        });
    }
    if out != points.nrows() {
        return Err(NdimageError::BufferLength {
            expected: points.nrows(),
            got: out,
        });
    }
    Ok(())
}

/// `e` with a non-finite coordinate named by the first one of `points`
/// (the chunk that met one named its own).
pub(super) fn name_non_finite(e: NdimageError, points: ArrayView2<'_, f64>) -> NdimageError {
    match e {
        NdimageError::NonFiniteCoordinate(_) => {
            first_non_finite(points).map_or(e, NdimageError::NonFiniteCoordinate)
        }
        e => e,
    }
}

/// The flat (row-major) index of the first non-finite coordinate of
/// `points`, if any: the rows checked in parallel in chunks of [`CHUNK`],
/// the first chunk with one named (run once a batch has met one: the
/// batches check their own points as they read them).
fn first_non_finite(points: ArrayView2<'_, f64>) -> Option<usize> {
    let (count, ndim) = points.dim();
    (0..count.div_ceil(CHUNK))
        .into_par_iter()
        .find_map_first(|c| {
            let rows = points.slice(s![c * CHUNK..((c + 1) * CHUNK).min(count), ..]);
            // By columns (contiguous for map_coordinates' points); the
            // position, row-major, only for a chunk with a non-finite one.
            let ok = rows.columns().into_iter().fold(true, |ok, col| {
                ok & match col.as_slice() {
                    Some(v) => v.iter().fold(true, |ok, x| ok & x.is_finite()),
                    None => col.fold(true, |ok, x| ok & x.is_finite()),
                }
            });
            (!ok).then(|| {
                let at = rows.iter().position(|x| !x.is_finite()).unwrap_or(0);
                c * CHUNK * ndim + at
            })
        })
}

/// Ask the cache for every line of `c[at..at + len]` (a hint, as
/// [`prefetch`]).
#[inline(always)]
fn prefetch_lines<T>(c: &[T], at: usize, len: usize) {
    let per_line = (64 / std::mem::size_of::<T>()).max(1);
    for k in (0..len).step_by(per_line) {
        prefetch(c, at + k, 1);
    }
}

/// Ask the cache for `c[at..at + len]` (its first and last byte: a run of at
/// most 64 bytes spans at most two lines). A hint: no effect on results, and
/// none at all off x86_64. Addresses are formed with wrapping arithmetic and
/// never dereferenced here.
#[inline(always)]
pub(super) fn prefetch<T>(c: &[T], at: usize, len: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let first = c.as_ptr().wrapping_add(at).cast::<i8>();
        let last = first.wrapping_add(len * std::mem::size_of::<T>() - 1);
        // SAFETY: `prefetch` never faults or reads into the program (a hint
        // to the cache, valid for any address), and SSE is part of the
        // x86_64 baseline the crate is built for.
        #[allow(unsafe_code)]
        unsafe {
            _mm_prefetch::<_MM_HINT_T0>(first);
            _mm_prefetch::<_MM_HINT_T0>(last);
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (c, at, len);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prelude::*;

    /// Under [`PointRule::CvalOutside`] a point outside `[0, n − 1]` on
    /// some axis takes `cval`, every other point the value of
    /// [`Interpolant::eval_many`]; under [`PointRule::Fold`] all are its values.
    #[test]
    fn cval_outside_rows_take_cval_and_equal_eval_many_inside() {
        let data =
            ndarray::Array2::from_shape_fn((6, 7), |(i, j)| (i as f64 * 0.7 + j as f64).sin());
        let mut opts = Options::new(3, Mode::Mirror);
        opts.cval = -2.5;
        let f = Interpolant::<f64>::new(&data, opts).unwrap();
        let pts = ndarray::Array2::from_shape_fn((300, 2), |(k, a)| {
            -1.5 + ((k * (a + 3)) % 97) as f64 * 0.1 + if a == 1 { 0.05 } else { 0.0 }
        });
        let (mut all, mut ruled, mut folded) = (vec![0.0; 300], vec![0.0; 300], vec![0.0; 300]);
        f.eval_many(pts.view(), &mut all).unwrap();
        f.eval_many_with(pts.view(), PointRule::CvalOutside, &mut ruled)
            .unwrap();
        f.eval_many_with(pts.view(), PointRule::Fold, &mut folded)
            .unwrap();
        assert_eq!(all, folded);
        let mut outside = 0;
        for (k, p) in pts.rows().into_iter().enumerate() {
            if p[0] < 0.0 || p[0] > 5.0 || p[1] < 0.0 || p[1] > 6.0 {
                outside += 1;
                assert_eq!(ruled[k], -2.5, "{p}");
            } else {
                assert_eq!(ruled[k], all[k], "{p}");
            }
        }
        assert!(outside > 50 && outside < 250, "{outside}");
    }

    /// A 0-d array (one sample, no axis) has no axis to place a point on:
    /// both the batch evaluation and the in-place reading refuse its
    /// points (they split the points into rows of `ndim`, none for 0).
    #[test]
    fn points_on_a_0d_array_are_refused() {
        let data = ndarray::arr0(2.5).into_dyn();
        let f = Interpolant::<f64>::new(&data, Options::new(1, Mode::Mirror)).unwrap();
        let pts = ndarray::Array2::<f64>::zeros((2, 0));
        let mut out = [0.0; 2];
        let refused = |e| matches!(e, Err(NdimageError::Axis { axis: 0, ndim: 0 }));
        assert!(refused(f.eval_many(pts.view(), &mut out)));
        let o = super::super::InPlaceOptions {
            order: super::super::SampleOrder::of_degree(1).unwrap(),
            mode: Mode::Mirror,
            cval: 0.0,
            nan_policy: NanPolicy::Propagate,
        };
        let got = super::super::map_samples_in_place::<f64, f64, f64>(
            &data.view(),
            pts.view(),
            &o,
            PointRule::Fold,
            &mut out,
        );
        assert!(refused(got));
    }
}
