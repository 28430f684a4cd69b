//! What `splinelab prefilter`, `interpolate` and `resample` share: the
//! engine options (degree or order, scipy mode, tolerance, precision,
//! `--nan-policy`), reading the samples, the conditioning check, the cost
//! estimate and the output file.
//!
//! Precision: without `--prec` the engine computes in f64 whatever the
//! input's type, as scipy does (an f32 `.npy` is widened exactly);
//! `--compute float32` opts into f32 arithmetic (the samples rounded to f32
//! first where they are not), `--prec BITS` computes in MPFR. The results
//! are rounded once from the working type into the output: the input's
//! dtype for `.npy`, decimal strings (the digits `BITS` carries) for
//! `.json`.

use super::prec::{Prec, parse_prec};
use crate::array_io::read_samples_as;
pub use crate::array_io::{check_input_file, read_samples, unravel};
use crate::array_io::{write_npy_f32, write_npy_f64};
use crate::budget::{BudgetArgs, Estimate, number_bytes, unit_seconds};
use crate::error::CliError;
use crate::input::input_error;
use crate::output::write_atomic;
use crate::path_text::path_text;
use clap::Args;
use clap::builder::{PossibleValuesParser, TypedValueParser};
use ndarray::ArrayD;
use serde_json::json;
use splinelab::ndimage::alloc::try_with_capacity;
use splinelab::prelude::{
    Mode, NanPolicy, NdimageError, Options, PrefilterError, RecursivePrefilter, Route, SplineFamily,
};
use splinelab::scalar::Real;
use splinelab_verify::check::UserFormat;
use std::path::{Path, PathBuf};

/// The tolerance of `--nan-policy local` without `--tol`: the engine's,
/// which the Python package's default reads too.
pub use splinelab::ndimage::nan_policy::LOCAL_TOL;

/// The `--nan-policy` parser: the engine's names ([`NanPolicy::all`]),
/// which clap lists in the help and in its refusal of any other word.
pub fn nan_policy_parser() -> impl TypedValueParser<Value = NanPolicy> {
    PossibleValuesParser::new(NanPolicy::all().map(NanPolicy::name))
        .try_map(|s| s.parse::<NanPolicy>())
}

/// Default `--max-error` in f64 and MPFR.
pub const MAX_ERROR_F64: f64 = 1e-8;
/// Default `--max-error` in f32 (unit roundoff 6·10⁻⁸).
pub const MAX_ERROR_F32: f64 = 1e-4;

/// The engine options shared by `prefilter` and `interpolate`.
#[derive(Debug, Args)]
pub struct EngineArgs {
    /// The samples: `.npy` (float64 or float32, any number of dimensions),
    /// `.json` (a list, or a list of equal lists) or text columns.
    #[arg(long)]
    pub input: PathBuf,
    /// Spline degree 1..=199 (scipy's `order`; interpolate also takes 0, the nearest sample).
    #[arg(long, value_parser = super::whole::<u32>)]
    pub degree: Option<u32>,
    /// B-spline order m = degree + 1, 2..=200 (instead of --degree).
    #[arg(long, value_parser = super::whole::<u32>)]
    pub order: Option<u32>,
    /// Boundary mode (scipy's names): mirror, reflect (grid-mirror),
    /// grid-wrap, nearest, grid-constant (scipy's wrap is refused: it is not grid-wrap).
    #[arg(long, default_value = "mirror", value_parser = parse_mode)]
    pub mode: Mode,
    /// The constant beyond the ends for grid-constant.
    #[arg(long, default_value_t = 0.0)]
    pub cval: f64,
    /// Truncate the prefilter to the certified width for this tolerance
    /// (0 < tol < 1): each coefficient moves by at most bound·max|s| per
    /// axis, bound < tol. Without it, the exact recursive filter (under
    /// --nan-policy local: 1e-12, as the Python package).
    #[arg(long)]
    pub tol: Option<f64>,
    /// What NaN and ±inf samples (missing data) do. propagate: scipy's
    /// pattern (a missing sample makes every line through it along each
    /// filtered axis NaN, so the whole result from degree 2 on). raise:
    /// refused, naming the first. local: NaN only within the certified reach
    /// of a missing sample (the truncated prefilter's half-width for --tol
    /// plus the spline's window; without --tol, tol = 1e-12, as the Python
    /// package: the exact prefilter has no finite reach); every other
    /// result within the printed bound of the exact spline of any filling
    /// of the missing samples by values up to max|finite sample|.
    #[arg(long, default_value_t = NanPolicy::default(), value_parser = nan_policy_parser())]
    pub nan_policy: NanPolicy,
    /// Working precision: f64, or MPFR bits (16..=2048). Default: f64 (a
    /// float32 .npy is computed in f64 and its result rounded once to
    /// float32, as scipy does).
    #[arg(long, value_parser = parse_prec)]
    pub prec: Option<Prec>,
    /// The arithmetic without --prec: float64 (the default, scipy's) or
    /// float32 (f32 samples and arithmetic: error about (A + 1)·6e-8 of
    /// max|s| with A the printed amplification, where float64's is one
    /// rounding of the result; the Python package's compute="float32").
    #[arg(long, default_value = "float64", value_parser = ["float64", "float32"])]
    pub compute: String,
    /// Largest accepted estimate u·1/|V(−1)| of the coefficients' relative
    /// error (default 1e-8, or 1e-4 when computing in f32); above it the
    /// degree is refused as ill-conditioned with a precision that meets it.
    #[arg(long)]
    pub max_error: Option<f64>,
    /// The result: `.npy` (the input's dtype, rounded once from the working
    /// precision) or `.json` (decimal strings).
    #[arg(long)]
    pub output: PathBuf,
    /// The run-time and memory budget.
    #[command(flatten)]
    pub budget: BudgetArgs,
}

