//! Affine resampling by runs along the last output axis
//! ([`Interpolant::resample_affine`] for the fixed-size kernels of
//! `kernel.rs`): scipy's `rotate` and `affine_transform`.
//!
//! Why: along the last output axis the point of output `o` is `x_h(o) =
//! (r_h + o · m_h) + shift` (`affine.rs`), monotone in `o` on every input
//! axis `h` (each operation is a rounded monotone map), so the outputs of
//! a run whose point lies inside `[0, n_h − 1]` on every axis form one
//! interval of `o`, found by a binary search on the same expressions. Inside
//! it no point is checked against the rule, folded or prefetched (every
//! mode's fold is the identity there, and consecutive points read
//! neighbouring rows, which the cache already holds); the points are
//! generated per batch in lanes and go straight to the cells, weights and
//! sums of `kernel.rs`. Outside it, under scipy's `constant`
//! ([`PointRule::CvalOutside`]) every output is `cval` without forming a
//! point; under the other rules the points go through the general batch
//! path ([`Interpolant::eval_kernel`] with [`AffinePoints`]).
//!
//! **Same values**: the points are formed by the same operations in the
//! same order as [`AffinePoints`] forms them, the inside test is the
//! kernels' own (`0 ≤ x ≤ n − 1`), and the cells, weights and sums are the
//! kernels' functions, so the results equal those of the batch path bit
//! for bit (`tests::runs_equal_the_batch_path_bit_for_bit`).

use super::affine::AffinePoints;
use super::batch::{BATCH, store_chunks};
use super::kernel::{bases_in_lanes, cells_and_weights, sum_fixed};
use super::{Interpolant, PointRule};
use crate::ndimage::NdimageError;
use crate::ndimage::samples::Stored;
use crate::scalar::Real;
use multiversion::multiversion;

/// One run of outputs along the last output axis: the sums of the other
/// axes' terms `row_h`, the last axis' column `step_h`, and the index of
/// its first output on that axis.
struct Run<'a> {
    row: &'a [f64],
    step: &'a [f64],
    shift: f64,
    first: usize,
}

impl Run<'_> {
    /// The point of output `first + j` on input axis `h`, as
    /// [`AffinePoints`] forms it: `(r_h + o · m_h) + shift` with `o` exact
    /// in `f64` (an index below `2^53`).
    #[inline(always)]
    fn coordinate(&self, h: usize, j: usize) -> f64 {
        (self.row[h] + (self.first + j) as f64 * self.step[h]) + self.shift
    }

    /// The outputs `lo..hi` of a run of `len` whose point lies inside `[0,
    /// high_h]` on every axis (`lo == hi` when none does): on each axis the
    /// two tests are monotone in `j` (falling or rising with the sign of
    /// `m_h`), so each bounds the interval from one side, found by binary
    /// search.
    fn inside_span(&self, high: &[f64], len: usize) -> (usize, usize) {
        let (mut lo, mut hi) = (0, len);
        for (h, &top) in high.iter().enumerate() {
            let above_low = |j: usize| self.coordinate(h, j) >= 0.0;
            let below_top = |j: usize| self.coordinate(h, j) <= top;
            if self.step[h] >= 0.0 {
                lo = lo.max(leading(len, |j| !above_low(j)));
                hi = hi.min(leading(len, below_top));
            } else {
                lo = lo.max(leading(len, |j| !below_top(j)));
                hi = hi.min(leading(len, above_low));
            }
        }
        (lo, hi.max(lo))
    }

    /// Whether the points of outputs `a..b` are finite on every axis (a
    /// point is monotone in `j`, so its ends decide).
    fn finite_between(&self, a: usize, b: usize) -> bool {
        (0..self.row.len())
            .all(|h| self.coordinate(h, a).is_finite() && self.coordinate(h, b - 1).is_finite())
    }
}

/// How many leading `j` in `0..len` satisfy `holds`, a test that holds on
/// a prefix of `0..len` and fails after it (a binary search).
fn leading(len: usize, holds: impl Fn(usize) -> bool) -> usize {
    let (mut lo, mut hi) = (0, len);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if holds(mid) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    lo
}

