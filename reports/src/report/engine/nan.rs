//! Part "Missing data" of the engine section (issue 37): one smooth 64×64
//! image with three pixels masked as NaN, zoomed by 1.5 at order 3
//! (mirror). scipy's answer is the committed fixture
//! (benches/scipy/nan_zoom.py, scipy 1.17.1): every output NaN. Beside it
//! the engine's `nan_policy = local` at `tol = 1e-6`, computed here, with
//! its claims measured: every NaN output lies within `nan_reach` of a
//! missing pixel, and every finite one is within
//! `local_bound · max|finite sample|` of the exact spline of the image
//! with the missing pixels filled by any values of at most that magnitude
//! (measured for the fillings `+max` and `−max`: the spread between their
//! exact zooms, and the local result's distance to each).

use super::{Part, Shown, num_err};
use crate::array_io::read_samples_as;
use crate::error::CliError;
use crate::heatmap::{Heatmap, Panel, figure_html};
use crate::html::num;
use crate::report::{Figure, ReportError};
use ndarray::ArrayD;
use serde_json::json;
use splinelab::ndimage::missing::local_bound;
use splinelab::prelude::*;
use std::path::PathBuf;

/// The prefilter's tolerance of the local result: reach 13 samples for
/// the cubic (the default 1e-12 reaches 24, half of this small image).
const TOL: f64 = 1e-6;
const DEGREE: u32 = 3;
const ZOOM: f64 = 1.5;

fn fixture(name: &str) -> Result<ArrayD<f64>, ReportError> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../benches/scipy")
        .join(format!("{name}.npy"));
    Ok(read_samples_as(&path, false)?.0)
}

/// scipy's `zoom` coordinates along one axis (`grid_mode=False`): output
/// `k` at `k (n − 1)/(m − 1)`, `m = round(n · zoom)`.
fn zoom_axis(n: usize) -> Vec<f64> {
    let m = (n as f64 * ZOOM).round_ties_even() as usize;
    (0..m)
        .map(|k| k as f64 * (n as f64 - 1.0) / (m as f64 - 1.0))
        .collect()
}

/// The zoom of `data` by the engine with `opts` (order 3, mirror).
fn zoom(data: &ArrayD<f64>, opts: Options) -> Result<(Vec<f64>, [usize; 2]), ReportError> {
    let axes: Vec<Vec<f64>> = data.shape().iter().map(|&n| zoom_axis(n)).collect();
    let shape = [axes[0].len(), axes[1].len()];
    let f = Interpolant::new(data, opts).map_err(num_err)?;
    let mut out = vec![0.0; shape[0] * shape[1]];
    let axes: Vec<&[f64]> = axes.iter().map(Vec::as_slice).collect();
    f.resample_grid(&axes, &[0, 0], &mut out).map_err(num_err)?;
    Ok((out, shape))
}

/// The exact (`tol = None`) zoom of `data` with its missing samples set to `v`.
fn filled(data: &ArrayD<f64>, v: f64) -> Result<Vec<f64>, ReportError> {
    let d = data.mapv(|x| if x.is_finite() { x } else { v });
    Ok(zoom(&d, Options::new(DEGREE, Mode::Mirror))?.0)
}

/// Whether output `(k, l)` lies within `r` samples of a missing pixel on
/// both axes (the mirror-folded distance: the engine's reach, checked
/// independently of its masks).
fn within_reach(missing: &[[usize; 2]], at: [f64; 2], r: usize, n: [usize; 2]) -> bool {
    missing.iter().any(|j| {
        (0..2).all(|a| {
            // Mirror copies of j: j + 2k(n − 1) and −j + 2k(n − 1).
            let period = 2.0 * (n[a] as f64 - 1.0);
            let j = j[a] as f64;
            [-1.0, 0.0, 1.0].iter().any(|k| {
                (at[a] - (j + k * period)).abs() <= r as f64
                    || (at[a] - (-j + k * period)).abs() <= r as f64
            })
        })
    })
}

/// What the part measures.
struct Measured {
    shape: [usize; 2],
    local: Vec<f64>,
    scipy: Vec<f64>,
    reach: usize,
    /// `local_bound · max|finite sample|`.
    bound: f64,
    outside_reach: usize,
    spread: f64,
    error: f64,
}

fn measure(field: &ArrayD<f64>) -> Result<Measured, ReportError> {
    let scipy = fixture("nan_zoom_scipy")?;
    let opts = Options {
        route: Route::Truncated { tol: TOL },
        nan_policy: NanPolicy::Local,
        ..Options::new(DEGREE, Mode::Mirror)
    };
    let (local, shape) = zoom(field, opts)?;
    if scipy.shape() != shape {
        return Err(CliError::Numerical(format!(
            "nan_zoom_scipy.npy has shape {:?}, the zoom {shape:?}",
            scipy.shape()
        )));
    }
    let filter = LineFilter::<f64>::new(
        &SplineFamily::Order(DEGREE + 1),
        Mode::Mirror,
        0.0,
        opts.route,
    )
    .map_err(num_err)?;
    let m = field
        .iter()
        .filter(|x| x.is_finite())
        .fold(0.0f64, |a, x| a.max(x.abs()));
    let bound = local_bound(&filter, 2) * m;
    let reach = nan_reach(DEGREE, TOL).map_err(num_err)?;
    let (hi, lo) = (filled(field, m)?, filled(field, -m)?);
    let n = [field.shape()[0], field.shape()[1]];
    let missing: Vec<[usize; 2]> = field
        .indexed_iter()
        .filter(|(_, x)| !x.is_finite())
        .map(|(i, _)| [i[0], i[1]])
        .collect();
    let axes = [zoom_axis(n[0]), zoom_axis(n[1])];
    let (mut outside_reach, mut spread, mut error) = (0, 0.0f64, 0.0f64);
    for (p, v) in local.iter().enumerate() {
        let at = [axes[0][p / shape[1]], axes[1][p % shape[1]]];
        if !v.is_finite() {
            outside_reach += usize::from(!within_reach(&missing, at, reach, n));
            continue;
        }
        spread = spread.max((hi[p] - lo[p]).abs());
        error = error.max((v - hi[p]).abs()).max((v - lo[p]).abs());
    }
    Ok(Measured {
        shape,
        local,
        scipy: scipy.iter().copied().collect(),
        reach,
        bound,
        outside_reach,
        spread,
        error,
    })
}

