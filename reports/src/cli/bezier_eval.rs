//! `splinelab bezier-eval`: evaluate a scalar Bernstein polynomial at given
//! parameters by one method, with the running error bound of each value and,
//! with `--reference`, its correct digits against the exact value.
//!
//! JSON schema (the same in every precision): `values`, `bounds` and, with
//! `--reference`, `reference`, `abs_error`, `rel_error` are decimal strings
//! (17 significant digits in f64, the requested precision's digits in MPFR);
//! `digits` are JSON numbers.

use super::prec::{Prec, parse_prec};
use crate::budget::{BudgetArgs, Estimate, number_bytes, unit_seconds};
use crate::error::CliError;
use crate::input::{input_error, parse_json, read_text};
use crate::outln;
use crate::output::{emit, print_json};
use crate::with_real;
use clap::Args;
use rayon::prelude::*;
use rug::float::{Round, Special};
use rug::{Float, Rational};
use serde::Deserialize;
use serde_json::{Value, json};
use splinelab::scalar::{Real, decimal_string};
use splinelab_verify::bezier_eval::{EvalError, Method, Prepared};
use splinelab_verify::check::bezier_eval::de_casteljau_exact;
use std::cmp::Ordering;
use std::path::{Path, PathBuf};

/// Arguments of `splinelab bezier-eval`.
#[derive(Debug, Args)]
pub struct BezierEvalArgs {
    /// JSON file `{"coeffs": [numbers], "t": [numbers]}`: the Bernstein
    /// coefficients b_0..b_n of p(t) = Σ b_i C(n,i) tⁱ(1−t)ⁿ⁻ⁱ and the
    /// parameters. Numbers are read as the nearest IEEE doubles, and those
    /// doubles are used exactly in every precision.
    #[arg(long)]
    pub input: PathBuf,
    /// Evaluation method: decasteljau, power (monomial conversion in the
    /// working precision + Horner), power-exact (exact conversion + Horner),
    /// bernstein (direct sum), vs (Volk–Schumaker), compensated (error-free
    /// transformations: as accurate as de Casteljau at twice the precision).
    #[arg(long, value_parser = parse_method)]
    pub method: Method,
    /// Working precision: f64, or MPFR bits (16..=2048; runs at the next compiled precision, at most 2× the bits).
    #[arg(long, default_value = "f64", value_parser = parse_prec)]
    pub prec: Prec,
    /// Also evaluate the exact inputs in rational arithmetic and report the
    /// correct significant digits, absolute and relative error of each value
    /// (the exact reference costs `n²/2` rational operations per parameter).
    #[arg(long)]
    pub reference: bool,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// The run-time and memory budget.
    #[command(flatten)]
    pub budget: BudgetArgs,
}

fn parse_method(s: &str) -> Result<Method, String> {
    s.parse()
}

/// The input file of `bezier-eval`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BezierEvalInput {
    /// The Bernstein coefficients `b_0..b_n`.
    pub coeffs: Vec<f64>,
    /// The parameters.
    pub t: Vec<f64>,
}

/// Parses and validates the input file's text (`path` names it in errors):
/// at least one coefficient, degree at most [`MAX_DEGREE`], at most
/// [`MAX_PARAMETERS`] parameters (finiteness: JSON has no NaN, and numbers
/// beyond the f64 range are refused by the parser).
pub fn parse_input(path: &Path, text: &str) -> Result<BezierEvalInput, CliError> {
    let input: BezierEvalInput = parse_json(path, text)?;
    let n = input.coeffs.len();
    if n == 0 {
        return Err(input_error(path, "field \"coeffs\" is empty"));
    }
    if n > MAX_DEGREE + 1 {
        return Err(input_error(
            path,
            format!("{n} coefficients: degree above {MAX_DEGREE}"),
        ));
    }
    if input.t.len() > MAX_PARAMETERS {
        return Err(input_error(
            path,
            format!("{} parameters: more than {MAX_PARAMETERS}", input.t.len()),
        ));
    }
    Ok(input)
}

/// One evaluated point, formatted for output.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// `p(t)` rounded to the requested precision, as a decimal string.
    pub value: String,
    /// A bound on `|value − p(t)|` (decimal string): the method's running
    /// error bound at the working precision plus, in MPFR, the rounding of
    /// the value to the requested bits.
    pub bound: String,
    /// `t` lies outside `[0, 1]`.
    pub extrapolated: bool,
    /// The value as an exact binary number, for the `--reference` comparison.
    pub exact: Float,
}

/// The comparison of one value with the exact `p(t)` of the f64 inputs.
#[derive(Debug, Clone, PartialEq)]
pub struct Accuracy {
    /// The exact value, rounded to the printed digits.
    pub reference: String,
    /// `|value − p(t)|`, 4 significant digits.
    pub abs_error: String,
    /// `|value − p(t)| / |p(t)|` (`inf` when `p(t) = 0 ≠ value`).
    pub rel_error: String,
    /// Correct significant decimal digits, `−log10(rel_error)` clamped to
    /// `0..=` the digits the precision carries (the maximum when exact).
    pub digits: f64,
}

