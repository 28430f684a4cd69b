//! Helpers shared by the command-line tests: run the built `splinelab`.

use serde_json::Value;
use std::path::{Path, PathBuf};
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

/// Runs `splinelab args`, asserts success and returns stdout.
pub fn stdout_ok(args: &[&str]) -> String {
    let out = splinelab(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// A fresh, empty folder for the files of one test (`topic`: the test
/// file, `tag`: the test), unique to this process.
pub fn tmpdir(topic: &str, tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("sl_{topic}_{tag}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `interpolate` of the `.npy` samples `input` at the points `at` by the
/// cubic in `mode`, written to `out`.
pub fn cubic_at<'a>(input: &'a Path, at: &'a Path, mode: &'a str, out: &'a Path) -> Vec<&'a str> {
    let path = |p: &'a Path| p.to_str().unwrap();
    vec![
        "interpolate",
        "--input",
        path(input),
        "--at",
        path(at),
        "--degree",
        "3",
        "--mode",
        mode,
        "--output",
        path(out),
    ]
}
