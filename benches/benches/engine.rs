//! The N-D engine: 1-D exact prefilter (sequential, and in certified
//! blocks on 1 and 2 threads), one line of 10^7 samples under `tol` (f64
//! and f32, 1 and 2 threads, beside a copy), 2-D `spline_filter` in place and 2-D / 3-D
//! `spline_filter_from` (the Python path), and batch evaluation of
//! 10^6 points on a 1024² cubic interpolant, f64, mirror ends. Ratios to scipy.ndimage on the same data
//! come from `benches/peers/scipy_ratio.py`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use splinelab::ndarray::{Array2, Array3};
use splinelab::ndimage::nd_prefilter::spline_filter_from;
use splinelab::prelude::*;
use std::hint::black_box;

fn value(i: usize) -> f64 {
    (((i * 7919) % 2003) as f64 - 1001.0) / 1001.0
}

fn engine(c: &mut Criterion) {
    let mut g = c.benchmark_group("engine");
    g.sample_size(10);
    for degree in [3u32, 5] {
        let family = SplineFamily::Order(degree + 1);
        let f = LineFilter::<f64>::new(&family, Mode::Mirror, 0.0, Route::Exact).unwrap();
        let blocks = BlockPrefilter::<f64>::new(&family, Mode::Mirror, 0.0, 1e-15).unwrap();
        let n = 1_000_000;
        let s: Vec<f64> = (0..n).map(value).collect();
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(
            BenchmarkId::new(format!("filter1d_d{degree}"), n),
            &s,
            |b, s| {
                let mut c = s.clone();
                b.iter(|| {
                    c.copy_from_slice(s);
                    f.apply(black_box(&mut c), &mut Vec::new());
                })
            },
        );
        // The block route on a pool of 1 and of 2 threads, into a reused
        // buffer, blocks as in engine_peer (a quarter per thread, ≥ 2^15).
        for threads in [1usize, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let block = (n / (4 * threads)).max(1 << 15);
            let mut out = vec![0.0; n];
            g.bench_with_input(
                BenchmarkId::new(format!("blocks1d_d{degree}_t{threads}"), n),
                &s,
                |b, s| {
                    pool.install(|| {
                        b.iter(|| blocks.apply_into(black_box(s), &mut out, block).unwrap())
                    })
                },
            );
        }
        let a = Array2::from_shape_fn((1024, 1024), |(i, j)| value(i * 1024 + j));
        g.throughput(Throughput::Elements(a.len() as u64));
        g.bench_function(BenchmarkId::new(format!("filter2d_d{degree}"), 1024), |b| {
            let mut c = a.clone();
            b.iter(|| {
                c.assign(&a);
                spline_filter(black_box(&mut c), &f).unwrap();
            })
        });
        // The Python path: the input read by the first pass into a
        // preallocated output (2-D: two passes; 3-D: axis 0, then slabs).
        let mut out = Array2::zeros(a.raw_dim());
        g.bench_function(
            BenchmarkId::new(format!("filter2d_from_d{degree}"), 1024),
            |b| b.iter(|| spline_filter_from(black_box(&a), &mut out, &[0, 1], Some(&f)).unwrap()),
        );
        let v = Array3::from_shape_fn((128, 128, 128), |(i, j, k)| value((i * 128 + j) * 128 + k));
        let mut out = Array3::zeros(v.raw_dim());
        g.throughput(Throughput::Elements(v.len() as u64));
        g.bench_function(
            BenchmarkId::new(format!("filter3d_from_d{degree}"), 128),
            |b| {
                b.iter(|| {
                    spline_filter_from(black_box(&v), &mut out, &[0, 1, 2], Some(&f)).unwrap()
                })
            },
        );
    }
    // One line of 10^7 samples under tol (spline_filter1d(x, d, tol=...)'s
    // route: BlockPrefilter::apply_line_into, the window kernels of
    // ndimage::window_recursion) on 1 and 2 threads, f64 and f32, beside a
    // plain copy of the same bytes (the memory wall).
    tol_line::<f64>(&mut g, 1e-12);
    tol_line::<f32>(&mut g, 1e-6);
    // Batch evaluation as in engine_peer's eval2d (the scipy_ratio.py case):
    // 10^6 scattered points on a 1024² cubic, one thread.
    let a = Array2::from_shape_fn((1024, 1024), |(i, j)| value(i * 1024 + j));
    let interp = Interpolant::new(&a, Options::new(3, Mode::Mirror)).unwrap();
    let pts = Array2::from_shape_fn((1_000_000, 2), |(k, ax)| {
        ((k * if ax == 0 { 7919 } else { 104_729 }) % 102_300) as f64 / 100.0
    });
    let mut out = vec![0.0; pts.nrows()];
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    g.throughput(Throughput::Elements(pts.nrows() as u64));
    g.bench_function("eval2d_cubic_1e6_t1", |b| {
        one.install(|| b.iter(|| interp.eval_many(pts.view(), black_box(&mut out)).unwrap()))
    });
    g.finish();
}

/// `tol1d_{f64,f32}_d{3,5}_t{1,2}` (apply_line_into into a reused buffer)
/// and `copy_{f64,f32}` of the same 10^7 samples.
fn tol_line<T: Real + Send + Sync>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    tol: f64,
) {
    let n = 10_000_000;
    let s: Vec<T> = (0..n).map(|i| T::from_f64_exact(value(i))).collect();
    let mut out = vec![T::zero(); n];
    let name = T::type_name();
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function(BenchmarkId::new(format!("copy_{name}"), n), |b| {
        b.iter(|| out.clone_from_slice(black_box(&s)))
    });
    for degree in [3u32, 5] {
        let route = Route::Truncated { tol };
        let f = LineFilter::<T>::new(&SplineFamily::Order(degree + 1), Mode::Mirror, 0.0, route)
            .unwrap();
        let blocks = BlockPrefilter::from_line_filter(&f).unwrap();
        for threads in [1usize, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let id = BenchmarkId::new(format!("tol1d_{name}_d{degree}_t{threads}"), n);
            g.bench_function(id, |b| {
                pool.install(|| b.iter(|| blocks.apply_line_into(black_box(&s), &mut out).unwrap()))
            });
        }
    }
}

criterion_group!(benches, engine);
criterion_main!(benches);
