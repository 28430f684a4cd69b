//! Fallible allocation of the engine's work arrays and results: a size the
//! allocator refuses (or that overflows `usize`) is
//! [`NdimageError::OutOfMemory`], which the Python layer raises as
//! `MemoryError`, instead of Rust's abort on a failed allocation, which
//! nothing can catch (a dead Jupyter kernel).

use super::NdimageError;
use crate::scalar::Real;
use ndarray::{Array, ArrayBase, CowArray, Data, Dimension};
use rayon::prelude::*;

/// `n` copies of `value` in a new vector, or [`NdimageError::OutOfMemory`]
/// naming `what` where the allocator refuses `n · size_of::<T>()` bytes.
///
/// ```
/// use splinelab::ndimage::alloc::try_filled;
/// assert_eq!(try_filled(3, 0.5f64, "test").unwrap(), vec![0.5; 3]);
/// assert!(try_filled(usize::MAX / 4, 0.0f64, "coefficients").is_err());
/// ```
pub fn try_filled<T: Clone>(
    n: usize,
    value: T,
    what: &'static str,
) -> Result<Vec<T>, NdimageError> {
    let mut v = try_with_capacity(n, what)?;
    v.resize(n, value);
    Ok(v)
}

/// An empty vector with room for `n` elements, or
/// [`NdimageError::OutOfMemory`] naming `what` (for vectors filled by
/// `extend` or `push` rather than with one value).
///
/// ```
/// use splinelab::ndimage::alloc::try_with_capacity;
/// assert!(try_with_capacity::<f64>(10, "test").unwrap().capacity() >= 10);
/// assert!(try_with_capacity::<f64>(usize::MAX / 4, "test").is_err());
/// ```
pub fn try_with_capacity<T>(n: usize, what: &'static str) -> Result<Vec<T>, NdimageError> {
    let mut v = Vec::new();
    v.try_reserve_exact(n)
        .map_err(|_| out_of_memory::<T>(n, what))?;
    Ok(v)
}

/// The number of elements of an array of `shape`, or
/// [`NdimageError::OutOfMemory`] naming `what` where the product overflows
/// `usize` (an array that large cannot be allocated either).
///
/// ```
/// use splinelab::ndimage::alloc::checked_len;
/// assert_eq!(checked_len(&[3, 4, 5], "test").unwrap(), 60);
/// assert!(checked_len(&[1 << 40, 1 << 40], "test").is_err());
/// ```
pub fn checked_len(shape: &[usize], what: &'static str) -> Result<usize, NdimageError> {
    shape
        .iter()
        .try_fold(1usize, |n, &k| n.checked_mul(k))
        .ok_or(NdimageError::OutOfMemory {
            bytes: usize::MAX,
            what,
        })
}

/// An array of `shape` (C order) filled with `value`, allocated fallibly
/// ([`try_filled`]; a shape whose size overflows is
/// [`NdimageError::OutOfMemory`] too).
///
/// ```
/// use splinelab::ndimage::alloc::try_array;
/// let a = try_array(ndarray::Ix2(2, 3), 1.5f64, "test").unwrap();
/// assert_eq!(a, ndarray::Array2::from_elem((2, 3), 1.5));
/// assert!(try_array(ndarray::IxDyn(&[1 << 40, 1 << 40]), 0.0f64, "test").is_err());
/// ```
pub fn try_array<T: Clone, D: Dimension>(
    shape: D,
    value: T,
    what: &'static str,
) -> Result<Array<T, D>, NdimageError> {
    let n = checked_len(shape.slice(), what)?;
    shaped(shape, try_filled(n, value, what)?)
}

/// An owned copy of `a` in C order, allocated fallibly (ndarray's
/// `to_owned` aborts where the allocator refuses; a zero-stride view from
/// `np.broadcast_to` can ask for far more than the memory it occupies).
///
/// ```
/// use splinelab::ndimage::alloc::try_to_owned;
/// let a = ndarray::array![[1.0, 2.0], [3.0, 4.0]];
/// assert_eq!(try_to_owned(&a.t(), "test").unwrap(), a.t().to_owned());
/// // A strided 3-D view: C order of its logical indices.
/// let b = ndarray::Array::from_iter(0..60).into_shape_with_order((3, 4, 5)).unwrap();
/// let v = b.slice(ndarray::s![.., 1..4;2, ..;-2]).permuted_axes([2, 0, 1]);
/// let c = try_to_owned(&v, "test").unwrap();
/// assert_eq!(c, v.to_owned());
/// assert_eq!(c.as_slice().unwrap()[..4], [9, 19, 29, 39]);
/// ```
pub fn try_to_owned<T, S, D>(
    a: &ArrayBase<S, D>,
    what: &'static str,
) -> Result<Array<T, D>, NdimageError>
where
    T: Clone,
    S: Data<Elem = T>,
    D: Dimension,
{
    let mut v = try_with_capacity(a.len(), what)?;
    if a.ndim() < 2 {
        v.extend(a.iter().cloned());
    } else {
        // Row by row: one step of the dynamic multi-index a row, not a
        // sample (a strided 43² view of a larger image: 40 µs by samples,
        // as reproject's chunks call it, against 2 µs by rows).
        for row in a.rows() {
            v.extend(row.iter().cloned());
        }
    }
    shaped(a.raw_dim(), v)
}