fn parse_mode(s: &str) -> Result<Mode, String> {
    s.parse()
        .map_err(|e: splinelab::ndimage::mode::UnknownMode| e.to_string())
}

/// The working type of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Working {
    /// IEEE binary32 (`--compute float32`).
    F32,
    /// f64 or MPFR, as `--prec`.
    Prec(Prec),
}

impl Working {
    /// Bits of the working significand.
    pub fn bits(self) -> u32 {
        match self {
            Working::F32 => 24,
            Working::Prec(p) => p.working_bits(),
        }
    }

    /// A name for messages and JSON (`f32`, `f64`, `256`).
    pub fn name(self) -> String {
        match self {
            Working::F32 => "f32".into(),
            Working::Prec(p) => p.to_string(),
        }
    }
}

/// Where the result goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OutputKind {
    /// A `.npy` of this dtype.
    Npy(UserFormat),
    /// A `.json` of decimal strings.
    Json,
}

/// The checked options of a run.
#[derive(Debug)]
pub struct Plan {
    /// The samples (widened exactly to f64), C order.
    pub data: ArrayD<f64>,
    /// The B-spline family (order = degree + 1).
    pub family: SplineFamily,
    /// The degree.
    pub degree: u32,
    /// The route.
    pub route: Route,
    /// The working type.
    pub working: Working,
    /// The output.
    pub output: OutputKind,
    /// The conditioning threshold.
    pub max_error: f64,
    /// What non-finite samples do.
    pub nan_policy: NanPolicy,
    /// How many samples are not finite.
    pub missing: usize,
}

/// Checks the options and reads the samples; degrees from `min_degree`
/// (0 for interpolation: the nearest sample, 1 for the prefilter).
pub fn plan(args: &EngineArgs, min_degree: u32) -> Result<Plan, CliError> {
    let degree = degree_from(args.degree, args.order, min_degree)?;
    // Degree 0 has no B-spline family to validate (order 1: the box).
    let family = match degree {
        0 => SplineFamily::Order(1),
        d => {
            SplineFamily::order(d + 1).map_err(|e| CliError::invalid("--degree", e.to_string()))?
        }
    };
    // `local` without --tol: the Python package's default (LOCAL_TOL).
    let tol = match (args.tol, args.nan_policy) {
        (None, NanPolicy::Local) => Some(LOCAL_TOL),
        (tol, _) => tol,
    };
    let route = match tol {
        None => Route::Exact,
        Some(t) if t > 0.0 && t < 1.0 => Route::Truncated { tol: t },
        Some(t) => {
            return Err(CliError::invalid(
                "--tol",
                format!("{t} is not in the open interval (0, 1)"),
            ));
        }
    };
    if !args.cval.is_finite() {
        return Err(CliError::invalid("--cval", "must be a finite number"));
    }
    let output = output_kind(&args.output)?;
    // Under raise the reader refuses the first non-finite sample (by its
    // multi-index); the other policies hand them to the engine.
    let data = read_samples_as(&args.input, args.nan_policy == NanPolicy::Raise)?;
    let missing = data.0.iter().filter(|x| !x.is_finite()).count();
    let working = match (args.prec, args.compute.as_str()) {
        (Some(_), "float32") => {
            return Err(CliError::invalid(
                "--compute",
                "float32 arithmetic takes no --prec (give one of them)",
            ));
        }
        (Some(p), _) => Working::Prec(p),
        (None, "float32") => Working::F32,
        (None, _) => Working::Prec(Prec::F64),
    };
    let output = match output {
        OutputKind::Npy(_) => OutputKind::Npy(data.1),
        json => json,
    };
    let max_error = args.max_error.unwrap_or(if working == Working::F32 {
        MAX_ERROR_F32
    } else {
        MAX_ERROR_F64
    });
    if !(max_error > 0.0 && max_error.is_finite()) {
        return Err(CliError::invalid(
            "--max-error",
            "must be a positive number",
        ));
    }
    Ok(Plan {
        data: data.0,
        family,
        degree,
        route,
        working,
        output,
        max_error,
        nan_policy: args.nan_policy,
        missing,
    })
}

