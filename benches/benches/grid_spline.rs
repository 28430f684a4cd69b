//! The exact not-a-knot grid spline (issue 49): construction on jittered
//! rectilinear grids (300×300×40 and 2000×2000 float64, cubic and quintic)
//! beside a plain copy of the same bytes (the memory wall: construction is
//! one copy in plus two sweeps per axis), and evaluation at 10⁵ random
//! points. Degenerate input: a grid whose nodes come in pairs 1e-9 apart
//! (κ of each axis ~1e9, the factorization still without pivoting). The
//! scipy peer is `python/bench/rgi.py` (`RegularGridInterpolator`, whose
//! iterative solve takes 11–48 s on the 3-D case).

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use splinelab::gridded::GridSpline;
use splinelab::ndarray::{ArrayD, IxDyn};
use std::hint::black_box;

/// A deterministic stream in [0, 1) (no rand dependency).
fn stream(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn jittered(n: usize, seed: u64) -> Vec<f64> {
    let mut r = stream(seed);
    let mut x = 0.0;
    (0..n)
        .map(|_| {
            x += 0.5 + r();
            x
        })
        .collect()
}

/// Pairs of nodes 1e-9 apart.
fn paired(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| (i / 2) as f64 + if i % 2 == 1 { 1e-9 } else { 0.0 })
        .collect()
}

fn values(grid: &[Vec<f64>]) -> ArrayD<f64> {
    let mut shape: Vec<usize> = grid.iter().map(Vec::len).collect();
    shape.push(1);
    let mut r = stream(99);
    ArrayD::from_shape_simple_fn(IxDyn(&shape), move || r() - 0.5)
}

fn construction(c: &mut Criterion) {
    let mut g = c.benchmark_group("grid_spline_build");
    g.sample_size(10);
    let cases = [
        (
            "300x300x40",
            vec![jittered(300, 1), jittered(300, 2), jittered(40, 3)],
        ),
        ("2000x2000", vec![jittered(2000, 4), jittered(2000, 5)]),
        ("paired-1e-9 300x300", vec![paired(300), paired(300)]),
    ];
    for (name, grid) in &cases {
        let v = values(grid);
        g.throughput(Throughput::Bytes((v.len() * 8) as u64));
        g.bench_function(BenchmarkId::new("memcpy", name), |b| {
            let mut out = vec![0.0; v.len()];
            b.iter(|| out.copy_from_slice(black_box(v.as_slice().unwrap())))
        });
        for k in [3usize, 5] {
            g.bench_function(BenchmarkId::new(format!("degree {k}"), name), |b| {
                b.iter(|| GridSpline::interpolate(grid.clone(), black_box(v.view()), k).unwrap())
            });
        }
    }
    g.finish();
}

fn evaluation(c: &mut Criterion) {
    let mut g = c.benchmark_group("grid_spline_eval");
    g.sample_size(10);
    let grid = vec![jittered(300, 1), jittered(300, 2), jittered(40, 3)];
    let v = values(&grid);
    let mut r = stream(7);
    let points: Vec<f64> = (0..100_000)
        .flat_map(|_| {
            grid.iter()
                .map(|g| g[0] + (g[g.len() - 1] - g[0]) * r())
                .collect::<Vec<_>>()
        })
        .collect();
    g.throughput(Throughput::Elements(100_000));
    for k in [1usize, 3, 5] {
        let s = GridSpline::interpolate(grid.clone(), v.view(), k).unwrap();
        let mut out = vec![0.0; 100_000];
        g.bench_function(BenchmarkId::new("300x300x40", format!("degree {k}")), |b| {
            b.iter(|| s.eval_into(black_box(&points), &[], &mut out).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, construction, evaluation);
criterion_main!(benches);
