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
    assert!(html.contains("No gated figure regressed"));
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

    // No figure in common: nothing would be compared, an error.
    let (code, out, _) = run_compare(
        &dir,
        &json!({"figures": [{"name": "other.x", "value": 1.0, "kind": "accuracy",
                 "unit": "digits", "better": "higher", "tolerance": 0.5}]}),
    );
    assert_eq!(code, 2);
    assert!(
        out.contains("cur.json") && out.contains("no figure in common"),
        "{out}"
    );

    let (code, out, _) = run_compare(&dir, &json!({"figures": [{"name": "x"}]}));
    assert_eq!(code, 2);
    assert!(out.contains("figures[0]"), "{out}");
}

#[test]
fn figures_only_one_file_has_are_listed_and_a_profile_change_is_said() {
    let dir = scratch("profiles");
    let mut cur = summary();
    cur["figures"].as_array_mut().unwrap().remove(0);
    cur["figures"].as_array_mut().unwrap().push(json!(
        {"name": "update_cost.global_over_local.N100000", "value": 50.0, "kind": "cost",
         "unit": "ratio", "better": "higher", "tolerance": 4.0}));
    cur["profile"] = json!("full");
    let (code, out, html) = run_compare(&dir, &cur);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains("profiles differ") && out.contains("not recorded") && out.contains("full"),
        "{out}"
    );
    assert!(
        out.contains("only in the baseline, not compared: conditioning.cond2_f64_digits.x"),
        "{out}"
    );
    assert!(
        out.contains(
            "only in the current run, not compared: update_cost.global_over_local.N100000"
        ),
        "{out}"
    );
    assert!(html.contains("Only in the baseline") && html.contains("profiles differ"));
    assert!(!out.contains("cannot read"), "{out}");
}

#[test]
fn wall_clock_figures_gate_only_with_timings() {
    let dir = scratch("timings");
    let mut cur = summary();
    cur["figures"][2]["value"] = json!(20.0); // 10× slower: beyond the 4× band
    let (code, out, html) = run_compare(&dir, &cur);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains("1 wall-clock timings shown but not gated"),
        "{out}"
    );
    assert!(html.contains("not gated"));
    let base = write(&dir, "base.json", &summary());
    let curp = write(&dir, "cur.json", &cur);
    let out = splinelab()
        .args(["compare", "--timings", "--baseline"])
        .arg(&base)
        .arg("--current")
        .arg(&curp)
        .arg("--out")
        .arg(dir.join("out2"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stdout).contains("REGRESSED report.conditioning.seconds"));
}

#[test]
fn the_regressed_figure_is_named_in_its_chart_and_numbered_globally() {
    let dir = scratch("named");
    let mut cur = summary();
    cur["figures"][1]["value"] = json!(5e-15);
    let (code, _, html) = run_compare(&dir, &cur);
    assert_eq!(code, 1);
    // One global numbering: the second figure is #2 although it is the first of its study.
    assert!(
        html.contains("<td>2</td><td class=\"name\">bezier.max_rel_error"),
        "{html}"
    );
    let svg = std::fs::read_to_string(dir.join("out/compare_bezier.svg")).unwrap();
    assert!(svg.contains("REGRESSED #2 bezier.max_rel_error"), "{svg}");
}

/// `summary()` with a profile and what each figure was measured over: the
/// first two over fixed cases, the timing over the profile's cases.
fn with_profile(profile: &str, digits_over: &str) -> Value {
    let mut s = summary();
    s["profile"] = json!(profile);
    s["figures"][0]["over"] = json!("fixed cases");
    s["figures"][1]["over"] = json!(digits_over);
    s["figures"][2]["over"] = json!(format!("{profile} profile's cases"));
    s
}

fn compare_files(dir: &Path, base: &Value, cur: &Value, extra: &[&str]) -> (i32, String) {
    let b = write(dir, "base.json", base);
    let c = write(dir, "cur.json", cur);
    let out = splinelab()
        .args(["compare", "--baseline"])
        .arg(&b)
        .arg("--current")
        .arg(&c)
        .arg("--out")
        .arg(dir.join("out"))
        .args(extra)
        .output()
        .unwrap();
    (
        out.status.code().unwrap(),
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr),
    )
}

#[test]
fn across_profiles_only_figures_measured_over_the_same_cases_gate() {
    let dir = scratch("across");
    let base = with_profile("quick", "quick profile's cases");
    // The full profile samples more points: this figure drops a digit for
    // that reason alone, and must not gate.
    let mut cur = with_profile("full", "full profile's cases");
    cur["figures"][1]["value"] = json!(1e-14);
    let (code, out) = compare_files(&dir, &base, &cur, &[]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains("baseline: quick, current: full")
            && out.contains(
                "measured over other cases than the baseline's (shown, not gated): \
                 bezier.max_rel_error"
            ),
        "{out}"
    );
    // A figure over fixed cases still gates across profiles.
    cur["figures"][0]["value"] = json!(10.0);
    let (code, out) = compare_files(&dir, &base, &cur, &[]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("REGRESSED conditioning.cond2_f64_digits.x"),
        "{out}"
    );
    // A baseline figure the full run lacks is listed, not a regression.
    let mut cur = with_profile("full", "full profile's cases");
    cur["figures"].as_array_mut().unwrap().remove(0);
    let (code, out) = compare_files(&dir, &base, &cur, &[]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("only in the baseline"), "{out}");
}

#[test]
fn within_one_profile_a_missing_gated_figure_is_a_regression_unless_allowed() {
    let dir = scratch("missing");
    let base = with_profile("quick", "quick profile's cases");
    let mut cur = base.clone();
    cur["figures"].as_array_mut().unwrap().remove(1);
    let (code, out) = compare_files(&dir, &base, &cur, &[]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("MISSING 1 gated figure(s)") && out.contains("bezier.max_rel_error"),
        "{out}"
    );
    let html = std::fs::read_to_string(dir.join("out/index.html")).unwrap();
    assert!(html.contains("missing from the current run"), "{html}");
    let (code, out) = compare_files(&dir, &base, &cur, &["--allow-missing"]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains("only in the baseline, not compared: bezier.max_rel_error"),
        "{out}"
    );
    // A missing wall-clock timing does not gate (it would not gate if present).
    let mut cur = base.clone();
    cur["figures"].as_array_mut().unwrap().remove(2);
    let (code, out) = compare_files(&dir, &base, &cur, &[]);
    assert_eq!(code, 0, "{out}");
}
