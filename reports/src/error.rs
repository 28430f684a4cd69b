//! The command line's error type.

use crate::path_text::path_text;
use std::path::PathBuf;

/// Everything that can go wrong in a command. Each is reported as
/// `error: …` on stderr with a non-zero exit status.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// An argument is out of its documented range or malformed.
    #[error("invalid argument {arg}: {why}")]
    InvalidArgument {
        /// The option, e.g. `--degree`.
        arg: &'static str,
        /// What is wrong with it.
        why: String,
    },
    /// An input file could not be read or parsed.
    #[error("cannot read {}: {why}", path_text(path))]
    Input {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        why: String,
    },
    /// An output file could not be written.
    #[error("cannot write {}: {source}", path_text(path))]
    Output {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Newton's method did not converge (`qi`): exit status 1, not 2, since
    /// the input was valid and the output (with `--json`) still came.
    #[error("{0}")]
    NotConverged(String),
    /// The computation itself failed (singular matrix, no convergence, …).
    #[error("{0}")]
    Numerical(String),
    /// Standard output is a pipe whose reader has gone (`| head`): not an
    /// error to report, the program ends quietly (exit status 141, as a shell
    /// shows for a Unix tool ended by SIGPIPE).
    #[error("standard output closed")]
    ClosedPipe,
    /// Writing to standard output failed (e.g. a full disk).
    #[error("cannot write to standard output: {0}")]
    Stdout(std::io::Error),
    /// The request's estimated cost exceeds its budget.
    #[error("{0}")]
    OverBudget(String),
    /// The run was interrupted (SIGINT/SIGTERM).
    #[error("interrupted")]
    Interrupted,
    /// A `check` refused its input or could not certify its reference.
    #[error("{0}")]
    Check(#[from] splinelab_verify::check::CheckError),
    /// A chart could not be drawn.
    #[error("chart '{0}': {1}")]
    Chart(String, String),
}

/// Exit status of a successful run.
pub const EXIT_OK: u8 = 0;
/// Exit status when a computation ran but its answer is a failure the
/// command defines: a regression in `compare`, Newton not converging in
/// `qi`. Distinct from bad input so that scripts can tell them apart.
pub const EXIT_FAILED: u8 = 1;
/// Exit status of every error: bad arguments or input, unwritable output,
/// a numerical failure, a request over budget.
pub const EXIT_ERROR: u8 = 2;
/// Exit status after SIGINT or SIGTERM (128 + SIGINT, as shells report).
pub const EXIT_INTERRUPTED: u8 = 130;
/// Exit status when stdout's reader has gone (128 + SIGPIPE, as shells
/// report for Unix tools).
pub const EXIT_CLOSED_PIPE: u8 = 141;

impl CliError {
    /// The exit status for this error.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::ClosedPipe => EXIT_CLOSED_PIPE,
            CliError::Interrupted => EXIT_INTERRUPTED,
            CliError::NotConverged(_) => EXIT_FAILED,
            _ => EXIT_ERROR,
        }
    }

    /// Shorthand for [`CliError::InvalidArgument`].
    pub fn invalid(arg: &'static str, why: impl Into<String>) -> Self {
        CliError::InvalidArgument {
            arg,
            why: why.into(),
        }
    }

    /// Wraps any displayable numerical error.
    pub fn numerical(e: impl std::fmt::Display) -> Self {
        CliError::Numerical(e.to_string())
    }
}
