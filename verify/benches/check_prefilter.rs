//! `check prefilter` on 10⁶ samples of a cubic (the figure: under
//! 10 s on the team's 2-core machine). The user's coefficients come from
//! splinelab's own f64 engine (mirror mode), so the check does its full
//! work: the 128/192-bit banded reference, the agreement test and the
//! per-element summary. Run with
//! `cargo bench -p splinelab-verify --bench check_prefilter -- --warm-up-time 1 --measurement-time 3`.

use criterion::{Criterion, criterion_group, criterion_main};
use splinelab::ndimage::line_filter::{LineFilter, Route};
use splinelab::sspline::SplineFamily;
use splinelab_verify::check::prefilter::{PrefilterInput, check_prefilter};
use splinelab_verify::check::{Mode, UserFormat};
use splinelab_verify::rng::SplitMix64;
use std::hint::black_box;

const N: usize = 1_000_000;

fn input() -> PrefilterInput {
    let family = SplineFamily::Order(4);
    let samples = SplitMix64::new(13).signal(N);
    let filter = LineFilter::<f64>::new(&family, Mode::Mirror, 0.0, Route::Exact).expect("filter");
    let mut user = samples.clone();
    filter.apply(&mut user, &mut Vec::new());
    PrefilterInput {
        samples,
        user,
        format: UserFormat::F64,
        family,
        mode: Mode::Mirror,
        max_ulps: None,
    }
}

fn bench(c: &mut Criterion) {
    let inp = input();
    let mut g = c.benchmark_group("check_prefilter");
    g.sample_size(10);
    g.bench_function("cubic_mirror_1e6", |b| {
        b.iter(|| black_box(check_prefilter(black_box(&inp)).expect("check")))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
