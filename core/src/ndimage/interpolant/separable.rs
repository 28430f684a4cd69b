//! Separable resampling of an [`Interpolant`] on a tensor grid of points
//! ([`Interpolant::resample_grid`]): the values `f(x⁰_{k₀}, x¹_{k₁}, …)` for
//! one coordinate vector per axis — scipy.ndimage's `zoom` and `shift`
//! (`NI_ZoomShift`) and `affine_transform` with a diagonal matrix.
//!
//! **Method.** The tensor-product sum `Σ_i D_i Π_a β(x^a_{k_a} − i_a)`
//! factors axis by axis: for each axis a 1-D evaluation matrix `W_a` with
//! `m = degree + 1` non-zero weights per output index (the B-spline window
//! of [`Interpolant::eval`], same folding and padding), applied along that
//! axis of the coefficient array, one axis after the other:
//! `f = W_0 ×₀ (W_1 ×₁ (… W_{D−1} ×_{D−1} D))`. **Cost** `O(m)` per output
//! sample and axis (`m·N·D` multiply-adds for `N` outputs in `D` dimensions
//! when the grid grows) instead of the `m^D` of [`Interpolant::eval`] at
//! every point; the last axis first (contiguous gathers), then each other
//! axis as `m` scaled rows added (contiguous, vectorised), rows in parallel.
//!
//! **Error.** Each axis rounds a sum of `m` products with non-negative
//! weights summing to 1: the result is within `≈ D·m·u·Σ_i |D_i| w_i` of the
//! exact tensor sum, the bound of [`Interpolant::eval`] (the terms are
//! grouped differently, so the two differ by a few ulps; tested against
//! pointwise evaluation in `separable_grid_equals_pointwise_evaluation`).
//! A window index beyond the padded coefficients (`grid-constant` far
//! outside) reads `cval`, as in [`Interpolant::eval`]: since the earlier
//! axes' weights sum to 1, a coefficient outside on this axis is `cval`
//! after them too.

use super::Interpolant;
use crate::ndimage::NdimageError;
use crate::ndimage::alloc::{checked_len, try_filled, try_with_capacity};
use crate::scalar::Real;
use crate::sspline::bspline_uniform::centred_cell;
use rayon::prelude::*;

/// What the resampling's work arrays hold (named where one cannot be allocated).
const WHAT: &str = "the separable resampling's intermediate values";

/// One axis of the resampling: for each output index the `m` window
/// indices into the padded coefficients (`None`: outside, reads `cval`)
/// and their weights.
struct AxisPlan<T> {
    m: usize,
    index: Vec<Option<usize>>,
    weight: Vec<T>,
}

impl<T: Real + Copy + Send + Sync> Interpolant<T> {
    /// The values on the grid `coordinates[0] × coordinates[1] × …`
    /// (sample indices, one vector per axis), written in C order into
    /// `out` (length the product of the vectors' lengths);
    /// `deriv[a]` the order of the partial derivative along axis `a`
    /// (all zero: the values). Same values as [`Interpolant::eval`] at each
    /// grid point (folding, padding and `cval` included) up to rounding;
    /// method, cost and error in the module documentation.
    ///
    ///
    /// **Method**: tensor-product resampling, one axis at a time: `(degree + 1)` weights per
    /// output index and axis, applied along that axis. **Accuracy**: pointwise evaluation's up
    /// to rounding (`separable.rs::tests::separable_grid_equals_pointwise_evaluation`,
    /// `separable_derivatives_equal_pointwise_ones`). **Source**: the separability of
    /// tensor-product B-splines (de Boor, *A Practical Guide to Splines*, ch. XVII); scipy's
    /// `zoom`/`shift` conventions.
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// let data = ndarray::array![[0.0, 1.0, 4.0], [1.0, 2.0, 5.0], [4.0, 5.0, 8.0]];
    /// let f: Interpolant<f64> = Interpolant::new(&data, Options::new(3, Mode::Mirror)).unwrap();
    /// let (rows, cols) = ([0.0, 1.5], [0.25, 2.0, 1.0]);
    /// let mut out = [0.0f64; 6];
    /// f.resample_grid(&[&rows, &cols], &[0, 0], &mut out).unwrap();
    /// assert!((out[1 * 3 + 2] - f.eval(&[1.5, 1.0]).unwrap()).abs() < 1e-14);
    /// ```
    pub fn resample_grid(
        &self,
        coordinates: &[&[f64]],
        deriv: &[u32],
        out: &mut [T],
    ) -> Result<(), NdimageError> {
        self.check_grid(coordinates, deriv, out.len())?;
        if out.is_empty() {
            // An axis of no points (scipy's zoom to a length of 0): nothing
            // to evaluate (and no chunks of 0 values to split the work into).
            return Ok(());
        }
        let plans: Vec<AxisPlan<T>> = coordinates
            .iter()
            .enumerate()
            .map(|(a, xs)| self.axis_plan(a, xs, deriv[a]))
            .collect::<Result<_, _>>()?;
        // The last axis first, each step into a new buffer, the final one
        // into `out` (no copy of the coefficients, no final copy).
        let mut shape: Vec<usize> = self.coeffs.shape().to_vec();
        let coeffs = self.coeffs.as_slice().expect("standard layout");
        let mut data: Vec<T> = Vec::new();
        for a in (0..self.ndim()).rev() {
            let src: &[T] = if a + 1 == self.ndim() { coeffs } else { &data };
            let mut next = shape.clone();
            next[a] = coordinates[a].len();
            if a == 0 {
                self.apply_axis(src, &shape, a, &plans[a], out);
                break;
            }
            let len = checked_len(&next, WHAT)?;
            let mut dst = try_filled(len, T::zero(), WHAT)?;
            self.apply_axis(src, &shape, a, &plans[a], &mut dst);
            data = dst;
            shape = next;
        }
        Ok(())
    }

