//! Work budgets: a command estimates its run time (and memory) from its
//! arguments before starting, and refuses a request beyond its budget with
//! the estimate and the flag that raises the budget. Allowed runs longer
//! than [`SPINNER_SECONDS`] show a spinner on stderr when it is a terminal.
//!
//! The estimates are models calibrated on measurements on the team's 2-core
//! machine (see [`unit_seconds`]); they are meant to be right within a
//! factor of a few, enough to tell a second from an hour.

use crate::error::CliError;
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::time::Duration;

/// Default `--budget`, in estimated seconds.
pub const DEFAULT_SECONDS: f64 = 60.0;
/// Default `--max-memory`, in MiB.
pub const DEFAULT_MEMORY_MIB: f64 = 2048.0;
/// Runs estimated longer than this show a spinner (on a terminal).
pub const SPINNER_SECONDS: f64 = 2.0;

/// The budget flags shared by the commands that estimate their cost.
#[derive(Debug, Clone, Copy, Args)]
pub struct BudgetArgs {
    /// Largest estimated run time accepted, in seconds (the estimate is
    /// printed when a request is refused).
    #[arg(long, value_name = "SECONDS", default_value_t = DEFAULT_SECONDS)]
    pub budget: f64,
    /// Largest estimated memory accepted, in MiB.
    #[arg(long, value_name = "MIB", default_value_t = DEFAULT_MEMORY_MIB)]
    pub max_memory: f64,
}

impl Default for BudgetArgs {
    fn default() -> Self {
        BudgetArgs {
            budget: DEFAULT_SECONDS,
            max_memory: DEFAULT_MEMORY_MIB,
        }
    }
}

// The cost models live in verify (the Python package budgets with them too).
pub use splinelab_verify::cost::{Estimate, OverBudget, number_bytes, unit_seconds};

impl BudgetArgs {
    /// Refuses `e` beyond the budget; otherwise returns a spinner (hidden
    /// unless stderr is a terminal and the run is long) to finish when done.
    pub fn check(&self, e: &Estimate) -> Result<Spinner, CliError> {
        if !(self.budget.is_finite() && self.budget > 0.0) {
            return Err(CliError::invalid(
                "--budget",
                format!("{} is not a positive number of seconds", self.budget),
            ));
        }
        if !(self.max_memory.is_finite() && self.max_memory > 0.0) {
            return Err(CliError::invalid(
                "--max-memory",
                format!("{} is not a positive number of MiB", self.max_memory),
            ));
        }
        e.within(self.budget, Some(self.max_memory))
            .map_err(|over| {
                let knob = match over {
                    OverBudget::Time { .. } => "the budget with --budget",
                    OverBudget::Memory { .. } => "the limit with --max-memory",
                };
                CliError::OverBudget(format!(
                    "{over}: reduce it, or raise {knob} {:.0}",
                    over.admit()
                ))
            })?;
        Ok(Spinner::start(e))
    }
}

/// A spinner with the estimate and the elapsed time on stderr, drawn only
/// on a terminal (indicatif hides it otherwise) and only for long runs;
/// cleared when dropped.
#[derive(Debug)]
pub struct Spinner(Option<ProgressBar>);

impl Spinner {
    fn start(e: &Estimate) -> Self {
        if e.seconds < SPINNER_SECONDS {
            return Spinner(None);
        }
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
        if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} ({elapsed})") {
            bar.set_style(style);
        }
        bar.set_message(format!(
            "{}: estimated {:.0} s, Ctrl-C stops",
            e.what, e.seconds
        ));
        bar.enable_steady_tick(Duration::from_millis(200));
        Spinner(Some(bar))
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}
