//! `splinelab flatten`: flattening of one Bézier curve to a tolerance, by
//! near-optimal greedy chords under a proven bound (default,
//! `curves::greedy_flatten`) or the seed's subdivision (seed 002 method 2,
//! `--method subdivision`), with the segment count uniform sampling needs for
//! the same maximum deviation (method 1) when that search is affordable.
//!
//! Input: a JSON file `{"points": [[x, y], …]}` (or `[x, y, z]` points), the
//! control points of one Bézier curve of any degree. Output (`--json`):
//! `method`, `polyline` (the vertices), `params` (their curve parameters),
//! `segments`, the measured `max_deviation` (always ≤ `tol`: the polyline
//! is made for `target_tol`, `tol` less the f64 evaluation error bound, see
//! [`aim`]), `uniform_compared`; then either `uniform_segments` and
//! `uniform_max_deviation`, or (comparison skipped) `uniform_skipped` with
//! the reason; a deviation that is not finite is null beside a
//! `…_why` field saying so; and how deviations are measured
//! (`deviation_samples` curve points per polyline segment, distance to that
//! segment). The uniform comparison never blocks the polyline: it is skipped
//! above [`UNIFORM_WORK`] or with `--no-uniform`.

use crate::error::CliError;
use crate::input::{array_field, excerpt, input_error, parse_object, read_text};
use crate::outln;
use crate::output::{emit, print_json};
use clap::Args;
use nalgebra::SVector;
use serde_json::{Value, json};
use splinelab::bernstein::bezier::Bezier;
use splinelab::curves::flatten::{
    flatten, max_deviation, rounding_floor, uniform_polyline, uniform_segments,
    uniform_segments_bound,
};
use splinelab::curves::greedy_flatten::flatten_greedy;
use std::path::{Path, PathBuf};

/// Curve samples per polyline segment when measuring deviations.
pub const DEVIATION_SAMPLES: usize = 32;

/// Largest degree accepted (de Casteljau is O(n²) per point).
pub const MAX_DEGREE: usize = 200;

/// Most de Casteljau steps the flattening itself may take (about 8 s in f64
/// on one core). Greedy chords cost about 30 subdivisions of `n(n+1)/2`
/// steps per chord plus `DEVIATION_SAMPLES` evaluations to measure it;
/// the chord count is at most the uniform count `m`.
pub const MAX_WORK: f64 = 5e9;

/// Most de Casteljau steps the optional uniform comparison may take (about
/// 1 s): it evaluates about `(4 + log₂ m) · m · DEVIATION_SAMPLES` points.
pub const UNIFORM_WORK: f64 = 1e9;

/// The a-priori uniform count `m` (an upper bound, [`uniform_segments_bound`])
/// and the de Casteljau steps of one point, `n(n+1)/2`.
fn sizes<const D: usize>(curve: &Bezier<f64, D>, tol: f64) -> Result<(f64, f64), CliError> {
    let m = uniform_segments_bound(curve, &tol)
        .map_err(|e| CliError::invalid("--tol", e.to_string()))?;
    let n = curve.degree() as f64;
    Ok((m, n * (n + 1.0) / 2.0))
}

/// Refuses a request whose flattening would exceed [`MAX_WORK`].
fn check_work<const D: usize>(curve: &Bezier<f64, D>, tol: f64) -> Result<(), CliError> {
    let (m, steps) = sizes(curve, tol)?;
    let work = m * (30.0 + DEVIATION_SAMPLES as f64) * steps;
    if work > MAX_WORK {
        let n = curve.degree();
        return Err(CliError::invalid(
            "--tol",
            format!(
                "flattening this degree-{n} curve to {tol:e} may need {m:.3e} segments \
                 ({work:.1e} de Casteljau steps, more than {MAX_WORK:e}): raise the tolerance"
            ),
        ));
    }
    Ok(())
}

/// Why the uniform comparison is skipped, if it is: its work above
/// [`UNIFORM_WORK`].
fn uniform_skip<const D: usize>(
    curve: &Bezier<f64, D>,
    tol: f64,
) -> Result<Option<String>, CliError> {
    let (m, steps) = sizes(curve, tol)?;
    let work = (4.0 + m.log2()) * m * DEVIATION_SAMPLES as f64 * steps;
    Ok((work > UNIFORM_WORK).then(|| {
        format!(
            "the uniform search may need {m:.3e} segments ({work:.1e} de Casteljau steps, \
             above {UNIFORM_WORK:e})"
        )
    }))
}

