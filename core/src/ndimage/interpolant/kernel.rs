//! Fixed-size evaluation kernels: [`Interpolant::eval_many`] and
//! [`Interpolant::resample_affine`] for 1 to 3 dimensions and degrees 1 to
//! 5 (scipy's range) at `f64`/`f32` precision, with the dimension `D` and
//! the order `M = degree + 1` known to the compiler.
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
//! (`verify/tests/engine_batch.rs::batch_equals_single_point_evaluation`).
//! In `f32` the weights are rounded once from `f64`, as there.

use super::batch::{BATCH, PointSource, prefetch};
use super::weights::closed_form;
use super::{Interpolant, Scratch};
use crate::ndimage::NdimageError;
use crate::scalar::Real;
use crate::sspline::bspline_uniform::centred_cell;

/// [`centred_cell`] for order `M`, the same `(first, u)`, without a call
/// to libm's `floor` (not inlined on the x86-64 baseline): below `2^52` in
/// magnitude `⌊x⌋` is the truncation `x as i64`, less one where that
/// exceeds `x`; beyond, `centred_cell` itself.
#[inline(always)]
fn cell_of<const M: usize>(x: f64) -> (i64, f64) {
    const EXACT: f64 = (1u64 << 52) as f64;
    if x.abs() >= EXACT || x.is_nan() {
        return centred_cell(M as u32, x);
    }
    let i = x as i64;
    let i = if (i as f64) > x { i - 1 } else { i };
    let t = x - i as f64;
    let half = (M / 2) as i64;
    let (fl, u) = if M.is_multiple_of(2) {
        (i + half, t)
    } else if t >= 0.5 {
        (i + half + 1, t - 0.5)
    } else {
        (i + half, t + 0.5)
    };
    (fl - M as i64 + 1, u)
}

impl<T: Real + Send + Sync> Interpolant<T> {
    /// Whether a fixed-size kernel serves this interpolant: `f64`/`f32`
    /// precision, 1 to 3 dimensions, degree 1 to 5.
    pub(super) fn has_kernel(&self) -> bool {
        T::BITS <= 53 && (1..=3).contains(&self.ndim()) && (2..=6).contains(&self.order)
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
        macro_rules! by_order {
            ($d:literal) => {
                match self.order {
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

    /// [`Self::eval_kernel`] for dimension `D` and order `M`: batches of
    /// [`BATCH`] points located (rows prefetched), then summed; a point
    /// whose window leaves the padded coefficients (`grid-constant` far
    /// outside) by the general [`Interpolant::eval_in`].
    fn eval_fixed<S: PointSource, const D: usize, const M: usize>(
        &self,
        src: &S,
        start: usize,
        out: &mut [T],
    ) -> Result<(), NdimageError> {
        let c = self.coeffs.as_slice().expect("standard layout");
        let mut xs = [0.0; BATCH * 3];
        let mut take_cval = [false; BATCH];
        // Weights and first offsets of a batch, written in place (no
        // per-point initialisation or move).
        let mut ws: [[[T; M]; D]; BATCH] =
            std::array::from_fn(|_| std::array::from_fn(|_| std::array::from_fn(|_| T::zero())));
        let mut bases = [None; BATCH];
        let mut fallback = None;
        for (b, batch) in out.chunks_mut(BATCH).enumerate() {
            let n = batch.len();
            src.fill(start + b * BATCH, &mut xs[..n * D], &mut take_cval[..n])?;
            for (j, o) in batch.iter_mut().enumerate() {
                bases[j] = None;
                if take_cval[j] {
                    *o = self.cval.clone();
                    continue;
                }
                let x: &[f64; D] = xs[j * D..(j + 1) * D].try_into().expect("D coordinates");
                bases[j] = self.locate_fixed::<D, M>(x, &mut ws[j]);
                match bases[j] {
                    Some(base) => self.prefetch_fixed::<D, M>(c, base),
                    None => *o = self.eval_slow(x, &mut fallback),
                }
            }
            for ((o, base), w) in batch.iter_mut().zip(&bases).zip(&ws) {
                if let Some(base) = *base {
                    *o = sum_fixed::<T, D, M>(c, base, w, &self.strides);
                }
            }
        }
        Ok(())
    }

    /// The general single-point evaluation, its work space made on first use.
    fn eval_slow(&self, x: &[f64], space: &mut Option<(Vec<T>, Vec<usize>, Vec<bool>)>) -> T {
        let (w, off, inside) = space.get_or_insert_with(|| self.scratch());
        let zero = [0; 3];
        let mut sc = Scratch { w, off, inside };
        self.eval_in(x, &zero[..x.len()], &mut sc)
    }

    /// The weights of `x` on every axis into `w` and the flat offset of its
    /// first coefficient (folded by the mode unless inside `[0, n − 1]`), or
    /// `None` when its window leaves the padded coefficients.
    #[inline(always)]
    fn locate_fixed<const D: usize, const M: usize>(
        &self,
        x: &[f64; D],
        w: &mut [[T; M]; D],
    ) -> Option<usize> {
        let mut base = 0;
        for a in 0..D {
            let n = self.shape[a];
            let xa = if x[a] >= 0.0 && x[a] <= (n - 1) as f64 {
                x[a]
            } else {
                self.coordinate(x[a], a)
            };
            let (first, u) = cell_of::<M>(xa);
            let i0 = first + self.pad as i64;
            if i0 < 0 || i0 as usize + M > n + 2 * self.pad {
                return None;
            }
            base += i0 as usize * self.strides[a];
            let f = closed_form::<M>(u).expect("kernels serve orders 2 to 6");
            for (t, v) in w[a].iter_mut().zip(f) {
                *t = T::from_f64_exact(v);
            }
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

/// `Σ_l w[l] · row[l]` over one row of `M` coefficients, from zero.
#[inline(always)]
fn dot<T: Real, const M: usize>(w: &[T; M], row: &[T]) -> T {
    let row: &[T; M] = row[..M].try_into().expect("M coefficients");
    let mut sum = T::zero();
    for l in 0..M {
        sum += w[l].clone() * &row[l];
    }
    sum
}

/// The tensor sum of a located point, in the order of
/// [`Interpolant::tensor_sum`]: rows of the last axis dotted, then weighted
/// by the middle axis, then by the first.
#[inline(always)]
fn sum_fixed<T: Real, const D: usize, const M: usize>(
    c: &[T],
    base: usize,
    w: &[[T; M]; D],
    strides: &[usize],
) -> T {
    // A slice, so that the arms of the other dimensions index it without
    // constant out-of-bounds indices.
    let w: &[[T; M]] = w;
    match D {
        1 => dot(&w[0], &c[base..]),
        2 => {
            let mut sum = T::zero();
            for l0 in 0..M {
                let at = base + l0 * strides[0];
                sum += w[0][l0].clone() * dot(&w[1], &c[at..]);
            }
            sum
        }
        _ => {
            let mut sum = T::zero();
            for l0 in 0..M {
                let mut plane = T::zero();
                for l1 in 0..M {
                    let at = base + l0 * strides[0] + l1 * strides[1];
                    plane += w[1][l1].clone() * dot(&w[2], &c[at..]);
                }
                sum += w[0][l0].clone() * plane;
            }
            sum
        }
    }
}
