//! Study "update cost" on the engine (issue 45): the local route
//! ([`splinelab::ndimage::local`]) against the global one.
//!
//! 1. **Points on a large memory-mapped array**: a `side × side` float64
//!    `.npy` written to a temporary file and memory-mapped (viewed in place
//!    by `ndarray-npy`); for each number of random points, the local route's
//!    time and peak anonymous memory ([`crate::peak_memory`]), and the
//!    global route's (the whole array prefiltered, then the points): the
//!    crossover is the number of points beyond which the global route is
//!    faster. Cubic, mirror, `tol=None` (each route's default).
//! 2. **Updates**: a [`LocalInterpolant`] over a `side × side` array with
//!    every tile cached, `c` scattered samples changed: the update's time
//!    against a full prefilter of the array (what a global interpolant
//!    recomputes), and the updated values against a rebuild from the
//!    changed samples (bit for bit: the update recomputes the coefficients
//!    within reach by the rebuild's operations).
//!
//! Timings are the minimum of a few in-process runs on this (shared)
//! machine.

use crate::peak_memory::measure;
use crate::rng::SplitMix64;
use ndarray_npy::{ViewNpyExt, WriteNpyExt};
use serde::Serialize;
use splinelab::ndarray::{Array2, ArrayViewD};
use splinelab::ndimage::interpolant::PointRule;
use splinelab::ndimage::local::{LocalInterpolant, LocalOptions, LocalPlan, LocalSpec};
use splinelab::prelude::*;

/// What to measure.
#[derive(Debug, Clone, Serialize)]
pub struct LocalRouteParams {
    /// Side of the memory-mapped array.
    pub side: usize,
    /// Numbers of random points.
    pub points: Vec<usize>,
    /// Side of the updated array.
    pub update_side: usize,
    /// Numbers of changed samples.
    pub changes: Vec<usize>,
    /// Timing repeats (the minimum is reported).
    pub repeats: usize,
}

impl LocalRouteParams {
    /// CI profile: a 2048² array (32 MB), a 1024² update.
    pub fn quick() -> Self {
        LocalRouteParams {
            side: 2048,
            points: vec![1, 10, 100, 1_000, 10_000, 100_000],
            update_side: 1024,
            changes: vec![1, 10, 100, 1_000],
            repeats: 3,
        }
    }

    /// Report profile: an 8192² array (512 MB), a 4096² update.
    pub fn full() -> Self {
        LocalRouteParams {
            side: 8192,
            points: vec![1, 10, 100, 1_000, 10_000, 100_000, 1_000_000],
            update_side: 4096,
            changes: vec![1, 10, 100, 1_000, 10_000],
            repeats: 3,
        }
    }
}

/// One number of points.
#[derive(Debug, Clone, Serialize)]
pub struct PointsRow {
    /// Random points.
    pub k: usize,
    /// Local route, seconds.
    pub local_s: f64,
    /// Local route, peak anonymous bytes.
    pub local_bytes: usize,
    /// Global route, seconds.
    pub global_s: f64,
    /// Global route, peak anonymous bytes.
    pub global_bytes: usize,
    /// Samples the local route read.
    pub samples_read: usize,
    /// The route the cost rule picks.
    pub chosen: &'static str,
}

/// One number of changed samples.
#[derive(Debug, Clone, Serialize)]
pub struct UpdateRow {
    /// Changed samples.
    pub changed: usize,
    /// The update, seconds.
    pub update_s: f64,
    /// Coefficients it recomputed.
    pub coefficients: usize,
}

