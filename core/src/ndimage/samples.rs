//! How the engine reads samples and stores results, whatever the element
//! types of the caller's arrays: the one place where the data's type (what
//! the user holds: float32 images, integers, float64) meets the compute
//! type `T` (what the engine does arithmetic in).
//!
//! scipy.ndimage computes every float32, float16 and integer input in
//! float64 and rounds once when it stores the result; the engine does the
//! same by reading samples through [`Sample`] (an exact widening into `T`,
//! done as the samples are read, so no widened copy of the input is made)
//! and writing results through [`Stored`] (one rounding, as they are
//! written). A compute type narrower than the data (`f32` arithmetic on
//! `f32` data) is the caller's explicit choice, never a default.
//!
//! [`SampleSource`] is what a route that reads only part of the array
//! needs: the samples of one box, converted into the compute type. The
//! global route reads every sample once; the local route reads the boxes
//! its points' windows cover (an `ndarray` view of a memory map reads only
//! those pages).

use super::NdimageError;
use crate::scalar::Real;
use ndarray::{ArrayBase, Axis, Data, Dimension, IxDyn, SliceInfoElem};

/// An element type the engine reads samples of, widened into the compute
/// type `T` by [`Sample::widen`]: exactly (`f32 → f64`, `f32 → f32`,
/// `f64 → f64`, integers of up to 32 bits → `f64`), or as numpy's `astype`
/// rounds (64-bit integers → `f64`, to nearest).
pub trait Sample<T>: Clone + Send + Sync + 'static {
    /// The sample as a value of the compute type.
    fn widen(&self) -> T;

    /// `src` as values of the compute type without a copy, where the
    /// sample type is the compute type itself (`None` otherwise): the
    /// engine's passes read such samples where they lie.
    #[inline(always)]
    fn as_compute(src: &[Self]) -> Option<&[T]> {
        let _ = src;
        None
    }

    /// `dst[i] = src[i].widen()` (the shorter length).
    #[inline(always)]
    fn widen_into(src: &[Self], dst: &mut [T]) {
        for (d, s) in dst.iter_mut().zip(src) {
            *d = s.widen();
        }
    }
}

/// An element type the engine stores results into from the compute type
/// `T` by [`Stored::store`]: `T` itself (no rounding), or `f32` from `f64`
/// (rounded to nearest once, as numpy's `astype` and scipy's C cast do).
pub trait Stored<T>: Clone + Send + Sync + 'static {
    /// The largest finite magnitude the stored type holds, where it is
    /// below the compute type's (`f32::MAX` for `f32` results of `f64`
    /// arithmetic), else ∞: what a check that the results stay finite
    /// compares against.
    const LARGEST: f64 = f64::INFINITY;

    /// The result as stored.
    fn store(value: &T) -> Self;

    /// `out` as a buffer of the compute type, where the result type is the
    /// compute type itself (`None` otherwise: the engine computes into a
    /// work buffer of `T` a chunk at a time and stores it through
    /// [`Stored::store_from`]).
    #[inline(always)]
    fn as_compute_mut(out: &mut [Self]) -> Option<&mut [T]> {
        let _ = out;
        None
    }

    /// `dst[i] = store(src[i])` (the shorter length).
    #[inline(always)]
    fn store_from(src: &[T], dst: &mut [Self]) {
        for (d, s) in dst.iter_mut().zip(src) {
            *d = Self::store(s);
        }
    }

    /// [`Stored::store_from`] into a new vector: results computed into a
    /// vector of `T` handed over as stored values (the compute type's own:
    /// `src` itself, no copy).
    ///
    /// ```
    /// use splinelab::ndimage::samples::Stored;
    /// let wide = vec![0.1f64, 1.0 + f64::EPSILON];
    /// assert_eq!(<f32 as Stored<f64>>::store_vec(wide.clone()), [0.1f32, 1.0]);
    /// assert_eq!(<f64 as Stored<f64>>::store_vec(wide.clone()), wide);
    /// ```
    fn store_vec(src: Vec<T>) -> Vec<Self> {
        src.iter().map(Self::store).collect()
    }
}

impl<T: Real> Sample<T> for T {
    #[inline(always)]
    fn widen(&self) -> T {
        self.clone()
    }

    #[inline(always)]
    fn as_compute(src: &[T]) -> Option<&[T]> {
        Some(src)
    }

    #[inline(always)]
    fn widen_into(src: &[T], dst: &mut [T]) {
        let n = src.len().min(dst.len());
        dst[..n].clone_from_slice(&src[..n]);
    }
}

impl<T: Real> Stored<T> for T {
    #[inline(always)]
    fn store(value: &T) -> Self {
        value.clone()
    }

    #[inline(always)]
    fn as_compute_mut(out: &mut [T]) -> Option<&mut [T]> {
        Some(out)
    }

