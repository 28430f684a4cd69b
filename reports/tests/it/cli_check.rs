//! `splinelab check` end to end on the committed scipy fixtures: the JSON
//! contract, exit codes 0/1/2, `--out` read back by `compare`, and bad input
//! refused with exit 2 and nothing written.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn splinelab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_splinelab"))
        .args(args)
        .output()
        .unwrap()
}

fn fixture(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../verify/fixtures/scipy")
        .join(name)
        .display()
        .to_string()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("cli_check_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `splinelab check prefilter --samples samples --coeffs coeffs extra…`.
fn check_prefilter(samples: &str, coeffs: &str, extra: &[&str]) -> Output {
    let mut args = vec![
        "check",
        "prefilter",
        "--samples",
        samples,
        "--coeffs",
        coeffs,
    ];
    args.extend_from_slice(extra);
    splinelab(&args)
}

/// [`check_prefilter`] on the fixture samples.
fn prefilter(coeffs: &str, extra: &[&str]) -> Output {
    check_prefilter(&fixture("prefilter/samples.npy"), coeffs, extra)
}

#[test]
fn json_contract_and_exit_codes() {
    let c = fixture("prefilter/d3_reflect.npy");
    let out = prefilter(&c, &["--degree", "3", "--mode", "reflect", "--json"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "kind",
        "n",
        "reference_bits",
        "worst",
        "regions",
        "digits_min",
        "failed",
        "verdict",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(
        (v["kind"].as_str(), v["n"].as_u64()),
        (Some("prefilter"), Some(200))
    );
    assert_eq!(v["regions"]["boundary"]["count"].as_u64(), Some(56));
    for key in ["index", "ulps", "rel", "abs", "region"] {
        assert!(v["worst"].get(key).is_some(), "missing worst.{key}");
    }
    // The same data with --order 4 and a threshold scipy's worst element misses.
    let out = prefilter(
        &c,
        &[
            "--order",
            "4",
            "--mode",
            "reflect",
            "--max-ulps",
            "1",
            "--json",
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["verdict"].as_str(), Some("fail"));
    assert!(v["failed"].as_u64().unwrap() >= 1);
    // Knot insertion: scipy's right end fails, an interior insertion passes.
    let ki = fixture("knot_insertion.json");
    let run = |case: &str| {
        splinelab(&[
            "check",
            "knot-insertion",
            "--input",
            &ki,
            "--case",
            case,
            "--json",
        ])
    };
    let out = run("right_end_3");
    assert_eq!(out.status.code(), Some(1));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["max_deviation"].as_f64().unwrap() > 0.1 && v.get("max_deviation_rel").is_some());
    assert_eq!(run("interior_1.5").status.code(), Some(0));
}

#[test]
fn out_dir_is_written_and_compare_accepts_it() {
    let d = scratch("out");
    let out_dir = d.join("report");
    let c = fixture("prefilter/d2_mirror.npy");
    let o = out_dir.display().to_string();
    let out = prefilter(&c, &["--degree", "2", "--out", &o]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in ["index.html", "summary.json", "check_error_vs_index.svg"] {
        assert!(out_dir.join(f).is_file(), "{f} missing");
    }
    let summary = out_dir.join("summary.json").display().to_string();
    let cmp = d.join("cmp").display().to_string();
    let out = splinelab(&[
        "compare",
        "--baseline",
        &summary,
        "--current",
        &summary,
        "--out",
        &cmp,
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // Rewriting replaces the directory whole (no temporary left beside it).
    assert_eq!(
        prefilter(&c, &["--degree", "2", "--out", &o]).status.code(),
        Some(0)
    );
    let left: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 2, "{left:?}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Writes `bytes` as a file in `dir`, returning its path.
fn put(dir: &Path, name: &str, bytes: &[u8]) -> String {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p.display().to_string()
}

#[test]
fn bad_input_exits_2_and_writes_nothing() {
    let d = scratch("bad");
    let good = std::fs::read(fixture("prefilter/d3_mirror.npy")).unwrap();
    let truncated = put(&d, "trunc.npy", &good[..good.len() - 100]);
    // An int64 .npy: the same header with '<i8'.
    let mut int = good.clone();
    let at = int.windows(3).position(|w| w == b"<f8").unwrap();
    int[at + 1] = b'i';
    let wrong_dtype = put(&d, "int.npy", &int);
    let short = put(&d, "short.json", b"[1, 2, 3]");
    let two_d = put(&d, "twod.txt", b"1 2\n3 4\n");
    let c = fixture("prefilter/d3_mirror.npy");
    let out_dir = d.join("out");
    let o = out_dir.display().to_string();
    let cases: &[(&[&str], &str)] = &[
        (&["--coeffs", &short, "--degree", "3"], "expected 200"),
        (&["--coeffs", &truncated, "--degree", "3"], "trunc.npy"),
        (&["--coeffs", &wrong_dtype, "--degree", "3"], "dtype"),
        (&["--coeffs", &two_d, "--degree", "3"], "1-D"),
        (&["--coeffs", &c, "--degree", "0"], "degree"),
        (&["--coeffs", &c, "--degree", "16"], "degree"),
        (
            &["--coeffs", &c, "--degree", "3", "--order", "4"],
            "--order",
        ),
        (&["--coeffs", &c, "--mode", "nearest-ish"], "--mode"),
        (&["--coeffs", &c, "--max-ulps", "-1"], "--max-ulps"),
    ];
    let samples = fixture("prefilter/samples.npy");
    for (extra, needle) in cases {
        let mut args = vec!["check", "prefilter", "--samples", &samples, "--out", &o];
        args.extend_from_slice(extra);
        let out = splinelab(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(needle), "{extra:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(!out_dir.exists(), "{extra:?} wrote {o}");
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// `splinelab check interp --json` on fixture files, with `extra` options.
fn interp(samples: &str, coords: &str, values: &str, extra: &[&str]) -> Output {
    let files = [samples, coords, values].map(fixture);
    let mut args = vec![
        "check",
        "interp",
        "--samples",
        &files[0],
        "--coords",
        &files[1],
        "--values",
        &files[2],
        "--json",
    ];
    args.extend_from_slice(extra);
    splinelab(&args)
}

#[test]
fn interp_2d_on_scipy_map_coordinates() {
    let run = |coords: &str, extra: &[&str]| {
        interp(
            "interp/samples2.npy",
            coords,
            "interp/v2_d3_mirror.npy",
            extra,
        )
    };
    let c = "interp/coords2.npy";
    let out = run(c, &["--degree", "3", "--max-ulps", "200"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (j["kind"].as_str(), j["n"].as_u64()),
        (Some("interp"), Some(80))
    );
    assert_eq!(j["mode"].as_str(), Some("mirror"));
    let counts: u64 = ["boundary", "interior"]
        .iter()
        .map(|r| j["regions"][r]["count"].as_u64().unwrap())
        .sum();
    assert_eq!(counts, 80);
    // A tight threshold fails (exit 1); the 1-D coordinates for 2-D samples are refused (exit 2).
    assert_eq!(run(c, &["--max-ulps", "1"]).status.code(), Some(1));
    let bad = run("interp/coords1.npy", &[]);
    assert_eq!(bad.status.code(), Some(2));
}

#[test]
fn interp_padded_modes_and_cval_follow_map_coordinates() {
    let run = |values: &str, extra: &[&str]| {
        interp("interp/samples1.npy", "interp/coords1.npy", values, extra)
    };
    let json = |out: &Output| -> Value {
        assert_eq!(
            out.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    // Within the bound of check_interp.rs for the padded modes: 256 ulps of max |f|.
    for mode in ["nearest", "grid-constant"] {
        let values = format!("interp/v1_d3_{mode}.npy");
        let j = json(&run(&values, &["--degree", "3", "--mode", mode]));
        assert!(
            j["max_ulps_scaled"].as_f64().unwrap() < 256.0,
            "{mode}: {j}"
        );
        let reference = j["reference"].as_str().unwrap();
        assert!(reference.contains("padded by 12"), "{reference}");
    }
    // scipy's cval = 0.75 passes with --cval 0.75 (also as a negative number's
    // spelling) and fails, exit 1, without it.
    let cval = "interp/v1_d3_grid-constant_cval.npy";
    let base = [
        "--degree",
        "3",
        "--mode",
        "grid-constant",
        "--max-ulps",
        "4096",
    ];
    let with = [&base[..], &["--cval", "0.75"]].concat();
    assert!(
        json(&run(cval, &with))["reference"]
            .as_str()
            .unwrap()
            .contains("cval 0.75")
    );
    assert_eq!(run(cval, &base).status.code(), Some(1));
    let nan = [&base[..], &["--cval", "nan"]].concat();
    assert_eq!(run(cval, &nan).status.code(), Some(2));
}

#[test]
fn a_nan_value_keeps_every_figure_and_is_counted() {
    let d = scratch("nan");
    let w = |name: &str, text: &str| {
        let p = d.join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    };
    // B(t) = 1 + 2t (Bernstein 1, 2, 3 of degree 2): exact values 1, 2, 3.
    let (b, t) = (w("b.txt", "1 2 3"), w("t.txt", "0 0.5 1"));
    let figures = |values: &str, out: &str| -> Vec<(String, f64)> {
        let out = d.join(out);
        let o = out.display().to_string();
        let args = [
            "check",
            "bezier-eval",
            "--coeffs",
            &b,
            "--t",
            &t,
            "--values",
            values,
            "--out",
            &o,
        ];
        splinelab(&args);
        let v: Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        v["figures"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| {
                (
                    f["name"].as_str().unwrap().to_string(),
                    f["value"].as_f64().unwrap(),
                )
            })
            .collect()
    };
    let good = figures(&w("good.txt", "1 2 3"), "good");
    let bad = figures(&w("bad.txt", "1 nan 3.0000000000000004"), "bad");
    let names = |f: &[(String, f64)]| f.iter().map(|x| x.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(&good), names(&bad));
    let get = |f: &[(String, f64)], n: &str| f.iter().find(|x| x.0 == n).unwrap().1;
    assert_eq!(get(&bad, "check.bezier-eval.non_finite"), 1.0);
    assert_eq!(get(&good, "check.bezier-eval.non_finite"), 0.0);
    // The finite maximum: one ulp at 3 (the NaN is counted, not drawn as ∞).
    assert_eq!(get(&bad, "check.bezier-eval.max_ulps"), 1.0);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn short_reflect_line_fails_by_default_and_out_holds_the_per_element_arrays() {
    // scipy 1.17.1's quintic reflect filter of 8 samples (gh-24550): exit 1
    // without --max-ulps, naming index 0 and the digits lost; --out writes
    // reference/error/bound .npy beside the page, read back here.
    let dir = scratch("short_reflect");
    let out_dir = dir.join("out");
    let (s, c) = (
        fixture("stable/s_n8.npy"),
        fixture("stable/d5_reflect_n8.npy"),
    );
    let out = check_prefilter(
        &s,
        &c,
        &[
            "--degree",
            "5",
            "--mode",
            "reflect",
            "--out",
            out_dir.to_str().unwrap(),
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("check prefilter: fail"), "{text}");
    assert!(text.contains("at index 0"), "{text}");
    assert!(
        text.contains("digits lost beyond the conditioning 7.9"),
        "{text}"
    );
    let read = |name: &str| {
        let f = std::fs::File::open(out_dir.join(name)).unwrap();
        <ndarray::Array1<f64> as ndarray_npy::ReadNpyExt>::read_npy(f).unwrap()
    };
    let (r, e, b) = (read("reference.npy"), read("error.npy"), read("bound.npy"));
    assert_eq!((r.len(), e.len(), b.len()), (8, 8, 8));
    // error.npy is |value − reference|: the user's value minus the reference.
    let user = {
        let f = std::fs::File::open(&c).unwrap();
        <ndarray::Array1<f64> as ndarray_npy::ReadNpyExt>::read_npy(f).unwrap()
    };
    // (reference.npy is the reference rounded to f64: one rounding apart.)
    assert!(
        ((user[0] - r[0]).abs() - e[0]).abs() <= f64::EPSILON * r[0].abs(),
        "{} {}",
        e[0],
        user[0] - r[0]
    );
    assert!(e[0] > 8.0 * b[0] && b.iter().all(|x| *x > 0.0));
    assert!(out_dir.join("check_error_vs_bound.svg").is_file());
    // The same check on the whole-sample rule passes, and says on what basis.
    let c = fixture("stable/d5_mirror_n8.npy");
    let out = check_prefilter(&s, &c, &["--degree", "5", "--json"]);
    assert_eq!(out.status.code(), Some(0));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["verdict_basis"], "stable-bound");
    assert_eq!(v["over_bound"], 0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn cond_says_why_it_has_no_stable_bound_verdict() {
    let dir = scratch("cond_basis");
    let (nodes, values) = (dir.join("nodes.json"), dir.join("cond.txt"));
    std::fs::write(&nodes, "[[0, 1], [0, 0.5, 1]]").unwrap();
    std::fs::write(&values, "1 3").unwrap();
    let out = splinelab(&[
        "check",
        "cond",
        "--nodes",
        nodes.to_str().unwrap(),
        "--basis",
        "bernstein",
        "--norm",
        "inf",
        "--values",
        values.to_str().unwrap(),
        "--json",
    ]);
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["verdict_basis"], "finite-only");
    assert!(
        v["no_verdict_reason"]
            .as_str()
            .unwrap()
            .contains("no stable bound")
    );
    let _ = std::fs::remove_dir_all(&dir);
}
