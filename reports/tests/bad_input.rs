//! The bad-input sweep: every subcommand fed malformed, truncated, non-finite,
//! empty, one-element, huge and duplicate inputs and unknown options. Each
//! must fail with a clear `error: …` message and a non-zero exit, never a
//! panic, and must leave no output file behind.

use std::path::{Path, PathBuf};
use std::process::Command;

struct Case {
    /// Arguments; `{in}` is replaced by the input file, `{out}` by a fresh
    /// output path that must not exist afterwards.
    args: Vec<&'static str>,
    /// Contents of the input file (if `{in}` is used).
    input: String,
}

fn case(args: &[&'static str], input: impl Into<String>) -> Case {
    Case {
        args: args.to_vec(),
        input: input.into(),
    }
}

fn huge_array(n: usize) -> String {
    format!("[{}]", vec!["0.5"; n].join(","))
}

fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    // Unknown subcommand and options, everywhere.
    v.push(case(&["frobnicate"], ""));
    for sub in [
        "cond",
        "report",
        "compare",
        "bezier-eval",
        "coeffs",
        "width",
        "qi",
    ] {
        v.push(case(&[sub, "--no-such-option"], ""));
    }
    // cond
    for (deg, nodes, prec) in [
        ("0", "equispaced", "f64"),
        ("501", "equispaced", "f64"),
        ("nan", "equispaced", "f64"),
        ("1e3", "equispaced", "f64"),
        ("5", "", "f64"),
        ("5", "Equispaced", "f64"),
        ("5", "equispaced", "15"),
        ("5", "equispaced", "1000001"),
        ("5", "equispaced", "inf"),
        ("5", "equispaced", "-64"),
    ] {
        v.push(case(
            &["cond", "--degree", deg, "--nodes", nodes, "--prec", prec],
            "",
        ));
    }
    // report: the output folder cannot be created (its parent is a file).
    v.push(case(
        &["report", "--quick", "--out", "{in}/sub"],
        "a file, not a folder",
    ));
    v.push(case(&["report", "--quick"], ""));
    // compare: malformed, truncated, wrong shapes, non-finite numbers.
    let good = r#"{"figures":[{"name":"a.b","value":1.0,"kind":"accuracy","unit":"u","better":"lower","tolerance":0.1}]}"#;
    for bad in [
        "",
        "{",
        &good[..good.len() / 2],
        "[]",
        "null",
        r#"{"figures": 3}"#,
        r#"{"figures": [{"name": "a.b"}]}"#,
        r#"{"figures": [{"name":"a.b","value":"1","kind":"accuracy","unit":"u","better":"lower","tolerance":0.1}]}"#,
        r#"{"figures": [{"name":"a.b","value":1e999,"kind":"accuracy","unit":"u","better":"lower","tolerance":0.1}]}"#,
        r#"{"figures": [{"name":"a.b","value":1,"kind":"speed","unit":"u","better":"lower","tolerance":0.1}]}"#,
        r#"{"figures": [{"name":"a.b","value":1,"kind":"accuracy","unit":"u","better":"lower","tolerance":-1}]}"#,
        r#"{"figures": []}"#,
    ] {
        v.push(case(
            &[
                "compare",
                "--baseline",
                "{good}",
                "--current",
                "{in}",
                "--out",
                "{out}",
            ],
            bad,
        ));
        v.push(case(
            &[
                "compare",
                "--baseline",
                "{in}",
                "--current",
                "{good}",
                "--out",
                "{out}",
            ],
            bad,
        ));
    }
    v.push(case(
        &[
            "compare",
            "--baseline",
            "/nonexistent/base.json",
            "--current",
            "{in}",
            "--out",
            "{out}",
        ],
        good,
    ));
    // bezier-eval: every input defect, for every method.
    for method in ["decasteljau", "power", "bernstein", "vs", "compensated"] {
        for bad in [
            String::new(),
            "{".into(),
            r#"{"coeffs": [1, 2], "t": [0.5"#.into(),
            r#"{"coeffs": [], "t": [0.5]}"#.into(),
            r#"{"coeffs": [1, "NaN"], "t": [0.5]}"#.into(),
            r#"{"coeffs": [1, 1e999], "t": [0.5]}"#.into(),
            r#"{"coeffs": [1, 2], "t": [1e999]}"#.into(),
            r#"{"coeffs": [1, 2], "t": ["0.5"]}"#.into(),
            r#"{"coeffs": [1, 2]}"#.into(),
            r#"{"coeffs": [1, 2], "t": [0.5], "extra": 1}"#.into(),
            r#"{"coeffs": 3, "t": [0.5]}"#.into(),
            format!(r#"{{"coeffs": {}, "t": [0.5]}}"#, huge_array(20_000)),
        ] {
            v.push(case(
                &[
                    "bezier-eval",
                    "--input",
                    "{in}",
                    "--method",
                    method,
                    "--json",
                ],
                bad,
            ));
        }
    }
    // coeffs and width
    for args in [
        &["coeffs", "--order", "1"][..],
        &["coeffs", "--order", "201"],
        &["coeffs", "--order", "4", "--count", "0"],
        &["coeffs", "--order", "4", "--count", "100001"],
        &["coeffs", "--order", "4", "--tension", "-1"],
        &["coeffs", "--order", "4", "--tension", "NaN"],
        &["coeffs", "--order", "4", "--tension", "inf"],
        &["coeffs", "--order", "4", "--prec", "8"],
        &["coeffs", "--order", "x"],
        &["width", "--order", "4", "--tol", "0"],
        &["width", "--order", "4", "--tol", "1"],
        &["width", "--order", "4", "--tol", "-1e-3"],
        &["width", "--order", "4", "--tol", "NaN"],
        &["width", "--order", "4", "--tol", "inf"],
        &["width", "--order", "1", "--tol", "1e-3"],
        &[
            "width",
            "--order",
            "4",
            "--tol",
            "1e-3",
            "--criterion",
            "best",
        ],
        &["width", "--tension", "-2", "--tol", "1e-3"],
        &["width", "--order", "4"],
    ] {
        v.push(case(args, ""));
    }
    // qi: every input defect.
    let many: Vec<String> = (0..201).map(|k| format!("[{k},{},0]", k * k)).collect();
    for bad in [
        String::new(),
        "{".into(),
        r#"{"points": [[0,0,0],[1,0,0],[2,1,0]"#.into(),
        r#"{"points": []}"#.into(),
        r#"{"points": [[0,0,0]]}"#.into(),
        r#"{"points": [[0,0,0],[1,0,0]]}"#.into(),
        r#"{"points": [[0,0,0],[0,0,0],[1,1,0]]}"#.into(),
        r#"{"points": [[0,0,0],[1,0,0],[1,0,0],[2,1,0]]}"#.into(),
        r#"{"points": [[0,0,0],[1,"NaN",0],[2,1,0]]}"#.into(),
        r#"{"points": [[0,0,0],[1,0,0],[2,1e999,0]]}"#.into(),
        r#"{"points": [[0,0,0],[1,0,"inf"],[2,1,0]]}"#.into(),
        r#"{"points": [[0,0],[1,0],[2,1]]}"#.into(),
        r#"{"points": [[0,0,0],[1,0,0],[2,1,0]], "start_tangent": [0,0,0]}"#.into(),
        r#"{"points": [[0,0,0],[1,0,0],[2,1,0]], "end_tangent": [1,"x",0]}"#.into(),
        r#"{"points": [[0,0,0],[1,0,0],[2,1,0]], "start_tangent": [1e1000000,0,0]}"#.into(),
        r#"{"points": 5}"#.into(),
        format!(r#"{{"points": [{}]}}"#, many.join(",")),
    ] {
        v.push(case(&["qi", "--input", "{in}", "--json"], bad));
    }
    v.push(case(
        &["qi", "--input", "{in}", "--max-iter", "0"],
        r#"{"points": [[0,0,0],[1,0,0],[2,1,0]]}"#,
    ));
    v.push(case(
        &["qi", "--input", "{in}", "--prec", "10"],
        r#"{"points": [[0,0,0],[1,0,0],[2,1,0]]}"#,
    ));
    v.push(case(
        &[
            "bezier-eval",
            "--input",
            "/nonexistent.json",
            "--method",
            "power",
        ],
        "",
    ));
    v.push(case(
        &["bezier-eval", "--input", "{in}", "--method", "horner"],
        r#"{"coeffs":[1],"t":[0]}"#,
    ));
    v.push(case(
        &[
            "bezier-eval",
            "--input",
            "{in}",
            "--method",
            "compensated",
            "--prec",
            "256",
        ],
        r#"{"coeffs":[1],"t":[0]}"#,
    ));
    v
}

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("splinelab-bad-input-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run_case(dir: &Path, k: usize, c: &Case) -> Result<(), String> {
    let input = dir.join(format!("in{k}.json"));
    std::fs::write(&input, &c.input).unwrap();
    let good = dir.join("good.json");
    std::fs::write(
        &good,
        r#"{"figures":[{"name":"a.b","value":1.0,"kind":"accuracy","unit":"u","better":"lower","tolerance":0.1}]}"#,
    )
    .unwrap();
    let out = dir.join(format!("out{k}"));
    let args: Vec<String> = c
        .args
        .iter()
        .map(|a| {
            a.replace("{in}", input.to_str().unwrap())
                .replace("{out}", out.to_str().unwrap())
                .replace("{good}", good.to_str().unwrap())
        })
        .collect();
    let res = Command::new(env!("CARGO_BIN_EXE_splinelab"))
        .args(&args)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&res.stderr);
    let why = if res.status.success() {
        "exited 0"
    } else if res.status.code().is_none() {
        "killed by a signal"
    } else if err.contains("panicked") {
        "panicked"
    } else if !err.to_lowercase().contains("error") {
        "no error message"
    } else if out.exists() {
        "left an output behind"
    } else {
        return Ok(());
    };
    Err(format!(
        "{args:?} with input {:.80?}: {why}\n{err}",
        c.input
    ))
}

#[test]
fn every_bad_input_is_a_clear_error_without_panic_or_output() {
    let dir = scratch();
    let cases = cases();
    let failures: Vec<String> = cases
        .iter()
        .enumerate()
        .filter_map(|(k, c)| run_case(&dir, k, c).err())
        .collect();
    println!("bad-input cases tried: {}", cases.len());
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}
