//! # splinelab-verify
//!
//! Measures the numerics of [`splinelab`] against independent references
//! (higher-precision MPFR runs, exact rationals, closed forms) and returns the
//! studies as plain serde data for the reports.

pub mod assertions;
pub mod bezier_eval;
pub mod bv_solvers;
pub mod check;
pub mod conditioning;
pub mod cost;
pub mod curves;
pub mod deform;
pub mod exact;
pub mod flatten_reference;
pub mod gridded;
pub mod interpolation_residual;
pub mod local_route;
pub mod metrics;
pub mod nd_prefilter;
pub mod peak_memory;
pub mod qi;
pub mod rng;
pub mod sspline;
pub mod study_error;
pub mod timing;
pub mod update_cost;