    #[inline(always)]
    fn store_from(src: &[T], dst: &mut [T]) {
        let n = src.len().min(dst.len());
        dst[..n].clone_from_slice(&src[..n]);
    }

    fn store_vec(src: Vec<T>) -> Vec<T> {
        src
    }
}

impl Sample<f64> for f32 {
    #[inline(always)]
    fn widen(&self) -> f64 {
        f64::from(*self)
    }
}

impl Stored<f64> for f32 {
    const LARGEST: f64 = f32::MAX as f64;

    #[inline(always)]
    fn store(value: &f64) -> Self {
        *value as f32
    }
}

/// Integers as float64 samples: exact up to 32 bits (`From`), rounded to
/// nearest for 64 bits (`as`, numpy's `astype(float64)`).
macro_rules! integer_samples {
    (exact: $($t:ty),*; rounded: $($r:ty),*) => {
        $(impl Sample<f64> for $t {
            #[inline(always)]
            fn widen(&self) -> f64 {
                f64::from(*self)
            }
        })*
        $(impl Sample<f64> for $r {
            #[inline(always)]
            fn widen(&self) -> f64 {
                *self as f64
            }
        })*
    };
}
integer_samples!(exact: i8, u8, i16, u16, i32, u32; rounded: i64, u64);

/// Samples read a box at a time, converted into the compute type `T`: an
/// in-memory array (any element type [`Sample<T>`], any strides: an
/// `ndarray` view of a memory-mapped file touches only the pages of the
/// boxes read), or blocks a caller fetched from an array that is not in
/// memory.
pub trait SampleSource<T>: Sync {
    /// The shape of the whole array.
    fn shape(&self) -> &[usize];

    /// The samples of the box `lo[a]..hi[a]` on every axis `a` (inside the
    /// array: `lo[a] < hi[a] ≤ shape[a]`) into `out` in C order
    /// (`out.len()` the box's size), widened into `T`.
    fn read_box(&self, lo: &[usize], hi: &[usize], out: &mut [T]) -> Result<(), NdimageError>;
}

impl<T, E, S, D> SampleSource<T> for ArrayBase<S, D>
where
    E: Sample<T>,
    S: Data<Elem = E> + Sync,
    D: Dimension,
{
    fn shape(&self) -> &[usize] {
        ArrayBase::shape(self)
    }

    fn read_box(&self, lo: &[usize], hi: &[usize], out: &mut [T]) -> Result<(), NdimageError> {
        let ndim = self.ndim();
        let inside = lo.len() == ndim
            && hi.len() == ndim
            && (0..ndim).all(|a| lo[a] < hi[a] && hi[a] <= self.shape()[a]);
        if !inside {
            return Err(NdimageError::BoxOutside {
                lo: lo.to_vec(),
                hi: hi.to_vec(),
                shape: self.shape().to_vec(),
            });
        }
        let size: usize = lo.iter().zip(hi).map(|(l, h)| h - l).product();
        if out.len() != size {
            return Err(NdimageError::BufferLength {
                expected: size,
                got: out.len(),
            });
        }
        let info: Vec<SliceInfoElem> = lo
            .iter()
            .zip(hi)
            .map(|(&l, &h)| SliceInfoElem::from(l..h))
            .collect();
        let view = self.view().into_dyn();
        let window = view.slice(info.as_slice());
        debug_assert_eq!(
            window.raw_dim(),
            IxDyn(&hi.iter().zip(lo).map(|(h, l)| h - l).collect::<Vec<_>>())
        );
        // Row by row along the last axis: a contiguous row is widened as
        // a slice (a dynamic-dimension element iterator costs several
        // times the copy itself on the boxes of the local route).
        let Some(last) = ndim.checked_sub(1) else {
            for (o, s) in out.iter_mut().zip(window.iter()) {
                *o = s.widen();
            }
            return Ok(());
        };
        let row = hi[last] - lo[last];
        for (o, lane) in out.chunks_mut(row).zip(window.lanes(Axis(last))) {
            match lane.as_slice() {
                Some(s) => E::widen_into(s, o),
                None => {
                    for (o, s) in o.iter_mut().zip(lane.iter()) {
                        *o = s.widen();
                    }
                }
            }
        }
        Ok(())
    }
}

/// Samples of an array that is not in memory (zarr, HDF5, dask, any
/// array-like): the blocks a caller fetched, each an `ndarray` view of any
/// [`Sample<T>`] element type placed at its first index. A box is read
/// from a block that holds it whole (the boxes a route asks for are the
/// boxes it planned, so the caller fetches exactly those); a box no block
/// holds is [`NdimageError::NotFetched`].
#[derive(Debug, Clone)]
pub struct Blocks<'a, E> {
    shape: Vec<usize>,
    blocks: Vec<(Vec<usize>, ndarray::ArrayViewD<'a, E>)>,
}

