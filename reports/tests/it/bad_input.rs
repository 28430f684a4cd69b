//! The bad-input sweep: every subcommand fed malformed, truncated, non-finite,
//! empty, one-element, huge and duplicate inputs and unknown options. Each
//! must fail with a clear `error: …` message and a non-zero exit, never a
//! panic, and must leave no output file behind.

use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::process::Command;

struct Case {
    /// Arguments; `{in}` is replaced by the input file, `{out}` by a fresh
    /// output path, which must be as `setup` left it afterwards (absent
    /// without a setup).
    args: Vec<&'static str>,
    /// Contents of the input file (if `{in}` is used).
    input: String,
    /// Prepares the output path before the run.
    setup: Option<fn(&Path)>,
}

fn case(args: &[&'static str], input: impl Into<String>) -> Case {
    Case {
        args: args.to_vec(),
        input: input.into(),
        setup: None,
    }
}

/// [`case`] of a command line whose words are split at spaces.
fn line(command: &'static str, input: impl Into<String>) -> Case {
    case(&command.split(' ').collect::<Vec<_>>(), input)
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
        "flatten",
        "deform",
        "prefilter",
        "interpolate",
    ] {
        v.push(case(&[sub, "--no-such-option"], ""));
    }
    flatten_cases(&mut v);
    deform_cases(&mut v);
    engine_cases(&mut v);
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
    v.push(line(
        "report --quick --out {in}/sub",
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
        v.push(line(
            "compare --baseline {good} --current {in} --out {out}",
            bad,
        ));
        v.push(line(
            "compare --baseline {in} --current {good} --out {out}",
            bad,
        ));
    }
    v.push(line(
        "compare --baseline /nonexistent/base.json --current {in} --out {out}",
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
        v.push(line("qi --input {in} --json", bad));
    }
    v.push(line(
        "qi --input {in} --max-iter 0",
        r#"{"points": [[0,0,0],[1,0,0],[2,1,0]]}"#,
    ));
    v.push(line(
        "qi --input {in} --prec 10",
        r#"{"points": [[0,0,0],[1,0,0],[2,1,0]]}"#,
    ));
    v.push(line(
        "bezier-eval --input /nonexistent.json --method power",
        "",
    ));
    v.push(line(
        "bezier-eval --input {in} --method horner",
        r#"{"coeffs":[1],"t":[0]}"#,
    ));
    v
}

/// Malformed or truncated JSON and the wrong top-level shapes, for any
/// command reading an object.
fn malformed(valid: &str) -> Vec<String> {
    vec![
        String::new(),
        " \n".into(),
        "{".into(),
        valid[..valid.len() / 2].into(),
        valid[..valid.len() - 1].into(),
        format!("{valid},"),
        "[]".into(),
        "null".into(),
        "\"points\"".into(),
        "{\"points\": [[0, 0], [1, 1]]".into(),
        "\u{feff}{}".into(),
        "{\"a\": NaN}".into(),
    ]
}

/// A valid `flatten` input: the parabola (2t, 4t(1 − t)).
const FLATTEN_VALID: &str = r#"{"points": [[0, 0], [1, 2], [2, 0]]}"#;

fn flatten_cases(v: &mut Vec<Case>) {
    let valid = FLATTEN_VALID;
    let zigzag: Vec<String> = (0..201).map(|k| format!("[{k},{}]", k % 2)).collect();
    let mut inputs = malformed(valid);
    inputs.extend(
        [
            // Non-finite: JSON has no NaN; overflow, huge exponents, strings.
            r#"{"points": [[0, 0], [1e999, 2], [2, 0]]}"#,
            r#"{"points": [[0, 0], [1, -1e400], [2, 0]]}"#,
            r#"{"points": [[0, 0], [1, 1e1000000], [2, 0]]}"#,
            r#"{"points": [[0, 0], [1, "NaN"], [2, 0]]}"#,
            r#"{"points": [[0, 0], ["inf", 1], [2, 0]]}"#,
            r#"{"points": [[0, 0], [1, null], [2, 0]]}"#,
            r#"{"points": [[0, 0], [true, 1], [2, 0]]}"#,
            // Empty, wrong shapes and dimensions.
            r#"{"points": []}"#,
            r#"{"points": [[]]}"#,
            r#"{"points": [[1]]}"#,
            r#"{"points": [[1, 2, 3, 4]]}"#,
            r#"{"points": [[0, 0], [1, 1, 1]]}"#,
            r#"{"points": [0, 1]}"#,
            r#"{"points": {"x": [0, 1]}}"#,
            r#"{"points": 3}"#,
            r#"{"pts": [[0, 0], [1, 1]]}"#,
            r#"{"points": [[0, 0], [1, 1]], "tol": 0.1}"#,
        ]
        .map(String::from),
    );
    // Huge: degree above the limit.
    inputs.push(format!(r#"{{"points": [{},[0,0]]}}"#, zigzag.join(",")));
    for input in inputs {
        v.push(line("flatten --input {in} --tol 1e-3", input));
    }
    // Bad tolerances, one of them a request of absurd work: a degree-200
    // zigzag to 10⁻⁴ would need ~10¹¹ de Casteljau steps.
    for tol in [
        "--tol=0",
        "--tol=-1",
        "--tol=-0",
        "--tol=NaN",
        "--tol=inf",
        "--tol=1e999",
        "--tol=1e-300",
        "--tol=x",
        "--tol=",
    ] {
        v.push(case(&["flatten", "--input", "{in}", tol], valid));
    }
    v.push(line(
        "flatten --input {in} --tol 1e-4",
        format!(r#"{{"points": [{}]}}"#, zigzag.join(",")),
    ));
    v.push(case(&["flatten", "--input", "{in}"], valid));
    v.push(case(&["flatten", "--tol", "1e-3"], ""));
    v.push(line("flatten --input /nonexistent/c.json --tol 1e-3", ""));
    // The input is a folder (`{out}` after the setup creates it).
    v.push(Case {
        setup: Some(|out| std::fs::create_dir_all(out).unwrap()),
        ..line("flatten --input {out} --tol 1e-3", "")
    });
}

/// A valid `deform` input: one bilinear patch lifted by 1.
/// Samples and points committed by the scipy fixtures (1-D, 2-D).
const X1: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../verify/fixtures/scipy/x1.npy"
);
const X2: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../verify/fixtures/scipy/x2.npy"
);
const P2: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../verify/fixtures/scipy/p2_mirror.npy"
);

/// `prefilter`, `interpolate`, `width --emit`: malformed arrays and points,
/// bad options; the output goes into the folder `{out}` (created empty by
/// the setup), which must stay empty.
fn engine_cases(v: &mut Vec<Case>) {
    let with = |args: &[&'static str], input: &str| Case {
        setup: Some(|out: &Path| std::fs::create_dir_all(out).unwrap()),
        ..case(args, input)
    };
    let malformed = [
        "",
        "[",
        "[]",
        "[[]]",
        "{}",
        "[1, \"x\"]",
        "[[1, 2], [3]]",
        "[1e999]",
        "[true]",
        "[[[1]]]",
    ];
    for bad in malformed {
        let args = [
            "prefilter",
            "--input",
            "{in}",
            "--degree",
            "3",
            "--output",
            "{out}/c.npy",
        ];
        v.push(with(&args, bad));
    }
    // `interpolate` of these samples at malformed points, or at points of
    // the wrong width for them.
    let wrong_width = [(X2, "[[0.5, 1.5, 2.5]]"), (X1, "[[0.5, 1.5], [2, 3]]")];
    for (samples, points) in malformed.map(|p| (X2, p)).into_iter().chain(wrong_width) {
        let args = [
            "interpolate",
            "--input",
            samples,
            "--degree",
            "3",
            "--at",
            "{in}",
            "--output",
            "{out}/v.npy",
        ];
        v.push(with(&args, points));
    }
    let good = "[1, 2, 0.5, 4, 3]";
    // `prefilter --input {in} … --output {out}/c.npy` with these options.
    let prefilter: &[&[&'static str]] = &[
        &["--degree", "0"],
        &["--degree", "200"],
        &["--order", "1"],
        &["--degree", "3", "--order", "4"],
        &[],
        &["--degree", "3", "--mode", "wrapped"],
        // scipy's `wrap` is not grid-wrap: refused, not aliased.
        &["--degree", "3", "--mode", "wrap"],
        &["--degree", "3", "--tol", "0"],
        &["--degree", "3", "--tol", "1"],
        &["--degree", "3", "--tol", "nan"],
        &["--degree", "3", "--prec", "15"],
        &["--degree", "3", "--axis", "1"],
        &["--degree", "3", "--max-error", "-1"],
        &["--degree", "3", "--cval", "nan"],
        &["--degree", "99"],
    ];
    for opts in prefilter {
        let args = [
            &["prefilter", "--input", "{in}"][..],
            opts,
            &["--output", "{out}/c.npy"],
        ];
        v.push(with(&args.concat(), good));
    }
    for args in [
        "prefilter --input {in} --degree 3 --output {out}/c.txt",
        "prefilter --input {in} --degree 3 --output /nonexistent/dir/c.npy",
        "prefilter --input /nonexistent/x.npy --degree 3 --output {out}/c.npy",
        "prefilter --input {out} --degree 3 --output {out}/c.npy",
        "interpolate --input {in} --degree 3 --output {out}/v.npy",
        "width --tol 1e-6 --emit fortran",
        "width --tol 1e-6 --emit npy",
        "width --tol 1e-6 --emit c --name 1abc",
        "width --tol 1e-6 --emit c --name a-b",
        "width --tol 1e-6 --emit c --dtype f16",
        "width --tol 1e-6 --emit c --json",
        "width --tol 1e-6 --output {out}/t.h",
        "width --tol 1e-6 --emit c --output /nonexistent/dir/t.h",
    ] {
        let args: Vec<&'static str> = args.split(' ').collect();
        v.push(with(&args, good));
    }
    // `interpolate --input X2 --at P2 … --output {out}/v.npy` with these options.
    for opts in [&["--degree", "3", "--tol", "2"][..], &["--degree", "120"]] {
        let args = [
            &["interpolate", "--input", X2, "--at", P2][..],
            opts,
            &["--output", "{out}/v.npy"],
        ];
        v.push(with(&args.concat(), good));
    }
}

fn tiny_deform() -> Value {
    let net: Vec<[f64; 3]> = (0..4)
        .map(|k| [(k / 2) as f64, (k % 2) as f64, 0.0])
        .collect();
    json!({
        "degree": 1, "nu": 1, "nv": 1,
        "patches": [net],
        "samples": {"family": "equispaced"},
        "flow": [[[0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1]]],
        "solver": "kronecker-marco-martinez",
        "correct": false,
    })
}

/// `tiny_deform()` with `pointer` set to `value` (raw JSON text, so that it
/// can hold what serde_json will not write: 1e999, truncated numbers).
fn deform_with(pointer: &str, value: &str) -> String {
    let mut doc = tiny_deform();
    *doc.pointer_mut(pointer).unwrap() = json!("@@");
    doc.to_string().replace("\"@@\"", value)
}

fn deform_cases(v: &mut Vec<Case>) {
    let valid = tiny_deform().to_string();
    let mut inputs = malformed(&valid);
    for (pointer, value) in [
        // Non-finite numbers and strings in place of numbers.
        ("/patches/0/1/0", "1e999"),
        ("/patches/0/1/0", "-1e1000000"),
        ("/patches/0/1/0", "\"NaN\""),
        ("/flow/0/2/2", "1e400"),
        ("/flow/0/2/2", "null"),
        ("/samples", r#"{"u": [0, 1e999], "v": [0, 1]}"#),
        // Degree and grid sizes: zero, negative, fractional, beyond usize, huge.
        ("/degree", "0"),
        ("/degree", "31"),
        ("/degree", "-1"),
        ("/degree", "1.5"),
        ("/degree", "1e30"),
        ("/degree", "100000000000000000000"),
        ("/nu", "0"),
        ("/nv", "2"),
        ("/nu", "1000000"),
        ("/nv", "18446744073709551615"),
        // Empty and one-element lists, wrong point sizes.
        ("/patches", "[]"),
        ("/patches/0", "[]"),
        ("/patches/0", "[[0, 0, 0]]"),
        ("/patches/0/2", "[1, 0]"),
        ("/patches/0/2", "[1, 0, 0, 0]"),
        ("/flow", "[]"),
        ("/flow/0", "[[0, 0, 1]]"),
        ("/samples", r#"{"u": [], "v": []}"#),
        ("/samples", r#"{"u": [0.5], "v": [0.5]}"#),
        // Duplicate, decreasing and out-of-range sample parameters.
        ("/samples", r#"{"u": [0.5, 0.5], "v": [0, 1]}"#),
        ("/samples", r#"{"u": [1, 0], "v": [0, 1]}"#),
        ("/samples", r#"{"u": [0, 1.5], "v": [0, 1]}"#),
        ("/samples", r#"{"u": [0, 1], "v": [0, 0.5, 1]}"#),
        ("/samples", r#"{"u": [0, 1]}"#),
        (
            "/samples",
            r#"{"family": "equispaced", "u": [0, 1], "v": [0, 1]}"#,
        ),
        ("/samples", r#"{"family": "lobatto"}"#),
        ("/samples", r#"{}"#),
        ("/samples", r#""equispaced""#),
        // Options: unknown solver, wrong type, correction below degree 3.
        ("/solver", r#""cholesky""#),
        ("/solver", "3"),
        ("/correct", r#""yes""#),
        ("/correct", "true"),
        ("/flow/0/1", r#"{"x": 0}"#),
    ] {
        inputs.push(deform_with(pointer, value));
    }
    let mut extra = tiny_deform();
    extra["scale"] = json!(2);
    inputs.push(extra.to_string());
    for input in inputs {
        v.push(line("deform --input {in} --out {out}", input));
    }
    for args in [
        &["deform", "--out", "{out}"][..],
        &["deform", "--input", "{in}"],
        &["deform", "--input", "{in}", "--example", "--out", "{out}"],
        &["deform", "--input", "/nonexistent/d.json", "--out", "{out}"],
        // Unwritable outputs: below a file, in /proc.
        &["deform", "--input", "{in}", "--out", "{in}/sub"],
        &["deform", "--example", "--out", "{in}/sub"],
        &[
            "deform",
            "--input",
            "{in}",
            "--out",
            "/proc/splinelab-bad-input",
        ],
    ] {
        v.push(case(args, valid.clone()));
    }
    // The output folder exists but a target name is taken by a folder: the
    // other file must not be written either.
    for blocker in ["deformed.json", "deformed.svg"] {
        let setup: fn(&Path) = match blocker {
            "deformed.json" => |out| std::fs::create_dir_all(out.join("deformed.json")).unwrap(),
            _ => |out| std::fs::create_dir_all(out.join("deformed.svg")).unwrap(),
        };
        v.push(Case {
            setup: Some(setup),
            ..line("deform --input {in} --out {out}", valid.clone())
        });
    }
}

/// Every path below `p` (itself included), sorted; empty if absent.
fn listing(p: &Path) -> Vec<PathBuf> {
    let mut all = Vec::new();
    if p.exists() {
        all.push(p.to_path_buf());
    }
    if let Ok(entries) = std::fs::read_dir(p) {
        for e in entries {
            all.extend(listing(&e.unwrap().path()));
        }
    }
    all.sort();
    all
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
    if let Some(setup) = c.setup {
        setup(&out);
    }
    let before = listing(&out);
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
    } else if listing(&out) != before {
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

/// The inputs the flatten and deform cases break are themselves accepted, so
/// each case fails for its own defect.
#[test]
fn the_valid_inputs_behind_the_cases_succeed() {
    let dir = std::env::temp_dir().join(format!("splinelab-bad-input-ok-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let (flat, def, out) = (dir.join("f.json"), dir.join("d.json"), dir.join("out"));
    std::fs::write(&flat, FLATTEN_VALID).unwrap();
    std::fs::write(&def, tiny_deform().to_string()).unwrap();
    let run = |args: &[&std::ffi::OsStr]| {
        Command::new(env!("CARGO_BIN_EXE_splinelab"))
            .args(args)
            .output()
            .unwrap()
    };
    let f = run(&[
        "flatten".as_ref(),
        "--input".as_ref(),
        flat.as_os_str(),
        "--tol=1e-3".as_ref(),
    ]);
    assert!(f.status.success(), "{}", String::from_utf8_lossy(&f.stderr));
    let d = run(&[
        "deform".as_ref(),
        "--input".as_ref(),
        def.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert!(d.status.success(), "{}", String::from_utf8_lossy(&d.stderr));
    let names: Vec<_> = listing(&out)
        .iter()
        .map(|p| p.file_name().unwrap().to_owned())
        .collect();
    assert_eq!(names, ["out", "deformed.json", "deformed.svg"]);
    let _ = std::fs::remove_dir_all(&dir);
}
