//! How an interpolant's coefficients are made from what the Python layer
//! passes: the samples prefiltered by the engine, prefiltered under scipy's
//! rule for another mode, or taken as given (`prefilter=False`).

use crate::error::value_error;
use pyo3::prelude::*;
use splinelab::prelude::Mode;

/// How the interpolant's coefficients are made: from samples (the engine
/// prefilters them under the mode), from samples prefiltered under another
/// rule and then taken as given (scipy's `nearest`/`grid-constant`), or
/// taken as given (scipy's `prefilter=False`).
#[derive(Debug, Clone, Copy)]
pub(crate) enum Coefficients {
    Prefilter,
    FilteredAs(Mode),
    Given,
}

impl Coefficients {
    /// From `prefilter` and the optional filter rule's name.
    pub(crate) fn new(prefilter: bool, filter_rule: Option<&str>) -> PyResult<Self> {
        Ok(match (prefilter, filter_rule) {
            (false, _) => Coefficients::Given,
            (true, None) => Coefficients::Prefilter,
            (true, Some(rule)) => Coefficients::FilteredAs(rule.parse().map_err(value_error)?),
        })
    }
}
