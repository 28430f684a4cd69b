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
//! axis as `m` scaled rows added (contiguous, vectorised). Axis 0 goes
//! last, by chunks of output rows in parallel: each output row adds the
//! `m` coefficient slabs `D[i, …]` of its window, each resampled along the
//! other axes when first read and kept in a cache of `m + 1` slabs while
//! the following windows read it. **Memory** beside the output: that cache
//! and one slab's intermediate per thread (no array of the whole
//! resampled intermediate: for a 2-D zoom by 2 that would be as large as a
//! float64 output); slabs at the start of each chunk are made twice.
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
use crate::ndimage::samples::Stored;
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

impl<T> AxisPlan<T> {
    /// The number of output indices.
    fn count(&self) -> usize {
        self.index.len() / self.m
    }

    /// The weights and window indices of output index `k`.
    fn window(&self, k: usize) -> (&[T], &[Option<usize>]) {
        let at = k * self.m..(k + 1) * self.m;
        (&self.weight[at.clone()], &self.index[at])
    }
}

/// The slabs of axis 0 a chunk of output rows has resampled along the
/// other axes, a few at a time (`capacity`, at least one window): a slab
/// is made on its first use and kept while the windows that follow read
/// it (consecutive windows share all but a row or two of their slabs).
struct SlabCache<T> {
    rows: Vec<Option<usize>>,
    used: Vec<u64>,
    data: Vec<T>,
    len: usize,
    clock: u64,
}

impl<T: Real + Copy> SlabCache<T> {
    fn new(capacity: usize, len: usize) -> Self {
        SlabCache {
            rows: vec![None; capacity],
            used: vec![0; capacity],
            data: vec![T::zero(); capacity * len],
            len,
            clock: 0,
        }
    }

    /// Slab `i` made by `make` into a slot unless it is kept already; the
    /// slot taken is the least recently used one that holds no slab of
    /// `window` (there is one: the capacity exceeds the window).
    fn ensure(&mut self, i: usize, window: &[Option<usize>], make: impl FnOnce(&mut [T])) {
        self.clock += 1;
        if let Some(s) = self.rows.iter().position(|&r| r == Some(i)) {
            self.used[s] = self.clock;
            return;
        }
        let free = (0..self.rows.len())
            .filter(|&s| self.rows[s].is_none_or(|r| !window.contains(&Some(r))))
            .min_by_key(|&s| self.used[s])
            .unwrap_or(0);
        make(&mut self.data[free * self.len..(free + 1) * self.len]);
        self.rows[free] = Some(i);
        self.used[free] = self.clock;
    }

