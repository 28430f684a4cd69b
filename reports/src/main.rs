//! The `splinelab` command line.

use std::process::ExitCode;

fn main() -> ExitCode {
    splinelab_reports::entry::main(std::env::args_os())
}