/// The degree from `--degree d` or `--order m = d + 1` (exactly one), in
/// `min..=199`.
pub fn degree_from(degree: Option<u32>, order: Option<u32>, min: u32) -> Result<u32, CliError> {
    let d = match (degree, order) {
        (Some(_), Some(_)) => {
            return Err(CliError::invalid(
                "--order",
                "give --degree d (scipy's order) or --order m = d + 1, not both",
            ));
        }
        (None, None) => {
            return Err(CliError::invalid(
                "--degree",
                "required (scipy's `order`, e.g. --degree 3 for cubics), or --order m = d + 1",
            ));
        }
        (Some(d), None) => d,
        (None, Some(m)) if m > min => m - 1,
        (None, Some(m)) => {
            return Err(CliError::invalid(
                "--order",
                format!("{m} is outside {}..=200 (order m = degree + 1)", min + 1),
            ));
        }
    };
    if !(min..=199).contains(&d) {
        return Err(CliError::invalid(
            "--degree",
            format!("{d} is outside {min}..=199"),
        ));
    }
    Ok(d)
}

/// The output kind from the extension of `--output`.
pub fn output_kind(path: &Path) -> Result<OutputKind, CliError> {
    match path.extension().and_then(|e| e.to_str()) {
        Some("npy") => Ok(OutputKind::Npy(UserFormat::F64)),
        Some("json") => Ok(OutputKind::Json),
        _ => Err(CliError::invalid(
            "--output",
            format!(
                "{}: the name must end in .npy (binary, the input's dtype) or .json (decimal strings)",
                path_text(path)
            ),
        )),
    }
}

/// Refuses a degree the working type cannot represent meaningfully: the
/// engine's [`RecursivePrefilter::new_within`] at `max_error`. Returns the
/// amplification `1/|V(−1)|`.
pub fn check_conditioning<T: Real>(plan: &Plan) -> Result<f64, CliError> {
    match RecursivePrefilter::<T>::new_within(&plan.family, plan.max_error) {
        Ok(f) => Ok(f.amplification()),
        Err(e @ PrefilterError::IllConditioned { .. }) => Err(CliError::Numerical(format!(
            "{e} (or accept it with --max-error)"
        ))),
        Err(e) => Err(CliError::numerical(e)),
    }
}

/// Units of one prefilter pass along one axis per sample: `4p + 1` for the
/// recursion (`p` poles; the truncated route runs it too, or its blocks),
/// `2n + 1` for a convolution of width `n`, estimated as
/// `n ≈ 7.25·m·log2(1/tol)/54` (the cubic's f64 saturation width is 29 at
/// `2^{−54}`, growing about linearly with the order `m`), plus copying.
fn per_sample_units(family: &SplineFamily, route: Route) -> f64 {
    let m = family.spline_order() as f64;
    match route {
        Route::Exact | Route::Truncated { .. } => 2.0 * m + 4.0,
        Route::Convolution { tol } => 2.0 * 7.25 * m * (-tol.log2()).max(1.0) / 54.0 + 4.0,
    }
}

/// The cost of prefiltering `plan.data` along `axes` axes (then evaluating
/// `extra_units` more): the poles (`≈ 50 m²` units at the guarded
/// precision), the passes, and memory for the input, the working copy and
/// the output.
pub fn estimate(plan: &Plan, axes: usize, extra_units: f64, what: &str) -> Estimate {
    let n = plan.data.len() as f64;
    let bits = plan.working.bits();
    let m = plan.family.spline_order() as f64;
    let wide = 2 * bits.max(64) + 512;
    let passes = n * axes as f64 * per_sample_units(&plan.family, plan.route);
    let bytes_each = if bits <= 53 { 8.0 } else { number_bytes(bits) };
    Estimate {
        seconds: 50.0 * m * m * unit_seconds(wide) + (passes + extra_units) * unit_seconds(bits),
        bytes: n * (16.0 + 2.0 * bytes_each),
        what: format!(
            "{what} of {} samples, degree {}, in {}",
            plan.data.len(),
            plan.degree,
            plan.working.name()
        ),
    }
}

