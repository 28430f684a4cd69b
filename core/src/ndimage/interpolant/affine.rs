//! Affine resampling of an [`Interpolant`] without a coordinate array
//! ([`Interpolant::resample_affine`]): scipy.ndimage's `affine_transform`
//! and `rotate` (`NI_GeometricTransform` with a matrix). The point of each
//! output index `o` is generated where it is evaluated, 64 at a time, in
//! chunks of 2048 outputs in parallel, and evaluated as
//! [`Interpolant::eval_many`] evaluates (batched, prefetched, the fixed-size
//! kernels of `kernel.rs`): no `ndim × count` array of coordinates in
//! memory; under [`PointRule::CvalOutside`] the points outside the grid
//! take `cval` without evaluation. Where a fixed-size kernel serves (1 to 3
//! dimensions, degrees 0 to 5, `f64`/`f32`), the outputs go by runs along
//! the last output axis (`runs.rs`): the interval of each run whose points
//! lie inside the grid is found once and evaluated without per-point
//! checks, the same values bit for bit.
//!
//! **Points** as scipy forms them, to the bit: `x_h = offset_h + o_0 M_{h0}
//! + o_1 M_{h1} + …` added in that order from `offset_h`, then `+ shift`
//! (scipy's 12-sample pre-padding for `nearest` / `grid-constant`), then
//! [`PointRule`]. **Cost** one multiply-add per point and input axis (the
//! sum of the other output axes' terms is kept along a row) plus
//! the evaluation (`(degree + 1)^ndim` multiply-adds). **Error**: that of
//! [`Interpolant::eval`].

use super::batch::PointSource;
use super::{Interpolant, PointRule};
use crate::ndimage::NdimageError;
use crate::ndimage::alloc::checked_len;
use crate::ndimage::samples::Stored;
use crate::scalar::Real;

impl<T: Real + Copy + Send + Sync> Interpolant<T> {
    /// The values at the points `matrix · o + offset` (+ `shift`) of every
    /// index `o` of an output of `out_shape`, written in C order into `out`.
    /// `matrix` is `ndim × out_shape.len()`, row-major. Method, cost and
    /// error in the module documentation.
    ///
    ///
    /// **Method**: the points of each block of output indices are formed by the affine map and
    /// evaluated as [`Interpolant::eval_many`] does (no coordinate array), by runs along the
    /// last output axis where a fixed-size kernel serves (`runs.rs`). **Accuracy**: the
    /// same values as pointwise [`Interpolant::eval`], bit for bit
    /// (`affine.rs::tests::affine_points_equal_pointwise_evaluation_bit_for_bit`,
    /// `runs.rs::tests::runs_equal_the_batch_path_bit_for_bit`). **Source**:
    /// scipy's `affine_transform` (`ni_interpolation.c`, `NI_GeometricTransform`).
    /// Results of another type than `T`: [`Self::resample_affine_as`].
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// use splinelab::ndimage::interpolant::PointRule;
    /// let data = ndarray::array![[0.0, 1.0, 4.0], [1.0, 2.0, 5.0], [4.0, 5.0, 8.0]];
    /// let f: Interpolant<f64> = Interpolant::new(&data, Options::new(3, Mode::Mirror)).unwrap();
    /// // The transpose: output (i, j) reads input (j, i).
    /// let mut out = [0.0f64; 9];
    /// f.resample_affine(&[0.0, 1.0, 1.0, 0.0], &[0.0, 0.0], &[3, 3], 0.0, PointRule::Fold, &mut out).unwrap();
    /// assert!((out[1] - data[[1, 0]]).abs() < 1e-14);
    /// ```
    pub fn resample_affine(
        &self,
        matrix: &[f64],
        offset: &[f64],
        out_shape: &[usize],
        shift: f64,
        rule: PointRule,
        out: &mut [T],
    ) -> Result<(), NdimageError> {
        self.resample_affine_as(matrix, offset, out_shape, shift, rule, out)
    }

    /// [`Self::resample_affine`] into results of any type `O` the compute
    /// type stores into ([`Stored`]: `f32` results of an `f64`
    /// interpolant), each rounded once, a chunk of 2048 at a time (no `T`
    /// copy of `out`).
    pub fn resample_affine_as<O: Stored<T>>(
        &self,
        matrix: &[f64],
        offset: &[f64],
        out_shape: &[usize],
        shift: f64,
        rule: PointRule,
        out: &mut [O],
    ) -> Result<(), NdimageError> {
        let (n, k) = (self.ndim(), out_shape.len());
        if matrix.len() != n * k || offset.len() != n || k == 0 {
            return Err(NdimageError::PointDimension {
                expected: n,
                got: if offset.len() != n { offset.len() } else { k },
            });
        }
        let count = checked_len(out_shape, "the affine resampling's output")?;
        if out.len() != count {
            return Err(NdimageError::BufferLength {
                expected: count,
                got: out.len(),
            });
        }
        if let Some(i) = matrix.iter().chain(offset).position(|v| !v.is_finite()) {
            return Err(NdimageError::NonFiniteCoordinate(i));
        }
        if out.is_empty() {
            // An output axis of length 0: no points (scipy returns the empty array).
            return Ok(());
        }
        let src = self.affine_points(matrix, offset, out_shape, shift, rule);
        // `const`: wider MPFR builds compile no run kernels (`Real::FITS_F64`).
        if const { T::FITS_F64 } && self.has_run_kernel(rule) {
            self.eval_affine_runs(&src, out)
        } else {
            self.eval_source(&src, out)
        }
    }

