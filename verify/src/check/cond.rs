//! `cond`: a user's condition numbers of Vandermonde-type matrices on their
//! own nodes, against MPFR references of the same matrices.
//!
//! For each node set `t_0..t_n` (exactly the user's f64 values) the matrix
//! `B_{ji} = B_i^n(t_j)` (Bernstein) or `t_jⁱ` (monomial) is formed in `T`
//! and `cond₂ = σ_max / σ_min` (singular values) or
//! `cond_∞ = ‖A‖_∞ ‖A⁻¹‖_∞` (LU inverse) computed in `T`
//! ([`splinelab::matrix_condition`]), certified by the `p / p + 64` agreement
//! of the whole computation — so the reference's own rounding, amplified by
//! the condition number, is shown to be far below one ulp of what is
//! reported, raising `p` as far as the conditioning needs. Cost `O(n³)` per
//! node set and precision.

use super::agreement::{Reference, certify};
use super::format::UserFormat;
use super::summary::{CheckSummary, Context, summarize};
use super::{CheckError, require_finite, require_len};
use crate::conditioning::Basis;
use splinelab::matrix_condition::{cond_inf, cond2};
use splinelab::scalar::Real;
use splinelab::surface_deformation::vandermonde::{bernstein_vandermonde, monomial_vandermonde};

/// Largest number of nodes in one set (a 501 × 501 matrix, as `splinelab cond`).
pub const MAX_NODES: usize = 501;

/// Largest total `Σ (n + 1)³` over the node sets.
pub const MAX_WORK: usize = 500_000_000;

/// Which condition number the user computed.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, strum::VariantArray, strum::IntoStaticStr,
)]
pub enum Norm {
    /// `cond₂ = σ_max / σ_min`.
    #[serde(rename = "2")]
    #[strum(serialize = "2")]
    Two,
    /// `cond_∞ = ‖A‖_∞ ‖A⁻¹‖_∞`.
    #[serde(rename = "inf")]
    #[strum(serialize = "inf")]
    Inf,
}

splinelab::named_enum!(Norm, "norm");

/// What `check cond` is given.
#[derive(Debug, Clone)]
pub struct CondInput {
    /// One node set per matrix (each at least two nodes).
    pub node_sets: Vec<Vec<f64>>,
    /// The basis of the Vandermonde matrix.
    pub basis: Basis,
    /// `cond₂` or `cond_∞`.
    pub norm: Norm,
    /// The user's condition numbers, one per node set.
    pub user: Vec<f64>,
    /// The user's format.
    pub format: UserFormat,
    /// `--max-ulps`.
    pub max_ulps: Option<f64>,
}

struct CondReference<'a>(&'a CondInput);

impl Reference for CondReference<'_> {
    fn compute<T: Real>(&self) -> Result<Vec<T>, CheckError> {
        let inp = self.0;
        inp.node_sets
            .iter()
            .enumerate()
            .map(|(k, set)| {
                let t: Vec<T> = set.iter().map(|x| T::from_f64_exact(*x)).collect();
                let a = match inp.basis {
                    Basis::Bernstein => bernstein_vandermonde(&t),
                    Basis::Monomial => monomial_vandermonde(&t),
                };
                match inp.norm {
                    Norm::Two => cond2(&a),
                    Norm::Inf => cond_inf(&a),
                }
                .map_err(|e| CheckError::Invalid(format!("node set {k}: {e}")))
            })
            .collect()
    }
}

fn validate(inp: &CondInput) -> Result<(), CheckError> {
    if inp.node_sets.is_empty() {
        return Err(CheckError::Empty("nodes".into()));
    }
    require_len(
        "values (one per node set)",
        inp.node_sets.len(),
        inp.user.len(),
    )?;
    let mut work = 0usize;
    for (k, set) in inp.node_sets.iter().enumerate() {
        if !(2..=MAX_NODES).contains(&set.len()) {
            return Err(CheckError::Invalid(format!(
                "node set {k} has {} nodes: 2..={MAX_NODES} accepted",
                set.len()
            )));
        }
        require_finite(&format!("nodes[{k}]"), set)?;
        work = work.saturating_add(set.len().pow(3));
    }
    if work > MAX_WORK {
        return Err(CheckError::TooLarge(format!(
            "Σ (n+1)³ = {work} exceeds {MAX_WORK}"
        )));
    }
    Ok(())
}

/// Checks the user's condition numbers. A singular matrix (repeated nodes)
/// is a typed error, a non-finite user value a failed element.
pub fn check_cond(input: &CondInput) -> Result<CheckSummary, CheckError> {
    validate(input)?;
    let cert = certify(&CondReference(input), input.format, 0)?;
    let ctx = Context {
        kind: "cond",
        format: input.format,
        reference_bits: Some(cert.bits),
        reference: format!(
            "cond_{} of the {} Vandermonde matrix of the exact nodes, MPFR {} bits agreeing with {} bits",
            input.norm.name(),
            input.basis.name(),
            cert.bits,
            cert.low_bits
        ),
        horizon: None,
        max_ulps: input.max_ulps,
    };
    Ok(summarize(&ctx, &input.user, &cert.values))
}
