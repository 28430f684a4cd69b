//! `splinelab compare` end to end: exit codes, the regressed figure named in
//! the output and the HTML, and an SVG chart in the page.

use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::process::Command;

fn splinelab() -> Command {
    Command::new(env!("CARGO_BIN_EXE_splinelab"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("splinelab-compare-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn summary() -> Value {
    json!({"figures": [
        {"name": "conditioning.cond2_f64_digits.x", "value": 12.0, "kind": "accuracy",
         "unit": "digits", "better": "higher", "tolerance": 0.5},
        {"name": "bezier.max_rel_error", "value": 1e-15, "kind": "accuracy",
         "unit": "relative error", "better": "lower", "tolerance": 1e-16},
        {"name": "report.conditioning.seconds", "value": 2.0, "kind": "cost",
         "unit": "s", "better": "lower", "tolerance": 4.0, "floor": 0.5}
    ]})
}

fn write(dir: &Path, name: &str, v: &Value) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, serde_json::to_string(v).unwrap()).unwrap();
    p
}

fn run_compare(dir: &Path, current: &Value) -> (i32, String, String) {
    let base = write(dir, "base.json", &summary());
    let cur = write(dir, "cur.json", current);
    let out = splinelab()
        .args(["compare", "--baseline"])
        .arg(&base)
        .arg("--current")
        .arg(&cur)
        .arg("--out")
        .arg(dir.join("out"))
        .output()
        .unwrap();
    let html = std::fs::read_to_string(dir.join("out/index.html")).unwrap_or_default();
    (
        out.status.code().unwrap(),
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr),
        html,
    )
}

#[test]
fn identical_files_pass() {
    let dir = scratch("same");
    let (code, _, html) = run_compare(&dir, &summary());
    assert_eq!(code, 0);
    assert!(html.contains("No figure regressed"));
}

#[test]
fn an_accuracy_regression_fails_and_is_named_in_output_and_html() {
    let dir = scratch("regress");
    let mut cur = summary();
    cur["figures"][1]["value"] = json!(5e-15); // error grew beyond its 1e-16 slack
    let (code, out, html) = run_compare(&dir, &cur);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("REGRESSED bezier.max_rel_error"), "{out}");
    assert!(html.contains("bezier.max_rel_error") && html.contains("REGRESSED"));
    assert!(html.contains("<svg"), "the page has an SVG chart");
}

#[test]
fn timing_drift_inside_the_noise_band_passes() {
    let dir = scratch("drift");
    let mut cur = summary();
    cur["figures"][2]["value"] = json!(6.5); // 3.25× slower: inside the 4× band
    let (code, out, _) = run_compare(&dir, &cur);
    assert_eq!(code, 0, "{out}");
}

#[test]
fn corrupted_or_mismatched_input_exits_2_naming_file_and_field() {
    let dir = scratch("corrupt");
    let base = write(&dir, "base.json", &summary());
    let truncated = dir.join("truncated.json");
    let text = serde_json::to_string(&summary()).unwrap();
    std::fs::write(&truncated, &text[..text.len() / 2]).unwrap();
    let out = splinelab()
        .args(["compare", "--baseline"])
        .arg(&base)
        .arg("--current")
        .arg(&truncated)
        .arg("--out")
        .arg(dir.join("out"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("truncated.json") && err.contains("JSON"),
        "{err}"
    );

    let mut missing = summary();
    missing["figures"].as_array_mut().unwrap().remove(0);
    let (code, out, _) = run_compare(&dir, &missing);
    assert_eq!(code, 2);
    assert!(
        out.contains("cur.json") && out.contains("conditioning.cond2_f64_digits.x"),
        "{out}"
    );

    let (code, out, _) = run_compare(&dir, &json!({"figures": [{"name": "x"}]}));
    assert_eq!(code, 2);
    assert!(out.contains("figures[0]"), "{out}");
}
