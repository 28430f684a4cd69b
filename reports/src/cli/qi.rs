//! `splinelab qi`: G2 interpolation of 3D points by quadratic quaternion-
//! integral curves (seed 004), solved by Newton's method.
//!
//! JSON schema (the same in every precision): real numbers are decimal
//! strings (17 significant digits in f64, the requested precision's digits in
//! MPFR; a failed run's residual history is kept in f64); counts and flags are
//! JSON numbers and booleans.

use super::prec::{Prec, parse_prec};
use crate::budget::{BudgetArgs, Estimate, number_bytes, unit_seconds};
use crate::error::CliError;
use crate::input::{array_field, input_error, kind, parse_object, read_text};
use crate::outln;
use crate::output::{emit, print_json};
use crate::with_real;
use clap::Args;
use nalgebra::Vector3;
use rug::{Integer, Rational};
use serde_json::{Value, json};
use splinelab::qi::{QiError, QiOptions, interpolate};
use splinelab::scalar::Real;
use std::path::{Path, PathBuf};

/// The convention of the output, stated in the JSON so that anyone can
/// re-integrate the curve from the paper alone.
pub const CONVENTION: &str = "Miura-Sakiyama (seed 004): segment i is C_i(t) = P_i + l_i * int_0^t \
T(alpha(tau), beta(tau)) dtau, t in [0,1]; alpha(t) = sum_j alpha_j B_{2,j}(t), beta likewise (Bernstein, \
degree 2); q = cos(beta) + (0, 0, cos(alpha), sin(alpha)) sin(beta) as (w, x, y, z); \
T = q (1,0,0) q^-1 = (cos 2beta, sin alpha sin 2beta, -cos alpha sin 2beta)";

/// Arguments of `splinelab qi`.
#[derive(Debug, Args)]
pub struct QiArgs {
    /// JSON file `{"points": [[x,y,z], ...], "start_tangent": [x,y,z], "end_tangent": [x,y,z]}` (tangents
    /// optional; default: circles through the first/last three points). Coordinates are JSON numbers
    /// (read as the nearest f64, converted exactly) or decimal strings (rounded once at the working
    /// precision; "nan"/"inf" are accepted and rejected by the solver with a typed error).
    #[arg(long)]
    pub input: PathBuf,
    /// Working precision: f64, or MPFR bits (16..=2048; runs at the next compiled precision, at most 2× the bits).
    #[arg(long, default_value = "f64", value_parser = parse_prec)]
    pub prec: Prec,
    /// Damped Newton (backtracking line search) instead of plain Newton.
    #[arg(long)]
    pub damped: bool,
    /// Maximum number of Newton steps (1..=1000).
    #[arg(long, default_value_t = 50, value_parser = super::whole::<usize>)]
    pub max_iter: usize,
    /// Print one JSON object (if Newton fails, the object still comes, with
    /// "converged": false and the residual history). Exit status: 0 when Newton
    /// converged, 1 when it did not (with or without --json), 2 for bad input.
    #[arg(long)]
    pub json: bool,
    /// The run-time and memory budget.
    #[command(flatten)]
    pub budget: BudgetArgs,
}

/// The parsed input file of `qi`, as exact rationals (or IEEE specials).
#[derive(Debug, Clone, PartialEq)]
pub struct QiInput {
    /// The points to interpolate.
    pub points: Vec<[Coord; 3]>,
    /// The start tangent, if given.
    pub start: Option<[Coord; 3]>,
    /// The end tangent, if given.
    pub end: Option<[Coord; 3]>,
}

/// A coordinate: exact rational, or a non-finite f64.
#[derive(Debug, Clone, PartialEq)]
pub enum Coord {
    /// A finite number, exactly.
    Exact(Rational),
    /// NaN or ±∞ (given as a string; the solver refuses it with a typed error).
    Special(f64),
}

impl Coord {
    fn to_real<T: Real>(&self) -> T {
        match self {
            Coord::Exact(q) => T::from_rational(q),
            Coord::Special(x) => T::from_f64_exact(*x),
        }
    }
}

/// Parses a decimal `[-+]digits[.digits][e[-+]digits]` exactly.
fn parse_decimal(s: &str) -> Option<Rational> {
    let s = s.trim();
    let (mant, exp) = match s.split_once(['e', 'E']) {
        Some((mant, exp)) => (mant, exp.parse::<i32>().ok()?),
        None => (s, 0),
    };
    let (neg, mant) = match mant.strip_prefix('-') {
        Some(m) => (true, m),
        None => (false, mant.strip_prefix('+').unwrap_or(mant)),
    };
    let (int, frac) = mant.split_once('.').unwrap_or((mant, ""));
    let digits = format!("{int}{frac}");
    if digits.is_empty()
        || !digits.bytes().all(|b| b.is_ascii_digit())
        || exp.unsigned_abs() > 100_000
    {
        return None;
    }
    let m = Integer::from_str_radix(&digits, 10).ok()?;
    // Digits after the point count as a negative exponent; as many as the
    // exponent's own bound (a longer fraction is refused, not a power of
    // ten of millions of digits).
    let e = exp.checked_sub(i32::try_from(frac.len()).ok().filter(|&f| f <= 100_000)?)?;
    let p = Integer::from(Integer::u_pow_u(10, e.unsigned_abs()));
    let q = if e >= 0 {
        Rational::from(m * p)
    } else {
        Rational::from((m, p))
    };
    Some(if neg { -q } else { q })
}