/// `a` itself where it is in C order, else a C-ordered copy allocated
/// fallibly ([`try_to_owned`]): ndarray's `as_standard_layout` with the
/// copy's allocation failure an error instead of an abort.
///
/// ```
/// use splinelab::ndimage::alloc::try_standard_layout;
/// let a = ndarray::array![[1.0, 2.0], [3.0, 4.0]];
/// let t = a.t();
/// let c = try_standard_layout(&t, "test").unwrap();
/// assert!(c.is_standard_layout() && c == t);
/// ```
pub fn try_standard_layout<'a, T, S, D>(
    a: &'a ArrayBase<S, D>,
    what: &'static str,
) -> Result<CowArray<'a, T, D>, NdimageError>
where
    T: Clone,
    S: Data<Elem = T>,
    D: Dimension,
{
    if a.is_standard_layout() {
        return Ok(CowArray::from(a.view()));
    }
    try_to_owned(a, what).map(CowArray::from)
}

/// `v` (C order) as an array of `shape`; a length that does not match is
/// [`NdimageError::BufferLength`] (the callers build `v` from `shape`).
fn shaped<T, D: Dimension>(shape: D, v: Vec<T>) -> Result<Array<T, D>, NdimageError> {
    let (expected, got) = (shape.size(), v.len());
    Array::from_shape_vec(shape, v).map_err(|_| NdimageError::BufferLength { expected, got })
}

fn out_of_memory<T>(n: usize, what: &'static str) -> NdimageError {
    NdimageError::OutOfMemory {
        bytes: n.saturating_mul(std::mem::size_of::<T>()),
        what,
    }
}

/// `n` zeros in a new vector for a large work array the engine writes
/// next (a coefficient array), or [`NdimageError::OutOfMemory`] as
/// [`try_filled`]. The pages are advised for transparent huge pages before
/// they are first touched (Linux, arrays of 4 MiB and more) and zeroed on
/// the pool, each thread touching the pages it zeroes: a 2048² f64 array
/// on 4 KiB pages takes 8192 page faults (a fifth of a rotation's time),
/// on 2 MiB pages 17. A hint: the contents are the same zeros either way.
///
/// ```
/// use splinelab::ndimage::alloc::try_zeros;
/// let v: Vec<f64> = try_zeros(5 << 20, "test").unwrap();
/// assert!(v.len() == 5 << 20 && v.iter().all(|x| x.to_bits() == 0));
/// assert!(try_zeros::<f64>(usize::MAX / 4, "coefficients").is_err());
/// ```
pub fn try_zeros<T: Real>(n: usize, what: &'static str) -> Result<Vec<T>, NdimageError> {
    let mut v: Vec<T> = try_with_capacity(n, what)?;
    advise_huge_pages(
        v.as_ptr().cast(),
        n.saturating_mul(std::mem::size_of::<T>()),
    );
    // Within the capacity just reserved: no reallocation.
    v.par_extend(rayon::iter::repeat_n(T::zero(), n));
    Ok(v)
}

/// The zeros of an array of `shape` grown by `pad` on both sides of every
/// axis ([`try_zeros`]), and that padded shape; a size that overflows
/// `usize` is [`NdimageError::OutOfMemory`] too.
///
/// ```
/// use splinelab::ndimage::alloc::try_padded_zeros;
/// let (shape, v) = try_padded_zeros::<f32>(&[3, 1], 2, "test").unwrap();
/// assert_eq!((shape, v.len()), (vec![7, 5], 35));
/// assert!(try_padded_zeros::<f64>(&[usize::MAX / 2, 3], 1, "test").is_err());
/// ```
pub fn try_padded_zeros<T: Real>(
    shape: &[usize],
    pad: usize,
    what: &'static str,
) -> Result<(Vec<usize>, Vec<T>), NdimageError> {
    let too_large = NdimageError::OutOfMemory {
        bytes: usize::MAX,
        what,
    };
    let padded: Vec<usize> = shape
        .iter()
        .map(|n| n.checked_add(pad.saturating_mul(2)))
        .collect::<Option<_>>()
        .ok_or(too_large.clone())?;
    let total = padded
        .iter()
        .try_fold(1usize, |t, &n| t.checked_mul(n))
        .ok_or(too_large)?;
    Ok((padded, try_zeros(total, what)?))
}

#[cfg(target_os = "linux")]
fn advise_huge_pages(start: *const u8, bytes: usize) {
    const PAGE: usize = 4096;
    if bytes < 4 << 20 {
        return;
    }
    let start = start as usize;
    // The whole pages inside the allocation.
    let first = start.next_multiple_of(PAGE);
    let len = (start + bytes - first) / PAGE * PAGE;
    // SAFETY: `[first, first + len)` lies inside the allocation of `bytes`
    // bytes at `start` that the caller holds; MADV_HUGEPAGE changes neither
    // the contents nor the protection of the range, only the page size the
    // kernel may use for it. A failure (no THP support) leaves the range as
    // it was.
    #[allow(unsafe_code)]
    unsafe {
        libc::madvise(first as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
    }
}

#[cfg(not(target_os = "linux"))]
fn advise_huge_pages(_: *const u8, _: usize) {}
