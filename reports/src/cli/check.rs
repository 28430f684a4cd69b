//! `splinelab check KIND`: verifies a user's own results against references
//! computed from the user's exact inputs (the library API is
//! `splinelab_verify::check`). Exit status: 0 pass, 1 fail (an element over
//! `K` × its stable bound, over `--max-ulps`, a non-finite value, a changed
//! curve), 2 bad input.

use super::check_out::write_check_dir;
use super::coeffs::family_from_args;
use super::cond::BasisArg;
pub use crate::array_io::interp_input;
use crate::array_io::{read_1d, read_array};
use crate::budget::{BudgetArgs, Estimate, Spinner, number_bytes, unit_seconds};
use crate::error::CliError;
use crate::input::{input_error, read_json};
use crate::outln;
use crate::output::{emit, print_json};
use clap::{Args, Subcommand};
use serde_json::{Map, Value};
use splinelab::sspline::SplineFamily;
pub use splinelab_verify::check::Outcome;
use splinelab_verify::check::bezier_eval::check_bezier_eval;
use splinelab_verify::check::bspline_eval::{BSplineEvalInput, check_bspline_eval};
use splinelab_verify::check::coeffs::check_coeffs;
use splinelab_verify::check::cond::{CondInput, Norm, check_cond};
use splinelab_verify::check::interp::{ScipyMode, check_interp_with_cval};
use splinelab_verify::check::knot_insertion::check_knot_insertion;
use splinelab_verify::check::outcome;
use splinelab_verify::check::prefilter::{PrefilterInput, check_prefilter, family_of_degree};
use splinelab_verify::check::rational_bspline::RationalBSpline;
use splinelab_verify::check::{CheckSummary, UserFormat};
use splinelab_verify::conditioning::Basis;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Arguments of `splinelab check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// What to check.
    #[command(subcommand)]
    pub kind: Kind,
}

/// The KINDs.
#[derive(Debug, Subcommand)]
pub enum Kind {
    /// Interpolation coefficients of samples (scipy.ndimage.spline_filter1d convention).
    Prefilter(PrefilterArgs),
    /// Interpolated values of N-D samples (scipy.ndimage.map_coordinates convention, prefilter on, every mode).
    Interp(InterpArgs),
    /// S-spline coefficients c_0..c_{K−1} of an order or a Beta2 tension.
    Coeffs(CoeffsArgs),
    /// Condition numbers (cond₂ or cond_∞) of Vandermonde matrices on the user's nodes.
    Cond(CondArgs),
    /// Values of a B-spline BSpline(t, c, k, extrapolate)(x) (scipy convention).
    BsplineEval(BSplineEvalArgs),
    /// Values of a Bernstein polynomial at parameters t.
    BezierEval(BezierEvalArgs),
    /// A B-spline before and after a knot insertion: the curve must not change.
    KnotInsertion(KnotInsertionArgs),
}

/// Options every KIND takes.
#[derive(Debug, Args)]
pub struct Common {
    /// Print the JSON summary instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Fail (exit 1) when any element is more than K ulps (of the user's format) off.
    #[arg(long, value_name = "K", allow_hyphen_values = true)]
    pub max_ulps: Option<f64>,
    /// Write an HTML page, SVG charts and summary.json into DIR (replaced atomically).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Judge the values in this format's ulps (default: the values file's dtype, f64 for text/JSON).
    #[arg(long, value_parser = parse_format)]
    pub format: Option<UserFormat>,
    /// The run-time and memory budget (checked once the inputs' sizes are known, before any reference is computed).
    #[command(flatten)]
    pub budget: BudgetArgs,
}

/// Bits of the first rung of the agreement ladder, the cost model's precision.
const MODEL_BITS: u32 = 192;

/// Refuses a check whose estimated cost is over `c`'s budget: `units` MPFR
/// multiply-adds at each of the two precisions of the first rung (exact
/// rational kinds count about ten units per operation), `numbers` stored
/// values. Calibrated on the 10⁶-sample cubic prefilter (8 s measured,
/// about 17 s estimated).
fn budget(c: &Common, units: f64, numbers: f64, what: String) -> Result<Spinner, CliError> {
    c.budget.check(&Estimate {
        seconds: 2.0 * units * unit_seconds(MODEL_BITS),
        bytes: 3.0 * numbers * number_bytes(MODEL_BITS),
        what,
    })
}

fn parse_format(s: &str) -> Result<UserFormat, String> {
    s.parse()
}

/// `--degree`/`--order` and `--mode`, shared by `prefilter` and `interp`.
#[derive(Debug, Args)]
pub struct SplineArgs {
    /// Spline degree d (scipy's `order`), 1..=15.
    #[arg(long, conflicts_with = "order")]
    pub degree: Option<usize>,
    /// Spline order m = d + 1 (the papers' convention).
    #[arg(long)]
    pub order: Option<usize>,
    /// End mode: mirror, reflect (grid-mirror), grid-wrap, nearest, grid-constant (prefilter: as scipy's spline_filter1d filters them, with the reflect and mirror rules; interp: as map_coordinates, which pads 12 samples first); interp also takes scipy's constant (the mirror spline inside [0, n − 1], cval outside) and wrap (period n − 1, mirror spline). prefilter filters those two with the mirror rule, as scipy's spline_filter1d does.
    #[arg(long, default_value = "mirror")]
    pub mode: String,
}

/// `check prefilter`.
#[derive(Debug, Args)]
pub struct PrefilterArgs {
    /// The samples s_j (.npy, .json or text, 1-D).
    #[arg(long)]
    pub samples: PathBuf,
    /// The user's coefficients D_j, same length.
    #[arg(long)]
    pub coeffs: PathBuf,
    /// Degree (or order) and end mode.
    #[command(flatten)]
    pub spline: SplineArgs,
    /// Common options.
    #[command(flatten)]
    pub common: Common,
}

/// `check interp`.
#[derive(Debug, Args)]
pub struct InterpArgs {
    /// The samples, any number of dimensions (.npy; .json or text for 1-D and 2-D).
    #[arg(long)]
    pub samples: PathBuf,
    /// Query points in sample indices, shape (ndim, count) as map_coordinates takes them (1-D for 1-D samples).
    #[arg(long)]
    pub coords: PathBuf,
    /// The user's values, one per point.
    #[arg(long)]
    pub values: PathBuf,
    /// Degree (or order) and end mode.
    #[command(flatten)]
    pub spline: SplineArgs,
    /// scipy's `cval` for grid-constant (its padding and the value beyond it) and constant (the value outside the grid).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub cval: f64,
    /// Common options.
    #[command(flatten)]
    pub common: Common,
}

/// `check cond`.
#[derive(Debug, Args)]
pub struct CondArgs {
    /// Nodes: 1-D (one matrix) or one node set per row (2-D, or a JSON list of lists of any lengths).
    #[arg(long)]
    pub nodes: PathBuf,
    /// Basis of the Vandermonde matrix.
    #[arg(long, value_enum, default_value = "bernstein")]
    pub basis: BasisArg,
    /// Which condition number the values are: 2 (σ_max/σ_min) or inf (‖A‖_∞‖A⁻¹‖_∞).
    #[arg(long, value_enum, default_value = "2")]
    pub norm: NormArg,
    /// The user's condition numbers, one per node set (1-D).
    #[arg(long)]
    pub values: PathBuf,
    /// Common options.
    #[command(flatten)]
    pub common: Common,
}

/// `--norm` values.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum NormArg {
    /// cond₂.
    #[value(name = "2")]
    Two,
    /// cond_∞.
    Inf,
}

/// `check coeffs`.
#[derive(Debug, Args)]
pub struct CoeffsArgs {
    /// The user's c_0..c_{K−1} (1-D).
    #[arg(long)]
    pub values: PathBuf,
    /// B-spline order m (degree m − 1), 2..=200.
    #[arg(long, conflicts_with_all = ["degree", "tension"])]
    pub order: Option<u32>,
    /// B-spline degree d = m − 1.
    #[arg(long, conflicts_with = "tension")]
    pub degree: Option<u32>,
    /// Beta2 tension β2 ≥ 0 (decimal or p/q, exactly).
    #[arg(long, allow_hyphen_values = true)]
    pub tension: Option<String>,
    /// Common options.
    #[command(flatten)]
    pub common: Common,
}

/// `check bspline-eval`.
#[derive(Debug, Args)]
pub struct BSplineEvalArgs {
    /// Knots t (1-D).
    #[arg(long)]
    pub knots: PathBuf,
    /// Coefficients c, len(t) − k − 1 of them (1-D).
    #[arg(long)]
    pub coeffs: PathBuf,
    /// Degree k.
    #[arg(long)]
    pub degree: usize,
    /// Evaluation points x (1-D).
    #[arg(long)]
    pub x: PathBuf,
    /// The user's values, one per x.
    #[arg(long)]
    pub values: PathBuf,
    /// scipy's extrapolate=False: NaN expected outside [t[k], t[n]].
    #[arg(long)]
    pub no_extrapolate: bool,
    /// Common options.
    #[command(flatten)]
    pub common: Common,
}

/// `check bezier-eval`.
#[derive(Debug, Args)]
pub struct BezierEvalArgs {
    /// Bernstein coefficients b_0..b_n (1-D).
    #[arg(long)]
    pub coeffs: PathBuf,
    /// Parameters t (1-D).
    #[arg(long)]
    pub t: PathBuf,
    /// The user's values, one per t.
    #[arg(long)]
    pub values: PathBuf,
    /// Common options.
    #[command(flatten)]
    pub common: Common,
}

/// `check knot-insertion`.
#[derive(Debug, Args)]
pub struct KnotInsertionArgs {
    /// JSON {"before": {t, c, k}, "after": {t, c, k}}, or {"cases": {NAME: {before, after}}} with --case.
    #[arg(long)]
    pub input: PathBuf,
    /// The case to take from a "cases" file.
    #[arg(long)]
    pub case: Option<String>,
    /// Common options.
    #[command(flatten)]
    pub common: Common,
}

/// Runs `splinelab check`.
pub fn run(args: &CheckArgs) -> Result<ExitCode, CliError> {
    let (outcome, extra, common) = match &args.kind {
        Kind::Prefilter(a) => (prefilter(a)?, degree_mode_extra(&a.spline)?, &a.common),
        Kind::Interp(a) => (interp(a)?, degree_mode_extra(&a.spline)?, &a.common),
        Kind::Coeffs(a) => (coeffs(a)?, Map::new(), &a.common),
        Kind::Cond(a) => (cond(a)?, Map::new(), &a.common),
        Kind::BsplineEval(a) => (bspline_eval(a)?, Map::new(), &a.common),
        Kind::BezierEval(a) => (bezier_eval(a)?, Map::new(), &a.common),
        Kind::KnotInsertion(a) => (knot_insertion(a)?, Map::new(), &a.common),
    };
    let json = outcome.to_json(&extra);
    if let Some(dir) = &common.out {
        write_check_dir(dir, &outcome, &json)?;
    }
    if common.json {
        print_json(&json)?;
    } else {
        emit(&table(&outcome))?;
    }
    Ok(if outcome.passed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// `--max-ulps` must be a finite number ≥ 0.
fn max_ulps(c: &Common) -> Result<Option<f64>, CliError> {
    match c.max_ulps {
        Some(k) if !(k.is_finite() && k >= 0.0) => Err(CliError::invalid(
            "--max-ulps",
            format!("{k} is not a finite number ≥ 0"),
        )),
        k => Ok(k),
    }
}

/// The output directory must not be an existing file (checked before any work).
fn check_out(c: &Common) -> Result<(), CliError> {
    match &c.out {
        Some(d) if d.exists() && !d.is_dir() => Err(CliError::invalid(
            "--out",
            format!("{} exists and is not a directory", d.display()),
        )),
        _ => Ok(()),
    }
}

/// The user's values and their format (`--format` overrides the file's dtype).
fn user_values(path: &Path, c: &Common) -> Result<(Vec<f64>, UserFormat), CliError> {
    check_out(c)?;
    let (v, f) = read_1d(path)?;
    Ok((v, c.format.unwrap_or(f)))
}

/// `--degree d` or `--order m = d + 1` (3 when neither is given).
fn degree_of(a: &SplineArgs) -> Result<usize, CliError> {
    match (a.degree, a.order) {
        (Some(d), None) => Ok(d),
        (None, Some(0)) => Err(CliError::invalid(
            "--order",
            "0 is not an order (m = d + 1 ≥ 1)",
        )),
        (None, Some(m)) => Ok(m - 1),
        (None, None) => Ok(3),
        (Some(_), Some(_)) => Err(CliError::invalid(
            "--degree",
            "give --degree or --order, not both",
        )),
    }
}

fn scipy_mode_of(mode: &str) -> Result<ScipyMode, CliError> {
    mode.parse::<ScipyMode>()
        .map_err(|e| CliError::invalid("--mode", e))
}

fn degree_mode_extra(a: &SplineArgs) -> Result<Map<String, Value>, CliError> {
    Ok(outcome::prefilter_extra(
        scipy_mode_of(&a.mode)?.name(),
        degree_of(a)?,
    ))
}

fn prefilter(a: &PrefilterArgs) -> Result<Outcome, CliError> {
    // scipy's spline_filter1d filters constant and wrap with the mirror rule.
    let mode = scipy_mode_of(&a.spline.mode)?.spline_mode();
    let family = family_of_degree(degree_of(&a.spline)?)
        .map_err(|e| CliError::invalid("--degree", e.to_string()))?;
    let max_ulps = max_ulps(&a.common)?;
    let (samples, _) = read_1d(&a.samples)?;
    let (user, format) = user_values(&a.coeffs, &a.common)?;
    let (n, q) = (samples.len() as f64, family.pole_count() as f64);
    let _spin = budget(
        &a.common,
        n * (2.0 * q + 1.0) * (q + 1.0),
        n * (2.0 * q + 2.0),
        format!("a prefilter check of {n} samples"),
    )?;
    let s = check_prefilter(&PrefilterInput {
        samples,
        user,
        format,
        family,
        mode,
        max_ulps,
    })?;
    Ok(Outcome::Elements(Box::new(s)))
}

fn interp(a: &InterpArgs) -> Result<Outcome, CliError> {
    let mode = scipy_mode_of(&a.spline.mode)?;
    let degree = degree_of(&a.spline)?;
    family_of_degree(degree).map_err(|e| CliError::invalid("--degree", e.to_string()))?;
    let max_ulps = max_ulps(&a.common)?;
    let values = user_values(&a.values, &a.common)?;
    let input = interp_input(&a.samples, &a.coords, values, degree, mode, max_ulps)?;
    let dims = input.shape.len();
    let m = degree as f64 + 2.0;
    let (n, k) = (
        input.samples.len() as f64,
        (input.points.len() / dims) as f64,
    );
    let _spin = budget(
        &a.common,
        n * m * m + k * m.powi(dims as i32) * 10.0,
        3.0 * n + k * m.powi(dims as i32),
        format!("an interpolation check of {n} samples at {k} points"),
    )?;
    let s = check_interp_with_cval(&input, a.cval)?;
    Ok(Outcome::Elements(Box::new(s)))
}

/// Node sets: the rows of a 2-D array, a 1-D array as one set, or a JSON
/// list of lists of different lengths.
fn node_sets(path: &Path) -> Result<Vec<Vec<f64>>, CliError> {
    if path.extension().is_some_and(|e| e == "json")
        && let Ok(sets) = read_json::<Vec<Vec<f64>>>(path)
    {
        return Ok(sets);
    }
    let a = read_array(path)?;
    Ok(match a.shape.as_slice() {
        [_] => vec![a.data],
        [_, cols] if *cols > 0 => a.data.chunks(*cols).map(<[f64]>::to_vec).collect(),
        _ => {
            return Err(input_error(
                path,
                format!("expected 1-D or 2-D nodes, got shape {:?}", a.shape),
            ));
        }
    })
}

fn cond(a: &CondArgs) -> Result<Outcome, CliError> {
    let max_ulps = max_ulps(&a.common)?;
    let node_sets = node_sets(&a.nodes)?;
    let (user, format) = user_values(&a.values, &a.common)?;
    let cubes: f64 = node_sets.iter().map(|t| (t.len() as f64).powi(3)).sum();
    let squares: f64 = node_sets.iter().map(|t| (t.len() as f64).powi(2)).sum();
    let _spin = budget(
        &a.common,
        10.0 * cubes,
        4.0 * squares,
        format!("{} condition numbers", node_sets.len()),
    )?;
    let s = check_cond(&CondInput {
        node_sets,
        basis: match a.basis {
            BasisArg::Bernstein => Basis::Bernstein,
            BasisArg::Monomial => Basis::Monomial,
        },
        norm: match a.norm {
            NormArg::Two => Norm::Two,
            NormArg::Inf => Norm::Inf,
        },
        user,
        format,
        max_ulps,
    })?;
    Ok(Outcome::Elements(Box::new(s)))
}

fn coeffs(a: &CoeffsArgs) -> Result<Outcome, CliError> {
    // --degree d is --order d + 1; the shared parser validates either.
    let family = match (a.degree, a.order) {
        (Some(d), _) if a.tension.is_none() => SplineFamily::order(d.saturating_add(1))
            .map_err(|e| CliError::invalid("--degree", e.to_string()))?,
        (_, m) => family_from_args(m.unwrap_or(4), a.tension.as_deref())?,
    };
    let max_ulps = max_ulps(&a.common)?;
    let (user, format) = user_values(&a.values, &a.common)?;
    let _spin = budget(
        &a.common,
        user.len() as f64 * 100.0,
        user.len() as f64,
        format!("{} coefficients", user.len()),
    )?;
    let s = check_coeffs(&family, &user, format, max_ulps)?;
    Ok(Outcome::Elements(Box::new(s)))
}

fn bspline_eval(a: &BSplineEvalArgs) -> Result<Outcome, CliError> {
    let max_ulps = max_ulps(&a.common)?;
    let (t, _) = read_1d(&a.knots)?;
    let (c, _) = read_1d(&a.coeffs)?;
    let (x, _) = read_1d(&a.x)?;
    let (user, format) = user_values(&a.values, &a.common)?;
    let w = (a.degree as f64 + 1.0).powi(2);
    let _spin = budget(
        &a.common,
        10.0 * x.len() as f64 * w,
        x.len() as f64 + c.len() as f64,
        format!("exact B-spline values at {} points", x.len()),
    )?;
    let s = check_bspline_eval(&BSplineEvalInput {
        t,
        c,
        k: a.degree,
        extrapolate: !a.no_extrapolate,
        x,
        user,
        format,
        max_ulps,
    })?;
    Ok(Outcome::Elements(Box::new(s)))
}

fn bezier_eval(a: &BezierEvalArgs) -> Result<Outcome, CliError> {
    let max_ulps = max_ulps(&a.common)?;
    let (b, _) = read_1d(&a.coeffs)?;
    let (t, _) = read_1d(&a.t)?;
    let (user, format) = user_values(&a.values, &a.common)?;
    let _spin = budget(
        &a.common,
        10.0 * t.len() as f64 * (b.len() as f64).powi(2),
        t.len() as f64 + b.len() as f64,
        format!(
            "exact Bézier values of degree {} at {} points",
            b.len().saturating_sub(1),
            t.len()
        ),
    )?;
    let s = check_bezier_eval(&b, &t, &user, format, max_ulps)?;
    Ok(Outcome::Elements(Box::new(s)))
}

/// A B-spline `{t, c, k}` from JSON.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SplineJson {
    t: Vec<f64>,
    c: Vec<f64>,
    k: usize,
}

#[derive(Debug, serde::Deserialize)]
struct PairJson {
    before: SplineJson,
    after: SplineJson,
}

fn knot_insertion(a: &KnotInsertionArgs) -> Result<Outcome, CliError> {
    let max_ulps = max_ulps(&a.common)?;
    check_out(&a.common)?;
    let v: Value = read_json(&a.input)?;
    let pair = match (&a.case, v.get("cases")) {
        (Some(name), Some(cases)) => cases
            .get(name)
            .cloned()
            .ok_or_else(|| input_error(&a.input, format!("no case \"{name}\" under \"cases\"")))?,
        (None, Some(_)) => {
            return Err(input_error(
                &a.input,
                "the file has \"cases\": pick one with --case",
            ));
        }
        (Some(_), None) => {
            return Err(input_error(
                &a.input,
                "--case given but the file has no \"cases\"",
            ));
        }
        (None, None) => v,
    };
    let p: PairJson = serde_json::from_value(pair).map_err(|e| {
        input_error(
            &a.input,
            format!("expected {{before: {{t, c, k}}, after: {{t, c, k}}}}: {e}"),
        )
    })?;
    let spline = |s: &SplineJson, what: &str| {
        RationalBSpline::from_f64(&s.t, &s.c, s.k)
            .map_err(|e| input_error(&a.input, format!("{what}: {e}")))
    };
    let format = a.common.format.unwrap_or(UserFormat::F64);
    let pieces = (p.before.t.len() + p.after.t.len()) as f64;
    let _spin = budget(
        &a.common,
        650.0 * pieces * (p.after.k as f64 + 1.0).powi(2),
        pieces,
        format!("an exact comparison over {pieces} knot intervals"),
    )?;
    let s = check_knot_insertion(
        &spline(&p.before, "before")?,
        &spline(&p.after, "after")?,
        format,
        max_ulps,
    )?;
    Ok(Outcome::Insertion(s))
}

/// The stable-bound part of the table: the worst excess, where it is, the
/// digits lost beyond the conditioning and the count over `K` × bound; or
/// why there is no such verdict.
fn bound_lines(text: &mut String, s: &CheckSummary) {
    match (&s.worst_excess, &s.no_verdict_reason) {
        (Some(w), _) => {
            outln!(
                text,
                "stable bound: worst excess {:.3} at index {} (error {:e}, bound {:e}{}); digits lost beyond the conditioning {:.2}; over {} × bound: {}",
                w.excess,
                w.index,
                w.error,
                w.bound,
                w.region
                    .map(|r| format!(", {}", r.name()))
                    .unwrap_or_default(),
                s.digits_lost.unwrap_or(0.0),
                fmt_opt(s.bound_factor),
                s.over_bound
            );
        }
        (None, Some(why)) => outln!(text, "verdict basis {}: {why}", s.verdict_basis),
        (None, None) => {}
    }
}

fn fmt_opt<T: std::fmt::Display>(x: Option<T>) -> String {
    x.map_or_else(|| "-".into(), |v| v.to_string())
}

/// The plain-text result (written through [`emit`]: a closed pipe or a
/// failed write is handled, never a panic); also the message of the Python
/// package's `splinelab.testing.assert_check`.
pub fn table(o: &Outcome) -> String {
    let mut text = String::new();
    match o {
        Outcome::Insertion(s) => {
            outln!(
                text,
                "check knot-insertion: {} ({})",
                s.verdict,
                s.reference
            );
            outln!(
                text,
                "max deviation {:e} (relative {:e}, {:.3} ulps of the scale) at x = {}",
                s.max_deviation,
                s.max_deviation_rel,
                s.max_deviation_ulps,
                s.worst_x
            );
            outln!(
                text,
                "identical curves: {}; threshold {} ulps",
                s.identical,
                s.max_ulps
            );
        }
        Outcome::Elements(s) => {
            outln!(
                text,
                "check {}: {} ({} elements, {} ulps)",
                s.kind,
                s.verdict,
                s.n,
                s.format.name()
            );
            outln!(
                text,
                "reference: {} (bits {})",
                s.reference,
                fmt_opt(s.reference_bits)
            );
            if let Some(w) = &s.worst {
                outln!(
                    text,
                    "worst: index {} — {:.3} ulps, rel {:e}, abs {:e}, region {}",
                    w.index,
                    w.ulps,
                    w.rel,
                    w.abs,
                    fmt_opt(w.region.map(|r| r.name()))
                );
            }
            for (name, r) in s.regions.iter().flatten() {
                outln!(
                    text,
                    "{name:>9}: {} elements, max {:.3} ulps, median {:.3} ulps",
                    r.count,
                    r.max_ulps,
                    r.median_ulps
                );
            }
            outln!(
                text,
                "correct digits ≥ {:.2}; median {:.3} ulps; non-finite {}; over --max-ulps {} ({})",
                s.digits_min,
                s.median_ulps,
                s.non_finite,
                fmt_opt(s.max_ulps),
                s.failed
            );
            bound_lines(&mut text, s);
        }
    }
    text
}
