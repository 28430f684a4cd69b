//! How accurately Bernstein–Vandermonde systems can be solved in f64
//! (seed 001 eq 3; Marco–Martínez 2007).
//!
//! For each degree, node family and kind of right-hand side the tensor system
//! `(B_u ⊗ B_u) x = r` is solved in f64 by the three [`TensorSolver`]s, and the
//! univariate system `B_u c = r` by GEPP and by Marco–Martínez. The reference
//! is the solution of *the same* system — the f64 nodes and the f64
//! right-hand side taken as exact data — computed by Kronecker LU in
//! `REF_BITS`-bit MPFR, whose own error (`≈ cond · 2^-256`) is negligible
//! next to anything f64 can resolve. The measured errors are set against
//! `cond₂ · u`, the error a backward-stable solver may make.

use crate::conditioning::{Basis, CondCase, condition_numbers};
use crate::metrics::relative_error;
use crate::timing::try_median_ns;
use nalgebra::DMatrix;
use rayon::prelude::*;
use rug::Float;
use serde::{Deserialize, Serialize};
use splinelab::scalar::{Mp, Real};
use splinelab::surface_deformation::bv_solve::{
    BvError, Method1d, TensorSolver, solve_1d, solve_tensor,
};
use splinelab::surface_deformation::vandermonde::NodeFamily;

/// Bits of the MPFR reference.
pub const REF_BITS: u32 = 256;
type Reference = Mp<REF_BITS>;

/// Right-hand sides per case (the errors reported are maxima over them).
pub const RHS_SAMPLES: usize = 4;

pub use crate::study_error::StudyError;

/// The kind of right-hand side.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RhsKind {
    /// Entries uniform in `[−1, 1]`.
    Random,
    /// `(−1)^{a+b} · w`, `w` uniform in `[½, 3/2]` (checkerboard for the
    /// tensor system, alternating for the univariate one): the data for
    /// which Marco–Martínez involves no cancellation at all.
    SignAlternating,
}

impl RhsKind {
    /// Both kinds.
    pub const ALL: [RhsKind; 2] = [RhsKind::Random, RhsKind::SignAlternating];

    /// Name for tables and JSON.
    pub fn name(self) -> &'static str {
        match self {
            RhsKind::Random => "random",
            RhsKind::SignAlternating => "sign-alternating",
        }
    }
}

/// A solution's error against the reference.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SolveError {
    /// `max_i |x̂_i − x_i| / |x_i|` over all components and right-hand sides.
    pub componentwise: f64,
    /// `max_col ‖x̂ − x‖_∞ / ‖x‖_∞`.
    pub normwise: f64,
}

/// One case: a degree, node family and kind of right-hand side.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BvRow {
    /// Degree `n` (univariate size `n + 1`, tensor size `(n+1)²`).
    pub degree: usize,
    /// Node family (both directions).
    pub nodes: NodeFamily,
    /// Kind of right-hand side.
    pub rhs: RhsKind,
    /// `cond₂(B_u)` (256-bit MPFR).
    pub cond2_1d: f64,
    /// `cond₂(B_u ⊗ B_u) = cond₂(B_u)²`.
    pub cond2_tensor: f64,
    /// (a) LU with partial pivoting on the assembled tensor matrix.
    pub full_lu: SolveError,
    /// (b) Kronecker structure, univariate GEPP.
    pub kronecker_lu: SolveError,
    /// (c) Kronecker structure, univariate Marco–Martínez.
    pub kronecker_mm: SolveError,
    /// Univariate GEPP on `B_u c = r`.
    pub gepp_1d: SolveError,
    /// Univariate Marco–Martínez on `B_u c = r`.
    pub mm_1d: SolveError,
}

use crate::rng::SplitMix64;

/// `RHS_SAMPLES` right-hand sides of `rows` entries; entry `k` of a tensor
/// right-hand side is grid point `(k / side, k % side)`.
pub fn right_hand_sides(kind: RhsKind, rows: usize, side: usize, seed: u64) -> DMatrix<f64> {
    let mut rng = SplitMix64::new(seed);
    DMatrix::from_fn(rows, RHS_SAMPLES, |k, _| {
        let x = rng.unit();
        match kind {
            RhsKind::Random => 2.0 * x - 1.0,
            RhsKind::SignAlternating => {
                let sign = if (k / side + k % side).is_multiple_of(2) {
                    1.0
                } else {
                    -1.0
                };
                sign * (0.5 + x)
            }
        }
    })
}

/// Componentwise and normwise errors of `x` against `reference`.
pub fn solve_error(x: &DMatrix<f64>, reference: &DMatrix<Reference>) -> SolveError {
    let mut e = SolveError {
        componentwise: 0.0,
        normwise: 0.0,
    };
    for (xc, rc) in x.column_iter().zip(reference.column_iter()) {
        let (mut diff, mut norm) = (0f64, 0f64);
        for (xi, ri) in xc.iter().zip(rc.iter()) {
            let rf = ri.to_float();
            e.componentwise = e.componentwise.max(relative_error(xi, &rf));
            let d = Float::with_val(REF_BITS, xi - &rf).abs().to_f64();
            diff = diff.max(d);
            norm = norm.max(rf.abs().to_f64());
        }
        e.normwise = e.normwise.max(if norm == 0.0 { diff } else { diff / norm });
    }
    e
}

fn solve_err(solver: &'static str) -> impl Fn(BvError) -> StudyError {
    move |source| StudyError::Solve { solver, source }
}