fn coord(v: &Value, what: &str) -> Result<Coord, String> {
    let field = |why: String| format!("{what}: {why}");
    match v {
        Value::Number(n) => {
            let x = n
                .as_f64()
                .ok_or_else(|| field("number out of range".into()))?;
            Rational::from_f64(x)
                .map(Coord::Exact)
                .ok_or_else(|| field("non-finite number".into()))
        }
        Value::String(s) => match s.trim().to_ascii_lowercase().as_str() {
            "nan" => Ok(Coord::Special(f64::NAN)),
            "inf" | "+inf" | "infinity" => Ok(Coord::Special(f64::INFINITY)),
            "-inf" | "-infinity" => Ok(Coord::Special(f64::NEG_INFINITY)),
            _ => parse_decimal(s)
                .map(Coord::Exact)
                .ok_or_else(|| field(format!("'{s}' is not a decimal number"))),
        },
        other => Err(field(format!(
            "expected a number or a decimal string, got {}",
            kind(other)
        ))),
    }
}

fn triple(v: &Value, what: &str) -> Result<[Coord; 3], String> {
    let Some([x, y, z]) = v.as_array().map(Vec::as_slice) else {
        return Err(format!("{what} must be [x, y, z]"));
    };
    Ok([coord(x, what)?, coord(y, what)?, coord(z, what)?])
}

/// The keys of the input object.
const KEYS: [&str; 3] = ["points", "start_tangent", "end_tangent"];

/// Parses and validates the input file's text (`path` names it in errors):
/// every point and tangent an `[x, y, z]` of numbers or decimal strings,
/// at most [`MAX_POINTS`] points, no unknown keys. The geometry (count,
/// coincident points, zero tangents) is left to the solver's typed errors.
pub fn parse_input(path: &Path, text: &str) -> Result<QiInput, CliError> {
    let map = parse_object(path, text, &KEYS)?;
    let pts = array_field(path, &map, "points")?;
    if pts.len() > MAX_POINTS {
        return Err(input_error(
            path,
            format!("{} points: more than {MAX_POINTS}", pts.len()),
        ));
    }
    let bad = |why| input_error(path, why);
    let points = pts
        .iter()
        .enumerate()
        .map(|(i, p)| triple(p, &format!("points[{i}]")))
        .collect::<Result<_, _>>()
        .map_err(bad)?;
    let opt = |key: &str| {
        map.get(key)
            .map(|t| triple(t, key))
            .transpose()
            .map_err(bad)
    };
    Ok(QiInput {
        points,
        start: opt("start_tangent")?,
        end: opt("end_tangent")?,
    })
}

fn vector<T: Real>(c: &[Coord; 3]) -> Vector3<T> {
    Vector3::new(c[0].to_real(), c[1].to_real(), c[2].to_real())
}

/// A real number for the JSON: a decimal string with the digits of the
/// requested precision, in every precision (one schema for f64 and MPFR).
fn out<T: Real>(prec: Prec, x: &T) -> Value {
    json!(prec.format(x))
}

fn out_all<T: Real>(prec: Prec, xs: &[T]) -> Value {
    xs.iter().map(|x| out(prec, x)).collect()
}

