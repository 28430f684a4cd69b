//! `splinelab flatten`: adaptive flattening of one Bézier curve (seed 002
//! method 2) with the segment count uniform sampling needs for the same
//! maximum deviation (method 1).
//!
//! Input: a JSON file `{"points": [[x, y], …]}` (or `[x, y, z]` points), the
//! control points of one Bézier curve of any degree. Output (`--json`):
//! `polyline` (the vertices), `params` (their curve parameters), `segments`,
//! `uniform_segments`, the measured `max_deviation` of both polylines, and
//! how deviations are measured (`deviation_samples` curve points per
//! polyline segment, distance to that segment).

use crate::error::CliError;
use crate::output::print_json;
use clap::Args;
use nalgebra::SVector;
use serde_json::{Value, json};
use splinelab::bernstein::bezier::Bezier;
use splinelab::curves::flatten::{flatten, max_deviation, uniform_polyline, uniform_segments};
use std::path::{Path, PathBuf};

/// Curve samples per polyline segment when measuring deviations.
pub const DEVIATION_SAMPLES: usize = 32;

/// Largest degree accepted (de Casteljau is O(n²) per point).
pub const MAX_DEGREE: usize = 200;

/// Arguments of `splinelab flatten`.
#[derive(Debug, Args)]
pub struct FlattenArgs {
    /// JSON file {"points": [[x, y], ...]} (2-D or 3-D): the Bézier control points.
    #[arg(long)]
    pub input: PathBuf,
    /// Flatness tolerance ε > 0: every curve point ends within ε of the polyline.
    #[arg(long)]
    pub tol: f64,
    /// Print one JSON object instead of a summary.
    #[arg(long)]
    pub json: bool,
}

fn input_error(path: &Path, why: impl Into<String>) -> CliError {
    CliError::Input {
        path: path.to_path_buf(),
        why: why.into(),
    }
}

/// Reads the control points: a non-empty list of 2-D or 3-D finite points,
/// all of one dimension.
fn read_points(path: &Path) -> Result<Vec<Vec<f64>>, CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| input_error(path, e.to_string()))?;
    let v: Value = serde_json::from_str(&text).map_err(|e| input_error(path, e.to_string()))?;
    let list = v
        .get("points")
        .and_then(Value::as_array)
        .ok_or_else(|| input_error(path, "expected an object with a \"points\" array"))?;
    let mut points = Vec::with_capacity(list.len());
    for (i, p) in list.iter().enumerate() {
        let coords: Option<Vec<f64>> = p
            .as_array()
            .map(|a| a.iter().map(Value::as_f64).collect())
            .unwrap_or(None);
        let coords = coords
            .ok_or_else(|| input_error(path, format!("point {i} is not an array of numbers")))?;
        if coords.iter().any(|x| !x.is_finite()) {
            return Err(input_error(path, format!("point {i} is not finite")));
        }
        points.push(coords);
    }
    let dim = points
        .first()
        .map(Vec::len)
        .ok_or_else(|| input_error(path, "no control points"))?;
    if !(dim == 2 || dim == 3) {
        return Err(input_error(
            path,
            format!("points must be 2-D or 3-D, point 0 has {dim} coordinates"),
        ));
    }
    if let Some(i) = points.iter().position(|p| p.len() != dim) {
        return Err(input_error(
            path,
            format!(
                "point {i} has {} coordinates, point 0 has {dim}",
                points[i].len()
            ),
        ));
    }
    if points.len() > MAX_DEGREE + 1 {
        return Err(input_error(
            path,
            format!("degree {} exceeds {MAX_DEGREE}", points.len() - 1),
        ));
    }
    Ok(points)
}

fn run_dim<const D: usize>(points: &[Vec<f64>], tol: f64) -> Result<Value, CliError> {
    let ctrl = points
        .iter()
        .map(|p| SVector::<f64, D>::from_column_slice(p))
        .collect();
    let curve = Bezier::new(ctrl).map_err(CliError::numerical)?;
    let poly = flatten(&curve, &tol).map_err(CliError::numerical)?;
    let m = uniform_segments(&curve, &tol, DEVIATION_SAMPLES).map_err(CliError::numerical)?;
    let uniform = uniform_polyline(&curve, m).map_err(CliError::numerical)?;
    let dev = |p| max_deviation(&curve, p, DEVIATION_SAMPLES).map_err(CliError::numerical);
    Ok(json!({
        "degree": curve.degree(),
        "dimension": D,
        "tol": tol,
        "polyline": poly.points.iter().map(|p| p.iter().copied().collect::<Vec<f64>>()).collect::<Vec<_>>(),
        "params": poly.params,
        "segments": poly.segments(),
        "max_deviation": dev(&poly)?,
        "uniform_segments": m,
        "uniform_max_deviation": dev(&uniform)?,
        "deviation_samples": DEVIATION_SAMPLES,
        "deviation_measure": "max over polyline segments of the distance from equally spaced interior curve samples to that segment",
    }))
}

/// Runs `splinelab flatten`.
pub fn run(args: &FlattenArgs) -> Result<(), CliError> {
    if !(args.tol.is_finite() && args.tol > 0.0) {
        return Err(CliError::invalid(
            "--tol",
            format!("{} is not a positive finite number", args.tol),
        ));
    }
    let points = read_points(&args.input)?;
    let out = if points[0].len() == 2 {
        run_dim::<2>(&points, args.tol)?
    } else {
        run_dim::<3>(&points, args.tol)?
    };
    if args.json {
        print_json(&out);
    } else {
        println!(
            "degree {} curve in {}-D, tolerance {:e}",
            out["degree"], out["dimension"], args.tol
        );
        println!(
            "adaptive (de Casteljau subdivision)  {} segments, max deviation {}",
            out["segments"], out["max_deviation"]
        );
        println!(
            "uniform sampling                     {} segments, max deviation {}",
            out["uniform_segments"], out["uniform_max_deviation"]
        );
    }
    Ok(())
}
