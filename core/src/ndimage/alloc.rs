//! Fallible allocation of the engine's work arrays and results: a size the
//! allocator refuses (or that overflows `usize`) is
//! [`NdimageError::OutOfMemory`], which the Python layer raises as
//! `MemoryError`, instead of Rust's abort on a failed allocation, which
//! nothing can catch (a dead Jupyter kernel).

use super::NdimageError;

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
    let mut v = Vec::new();
    v.try_reserve_exact(n)
        .map_err(|_| NdimageError::OutOfMemory {
            bytes: n.saturating_mul(std::mem::size_of::<T>()),
            what,
        })?;
    v.resize(n, value);
    Ok(v)
}