/// Evaluates `input` at every parameter by `method` in the working
/// precision `T` (which `prec` names).
pub fn evaluate<T: Real>(
    input: &BezierEvalInput,
    method: Method,
    prec: Prec,
) -> Result<Vec<Row>, CliError> {
    let fail = |e: EvalError| CliError::numerical(e);
    let coeffs = input.coeffs.iter().map(|&c| T::from_f64_exact(c)).collect();
    let prepared = Prepared::<T>::new(coeffs).map_err(|e| fail(e.into()))?;
    input
        .t
        .iter()
        .map(|&t| {
            let e = prepared
                .evaluate(method, &T::from_f64_exact(t))
                .map_err(fail)?;
            Ok(row(prec, &e.value, &e.bound, e.extrapolated))
        })
        .collect()
}

/// Rounds a working-precision value to the requested bits and widens its
/// running bound by that rounding (half an ulp at the requested bits, bounded
/// by `|v|·2^−bits`), rounding the bound up.
fn row<T: Real>(prec: Prec, value: &T, bound: &T, extrapolated: bool) -> Row {
    let bits = prec.working_bits().min(match prec {
        Prec::F64 => 53,
        Prec::Bits(b) => b,
    });
    let exact = Float::with_val(bits, value.to_float());
    let mut total = Float::with_val_round(64, bound.to_float(), Round::Up).0;
    if prec != Prec::F64 {
        let half_ulp = Float::with_val_round(64, value.to_float().abs() >> bits, Round::Up).0;
        total = Float::with_val_round(64, &total + &half_ulp, Round::Up).0;
    }
    Row {
        value: prec.format(value),
        bound: decimal_string(&total, 4),
        extrapolated,
        exact,
    }
}

/// Compares each row with the exact value of the Bernstein polynomial of the
/// f64 inputs (rational de Casteljau, [`de_casteljau_exact`]): an independent
/// reference, since no rounding enters it.
pub fn accuracy(
    input: &BezierEvalInput,
    rows: &[Row],
    prec: Prec,
) -> Result<Vec<Accuracy>, CliError> {
    // JSON numbers are finite; the check keeps a non-finite one an error.
    let q = |x: f64| {
        Rational::from_f64(x).ok_or_else(|| CliError::numerical(format!("input {x} is not finite")))
    };
    let b: Vec<Rational> = input
        .coeffs
        .iter()
        .map(|&c| q(c))
        .collect::<Result<_, _>>()?;
    input
        .t
        .par_iter()
        .zip(rows.par_iter())
        .map(|(&t, r)| {
            Ok(compare_exact(
                &de_casteljau_exact(&b, &q(t)?),
                &r.exact,
                prec,
            ))
        })
        .collect()
}

fn compare_exact(exact: &Rational, value: &Float, prec: Prec) -> Accuracy {
    let max_digits = prec.digits() as f64;
    // A value that overflowed (a non-finite result of finite inputs) is
    // infinitely far from the exact one.
    let err = value
        .to_rational()
        .map(|v| Rational::from(&v - exact).abs());
    let abs = err.as_ref().map_or_else(
        || Float::with_val(64, Special::Infinity),
        |e| Float::with_val(64, e),
    );
    let reference = decimal_string(
        &Float::with_val(prec.working_bits() + 64, exact),
        prec.digits(),
    );
    let Some(err) = err else {
        let inf = decimal_string(&abs, 4);
        return Accuracy {
            reference,
            abs_error: inf.clone(),
            rel_error: inf,
            digits: 0.0,
        };
    };
    let (rel, digits) = if exact.cmp0() == Ordering::Equal {
        if err.cmp0() == Ordering::Equal {
            (Float::with_val(64, 0), max_digits)
        } else {
            (Float::with_val(64, Special::Infinity), 0.0)
        }
    } else {
        let rel = Float::with_val(64, &err / Rational::from(exact.abs_ref()));
        let d = if rel.is_zero() {
            max_digits
        } else {
            (-rel.clone().log10().to_f64()).clamp(0.0, max_digits)
        };
        (rel, d)
    };
    Accuracy {
        reference,
        abs_error: decimal_string(&abs, 4),
        rel_error: decimal_string(&rel, 4),
        digits,
    }
}

/// Largest degree accepted: de Casteljau costs O(n²) per parameter, so a
/// degree of 10⁴ is already ~0.1 s per t in f64.
pub const MAX_DEGREE: usize = 10_000;
/// Most parameters accepted in one call.
pub const MAX_PARAMETERS: usize = 1_000_000;