    /// The points [`Self::resample_affine`] evaluates, from its arguments
    /// (checked there).
    pub(super) fn affine_points<'a>(
        &'a self,
        matrix: &'a [f64],
        offset: &'a [f64],
        out_shape: &'a [usize],
        shift: f64,
        rule: PointRule,
    ) -> AffinePoints<'a> {
        AffinePoints {
            matrix,
            offset,
            out_shape,
            shift,
            rule,
            shape: &self.shape,
        }
    }
}

/// The points of [`Interpolant::resample_affine`], generated batch by batch.
pub(super) struct AffinePoints<'a> {
    pub(super) matrix: &'a [f64],
    pub(super) offset: &'a [f64],
    pub(super) out_shape: &'a [usize],
    pub(super) shift: f64,
    pub(super) rule: PointRule,
    /// The input's shape.
    pub(super) shape: &'a [usize],
}

impl PointSource for AffinePoints<'_> {
    /// Along the last output axis only its term changes: the sum of the
    /// others (`offset_h + o_0 M_{h0} + …`, scipy's order) is formed once
    /// per run of the batch along that axis, so each point costs one
    /// multiply-add per input axis, same bits; no allocation for up to
    /// [`STACK_AXES`] axes.
    fn fill(
        &self,
        start: usize,
        xs: &mut [f64],
        take_cval: &mut [bool],
    ) -> Result<(), NdimageError> {
        let n = self.shape.len();
        // The last output axis' column of the matrix and the input's upper
        // ends, as f64 once per batch (no integer conversion per point).
        let (mut step_stack, mut high_stack) = ([0.0; STACK_AXES], [0.0; STACK_AXES]);
        let (mut step_heap, mut high_heap) = (Vec::new(), Vec::new());
        let step = on_stack_or_heap(&mut step_stack, &mut step_heap, n);
        let high = on_stack_or_heap(&mut high_stack, &mut high_heap, n);
        self.steps_and_tops(step, high);
        self.for_each_run(start, take_cval.len(), |done, first, run, row| {
            let at = done * n..(done + run) * n;
            let cv = &mut take_cval[done..done + run];
            self.fill_run(row, step, high, first as f64, &mut xs[at], cv);
            Ok(())
        })?;
        // One pass for the rare overflow to infinity (finite matrix and
        // offset, huge indices); the position only then.
        if !xs.iter().fold(true, |ok, t| ok & t.is_finite()) {
            let at = xs.iter().position(|t| !t.is_finite()).unwrap_or(0);
            return Err(NdimageError::NonFiniteCoordinate(start * n + at));
        }
        Ok(())
    }
}

/// Axes of the output and input an [`AffinePoints`] batch keeps on the stack.
const STACK_AXES: usize = 8;

/// The first `len` elements of `stack`, or of `heap` (resized) when longer.
fn on_stack_or_heap<'a, V: Copy + Default>(
    stack: &'a mut [V; STACK_AXES],
    heap: &'a mut Vec<V>,
    len: usize,
) -> &'a mut [V] {
    if len <= STACK_AXES {
        &mut stack[..len]
    } else {
        heap.resize(len, V::default());
        heap
    }
}

