//! Boehm knot insertion cost against the number of control points N (cubic,
//! clamped uniform knots), one insertion mid-domain, plus global midpoint
//! refinement (N insertions). Degenerate input: inserting an existing knot.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use nalgebra::Vector2;
use splinelab::bspline::de_boor::BSpline;
use splinelab::bspline::knots::KnotVector;
use std::hint::black_box;

fn insertion(c: &mut Criterion) {
    let mut g = c.benchmark_group("knot_insertion");
    for exp in 2..=5u32 {
        let n = 10usize.pow(exp);
        let q: Vec<Vector2<f64>> = (0..n)
            .map(|i| Vector2::new(i as f64, ((i * 13) % 7) as f64))
            .collect();
        let curve = BSpline::new(4, q, KnotVector::clamped_uniform(4, n).unwrap()).unwrap();
        let existing = curve.knots().as_slice()[n / 2];
        g.bench_with_input(BenchmarkId::new("insert_once", n), &n, |b, _| {
            b.iter(|| curve.insert_knot(black_box(&0.5003)).unwrap())
        });
        g.bench_with_input(BenchmarkId::new("insert_existing", n), &n, |b, _| {
            b.iter(|| curve.insert_knot(black_box(&existing)).unwrap())
        });
        if n <= 1000 {
            g.bench_with_input(BenchmarkId::new("refine_midpoints", n), &n, |b, _| {
                b.iter(|| curve.refine_midpoints().unwrap())
            });
        }
    }
    g.finish();
}

criterion_group!(benches, insertion);
criterion_main!(benches);