fn nan_fraction(v: &[f64]) -> f64 {
    v.iter().filter(|x| x.is_nan()).count() as f64 / v.len() as f64
}

/// Runs the part: the table, the picture, the figures.
pub(super) fn part() -> Result<Part, ReportError> {
    let field = fixture("nan_field")?;
    let m = measure(&field)?;
    let (fl, fs) = (nan_fraction(&m.local), nan_fraction(&m.scipy));
    let missing = field.iter().filter(|x| !x.is_finite()).count();
    // One image in every profile: the figures compare across profiles.
    let figures = [
        Figure::error("engine.nan.scipy.nan_fraction", fs, "fraction", 0.0),
        Figure::error("engine.nan.local.nan_fraction", fl, "fraction", 0.01),
        Figure::error(
            "engine.nan.local.nan_outside_reach",
            m.outside_reach as f64,
            "outputs",
            0.0,
        ),
        Figure::error(
            "engine.nan.local.fill_spread_over_bound",
            m.spread / m.bound,
            "ratio",
            0.05,
        ),
        Figure::error(
            "engine.nan.local.error_over_bound",
            m.error / m.bound,
            "ratio",
            0.05,
        ),
    ]
    .map(|f| f.measured_over("fixed cases"))
    .into();
    let total = m.local.len() as f64;
    let rows = vec![
        vec![
            "scipy 1.17.1 zoom, order 3 (fixture)".into(),
            format!("{} of {total}", (fs * total).round()),
            "the whole image".into(),
            "—".into(),
            "—".into(),
        ],
        vec![
            format!("splinelab nan_policy=\"local\", tol {TOL:e}"),
            format!("{} of {total}", (fl * total).round()),
            format!("{} samples ({} outside it)", m.reach, m.outside_reach),
            num(m.bound),
            format!("{} / {}", num(m.spread), num(m.error)),
        ],
    ];
    let shown = Shown {
        intro: "Missing data (issue 37): a smooth 64×64 image with 3 pixels masked as NaN, zoomed by 1.5 at order 3 \
         (mirror). scipy's recursive prefilter carries a NaN along every line and then every axis, so one masked \
         pixel leaves no finite output. Under nan_policy=\"local\" the truncated prefilter's certified half-width \
         confines each NaN to nan_reach(3, tol) samples of it; every other output is within local_bound · \
         max|finite sample| of the exact spline of the image with the missing pixels filled by any values of at \
         most that magnitude — measured for the fillings +max and −max (the spread between their exact zooms, \
         and the local result's largest distance to either).",
        title: "One masked image, scipy's zoom beside the local policy",
        headers: &[
            "result",
            "NaN outputs",
            "reach of a missing pixel",
            "bound outside (local_bound · max|s|)",
            "fill spread / local vs exact fill",
        ],
        rows,
    };
    let json = json!({"tol": TOL, "degree": DEGREE, "zoom": ZOOM, "missing_pixels": missing,
        "shape": m.shape, "reach": m.reach, "bound": m.bound, "nan_fraction_local": fl,
        "nan_fraction_scipy": fs, "nan_outside_reach": m.outside_reach, "fill_spread": m.spread,
        "local_vs_exact_fill": m.error});
    let mut part = Part::tabled(shown, json, figures);
    part.html += &picture(&field, &m)?;
    Ok(part)
}

/// The input, scipy's zoom and the local zoom side by side.
fn picture(field: &ArrayD<f64>, m: &Measured) -> Result<String, ReportError> {
    let panel = |title: &str, shape: [usize; 2], values: Vec<f64>| Panel {
        title: title.into(),
        shape,
        values,
    };
    let n = [field.shape()[0], field.shape()[1]];
    let map = Heatmap {
        title: "A 64×64 image with 3 masked pixels, zoomed ×1.5 at order 3".into(),
        panels: vec![
            panel("input (3 pixels NaN)", n, field.iter().copied().collect()),
            panel("scipy 1.17.1 zoom", m.shape, m.scipy.clone()),
            panel(
                &format!("splinelab local, tol {TOL:e}"),
                m.shape,
                m.local.clone(),
            ),
        ],
    };
    let svg = map
        .render_svg()
        .map_err(|e| CliError::Chart("engine_nan_local".into(), e.to_string()))?;
    Ok(figure_html(
        &svg,
        &format!(
            "Red is NaN. scipy's zoom is NaN everywhere; the local policy's NaN stays within {} samples of the \
             masked pixels, and the rest of the image is the spline of any filling of them to within {:.1e}.",
            m.reach, m.bound
        ),
    ))
}