/// Runs the interpolation at `T` (which `args.prec` names); returns the JSON
/// and Newton's failure if any.
pub fn solve<T: Real>(
    input: &QiInput,
    args: &QiArgs,
) -> Result<(Value, Option<QiError>), CliError> {
    let points: Vec<Vector3<T>> = input.points.iter().map(vector).collect();
    let opts = QiOptions::<T> {
        damped: args.damped,
        max_iter: args.max_iter,
        start_tangent: input.start.as_ref().map(vector),
        end_tangent: input.end.as_ref().map(vector),
        ..Default::default()
    };
    let prec = args.prec;
    let mut m = serde_json::Map::new();
    m.insert("prec".into(), json!(prec.to_string()));
    m.insert("working_bits".into(), json!(prec.working_bits()));
    m.insert("damped".into(), json!(args.damped));
    m.insert("points".into(), json!(points.len()));
    m.insert("tol".into(), out(prec, &opts.tol));
    m.insert("convention".into(), json!(CONVENTION));
    match interpolate(&points, &opts) {
        Ok(fit) => {
            let segs: Vec<Value> = fit
                .segments
                .iter()
                .map(|s| {
                    json!({
                        "alpha": s.alpha.iter().map(|a| out(prec, a)).collect::<Vec<_>>(),
                        "beta": s.beta.iter().map(|b| out(prec, b)).collect::<Vec<_>>(),
                        "length": out(prec, &s.length),
                    })
                })
                .collect();
            m.insert("converged".into(), json!(true));
            m.insert("iterations".into(), json!(fit.iterations()));
            m.insert(
                "residuals".into(),
                json!(
                    fit.residuals()
                        .iter()
                        .map(|r| out(prec, r))
                        .collect::<Vec<_>>()
                ),
            );
            m.insert("quadrature_order".into(), json!(fit.rule.order()));
            m.insert(
                "quadrature_error_estimate".into(),
                out(prec, &fit.quad_error),
            );
            m.insert("segments".into(), json!(segs));
            Ok((Value::Object(m), None))
        }
        Err(QiError::NotConverged {
            reason,
            residuals,
            steps,
        }) => {
            m.insert("converged".into(), json!(false));
            m.insert(
                "iterations".into(),
                json!(residuals.len().saturating_sub(1)),
            );
            // Newton's failure history is kept in f64 whatever the precision.
            m.insert("residuals".into(), out_all(Prec::F64, &residuals));
            m.insert("steps".into(), out_all(Prec::F64, &steps));
            m.insert("failure".into(), json!(reason.to_string()));
            m.insert("segments".into(), json!([]));
            let e = QiError::NotConverged {
                reason,
                residuals,
                steps,
            };
            Ok((Value::Object(m), Some(e)))
        }
        Err(e) => Err(CliError::numerical(e)),
    }
}

/// Most points accepted: Newton solves a dense 7n × 7n system, whose
/// matrix at 200 points already holds 2 million entries (MPFR: gigabytes).
pub const MAX_POINTS: usize = 200;

/// The cost of `qi`: the quadrature, whose order grows with the precision
/// (`≈ 700·(bits/64)²` units per point; measured: 4 points take 0.15 s at
/// 256 bits and 9 s at 2048), plus Newton on the dense `7n × 7n` system
/// (`(7n)³/3` per step, at most 10 steps counted).
pub fn estimate(points: usize, max_iter: usize, bits: u32) -> Estimate {
    let n = points as f64;
    let b = bits as f64 / 64.0;
    let dim = 7.0 * n;
    let steps = max_iter.min(10) as f64;
    let units = 700.0 * b * b * n + steps * dim.powi(3) / 3.0;
    Estimate {
        seconds: units * unit_seconds(bits),
        bytes: dim * dim * number_bytes(bits),
        what: format!("{points} points at {bits} bits"),
    }
}

/// Runs `splinelab qi`.
pub fn run(args: &QiArgs) -> Result<(), CliError> {
    if !(1..=1000).contains(&args.max_iter) {
        return Err(CliError::invalid(
            "--max-iter",
            format!("{} is outside 1..=1000", args.max_iter),
        ));
    }
    let input = parse_input(&args.input, &read_text(&args.input)?)?;
    let prec = args.prec;
    let e = estimate(input.points.len(), args.max_iter, prec.working_bits());
    let _spinner = args.budget.check(&e)?;
    let (obj, failure) = with_real!(prec, T => solve::<T>(&input, args)?);
    if args.json {
        print_json(&obj)?;
    } else {
        emit(&print_text(&obj))?;
    }
    match failure {
        Some(e) => Err(CliError::NotConverged(e.to_string())),
        None => Ok(()),
    }
}

fn print_text(obj: &Value) -> String {
    let mut text = String::new();
    let show = |v: &Value| {
        v.as_str()
            .map(str::to_string)
            .unwrap_or_else(|| v.to_string())
    };
    outln!(
        text,
        "QI interpolation of {} points, precision {} ({} bits), {}",
        obj["points"],
        show(&obj["prec"]),
        obj["working_bits"],
        if obj["damped"] == json!(true) {
            "damped Newton"
        } else {
            "Newton"
        }
    );
    outln!(
        text,
        "converged  {}  after {} iterations",
        obj["converged"],
        obj["iterations"]
    );
    for (k, r) in obj["residuals"]
        .as_array()
        .into_iter()
        .flatten()
        .enumerate()
    {
        outln!(text, "  ‖F(x_{k})‖₂ = {}", show(r));
    }
    for (i, s) in obj["segments"].as_array().into_iter().flatten().enumerate() {
        outln!(
            text,
            "segment {i}: alpha {} beta {} length {}",
            s["alpha"],
            s["beta"],
            show(&s["length"])
        );
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimals_parse_exactly() {
        assert_eq!(parse_decimal("0.1"), Some(Rational::from((1, 10))));
        assert_eq!(parse_decimal("-2.5e-3"), Some(Rational::from((-1, 400))));
        assert_eq!(parse_decimal("12E2"), Some(Rational::from(1200)));
        assert_eq!(parse_decimal("1.x"), None);
        assert_eq!(parse_decimal(""), None);
    }
}
