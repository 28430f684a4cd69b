//! # splinelab-reports
//!
//! Presents the studies of `splinelab-verify`: the `splinelab` command line,
//! an HTML report with SVG charts (plotters), and machine-readable JSON.

pub mod array_io;
pub mod budget;
pub mod chart;
pub mod check_charts;
pub mod cli;
pub mod error;
pub mod heatmap;
pub mod html;
pub mod input;
pub mod interrupt;
pub mod npy_layout;
pub mod output;
pub mod page;
pub mod path_text;
pub mod report;
pub mod session;
pub mod threads;
