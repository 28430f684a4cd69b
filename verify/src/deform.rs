//! The deformation experiment of seed 001 §3: a 10 × 10 grid of bicubic
//! patches on the plane `z = 0`, "pushed" by a smooth flow field through the
//! Bernstein inverse mapping (eq 4), then corrected for continuity (§2.3).
//!
//! Measured: that every deformed patch passes through its moved samples
//! (eq 4's promise), the join defects (C⁰ gap and cross-boundary tangent
//! mismatch) before and after the correction, and how far the f64 control
//! points are from an MPFR twin of the whole computation.

use serde::{Deserialize, Serialize};
use splinelab::scalar::{Mp, Real};
use splinelab::surface_deformation::bv_solve::TensorSolver;
use splinelab::surface_deformation::continuity::{
    ContinuityError, correct_continuity, join_defects,
};
use splinelab::surface_deformation::inverse_mapping::{
    InverseMappingError, SampleGrid, deform_grid, sample,
};
use splinelab::surface_deformation::patch::{PatchError, PatchGrid, Point3};
use splinelab::surface_deformation::vandermonde::NodeFamily;

/// Errors of the experiment.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DeformError {
    /// Building the surface failed.
    #[error(transparent)]
    Patch(#[from] PatchError),
    /// The inverse mapping failed.
    #[error(transparent)]
    Mapping(#[from] InverseMappingError),
    /// The correction failed.
    #[error(transparent)]
    Continuity(#[from] ContinuityError),
}

/// The push: `F(x, y, z) = (0, 0, −depth · exp(−((x−cx)² + (y−cy)²)/(2σ²)))`
/// applied to a plane of `patches × patches` unit patches of `degree`.
/// All values are dyadic, so they are exact in every precision.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PushParams {
    /// Patches per side (10 in the paper).
    pub patches: usize,
    /// Patch degree (3 in the paper).
    pub degree: usize,
    /// Centre of the push, `x`.
    pub cx: f64,
    /// Centre of the push, `y`.
    pub cy: f64,
    /// Width σ of the Gaussian.
    pub sigma: f64,
    /// Depth of the push.
    pub depth: f64,
    /// Sample parameters on every patch.
    pub nodes: NodeFamily,
    /// Solver for eq 4.
    pub solver: TensorSolver,
}

impl Default for PushParams {
    fn default() -> Self {
        PushParams {
            patches: 10,
            degree: 3,
            cx: 4.625,
            cy: 5.25,
            sigma: 1.75,
            depth: 2.5,
            nodes: NodeFamily::Equispaced,
            solver: TensorSolver::KroneckerMarcoMartinez,
        }
    }
}

/// The flow vector at `p` (see [`PushParams`]).
pub fn push_flow<T: Real>(p: &Point3<T>, params: &PushParams) -> Point3<T> {
    let c = |x: f64| T::from_f64_exact(x);
    let (dx, dy) = (p[0].clone() - c(params.cx), p[1].clone() - c(params.cy));
    let s2 = c(2.0 * params.sigma * params.sigma);
    let g = (-(dx.clone() * dx + dy.clone() * dy) / s2).exp();
    Point3::new(T::zero(), T::zero(), -(c(params.depth) * g))
}

/// The three surfaces of the experiment.
#[derive(Debug, Clone)]
pub struct PushSurfaces<T: Real> {
    /// The initial plane.
    pub initial: PatchGrid<T>,
    /// After eq 4, patch by patch.
    pub deformed: PatchGrid<T>,
    /// After the §2.3 correction.
    pub corrected: PatchGrid<T>,
    /// The sample grid used on every patch.
    pub samples: SampleGrid<T>,
    /// The flow vectors, per patch.
    pub flows: Vec<Vec<Point3<T>>>,
}

/// Runs the experiment in precision `T`.
pub fn push_surfaces<T: Real>(params: &PushParams) -> Result<PushSurfaces<T>, DeformError> {
    let initial = PatchGrid::planar(params.patches, params.patches, params.degree, &T::one())?;
    let samples = SampleGrid::from_family(params.nodes, params.degree)?;
    let flows = initial
        .patches()
        .iter()
        .map(|p| {
            Ok(sample(p, &samples)?
                .iter()
                .map(|s| push_flow(s, params))
                .collect())
        })
        .collect::<Result<Vec<Vec<_>>, DeformError>>()?;
    let deformed = deform_grid(&initial, &samples, &flows, params.solver)?;
    let corrected = correct_continuity(&deformed)?;
    Ok(PushSurfaces {
        initial,
        deformed,
        corrected,
        samples,
        flows,
    })
}

/// Join defects in f64 (see [`splinelab::surface_deformation::continuity::JoinDefects`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Defects {
    /// Largest C⁰ gap.
    pub position: f64,
    /// Largest cross-boundary derivative mismatch.
    pub tangent: f64,
    /// `tangent` divided by the largest derivative norm.
    pub tangent_relative: f64,
}