impl<'a, E> Blocks<'a, E> {
    /// The blocks `(first index, samples)` of an array of `shape`; each
    /// must lie inside the array ([`NdimageError::BoxOutside`]).
    pub fn new(
        shape: &[usize],
        blocks: Vec<(Vec<usize>, ndarray::ArrayViewD<'a, E>)>,
    ) -> Result<Self, NdimageError> {
        for (lo, b) in &blocks {
            let hi: Vec<usize> = lo.iter().zip(b.shape()).map(|(l, n)| l + n).collect();
            let inside = lo.len() == shape.len() && hi.iter().zip(shape).all(|(h, n)| h <= n);
            if !inside {
                return Err(NdimageError::BoxOutside {
                    lo: lo.clone(),
                    hi,
                    shape: shape.to_vec(),
                });
            }
        }
        Ok(Blocks {
            shape: shape.to_vec(),
            blocks,
        })
    }
}

impl<T, E> SampleSource<T> for Blocks<'_, E>
where
    E: Sample<T>,
{
    fn shape(&self) -> &[usize] {
        &self.shape
    }

    fn read_box(&self, lo: &[usize], hi: &[usize], out: &mut [T]) -> Result<(), NdimageError> {
        let holder = self.blocks.iter().find(|(first, b)| {
            lo.len() == first.len()
                && (0..lo.len()).all(|a| first[a] <= lo[a] && hi[a] <= first[a] + b.shape()[a])
        });
        let Some((first, b)) = holder else {
            return Err(NdimageError::NotFetched {
                lo: lo.to_vec(),
                hi: hi.to_vec(),
            });
        };
        let l: Vec<usize> = lo.iter().zip(first).map(|(l, f)| l - f).collect();
        let h: Vec<usize> = hi.iter().zip(first).map(|(h, f)| h - f).collect();
        b.read_box(&l, &h, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::Array2;

    #[test]
    fn float32_samples_widen_exactly_and_store_rounded_once() {
        // 1 + 2^-23 is a float32; widened it keeps every bit.
        let x = 1.0f32 + f32::EPSILON;
        assert_eq!(Sample::<f64>::widen(&x), 1.0 + 2f64.powi(-23));
        // 1 + 2^-24 + 2^-30 rounds up to 1 + 2^-23 (nearest), not down.
        let v = 1.0 + 2f64.powi(-24) + 2f64.powi(-30);
        assert_eq!(<f32 as Stored<f64>>::store(&v), 1.0 + f32::EPSILON);
        // 2^53 + 1 as an i64 rounds to 2^53 (ties to even), as numpy's astype.
        assert_eq!(Sample::<f64>::widen(&((1i64 << 53) + 1)), 2f64.powi(53));
        assert_eq!(Sample::<f64>::widen(&u32::MAX), 4294967295.0);
    }

    #[test]
    fn a_box_reads_the_samples_it_covers_in_c_order() {
        let a = Array2::from_shape_fn((4, 5), |(i, j)| (10 * i + j) as f32);
        let mut out = [0.0f64; 6];
        a.read_box(&[1, 2], &[3, 5], &mut out).unwrap();
        assert_eq!(out, [12.0, 13.0, 14.0, 22.0, 23.0, 24.0]);
        // Strided views read the same samples.
        let t = a.t();
        let mut out_t = [0.0f64; 2];
        t.read_box(&[3, 1], &[4, 3], &mut out_t).unwrap();
        assert_eq!(out_t, [13.0, 23.0]);
    }

    #[test]
    fn blocks_read_what_they_hold_and_name_what_they_do_not() {
        let a = Array2::from_shape_fn((6, 8), |(i, j)| (10 * i + j) as f32);
        let part = a.slice(ndarray::s![2..5, 3..8]).into_dyn();
        let blocks = Blocks::new(&[6, 8], vec![(vec![2, 3], part)]).unwrap();
        let mut out = [0.0f64; 4];
        blocks.read_box(&[3, 5], &[5, 7], &mut out).unwrap();
        assert_eq!(out, [35.0, 36.0, 45.0, 46.0]);
        let e = blocks.read_box(&[0, 0], &[2, 2], &mut out).unwrap_err();
        assert!(matches!(e, NdimageError::NotFetched { .. }), "{e}");
        let part = a.slice(ndarray::s![2..5, 3..8]).into_dyn();
        assert!(Blocks::new(&[4, 8], vec![(vec![2, 3], part)]).is_err());
    }

    #[test]
    fn a_box_outside_the_array_is_refused() {
        let a = Array2::<f64>::zeros((3, 3));
        let mut out = [0.0f64; 4];
        let e = a.read_box(&[2, 0], &[4, 2], &mut out).unwrap_err();
        assert!(matches!(e, NdimageError::BoxOutside { .. }), "{e}");
        let e = a.read_box(&[0, 0], &[1, 1], &mut out).unwrap_err();
        assert!(
            matches!(
                e,
                NdimageError::BufferLength {
                    expected: 1,
                    got: 4
                }
            ),
            "{e}"
        );
    }
}
