//! `splinelab width`: the smallest S-spline truncation half-width meeting a
//! tolerance (seed 000 eq 10, 28), with the error achieved and the tail bound.

use super::coeffs::family_from_args;
use super::width_emit::{Dtype, Emit, Table, parse_dtype, parse_emit, parse_name};
use crate::budget::BudgetArgs;
use crate::error::CliError;
use crate::outln;
use crate::output::{emit, print_json, write_atomic};
use crate::path_text::path_text;
use clap::Args;
use serde_json::json;
use splinelab::sspline::width::certified_width;
use splinelab::sspline::{
    Criterion, SplineFamily, WidthChoice, f64_saturation_width, truncation_width,
};
use splinelab_verify::cost::width_search;
use std::path::PathBuf;

/// Arguments of `splinelab width`.
#[derive(Debug, Args)]
pub struct WidthArgs {
    /// B-spline order m (degree m − 1), 2..=200. Ignored with --tension (cubic Beta2).
    #[arg(long, default_value_t = 4, value_parser = super::whole::<u32>)]
    pub order: u32,
    /// Beta2 tension β2 ≥ 0 (decimal or p/q, taken exactly); implies the cubic Beta2 family.
    #[arg(long)]
    pub tension: Option<String>,
    /// Tolerance ε, 0 < ε < 1.
    #[arg(long)]
    pub tol: f64,
    /// coeff: |c_n| < ε (the paper's rule); knot: max_j |S_n(j) − δ_0j| < ε;
    /// uniform: sup_x Σ_k |S(x−k) − S_n(x−k)| < ε (worst curve error for |P| ≤ 1).
    #[arg(long, default_value = "uniform", value_parser = parse_criterion)]
    pub criterion: Criterion,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Emit the coefficient table c_0..c_n instead: a C header, Rust
    /// constants, JSON, or a .npy (needs --output).
    #[arg(long, value_parser = parse_emit)]
    pub emit: Option<Emit>,
    /// Prefix of the emitted names (a C identifier): PREFIX_HALF_WIDTH, PREFIX_coeffs.
    #[arg(long, default_value = "splinelab", value_parser = parse_name)]
    pub name: String,
    /// Element type of the emitted table: f64 (double) or f32 (float).
    #[arg(long, default_value = "f64", value_parser = parse_dtype)]
    pub dtype: Dtype,
    /// Write the emitted table to this file (atomically) instead of stdout.
    #[arg(long)]
    pub output: Option<PathBuf>,
    /// The run-time and memory budget.
    #[command(flatten)]
    pub budget: BudgetArgs,
}

fn parse_criterion(s: &str) -> Result<Criterion, String> {
    s.parse()
}

/// Runs `splinelab width`.
pub fn run(args: &WidthArgs) -> Result<(), CliError> {
    let family = family_from_args(args.order, args.tension.as_deref())?;
    if !(args.tol > 0.0 && args.tol < 1.0) {
        return Err(CliError::invalid(
            "--tol",
            format!("{} is not in the open interval (0, 1)", args.tol),
        ));
    }
    let saturation = f64_saturation_width(&family).map_err(CliError::numerical)?;
    let _spinner = args
        .budget
        .check(&width_search(&family, saturation, args.tol))?;
    let w = truncation_width(&family, args.tol, args.criterion).map_err(CliError::numerical)?;
    if let Some(form) = args.emit {
        return emit_table(args, &family, &w, form);
    }
    if args.output.is_some() {
        return Err(CliError::invalid(
            "--output",
            "writes an emitted table: add --emit",
        ));
    }
    // The width guaranteed by the tail bound alone, when the chosen one is
    // only met by the measured error.
    let certified = if w.bound >= args.tol {
        Some(certified_width(&family, args.tol).map_err(CliError::numerical)?)
    } else {
        None
    };
    if args.json {
        print_json(&json!({
            "order": family.spline_order(),
            "tension": family.tension().map(|t| t.to_string()),
            "family": family.to_string(),
            "tol": args.tol,
            "criterion": w.criterion.name(),
            "n": w.n,
            "achieved": w.achieved,
            "bound": w.bound,
            "support_radius": w.n as f64 + family.half_support(),
            "support_radius_unit": "samples",
            "bound_meets_tol": w.bound < args.tol,
            "certified_n": certified.map(|c| c.0),
            "certified_bound": certified.map(|c| c.1),
            "f64_saturation_n": saturation,
        }))?;
    } else {
        let mut text = String::new();
        outln!(text, "S-spline truncation width, {family}");
        outln!(text, "criterion        {} < {:e}", w.criterion, args.tol);
        outln!(text, "half-width n     {}", w.n);
        outln!(text, "achieved error   {:e}", w.achieved);
        outln!(
            text,
            "tail bound       {:e}  (≥ worst curve error for |P| ≤ 1)",
            w.bound
        );
        if let Some((n_c, b_c)) = certified {
            outln!(
                text,
                "                 the bound is above the tolerance: n meets it by the achieved \
                 error (computed in 320-bit MPFR; for uniform a located sup, within ~1e-9 \
                 relative); the bound alone guarantees it from n = {n_c} (bound {b_c:e})"
            );
        }
        outln!(
            text,
            "support radius   {} samples  (n + m/2: samples each side that one output reads)",
            w.n as f64 + family.half_support()
        );
        outln!(
            text,
            "f64 saturation n {saturation}  (wider cannot change an f64 result)"
        );
        emit(&text)?;
    }
    Ok(())
}

/// `--emit`: the table in the chosen form, to `--output` or stdout.
fn emit_table(
    args: &WidthArgs,
    family: &SplineFamily,
    w: &WidthChoice,
    form: Emit,
) -> Result<(), CliError> {
    if args.json {
        return Err(CliError::invalid(
            "--json",
            "not with --emit (use --emit json)",
        ));
    }
    let table = Table::new(family, w, args.dtype)?;
    let bytes = match form {
        Emit::C => table.c_header(&args.name).into_bytes(),
        Emit::Rust => table.rust_items(&args.name).into_bytes(),
        Emit::Json => {
            let t = serde_json::to_string_pretty(&table.json()).map_err(CliError::numerical)?;
            (t + "\n").into_bytes()
        }
        Emit::Npy => table.npy()?,
    };
    match &args.output {
        Some(path) => {
            write_atomic(path, &bytes)?;
            emit(&format!(
                "wrote {} (c_0..c_{}, bound {:e})\n",
                path_text(path),
                w.n,
                w.bound
            ))
        }
        None if form == Emit::Npy => Err(CliError::invalid(
            "--output",
            "required with --emit npy (binary data is not written to the terminal)",
        )),
        None => emit(&String::from_utf8_lossy(&bytes)),
    }
}
