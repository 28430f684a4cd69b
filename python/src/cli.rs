//! The `splinelab` command line inside the Python package: the wheel's
//! `splinelab` console script and `python -m splinelab` (splinelab/__main__.py)
//! run the same program as the Rust binary, so CI jobs and users get
//! `splinelab check`/`compare` from `pip install` without a Rust toolchain.

use pyo3::prelude::*;
use splinelab_reports::cli::entry::{main, status_number};
use std::ffi::OsString;

/// Runs `splinelab ARGS…` (`args[0]` is the program name) with the GIL
/// released and returns its exit status; it prints to the process's own
/// stdout and stderr.
#[pyfunction]
pub fn cli_main(py: Python<'_>, args: Vec<OsString>) -> u8 {
    py.detach(|| crate::pool::parallel(|| status_number(main(args))))
}
