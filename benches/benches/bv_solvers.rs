//! Bernstein–Vandermonde solver cost against degree: the tensor system
//! `(B_u ⊗ B_u) X = R` of seed 001 eq 3 with 3 right-hand-side columns (a
//! patch's x, y, z) by full LU (`O(n⁶)`), Kronecker LU and Kronecker
//! Marco–Martínez (`O(n³)`), and the univariate solves (GEPP `O(n³)` vs
//! Marco–Martínez `O(n²)`), each including its factorisation. The degenerate
//! input: nodes with both endpoints (equispaced), where `t_n = 1` makes
//! `x_n = t_n/(1 − t_n)` infinite and the endpoint treatment is exercised.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use nalgebra::DMatrix;
use splinelab::surface_deformation::bv_solve::{Method1d, TensorSolver, solve_1d, solve_tensor};
use splinelab::surface_deformation::vandermonde::NodeFamily;
use std::hint::black_box;

/// Deterministic right-hand side in [−1, 1] (a fixed LCG: no rand dependency).
fn rhs(rows: usize, cols: usize) -> DMatrix<f64> {
    let mut s = 0x9E37_79B9_7F4A_7C15u64;
    DMatrix::from_fn(rows, cols, |_, _| {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    })
}

fn tensor(c: &mut Criterion) {
    let mut g = c.benchmark_group("bv_tensor_solve");
    for n in [3usize, 5, 10, 15, 20] {
        let t: Vec<f64> = NodeFamily::Equispaced.nodes(n).unwrap();
        let r = rhs((n + 1) * (n + 1), 3);
        for s in TensorSolver::all() {
            if s == TensorSolver::FullLu && n > 15 {
                continue; // O(n⁶): seconds per sample beyond this.
            }
            g.bench_with_input(BenchmarkId::new(s.name(), n), &n, |b, _| {
                b.iter(|| solve_tensor(black_box(&t), black_box(&t), black_box(&r), s).unwrap())
            });
        }
    }
    g.finish();
}

fn univariate(c: &mut Criterion) {
    let mut g = c.benchmark_group("bv_1d_solve");
    for n in [3usize, 10, 30, 60] {
        for family in [NodeFamily::Equispaced, NodeFamily::ChebyshevGauss] {
            let t: Vec<f64> = family.nodes(n).unwrap();
            let r = rhs(n + 1, 1);
            for (m, name) in [
                (Method1d::Gepp, "gepp"),
                (Method1d::MarcoMartinez, "marco-martinez"),
            ] {
                g.bench_with_input(
                    BenchmarkId::new(format!("{name}/{family}"), n),
                    &n,
                    |b, _| b.iter(|| solve_1d(black_box(&t), black_box(&r), m).unwrap()),
                );
            }
        }
    }
    g.finish();
}

criterion_group!(benches, tensor, univariate);
criterion_main!(benches);