    /// Slab `i` (made by [`Self::ensure`]).
    fn slab(&self, i: usize) -> &[T] {
        let s = self.rows.iter().position(|&r| r == Some(i)).unwrap_or(0);
        &self.data[s * self.len..(s + 1) * self.len]
    }
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
    /// Results of another type than `T`: [`Self::resample_grid_as`].
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
        self.resample_grid_as(coordinates, deriv, out)
    }

    /// [`Self::resample_grid`] into results of any type `O` the compute
    /// type stores into ([`Stored`]: `f32` results of an `f64`
    /// interpolant): the last step (axis 0) computes each row of the output
    /// in `T` and stores it rounded once (a row, or 2048 values of a 1-D
    /// output, at a time; no `T` copy of `out`); the values of
    /// [`Self::resample_grid`] rounded once.
    pub fn resample_grid_as<O: Stored<T>>(
        &self,
        coordinates: &[&[f64]],
        deriv: &[u32],
        out: &mut [O],
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
        let shape: Vec<usize> = self.coeffs.shape().to_vec();
        let coeffs = self.coeffs.as_slice().expect("standard layout");
        if self.ndim() == 1 {
            self.apply_axis(coeffs, &shape, 0, &plans[0], out);
            return Ok(());
        }
        // Axis 0 last, by chunks of output rows on the pool, each row the
        // combination of the coefficient slabs its window reads, resampled
        // along the other axes (`trailing`) and kept in a cache of a few
        // slabs: no array of the whole resampled intermediate.
        let inner: usize = plans[1..].iter().map(AxisPlan::count).product();
        let rows = plans[0].count();
        if inner == 0 || rows == 0 {
            return Ok(());
        }
        // A few chunks per thread: each makes up to a window of slabs again
        // where it starts.
        let per = rows.div_ceil((4 * rayon::current_num_threads()).min(rows));
        let plan = &plans[0];
        out.par_chunks_mut(per * inner)
            .enumerate()
            .for_each(|(c, block)| {
                let mut cache = SlabCache::new(plan.m + 1, inner);
                let mut work = (Vec::new(), Vec::new());
                let mut buf = Vec::new();
                for (j, row) in block.chunks_mut(inner).enumerate() {
                    let k = c * per + j;
                    let idx = &plan.index[k * plan.m..(k + 1) * plan.m];
                    let w = &plan.weight[k * plan.m..(k + 1) * plan.m];
                    for i in idx.iter().flatten() {
                        cache.ensure(*i, idx, |dst| {
                            self.trailing(coeffs, &shape, &plans, *i, &mut work, dst)
                        });
                    }
                    store_row(row, &mut buf, |row| {
                        combine_row(w, idx, |i| cache.slab(i), self.cval, row)
                    });
                }
            });
        Ok(())
    }

    /// The coefficient slab `i` of axis 0 (the padded array's `[i, …]`)
    /// resampled along every other axis, last first, into `dst` (the
    /// output's trailing shape), sequentially; `work` the two buffers the
    /// steps between go through.
    fn trailing(
        &self,
        coeffs: &[T],
        shape: &[usize],
        plans: &[AxisPlan<T>],
        i: usize,
        work: &mut (Vec<T>, Vec<T>),
        dst: &mut [T],
    ) {
        let len: usize = shape[1..].iter().product();
        let mut sub: Vec<usize> = shape[1..].to_vec();
        let slab = &coeffs[i * len..(i + 1) * len];
        let (a, b) = work;
        for axis in (1..shape.len()).rev() {
            let src: &[T] = if axis + 1 == shape.len() { slab } else { a };
            let mut next = sub.clone();
            next[axis - 1] = plans[axis].count();
            if axis == 1 {
                self.axis_into(src, &sub, axis - 1, &plans[axis], dst);
                break;
            }
            b.resize(next.iter().product(), T::zero());
            self.axis_into(src, &sub, axis - 1, &plans[axis], b);
            std::mem::swap(a, b);
            sub = next;
        }
    }

    /// [`Self::apply_axis`] in turn on this thread (within one task).
    fn axis_into(&self, src: &[T], shape: &[usize], a: usize, plan: &AxisPlan<T>, dst: &mut [T]) {
        let len = shape[a];
        let inner: usize = shape[a + 1..].iter().product();
        let count = plan.count();
        if inner == 1 {
            for (o, row) in dst.chunks_mut(count.max(1)).enumerate() {
                gather_rows(&src[o * len..(o + 1) * len], plan, self.cval, 0, row);
            }
            return;
        }
        for (r, row) in dst.chunks_mut(inner).enumerate() {
            let (o, k) = (r / count, r % count);
            let block = &src[o * len * inner..(o + 1) * len * inner];
            let (w, idx) = plan.window(k);
            combine_row(
                w,
                idx,
                |i| &block[i * inner..(i + 1) * inner],
                self.cval,
                row,
            );
        }
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
    /// `dst` (every element written; stored through [`Stored`], a row or a
    /// piece of [`GATHER`] values of one at a time, where `O` is not `T`).
    fn apply_axis<O: Stored<T>>(
        &self,
        src: &[T],
        shape: &[usize],
        a: usize,
        plan: &AxisPlan<T>,
        dst: &mut [O],
    ) {
        let len = shape[a];
        let inner: usize = shape[a + 1..].iter().product();
        let count = plan.count();
        let cval = self.cval;
        if inner == 1 {
            // Rows of `count` outputs, each in pieces of GATHER (a 1-D
            // output is one row).
            dst.par_chunks_mut(count.max(1))
                .with_min_len(4)
                .enumerate()
                .for_each(|(o, row)| {
                    let line = &src[o * len..(o + 1) * len];
                    row.par_chunks_mut(GATHER).enumerate().for_each_init(
                        Vec::new,
                        |buf, (p, piece)| {
                            store_row(piece, buf, |r| gather_rows(line, plan, cval, p * GATHER, r));
                        },
                    );
                });
            return;
        }
        dst.par_chunks_mut(inner)
            .with_min_len(64)
            .enumerate()
            .for_each_init(Vec::new, |buf, (r, row)| {
                let (o, k) = (r / count, r % count);
                let block = &src[o * len * inner..(o + 1) * len * inner];
                let (w, idx) = plan.window(k);
                store_row(row, buf, |row| {
                    combine_row(w, idx, |i| &block[i * inner..(i + 1) * inner], cval, row)
                });
            });
    }
}

