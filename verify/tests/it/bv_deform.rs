//! Patch deformation by the Bernstein inverse mapping (seed 001 eq 4) and the
//! continuity correction (§2.3), checked by evaluating the surfaces.

use splinelab::scalar::prelude::*;
use splinelab::surface_deformation::bv_solve::TensorSolver;
use splinelab::surface_deformation::continuity::{correct_continuity, join_defects};
use splinelab::surface_deformation::inverse_mapping::sample;
use splinelab::surface_deformation::vandermonde::NodeFamily;
use splinelab_verify::deform::{PushParams, push_surfaces, run_push};

fn params(patches: usize, degree: usize, nodes: NodeFamily, solver: TensorSolver) -> PushParams {
    PushParams {
        patches,
        degree,
        cx: 1.625,
        cy: 2.25,
        sigma: 1.25,
        depth: 1.5,
        nodes,
        solver,
    }
}

/// After eq 4 every patch passes through its moved samples, within the
/// backward-error bound of the solve (the samples have size ≈ 4 and
/// `cond(B̃)` is below 100 at degree 3).
fn passes_through_moved_samples<T: Real>(p: &PushParams) {
    let s = push_surfaces::<T>(p).unwrap();
    let tol = T::from_int(4096) * T::unit_roundoff();
    for ((before, after), flow) in s
        .initial
        .patches()
        .iter()
        .zip(s.deformed.patches())
        .zip(&s.flows)
    {
        let (b, a) = (
            sample(before, &s.samples).unwrap(),
            sample(after, &s.samples).unwrap(),
        );
        for ((b, a), f) in b.iter().zip(&a).zip(flow) {
            assert!((b + f - a).amax() <= tol, "{p:?}: {:?}", (b + f - a));
        }
    }
}

#[test]
fn deformed_patches_pass_through_the_moved_samples() {
    for solver in TensorSolver::all() {
        passes_through_moved_samples::<f64>(&params(3, 3, NodeFamily::Equispaced, solver));
    }
    passes_through_moved_samples::<Mp<128>>(&params(
        2,
        3,
        NodeFamily::ChebyshevGauss,
        TensorSolver::KroneckerMarcoMartinez,
    ));
}

/// C⁰ and matching cross-boundary derivatives (C¹ ⇒ G¹) along every shared
/// edge after the correction, measured by evaluating both patches; before it
/// the tangents visibly disagree (so the test can fail).
fn correction_restores_smooth_joins<T: Real>(p: &PushParams) {
    let s = push_surfaces::<T>(p).unwrap();
    let before = join_defects(&s.deformed, 7).unwrap();
    let after = join_defects(&s.corrected, 7).unwrap();
    let u = T::unit_roundoff();
    assert!(
        before.tangent > T::from_f64_exact(1e-6),
        "{p:?}: deformation left C¹ joins already"
    );
    assert!(
        after.position <= T::from_int(64) * u.clone(),
        "{p:?}: C⁰ gap {}",
        after.position.to_f64()
    );
    assert!(
        after.tangent <= T::from_int(256) * u * after.tangent_scale,
        "{p:?}: tangent mismatch {}",
        after.tangent.to_f64()
    );
    // Every shared edge's normals agree too (G¹), away from degenerate points.
    for q in 0..p.patches {
        for r in 0..p.patches - 1 {
            for k in 0..5 {
                let t = T::from_int(k) / T::from_int(4);
                let a = s.corrected.patch(q, r).normal(&t, &T::one()).unwrap();
                let b = s.corrected.patch(q, r + 1).normal(&t, &T::zero()).unwrap();
                assert!(
                    (a - b).norm()
                        <= T::from_f64_exact(1e-9).max(T::from_int(1024) * T::unit_roundoff())
                );
            }
        }
    }
}

#[test]
fn continuity_correction_gives_c0_and_g1_joins() {
    // Endpoint nodes keep C⁰ through the deformation; Chebyshev–Gauss nodes
    // break it, and the correction must restore it.
    for nodes in [NodeFamily::Equispaced, NodeFamily::ChebyshevGauss] {
        correction_restores_smooth_joins::<f64>(&params(
            4,
            3,
            nodes,
            TensorSolver::KroneckerMarcoMartinez,
        ));
    }
    // Degree 5 exercises the edge blocks between joint blocks.
    correction_restores_smooth_joins::<f64>(&params(
        3,
        5,
        NodeFamily::ChebyshevLobatto,
        TensorSolver::KroneckerLu,
    ));
    correction_restores_smooth_joins::<Mp<128>>(&params(
        3,
        3,
        NodeFamily::Equispaced,
        TensorSolver::FullLu,
    ));
}

#[test]
fn correction_is_idempotent() {
    let s = push_surfaces::<Mp<128>>(&params(
        3,
        3,
        NodeFamily::Equispaced,
        TensorSolver::KroneckerLu,
    ))
    .unwrap();
    let twice = correct_continuity(&s.corrected).unwrap();
    for (a, b) in twice.patches().iter().zip(s.corrected.patches()) {
        for (x, y) in a.control().iter().zip(b.control()) {
            assert!((x - y).amax() < Mp::<128>::from_f64_exact(1e-34));
        }
    }
}

#[test]
fn the_paper_experiment_10_by_10_bicubic_push() {
    let study = run_push(&PushParams::default()).unwrap();
    // The push reaches depth 2.5 at the centre; the control net dips below it
    // (control points overshoot a bump) but stays of that size.
    assert!(study.min_z < -2.0 && study.min_z > -4.0, "{}", study.min_z);
    assert!(
        study.max_sample_residual < 1e-13,
        "{}",
        study.max_sample_residual
    );
    assert!(study.deformed.tangent_relative > 1e-3);
    assert!(study.corrected.tangent_relative < 1e-14);
    assert!(study.corrected.position < 1e-14);
    // The f64 run agrees with the 128-bit twin to the conditioning of the
    // cubic solve (cond(B̃) < 100) times u.
    assert!(
        study.max_diff_vs_mp128 < 1e-13,
        "{}",
        study.max_diff_vs_mp128
    );
}
