//! Matrix condition numbers in any precision.
//!
//! `cond₂(A) = σ_max / σ_min` (singular values by nalgebra's bidiagonal SVD,
//! Golub–Kahan) and `cond_∞(A) = ‖A‖_∞ ‖A⁻¹‖_∞` (inverse by LU with partial
//! pivoting). Both run in `f64` and in [`Mp`](crate::scalar::Mp).

use crate::scalar::Real;
use crate::validation::{InputError, finite_entries};
use nalgebra::DMatrix;
use nalgebra::linalg::SVD;

/// Why a condition number could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConditionError {
    /// The matrix is empty or not square.
    #[error("matrix must be square and non-empty, got {rows}×{cols}")]
    Shape {
        /// Number of rows.
        rows: usize,
        /// Number of columns.
        cols: usize,
    },
    /// An entry is NaN or infinite (the first, in column-major order).
    #[error(transparent)]
    Input(#[from] InputError),
    /// The matrix is singular in the working precision (a zero singular value
    /// or a zero pivot): its condition number is infinite.
    #[error("matrix is singular in the working precision")]
    Singular,
    /// The SVD iteration did not converge within its iteration limit.
    #[error("SVD did not converge")]
    NoConvergence,
}

/// Iteration cap for the SVD: nalgebra's `svd()` loops forever when its
/// stopping test cannot be met; 100 sweeps per singular value is far more than
/// the implicit-shift QR needs (typically 2–3).
const SVD_SWEEPS_PER_VALUE: usize = 100;

fn check<T: Real>(a: &DMatrix<T>) -> Result<(), ConditionError> {
    if a.nrows() != a.ncols() || a.is_empty() {
        return Err(ConditionError::Shape {
            rows: a.nrows(),
            cols: a.ncols(),
        });
    }
    Ok(finite_entries("matrix", a)?)
}

/// The singular values of `a`, in decreasing order.
///
/// Golub–Kahan bidiagonalisation and implicit-shift QR (nalgebra), with the
/// stopping tolerance the machine epsilon of `T` (`2^(1−BITS)` for `Mp`).
/// **Cost** `O(n³)`. **Accuracy**: backward stable: each computed `σ_i` is
/// within `O(n u) σ_max` of the exact one, so small singular values are only
/// known to `O(n u) · cond₂` relative.
pub fn singular_values<T: Real>(a: &DMatrix<T>) -> Result<Vec<T>, ConditionError> {
    check(a)?;
    let max_niter = SVD_SWEEPS_PER_VALUE * a.nrows().max(1);
    let svd = SVD::try_new(a.clone(), false, false, T::default_epsilon(), max_niter)
        .ok_or(ConditionError::NoConvergence)?;
    let mut s: Vec<T> = svd.singular_values.iter().cloned().collect();
    s.sort_by(|x, y| y.partial_cmp(x).unwrap_or(std::cmp::Ordering::Equal));
    Ok(s)
}

/// The 2-norm condition number `σ_max / σ_min`.
///
/// **Accuracy**: the relative error is about `c · n · u · cond₂(A)` (the
/// error of `σ_min`), so in f64 it has roughly `−log10(n u cond₂)` correct
/// digits and none at all once `cond₂ ≳ 1/u`. Studies compare against an MPFR
/// run to report the digits that actually agree.
///
/// ```
/// use nalgebra::DMatrix;
/// use splinelab::matrix_condition::cond2;
/// let a = DMatrix::from_row_slice(2, 2, &[2.0f64, 0.0, 0.0, 0.5]);
/// assert!((cond2(&a).unwrap() - 4.0).abs() < 1e-15);
/// ```
///
/// ```
/// use splinelab::matrix_condition::cond2;
/// // In MPFR: cond₂ [[1, 1], [0, 1]] = φ² = (3 + √5)/2 (σ = φ, 1/φ).
/// use splinelab::nalgebra::{ComplexField, DMatrix};
/// use splinelab::scalar::{Mp, Real};
/// type M = Mp<200>;
/// let a = DMatrix::from_fn(2, 2, |i, j| M::from_int(if i > j { 0 } else { 1 }));
/// let want = (M::from_int(3) + M::from_int(5).sqrt()) / M::from_int(2);
/// assert!((cond2(&a).unwrap() - want).to_f64().abs() < 1e-40);
/// ```
pub fn cond2<T: Real>(a: &DMatrix<T>) -> Result<T, ConditionError> {
    let s = singular_values(a)?;
    let (max, min) = (s[0].clone(), s[s.len() - 1].clone());
    if min.is_zero() {
        return Err(ConditionError::Singular);
    }
    Ok(max / min)
}

/// The ∞-norm (maximum absolute row sum).
pub fn norm_inf<T: Real>(a: &DMatrix<T>) -> T {
    a.row_iter()
        .map(|r| r.iter().fold(T::zero(), |s, x| s + x.clone().abs()))
        .fold(T::zero(), |m, s| m.max(s))
}

/// The ∞-norm condition number `‖A‖_∞ ‖A⁻¹‖_∞`, the inverse by LU with
/// partial pivoting. **Cost** `O(n³)`. **Accuracy**: the computed inverse has
/// relative error `O(n u cond)`, hence so does the result.
/// In MPFR it reproduces `cond_∞(B_u ⊗ B_v) = cond_∞(B_u) cond_∞(B_v)` to `1e-60`
/// relative (`verify/tests/it/conditioning.rs::tensor_condition_numbers_are_products_of_the_univariate_ones`).
/// **Source**: Higham, 2nd ed., §14.3 (inversion by LU) and Golub & Van
/// Loan, §3.4; the quantity is seed 001's `cond(B̃)`.
pub fn cond_inf<T: Real>(a: &DMatrix<T>) -> Result<T, ConditionError> {
    check(a)?;
    let inv = a
        .clone()
        .lu()
        .try_inverse()
        .ok_or(ConditionError::Singular)?;
    if inv.iter().any(|x| !x.is_finite()) {
        return Err(ConditionError::Singular);
    }
    Ok(norm_inf(a) * norm_inf(&inv))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;

    #[test]
    fn a_non_finite_entry_is_named_by_its_position_in_f64_and_mpfr() {
        let mut a = DMatrix::from_row_slice(2, 2, &[2.0f64, 1.0, 1.0, 2.0]);
        a[(0, 1)] = f64::NEG_INFINITY;
        let at = InputError::NonFiniteEntry {
            what: "matrix",
            row: 0,
            col: 1,
        };
        assert_eq!(cond2(&a), Err(ConditionError::Input(at.clone())));
        let m = a.map(Mp::<96>::from_f64_exact);
        assert_eq!(cond_inf(&m), Err(ConditionError::Input(at)));
        assert_eq!(
            singular_values(&m).unwrap_err().to_string(),
            "matrix entry (0, 1) is not finite"
        );
    }
}