/// Everything the report shows.
#[derive(Debug, Clone, Serialize)]
pub struct LocalRouteData {
    /// The parameters.
    pub params: LocalRouteParams,
    /// The cubic's certified half-width under `tol=None`.
    pub half_width: usize,
    /// Per number of points.
    pub points: Vec<PointsRow>,
    /// The smallest measured number of points at which the global route was
    /// faster (`None`: never, up to the largest).
    pub crossover: Option<usize>,
    /// `max |local − global| / (((A + b)² − A²) max|s| + rounding)` over
    /// every point of every row (≤ 1: within the stated bound).
    pub error_over_bound: f64,
    /// Per number of changed samples.
    pub updates: Vec<UpdateRow>,
    /// The full prefilter of the updated array, seconds.
    pub full_prefilter_s: f64,
    /// `max |updated − rebuilt|` after every update (0: bit for bit).
    pub update_vs_rebuild: f64,
}

fn random(rng: &mut SplitMix64) -> f64 {
    rng.unit() * 2.0 - 1.0
}

/// Writes the study's array to a temporary `.npy` and maps it.
fn mapped_array(side: usize) -> std::io::Result<(tempfile_path::Guard, memmap2::Mmap)> {
    let guard = tempfile_path::Guard::new("local_route", "npy")?;
    let mut rng = SplitMix64::new(45);
    let a = Array2::from_shape_fn((side, side), |_| random(&mut rng));
    let file = std::fs::File::create(&guard.path)?;
    a.write_npy(std::io::BufWriter::new(file))
        .map_err(std::io::Error::other)?;
    let file = std::fs::File::open(&guard.path)?;
    // SAFETY: a private temporary file this study wrote and nobody else
    // writes; the map is read-only and dropped before the file is removed.
    #[allow(unsafe_code)]
    let map = unsafe { memmap2::Mmap::map(&file)? };
    Ok((guard, map))
}

/// A temporary file removed when dropped.
mod tempfile_path {
    use std::path::PathBuf;

    pub struct Guard {
        pub path: PathBuf,
    }

    impl Guard {
        pub fn new(stem: &str, ext: &str) -> std::io::Result<Self> {
            let path =
                std::env::temp_dir().join(format!("splinelab-{stem}-{}.{ext}", std::process::id()));
            Ok(Guard { path })
        }
    }