/// Samples per edge for the defect measurement.
pub const EDGE_SAMPLES: usize = 9;

/// The join defects of `g` measured at [`EDGE_SAMPLES`] points per edge.
pub fn defects<T: Real>(g: &PatchGrid<T>) -> Result<Defects, DeformError> {
    let d = join_defects(g, EDGE_SAMPLES)?;
    let scale = d.tangent_scale.to_f64();
    Ok(Defects {
        position: d.position.to_f64(),
        tangent: d.tangent.to_f64(),
        tangent_relative: if scale > 0.0 {
            d.tangent.to_f64() / scale
        } else {
            d.tangent.to_f64()
        },
    })
}

/// A grid's control nets as plain f64 triples (for pictures and JSON).
pub fn grid_to_f64<T: Real>(g: &PatchGrid<T>) -> Vec<Vec<[f64; 3]>> {
    g.patches()
        .iter()
        .map(|p| {
            p.control()
                .iter()
                .map(|q| [q[0].to_f64(), q[1].to_f64(), q[2].to_f64()])
                .collect()
        })
        .collect()
}

/// The experiment's measurements and its surfaces (f64).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PushStudy {
    /// The parameters.
    pub params: PushParams,
    /// `max |R'(u_a, v_b) − (R(u_a, v_b) + F_ab)|` over all patches and
    /// samples: the deformed surface passes through the moved samples.
    pub max_sample_residual: f64,
    /// Join defects after eq 4, before the correction.
    pub deformed: Defects,
    /// Join defects after the correction.
    pub corrected: Defects,
    /// Largest move of a control point by the correction.
    pub max_correction_shift: f64,
    /// Largest difference between the f64 corrected control points and a
    /// 128-bit MPFR run of the whole experiment.
    pub max_diff_vs_mp128: f64,
    /// Deepest point of the corrected surface's control net (`min z`).
    pub min_z: f64,
    /// Control nets of the initial, deformed and corrected surfaces.
    pub surfaces: [Vec<Vec<[f64; 3]>>; 3],
}

/// `max |R'(u_a, v_b) − (R(u_a, v_b) + F_ab)|` over every patch and sample:
/// how far the deformed surface misses the moved samples (eq 4's promise is 0).
pub fn sample_residual<T: Real>(
    initial: &PatchGrid<T>,
    deformed: &PatchGrid<T>,
    samples: &SampleGrid<T>,
    flows: &[Vec<Point3<T>>],
) -> Result<f64, DeformError> {
    let mut worst = 0f64;
    for ((before, after), flow) in initial.patches().iter().zip(deformed.patches()).zip(flows) {
        let (b, a) = (sample(before, samples)?, sample(after, samples)?);
        for ((b, a), f) in b.iter().zip(&a).zip(flow) {
            worst = worst.max((b + f - a).norm().to_f64());
        }
    }
    Ok(worst)
}

fn max_diff(a: &[Vec<[f64; 3]>], b: &[Vec<[f64; 3]>]) -> f64 {
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .flat_map(|(p, q)| p.iter().zip(q).map(|(x, y)| (x - y).abs()))
        .fold(0.0, f64::max)
}

/// Runs the experiment in f64 and in 128-bit MPFR and measures it.
pub fn run_push(params: &PushParams) -> Result<PushStudy, DeformError> {
    let s = push_surfaces::<f64>(params)?;
    let twin = push_surfaces::<Mp<128>>(params)?;
    let corrected = grid_to_f64(&s.corrected);
    let deformed = grid_to_f64(&s.deformed);
    Ok(PushStudy {
        params: *params,
        max_sample_residual: sample_residual(&s.initial, &s.deformed, &s.samples, &s.flows)?,
        deformed: defects(&s.deformed)?,
        corrected: defects(&s.corrected)?,
        max_correction_shift: max_diff(&corrected, &deformed),
        max_diff_vs_mp128: max_diff(&corrected, &grid_to_f64(&twin.corrected)),
        min_z: corrected
            .iter()
            .flatten()
            .map(|p| p[2])
            .fold(f64::INFINITY, f64::min),
        surfaces: [grid_to_f64(&s.initial), deformed, corrected],
    })
}
