//! The command line's integration tests, one module per topic, in ONE test
//! binary (each further `tests/*.rs` would be its own binary linking GMP,
//! MPFR and the whole workspace; see verify/tests/it/main.rs).

mod common;

mod bad_input;
mod cli_bezier_eval;
mod cli_check;
mod cli_cond;
mod cli_docs;
mod cli_engine;
mod cli_flatten;
mod cli_local;
mod cli_nan_policy;
mod compare;
mod fault_sweep;
mod full_stdout;
mod fuzz_json_input;
mod layering;
mod messages;
mod npy_sweep;