fn to_ref(m: &DMatrix<f64>) -> DMatrix<Reference> {
    m.map(Reference::from_f64_exact)
}

/// Measures one case (see the module docs).
pub fn measure(degree: usize, nodes: NodeFamily, rhs: RhsKind) -> Result<BvRow, StudyError> {
    let t: Vec<f64> = nodes.nodes(degree)?;
    let t_ref: Vec<Reference> = t.iter().map(|&x| Reference::from_f64_exact(x)).collect();
    let side = degree + 1;
    let seed = (degree as u64) << 8 | (nodes as u64) << 4 | rhs as u64;
    let r2 = right_hand_sides(rhs, side * side, side, seed);
    let r1 = right_hand_sides(rhs, side, side, seed ^ 0x5555);
    let ref2 = solve_tensor(&t_ref, &t_ref, &to_ref(&r2), TensorSolver::KroneckerLu)
        .map_err(solve_err("reference"))?;
    let ref1 = solve_1d(&t_ref, &to_ref(&r1), Method1d::Gepp).map_err(solve_err("reference"))?;
    let tensor = |s: TensorSolver| -> Result<SolveError, StudyError> {
        Ok(solve_error(
            &solve_tensor(&t, &t, &r2, s).map_err(solve_err(s.name()))?,
            &ref2,
        ))
    };
    let one_d = |m: Method1d, name| -> Result<SolveError, StudyError> {
        Ok(solve_error(
            &solve_1d(&t, &r1, m).map_err(solve_err(name))?,
            &ref1,
        ))
    };
    let case = CondCase {
        degree,
        nodes,
        basis: Basis::Bernstein,
        tensor: false,
    };
    let c1 = condition_numbers::<Reference>(&case)?.cond2.to_f64();
    Ok(BvRow {
        degree,
        nodes,
        rhs,
        cond2_1d: c1,
        cond2_tensor: c1 * c1,
        full_lu: tensor(TensorSolver::FullLu)?,
        kronecker_lu: tensor(TensorSolver::KroneckerLu)?,
        kronecker_mm: tensor(TensorSolver::KroneckerMarcoMartinez)?,
        gepp_1d: one_d(Method1d::Gepp, "gepp-1d")?,
        mm_1d: one_d(Method1d::MarcoMartinez, "marco-martinez-1d")?,
    })
}

/// Every degree × family × right-hand-side kind, in parallel; rows in a fixed
/// order (family, kind, degree) whatever the thread count. Largest cases
/// first, so the `O(n⁶)` full LU of high degrees does not end the run alone.
pub fn run_bv_solvers(
    degrees: &[usize],
    families: &[NodeFamily],
    kinds: &[RhsKind],
) -> Result<Vec<BvRow>, StudyError> {
    let mut cases: Vec<(usize, NodeFamily, RhsKind)> = families
        .iter()
        .flat_map(|&f| {
            kinds
                .iter()
                .flat_map(move |&k| degrees.iter().map(move |&d| (d, f, k)))
        })
        .collect();
    let order = cases.clone();
    cases.sort_by_key(|c| std::cmp::Reverse(c.0));
    let mut rows: Vec<BvRow> = cases
        .par_iter()
        .map(|&(d, f, k)| measure(d, f, k))
        .collect::<Result<_, _>>()?;
    rows.sort_by_key(|r| order.iter().position(|c| *c == (r.degree, r.nodes, r.rhs)));
    Ok(rows)
}

/// Wall-clock time of one solver at one degree.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TimingRow {
    /// Degree `n`.
    pub degree: usize,
    /// Solver name ([`TensorSolver::name`], or `gepp-1d` / `marco-martinez-1d`).
    pub solver: String,
    /// Median time of one solve over the repetitions, in seconds
    /// (includes factorising; [`crate::timing`]).
    pub seconds: f64,
}

/// Times every solver on a 3-column right-hand side (the x, y, z of a
/// patch) at equispaced nodes: the median of `reps` samples. Sequential, so
/// the solvers do not compete for cores. Not used in any test: speed is
/// only reported, the criterion benches are the reference.
pub fn time_solvers(degrees: &[usize], reps: usize) -> Result<Vec<TimingRow>, StudyError> {
    let mut rows = Vec::new();
    for &degree in degrees {
        let t: Vec<f64> = NodeFamily::Equispaced.nodes(degree)?;
        let side = degree + 1;
        let r2 = right_hand_sides(RhsKind::Random, side * side, side, 7)
            .columns(0, 3)
            .into_owned();
        let r1 = right_hand_sides(RhsKind::Random, side, side, 7)
            .columns(0, 3)
            .into_owned();
        for s in TensorSolver::all() {
            let seconds = 1e-9
                * try_median_ns(reps, || {
                    solve_tensor(&t, &t, &r2, s)
                        .map(drop)
                        .map_err(solve_err(s.name()))
                })?;
            rows.push(TimingRow {
                degree,
                solver: s.name().into(),
                seconds,
            });
        }
        for (m, name) in [
            (Method1d::Gepp, "gepp-1d"),
            (Method1d::MarcoMartinez, "marco-martinez-1d"),
        ] {
            let seconds = 1e-9
                * try_median_ns(reps, || {
                    solve_1d(&t, &r1, m).map(drop).map_err(solve_err(name))
                })?;
            rows.push(TimingRow {
                degree,
                solver: name.into(),
                seconds,
            });
        }
    }
    Ok(rows)
}
