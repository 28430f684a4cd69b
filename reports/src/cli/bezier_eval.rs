//! `splinelab bezier-eval`: evaluate a scalar Bernstein polynomial at given
//! parameters by one method, with the running error bound of each value.

use super::prec::{Prec, parse_prec};
use crate::error::CliError;
use crate::output::print_json;
use crate::with_real;
use clap::Args;
use serde::Deserialize;
use serde_json::{Value, json};
use splinelab::scalar::Real;
use splinelab_verify::bezier_eval::{EvalError, Method, Prepared};
use std::path::PathBuf;

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
    /// bernstein (direct sum), vs (Volk–Schumaker), compensated (f64 only).
    #[arg(long, value_parser = parse_method)]
    pub method: Method,
    /// Working precision: f64, or MPFR bits (16..=1000000).
    #[arg(long, default_value = "f64", value_parser = parse_prec)]
    pub prec: Prec,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
}

fn parse_method(s: &str) -> Result<Method, String> {
    s.parse()
}

/// The input file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Input {
    coeffs: Vec<f64>,
    t: Vec<f64>,
}

fn read_input(path: &PathBuf) -> Result<Input, CliError> {
    let err = |why: String| CliError::Input {
        path: path.clone(),
        why,
    };
    let text = std::fs::read_to_string(path).map_err(|e| err(e.to_string()))?;
    serde_json::from_str(&text).map_err(|e| err(e.to_string()))
}

/// One evaluated point, formatted for output.
struct Row {
    value: Value,
    bound: Option<Value>,
    extrapolated: bool,
}

fn evaluate<T: Real>(input: &Input, method: Method, prec: Prec) -> Result<Vec<Row>, CliError> {
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
            Ok(match prec {
                // f64: JSON numbers (serde_json prints the shortest string that round-trips).
                Prec::F64 => Row {
                    value: json!(e.value.to_f64()),
                    bound: Some(json!(e.bound.to_f64())),
                    extrapolated: e.extrapolated,
                },
                // MPFR: decimal strings with the digits the requested precision carries.
                // The bound refers to the working-precision value, not to its rounding
                // to the requested bits, so it is not reported.
                Prec::Bits(_) => Row {
                    value: json!(prec.format(&e.value)),
                    bound: None,
                    extrapolated: e.extrapolated,
                },
            })
        })
        .collect()
}

/// Largest degree accepted: de Casteljau costs O(n²) per parameter, so a
/// degree of 10⁴ is already ~0.1 s per t in f64.
pub const MAX_DEGREE: usize = 10_000;
/// Most parameters accepted in one call.
pub const MAX_PARAMETERS: usize = 1_000_000;

/// Runs `splinelab bezier-eval`.
pub fn run(args: &BezierEvalArgs) -> Result<(), CliError> {
    let input = read_input(&args.input)?;
    if input.coeffs.len() > MAX_DEGREE + 1 {
        return Err(CliError::invalid(
            "--input",
            format!(
                "{} coefficients: degree above {MAX_DEGREE}",
                input.coeffs.len()
            ),
        ));
    }
    if input.t.len() > MAX_PARAMETERS {
        return Err(CliError::invalid(
            "--input",
            format!("{} parameters: more than {MAX_PARAMETERS}", input.t.len()),
        ));
    }
    if args.method == Method::Compensated && args.prec != Prec::F64 {
        return Err(CliError::invalid(
            "--method",
            "compensated is an f64 algorithm: use --prec f64",
        ));
    }
    let prec = args.prec;
    let rows = with_real!(prec, T => evaluate::<T>(&input, args.method, prec)?);
    if args.json {
        let mut out = json!({
            "method": args.method.name(),
            "prec": prec.to_string(),
            "working_bits": prec.working_bits(),
            "degree": input.coeffs.len() - 1,
            "t": input.t,
            "values": rows.iter().map(|r| r.value.clone()).collect::<Vec<_>>(),
            "extrapolated": rows.iter().map(|r| r.extrapolated).collect::<Vec<_>>(),
        });
        if prec == Prec::F64 {
            out["bounds"] = rows
                .iter()
                .map(|r| r.bound.clone().unwrap_or(Value::Null))
                .collect();
        }
        print_json(&out);
    } else {
        println!(
            "method {}, degree {}, precision {prec}",
            args.method,
            input.coeffs.len() - 1
        );
        for (t, r) in input.t.iter().zip(&rows) {
            let bound = r
                .bound
                .as_ref()
                .map(|b| format!("  ± {b}"))
                .unwrap_or_default();
            let flag = if r.extrapolated {
                "  (extrapolated)"
            } else {
                ""
            };
            println!("t = {t:<24} p = {}{bound}{flag}", r.value);
        }
    }
    Ok(())
}
