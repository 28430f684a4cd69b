//! scipy.ndimage's interpolation modes as the engine evaluates them: the
//! one mapping (issue 50) from scipy's `mode` to the engine's mode, point
//! rule and scipy's padding. The Python layer asks it through
//! `splinelab._modes.engine_args` (the drop-in, the local route, the dask
//! wrappers); the common call's one step ([`crate::interp`]) asks it here.

use crate::error::value_error;
use pyo3::prelude::*;
use splinelab::ndimage::interpolant::PointRule;
use splinelab::prelude::Mode;

/// The samples scipy pads on every side before its filter for `nearest`
/// and `grid-constant` at degrees 2 to 5 (`ni_interpolation.c`).
const SCIPY_PAD: usize = 12;

/// scipy's `mode` as the engine evaluates it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct EngineArgs {
    /// The engine's mode (the spline's extension).
    pub mode: Mode,
    /// What happens to a point before the spline is evaluated there.
    pub rule: PointRule,
    /// Samples padded on every side (scipy's route), else 0.
    pub pad: usize,
}

/// scipy's interpolation `mode` at `degree`: 'constant' is the mirror
/// spline with `cval` at points outside the grid; 'wrap' the mirror spline
/// at the point moved by whole periods `n − 1`; 'nearest' and
/// 'grid-constant' at degrees 2 to 5 with the prefilter (and without
/// `exact_edges`) scipy's route, the samples padded by 12 and filtered with
/// scipy's rule, the point moved by 12; every other mode the engine's own,
/// points folded. `None`: not one of scipy's names.
pub(crate) fn engine_args(
    mode: &str,
    degree: u32,
    prefilter: bool,
    exact_edges: bool,
) -> Option<EngineArgs> {
    let (mode, rule) = match mode {
        "constant" => (Mode::Mirror, PointRule::CvalOutside),
        "wrap" => (Mode::Mirror, PointRule::WrapPeriodNMinus1),
        other => (other.parse().ok()?, PointRule::Fold),
    };
    let padded = matches!(mode, Mode::Nearest | Mode::GridConstant)
        && rule == PointRule::Fold
        && prefilter
        && (2..=5).contains(&degree)
        && !exact_edges;
    Some(EngineArgs {
        mode,
        rule,
        pad: if padded { SCIPY_PAD } else { 0 },
    })
}

/// The filter scipy's `spline_filter1d` applies under its `mode`
/// (`ni_splines.c` has three: the mirror rule, the reflect (half-sample)
/// rule and the periodic one), or with `exact_edges` the exact extension
/// for 'nearest' / 'grid-constant' (cval 0). `None`: not one of scipy's
/// names.
pub(crate) fn filter_rule(mode: &str, exact_edges: bool) -> Option<Mode> {
    Some(match mode {
        "nearest" if exact_edges => Mode::Nearest,
        "grid-constant" if exact_edges => Mode::GridConstant,
        "mirror" | "constant" | "grid-constant" | "wrap" => Mode::Mirror,
        "reflect" | "grid-mirror" | "nearest" => Mode::Reflect,
        "grid-wrap" => Mode::GridWrap,
        _ => return None,
    })
}

/// [`filter_rule`] for Python: the engine mode's name.
#[pyfunction(name = "filter_rule")]
pub fn filter_rule_py(mode: &str, exact_edges: bool) -> PyResult<&'static str> {
    filter_rule(mode, exact_edges)
        .map(Mode::name)
        .ok_or_else(|| value_error(format!("unknown mode {mode:?}")))
}

/// A point rule by the Python layer's name.
pub(crate) fn point_rule(rule: &str) -> PyResult<PointRule> {
    Ok(match rule {
        "fold" => PointRule::Fold,
        "cval-outside" => PointRule::CvalOutside,
        "wrap" => PointRule::WrapPeriodNMinus1,
        other => return Err(value_error(format!("unknown point rule {other:?}"))),
    })
}

/// The Python layer's name of a point rule (inverse of [`point_rule`]).
fn rule_name(rule: PointRule) -> &'static str {
    match rule {
        PointRule::Fold => "fold",
        PointRule::CvalOutside => "cval-outside",
        PointRule::WrapPeriodNMinus1 => "wrap",
    }
}

/// [`engine_args`] for Python: `(engine mode, point rule, pad)`, the
/// engine mode by its canonical name ('grid-mirror' is 'reflect').
#[pyfunction(name = "engine_args")]
pub fn engine_args_py(
    mode: &str,
    degree: u32,
    prefilter: bool,
    exact_edges: bool,
) -> PyResult<(&'static str, &'static str, usize)> {
    let a = engine_args(mode, degree, prefilter, exact_edges)
        .ok_or_else(|| value_error(format!("unknown mode {mode:?}")))?;
    Ok((a.mode.name(), rule_name(a.rule), a.pad))
}
