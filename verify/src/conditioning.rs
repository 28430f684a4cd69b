//! The Bernstein–Vandermonde conditioning study (seed 001 eq 2–3).
//!
//! For each degree, node family and basis the condition numbers are computed
//! twice: in f64 from f64 nodes, and in MPFR (`REF_BITS` bits) from nodes
//! computed in MPFR. The MPFR value is the reference; the study reports how
//! many digits the f64 value shares with it, next to the number the error
//! analysis predicts, `−log10((n+1) u cond₂)`, so a reader can see where f64
//! stops being trustworthy instead of reading a wrong number as a right one.

use crate::metrics::{F64_DIGITS, correct_digits, relative_error};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use splinelab::matrix_condition::{cond_inf, cond2};
use splinelab::scalar::{Mp, Real};
use splinelab::surface_deformation::vandermonde::{
    NodeFamily, bernstein_vandermonde, monomial_vandermonde,
};

/// Bits of the MPFR reference: 256 bits carry 77 digits, more than enough
/// for condition numbers up to 1e40 to be right to 30+ digits.
pub const REF_BITS: u32 = 256;
type Reference = Mp<REF_BITS>;

/// Which basis the Vandermonde matrix is built from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[derive(strum::VariantArray, strum::IntoStaticStr)]
#[strum(serialize_all = "lowercase")]
pub enum Basis {
    /// `B_i^n(t_j)`.
    Bernstein,
    /// `t_jᶦ`.
    Monomial,
}

splinelab::named_enum!(Basis, "basis");

/// What to measure: a degree, node family, basis, and whether the tensor
/// (Kronecker) matrix of seed 001 eq 2 is meant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct CondCase {
    /// Polynomial degree `n` (matrix size `n + 1`, or `(n+1)²` for tensor).
    pub degree: usize,
    /// The node family.
    pub nodes: NodeFamily,
    /// The basis.
    pub basis: Basis,
    /// The tensor matrix `B_u ⊗ B_u` on the grid of the same nodes.
    pub tensor: bool,
}

impl CondCase {
    /// The matrix order: `n + 1`, or `(n + 1)²` for the tensor matrix.
    pub fn matrix_size(&self) -> usize {
        let m = self.degree + 1;
        if self.tensor { m * m } else { m }
    }
}

pub use crate::study_error::StudyError;

/// Both condition numbers of one case in one precision.
#[derive(Debug, Clone, PartialEq)]
pub struct CondPair<T> {
    /// `cond₂`.
    pub cond2: T,
    /// `cond_∞`.
    pub cond_inf: T,
}

/// The condition numbers of `case` computed entirely in `T`.
///
/// For the tensor case the Kronecker identity `cond(B_u ⊗ B_v) =
/// cond(B_u) cond(B_v)` (exact for the 2-norm, and for the ∞-norm because
/// `‖A ⊗ B‖_∞ = ‖A‖_∞ ‖B‖_∞` and `(A ⊗ B)⁻¹ = A⁻¹ ⊗ B⁻¹`) is used, so the
/// cost stays `O(n³)`; the tests check it against the full `(n+1)²` matrix.
pub fn condition_numbers<T: Real>(case: &CondCase) -> Result<CondPair<T>, StudyError> {
    let nodes: Vec<T> = case.nodes.nodes(case.degree)?;
    let a = match case.basis {
        Basis::Bernstein => bernstein_vandermonde(&nodes),
        Basis::Monomial => monomial_vandermonde(&nodes),
    };
    let (c2, ci) = (cond2(&a)?, cond_inf(&a)?);
    Ok(if case.tensor {
        CondPair {
            cond2: c2.clone() * c2,
            cond_inf: ci.clone() * ci,
        }
    } else {
        CondPair {
            cond2: c2,
            cond_inf: ci,
        }
    })
}

/// One row of the study: the MPFR reference, the f64 value and the digits
/// they share.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CondRow {
    /// The case measured.
    pub case: CondCase,
    /// `cond₂` in MPFR, 40 significant digits.
    pub cond2_ref: String,
    /// The same, rounded to f64 (for charts).
    pub cond2_ref_f64: f64,
    /// `cond₂` computed in f64.
    pub cond2_f64: f64,
    /// Decimal digits the f64 `cond₂` shares with the reference.
    pub cond2_digits: f64,
    /// Digits the error analysis predicts, `−log10((n+1) u cond₂)`, floored at 0.
    pub cond2_digits_predicted: f64,
    /// `cond_∞` in MPFR, 40 significant digits.
    pub cond_inf_ref: String,
    /// `cond_∞` computed in f64.
    pub cond_inf_f64: f64,
    /// Decimal digits the f64 `cond_∞` shares with the reference.
    pub cond_inf_digits: f64,
}

/// Measures one case in f64 and in the MPFR reference.
///
/// If the f64 computation fails (the matrix is numerically singular in f64)
/// the f64 fields are `f64::INFINITY` with 0 digits: reported, never hidden.
pub fn measure(case: &CondCase) -> Result<CondRow, StudyError> {
    let reference = condition_numbers::<Reference>(case)?;
    let fast = condition_numbers::<f64>(case).unwrap_or(CondPair {
        cond2: f64::INFINITY,
        cond_inf: f64::INFINITY,
    });
    let (r2, ri) = (reference.cond2.to_float(), reference.cond_inf.to_float());
    let n1 = (case.degree + 1) as f64;
    let predicted = -(n1 * f64::EPSILON / 2.0 * r2.to_f64()).log10();
    Ok(CondRow {
        case: *case,
        cond2_ref: reference.cond2.to_decimal(40),
        cond2_ref_f64: reference.cond2.to_f64(),
        cond2_f64: fast.cond2,
        cond2_digits: correct_digits(relative_error(&fast.cond2, &r2), F64_DIGITS),
        cond2_digits_predicted: predicted.clamp(0.0, F64_DIGITS),
        cond_inf_ref: reference.cond_inf.to_decimal(40),
        cond_inf_f64: fast.cond_inf,
        cond_inf_digits: correct_digits(relative_error(&fast.cond_inf, &ri), F64_DIGITS),
    })
}

/// The whole study: every degree in `degrees`, every node family, both
/// bases (univariate), measured in parallel. Rows come back in a fixed order
/// (basis, family, degree) whatever the thread count.
pub fn run_conditioning(degrees: &[usize]) -> Result<Vec<CondRow>, StudyError> {
    let cases: Vec<CondCase> = [Basis::Bernstein, Basis::Monomial]
        .into_iter()
        .flat_map(|basis| {
            NodeFamily::all().flat_map(move |nodes| {
                degrees.iter().map(move |&degree| CondCase {
                    degree,
                    nodes,
                    basis,
                    tensor: false,
                })
            })
        })
        .collect();
    cases.par_iter().map(measure).collect()
}