impl AffinePoints<'_> {
    /// The last output axis' column of the matrix into `step` and the
    /// input's upper ends `n_h − 1` into `high`, in `f64`.
    pub(super) fn steps_and_tops(&self, step: &mut [f64], high: &mut [f64]) {
        let k = self.out_shape.len();
        for (h, (m, hi)) in step.iter_mut().zip(high.iter_mut()).enumerate() {
            *m = self.matrix[h * k + k - 1];
            *hi = (self.shape[h] - 1) as f64;
        }
    }

    /// `visit(done, first, len, row)` for each run along the last output
    /// axis among the outputs `start..start + count`, in order: `done`
    /// outputs before it, its first index `first` on that axis, its length,
    /// and its row sums ([`Self::row_sums`]).
    pub(super) fn for_each_run(
        &self,
        start: usize,
        count: usize,
        mut visit: impl FnMut(usize, usize, usize, &[f64]) -> Result<(), NdimageError>,
    ) -> Result<(), NdimageError> {
        let (n, k) = (self.shape.len(), self.out_shape.len());
        let (mut index_stack, mut row_stack) = ([0; STACK_AXES], [0.0; STACK_AXES]);
        let (mut index_heap, mut row_heap) = (Vec::new(), Vec::new());
        let index = on_stack_or_heap(&mut index_stack, &mut index_heap, k);
        let row = on_stack_or_heap(&mut row_stack, &mut row_heap, n);
        let run_len = self.out_shape[k - 1];
        let mut done = 0;
        while done < count {
            unflatten_into(start + done, self.out_shape, index);
            self.row_sums(index, row);
            let first = index[k - 1];
            let len = (run_len - first).min(count - done);
            visit(done, first, len, row)?;
            done += len;
        }
        Ok(())
    }

    /// The points of one run along the last output axis, from its index
    /// `first` (an integer below `2^53`, so `+ 1` stays exact), of row
    /// sums `row`: `x_h = (row_h + o · step_h) + shift`, then the rule
    /// (`high_h = n_h − 1`).
    fn fill_run(
        &self,
        row: &[f64],
        step: &[f64],
        high: &[f64],
        first: f64,
        xs: &mut [f64],
        take_cval: &mut [bool],
    ) {
        let n = row.len();
        let mut last = first;
        for (x, cv) in xs.chunks_exact_mut(n).zip(take_cval.iter_mut()) {
            for ((xh, r), m) in x.iter_mut().zip(row).zip(step) {
                *xh = (r + last * m) + self.shift;
            }
            last += 1.0;
            *cv = match self.rule {
                PointRule::CvalOutside => x
                    .iter()
                    .zip(high)
                    .fold(false, |out, (&t, &hi)| out | (t < 0.0) | (t > hi)),
                rule => rule.apply(x, self.shape),
            };
        }
    }

    /// `offset_h + o_0 M_{h0} + … + o_{k−2} M_{h,k−2}` for every input axis
    /// `h`, added in scipy's order (all but the last output axis).
    fn row_sums(&self, o: &[usize], row: &mut [f64]) {
        let k = o.len();
        for (h, t) in row.iter_mut().enumerate() {
            *t = self.offset[h];
            for (l, &ol) in o[..k - 1].iter().enumerate() {
                *t += ol as f64 * self.matrix[h * k + l];
            }
        }
    }
}

/// The multi-index of flat C-order position `flat` in `shape`, into `index`.
fn unflatten_into(mut flat: usize, shape: &[usize], index: &mut [usize]) {
    for (i, &n) in index.iter_mut().zip(shape).rev() {
        *i = flat % n.max(1);
        flat /= n.max(1);
    }
}

#[cfg(test)]
mod tests {
    use super::super::point_rule::wrap_period_n_minus_1;
    use super::*;
    use crate::prelude::*;

    /// The generated points evaluated equal eval at the same points formed
    /// by hand, bit for bit, for a 3-D input and a 2-D output (a plane).
    #[test]
    fn affine_points_equal_pointwise_evaluation_bit_for_bit() {
        let data = ndarray::Array3::from_shape_fn((7, 8, 9), |(i, j, k)| {
            ((i * 3 + j * 5 + k) as f64 * 0.37).sin()
        });
        let m = [0.9, -0.2, 0.1, 0.8, 0.3, 0.25];
        let off = [-1.5, 2.25, 0.5];
        for rule in [
            PointRule::Fold,
            PointRule::CvalOutside,
            PointRule::WrapPeriodNMinus1,
        ] {
            let mut opts = Options::new(3, Mode::Mirror);
            opts.cval = 0.5;
            let f = Interpolant::<f64>::new(&data, opts).unwrap();
            let shape = [11, 12];
            let mut out = vec![0.0; 132];
            f.resample_affine(&m, &off, &shape, 0.0, rule, &mut out)
                .unwrap();
            // The same points formed by hand, through eval_many (whose cubic
            // weights are the closed form, so compared with it, not eval).
            let mut pts = ndarray::Array2::<f64>::zeros((132, 3));
            let mut outside = [false; 132];
            for i in 0..11 {
                for j in 0..12 {
                    for h in 0..3 {
                        let n = [7, 8, 9][h];
                        let mut t = off[h] + i as f64 * m[2 * h] + j as f64 * m[2 * h + 1];
                        outside[i * 12 + j] |= t < 0.0 || t > n as f64 - 1.0;
                        if rule == PointRule::WrapPeriodNMinus1 {
                            t = wrap_period_n_minus_1(t, n);
                        }
                        pts[[i * 12 + j, h]] = t;
                    }
                }
            }
            let mut want = vec![0.0; 132];
            f.eval_many(pts.view(), &mut want).unwrap();
            for (k, w) in want.iter_mut().enumerate() {
                if rule == PointRule::CvalOutside && outside[k] {
                    *w = 0.5;
                }
            }
            assert_eq!(out, want, "{rule:?}");
        }
        assert_eq!(wrap_period_n_minus_1(-0.5, 5), 3.5);
        assert_eq!(wrap_period_n_minus_1(9.0, 5), 1.0);
        assert_eq!(wrap_period_n_minus_1(8.0, 5), 0.0);
    }
}