    impl Drop for Guard {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

fn points_rows(
    p: &LocalRouteParams,
    view: &ArrayViewD<'_, f64>,
) -> Result<(Vec<PointsRow>, f64, usize), NdimageError> {
    let side = p.side;
    let opts = LocalOptions::new(3, Mode::Mirror);
    let spec = LocalSpec::<f64>::new(view.shape(), opts)?;
    let max = view.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let (a, b) = (spec.amplification(), spec.bound());
    let u = f64::EPSILON / 2.0;
    let allowed =
        ((a + b).powi(2) - a * a + 32.0 * (spec.half_width() as f64 + 8.0) * u * a * a) * max;
    let mut rng = SplitMix64::new(7);
    let mut worst = 0.0f64;
    let mut rows = Vec::new();
    for &k in &p.points {
        let pts = Array2::from_shape_fn((k, 2), |_| rng.unit() * (side - 1) as f64);
        let plan = LocalPlan::new(&spec, pts.view(), PointRule::Fold, None)?;
        let mut best = (f64::INFINITY, 0usize, 0usize);
        let mut local = vec![0.0; k];
        for _ in 0..p.repeats {
            let (stats, s, bytes) = measure(|| plan.evaluate(&spec, view, None, &mut local));
            let stats = stats?;
            if s < best.0 {
                best = (s, bytes, stats.samples_read);
            }
        }
        let (global, gs, gbytes) = measure(|| -> Result<Vec<f64>, NdimageError> {
            let f = Interpolant::new(view, Options::new(3, Mode::Mirror))?;
            let mut out = vec![0.0; k];
            f.eval_many(pts.view(), &mut out)?;
            Ok(out)
        });
        let global = global?;
        worst = local
            .iter()
            .zip(&global)
            .fold(worst, |w, (l, g)| w.max((l - g).abs() / allowed));
        rows.push(PointsRow {
            k,
            local_s: best.0,
            local_bytes: best.1,
            global_s: gs,
            global_bytes: gbytes,
            samples_read: best.2,
            chosen: if plan.cost().prefer_local() {
                "local"
            } else {
                "global"
            },
        });
    }
    Ok((rows, worst, spec.half_width()))
}

fn update_rows(p: &LocalRouteParams) -> Result<(Vec<UpdateRow>, f64, f64), NdimageError> {
    let side = p.update_side;
    let mut rng = SplitMix64::new(11);
    let data = Array2::from_shape_fn((side, side), |_| random(&mut rng)).into_dyn();
    let opts = LocalOptions::new(3, Mode::Mirror);
    let mut f = LocalInterpolant::<f64>::new(data.shape(), opts, usize::MAX)?;
    // One point in every tile: every tile cached.
    let centres: Vec<f64> = (0..side).step_by(32).map(|i| i as f64 + 16.0).collect();
    let grid = Array2::from_shape_fn((centres.len().pow(2), 2), |(i, a)| {
        centres[if a == 0 {
            i / centres.len()
        } else {
            i % centres.len()
        }]
        .min((side - 1) as f64)
    });
    let mut out = vec![0.0; grid.nrows()];
    f.eval_many(&data, grid.view(), PointRule::Fold, None, &mut out)?;
    let mut changed = data.clone();
    let mut rows = Vec::new();
    for &c in &p.changes {
        let mut best = (f64::INFINITY, 0usize);
        for _ in 0..p.repeats {
            let idx: Vec<usize> = (0..2 * c)
                .map(|_| (rng.unit() * side as f64) as usize % side)
                .collect();
            let vals: Vec<f64> = (0..c).map(|_| random(&mut rng)).collect();
            for (i, v) in idx.chunks(2).zip(&vals) {
                changed[[i[0], i[1]]] = *v;
            }
            let (stats, s, _) = measure(|| f.update(&data, &idx, &vals));
            let stats = stats?;
            if s < best.0 {
                best = (s, stats.coefficients);
            }
        }
        rows.push(UpdateRow {
            changed: c,
            update_s: best.0,
            coefficients: best.1,
        });
    }
    let pts = Array2::from_shape_fn((2000, 2), |_| rng.unit() * (side - 1) as f64);
    let fresh = LocalInterpolant::<f64>::new(data.shape(), opts, usize::MAX)?;
    let (mut got, mut want) = (vec![0.0; 2000], vec![0.0; 2000]);
    f.eval_many(&data, pts.view(), PointRule::Fold, None, &mut got)?;
    fresh.eval_many(&changed, pts.view(), PointRule::Fold, None, &mut want)?;
    let diff = got
        .iter()
        .zip(&want)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let filter = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact)?;
    let mut full = f64::INFINITY;
    for _ in 0..p.repeats {
        let mut c = changed.clone();
        let (r, s, _) = measure(|| spline_filter(&mut c, &filter));
        r?;
        full = full.min(s);
    }
    Ok((rows, full, diff))
}

/// Runs the study.
pub fn run_local_route(p: &LocalRouteParams) -> Result<LocalRouteData, String> {
    let (guard, map) = mapped_array(p.side).map_err(|e| e.to_string())?;
    let view = ArrayViewD::<f64>::view_npy(&map).map_err(|e| e.to_string())?;
    let (points, error_over_bound, half_width) =
        points_rows(p, &view).map_err(|e| e.to_string())?;
    drop(map);
    drop(guard);
    let crossover = points.iter().find(|r| r.global_s < r.local_s).map(|r| r.k);
    let (updates, full_prefilter_s, update_vs_rebuild) =
        update_rows(p).map_err(|e| e.to_string())?;
    Ok(LocalRouteData {
        params: p.clone(),
        half_width,
        points,
        crossover,
        error_over_bound,
        updates,
        full_prefilter_s,
        update_vs_rebuild,
    })
}
