//! Times one engine kernel on deterministic data, for
//! `benches/peers/scipy_ratio.py` (which builds the same data in numpy and
//! times scipy.ndimage on it). Prints `{"kind":…,"seconds":…}` with the
//! median of `reps` runs (process start-up and data generation excluded).
//!
//! Usage: `engine_peer KIND DEGREE N REPS` with KIND one of `filter1d`,
//! `blocks1d` (1-D, blocks overlapping by the width of 1e-15, a quarter of
//! the signal per thread and at least 2^15 samples per block), `tol1d` (1-D,
//! the `tol=1e-12` route: `BlockPrefilter::apply_line_into`), `tol1d32`
//! (the same in f32 at `tol=1e-6`), `filter2d`
//! (N × N), `filter3d` (N × N × N), `lines2d` (N × N, the contiguous axis
//! only: `spline_filter1d` along axis 1), `eval2d` (10⁶ points on an N × N
//! cubic interpolant, mirror), `copy1d` (a plain copy of N `f64` into a
//! reused buffer: the memory wall the 1-D routes are quoted against, timed
//! by the same clock in the same run). Threads: `RAYON_NUM_THREADS`.

use splinelab::ndarray::{Array2, ArrayD, IxDyn};
use splinelab::prelude::*;
use std::hint::black_box;
use std::time::Instant;

/// Sample `i` of the flattened data: the formula scipy_ratio.py repeats.
fn value(i: usize) -> f64 {
    (((i * 7919) % 2003) as f64 - 1001.0) / 1001.0
}

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn time(reps: usize, mut f: impl FnMut()) -> f64 {
    f();
    median(
        (0..reps)
            .map(|_| {
                let t0 = Instant::now();
                f();
                t0.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

/// `BlockPrefilter::apply_line_into` of `n` samples into a reused buffer.
fn tol_line<T: Real + Send + Sync>(family: &SplineFamily, n: usize, reps: usize, tol: f64) -> f64 {
    let s: Vec<T> = (0..n).map(|i| T::from_f64_exact(value(i))).collect();
    let route = Route::Truncated { tol };
    let f = LineFilter::<T>::new(family, Mode::Mirror, 0.0, route).expect("filter");
    let b = BlockPrefilter::from_line_filter(&f).expect("blocks");
    let mut out = vec![T::zero(); n];
    time(reps, || {
        b.apply_line_into(black_box(&s), &mut out).unwrap();
        black_box(&out);
    })
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 5 {
        eprintln!(
            "usage: engine_peer filter1d|blocks1d|tol1d|tol1d32|copy1d|filter2d|filter3d|lines2d|eval2d DEGREE N REPS"
        );
        std::process::exit(2);
    }
    let (kind, degree, n, reps) = (
        args[1].as_str(),
        args[2].parse::<u32>().expect("degree"),
        args[3].parse::<usize>().expect("N"),
        args[4].parse::<usize>().expect("reps"),
    );
    let family = SplineFamily::Order(degree + 1);
    let filter = LineFilter::<f64>::new(&family, Mode::Mirror, 0.0, Route::Exact).expect("filter");
    let seconds = match kind {
        "filter1d" => {
            let s: Vec<f64> = (0..n).map(value).collect();
            let mut c = s.clone();
            let mut scratch = Vec::new();
            time(reps, || {
                c.copy_from_slice(&s);
                filter.apply(black_box(&mut c), &mut scratch);
            })
        }
        "blocks1d" => {
            let s: Vec<f64> = (0..n).map(value).collect();
            let b = BlockPrefilter::<f64>::new(&family, Mode::Mirror, 0.0, 1e-15).expect("blocks");
            let block = (n / (4 * rayon::current_num_threads())).max(1 << 15);
            let mut out = vec![0.0; n];
            time(reps, || {
                b.apply_into(black_box(&s), &mut out, block).unwrap();
                black_box(&out);
            })
        }
        "copy1d" => {
            let s: Vec<f64> = (0..n).map(value).collect();
            let mut out = vec![0.0; n];
            time(reps, || {
                out.copy_from_slice(black_box(&s));
                black_box(&out);
            })
        }
        // The `tol=` route of one line (what Python's spline_filter1d runs).
        "tol1d" => tol_line::<f64>(&family, n, reps, 1e-12),
        "tol1d32" => tol_line::<f32>(&family, n, reps, 1e-6),
        "filter2d" | "filter3d" => {
            let dims = if kind == "filter2d" {
                vec![n, n]
            } else {
                vec![n, n, n]
            };
            let total: usize = dims.iter().product();
            let a = ArrayD::from_shape_vec(IxDyn(&dims), (0..total).map(value).collect()).unwrap();
            let mut c = a.clone();
            time(reps, || {
                c.assign(&a);
                spline_filter(black_box(&mut c), &filter).unwrap();
            })
        }
        "lines2d" => {
            let a = Array2::from_shape_fn((n, n), |(i, j)| value(i * n + j));
            let mut c = a.clone();
            time(reps, || {
                c.assign(&a);
                spline_filter1d(black_box(&mut c), 1, &filter).unwrap();
            })
        }
        "eval2d" => {
            let a = Array2::from_shape_fn((n, n), |(i, j)| value(i * n + j));
            let f = Interpolant::new(&a, Options::new(degree, Mode::Mirror)).unwrap();
            let span = (n - 1) * 100;
            let pts = Array2::from_shape_fn((1_000_000, 2), |(k, ax)| {
                let mult = if ax == 0 { 7919 } else { 104_729 };
                ((k * mult) % span) as f64 / 100.0
            });
            let mut out = vec![0.0; pts.nrows()];
            time(reps, || {
                f.eval_many(pts.view(), black_box(&mut out)).unwrap()
            })
        }
        _ => {
            eprintln!("unknown kind {kind}");
            std::process::exit(2);
        }
    };
    println!("{{\"kind\":\"{kind}\",\"degree\":{degree},\"n\":{n},\"seconds\":{seconds:e}}}");
}