/// Output values of the last axis that one task gathers at a time.
const GATHER: usize = 2048;

/// `fill` computes the values of `out` in `T`: into `out` itself where `O`
/// is `T`, else into `buf` (resized), then stored rounded once.
fn store_row<T: Real + Copy, O: Stored<T>>(
    out: &mut [O],
    buf: &mut Vec<T>,
    fill: impl FnOnce(&mut [T]),
) {
    if let Some(values) = O::as_compute_mut(out) {
        return fill(values);
    }
    buf.resize(out.len(), T::zero());
    fill(buf);
    O::store_from(buf, out);
}

/// `row = Σ_l w[l] · slab(index[l])` (`cval` where the index is outside),
/// added from zero in the window's order.
fn combine_row<'a, T: Real + Copy + 'a>(
    w: &[T],
    index: &[Option<usize>],
    slab: impl Fn(usize) -> &'a [T],
    cval: T,
    row: &mut [T],
) {
    row.fill(T::zero());
    for (wl, il) in w.iter().zip(index) {
        match il {
            Some(i) => axpy(*wl, slab(*i), row),
            None => row.iter_mut().for_each(|y| *y += *wl * cval),
        }
    }
}

/// The last axis: `row[j] = Σ_l w[k, l] · line[index[k, l]]` for the
/// output indices `k = first + j`.
fn gather_rows<T: Real + Copy>(
    line: &[T],
    plan: &AxisPlan<T>,
    cval: T,
    first: usize,
    row: &mut [T],
) {
    let m = plan.m;
    for (j, y) in row.iter_mut().enumerate() {
        let k = first + j;
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
                    let mut grid = vec![0.0f64; count];
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

    /// Each output row's bits do not depend on the chunk it falls in, on
    /// the slabs the cache holds or on the order of the rows: the same grid
    /// on 1 and 3 threads, and with axis 0's coordinates shuffled (windows
    /// that go back and forth, past the ends), row for row; f32 results the
    /// f64 ones rounded once.
    #[test]
    fn rows_do_not_depend_on_chunks_cache_or_order() {
        let data = ndarray::Array3::from_shape_fn((11, 9, 8), |(i, j, k)| {
            ((i * 7 + j * 3 + k) as f64 * 0.61).sin()
        });
        let f = Interpolant::<f64>::new(&data, Options::new(3, Mode::Mirror)).unwrap();
        let x0: Vec<f64> = (0..40).map(|k| -4.0 + k as f64 * 0.47).collect();
        let perm: Vec<usize> = (0..40).map(|k| (k * 17) % 40).collect();
        let shuffled: Vec<f64> = perm.iter().map(|&k| x0[k]).collect();
        let (x1, x2) = ([0.5, 2.25, 7.0], [0.0, 3.3, 6.9, 7.4]);
        let run = |threads: usize, first: &[f64]| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut out = vec![0.0f64; first.len() * 12];
            pool.install(|| f.resample_grid(&[first, &x1, &x2], &[0, 0, 0], &mut out))
                .unwrap();
            out
        };
        let one = run(1, &x0);
        assert_eq!(one, run(3, &x0));
        let mixed = run(3, &shuffled);
        for (r, &k) in perm.iter().enumerate() {
            assert_eq!(
                mixed[r * 12..(r + 1) * 12],
                one[k * 12..(k + 1) * 12],
                "row {k}"
            );
        }
        let mut narrow = vec![0.0f32; 40 * 12];
        f.resample_grid_as(&[&x0, &x1, &x2], &[0, 0, 0], &mut narrow)
            .unwrap();
        assert!(narrow.iter().zip(&one).all(|(n, w)| *n == *w as f32));
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
