//! # splinelab-reports
//!
//! Presents the studies of `splinelab-verify`: the `splinelab` command line,
//! an HTML report with SVG charts (plotters), and machine-readable JSON.

// The modules a user's command line and files reach (the commands, the
// arrays read and the files written) are declared with lints that refuse a
// panic there: `unwrap`, `expect`, `panic!`, `unreachable!` and indexing
// that can panic (issue 42: a bad input or a refused allocation is an error
// message and an exit status, never a backtrace). An `#[allow]` inside
// carries a comment saying why it cannot panic; python/tests/test_no_panics.py
// checks both.
#[deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#[deny(clippy::indexing_slicing, clippy::unreachable)]
#[deny(clippy::todo, clippy::unimplemented)]
pub mod array_io;
#[deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#[deny(clippy::indexing_slicing, clippy::unreachable)]
#[deny(clippy::todo, clippy::unimplemented)]
pub mod cli;
#[deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#[deny(clippy::indexing_slicing, clippy::unreachable)]
#[deny(clippy::todo, clippy::unimplemented)]
pub mod input;
#[deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#[deny(clippy::indexing_slicing, clippy::unreachable)]
#[deny(clippy::todo, clippy::unimplemented)]
pub mod npy_layout;
#[deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#[deny(clippy::indexing_slicing, clippy::unreachable)]
#[deny(clippy::todo, clippy::unimplemented)]
pub mod output;

pub mod budget;
pub mod chart;
pub mod check_charts;
pub mod error;
pub mod heatmap;
pub mod html;
pub mod interrupt;
pub mod page;
pub mod path_text;
pub mod report;
pub mod session;
pub mod threads;
