//! verify's integration tests, one module per topic, in ONE test binary:
//! each further `tests/*.rs` would be its own binary linking GMP, MPFR and
//! the whole workspace (56 such binaries took most of the 23 min test
//! command of issue 38). `engine_alloc` stays a binary of its own: it
//! counts allocations through a global allocator, which would see the other
//! tests' threads. proptest keeps its regression seeds in
//! `tests/proptest-regressions/<topic>.txt` (its default lookup from a
//! module beside this `main.rs`).

mod common;

mod arclength;
mod bad_constructors;
mod bezier_eval_bounds;
mod bezier_eval_subdivision;
mod bv_deform;
mod bv_solvers;
mod check;
mod check_cond;
mod check_interp;
mod check_stable_bound;
mod conditioning;
mod curves_bspline;
mod curves_catmull_rom;
mod curves_flatten;
mod curves_flatten_any;
mod curves_hermite;
mod curves_rational;
mod determinism;
mod engine_batch;
mod engine_float32;
mod engine_lanes;
mod engine_properties;
mod engine_proptest;
mod engine_scipy;
mod gridded;
mod knot_insertion;
mod module_cycles;
mod nan_policy;
mod nd_prefilter_mpfr;
mod param_curve;
mod prefilter_every_order;
mod prefilter_rounding;
mod qi_interpolation;
mod qi_properties;
mod scalar;
mod sspline_coefficients;
mod sspline_curve;
mod sspline_prefilter;
mod sspline_truncation;
mod sspline_width_closed_forms;
