//! Point-edit cost: S-spline local update (cubic, half-width for ε = 1e-6
//! by the uniform criterion) against the global natural cubic spline
//! re-solve, for curves (N = 1e2..1e6) and surfaces (32²..1024²).
//! Degenerate input: an edit at the free end (owns every extended index).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use nalgebra::{Vector2, Vector3};
use splinelab::curves::global_cubic::{CubicEnds, control_points, surface_control_points};
use splinelab::curves::sspline_curve::SsplineCurve;
use splinelab::curves::sspline_surface::{Direction, SsplineSurface};
use splinelab::sspline::end_conditions::{EndCondition, EndRule};
use splinelab::sspline::{Criterion as Width, SplineFamily, truncation_width};
use std::hint::black_box;

fn width() -> usize {
    truncation_width(&SplineFamily::Order(4), 1e-6, Width::Uniform)
        .unwrap()
        .n
}

fn curve(c: &mut Criterion) {
    let n = width();
    let mut g = c.benchmark_group("curve_point_edit");
    for exp in 2..=6u32 {
        let len = 10usize.pow(exp);
        let data: Vec<Vector2<f64>> = (0..len)
            .map(|i| Vector2::new(i as f64, ((i * 7919) % 101) as f64))
            .collect();
        let mut s =
            SsplineCurve::new(&SplineFamily::Order(4), n, &data, EndCondition::Free).unwrap();
        let k = len / 2;
        let mut flip = false;
        g.bench_with_input(
            BenchmarkId::new("sspline_local_recompute", len),
            &len,
            |b, _| {
                b.iter(|| {
                    flip = !flip;
                    s.move_point(k, Vector2::new(k as f64, flip as u8 as f64))
                        .unwrap()
                })
            },
        );
        g.bench_with_input(
            BenchmarkId::new("sspline_local_shift", len),
            &len,
            |b, _| {
                b.iter(|| {
                    flip = !flip;
                    s.shift_point(k, Vector2::new(k as f64, flip as u8 as f64))
                        .unwrap()
                })
            },
        );
        g.bench_with_input(BenchmarkId::new("sspline_free_end", len), &len, |b, _| {
            b.iter(|| {
                s.move_point(0, Vector2::new(0.0, flip as u8 as f64))
                    .unwrap()
            })
        });
        let mut p = data.clone();
        g.bench_with_input(
            BenchmarkId::new("global_natural_resolve", len),
            &len,
            |b, _| {
                b.iter(|| {
                    flip = !flip;
                    p[k] = Vector2::new(k as f64, flip as u8 as f64);
                    control_points(black_box(&p), &CubicEnds::Natural).unwrap()
                })
            },
        );
    }
    g.finish();
}

fn surface(c: &mut Criterion) {
    let n = width();
    let mut g = c.benchmark_group("surface_point_edit");
    g.sample_size(10);
    for side in [32usize, 128, 512, 1024] {
        let data: Vec<Vector3<f64>> = (0..side * side)
            .map(|x| Vector3::new((x / side) as f64, (x % side) as f64, ((x * 31) % 17) as f64))
            .collect();
        let d = Direction {
            family: SplineFamily::Order(4),
            n,
            rule: EndRule::Free,
        };
        let mut s = SsplineSurface::new(&d, &d, side, side, &data).unwrap();
        let k = side / 2;
        let mut flip = false;
        g.bench_with_input(
            BenchmarkId::new("sspline_local_shift", side),
            &side,
            |b, _| {
                b.iter(|| {
                    flip = !flip;
                    s.shift_point(k, k, Vector3::new(k as f64, k as f64, flip as u8 as f64))
                        .unwrap()
                })
            },
        );
        g.bench_with_input(
            BenchmarkId::new("sspline_local_recompute", side),
            &side,
            |b, _| {
                b.iter(|| {
                    flip = !flip;
                    s.move_point(k, k, Vector3::new(k as f64, k as f64, flip as u8 as f64))
                        .unwrap()
                })
            },
        );
        let mut p = data.clone();
        g.bench_with_input(
            BenchmarkId::new("global_natural_resolve", side),
            &side,
            |b, _| {
                b.iter(|| {
                    flip = !flip;
                    p[k * side + k] = Vector3::new(k as f64, k as f64, flip as u8 as f64);
                    surface_control_points(black_box(&p), side, side, &CubicEnds::Natural).unwrap()
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, curve, surface);
criterion_main!(benches);
