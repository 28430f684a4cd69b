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

use crate::ndimage::NdimageError;
use crate::ndimage::alloc::{checked_len, try_filled, try_standard_layout, try_to_owned};
use crate::ndimage::mode::Mode;
use crate::ndimage::nd_prefilter::scan_block;
use crate::scalar::Real;
use ndarray::{ArrayBase, ArrayD, Data, Dimension, IxDyn};
use rayon::prelude::*;

/// `a` extended by `pad` values beyond each end of each axis as `mode`
/// extends samples (`cval` where the mode gives none), C order, and
/// whether every element of `a` is finite (each row scanned as it is
/// copied, [`scan_block`]: no separate pass over `a`).
/// [`NdimageError::OutOfMemory`] where the padded array (or the C-ordered
/// copy of a strided `a`) cannot be allocated.
pub(super) fn extend_padded<T, S, D>(
    a: &ArrayBase<S, D>,
    mode: Mode,
    cval: &T,
    pad: usize,
) -> Result<(ArrayD<T>, bool), NdimageError>
where
    T: Real + Send + Sync,
    S: Data<Elem = T>,
    D: Dimension,
{
    if a.ndim() == 0 {
        let finite = a.iter().all(|x| x.is_finite());
        return Ok((try_to_owned(a, WHAT)?.into_dyn(), finite));
    }
    let a = try_standard_layout(a, "a C-ordered copy of the input")?;
    let src = a.as_slice().ok_or(NdimageError::BufferLength {
        expected: a.len(),
        got: 0,
    })?;
    let shape = a.shape();
    let nd = shape.len();
    let padded: Vec<usize> = shape.iter().map(|n| n.saturating_add(2 * pad)).collect();
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
    let mut out = zeros_on_huge_pages(checked_len(&padded, WHAT)?)?;
    let finite = out
        .par_chunks_mut(row_len)
        .enumerate()
        .map(|(r, row)| {
            // The source row: the fold of the row's leading indices.
            let (mut rest, mut base) = (r, Some(0));
            for k in (0..nd - 1).rev() {
                let j = rest % padded[k];
                rest /= padded[k];
                base = base.zip(maps[k][j]).map(|(b, i)| b + i * src_strides[k]);
            }
            let Some(base) = base else {
                row.fill(cval.clone());
                return true;
            };
            let line = &src[base..base + n_last];
            row[pad..pad + n_last].clone_from_slice(line);
            let last = &maps[nd - 1];
            for j in (0..pad).chain(pad + n_last..row_len) {
                row[j] = last[j].map_or_else(|| cval.clone(), |i| line[i].clone());
            }
            scan_block(&row[pad..pad + n_last]).0
        })
        .reduce(|| true, |a, b| a & b);
    let out =
        ArrayD::from_shape_vec(IxDyn(&padded), out).map_err(|_| NdimageError::BufferLength {
            expected: padded.iter().product(),
            got: 0,
        })?;
    Ok((out, finite))
}

/// What [`extend_padded`] and [`zeros_on_huge_pages`] allocate.
const WHAT: &str = "the padded spline coefficients";

/// `n` zeros whose memory the kernel may back with transparent huge pages
/// (Linux `madvise(MADV_HUGEPAGE)` before the first touch; elsewhere, and
/// for arrays under 4 MiB, a plain vector). A large vector's pages are
/// fresh from `mmap` and faulted in on first write: on 4 KiB pages a 2048²
/// f64 array (8192 faults, each zeroing its page) cost a fifth of a
/// rotation's time; on 2 MiB pages the same bytes take 17 faults. A hint:
/// the contents are the same zeros either way. Allocated fallibly
/// ([`try_filled`]): [`NdimageError::OutOfMemory`] where the allocator
/// refuses, not an abort.
pub(super) fn zeros_on_huge_pages<T: Real>(n: usize) -> Result<Vec<T>, NdimageError> {
    let v = try_filled(n, T::zero(), WHAT)?;
    advise_huge_pages(&v);
    Ok(v)
}

#[cfg(target_os = "linux")]
fn advise_huge_pages<T>(v: &[T]) {
    const PAGE: usize = 4096;
    let bytes = std::mem::size_of_val(v);
    if bytes < 4 << 20 {
        return;
    }
    let start = v.as_ptr() as usize;
    // The whole pages inside the vector.
    let first = start.next_multiple_of(PAGE);
    let len = (start + bytes - first) / PAGE * PAGE;
    // SAFETY: `[first, first + len)` lies inside `v`'s allocation, which
    // this function borrows; MADV_HUGEPAGE changes neither the contents
    // nor the protection of the range, only the page size the kernel may
    // use for it. A failure (no THP support) leaves the range as it was.
    #[allow(unsafe_code)]
    unsafe {
        libc::madvise(first as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
    }
}

#[cfg(not(target_os = "linux"))]
fn advise_huge_pages<T>(_: &[T]) {}

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
            let v: Vec<f64> = zeros_on_huge_pages(n).unwrap();
            assert_eq!(v.len(), n);
            assert!(v.iter().all(|&x| x.to_bits() == 0), "{n}");
        }
        let v: Vec<f32> = zeros_on_huge_pages((9 << 20) / 4 + 1).unwrap();
        assert!(v.iter().all(|&x| x.to_bits() == 0));
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
