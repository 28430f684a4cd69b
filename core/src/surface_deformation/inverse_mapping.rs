//! The Bernstein inverse mapping of seed 001 (Maeno–Okada–Toriwaki) eq 2–4:
//! from `(n+1)²` points sampled on a degree-`n` patch back to its control
//! points, and the deformation of a patch by flow vectors at those samples.
//!
//! Samples sit on a parameter grid `u_a × v_b` ([`SampleGrid`]), so the
//! matrix of eq 2 is `B̃ = B_u ⊗ B_v` and every solve goes through
//! [`solve_tensor`] with a caller-chosen [`TensorSolver`].

use super::bv_solve::{BvError, TensorSolver, check_nodes, solve_tensor};
use super::patch::{Patch, PatchError, PatchGrid, Point3};
use super::vandermonde::{NodeFamily, VandermondeError};
use crate::scalar::Real;
use crate::validation::{InputError, finite_points};
use nalgebra::DMatrix;

/// Why an inverse mapping or deformation failed. Nothing is computed on bad
/// input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InverseMappingError {
    /// The sample parameters are invalid (repeated — `B̃` singular —, out of
    /// `[0, 1]`, not increasing, non-finite) or a solve failed.
    #[error("sample parameters: {0}")]
    Nodes(#[from] BvError),
    /// A node family could not produce nodes.
    #[error(transparent)]
    Family(#[from] VandermondeError),
    /// A patch could not be built.
    #[error(transparent)]
    Patch(#[from] PatchError),
    /// The sample grid is not `(n+1) × (n+1)` for the patch degree.
    #[error("a degree-{degree} patch needs a {}×{} sample grid, got {u}×{v}", degree + 1, degree + 1)]
    GridShape {
        /// The patch degree.
        degree: usize,
        /// Parameters in `u`.
        u: usize,
        /// Parameters in `v`.
        v: usize,
    },
    /// The number of sample points or flow vectors is not `(n+1)²`.
    #[error("expected {expected} {what}, got {got}")]
    Count {
        /// `sample points` or `flow vectors`.
        what: &'static str,
        /// `(n+1)²`.
        expected: usize,
        /// Number given.
        got: usize,
    },
    /// A sample point or flow vector (index `a(n+1) + b`) is not finite.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The number of per-patch flow fields does not match the grid.
    #[error("the grid has {expected} patches, got flow vectors for {got}")]
    PatchCount {
        /// `n_u · n_v`.
        expected: usize,
        /// Flow fields given.
        got: usize,
    },
}

/// The sample parameters `u_0 < … < u_n` and `v_0 < … < v_n` in `[0, 1]`:
/// the `(n+1)²` samples are `R(u_a, v_b)`, stored at `a(n+1) + b`.
#[derive(Debug, Clone, PartialEq)]
pub struct SampleGrid<T: Real> {
    u: Vec<T>,
    v: Vec<T>,
}

impl<T: Real> SampleGrid<T> {
    /// A grid from explicit parameters, validated by [`check_nodes`] (so `B̃`
    /// is nonsingular) and of equal length `n + 1 ≥ 2`.
    /// **Method**: validation only; exact. **Source**: seed 001 eq 2 (the sample parameters).
    pub fn new(u: Vec<T>, v: Vec<T>) -> Result<Self, InverseMappingError> {
        check_nodes(&u)?;
        check_nodes(&v)?;
        if u.len() != v.len() || u.len() < 2 {
            return Err(InverseMappingError::GridShape {
                degree: u.len().max(2) - 1,
                u: u.len(),
                v: v.len(),
            });
        }
        Ok(SampleGrid { u, v })
    }

    /// The same node family in both directions, for degree `n`.
    pub fn from_family(family: NodeFamily, degree: usize) -> Result<Self, InverseMappingError> {
        let nodes: Vec<T> = family.nodes(degree)?;
        SampleGrid::new(nodes.clone(), nodes)
    }

    /// The degree `n` the grid serves.
    pub fn degree(&self) -> usize {
        self.u.len() - 1
    }

    /// The `u` parameters.
    pub fn u(&self) -> &[T] {
        &self.u
    }

    /// The `v` parameters.
    pub fn v(&self) -> &[T] {
        &self.v
    }

    fn check_degree(&self, degree: usize) -> Result<(), InverseMappingError> {
        if self.degree() != degree {
            return Err(InverseMappingError::GridShape {
                degree,
                u: self.u.len(),
                v: self.v.len(),
            });
        }
        Ok(())
    }
}

/// The samples `R̃ = B̃ P̃` of seed 001 eq 2: `R(u_a, v_b)` by evaluating the
/// patch ([`Patch::eval`], independent of any solver). **Cost** `O(n⁴)`.
/// **Accuracy**: that of [`Patch::eval`], `≤ γ_{4n+2} max |P_ij|` per
/// coordinate (non-negative Bernstein weights; Farouki & Rajan 1987).
pub fn sample<T: Real>(
    patch: &Patch<T>,
    grid: &SampleGrid<T>,
) -> Result<Vec<Point3<T>>, InverseMappingError> {
    grid.check_degree(patch.degree())?;
    let mut out = Vec::with_capacity(grid.u.len() * grid.v.len());
    for ua in &grid.u {
        for vb in &grid.v {
            out.push(patch.eval(ua, vb)?);
        }
    }
    Ok(out)
}

fn to_matrix<T: Real>(
    points: &[Point3<T>],
    what: &'static str,
    expected: usize,
) -> Result<DMatrix<T>, InverseMappingError> {
    if points.len() != expected {
        return Err(InverseMappingError::Count {
            what,
            expected,
            got: points.len(),
        });
    }
    finite_points(what, points)?;
    Ok(DMatrix::from_fn(expected, 3, |r, c| points[r][c].clone()))
}

fn to_points<T: Real>(m: &DMatrix<T>) -> Vec<Point3<T>> {
    m.row_iter()
        .map(|r| Point3::new(r[0].clone(), r[1].clone(), r[2].clone()))
        .collect()
}

/// The Bernstein inverse mapping, seed 001 eq 3: `P̃ = B̃⁻¹ R̃`, the control
/// points of the degree-`n` patch that passes through `samples[a(n+1)+b]` at
/// `(u_a, v_b)`.
///
/// **Cost** and **accuracy**: those of `solver` (see [`solve_tensor`]):
/// `O(n⁶)` or `O(n³)`; backward-stable solvers lose `log10 cond(B̃)`
/// digits, Marco–Martínez loses far fewer.
///
/// ```
/// use nalgebra::Vector3;
/// use splinelab::surface_deformation::bv_solve::TensorSolver;
/// use splinelab::surface_deformation::inverse_mapping::{SampleGrid, control_points};
/// use splinelab::surface_deformation::vandermonde::NodeFamily;
/// let grid = SampleGrid::<f64>::from_family(NodeFamily::Equispaced, 1).unwrap();
/// let s = [Vector3::zeros(), Vector3::y(), Vector3::x(), Vector3::new(1.0, 1.0, 1.0)];
/// let p = control_points(&grid, &s, TensorSolver::KroneckerMarcoMartinez).unwrap();
/// assert_eq!(p.point(1, 1), &Vector3::new(1.0, 1.0, 1.0));
/// ```
pub fn control_points<T: Real>(
    grid: &SampleGrid<T>,
    samples: &[Point3<T>],
    solver: TensorSolver,
) -> Result<Patch<T>, InverseMappingError> {
    let n = grid.degree();
    let r = to_matrix(samples, "sample points", (n + 1) * (n + 1))?;
    let p = solve_tensor(&grid.u, &grid.v, &r, solver)?;
    Ok(Patch::new(n, to_points(&p))?)
}

/// Deformation by flow vectors, seed 001 eq 4 (OCR fixed):
/// `P̃' = B̃⁻¹(B̃ P̃ + F̃) = P̃ + F̃⁰` with `F̃⁰ = B̃⁻¹ F̃`: the sample
/// `R(u_a, v_b)` moves by `flow[a(n+1)+b]` and the new patch passes through the
/// moved samples. Solving for `F̃⁰` rather than for the moved samples keeps the
/// undeformed part exact (`F = 0` gives `P' = P` bit for bit).
///
/// **Cost**/**accuracy**: those of `solver` on one 3-column right-hand side;
/// the error in `P'` is the error of `F̃⁰`, relative to `|F̃⁰|`.
pub fn deform<T: Real>(
    patch: &Patch<T>,
    grid: &SampleGrid<T>,
    flow: &[Point3<T>],
    solver: TensorSolver,
) -> Result<Patch<T>, InverseMappingError> {
    let n = patch.degree();
    grid.check_degree(n)?;
    let f = to_matrix(flow, "flow vectors", (n + 1) * (n + 1))?;
    let f0 = solve_tensor(&grid.u, &grid.v, &f, solver)?;
    let moved = patch
        .control()
        .iter()
        .zip(to_points(&f0))
        .map(|(p, d)| p + d)
        .collect();
    Ok(Patch::new(n, moved)?)
}

/// [`deform`] applied to every patch of a grid, `flows[p·n_v + q]` being the
/// flow at patch `(p, q)`'s samples. Everything is validated before anything
/// is solved. The joins between patches are not corrected here (see
/// [`continuity`](super::continuity)).
/// **Method**: [`deform`] per patch, seed 001 eq 4. **Accuracy**: every
/// deformed patch passes through its moved samples
/// (`verify/tests/it/bv_deform.rs::deformed_patches_pass_through_the_moved_samples`,
/// which runs this routine through verify's `push_surfaces`).
pub fn deform_grid<T: Real>(
    surface: &PatchGrid<T>,
    grid: &SampleGrid<T>,
    flows: &[Vec<Point3<T>>],
    solver: TensorSolver,
) -> Result<PatchGrid<T>, InverseMappingError> {
    let expected = surface.patches().len();
    if flows.len() != expected {
        return Err(InverseMappingError::PatchCount {
            expected,
            got: flows.len(),
        });
    }
    grid.check_degree(surface.degree())?;
    let k = (grid.degree() + 1).pow(2);
    for f in flows {
        to_matrix(f, "flow vectors", k)?;
    }
    let patches = surface
        .patches()
        .iter()
        .zip(flows)
        .map(|(p, f)| deform(p, grid, f, solver))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(PatchGrid::new(surface.nu(), surface.nv(), patches)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deformed_patch_passes_through_the_moved_samples() {
        let p = Patch::<f64>::bilinear(3, &Point3::zeros(), &Point3::x(), &Point3::y()).unwrap();
        let grid = SampleGrid::from_family(NodeFamily::ChebyshevGauss, 3).unwrap();
        let before = sample(&p, &grid).unwrap();
        let flow: Vec<Point3<f64>> = before
            .iter()
            .map(|s| Point3::new(0.1 * s.y, 0.0, (s.x * 3.0).sin() * s.y))
            .collect();
        for solver in TensorSolver::all() {
            let q = deform(&p, &grid, &flow, solver).unwrap();
            let after = sample(&q, &grid).unwrap();
            for ((b, f), a) in before.iter().zip(&flow).zip(&after) {
                assert!(
                    (b + f - a).norm() < 1e-14,
                    "{solver:?}: {a:?} vs {:?}",
                    b + f
                );
            }
        }
    }

    #[test]
    fn bad_samples_and_flows_are_typed_errors() {
        let p = Patch::<f64>::bilinear(2, &Point3::zeros(), &Point3::x(), &Point3::y()).unwrap();
        assert!(matches!(
            SampleGrid::new(vec![0.0, 0.5, 0.5], vec![0.0, 0.5, 1.0]),
            Err(InverseMappingError::Nodes(BvError::RepeatedNode {
                index: 1
            }))
        ));
        assert!(matches!(
            SampleGrid::new(vec![0.0, 0.5, 1.2], vec![0.0, 0.5, 1.0]),
            Err(InverseMappingError::Nodes(BvError::NodeOutOfRange {
                index: 2,
                ..
            }))
        ));
        assert!(matches!(
            SampleGrid::new(vec![0.0, 1.0], vec![0.0, 0.5, 1.0]),
            Err(InverseMappingError::GridShape { .. })
        ));
        let g3 = SampleGrid::from_family(NodeFamily::Equispaced, 3).unwrap();
        assert!(matches!(
            sample(&p, &g3),
            Err(InverseMappingError::GridShape { degree: 2, .. })
        ));
        let g = SampleGrid::from_family(NodeFamily::Equispaced, 2).unwrap();
        let mut flow = vec![Point3::zeros(); 9];
        assert!(matches!(
            deform(&p, &g, &flow[..8], TensorSolver::FullLu),
            Err(InverseMappingError::Count {
                expected: 9,
                got: 8,
                ..
            })
        ));
        flow[4].z = f64::NAN;
        assert!(matches!(
            deform(&p, &g, &flow, TensorSolver::FullLu),
            Err(InverseMappingError::Input(InputError::NonFiniteAt {
                index: 4,
                ..
            }))
        ));
    }
}