/// Rounds a working value once to f64.
pub fn round_f64<T: Real>(x: &T) -> f64 {
    x.to_f64()
}

/// Rounds a working value once to f32 (from MPFR directly; an f64 result is
/// cast, one rounding of the f64 value).
pub fn round_f32<T: Real>(x: &T) -> f32 {
    if T::BITS <= 53 {
        x.to_f64() as f32
    } else {
        x.to_float().to_f32()
    }
}

/// Writes `values` (shape `shape`) to `path` as the plan says, atomically.
/// `header` goes into the JSON output beside the values.
pub fn write_result<T: Real>(
    plan: &Plan,
    path: &Path,
    shape: &[usize],
    values: &[T],
    header: serde_json::Value,
) -> Result<(), CliError> {
    write_values(plan.output, plan.working, path, shape, values, header)
}

/// [`write_result`] by the output kind and working type alone.
pub fn write_values<T: Real>(
    output: OutputKind,
    working: Working,
    path: &Path,
    shape: &[usize],
    values: &[T],
    header: serde_json::Value,
) -> Result<(), CliError> {
    let bytes = match output {
        OutputKind::Npy(UserFormat::F64) => write_npy_f64(
            shape,
            try_collect(values.len(), values.iter().map(round_f64))?,
        )?,
        OutputKind::Npy(UserFormat::F32) => write_npy_f32(
            shape,
            try_collect(values.len(), values.iter().map(round_f32))?,
        )?,
        OutputKind::Json => {
            let strings: Vec<String> = values.iter().map(|x| decimal(working, x)).collect();
            let mut doc = json!({
                "shape": shape,
                "prec": working.name(),
                "working_bits": working.bits(),
                "values": strings,
            });
            if let (Some(d), serde_json::Value::Object(h)) = (doc.as_object_mut(), header) {
                d.extend(h);
            }
            let text = serde_json::to_string_pretty(&doc).map_err(CliError::numerical)?;
            (text + "\n").into_bytes()
        }
    };
    write_atomic(path, &bytes)
}

/// The `n` items of `items` in a vector allocated fallibly (an output the
/// machine cannot hold twice is an error naming it, not an abort).
fn try_collect<U>(n: usize, items: impl Iterator<Item = U>) -> Result<Vec<U>, CliError> {
    let mut v = try_with_capacity(n, "the output file's values").map_err(CliError::numerical)?;
    v.extend(items);
    Ok(v)
}

/// A value as decimal text: the shortest round-trip string in f32/f64,
/// the digits the requested bits carry in MPFR.
pub fn decimal<T: Real>(working: Working, x: &T) -> String {
    match working {
        Working::F32 => format!("{:e}", round_f32(x)),
        Working::Prec(Prec::F64) => format!("{:e}", round_f64(x)),
        Working::Prec(p) => p.format(x),
    }
}

/// The engine options of a run (degree, mode, cval, route, nan policy).
pub fn options(plan: &Plan, args: &EngineArgs) -> Options {
    Options {
        cval: args.cval,
        route: plan.route,
        nan_policy: plan.nan_policy,
        ..Options::new(plan.degree, args.mode)
    }
}

/// Converts the f64 samples (exact: every input value is an f64) to `T`.
pub fn to_working<T: Real>(data: &ArrayD<f64>) -> ArrayD<T> {
    data.mapv(T::from_f64_exact)
}

/// An engine error about the input, with the file named.
pub fn engine_error(input: &Path, e: NdimageError) -> CliError {
    match e {
        NdimageError::NonFinite { .. } | NdimageError::Empty => input_error(input, e.to_string()),
        NdimageError::Prefilter(PrefilterError::IllConditioned { .. }) => {
            CliError::Numerical(format!("{e} (or accept it with --max-error)"))
        }
        NdimageError::LocalNeedsTol => CliError::invalid("--tol", e.to_string()),
        NdimageError::DegreeRange { .. } => CliError::invalid("--degree", e.to_string()),
        e => CliError::numerical(e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degree_or_order_exactly_once() {
        assert_eq!(degree_from(Some(3), None, 1).unwrap(), 3);
        assert_eq!(degree_from(None, Some(4), 1).unwrap(), 3);
        assert!(degree_from(Some(3), Some(4), 1).is_err());
        assert!(degree_from(None, None, 1).is_err());
        assert!(degree_from(Some(0), None, 1).is_err());
        assert_eq!(degree_from(Some(0), None, 0).unwrap(), 0);
        assert_eq!(degree_from(None, Some(1), 0).unwrap(), 0);
        assert!(degree_from(Some(200), None, 0).is_err());
        assert!(degree_from(None, Some(1), 1).is_err());
        assert_eq!(unravel(5, &[2, 3]), vec![1, 2]);
    }
}