    fn check_grid(&self, xs: &[&[f64]], deriv: &[u32], len: usize) -> Result<(), NdimageError> {
        if xs.len() != self.ndim() || deriv.len() != self.ndim() {
            return Err(NdimageError::PointDimension {
                expected: self.ndim(),
                got: if xs.len() != self.ndim() {
                    xs.len()
                } else {
                    deriv.len()
                },
            });
        }
        let count: usize = xs.iter().map(|x| x.len()).product();
        if count != len {
            return Err(NdimageError::BufferLength {
                expected: count,
                got: len,
            });
        }
        let mut flat = 0;
        for x in xs {
            if let Some(k) = x.iter().position(|c| !c.is_finite()) {
                return Err(NdimageError::NonFiniteCoordinate(flat + k));
            }
            flat += x.len();
        }
        match deriv.iter().find(|&&d| d >= self.order) {
            Some(&d) => Err(NdimageError::DerivativeTooHigh {
                order: d,
                degree: self.degree(),
            }),
            None => Ok(()),
        }
    }

    /// Window indices (into the padded axis) and weights of every output
    /// index on axis `a`, as [`Interpolant::eval`] forms them.
    fn axis_plan(&self, a: usize, xs: &[f64], deriv: u32) -> Result<AxisPlan<T>, NdimageError> {
        let m = self.order as usize;
        let padded = self.shape[a] + 2 * self.pad;
        let n = checked_len(&[xs.len(), m], WHAT)?;
        let mut index = try_with_capacity(n, WHAT)?;
        let mut weight = try_filled(n, T::zero(), WHAT)?;
        for (k, &x) in xs.iter().enumerate() {
            let w = &mut weight[k * m..(k + 1) * m];
            if m == 1 {
                w[0] = T::one();
                index.push(
                    self.mode
                        .nearest_index(x, self.shape[a])
                        .map(|i| i + self.pad),
                );
                continue;
            }
            let (first, u) = centred_cell(self.order, self.coordinate(x, a));
            super::cell_weights_into(self.order, deriv, u, w);
            for l in 0..m {
                let i = first + l as i64 + self.pad as i64;
                index.push(usize::try_from(i).ok().filter(|&i| i < padded));
            }
        }
        Ok(AxisPlan { m, index, weight })
    }

    /// `B[o, k, i] = Σ_l w[k, l] · A[o, index[k, l], i]` (`cval` where the
    /// index is outside) for `A` of `shape` in C order, axis `a`, into
    /// `dst` (every element written).
    fn apply_axis(&self, src: &[T], shape: &[usize], a: usize, plan: &AxisPlan<T>, dst: &mut [T]) {
        let len = shape[a];
        let inner: usize = shape[a + 1..].iter().product();
        let count = plan.index.len() / plan.m;
        let cval = self.cval;
        if inner == 1 {
            dst.par_chunks_mut(count)
                .with_min_len(4)
                .enumerate()
                .for_each(|(o, row)| {
                    let line = &src[o * len..(o + 1) * len];
                    gather_rows(line, plan, cval, row);
                });
            return;
        }
        dst.par_chunks_mut(inner)
            .with_min_len(64)
            .enumerate()
            .for_each(|(r, row)| {
                let (o, k) = (r / count, r % count);
                let block = &src[o * len * inner..(o + 1) * len * inner];
                let w = &plan.weight[k * plan.m..(k + 1) * plan.m];
                let idx = &plan.index[k * plan.m..(k + 1) * plan.m];
                row.fill(T::zero());
                for (wl, il) in w.iter().zip(idx) {
                    match il {
                        Some(i) => axpy(*wl, &block[i * inner..(i + 1) * inner], row),
                        None => row.iter_mut().for_each(|y| *y += *wl * cval),
                    }
                }
            });
    }
}

