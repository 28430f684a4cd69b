//! `splinelab coeffs`: the S-spline coefficients `c_0..c_{K−1}` and poles of
//! one family (seed 000 eq 17, 29).

use super::prec::{Prec, parse_prec};
use crate::budget::{BudgetArgs, Estimate, number_bytes, unit_seconds};
use crate::error::CliError;
use crate::outln;
use crate::output::{emit, print_json};
use crate::with_real;
use clap::Args;
use serde_json::json;
use splinelab::sspline::coefficients::poles_rounded;
use splinelab::sspline::{CoefficientMethod, SplineFamily, coefficients};

/// Largest `--count` accepted.
pub const MAX_COUNT: usize = 100_000;

/// Arguments of `splinelab coeffs`.
#[derive(Debug, Args)]
pub struct CoeffsArgs {
    /// B-spline order m (degree m − 1), 2..=200. Ignored with --tension (cubic Beta2).
    #[arg(long, default_value_t = 4, value_parser = super::whole::<u32>)]
    pub order: u32,
    /// Beta2 tension β2 ≥ 0 (decimal or p/q, taken exactly); implies the cubic Beta2 family.
    #[arg(long)]
    pub tension: Option<String>,
    /// Working precision: f64, or MPFR bits (16..=2048; runs at the next compiled precision, at most 2× the bits).
    #[arg(long, default_value = "f64", value_parser = parse_prec)]
    pub prec: Prec,
    /// Number of coefficients c_0..c_{K−1} (1..=100000).
    #[arg(long, default_value_t = 10, value_parser = super::whole::<usize>)]
    pub count: usize,
    /// Method: production (partial fractions with ≥128 guard bits, rounded once),
    /// partial-fractions, recursive-filter or toeplitz-solve (all in the working precision).
    #[arg(long, default_value = "production", value_parser = parse_method)]
    pub method: CoefficientMethod,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// The run-time and memory budget.
    #[command(flatten)]
    pub budget: BudgetArgs,
}

fn parse_method(s: &str) -> Result<CoefficientMethod, String> {
    CoefficientMethod::INDEPENDENT
        .into_iter()
        .chain([CoefficientMethod::Production])
        .find(|m| m.name() == s)
        .ok_or_else(|| {
            format!("unknown method '{s}' (production, partial-fractions, recursive-filter, toeplitz-solve)")
        })
}

/// The family from `--order` / `--tension`, validated.
pub fn family_from_args(order: u32, tension: Option<&str>) -> Result<SplineFamily, CliError> {
    match tension {
        Some(t) => SplineFamily::parse_tension(t)
            .map_err(|e| CliError::invalid("--tension", e.to_string())),
        None => SplineFamily::order(order).map_err(|e| CliError::invalid("--order", e.to_string())),
    }
}

/// The cost of `coeffs`: the poles (`≈ 50·m²` units at the guarded
/// precision, ≤ 2× the bits + 512), then per method: partial fractions
/// `count·p`, recursive filter `2·(2n+1)·p`, Toeplitz band solve
/// `(2n+1)·p²` with `(2n+1)(2p+1)` stored numbers, where `p ≈ m/2` and
/// `n = count + (bits+16)/log2(1/ρ)`, `log2(1/ρ) ≈ 54/n_sat`.
pub fn estimate(
    family: &SplineFamily,
    count: usize,
    method: CoefficientMethod,
    bits: u32,
    n_sat: usize,
) -> Estimate {
    let m = family.spline_order() as f64;
    let p = (m / 2.0).max(1.0);
    let wide = 2 * bits.max(64) + 512;
    let poles = 50.0 * m * m * unit_seconds(wide);
    let count = count as f64;
    let n = count + (bits as f64 + 16.0) * n_sat.max(1) as f64 / 54.0 + 2.0;
    let size = 2.0 * n + 1.0;
    let (work, stored, at) = match method {
        CoefficientMethod::Production => (count * p, count, wide),
        CoefficientMethod::PartialFractions => (count * p, count, bits),
        CoefficientMethod::RecursiveFilter => (2.0 * size * p, size, bits),
        CoefficientMethod::ToeplitzSolve => (size * p * p, size * (2.0 * p + 1.0), bits),
    };
    Estimate {
        seconds: poles + work * unit_seconds(at),
        bytes: stored * number_bytes(at),
        what: format!(
            "{} coefficients of {family} by {} at {bits} bits",
            count,
            method.name()
        ),
    }
}

/// Runs `splinelab coeffs`.
pub fn run(args: &CoeffsArgs) -> Result<(), CliError> {
    let family = family_from_args(args.order, args.tension.as_deref())?;
    if !(1..=MAX_COUNT).contains(&args.count) {
        return Err(CliError::invalid(
            "--count",
            format!("{} is outside 1..={MAX_COUNT}", args.count),
        ));
    }
    let prec = args.prec;
    let n_sat = splinelab::sspline::f64_saturation_width(&family).map_err(CliError::numerical)?;
    let e = estimate(&family, args.count, args.method, prec.working_bits(), n_sat);
    let _spinner = args.budget.check(&e)?;
    let (c, xi) = with_real!(prec, T => {
        let c: Vec<T> = coefficients(&family, args.count, args.method).map_err(CliError::numerical)?;
        let xi: Vec<T> = poles_rounded(&family).map_err(CliError::numerical)?;
        (
            c.iter().map(|x| prec.format(x)).collect::<Vec<_>>(),
            xi.iter().map(|x| prec.format(x)).collect::<Vec<_>>(),
        )
    });
    let tension = family.tension().map(|t| t.to_string());
    if args.json {
        print_json(&json!({
            "order": family.spline_order(),
            "tension": tension,
            "family": family.to_string(),
            "prec": prec.to_string(),
            "working_bits": prec.working_bits(),
            "method": args.method.name(),
            "c": c,
            "poles": xi,
        }))?;
    } else {
        let mut text = String::new();
        outln!(
            text,
            "S-spline coefficients, {family} ({} method)",
            args.method.name()
        );
        outln!(
            text,
            "precision {prec} (computed at {} bits)",
            prec.working_bits()
        );
        for (r, x) in xi.iter().enumerate() {
            outln!(text, "pole ξ_{r:<3} {x}");
        }
        outln!(text, "{:>6}  c_i = c_-i", "i");
        for (i, x) in c.iter().enumerate() {
            outln!(text, "{i:>6}  {x}");
        }
        emit(&text)?;
    }
    Ok(())
}