/// How the polyline is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FlattenMethod {
    /// Longest chords certified by a proven second-difference bound
    /// (near-optimal: within ~10% of the fewest chords).
    Greedy,
    /// The seed's method 2: split at t = ½ until the control polygon is flat.
    Subdivision,
}

/// Arguments of `splinelab flatten`.
#[derive(Debug, Args)]
pub struct FlattenArgs {
    /// JSON file {"points": [[x, y], ...]} (2-D or 3-D): the Bézier control points.
    #[arg(long)]
    pub input: PathBuf,
    /// Flatness tolerance ε > 0: every curve point ends within ε of the polyline.
    #[arg(long)]
    pub tol: f64,
    /// How the polyline is made.
    #[arg(long, value_enum, default_value = "greedy")]
    pub method: FlattenMethod,
    /// Skip the uniform-sampling comparison (it is also skipped, and said so,
    /// when it would take more than about a second).
    #[arg(long)]
    pub no_uniform: bool,
    /// Print one JSON object instead of a summary.
    #[arg(long)]
    pub json: bool,
}

/// The coordinates of `p`, the point at `index`, or why they are not numbers.
fn coordinates(index: usize, p: &Value) -> Result<Vec<f64>, String> {
    p.as_array()
        .and_then(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>())
        .ok_or_else(|| {
            format!(
                "points[{index}]: not an array of numbers, got {}",
                excerpt(&p.to_string())
            )
        })
}

/// Parses and validates the input file's text (`path` names it in errors):
/// an object `{"points": [...]}` of 1 to [`MAX_DEGREE`] + 1 points, all 2-D
/// or all 3-D (finite: JSON has no NaN and the parser refuses overflow).
pub fn parse_points(path: &Path, text: &str) -> Result<Vec<Vec<f64>>, CliError> {
    let map = parse_object(path, text, &["points"])?;
    let list = array_field(path, &map, "points")?;
    let bad = |why: String| input_error(path, why);
    if list.len() > MAX_DEGREE + 1 {
        return Err(bad(format!(
            "{} control points: degree above {MAX_DEGREE}",
            list.len()
        )));
    }
    let points = list
        .iter()
        .enumerate()
        .map(|(i, p)| coordinates(i, p))
        .collect::<Result<Vec<_>, _>>()
        .map_err(bad)?;
    let dim = points
        .first()
        .map(Vec::len)
        .ok_or_else(|| bad("no control points".into()))?;
    if !(dim == 2 || dim == 3) {
        return Err(bad(format!(
            "points must be 2-D or 3-D, points[0] has {dim} coordinates"
        )));
    }
    if let Some((i, p)) = points.iter().enumerate().find(|(_, p)| p.len() != dim) {
        return Err(bad(format!(
            "points[{i}] has {} coordinates, points[0] has {dim}",
            p.len()
        )));
    }
    Ok(points)
}

/// Flattens the curve with control points `points` (as from
/// [`parse_points`]) to tolerance `tol`: the JSON object `--json` prints.
pub fn flatten_points(
    points: &[Vec<f64>],
    tol: f64,
    method: FlattenMethod,
    uniform: bool,
) -> Result<Value, CliError> {
    if !(tol.is_finite() && tol > 0.0) {
        return Err(CliError::invalid(
            "--tol",
            format!("{tol} is not a positive finite number"),
        ));
    }
    match points.first().map(Vec::len) {
        Some(2) => run_dim::<2>(points, tol, method, uniform),
        Some(3) => run_dim::<3>(points, tol, method, uniform),
        _ => Err(CliError::invalid("--input", "points must be 2-D or 3-D")),
    }
}

