//! The padded coefficient array of an [`Interpolant`](super::Interpolant):
//! the coefficients with `pad` more on each side of each axis, extended by
//! the boundary mode, in C order.
//!
//! Two ways to it. [`extend_padded`] copies a source array (given
//! coefficients, or samples for degrees 0 and 1, widened into `T` as they
//! are read) into a new padded array, row by row. The prefiltered route
//! makes no second array: the coefficients are computed into the front of
//! the padded allocation in their compact C order, moved to their padded
//! places in place ([`relocate_to_padded`]), and the pads are filled from
//! them in place ([`extend_in_place`]) — one input-sized array where the
//! filter-then-copy route held two (3.9 GB for a 2 GB float64 input).
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
//! (`padding.rs::tests::extension_equals_the_lane_by_lane_one`,
//! `in_place_extension_equals_the_copying_one`).

use crate::ndimage::NdimageError;
use crate::ndimage::alloc::{try_padded_zeros, try_standard_layout, try_with_capacity};
use crate::ndimage::mode::Mode;
use crate::ndimage::nd_prefilter::scan_block;
use crate::ndimage::samples::Sample;
use crate::scalar::Real;
use ndarray::{ArrayBase, ArrayD, Data, Dimension, IxDyn};
use rayon::prelude::*;

/// `a` (read into `T`) extended by `pad` values beyond each end of each
/// axis as `mode` extends samples (`cval` where the mode gives none), C
/// order, and whether every element of `a` is finite (each row scanned as
/// it is copied, [`scan_block`]: no separate pass over `a`). The array is
/// allocated fallibly ([`NdimageError::OutOfMemory`]).
pub(super) fn extend_padded<T, E, S, D>(
    a: &ArrayBase<S, D>,
    mode: Mode,
    cval: &T,
    pad: usize,
) -> Result<(ArrayD<T>, bool), NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    S: Data<Elem = E>,
    D: Dimension,
{
    if a.ndim() == 0 {
        // Allocated fallibly: a zero-stride view can ask for far more
        // than the memory it occupies (issue 42).
        let mut v = try_with_capacity(a.len(), "the spline coefficients")?;
        v.extend(a.iter().map(Sample::widen));
        let finite = v.iter().all(|x: &T| x.is_finite());
        let c = ArrayD::from_shape_vec(IxDyn(a.shape()), v).map_err(|_| {
            NdimageError::BufferLength {
                expected: a.len(),
                got: 0,
            }
        })?;
        return Ok((c, finite));
    }
    let a = try_standard_layout(a, "a C-ordered copy of the input")?;
    let src = a.as_slice().ok_or(NdimageError::BufferLength {
        expected: a.len(),
        got: 0,
    })?;
    let shape = a.shape();
    let nd = shape.len();
    let (padded, mut out) = try_padded_zeros::<T>(shape, pad, "padded coefficients")?;
    // Per axis, the source index of every padded index (None: cval).
    let maps: Vec<Vec<Option<usize>>> = shape
        .iter()
        .map(|&n| {
            (0..n + 2 * pad)
                .map(|j| mode.fold(j as i64 - pad as i64, n))
                .collect()
        })
        .collect();
    let sources = row_sources(&maps[..nd - 1], shape)?;
    let (n_last, row_len) = (shape[nd - 1], padded[nd - 1]);
    let finite = out
        .par_chunks_mut(row_len.max(1))
        .zip(sources.par_iter())
        .map(|(row, base)| {
            let Some(base) = *base else {
                row.fill(cval.clone());
                return true;
            };
            let line = &src[base..base + n_last];
            E::widen_into(line, &mut row[pad..pad + n_last]);
            let last = &maps[nd - 1];
            for j in (0..pad).chain(pad + n_last..row_len) {
                row[j] = last[j].map_or_else(|| cval.clone(), |i| row[pad + i].clone());
            }
            scan_block(&row[pad..pad + n_last]).0
        })
        .reduce(|| true, |a, b| a & b);
    let expected = out.len();
    let out = ArrayD::from_shape_vec(IxDyn(&padded), out)
        .map_err(|_| NdimageError::BufferLength { expected, got: 0 })?;
    Ok((out, finite))
}

