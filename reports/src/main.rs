//! The `splinelab` command line.

use std::process::ExitCode;

fn main() -> ExitCode {
    splinelab_reports::cli::entry::main(std::env::args_os())
}