// Justified: serde_json's `Value` index, on an object built by `json!({…})`
// here: reading gives Null when a key is absent, writing inserts it.
#[allow(clippy::indexing_slicing)]
fn run_dim<const D: usize>(
    points: &[Vec<f64>],
    tol: f64,
    method: FlattenMethod,
    uniform: bool,
) -> Result<Value, CliError> {
    let ctrl = points
        .iter()
        .map(|p| SVector::<f64, D>::from_column_slice(p))
        .collect();
    let curve = Bezier::new(ctrl).map_err(CliError::numerical)?;
    check_work(&curve, tol)?;
    let target = aim(&curve, tol)?;
    let poly = match method {
        FlattenMethod::Greedy => flatten_greedy(&curve, &target),
        FlattenMethod::Subdivision => flatten(&curve, &target),
    }
    .map_err(CliError::numerical)?;
    let dev = |p| max_deviation(&curve, p, DEVIATION_SAMPLES).map_err(CliError::numerical);
    let skipped = if uniform {
        uniform_skip(&curve, tol)?
    } else {
        Some("--no-uniform".to_string())
    };
    let mut out = json!({
        "degree": curve.degree(),
        "dimension": D,
        "tol": tol,
        "method": match method { FlattenMethod::Greedy => "greedy", FlattenMethod::Subdivision => "subdivision" },
        "polyline": poly.points.iter().map(|p| p.iter().copied().collect::<Vec<f64>>()).collect::<Vec<_>>(),
        "params": poly.params,
        "segments": poly.segments(),
        "target_tol": target,
        "uniform_compared": skipped.is_none(),
        "deviation_samples": DEVIATION_SAMPLES,
        "deviation_measure": "max over polyline segments of the distance from equally spaced interior curve samples to that segment",
    });
    set_measured(&mut out, "max_deviation", dev(&poly)?);
    match skipped {
        Some(why) => out["uniform_skipped"] = json!(why),
        None => {
            let m =
                uniform_segments(&curve, &tol, DEVIATION_SAMPLES).map_err(CliError::numerical)?;
            let uniform = uniform_polyline(&curve, m).map_err(CliError::numerical)?;
            out["uniform_segments"] = json!(m);
            set_measured(&mut out, "uniform_max_deviation", dev(&uniform)?);
        }
    }
    Ok(out)
}

/// The tolerance the polyline is made for: `tol` less a bound of the f64
/// evaluation error of the deviation measure, so that the measured
/// `max_deviation` (and the true one, judged in 256-bit MPFR by
/// `reports/tests/it/cli_flatten.rs`) stays within `tol` itself. The bound is
/// an eighth of [`rounding_floor`], `32 u max(n·max|P|, 1)`, above the
/// `(2n + 8) u max|P|` that de Casteljau's error (Higham, *Accuracy and
/// Stability*, §5: `γ_{2n}` of the sum of the absolute terms) and the
/// point-to-chord distance add up to. Refused when what is left is below
/// the floor itself.
fn aim<const D: usize>(curve: &Bezier<f64, D>, tol: f64) -> Result<f64, CliError> {
    let floor = rounding_floor(curve).map_err(CliError::numerical)?;
    let target = tol - floor / 8.0;
    if target < floor {
        return Err(CliError::invalid(
            "--tol",
            format!(
                "{tol:e} is below {:e}: f64 cannot certify this curve's deviation closer \
                 (the rounding floor {floor:e} plus the evaluation margin {:e})",
                floor * 1.125,
                floor / 8.0
            ),
        ));
    }
    Ok(target)
}

/// Sets `out[key]` to a measured value, or (not finite: the curve's points
/// overflow f64 when sampled) to null with `key_why` saying why: a null is
/// never left unexplained.
fn set_measured(out: &mut Value, key: &str, value: f64) {
    if value.is_finite() {
        out[key] = json!(value);
    } else {
        out[key] = Value::Null;
        out[format!("{key}_why")] = json!(format!(
            "not finite in f64 ({value}): the sampled curve points or distances overflow; scale the \
             control points down"
        ));
    }
}

/// Runs `splinelab flatten`.
// Justified: serde_json's `Value` index, on an object built by `json!({…})`
// here: reading gives Null when a key is absent, writing inserts it.
#[allow(clippy::indexing_slicing)]
pub fn run(args: &FlattenArgs) -> Result<(), CliError> {
    let points = parse_points(&args.input, &read_text(&args.input)?)?;
    let out = flatten_points(&points, args.tol, args.method, !args.no_uniform)?;
    if args.json {
        print_json(&out)?;
    } else {
        let mut text = String::new();
        outln!(
            text,
            "degree {} curve in {}-D, tolerance {:e}",
            out["degree"],
            out["dimension"],
            args.tol
        );
        let label = match args.method {
            FlattenMethod::Greedy => "greedy chords (proven bound)",
            FlattenMethod::Subdivision => "de Casteljau subdivision",
        };
        outln!(
            text,
            "{label:<36} {} segments, max deviation {}",
            out["segments"],
            out["max_deviation"]
        );
        match out["uniform_skipped"].as_str() {
            None => outln!(
                text,
                "{:<36} {} segments, max deviation {}",
                "uniform sampling",
                out["uniform_segments"],
                out["uniform_max_deviation"]
            ),
            Some(why) => outln!(text, "uniform sampling: not compared ({why})"),
        }
        emit(&text)?;
    }
    Ok(())
}