/// The source offset (in the C-ordered source of `shape`) of every padded
/// row, in C order over the padded leading axes (`maps`, one per axis but
/// the last: each padded index's source index, `None` for `cval`); `None`
/// where a leading index is `cval`'s. Built axis by axis, one addition per
/// row, where each row on its own took a division and a remainder per
/// axis. Allocated fallibly.
fn row_sources(
    maps: &[Vec<Option<usize>>],
    shape: &[usize],
) -> Result<Vec<Option<usize>>, NdimageError> {
    let rows = maps.iter().map(Vec::len).product::<usize>();
    let mut sources = try_with_capacity(rows, "the padded rows' sources")?;
    sources.push(Some(0));
    let mut next = try_with_capacity(rows, "the padded rows' sources")?;
    for (k, map) in maps.iter().enumerate() {
        // The source stride of axis `k`: the product of the later extents.
        let stride = shape[k + 1..].iter().product::<usize>();
        next.clear();
        for base in &sources {
            next.extend(
                map.iter()
                    .map(|i| base.zip(*i).map(|(b, i)| b + i * stride)),
            );
        }
        std::mem::swap(&mut sources, &mut next);
    }
    Ok(sources)
}

/// The padded layout of `shape`: the padded shape and its C-order strides.
fn padded_layout(shape: &[usize], pad: usize) -> (Vec<usize>, Vec<usize>) {
    let padded: Vec<usize> = shape.iter().map(|n| n + 2 * pad).collect();
    let mut strides = vec![1; shape.len()];
    for k in (0..shape.len().saturating_sub(1)).rev() {
        strides[k] = strides[k + 1] * padded[k + 1];
    }
    (padded, strides)
}

/// Moves the C-order array of `shape` held in `buf[..N]` (`N` its size) to
/// its places in the padded layout of `buf` (each axis grown by `pad` on
/// both sides, C order): row `r` of the last axis, at `r·ν` before, goes
/// to `dest(r) = Σ_k (i_k + pad)·P_k + pad`. Every row moves up
/// (`dest(r) ≥ r·ν`, and `dest(r + 1) ≥ dest(r) + ν`), so the rows move
/// from the last one down, in stages: the rows `lo..hi` whose
/// destinations all lie above the sources of rows `0..hi` are copied in
/// parallel, then the stage below. The pads hold unspecified values after
/// it ([`extend_in_place`] fills them). Copies only.
pub(super) fn relocate_to_padded<T: Real + Send + Sync>(
    buf: &mut [T],
    shape: &[usize],
    pad: usize,
) {
    let nd = shape.len();
    if nd == 0 || pad == 0 {
        return;
    }
    let len = shape[nd - 1];
    let rows: usize = shape[..nd - 1].iter().product();
    if len == 0 || rows == 0 {
        return;
    }
    let (_, strides) = padded_layout(shape, pad);
    let dest = |r: usize| {
        let (mut rest, mut at) = (r, pad);
        for k in (0..nd - 1).rev() {
            at += (rest % shape[k] + pad) * strides[k];
            rest /= shape[k];
        }
        at
    };
    let mut hi = rows;
    while hi > 0 {
        // The first row whose destination starts at or above the end of
        // the sources of rows 0..hi (destinations increase with r).
        let (mut lo, mut top) = (0, hi);
        while lo < top {
            let mid = (lo + top) / 2;
            if dest(mid) < hi * len {
                lo = mid + 1;
            } else {
                top = mid;
            }
        }
        if lo == hi {
            // Row hi − 1's destination overlaps its own source (one
            // dimension only): moved up element by element from its end.
            let (from, to) = ((hi - 1) * len, dest(hi - 1));
            for i in (0..len).rev() {
                let v = buf[from + i].clone();
                buf[to + i] = v;
            }
            hi -= 1;
            continue;
        }
        let start = dest(lo);
        let (sources, above) = buf.split_at_mut(start);
        let mut targets = Vec::with_capacity(hi - lo);
        let (mut rest, mut at) = (above, start);
        for r in lo..hi {
            let d = dest(r);
            let (_, tail) = std::mem::take(&mut rest).split_at_mut(d - at);
            let (row, tail) = tail.split_at_mut(len);
            targets.push((r, row));
            (rest, at) = (tail, d + len);
        }
        let sources = &*sources;
        targets
            .into_par_iter()
            .with_min_len((1 << 14) / len.max(1) + 1)
            .for_each(|(r, row)| row.clone_from_slice(&sources[r * len..(r + 1) * len]));
        hi = lo;
    }
}

