//! Subcommands of `splinelab`, one file each. A new command adds one variant
//! to [`Command`] and one arm to [`run`].

pub mod bezier_eval;
pub mod check;
pub mod check_out;
pub mod cli_docs;
pub mod coeffs;
pub mod compare;
pub mod cond;
pub mod deform;
pub mod engine_io;
pub mod entry;
pub mod flatten;
pub mod interpolate;
pub mod interpolate_local;
pub mod nan_io;
pub mod prec;
pub mod prefilter;
pub mod qi;
pub mod report;
pub mod resample;
pub mod width;
pub mod width_emit;

use crate::error::CliError;
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::process::ExitCode;

/// splinelab: precision studies of spline and Bézier algorithms in f64 and
/// MPFR arbitrary precision.
#[derive(Debug, Parser)]
#[command(name = "splinelab", version, about, long_about = None, after_help = ENVIRONMENT)]
pub struct Cli {
    /// The subcommand to run.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Condition numbers of Bernstein (or monomial) Vandermonde matrices.
    Cond(cond::CondArgs),
    /// Run every study and write the HTML report, charts and summary.json.
    Report(report::ReportArgs),
    /// Compare a summary.json with a baseline; exit 1 when a figure regressed.
    Compare(compare::CompareArgs),
    /// Evaluate a Bernstein polynomial by one method, with running error bounds.
    BezierEval(bezier_eval::BezierEvalArgs),
    /// G2 interpolation of 3D points by quaternion-integral curves (Newton).
    Qi(qi::QiArgs),
    /// S-spline coefficients c_i and poles for an order or a Beta2 tension.
    Coeffs(coeffs::CoeffsArgs),
    /// Smallest S-spline truncation half-width meeting a tolerance.
    Width(width::WidthArgs),
    /// Deform a Bézier patch grid by flow vectors (Bernstein inverse mapping) and correct its joins.
    Deform(deform::DeformArgs),
    /// Adaptive flattening of a Bézier curve vs uniform sampling (seed 002).
    Flatten(flatten::FlattenArgs),
    /// Check your own results (prefilter, coefficients, B-spline/Bézier values,
    /// knot insertion) against certified references; exit 1 on failure.
    Check(check::CheckArgs),
    /// Interpolation coefficients of an N-D array (scipy's spline_filter), any degree 1..=199.
    Prefilter(prefilter::PrefilterArgs),
    /// Evaluate the spline interpolant of an N-D array at points (scipy's map_coordinates).
    Interpolate(interpolate::InterpolateArgs),
    /// scipy's zoom, shift, rotate and affine_transform of an N-D array (.npy in and out).
    Resample(resample::ResampleArgs),
    /// The command line's reference: man pages and a Markdown page of every
    /// `--help` (for the documentation site).
    #[command(hide = true)]
    CliDocs(cli_docs::CliDocsArgs),
}

/// The environment and exit statuses, shown under `--help`.
pub const ENVIRONMENT: &str = "\
Environment:
  SPLINELAB_MAX_INPUT_BYTES  largest input file read (default 67108864 = 64 MiB)
  RAYON_NUM_THREADS          worker threads (clamped to 1..=256)
Exit status: 0 success; 1 a defined failure (compare: a figure regressed; qi: Newton
did not converge); 2 an error (bad argument or input, unwritable output, over budget,
numerical failure); 130 interrupted (SIGINT/SIGTERM, no partial files left);
141 standard output closed by its reader (e.g. `| head`).";

/// Parses the command line. Every subcommand takes negative numbers as
/// values (`--max-iter -1` is then refused by its range check with a clear
/// message, not mistaken for a flag).
pub fn parse_args<I, T>(args: I) -> Result<Cli, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let mut cmd = Cli::command();
    let names: Vec<String> = cmd
        .get_subcommands()
        .map(|c| c.get_name().to_string())
        .collect();
    for name in names {
        cmd = cmd.mut_subcommand(name, |c| c.allow_negative_numbers(true));
    }
    let args = join_hyphen_values(&cmd, args.into_iter().map(Into::into).collect());
    let matches = cmd.try_get_matches_from(args)?;
    Cli::from_arg_matches(&matches)
}

