//! The pytest plugin's session page, drawn by the reports crate
//! (`splinelab_reports::session`) with the report's chart code and
//! stylesheet, so the pages a CI run leaves share one look.

use crate::error::value_error;
use pyo3::prelude::*;
use splinelab_reports::session::{SessionCheck, session_files};

/// `session_page(checks_json)`: the files of the session page, a list of
/// `(name, text)` (`index.html` and the chart's SVG), from a JSON list of
/// `{"label", "page", "check"}` (a check's `summary.json` `check` object).
/// Malformed JSON is a `ValueError`.
#[pyfunction]
pub fn session_page(py: Python<'_>, checks_json: &str) -> PyResult<Vec<(String, String)>> {
    let checks: Vec<SessionCheck> = serde_json::from_str(checks_json).map_err(value_error)?;
    py.detach(|| crate::pool::parallel(|| session_files(&checks)))
        .map_err(value_error)
}