/// The last axis: `row[k] = Σ_l w[k, l] · line[index[k, l]]`.
fn gather_rows<T: Real + Copy>(line: &[T], plan: &AxisPlan<T>, cval: T, row: &mut [T]) {
    let m = plan.m;
    for (k, y) in row.iter_mut().enumerate() {
        let mut sum = T::zero();
        for l in 0..m {
            let v = plan.index[k * m + l].map_or(cval, |i| line[i]);
            sum += plan.weight[k * m + l] * v;
        }
        *y = sum;
    }
}

/// `y += w · x` element-wise.
#[inline]
fn axpy<T: Real + Copy>(w: T, x: &[T], y: &mut [T]) {
    for (y, x) in y.iter_mut().zip(x) {
        *y += w * *x;
    }
}

#[cfg(test)]
mod tests {
    use crate::prelude::*;
    use ndarray::Dimension;

    /// The separable sums against the pointwise ones at every grid point,
    /// every mode, degrees 0..7, 1-D to 3-D, points inside and outside.
    #[test]
    fn separable_grid_equals_pointwise_evaluation() {
        let shape = [9usize, 7, 6];
        for ndim in 1..=3 {
            let sh = &shape[..ndim];
            let data = ndarray::ArrayD::from_shape_fn(sh, |i| {
                let i = i.slice();
                (0..ndim)
                    .map(|a| ((i[a] * (a + 3)) as f64 * 0.7).sin())
                    .sum::<f64>()
            });
            let xs: Vec<Vec<f64>> = sh
                .iter()
                .map(|&n| (0..n + 5).map(|k| -3.3 + k as f64 * 1.07).collect())
                .collect();
            let axes: Vec<&[f64]> = xs.iter().map(|x| x.as_slice()).collect();
            for mode in Mode::ALL {
                for degree in 0..=7 {
                    let mut opts = Options::new(degree, mode);
                    opts.cval = 0.375;
                    let f = Interpolant::<f64>::new(&data, opts).unwrap();
                    let count: usize = xs.iter().map(Vec::len).product();
                    let mut grid = vec![0.0; count];
                    f.resample_grid(&axes, &vec![0; ndim], &mut grid).unwrap();
                    let scale = grid.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                    for (flat, g) in grid.iter().enumerate() {
                        let mut rest = flat;
                        let mut x = vec![0.0; ndim];
                        for a in (0..ndim).rev() {
                            x[a] = xs[a][rest % xs[a].len()];
                            rest /= xs[a].len();
                        }
                        let e = f.eval(&x).unwrap();
                        assert!(
                            (g - e).abs() <= 64.0 * f64::EPSILON * scale,
                            "{mode} degree {degree} at {x:?}: {g} vs {e}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn separable_derivatives_equal_pointwise_ones() {
        let data =
            ndarray::Array2::from_shape_fn((8, 9), |(i, j)| (i as f64 * 0.4).cos() * j as f64);
        let f = Interpolant::<f64>::new(&data, Options::new(5, Mode::Reflect)).unwrap();
        let (r, c) = ([0.5, 3.25, 7.9], [-1.0, 4.5]);
        let mut out = [0.0; 6];
        f.resample_grid(&[&r, &c], &[1, 2], &mut out).unwrap();
        for (k, &x0) in r.iter().enumerate() {
            for (l, &x1) in c.iter().enumerate() {
                let e = f.eval_derivative(&[x0, x1], &[1, 2]).unwrap();
                assert!((out[k * 2 + l] - e).abs() <= 1e-12, "{x0} {x1}");
            }
        }
        let err = f.resample_grid(&[&r, &c], &[0, 6], &mut out).unwrap_err();
        assert!(err.to_string().contains('6'), "{err}");
        let err = f.resample_grid(&[&r], &[0], &mut out).unwrap_err();
        assert!(matches!(err, NdimageError::PointDimension { .. }), "{err}");
    }
}
