//! Helpers shared by the command-line tests: run the built `splinelab`.

use serde_json::Value;
use std::process::{Command, Output};

/// Runs the `splinelab` binary of this build with `args`.
pub fn splinelab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_splinelab"))
        .args(args)
        .output()
        .unwrap()
}

/// Runs `splinelab args`, asserts success and parses stdout as JSON.
pub fn json_ok(args: &[&str]) -> Value {
    let out = splinelab(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}
