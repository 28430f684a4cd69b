//! `splinelab._splinelab`: the compiled half of the Python package
//! `splinelab` (python/splinelab/ holds the Python half with scipy's
//! argument handling, docstrings and the dask wrappers).
//!
//! Every function here takes already-normalised arguments (dtype, axes,
//! mode name), releases the GIL while it computes, and turns every Rust
//! error into a Python exception carrying the Rust message (`ValueError`,
//! or `MemoryError` where an allocation is refused: [`error`]).
//!
//! No call may end in a Rust panic (pyo3's `PanicException`, which derives
//! from `BaseException`, so `except Exception` does not catch it): the
//! lints below refuse `unwrap`, `expect`, `panic!`, `unreachable!` and
//! indexing that can panic in this crate, and results are allocated by
//! numpy ([`alloc`]) or fallibly by the engine. python/tests/test_no_panics.py
//! checks that they stay denied.

#![deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#![deny(clippy::indexing_slicing, clippy::unreachable)]
#![deny(clippy::todo, clippy::unimplemented)]

mod alloc;
mod check;
mod cli;
mod coefficients;
mod common;
mod error;
mod filter;
mod grid;
mod interp;
mod local;
mod mapping;
mod pages;
mod pool;
mod resample;
mod samples;
mod scipy_mode;
mod width;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _splinelab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add(
        "NonFiniteCoordinateError",
        m.py().get_type::<error::NonFiniteCoordinateError>(),
    )?;
    // `nan_policy="local"`'s default tolerance: the engine's, as the CLI's.
    m.add("LOCAL_TOL", splinelab::prelude::LOCAL_TOL)?;
    // The local route's pricing constants (nanoseconds) that decide the
    // global route before any call (`splinelab._local.may_be_local`).
    {
        use splinelab::ndimage::local::route::{
            C_CALL, C_COPY, C_GLOBAL, C_IN_PLACE_TAP, C_LOCATE, C_POINT, C_READ, C_TAP,
        };
        let cost = pyo3::types::PyDict::new(m.py());
        cost.set_item("call", C_CALL)?;
        cost.set_item("locate", C_LOCATE)?;
        cost.set_item("point", C_POINT)?;
        cost.set_item("read", C_READ)?;
        cost.set_item("tap", C_TAP)?;
        cost.set_item("global", C_GLOBAL)?;
        cost.set_item("copy", C_COPY)?;
        cost.set_item("in_place_tap", C_IN_PLACE_TAP)?;
        m.add("LOCAL_ROUTE_COST", cost)?;
    }
    m.add_function(wrap_pyfunction!(filter::nan_reach, m)?)?;
    m.add_function(wrap_pyfunction!(filter::filter, m)?)?;
    m.add_function(wrap_pyfunction!(filter::filter_common, m)?)?;
    m.add_function(wrap_pyfunction!(scipy_mode::filter_rule_py, m)?)?;
    m.add_function(wrap_pyfunction!(filter::filter_bound, m)?)?;
    m.add_function(wrap_pyfunction!(interp::map_coordinates, m)?)?;
    m.add_function(wrap_pyfunction!(interp::in_place_pays, m)?)?;
    m.add_function(wrap_pyfunction!(interp::map_coordinates_common, m)?)?;
    m.add_function(wrap_pyfunction!(scipy_mode::engine_args_py, m)?)?;
    m.add_function(wrap_pyfunction!(local::local_map_f64, m)?)?;
    m.add_function(wrap_pyfunction!(local::local_map_f32, m)?)?;
    m.add_function(wrap_pyfunction!(local::local_route_cost, m)?)?;
    m.add_function(wrap_pyfunction!(local::local_half_width, m)?)?;
    m.add_class::<local::LocalSplineF64>()?;
    m.add_class::<local::LocalSplineF32>()?;
    m.add_class::<grid::GridSpline>()?;
    m.add_function(wrap_pyfunction!(grid::grid_cardinal_weights, m)?)?;
    m.add_function(wrap_pyfunction!(grid::grid_linear, m)?)?;
    m.add_function(wrap_pyfunction!(grid::grid_nearest, m)?)?;
    m.add_function(wrap_pyfunction!(grid::grid_points_scan, m)?)?;
    m.add_function(wrap_pyfunction!(grid::grid_pchip, m)?)?;
    m.add_function(wrap_pyfunction!(resample::resample, m)?)?;
    m.add_function(wrap_pyfunction!(resample::affine, m)?)?;
    m.add_function(wrap_pyfunction!(resample::shift_common, m)?)?;
    m.add_function(wrap_pyfunction!(resample::zoom_common, m)?)?;
    m.add_function(wrap_pyfunction!(resample::affine_common, m)?)?;
    m.add_function(wrap_pyfunction!(mapping::mapped_points, m)?)?;
    m.add_function(wrap_pyfunction!(width::truncation_width, m)?)?;
    m.add_function(wrap_pyfunction!(width::coefficients_f64, m)?)?;
    m.add_function(wrap_pyfunction!(width::coefficients_decimal, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_prefilter, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_coeffs, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_bspline_eval, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_bezier_eval, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_knot_insertion, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_interp, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_grid_spline, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_cond, m)?)?;
    m.add_function(wrap_pyfunction!(cli::cli_main, m)?)?;
    // The pages a CI run leaves (report, check, compare, session) share it.
    m.add("REPORT_CSS", splinelab_reports::page::STYLE)?;
    m.add_function(wrap_pyfunction!(pages::session_page, m)?)?;
    Ok(())
}
