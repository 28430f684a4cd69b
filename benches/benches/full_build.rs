//! Full build of the interpolation coefficients from N = 1e3..1e7 samples
//! (f64, mirror ends), cubic and quintic: the exact recursive prefilter
//! (Unser's causal/anti-causal recursions) against the truncated S-spline
//! convolution at the ε = 1e-6 width and at the f64-saturating width.
//! Throughput is reported in samples per second. The accuracy of each route
//! against a 256-bit build is in the report section `update_cost`.
//! Degenerate input: a two-sample signal (the exact initial sums).

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use splinelab::sspline::end_conditions::EndRule;
use splinelab::sspline::prefilter::{ConvolutionPrefilter, RecursivePrefilter};
use splinelab::sspline::{
    Criterion as Width, SplineFamily, f64_saturation_width, truncation_width,
};
use std::hint::black_box;

fn signal(len: usize) -> Vec<f64> {
    (0..len)
        .map(|i| (((i * 7919) % 2003) as f64 - 1001.0) / 1001.0)
        .collect()
}

fn full_build(c: &mut Criterion) {
    for (name, family) in [
        ("cubic", SplineFamily::Order(4)),
        ("quintic", SplineFamily::Order(6)),
    ] {
        let mut g = c.benchmark_group(format!("full_build_{name}"));
        g.sample_size(10);
        let rec = RecursivePrefilter::<f64>::new(&family).unwrap();
        let eps = truncation_width(&family, 1e-6, Width::Uniform).unwrap().n;
        let sat = f64_saturation_width(&family).unwrap();
        let conv = |n| ConvolutionPrefilter::<f64>::new(&family, n).unwrap();
        let (ce, cs) = (conv(eps), conv(sat));
        for exp in 3..=7u32 {
            let len = 10usize.pow(exp);
            let s = signal(len);
            g.throughput(Throughput::Elements(len as u64));
            g.bench_with_input(BenchmarkId::new("recursive", len), &s, |b, s| {
                b.iter(|| rec.apply(black_box(s), EndRule::Reflect).unwrap())
            });
            g.bench_with_input(
                BenchmarkId::new(format!("convolution_n{eps}"), len),
                &s,
                |b, s| b.iter(|| ce.apply(black_box(s), EndRule::Reflect).unwrap()),
            );
            g.bench_with_input(
                BenchmarkId::new(format!("convolution_n{sat}"), len),
                &s,
                |b, s| b.iter(|| cs.apply(black_box(s), EndRule::Reflect).unwrap()),
            );
        }
        g.throughput(Throughput::Elements(2));
        g.bench_function("recursive_two_samples", |b| {
            b.iter(|| {
                rec.apply(black_box(&[1.0, -1.0]), EndRule::Reflect)
                    .unwrap()
            })
        });
        g.finish();
    }
}

criterion_group!(benches, full_build);
criterion_main!(benches);