impl<T: Real + Send + Sync> Interpolant<T> {
    /// Whether [`Self::eval_affine_runs`] serves this interpolant and rule:
    /// a fixed-size kernel, and for scipy's `wrap` every axis longer than one
    /// sample (its fold of a one-sample axis is `+0` even at `−0`).
    pub(super) fn has_run_kernel(&self, rule: PointRule) -> bool {
        self.has_kernel()
            && (rule != PointRule::WrapPeriodNMinus1 || self.shape.iter().all(|&n| n > 1))
    }

    /// The outputs of `src` into `out` by runs (module documentation), in
    /// parallel over chunks of [`CHUNK`] outputs.
    pub(super) fn eval_affine_runs<O: Stored<T>>(
        &self,
        src: &AffinePoints<'_>,
        out: &mut [O],
    ) -> Result<(), NdimageError> {
        store_chunks(out, |start, chunk| self.affine_chunk(src, start, chunk))
    }

    /// Outputs `start..start + out.len()` of `src`, run by run.
    fn affine_chunk(
        &self,
        src: &AffinePoints<'_>,
        start: usize,
        out: &mut [T],
    ) -> Result<(), NdimageError> {
        let n = self.ndim();
        // Input axes are at most 3 here (the kernels' range).
        let (mut step, mut high) = ([0.0; 3], [0.0; 3]);
        src.steps_and_tops(&mut step[..n], &mut high[..n]);
        src.for_each_run(start, out.len(), |done, first, len, row| {
            let run = Run {
                row,
                step: &step[..n],
                shift: src.shift,
                first,
            };
            let (lo, hi) = run.inside_span(&high[..n], len);
            let piece = &mut out[done..done + len];
            let (before, rest) = piece.split_at_mut(lo);
            let (inside, after) = rest.split_at_mut(hi - lo);
            self.outside_piece(src, &run, start + done, 0, before)?;
            self.inside_piece(&run, lo, inside);
            self.outside_piece(src, &run, start + done, hi, after)
        })
    }

    /// Outputs `at..at + out.len()` of a run (flat index of its first
    /// output `flat`) whose points lie outside the grid on some axis:
    /// `cval` under [`PointRule::CvalOutside`] (when finite: an infinite
    /// point is the batch path's error), else the batch path.
    fn outside_piece(
        &self,
        src: &AffinePoints<'_>,
        run: &Run<'_>,
        flat: usize,
        at: usize,
        out: &mut [T],
    ) -> Result<(), NdimageError> {
        if out.is_empty() {
            return Ok(());
        }
        if src.rule == PointRule::CvalOutside && run.finite_between(at, at + out.len()) {
            out.fill(self.cval.clone());
            return Ok(());
        }
        self.eval_kernel(src, flat + at, out)
    }

    /// Outputs `at..at + out.len()` of a run, every point inside the grid,
    /// by the kernel of this interpolant's dimension and order.
    fn inside_piece(&self, run: &Run<'_>, at: usize, out: &mut [T]) {
        macro_rules! by_order {
            ($d:literal) => {
                match self.order {
                    1 => self.inside_fixed::<$d, 1>(run, at, out),
                    2 => self.inside_fixed::<$d, 2>(run, at, out),
                    3 => self.inside_fixed::<$d, 3>(run, at, out),
                    4 => self.inside_fixed::<$d, 4>(run, at, out),
                    5 => self.inside_fixed::<$d, 5>(run, at, out),
                    _ => self.inside_fixed::<$d, 6>(run, at, out),
                }
            };
        }
        match self.ndim() {
            1 => by_order!(1),
            2 => by_order!(2),
            _ => by_order!(3),
        }
    }

