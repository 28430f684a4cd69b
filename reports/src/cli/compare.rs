//! `splinelab compare`: regression check of a report against a baseline.

use crate::error::CliError;
use crate::outln;
use crate::output::emit;
use crate::report::compare::{Gates, compare, read_figures, read_profile, write_compare};
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `splinelab compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The baseline summary.json (e.g. reports/baseline/summary.json).
    #[arg(long)]
    pub baseline: PathBuf,
    /// The summary.json of the run under test.
    #[arg(long)]
    pub current: PathBuf,
    /// Output folder for index.html and the charts.
    #[arg(long)]
    pub out: PathBuf,
    /// Let wall-clock figures (seconds, nanoseconds) fail the compare too.
    /// Off by default: on a shared machine only same-run ratios and
    /// deterministic figures are reliable gates.
    #[arg(long)]
    pub timings: bool,
    /// Accept gated figures of the baseline that the current run (same
    /// profile) no longer has; without it each is a regression (exit 1).
    #[arg(long)]
    pub allow_missing: bool,
}

/// Runs `splinelab compare`: exit 0 when no gated figure regressed, 1 when
/// one did; unreadable inputs, or two files with no figure in common, are
/// errors (exit 2) naming the file and the field. Figures only one file has
/// are listed, and a difference of profiles is said plainly.
pub fn run(args: &CompareArgs) -> Result<ExitCode, CliError> {
    let baseline = read_figures(&args.baseline)?;
    let current = read_figures(&args.current)?;
    let profiles = (read_profile(&args.baseline)?, read_profile(&args.current)?);
    let gates = Gates {
        timings: args.timings,
        allow_missing: args.allow_missing,
    };
    let outcome = compare(&baseline, &current, &args.current, gates, profiles)?;
    let (staged, regressed) = write_compare(&args.out, &outcome, (&args.baseline, &args.current))?;
    let mut text = String::new();
    if let Some(note) = outcome.profile_note() {
        outln!(text, "{note}");
    }
    for (what, names) in [
        ("only in the baseline", &outcome.only_baseline),
        ("only in the current run", &outcome.only_current),
        ("with a changed kind, unit or direction", &outcome.changed),
    ] {
        if !names.is_empty() {
            outln!(
                text,
                "{} figure(s) {what}, not compared: {}",
                names.len(),
                names.join(", ")
            );
        }
    }
    if !outcome.incomparable.is_empty() {
        outln!(
            text,
            "{} figure(s) measured over other cases than the baseline's (shown, not gated): {}",
            outcome.incomparable.len(),
            outcome.incomparable.join(", ")
        );
    }
    let ungated = outcome
        .rows
        .iter()
        .filter(|r| r.comparable && !r.gated)
        .count();
    outln!(
        text,
        "compared {} figures ({} wall-clock timings shown but not gated{}): {} regressed",
        outcome.rows.len(),
        ungated,
        if ungated > 0 {
            "; --timings gates them"
        } else {
            ""
        },
        regressed.len()
    );
    for r in outcome.regressed() {
        outln!(
            text,
            "REGRESSED {}: baseline {} -> current {} ({})",
            r.baseline.name,
            r.baseline.value,
            r.current,
            r.baseline.unit
        );
    }
    if !outcome.missing.is_empty() {
        outln!(
            text,
            "MISSING {} gated figure(s) from the current run (same profile; --allow-missing \
             accepts this): {}",
            outcome.missing.len(),
            outcome.missing.join(", ")
        );
    }
    outln!(
        text,
        "compare page: {}",
        args.out.join("index.html").display()
    );
    emit(&text)?;
    staged.commit()?;
    Ok(if !outcome.failed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
