//! Why a study of the Bernstein–Vandermonde matrices (conditioning, the
//! tensor solvers) could not be measured: one error type for both.

use splinelab::matrix_condition::ConditionError;
use splinelab::surface_deformation::bv_solve::BvError;
use splinelab::surface_deformation::vandermonde::VandermondeError;

/// Errors of the conditioning and solver studies.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StudyError {
    /// The nodes or the matrix could not be built.
    #[error(transparent)]
    Nodes(#[from] VandermondeError),
    /// A condition number could not be computed.
    #[error(transparent)]
    Condition(#[from] ConditionError),
    /// A solve failed (in f64 or in the reference).
    #[error("{solver}: {source}")]
    Solve {
        /// The solver that failed.
        solver: &'static str,
        /// Why.
        source: BvError,
    },
}