/// Fills the pads of the padded array `buf` (of the padded layout of
/// `shape`, its interior already holding the array) as [`extend_padded`]
/// does: element `j` of a padded axis is interior element
/// [`Mode::fold`]`(j − pad)`, `cval` where it is `None`. The last axis'
/// pads of every interior row first, then for each axis from the last but
/// one to the first the pad blocks of that axis, each a copy of a
/// complete interior block (or `cval`); blocks in parallel. Copies only.
pub(super) fn extend_in_place<T: Real + Send + Sync>(
    buf: &mut [T],
    shape: &[usize],
    mode: Mode,
    cval: &T,
    pad: usize,
) {
    if pad == 0 || shape.is_empty() || shape.contains(&0) {
        return;
    }
    let (padded, _) = padded_layout(shape, pad);
    extend_block(buf, shape, &padded, mode, cval, pad);
}

/// [`extend_in_place`] of one block: the axes `shape` (the trailing ones)
/// at interior indices of the leading ones, `block` exactly its elements.
fn extend_block<T: Real + Send + Sync>(
    block: &mut [T],
    shape: &[usize],
    padded: &[usize],
    mode: Mode,
    cval: &T,
    pad: usize,
) {
    let n = shape[0];
    let fold = |j: usize| mode.fold(j as i64 - pad as i64, n);
    if shape.len() == 1 {
        for j in (0..pad).chain(pad + n..n + 2 * pad) {
            block[j] = fold(j).map_or_else(|| cval.clone(), |i| block[pad + i].clone());
        }
        return;
    }
    let sub = block.len() / padded[0];
    let (head, rest) = block.split_at_mut(pad * sub);
    let (mid, tail) = rest.split_at_mut(n * sub);
    mid.par_chunks_mut(sub)
        .with_min_len((1 << 14) / sub + 1)
        .for_each(|b| extend_block(b, &shape[1..], &padded[1..], mode, cval, pad));
    let mid = &*mid;
    let copy = |j: usize, b: &mut [T]| match fold(j) {
        Some(i) => b.clone_from_slice(&mid[i * sub..(i + 1) * sub]),
        None => b.fill(cval.clone()),
    };
    head.par_chunks_mut(sub)
        .enumerate()
        .for_each(|(j, b)| copy(j, b));
    tail.par_chunks_mut(sub)
        .enumerate()
        .for_each(|(t, b)| copy(pad + n + t, b));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ndimage::alloc::try_zeros;
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
                    let (ours, finite) = extend_padded(&a, mode, &-0.5, pad).unwrap();
                    let lanes = padded_extension(&a, mode, -0.5, pad).unwrap();
                    assert_eq!(ours, lanes, "{shape:?} {mode} pad {pad}");
                    assert!(finite);
                }
            }
        }
    }

    /// The advised vectors hold `n` zeros whatever their size and
    /// alignment: below the 4 MiB threshold, at it, and above it with a
    /// length that leaves a partial page at the end.
    #[test]
    fn huge_page_zeros_are_zeros() {
        for n in [0, 1, 1000, (4 << 20) / 8, (5 << 20) / 8 + 3] {
            let v: Vec<f64> = try_zeros(n, "test").unwrap();
            assert_eq!(v.len(), n);
            assert!(v.iter().all(|&x| x.to_bits() == 0), "{n}");
        }
        let v: Vec<f32> = try_zeros((9 << 20) / 4 + 1, "test").unwrap();
        assert!(v.iter().all(|&x| x.to_bits() == 0));
    }

    /// The one-array route (the compact array at the front of the padded
    /// allocation, moved up in place, its pads filled in place) against
    /// the copying [`extend_padded`] of the same array, bit for bit: every
    /// mode, 1-D to 4-D, axes of one sample, pads shorter and longer than
    /// the axes.
    #[test]
    fn in_place_extension_equals_the_copying_one() {
        let shapes: [&[usize]; 7] = [
            &[5],
            &[1],
            &[3, 4],
            &[1, 7],
            &[2, 3, 1],
            &[4, 1, 5],
            &[2, 3, 2, 3],
        ];
        for shape in shapes {
            let a = ArrayD::from_shape_fn(IxDyn(shape), |i| {
                i.slice()
                    .iter()
                    .fold(0.0, |s, &k| s * 10.0 + k as f64 + 1.0)
            });
            for mode in Mode::ALL {
                for pad in [1, 2, 7] {
                    let (want, _) = extend_padded(&a, mode, &-0.5, pad).unwrap();
                    let mut buf = vec![f64::NAN; want.len()];
                    buf[..a.len()].copy_from_slice(a.as_slice().unwrap());
                    relocate_to_padded(&mut buf, shape, pad);
                    extend_in_place(&mut buf, shape, mode, &-0.5, pad);
                    let got: Vec<u64> = buf.iter().map(|x| x.to_bits()).collect();
                    let want: Vec<u64> = want.iter().map(|x| x.to_bits()).collect();
                    assert_eq!(got, want, "{shape:?} {mode} pad {pad}");
                }
            }
        }
    }

    /// Rows move in stages of many rows where the pads leave room: a large
    /// 2-D and 3-D array, checked element by element.
    #[test]
    fn relocation_of_large_arrays_puts_every_row_in_place() {
        for shape in [&[300usize, 257][..], &[20, 33, 41]] {
            let n: usize = shape.iter().product();
            let pad = 3;
            let (padded, strides) = padded_layout(shape, pad);
            let total: usize = padded.iter().product();
            let mut buf: Vec<f64> = (0..total)
                .map(|i| if i < n { i as f64 } else { -1.0 })
                .collect();
            relocate_to_padded(&mut buf, shape, pad);
            for (flat, index) in ndarray::indices(IxDyn(shape)).into_iter().enumerate() {
                let at: usize = (0..shape.len())
                    .map(|k| (index[k] + pad) * strides[k])
                    .sum();
                assert_eq!(buf[at], flat as f64, "{shape:?} {index:?}");
            }
        }
    }

    /// The finiteness the copy reports is that of every element of the
    /// source, wherever a NaN or ±∞ lies (first, last, interior, on a row
    /// that only pad rows repeat), and `from_coefficients` refuses such
    /// coefficients naming the first, in every mode.
    #[test]
    fn non_finite_sources_are_reported_and_named() {
        use crate::ndimage::NdimageError;
        use crate::ndimage::interpolant::{Interpolant, Options};
        use crate::ndimage::nan_policy::NanPolicy;
        let shape = [4usize, 5, 3];
        let clean = ArrayD::from_shape_fn(IxDyn(&shape), |i| (i[0] * 15 + i[1] * 3 + i[2]) as f64);
        for mode in Mode::ALL {
            assert!(extend_padded(&clean, mode, &0.0, 3).unwrap().1, "{mode}");
            for (at, bad) in [(0, f64::NAN), (59, f64::INFINITY), (31, f64::NEG_INFINITY)] {
                let mut a = clean.clone();
                a.as_slice_mut().unwrap()[at] = bad;
                a.as_slice_mut().unwrap()[at.max(40)] = f64::NAN;
                assert!(
                    !extend_padded(&a, mode, &0.0, 3).unwrap().1,
                    "{mode} at {at}"
                );
                let opts = Options {
                    nan_policy: NanPolicy::Raise,
                    ..Options::new(3, mode)
                };
                match Interpolant::<f64>::from_coefficients_with(&a, opts) {
                    Err(NdimageError::NonFinite { index, .. }) => assert_eq!(index, at, "{mode}"),
                    other => panic!("{mode} at {at}: {other:?}"),
                }
            }
        }
    }
}
