//! Fallible allocation of the engine's work arrays and results: a size the
//! allocator refuses (or that overflows `usize`) is
//! [`NdimageError::OutOfMemory`], which the Python layer raises as
//! `MemoryError`, instead of Rust's abort on a failed allocation, which
//! nothing can catch (a dead Jupyter kernel).

use super::NdimageError;
use crate::scalar::Real;
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
    let mut v = try_capacity(n, what)?;
    v.resize(n, value);
    Ok(v)
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
    let mut v: Vec<T> = try_capacity(n, what)?;
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

/// An empty vector with room for exactly `n` values, or the error.
fn try_capacity<T>(n: usize, what: &'static str) -> Result<Vec<T>, NdimageError> {
    let mut v = Vec::new();
    v.try_reserve_exact(n)
        .map_err(|_| NdimageError::OutOfMemory {
            bytes: n.saturating_mul(std::mem::size_of::<T>()),
            what,
        })?;
    Ok(v)
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
