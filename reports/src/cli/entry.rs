//! The `splinelab` program as a function of its arguments: the binary's
//! `main` and the Python package's `splinelab` console script
//! (`splinelab.__main__`, through the extension) both run it, so a wheel
//! installs the same command line without a Rust toolchain.

use super::{parse_args, run};
use crate::error::{CliError, EXIT_ERROR};
use crate::output::{cap_echo, emit, note};
use std::ffi::OsString;
use std::process::ExitCode;

/// Parses `args` (the program name first), runs the subcommand and returns
/// its exit status (see [`crate::cli::ENVIRONMENT`]). It owns the process:
/// it sizes the global thread pool and installs the SIGINT/SIGTERM handler
/// that removes partial outputs.
pub fn main<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match parse_args(args) {
        Ok(cli) => cli,
        Err(e) => return clap_exit(&e),
    };
    crate::threads::configure();
    crate::interrupt::install();
    match run(&cli.command) {
        Ok(code) => code,
        Err(e) => fail(&e),
    }
}

/// The number behind an [`ExitCode`] (which has no accessor), for a host
/// that exits by itself.
pub fn status_number(code: ExitCode) -> u8 {
    (0..=u8::MAX)
        .find(|&n| ExitCode::from(n) == code)
        .unwrap_or(EXIT_ERROR)
}

/// Reports `e` on stderr (nothing for a closed stdout pipe) and returns its
/// exit status.
fn fail(e: &CliError) -> ExitCode {
    if !matches!(e, CliError::ClosedPipe) {
        note(&cap_echo(&format!("error: {e}")));
    }
    ExitCode::from(e.exit_code())
}

/// `--help` and `--version` go to stdout through [`emit`] (a failed write is
/// an error, not a silent exit 0); usage errors go to stderr, with long
/// echoed values shortened.
fn clap_exit(e: &clap::Error) -> ExitCode {
    let text = e.render().to_string();
    if e.use_stderr() {
        note(cap_echo(&text).trim_end());
        return ExitCode::from(EXIT_ERROR);
    }
    match emit(&text) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => fail(&err),
    }
}
