//! The N-D prefilter's error against 256-bit MPFR over many random arrays:
//! the statistics behind a change of rounding order, where the report's
//! `engine.mpfr.*` figures (worst over scipy's two fixture arrays) move by
//! an ulp either way.
//!
//! ```sh
//! cargo run --release -p splinelab-verify --example nd_prefilter_accuracy -- [SEEDS]
//! ```
//!
//! For each degree 2–5 and format (f64, f32): `SEEDS` (default 20) arrays
//! of each of five shapes (9×11, 5×6×7, 16×16, 8×8×8, 33×17; samples in
//! [−1, 1) from `SplitMix64`, `cval` 0.7) in every mode; prints the mean
//! and the largest error in ulps of max|D*| (`verify::nd_prefilter::measure`),
//! and the mean per mode.

use splinelab::ndarray::{ArrayD, IxDyn};
use splinelab::prelude::*;
use splinelab_verify::nd_prefilter::measure;
use splinelab_verify::rng::SplitMix64;

const SHAPES: [&[usize]; 5] = [&[9, 11], &[5, 6, 7], &[16, 16], &[8, 8, 8], &[33, 17]];

/// The errors of one degree, format and mode over every seed and shape.
fn errors(degree: u32, f32: bool, mode: Mode, seeds: u64) -> Result<Vec<f64>, NdimageError> {
    let mut out = vec![];
    for seed in 0..seeds {
        for shape in SHAPES {
            let len: usize = shape.iter().product();
            let v = SplitMix64::new(seed * 31 + len as u64).signal(len);
            let x = ArrayD::from_shape_vec(IxDyn(shape), v).expect("shape and length agree");
            let m = if f32 {
                measure::<f32>(&x, degree, mode, 0.7)?.0
            } else {
                measure::<f64>(&x, degree, mode, 0.7)?.0
            };
            out.push(m.error);
        }
    }
    Ok(out)
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

fn main() -> Result<(), NdimageError> {
    let seeds = std::env::args()
        .nth(1)
        .map_or(20, |s| s.parse().expect("SEEDS: a count"));
    for degree in 2..=5u32 {
        for f32 in [false, true] {
            let (mut all, mut per_mode) = (vec![], vec![]);
            for mode in Mode::ALL {
                let e = errors(degree, f32, mode, seeds)?;
                per_mode.push(format!("{mode} {:.3}", mean(&e)));
                all.extend(e);
            }
            let max = all.iter().cloned().fold(0.0, f64::max);
            println!(
                "d{degree} {}: mean {:.3} max {:.3} over {} arrays; mean per mode: {}",
                if f32 { "f32" } else { "f64" },
                mean(&all),
                max,
                all.len(),
                per_mode.join(", ")
            );
        }
    }
    Ok(())
}