/// Rewrites `--flag -v` as `--flag=-v` when `--flag` takes a value and `-v`
/// is not itself an option (`--…`): clap would otherwise read values like
/// `-1e-3` or `-inf` as unknown short flags ("unexpected argument '-1'"),
/// and the range check of the option gives the clear message instead.
fn join_hyphen_values(
    cmd: &clap::Command,
    args: Vec<std::ffi::OsString>,
) -> Vec<std::ffi::OsString> {
    let mut sub: Option<&clap::Command> = None;
    let mut out: Vec<std::ffi::OsString> = Vec::with_capacity(args.len());
    let mut it = args.into_iter().peekable();
    while let Some(arg) = it.next() {
        let text = arg.to_str().map(str::to_owned);
        // Descend into nested subcommands too (`check prefilter …`).
        if let Some(next) = text
            .as_deref()
            .and_then(|t| sub.unwrap_or(cmd).find_subcommand(t))
        {
            sub = Some(next);
        }
        let takes_value = text
            .as_deref()
            .and_then(|t| t.strip_prefix("--"))
            .filter(|name| !name.contains('='))
            .and_then(|name| {
                sub.unwrap_or(cmd)
                    .get_arguments()
                    .find(|a| a.get_long() == Some(name))
            })
            .is_some_and(|a| a.get_action().takes_values());
        let next_is_hyphen_value = it.peek().and_then(|n| n.to_str()).is_some_and(|n| {
            n.starts_with('-') && !n.starts_with("--") && n.len() > 1 && n != "-h"
        });
        if takes_value && next_is_hyphen_value {
            let mut joined = arg;
            joined.push("=");
            joined.push(it.next().unwrap_or_default());
            out.push(joined);
        } else {
            out.push(arg);
        }
    }
    out
}

/// Parses a whole-number option with a message that says what is wrong
/// (negative, too large, not a number) instead of Rust's parse error.
pub fn whole<N: std::str::FromStr + TryFrom<u64>>(s: &str) -> Result<N, String> {
    let t = s.trim();
    let digits = t.strip_prefix('+').unwrap_or(t);
    if let Some(neg) = digits.strip_prefix('-')
        && !neg.is_empty()
        && neg.bytes().all(|b| b.is_ascii_digit())
    {
        return Err("a negative number is not accepted here".into());
    }
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err("not a whole number".into());
    }
    digits
        .parse::<N>()
        .map_err(|_| "too large (out of range)".to_string())
}

/// Runs a parsed command. `Ok` carries the exit code (0 unless a command
/// defines others, like a regression compare).
pub fn run(command: &Command) -> Result<ExitCode, CliError> {
    let done = |r: Result<(), CliError>| r.map(|()| ExitCode::SUCCESS);
    match command {
        Command::Cond(a) => done(cond::run(a)),
        Command::Report(a) => done(report::run(a)),
        Command::Compare(a) => compare::run(a),
        Command::BezierEval(a) => done(bezier_eval::run(a)),
        Command::Qi(a) => done(qi::run(a)),
        Command::Coeffs(a) => done(coeffs::run(a)),
        Command::Width(a) => done(width::run(a)),
        Command::Deform(a) => done(deform::run(a)),
        Command::Flatten(a) => done(flatten::run(a)),
        Command::Check(a) => check::run(a),
        Command::Prefilter(a) => done(prefilter::run(a)),
        Command::Interpolate(a) => done(interpolate_any(a)),
        Command::Resample(a) => done(resample::run(a)),
        Command::CliDocs(a) => done(cli_docs::run(a)),
    }
}

/// `splinelab interpolate`: a memory-mapped .npy on the local route where it
/// pays (issue 45), the global route otherwise.
fn interpolate_any(args: &interpolate::InterpolateArgs) -> Result<(), CliError> {
    if interpolate_local::try_run(args)? {
        return Ok(());
    }
    interpolate::run(args)
}
