//! The padded coefficient array of an [`Interpolant`](super::Interpolant):
//! the coefficients with `pad` more on each side of each axis, extended by
//! the boundary mode, in C order.
//!
//! Why not [`padded_extension`](crate::ndimage::nd_prefilter::padded_extension)
//! lane by lane: along a strided axis each lane is a column, read one
//! element per cache line (measured: about 70 ms of a 2048² rotation's
//! 300 ms). Here the array is written once, row by row of the last axis:
//! each output row is one source row (the fold of its other indices)
//! copied as a slice, with `pad` folded values at each end.
//!
//! **Same values** as `padded_extension`: element `j` of a padded axis is
//! source element [`Mode::fold`]`(j − pad)` (`cval` where it is `None`), the
//! rule `padded_extension` and [`LineFilter`](crate::ndimage::LineFilter)'s
//! symmetric padding use; copies only, no rounding
//! (`padding.rs::tests::extension_equals_the_lane_by_lane_one`).

use crate::ndimage::mode::Mode;
use crate::scalar::Real;
use ndarray::{ArrayBase, ArrayD, Data, Dimension, IxDyn};
use rayon::prelude::*;

/// `a` extended by `pad` values beyond each end of each axis as `mode`
/// extends samples (`cval` where the mode gives none), C order.
pub(super) fn extend_padded<T, S, D>(
    a: &ArrayBase<S, D>,
    mode: Mode,
    cval: &T,
    pad: usize,
) -> ArrayD<T>
where
    T: Real + Send + Sync,
    S: Data<Elem = T>,
    D: Dimension,
{
    if a.ndim() == 0 {
        return a.to_owned().into_dyn();
    }
    let a = a.as_standard_layout();
    let src = a.as_slice().expect("standard layout");
    let shape = a.shape();
    let nd = shape.len();
    let padded: Vec<usize> = shape.iter().map(|n| n + 2 * pad).collect();
    // Per axis, the source index of every padded index (None: cval).
    let maps: Vec<Vec<Option<usize>>> = shape
        .iter()
        .map(|&n| {
            (0..n + 2 * pad)
                .map(|j| mode.fold(j as i64 - pad as i64, n))
                .collect()
        })
        .collect();
    let mut src_strides = vec![1; nd];
    for k in (0..nd.saturating_sub(1)).rev() {
        src_strides[k] = src_strides[k + 1] * shape[k + 1];
    }
    let (n_last, row_len) = (shape[nd - 1], padded[nd - 1]);
    let total: usize = padded.iter().product();
    let mut out = vec![T::zero(); total];
    out.par_chunks_mut(row_len)
        .enumerate()
        .for_each(|(r, row)| {
            // The source row: the fold of the row's leading indices.
            let (mut rest, mut base) = (r, Some(0));
            for k in (0..nd - 1).rev() {
                let j = rest % padded[k];
                rest /= padded[k];
                base = base.zip(maps[k][j]).map(|(b, i)| b + i * src_strides[k]);
            }
            let Some(base) = base else {
                row.fill(cval.clone());
                return;
            };
            let line = &src[base..base + n_last];
            row[pad..pad + n_last].clone_from_slice(line);
            let last = &maps[nd - 1];
            for j in (0..pad).chain(pad + n_last..row_len) {
                row[j] = last[j].map_or_else(|| cval.clone(), |i| line[i].clone());
            }
        });
    ArrayD::from_shape_vec(IxDyn(&padded), out).expect("padded shape")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ndimage::nd_prefilter::padded_extension;

    /// Every mode, 1-D to 3-D, pads shorter and longer than the axes: the
    /// same array as the lane-by-lane `padded_extension`.
    #[test]
    fn extension_equals_the_lane_by_lane_one() {
        for shape in [&[5usize][..], &[3, 4], &[2, 3, 1], &[1, 1]] {
            let a = ArrayD::from_shape_fn(IxDyn(shape), |i| {
                i.slice()
                    .iter()
                    .fold(0.0, |s, &k| s * 10.0 + k as f64 + 1.0)
            });
            for mode in Mode::ALL {
                for pad in [0, 2, 7] {
                    let ours = extend_padded(&a, mode, &-0.5, pad);
                    let lanes = padded_extension(&a, mode, -0.5, pad).unwrap();
                    assert_eq!(ours, lanes, "{shape:?} {mode} pad {pad}");
                }
            }
        }
    }
}
