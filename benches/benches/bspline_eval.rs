//! B-spline and global-cubic evaluation at 10⁶ parameters: one `eval` per
//! point (a `Result` each, collected) against batch `eval_into` a caller's
//! buffer, for sorted and for shuffled parameters. Curves: a cubic on N = 1000
//! planar control points with clamped uniform knots, and the natural global
//! cubic interpolant of 1000 planar points. The scipy peer is
//! `benches/scipy/bspline_eval.py` (`BSpline.__call__`, same curves and
//! parameters). Degenerate input: every parameter at one knot.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::Vector2;
use splinelab::bspline::de_boor::BSpline;
use splinelab::bspline::knots::KnotVector;
use splinelab::curves::global_cubic::{CubicEnds, interpolant};
use std::hint::black_box;

const POINTS: usize = 1000;
const PARAMS: usize = 1_000_000;

fn net() -> Vec<Vector2<f64>> {
    (0..POINTS)
        .map(|i| Vector2::new(i as f64, ((i * 13) % 7) as f64))
        .collect()
}

/// `PARAMS` parameters evenly over `[lo, hi]`, in order or shuffled by a
/// fixed multiplicative permutation (no rand dependency).
fn params(lo: f64, hi: f64, shuffled: bool) -> Vec<f64> {
    let at = |j: usize| lo + (hi - lo) * j as f64 / (PARAMS - 1) as f64;
    if shuffled {
        // 999_983 is prime and coprime to 10⁶: j ↦ 999_983·j mod 10⁶ permutes.
        (0..PARAMS).map(|j| at(j * 999_983 % PARAMS)).collect()
    } else {
        (0..PARAMS).map(at).collect()
    }
}

fn curves() -> Vec<(&'static str, BSpline<f64, 2>)> {
    let clamped = BSpline::new(4, net(), KnotVector::clamped_uniform(4, POINTS).unwrap()).unwrap();
    let global = interpolant(&net(), &CubicEnds::Natural).unwrap();
    vec![("bspline", clamped), ("global-cubic", global)]
}

fn evaluation(c: &mut Criterion) {
    let mut g = c.benchmark_group("bspline_eval");
    g.throughput(Throughput::Elements(PARAMS as u64));
    g.sample_size(10);
    for (name, curve) in curves() {
        let (lo, hi) = curve.domain();
        let knot = curve.knots().as_slice()[POINTS / 2];
        let sets = [
            ("sorted", params(lo, hi, false)),
            ("shuffled", params(lo, hi, true)),
            ("at-one-knot", vec![knot; PARAMS]),
        ];
        for (order, ts) in &sets {
            let id = format!("{name}/{order}");
            g.bench_function(BenchmarkId::new("pointwise", &id), |b| {
                b.iter(|| {
                    ts.iter()
                        .map(|t| curve.eval(black_box(t)).unwrap())
                        .collect::<Vec<_>>()
                })
            });
            let mut out = vec![Vector2::zeros(); PARAMS];
            g.bench_function(BenchmarkId::new("eval_into", &id), |b| {
                b.iter(|| curve.eval_into(black_box(ts), &mut out).unwrap())
            });
        }
    }
    g.finish();
}

criterion_group!(benches, evaluation);
criterion_main!(benches);