    /// [`Self::inside_piece`] for dimension `D` and order `M`: batches of
    /// [`BATCH`] points formed axis by axis in lanes, then the kernels'
    /// cells and weights ([`cells_and_weights`]), offsets
    /// ([`Self::base_fixed`]) and sums ([`sum_fixed`]).
    fn inside_fixed<const D: usize, const M: usize>(
        &self,
        run: &Run<'_>,
        at: usize,
        out: &mut [T],
    ) {
        if out.is_empty() {
            return;
        }
        let c = self.coeffs.as_slice().expect("standard layout");
        let mut xs = [[0.0; BATCH]; D];
        let mut firsts = [[0.0; BATCH]; D];
        let mut ws: [[[T; BATCH]; M]; D] =
            std::array::from_fn(|_| std::array::from_fn(|_| std::array::from_fn(|_| T::zero())));
        let mut fallback = None;
        let (pad, top, strides) = self.lane_bounds::<D, M>();
        let mut bases = [0; BATCH];
        for (b, batch) in out.chunks_mut(BATCH).enumerate() {
            let from = (run.first + at + b * BATCH) as f64;
            for (h, x) in xs.iter_mut().enumerate() {
                points_in_lanes(run.row[h], run.step[h], run.shift, from, x);
            }
            for a in 0..D {
                cells_and_weights::<T, M>(&xs[a], &mut firsts[a], &mut ws[a]);
            }
            // Every window of a full batch inside the padded coefficients
            // (always, for points inside the grid): the offsets in lanes;
            // else (a short last batch, whose unused lanes run past the
            // run) point by point.
            if batch.len() == BATCH && bases_in_lanes(&firsts, pad, &top, &strides, &mut bases) {
                for (j, o) in batch.iter_mut().enumerate() {
                    *o = sum_fixed::<T, D, M>(c, bases[j], &ws, j, &self.strides);
                }
                continue;
            }
            for (j, o) in batch.iter_mut().enumerate() {
                *o = match self.base_fixed::<D, M>(&xs, &mut firsts, &mut ws, j) {
                    Some(base) => sum_fixed::<T, D, M>(c, base, &ws, j, &self.strides),
                    None => {
                        let x: [f64; D] = std::array::from_fn(|h| xs[h][j]);
                        self.eval_slow(&x, &mut fallback)
                    }
                };
            }
        }
    }
}