/// The cost of `bezier-eval`: de Casteljau `1.7·n²/2` units per parameter
/// (measured: degree 2000 at 10 parameters takes 115 s at 256 bits),
/// compensated three times that; the other methods `0.5·(n² + n)` per
/// parameter at most (conversion plus Horner or a direct sum).
///
/// With `reference`, the exact rational de Casteljau adds `n²/2` rational
/// operations per parameter, whose operands grow to about `n·(53 + 53)` bits:
/// counted as `n²/2` units at that width.
pub fn estimate(
    degree: usize,
    params: usize,
    method: Method,
    bits: u32,
    reference: bool,
) -> Estimate {
    let n = degree as f64 + 1.0;
    let t = params as f64;
    let units = match method {
        Method::DeCasteljau => 1.7 * n * n / 2.0 * t,
        Method::Compensated => 5.1 * n * n / 2.0 * t,
        _ => 0.5 * (n * n + n * t),
    };
    let exact_bits = (106.0 * n).min(f64::from(u32::MAX)) as u32;
    let reference_seconds = if reference {
        n * n / 2.0 * t * unit_seconds(exact_bits)
    } else {
        0.0
    };
    Estimate {
        seconds: units * unit_seconds(bits) + reference_seconds,
        bytes: (2.0 * n + 2.0 * t) * number_bytes(bits),
        what: format!("degree {degree} at {params} parameters by {method} at {bits} bits"),
    }
}

/// Runs `splinelab bezier-eval`.
pub fn run(args: &BezierEvalArgs) -> Result<(), CliError> {
    let input = parse_input(&args.input, &read_text(&args.input)?)?;
    let prec = args.prec;
    let degree = input.coeffs.len().saturating_sub(1);
    let e = estimate(
        degree,
        input.t.len(),
        args.method,
        prec.working_bits(),
        args.reference,
    );
    let _spinner = args.budget.check(&e)?;
    let rows = with_real!(prec, T => evaluate::<T>(&input, args.method, prec)?);
    let acc = args
        .reference
        .then(|| accuracy(&input, &rows, prec))
        .transpose()?;
    if args.json {
        print_json(&to_json(args.method, prec, &input, &rows, acc.as_deref()))?;
    } else {
        emit(&to_text(args.method, prec, &input, &rows, acc.as_deref()))?;
    }
    Ok(())
}

/// The `--json` object (schema in the module documentation).
// Justified: serde_json's `Value` index, on an object built by `json!({…})`
// here: reading gives Null when a key is absent, writing inserts it.
#[allow(clippy::indexing_slicing)]
fn to_json(
    method: Method,
    prec: Prec,
    input: &BezierEvalInput,
    rows: &[Row],
    acc: Option<&[Accuracy]>,
) -> Value {
    let mut out = json!({
        "method": method.name(),
        "prec": prec.to_string(),
        "working_bits": prec.working_bits(),
        "degree": input.coeffs.len().saturating_sub(1),
        "t": input.t,
        "values": rows.iter().map(|r| r.value.clone()).collect::<Vec<_>>(),
        "bounds": rows.iter().map(|r| r.bound.clone()).collect::<Vec<_>>(),
        "extrapolated": rows.iter().map(|r| r.extrapolated).collect::<Vec<_>>(),
    });
    if let Some(acc) = acc {
        let col = |f: fn(&Accuracy) -> Value| acc.iter().map(f).collect::<Vec<_>>();
        out["reference"] = json!(col(|a| json!(a.reference)));
        out["abs_error"] = json!(col(|a| json!(a.abs_error)));
        out["rel_error"] = json!(col(|a| json!(a.rel_error)));
        out["digits"] = json!(col(|a| json!(round2(a.digits))));
        out["digits_min"] = json!(round2(
            acc.iter().map(|a| a.digits).fold(f64::INFINITY, f64::min)
        ));
    }
    out
}

fn round2(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

/// The plain table: one line per parameter.
fn to_text(
    method: Method,
    prec: Prec,
    input: &BezierEvalInput,
    rows: &[Row],
    acc: Option<&[Accuracy]>,
) -> String {
    let mut text = String::new();
    outln!(
        text,
        "method {method}, degree {}, precision {prec}",
        input.coeffs.len().saturating_sub(1)
    );
    for (i, (t, r)) in input.t.iter().zip(rows).enumerate() {
        let flag = if r.extrapolated {
            "  (extrapolated)"
        } else {
            ""
        };
        let digits = acc
            .and_then(|a| a.get(i))
            .map(|a| {
                format!(
                    "  {:.1} correct digits (rel. error {})",
                    a.digits, a.rel_error
                )
            })
            .unwrap_or_default();
        outln!(
            text,
            "t = {t:<24} p = {}  ± {}{digits}{flag}",
            r.value,
            r.bound
        );
    }
    text
}