/// The points `x_j = (row + (first + j) · step) + shift` of a batch on one
/// axis ([`Run::coordinate`]'s operations; `first + j` is exact), in lanes.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma"))]
fn points_in_lanes(row: f64, step: f64, shift: f64, first: f64, x: &mut [f64; BATCH]) {
    for (j, xj) in x.iter_mut().enumerate() {
        *xj = (row + (first + j as f64) * step) + shift;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prelude::*;
    use ndarray::{ArrayD, Dimension, IxDyn};

    /// Samples with values in `[−1, 1]` from an integer hash (no libm).
    fn samples(shape: &[usize]) -> ArrayD<f64> {
        ArrayD::from_shape_fn(IxDyn(shape), |ix| {
            let k = ix.slice().iter().fold(11, |k, &i| k * 131 + i * 97);
            (k * 7919 % 257) as f64 / 128.0 - 1.0
        })
    }

    /// `resample_affine` (by runs where [`Interpolant::has_run_kernel`])
    /// against the batch path on the same generated points
    /// ([`Interpolant::eval_source`] with [`AffinePoints`]), bit for bit; the
    /// number of outputs that differ from `cval` is returned, so a caller can
    /// see that both inside and outside points were met.
    fn compare<T: Real + Copy + Send + Sync + std::fmt::Debug>(
        f: &Interpolant<T>,
        matrix: &[f64],
        offset: &[f64],
        out_shape: &[usize],
        shift: f64,
        rule: PointRule,
    ) -> usize {
        assert!(f.has_run_kernel(rule));
        let count = out_shape.iter().product();
        let mut runs = vec![T::zero(); count];
        f.resample_affine(matrix, offset, out_shape, shift, rule, &mut runs)
            .unwrap();
        let src = f.affine_points(matrix, offset, out_shape, shift, rule);
        let mut batch = vec![T::zero(); count];
        f.eval_source(&src, &mut batch).unwrap();
        for (k, (r, b)) in runs.iter().zip(&batch).enumerate() {
            assert!(
                r.to_f64().to_bits() == b.to_f64().to_bits(),
                "output {k} of {out_shape:?}, {rule:?}, {:?} degree {}: {r:?} != {b:?}",
                f.mode(),
                f.degree()
            );
        }
        runs.iter()
            .filter(|v| v.to_f64() != f.cval.to_f64())
            .count()
    }

    /// Rotations (runs crossing cell boundaries, entering and leaving the
    /// grid, both signs of the step), a transpose and a constant step (whole
    /// runs inside or outside), integer offsets whose points fall exactly on
    /// the grid's ends, every mode, degrees 0 to 5, f64 and f32, 1 to 3
    /// dimensions, runs longer than a chunk: the runs equal the batch path
    /// bit for bit under every rule.
    #[test]
    fn runs_equal_the_batch_path_bit_for_bit() {
        let modes = Mode::ALL;
        let rules = [
            PointRule::Fold,
            PointRule::CvalOutside,
            PointRule::WrapPeriodNMinus1,
        ];
        let (c, s) = (0.52f64.cos(), 0.52f64.sin());
        let d2 = samples(&[23, 19]);
        let cases_2d: [(&[f64], &[f64], &[usize]); 5] = [
            (&[c, s, -s, c], &[-4.25, 6.5], &[31, 29]),
            (&[-c, s, s, c], &[30.0, -3.0], &[9, 2100]),
            (&[0.0, 1.0, 1.0, 0.0], &[0.0, 0.0], &[19, 23]),
            (&[1.0, 0.0, 0.0, 0.0], &[-2.0, 5.5], &[27, 40]),
            (&[1.0, 0.0, 0.0, -1.0], &[0.0, 18.0], &[23, 25]),
        ];
        let mut inside = 0;
        for mode in modes {
            for degree in 0..=5 {
                let mut opts = Options::new(degree, mode);
                opts.cval = 0.625;
                let f = Interpolant::<f64>::new(&d2, opts).unwrap();
                let g = Interpolant::<f32>::new(&d2.mapv(|v| v as f32), opts).unwrap();
                for (m, off, shape) in cases_2d {
                    for rule in rules {
                        inside += compare(&f, m, off, shape, 0.0, rule);
                        inside += compare(&g, m, off, shape, 0.0, rule);
                    }
                }
                // scipy's pre-padding shift, and a 1-D input read by a 2-D output.
                inside += compare(&f, &[c, s, -s, c], &[-1.0, 2.0], &[30, 30], 12.0, rules[1]);
                let d1 = samples(&[17]);
                let h = Interpolant::<f64>::new(&d1, opts).unwrap();
                for rule in rules {
                    inside += compare(&h, &[0.3, -0.7], &[4.0], &[13, 11], 0.0, rule);
                }
            }
        }
        let d3 = samples(&[9, 8, 10]);
        let m3 = [0.9, 0.1, 0.05, -0.1, 0.95, 0.02, 0.03, -0.02, 1.05];
        for mode in [Mode::Mirror, Mode::Nearest, Mode::GridConstant] {
            for degree in [0, 1, 3, 5] {
                let f = Interpolant::<f64>::new(&d3, Options::new(degree, mode)).unwrap();
                for rule in rules {
                    inside += compare(&f, &m3, &[-0.5, 0.25, -1.0], &[10, 9, 12], 0.0, rule);
                }
            }
        }
        assert!(inside > 100_000, "{inside}");
    }

    /// A point that overflows to infinity is the batch path's error under
    /// every rule, also where the runs would give `cval`.
    #[test]
    fn infinite_points_are_errors() {
        let f = Interpolant::<f64>::new(&samples(&[6, 7]), Options::new(3, Mode::Mirror)).unwrap();
        let mut out = vec![0.0; 4];
        for rule in [
            PointRule::Fold,
            PointRule::CvalOutside,
            PointRule::WrapPeriodNMinus1,
        ] {
            let err = f
                .resample_affine(
                    &[1.0, 0.0, 0.0, f64::MAX],
                    &[0.0, f64::MAX],
                    &[2, 2],
                    0.0,
                    rule,
                    &mut out,
                )
                .unwrap_err();
            assert!(
                matches!(err, NdimageError::NonFiniteCoordinate(_)),
                "{err:?}"
            );
        }
    }

    /// `leading` counts the prefix where a test holds, for empty, full and
    /// partial prefixes.
    #[test]
    fn leading_counts_the_prefix() {
        assert_eq!(leading(0, |_| true), 0);
        assert_eq!(leading(10, |_| true), 10);
        assert_eq!(leading(10, |_| false), 0);
        for cut in 0..=10 {
            assert_eq!(leading(10, |j| j < cut), cut);
        }
    }
}
