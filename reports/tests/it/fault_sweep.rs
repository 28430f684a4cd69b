//! A generated sweep of hostile inputs and faults against the built
//! `splinelab` binary: edge flag values, malformed and huge JSON, FIFOs and
//! devices as inputs, directories where files are expected, non-UTF-8
//! paths, a full disk (`/dev/full`), closed pipes, overflowing deformations,
//! unsafe compare figure names and interrupted runs (SIGINT/SIGTERM).
//!
//! Every case runs in its own process, in parallel, with a timeout. The
//! sweep asserts: no panic (exit 101 or "panicked"), no run past its
//! timeout, no partial output (no temporary left beside an output folder,
//! an output folder either untouched or complete), no silent success where
//! failure is the only right answer (a full disk, an overflow), and error
//! messages that are clear (start with `error:`, name the flag or file,
//! stay short) in at least 99% of the error cases. It prints the counts.

use std::collections::BTreeMap;
use std::ffi::OsString;
use std::os::unix::ffi::OsStringExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_splinelab");
/// Per-case timeout: the issue's bar, 60 s. Nothing here needs 10 s on an
/// idle machine, but `flatten --tol 1e-12` (857k chords, 6 s idle) ran past
/// 30 s with four copies in parallel on a machine loaded 10 deep.
const TIMEOUT: Duration = Duration::from_secs(60);

/// Where stdout goes.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Sink {
    Null,
    Full,
    ClosedPipe,
}

/// What a case must do.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Expect {
    /// Anything but a panic or hang; an error must be clear.
    Any,
    /// Must fail (non-zero exit) with a clear message.
    Fail,
}

#[derive(Clone, Debug)]
struct Case {
    class: &'static str,
    args: Vec<OsString>,
    env: Vec<(&'static str, String)>,
    sink: Sink,
    expect: Expect,
    /// Words one of which a clear error message names (flag, file, topic).
    subject: Vec<String>,
    /// An output folder to check for partial output.
    out: Option<PathBuf>,
    /// Send this signal after this delay.
    signal: Option<(&'static str, Duration)>,
}

fn case(class: &'static str, args: &[&str], subject: &[&str]) -> Case {
    Case {
        class,
        args: args.iter().map(OsString::from).collect(),
        env: vec![],
        sink: Sink::Null,
        expect: Expect::Any,
        subject: subject.iter().map(|s| s.to_string()).collect(),
        out: None,
        signal: None,
    }
}

#[derive(Debug, Default)]
struct Tally {
    cases: usize,
    ok: usize,
    errors: usize,
    panics: Vec<String>,
    timeouts: Vec<String>,
    partial: Vec<String>,
    silent: Vec<String>,
    unclear: Vec<String>,
    by_class: BTreeMap<&'static str, usize>,
}

/// A small deterministic generator (xorshift), so the sweep is reproducible.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[(self.next() % xs.len() as u64) as usize]
    }
}

const EDGE_NUMBERS: &[&str] = &[
    "-1",
    "0",
    "-0",
    "1",
    "2",
    "3",
    "17",
    "+5",
    "1e308",
    "-1e-3",
    "1e-300",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "4294967296",
    "18446744073709551616",
    "",
    " ",
    "abc",
    "1/0",
    "0x10",
    "2049",
    "2048",
    "1.5",
    "1e3",
    "０",
    "--",
];

fn big_digits() -> String {
    "9".repeat(100_000)
}

struct Fixture {
    dir: PathBuf,
}

impl Fixture {
    fn new() -> Self {
        let dir = std::env::temp_dir().join(format!("splinelab_sweep_{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Fixture { dir }
    }
    fn file(&self, name: &str, contents: &[u8]) -> String {
        let p = self.dir.join(name);
        std::fs::write(&p, contents).unwrap();
        p.to_string_lossy().into_owned()
    }
    fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }
}

const QI_DOC: &str = r#"{"points": [[0,0,0],[1,0.5,0.2],[2,1.5,0.1],[3,1.2,0.8]]}"#;
const BEZIER_DOC: &str = r#"{"coeffs": [1, -2, 0.5, 3], "t": [0, 0.25, 0.5, 1.5]}"#;
const FLATTEN_DOC: &str = r#"{"points": [[0,0],[1,2],[3,-1],[4,0]]}"#;

fn deform_doc(flow: f64) -> String {
    let net: Vec<[f64; 3]> = (0..4)
        .map(|k| [(k / 2) as f64, (k % 2) as f64, 0.0])
        .collect();
    let flows = vec![vec![[0.0, 0.0, flow]; 4]];
    serde_json::json!({
        "degree": 1, "nu": 1, "nv": 1, "patches": [net],
        "samples": {"family": "equispaced"},
        "flow": flows, "correct": false
    })
    .to_string()
}

/// A tiny summary file with the given figure names.
fn summary(names: &[&str]) -> String {
    let figs: Vec<_> = names
        .iter()
        .map(|n| {
            serde_json::json!({"name": n, "value": 1.0, "kind": "accuracy", "better": "higher",
                "unit": "digits", "tolerance": 0.5, "floor": 0.0})
        })
        .collect();
    serde_json::json!({ "figures": figs }).to_string()
}

/// Every generated case.
fn cases(fx: &Fixture) -> Vec<Case> {
    let mut v = Vec::new();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let qi = fx.file("qi.json", QI_DOC.as_bytes());
    let be = fx.file("be.json", BEZIER_DOC.as_bytes());
    let fl = fx.file("fl.json", FLATTEN_DOC.as_bytes());
    let de = fx.file("de.json", deform_doc(0.5).as_bytes());
    let ck_s = fx.file("ck_s.txt", b"1 2 3 4 5 6 7 8 9 10");
    let ck_c = fx.file("ck_c.txt", b"0.5 2 3 4 5 6 7 8 9 10.5");
    let base = fx.file("base.json", summary(&["a.x", "b.y"]).as_bytes());
    let big = big_digits();

    // 1. Edge values of every numeric or enumerated flag.
    type Flag = (&'static str, &'static str, Vec<&'static str>);
    let flags: Vec<Flag> = vec![
        ("cond", "--degree", vec!["--nodes", "equispaced"]),
        (
            "cond",
            "--prec",
            vec!["--degree", "3", "--nodes", "equispaced"],
        ),
        ("cond", "--nodes", vec!["--degree", "3"]),
        (
            "cond",
            "--basis",
            vec!["--degree", "3", "--nodes", "equispaced"],
        ),
        (
            "cond",
            "--budget",
            vec!["--degree", "3", "--nodes", "equispaced"],
        ),
        (
            "cond",
            "--max-memory",
            vec!["--degree", "3", "--nodes", "equispaced"],
        ),
        ("coeffs", "--order", vec![]),
        ("coeffs", "--tension", vec![]),
        ("coeffs", "--prec", vec![]),
        ("coeffs", "--count", vec![]),
        ("coeffs", "--method", vec![]),
        ("width", "--order", vec!["--tol", "1e-3"]),
        ("width", "--tension", vec!["--tol", "1e-3"]),
        ("width", "--tol", vec![]),
        ("width", "--criterion", vec!["--tol", "1e-3"]),
        ("bezier-eval", "--prec", vec!["--method", "decasteljau"]),
        ("bezier-eval", "--method", vec![]),
        ("qi", "--prec", vec![]),
        ("qi", "--max-iter", vec![]),
        ("flatten", "--tol", vec![]),
        ("check", "--degree", vec![]),
        ("check", "--order", vec![]),
        ("check", "--mode", vec![]),
        ("check", "--max-ulps", vec![]),
        ("check", "--format", vec![]),
        ("check", "--budget", vec![]),
        ("check", "--max-memory", vec![]),
    ];
    let input_for = |cmd: &str| match cmd {
        "check" => ["prefilter", "--samples", &ck_s, "--coeffs", &ck_c]
            .map(String::from)
            .to_vec(),
        "bezier-eval" => vec!["--input".to_string(), be.clone()],
        "qi" => vec!["--input".to_string(), qi.clone()],
        "flatten" => vec!["--input".to_string(), fl.clone()],
        _ => vec![],
    };
    for (cmd, flag, rest) in &flags {
        let mut values: Vec<String> = EDGE_NUMBERS.iter().map(|s| s.to_string()).collect();
        values.push(big.clone());
        values.push(format!("-{big}"));
        for value in values {
            let mut c = case("edge flag value", &[cmd], &[flag]);
            c.args
                .extend(input_for(cmd).into_iter().map(OsString::from));
            c.args.extend(rest.iter().map(OsString::from));
            c.args.push(flag.into());
            c.args.push(value.into());
            if !flag.starts_with("--budget") {
                c.args.extend(["--budget", "2"].map(OsString::from));
                if !["cond", "coeffs", "width", "bezier-eval", "qi", "check"].contains(cmd) {
                    c.args.truncate(c.args.len() - 2);
                }
            }
            c.subject
                .extend(["--budget", "--max-memory", "input"].map(String::from));
            v.push(c);
        }
        // The flag with no value, or followed by another flag.
        let mut c = case("edge flag value", &[cmd, flag], &[flag]);
        c.args
            .extend(input_for(cmd).into_iter().map(OsString::from));
        v.push(c);
    }

    // 2. Random combinations of edge values across a command's flags.
    let combos: Vec<(&str, Vec<&str>)> = vec![
        ("cond", vec!["--degree", "--prec", "--nodes"]),
        ("coeffs", vec!["--order", "--prec", "--count", "--method"]),
        ("width", vec!["--order", "--tol", "--criterion"]),
        ("bezier-eval", vec!["--prec", "--method"]),
        ("qi", vec!["--prec", "--max-iter"]),
        ("flatten", vec!["--tol"]),
    ];
    let legal: BTreeMap<&str, Vec<&str>> = BTreeMap::from([
        ("--degree", vec!["1", "5", "40", "500", "501"]),
        (
            "--prec",
            vec!["f64", "16", "64", "100", "256", "1025", "2048", "2049"],
        ),
        (
            "--nodes",
            vec!["equispaced", "chebyshev-lobatto", "chebyshev-gauss", "x"],
        ),
        ("--order", vec!["2", "3", "4", "7", "60", "200", "201"]),
        ("--count", vec!["1", "10", "1000", "100000", "100001"]),
        (
            "--method",
            vec![
                "production",
                "partial-fractions",
                "recursive-filter",
                "toeplitz-solve",
                "decasteljau",
                "power",
                "power-exact",
                "bernstein",
                "vs",
                "compensated",
            ],
        ),
        ("--tol", vec!["1e-3", "1e-12", "1e-300", "0.5", "1"]),
        ("--criterion", vec!["coeff", "knot", "uniform", "x"]),
        ("--max-iter", vec!["1", "50", "1000", "1001"]),
    ]);
    for k in 0..3000 {
        let (cmd, fl) = &combos[k % combos.len()];
        let mut c = case("flag combination", &[cmd], &[]);
        c.args
            .extend(input_for(cmd).into_iter().map(OsString::from));
        for f in fl {
            c.subject.push(f.to_string());
            let value = if rng.next().is_multiple_of(4) {
                rng.pick(EDGE_NUMBERS).to_string()
            } else {
                rng.pick(&legal[f]).to_string()
            };
            c.args.push(f.into());
            c.args.push(value.into());
        }
        if ["cond", "coeffs", "width", "bezier-eval", "qi"].contains(cmd) {
            c.args.extend(["--budget", "2"].map(OsString::from));
        }
        c.subject
            .extend(["--budget", "--max-memory", "input", "numerical"].map(String::from));
        if rng.next().is_multiple_of(3) {
            c.args.push("--json".into());
        }
        v.push(c);
    }

    // 3. Malformed and huge JSON for every command that reads a file.
    let inputs: Vec<(&str, &str, Vec<&str>)> = vec![
        ("qi", QI_DOC, vec![]),
        ("bezier-eval", BEZIER_DOC, vec!["--method", "decasteljau"]),
        ("flatten", FLATTEN_DOC, vec!["--tol", "1e-3"]),
    ];
    let deform = deform_doc(0.5);
    let mut docs: Vec<(&str, String, Vec<&str>)> = inputs
        .iter()
        .map(|(c, d, r)| (*c, d.to_string(), r.clone()))
        .collect();
    docs.push(("deform", deform.clone(), vec![]));
    docs.push(("compare-baseline", summary(&["a.x", "b.y"]), vec![]));
    let mut n = 0;
    for (cmd, doc, rest) in &docs {
        let bytes = doc.as_bytes();
        let mut variants: Vec<Vec<u8>> = (0..bytes.len()).map(|k| bytes[..k].to_vec()).collect();
        variants.extend((0..bytes.len()).step_by(3).map(|k| {
            let mut b = bytes.to_vec();
            let junk = b"x]}\",0\xff\x00-e";
            b[k] = junk[k % junk.len()];
            b
        }));
        variants.push(format!("{{\"{}\": 1}}", "k".repeat(1 << 20)).into_bytes());
        variants.push(doc.replacen('1', &big, 1).into_bytes());
        variants.push(doc.replacen('1', "1e999", 1).into_bytes());
        variants.push(doc.replacen('1', "-1e-999", 1).into_bytes());
        variants.push(format!("{}{}", "[".repeat(100_000), "]".repeat(100_000)).into_bytes());
        variants.push(b"\xef\xbb\xbf{}".to_vec());
        variants.push(b"null".to_vec());
        variants.push(vec![0u8; 64]);
        for body in variants {
            n += 1;
            let file = fx.file(&format!("in{n}.json"), &body);
            let mut c = match *cmd {
                "deform" => {
                    let out = fx.path(&format!("deform_out{n}"));
                    let mut c = case("malformed JSON", &["deform", "--input", &file], &[&file]);
                    c.args.push("--out".into());
                    c.args.push(out.clone().into());
                    c.out = Some(out);
                    c
                }
                "compare-baseline" => {
                    let out = fx.path(&format!("cmp_out{n}"));
                    let mut c = case(
                        "malformed JSON",
                        &["compare", "--baseline", &file, "--current", &base],
                        &[&file, &base],
                    );
                    c.args.push("--out".into());
                    c.args.push(out.clone().into());
                    c.out = Some(out);
                    c
                }
                _ => case("malformed JSON", &[cmd, "--input", &file], &[&file]),
            };
            c.args.extend(rest.iter().map(OsString::from));
            v.push(c);
        }
    }

    // 4. File-system faults as inputs: FIFO, devices, directories, missing,
    // non-UTF-8 names.
    let fifo = fx.path("fifo");
    let _ = Command::new("mkfifo").arg(&fifo).status();
    let fifo = fifo.to_string_lossy().into_owned();
    let dir = fx.dir.to_string_lossy().into_owned();
    let mut weird = fx.dir.clone().into_os_string().into_vec();
    weird.extend_from_slice(b"/in\xff.json");
    let weird = OsString::from_vec(weird);
    std::fs::write(&weird, QI_DOC).unwrap();
    let specials: Vec<OsString> = vec![
        fifo.clone().into(),
        "/dev/zero".into(),
        "/dev/null".into(),
        "/dev/full".into(),
        dir.clone().into(),
        fx.path("missing.json").into(),
        weird.clone(),
        "".into(),
    ];
    for (cmd, rest) in [
        ("qi", vec![]),
        ("bezier-eval", vec!["--method", "vs"]),
        ("flatten", vec!["--tol", "1e-2"]),
        ("deform", vec!["--out", "OUT"]),
        ("compare-b", vec!["--current", &base, "--out", "OUT"]),
        ("compare-c", vec!["--baseline", &base, "--out", "OUT"]),
    ] {
        for (k, s) in specials.iter().enumerate() {
            for rep in 0..8 {
                let out = fx.path(&format!("fs_{cmd}_{k}_{rep}"));
                let (name, key) = match cmd {
                    "compare-b" => ("compare", "--baseline"),
                    "compare-c" => ("compare", "--current"),
                    c => (c, "--input"),
                };
                let mut c = case("file-system fault", &[name, key], &["cannot read", key]);
                c.args.push(s.clone());
                for r in &rest {
                    c.args.push(if *r == "OUT" {
                        out.clone().into()
                    } else {
                        r.into()
                    });
                }
                if rest.contains(&"OUT") {
                    c.out = Some(out);
                }
                if s != &weird && s != "/dev/null" {
                    c.expect = Expect::Fail;
                }
                if rep % 2 == 1 {
                    c.args.push("--json".into());
                    if name == "compare" {
                        c.args.pop();
                    }
                }
                if rep >= 4 {
                    c.env.push((
                        "SPLINELAB_MAX_INPUT_BYTES",
                        ["10", "x", "0", "99999999999"][rep - 4].into(),
                    ));
                    c.subject.push("SPLINELAB_MAX_INPUT_BYTES".into());
                }
                v.push(c);
            }
        }
    }

    // 5. Outputs: a full disk, a closed pipe, for every command, with and
    // without --json, --help and --version.
    let valid: Vec<Vec<String>> = vec![
        vec!["cond", "--degree", "8", "--nodes", "equispaced"],
        vec!["coeffs", "--count", "2000"],
        vec!["coeffs", "--count", "50", "--prec", "256"],
        vec!["width", "--tol", "1e-6"],
        vec!["bezier-eval", "--input", &be, "--method", "power"],
        vec!["qi", "--input", &qi],
        vec!["flatten", "--input", &fl, "--tol", "1e-3"],
        vec!["--help"],
        vec!["--version"],
        vec!["cond", "--help"],
        vec!["qi", "--help"],
    ]
    .into_iter()
    .map(|a| a.into_iter().map(String::from).collect())
    .collect();
    for (k, a) in valid.iter().enumerate() {
        for sink in [Sink::Full, Sink::ClosedPipe] {
            for json in [false, true] {
                for rep in 0..4 {
                    let args: Vec<&str> = a.iter().map(String::as_str).collect();
                    let mut c = case("full disk / closed pipe", &args, &["standard output"]);
                    if json
                        && !a
                            .iter()
                            .any(|x| x.starts_with("--help") || x == "--version")
                    {
                        c.args.push("--json".into());
                    }
                    c.sink = sink;
                    if sink == Sink::Full {
                        c.expect = Expect::Fail;
                    }
                    if rep % 2 == 1 {
                        c.env
                            .push(("RAYON_NUM_THREADS", ["100000", "0", "abc"][k % 3].into()));
                    }
                    v.push(c);
                }
            }
        }
    }
    // deform to a full disk and to closed pipes, with an out folder.
    for (k, sink) in [Sink::Full, Sink::ClosedPipe].into_iter().enumerate() {
        let out = fx.path(&format!("deform_sink{k}"));
        let mut c = case(
            "full disk / closed pipe",
            &["deform", "--input", &de, "--json", "--out"],
            &["standard output"],
        );
        c.args.push(out.into());
        c.sink = sink;
        if sink == Sink::Full {
            c.expect = Expect::Fail;
        }
        v.push(c);
    }

    // 6. Directories where files are expected, files where folders are, and
    // non-UTF-8 output names.
    let a_file = fx.file("plain.txt", b"x");
    let foreign = fx.path("foreign");
    std::fs::create_dir_all(foreign.join("sub")).unwrap();
    std::fs::write(foreign.join("notes.txt"), "keep").unwrap();
    let summary_dir = fx.path("summary_is_dir");
    std::fs::create_dir_all(summary_dir.join("summary.json")).unwrap();
    std::fs::write(summary_dir.join("index.html"), "old").unwrap();
    let mut weird_out = fx.dir.clone().into_os_string().into_vec();
    weird_out.extend_from_slice(b"/out\xff");
    let weird_out = PathBuf::from(OsString::from_vec(weird_out));
    for rep in 0..10 {
        for (cmd, out, fail) in [
            ("report", summary_dir.clone(), true),
            ("report", foreign.clone(), true),
            ("report", PathBuf::from(&a_file), true),
            ("compare", summary_dir.clone(), true),
            ("compare", foreign.clone(), true),
            ("compare", PathBuf::from(&a_file), true),
            ("compare", weird_out.join(format!("c{rep}")), false),
            ("deform", PathBuf::from(&a_file), true),
            ("deform", weird_out.join(format!("d{rep}")), false),
        ] {
            let mut c = match cmd {
                "report" => case(
                    "directory faults",
                    &["report", "--quick", "--quiet"],
                    &["cannot write"],
                ),
                "compare" => case(
                    "directory faults",
                    &["compare", "--baseline", &base, "--current", &base],
                    &["cannot write"],
                ),
                _ => case(
                    "directory faults",
                    &["deform", "--input", &de, "--json"],
                    &["cannot write"],
                ),
            };
            c.args.push("--out".into());
            c.args.push(out.clone().into());
            c.out = Some(out);
            if fail {
                c.expect = Expect::Fail;
            }
            v.push(c);
        }
    }

    // 7. Silent wrong results: overflowing deformations must fail. The
    // seed-001 example (bicubic, corrected joins) with its flows scaled.
    let example = fx.path("example");
    let made = Command::new(BIN)
        .args(["deform", "--example", "--out"])
        .arg(&example)
        .stdout(Stdio::null())
        .status()
        .unwrap();
    assert!(made.success());
    let input: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(example.join("input.json")).unwrap())
            .unwrap();
    for (k, scale) in [1e300, -1e300, 1e308, -1e250, 1e200, 1e150, 1.0, 1e-300]
        .iter()
        .enumerate()
    {
        let mut scaled = input.clone();
        for f in scaled["flow"]
            .as_array_mut()
            .unwrap()
            .iter_mut()
            .flat_map(|f| f.as_array_mut().unwrap())
        {
            for x in f.as_array_mut().unwrap() {
                *x = serde_json::json!(x.as_f64().unwrap() * scale);
            }
        }
        for rep in 0..5 {
            let file = fx.file(
                &format!("deform_big{k}_{rep}.json"),
                scaled.to_string().as_bytes(),
            );
            let out = fx.path(&format!("deform_big_out{k}_{rep}"));
            let mut c = case(
                "overflow",
                &["deform", "--input", &file, "--out"],
                &["overflow", &file],
            );
            c.args.push(out.clone().into());
            if rep % 2 == 0 {
                c.args.push("--json".into());
            }
            c.out = Some(out);
            if scale.abs() >= 1e200 {
                c.expect = Expect::Fail;
            }
            v.push(c);
        }
    }

    // 8. Compare figure names that are unsafe as file names.
    for (k, name) in [
        "a/../../escape.x",
        "b\u{0}nul.y",
        "../c.z",
        "/abs.w",
        ".hidden.v",
        "ü/ß.u",
        "con.t",
        &"l".repeat(300),
    ]
    .iter()
    .enumerate()
    {
        let s = fx.file(
            &format!("unsafe{k}.json"),
            summary(&[name, "ok.fig"]).as_bytes(),
        );
        for rep in 0..3 {
            let out = fx.path(&format!("unsafe_out{k}_{rep}"));
            let mut c = case(
                "unsafe names",
                &["compare", "--baseline", &s, "--current", &s, "--out"],
                &[name, "cannot"],
            );
            c.args.push(out.clone().into());
            c.out = Some(out);
            v.push(c);
        }
    }

    // 9. Budgets: the issue's long requests must be refused quickly.
    for a in [
        vec![
            "width",
            "--order",
            "200",
            "--criterion",
            "uniform",
            "--tol",
            "1e-300",
        ],
        vec![
            "cond",
            "--degree",
            "10",
            "--prec",
            "1000000",
            "--nodes",
            "equispaced",
        ],
        vec![
            "cond",
            "--degree",
            "500",
            "--prec",
            "2048",
            "--nodes",
            "equispaced",
        ],
        vec![
            "coeffs",
            "--order",
            "200",
            "--count",
            "100000",
            "--method",
            "toeplitz-solve",
            "--prec",
            "512",
        ],
        vec!["qi", "--input", &qi, "--prec", "1000000"],
    ] {
        for rep in 0..4 {
            let mut c = case("budget", &a, &["--budget", "--prec", "--max-memory"]);
            c.expect = Expect::Fail;
            if rep % 2 == 1 {
                c.args.push("--json".into());
            }
            v.push(c);
        }
    }

    // 10. Interrupted runs: SIGINT/SIGTERM during report and compare must
    // leave no partial output; during a long computation, a clean stop.
    for (k, sig) in ["INT", "TERM", "INT", "TERM"].iter().enumerate() {
        let out = fx.path(&format!("report_int{k}"));
        let mut c = case(
            "interrupted",
            &["report", "--quick", "--quiet", "--out"],
            &["interrupted"],
        );
        c.args.push(out.clone().into());
        c.out = Some(out);
        c.signal = Some((sig, Duration::from_millis(300 + 400 * k as u64)));
        v.push(c);
    }
    for (k, sig) in ["INT", "TERM"].iter().enumerate() {
        let mut c = case(
            "interrupted",
            &[
                "cond",
                "--degree",
                "200",
                "--nodes",
                "equispaced",
                "--prec",
                "256",
            ],
            &["interrupted"],
        );
        c.signal = Some((sig, Duration::from_millis(300)));
        v.push(c);
        let out = fx.path(&format!("compare_int{k}"));
        let mut c = case(
            "interrupted",
            &["compare", "--baseline", &base, "--current", &base, "--out"],
            &["interrupted"],
        );
        c.args.push(out.clone().into());
        c.out = Some(out);
        c.signal = Some((sig, Duration::from_millis(2)));
        v.push(c);
    }
    engine_cases(fx, &mut v);
    v
}

/// A `.npy` file: version 1.0 header for `descr` and `shape`, then `data`.
fn npy(descr: &str, fortran: bool, shape: &str, data: &[u8]) -> Vec<u8> {
    let dict = format!(
        "{{'descr': '{descr}', 'fortran_order': {}, 'shape': {shape}, }}",
        if fortran { "True" } else { "False" }
    );
    let mut header = dict.into_bytes();
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(b' ');
    }
    header.push(b'\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend((header.len() as u16).to_le_bytes());
    out.extend(header);
    out.extend(data);
    out
}

fn f64_bytes(xs: &[f64]) -> Vec<u8> {
    xs.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// Section 11: `prefilter` / `interpolate` / `width --emit` on hostile `.npy` files
/// (truncated, wrong dtype, NaN, empty, 0-d, garbage) and edge flags. Each
/// writes into its own empty folder, which must stay empty on failure.
fn engine_cases(fx: &Fixture, v: &mut Vec<Case>) {
    let six = f64_bytes(&[0.5, -1.0, 2.0, 0.25, 3.0, 1.5]);
    let good = fx.file("e_good.npy", &npy("<f8", false, "(2, 3)", &six));
    let good1 = fx.file("e_good1.npy", &npy("<f8", false, "(6,)", &six));
    let pts = fx.file(
        "e_pts.npy",
        &npy("<f8", false, "(2, 2)", &f64_bytes(&[0.5, 1.5, -3.0, 9.0])),
    );
    let mut nan = six.clone();
    nan[16..24].copy_from_slice(&f64::NAN.to_le_bytes());
    let mut inf = six.clone();
    inf[40..48].copy_from_slice(&f64::NEG_INFINITY.to_le_bytes());
    let bad: Vec<(&str, Vec<u8>)> = vec![
        ("truncated", npy("<f8", false, "(2, 3)", &six[..20])),
        (
            "long",
            npy("<f8", false, "(2, 3)", &[six.clone(), vec![0; 8]].concat()),
        ),
        ("header only", npy("<f8", false, "(2, 3)", &[])),
        (
            "cut header",
            npy("<f8", false, "(2, 3)", &six)[..30].to_vec(),
        ),
        ("int", npy("<i8", false, "(2, 3)", &six)),
        ("complex", npy("<c16", false, "(3,)", &six)),
        ("bool", npy("|b1", false, "(6,)", &[1; 6])),
        ("object", npy("|O", false, "(6,)", &six)),
        ("f16", npy("<f2", false, "(6,)", &six[..12])),
        ("nan", npy("<f8", false, "(2, 3)", &nan)),
        ("inf", npy("<f8", false, "(2, 3)", &inf)),
        ("empty", npy("<f8", false, "(0,)", &[])),
        ("empty axis", npy("<f8", false, "(3, 0)", &[])),
        ("0-d", npy("<f8", false, "()", &six[..8])),
        ("bad shape", npy("<f8", false, "(2, -3)", &six)),
        (
            "huge shape",
            npy("<f8", false, "(4294967296, 4294967296)", &six),
        ),
        ("garbage", b"not an npy file at all".to_vec()),
        ("empty file", vec![]),
        (
            "f32 nan",
            npy(
                "<f4",
                false,
                "(2,)",
                &[f32::NAN.to_le_bytes(), 1f32.to_le_bytes()].concat(),
            ),
        ),
    ];
    for (k, (what, bytes)) in bad.iter().enumerate() {
        let f = fx.file(&format!("e_bad{k}.npy"), bytes);
        for (cmd, rest) in [
            ("prefilter", vec![]),
            ("interpolate", vec!["--at".to_string(), pts.clone()]),
        ] {
            // As the samples.
            let out = fx.path(&format!("e_out_{cmd}_{k}"));
            std::fs::create_dir_all(&out).unwrap();
            let mut c = case("engine npy", &[cmd, "--input", &f, "--degree", "3"], &[&f]);
            c.args.extend(rest.iter().map(OsString::from));
            // Non-finite samples are refused under raise only: the default
            // (propagate, scipy's) and local compute with them.
            let non_finite = what.contains("nan") || what.contains("inf");
            if non_finite {
                let mut any = c.clone();
                let elsewhere = fx.path(&format!("e_any_{cmd}_{k}.npy"));
                any.args.extend(["--output".into(), elsewhere.into()]);
                any.expect = Expect::Any;
                v.push(any);
                c.args.extend(["--nan-policy".into(), "raise".into()]);
            }
            c.args.extend(["--output".into(), out.join("r.npy").into()]);
            c.out = Some(out);
            c.expect = Expect::Fail;
            v.push(c);
        }
        // As the points.
        let out = fx.path(&format!("e_out_pts_{k}"));
        std::fs::create_dir_all(&out).unwrap();
        let mut c = case(
            "engine npy",
            &["interpolate", "--input", &good, "--degree", "3", "--at", &f],
            &[&f],
        );
        c.args.extend(["--output".into(), out.join("r.npy").into()]);
        c.out = Some(out);
        c.expect = Expect::Fail;
        v.push(c);
    }
    // Edge values of the engine's flags (any outcome but a panic or hang;
    // failures must be clear and leave the folder empty).
    for (flag, rest) in [
        ("--degree", vec![]),
        ("--order", vec![]),
        ("--tol", vec!["--degree", "3"]),
        ("--prec", vec!["--degree", "3"]),
        ("--axis", vec!["--degree", "3"]),
        ("--cval", vec!["--degree", "3", "--mode", "grid-constant"]),
        ("--max-error", vec!["--degree", "3"]),
        ("--mode", vec!["--degree", "3"]),
        ("--budget", vec!["--degree", "3"]),
    ] {
        for (j, value) in EDGE_NUMBERS.iter().enumerate() {
            let out = fx.path(&format!("e_flag{}_{j}", flag.trim_start_matches('-')));
            std::fs::create_dir_all(&out).unwrap();
            let mut c = case(
                "engine flag",
                &["prefilter", "--input", &good],
                &[flag, "--budget"],
            );
            c.args.extend(rest.iter().map(OsString::from));
            c.args
                .extend([flag.into(), (*value).into(), "--output".into()]);
            c.args.push(out.join("r.npy").into());
            v.push(c);
        }
    }
    // Points far outside the grid, every mode: the mode defines the value.
    let far = fx.file(
        "e_far.npy",
        &npy(
            "<f8",
            false,
            "(4, 1)",
            &f64_bytes(&[1e308, -1e308, 4503599627370497.0, -0.5]),
        ),
    );
    for mode in ["mirror", "reflect", "grid-wrap", "nearest", "grid-constant"] {
        let out = fx.path(&format!("e_far_{mode}.npy"));
        let c = case(
            "engine far points",
            &[
                "interpolate",
                "--input",
                &good1,
                "--degree",
                "5",
                "--mode",
                mode,
                "--at",
                &far,
                "--output",
                out.to_str().unwrap(),
            ],
            &[],
        );
        v.push(c);
    }
    // resample (issue 42): outputs too large to count or allocate, huge and
    // non-finite factors and angles, a degree beyond f64's range — an error
    // naming the flag or the memory, never a panic or an abort.
    let matrix = fx.file(
        "e_matrix.npy",
        &npy("<f8", false, "(2, 2)", &f64_bytes(&[1.0, 0.0, 0.0, 1.0])),
    );
    let hostile: [&[&str]; 14] = [
        &["--zoom", "1e300"],
        &["--zoom", "1e9"],
        &["--zoom", "1e5,1"],
        &["--zoom", "0"],
        &["--zoom", "0.01"],
        &["--zoom", "-1"],
        &["--zoom", "nan"],
        &["--shift", "1e300"],
        &["--rotate", "1e300"],
        &["--rotate", "inf"],
        &[
            "--matrix",
            &matrix,
            "--output-shape",
            "4294967296,4294967296",
        ],
        &["--matrix", &matrix, "--output-shape", "0,5"],
        &["--zoom", "2", "--degree", "199"],
        &[
            "--zoom",
            "2",
            "--degree",
            "6",
            "--mode",
            "grid-constant",
            "--cval",
            "1e308",
        ],
    ];
    for (k, flags) in hostile.iter().enumerate() {
        let out = fx.path(&format!("e_resample_{k}.npy"));
        let mut c = case(
            "engine resample",
            &["resample", "--input", &good],
            &[
                "--zoom",
                "--shift",
                "--rotate",
                "--matrix",
                "--output-shape",
                "--degree",
                "--cval",
                "--budget",
                "allocate",
                "--prec",
                "--max-error",
            ],
        );
        c.args.extend(flags.iter().map(OsString::from));
        if !flags.contains(&"--degree") {
            c.args.extend(["--degree".into(), "3".into()]);
        }
        c.args.extend(["--output".into(), out.into()]);
        v.push(c);
    }
    // Budget: a large array at high precision is refused before any work.
    let big = fx.file(
        "e_big.npy",
        &npy("<f8", false, "(200000,)", &vec![0u8; 1_600_000]),
    );
    let out = fx.path("e_budget");
    std::fs::create_dir_all(&out).unwrap();
    let mut c = case(
        "budget",
        &[
            "prefilter",
            "--input",
            &big,
            "--degree",
            "199",
            "--prec",
            "2048",
            "--output",
        ],
        &["--budget"],
    );
    c.args.push(out.join("r.npy").into());
    c.out = Some(out);
    c.expect = Expect::Fail;
    v.push(c);
    // Full disk for each output form (stdout on /dev/full; the prefilter's
    // file is written before its summary fails).
    let full_out = fx.path("e_full.npy").to_string_lossy().into_owned();
    for a in [
        vec!["width", "--tol", "1e-6", "--emit", "c"],
        vec!["width", "--tol", "1e-6", "--emit", "rust", "--dtype", "f32"],
        vec!["width", "--tol", "1e-6", "--emit", "json"],
        vec![
            "prefilter",
            "--input",
            &good,
            "--degree",
            "3",
            "--output",
            &full_out,
        ],
    ] {
        let mut c = case(
            "full disk / closed pipe",
            &a,
            &["standard output", "/dev/full"],
        );
        c.sink = Sink::Full;
        c.expect = Expect::Fail;
        v.push(c);
    }
}

/// Names in `dir`'s parent that are our temporaries for `dir`.
fn leftovers(out: &Path) -> Vec<String> {
    let Some(parent) = out.parent() else {
        return vec![];
    };
    let Some(stem) = out.file_name() else {
        return vec![];
    };
    let prefix = format!(".{}.tmp", stem.to_string_lossy());
    std::fs::read_dir(parent)
        .map(|d| {
            d.filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| n.starts_with(&prefix))
                .collect()
        })
        .unwrap_or_default()
}

fn listing(dir: &Path) -> Option<Vec<String>> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .ok()?
        .filter_map(Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    Some(names)
}

/// The message is clear: `error: …`, short, naming one of the subjects.
fn clear(stderr: &str, subject: &[String]) -> bool {
    let first = stderr.lines().next().unwrap_or("");
    first.starts_with("error:")
        && stderr.len() <= 2000
        && !stderr.contains("Os {")
        && (subject.is_empty()
            || subject
                .iter()
                .any(|s| stderr.contains(s.chars().take(60).collect::<String>().as_str())))
}

fn run_case(c: &Case, tally: &Mutex<Tally>) {
    let before = c.out.as_ref().and_then(|o| listing(o));
    let mut cmd = Command::new(BIN);
    cmd.args(&c.args)
        .stdin(Stdio::null())
        .stderr(Stdio::piped());
    for (k, v) in &c.env {
        cmd.env(k, v);
    }
    match c.sink {
        Sink::Null => cmd.stdout(Stdio::null()),
        Sink::Full => cmd.stdout(std::fs::File::create("/dev/full").unwrap()),
        Sink::ClosedPipe => cmd.stdout(Stdio::piped()),
    };
    let mut child = cmd.spawn().expect("spawn splinelab");
    drop(child.stdout.take());
    let stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        use std::io::Read;
        let mut s = Vec::new();
        let _ = stderr.take(1 << 20).read_to_end(&mut s);
        String::from_utf8_lossy(&s).into_owned()
    });
    let start = Instant::now();
    let mut signalled = false;
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break Some(s);
        }
        if let Some((sig, delay)) = c.signal
            && !signalled
            && start.elapsed() >= delay
        {
            let _ = Command::new("kill")
                .args([format!("-{sig}"), child.id().to_string()])
                .status();
            signalled = true;
        }
        if start.elapsed() > TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(3));
    };
    let err = reader.join().unwrap_or_default();
    let label = format!("{:?} [{}]", c.args, c.class);
    let label: String = label.chars().take(300).collect();
    let mut t = tally.lock().unwrap();
    t.cases += 1;
    *t.by_class.entry(c.class).or_default() += 1;
    let Some(status) = status else {
        t.timeouts.push(label);
        return;
    };
    let code = status.code();
    if code == Some(101) || err.contains("panicked") {
        t.panics.push(format!(
            "{label}: {}",
            err.chars().take(300).collect::<String>()
        ));
        return;
    }
    if let Some(out) = &c.out {
        let left = leftovers(out);
        let now = listing(out);
        let complete = now
            .as_ref()
            .is_some_and(|n| n.iter().any(|f| f == "index.html" || f == "deformed.json"));
        let untouched = now == before;
        if !left.is_empty()
            || !(untouched || (code == Some(0) || code == Some(1) || code == Some(141)) && complete)
        {
            t.partial.push(format!(
                "{label}: code {code:?}, temporaries {left:?}, now {now:?}, before {before:?}"
            ));
            return;
        }
    }
    match code {
        Some(0) | Some(1) if c.expect == Expect::Fail => {
            t.silent.push(format!("{label}: exit {code:?}"));
        }
        Some(0) => t.ok += 1,
        Some(141) if c.sink == Sink::ClosedPipe && err.is_empty() => t.ok += 1,
        Some(130) if c.signal.is_some() => t.ok += 1,
        // Killed by the signal before the handler was installed (nothing
        // can have been written yet: the output check above passed).
        None if c.signal.is_some() => t.ok += 1,
        _ => {
            t.errors += 1;
            if code == Some(1) && !err.is_empty() && !err.starts_with("error:") {
                // qi without --json prints its failure as an error too.
                t.unclear.push(format!(
                    "{label}: {}",
                    err.chars().take(300).collect::<String>()
                ));
            } else if code != Some(1) && !clear(&err, &c.subject) {
                t.unclear.push(format!(
                    "{label}: {}",
                    err.chars().take(300).collect::<String>()
                ));
            }
        }
    }
}

/// Classes with more cases than this run every `QUICK_STRIDE`-th of them
/// in the quick test profile (`SPLINELAB_TEST_PROFILE=quick`, set by
/// `scripts/test.sh --quick`, which CI runs); the full profile runs all.
const QUICK_CLASS_CAP: usize = 100;
const QUICK_STRIDE: usize = 4;

/// The cases this profile runs: all of them, or in the quick profile every
/// small class whole and every `QUICK_STRIDE`-th case of the large ones
/// (flag combinations, edge values, malformed JSON, file-system faults),
/// so every class and every generator still runs.
fn for_profile(all: Vec<Case>) -> (Vec<Case>, usize) {
    if std::env::var("SPLINELAB_TEST_PROFILE").as_deref() != Ok("quick") {
        return (all, 5000);
    }
    let mut sizes: BTreeMap<&str, usize> = BTreeMap::new();
    for c in &all {
        *sizes.entry(c.class).or_default() += 1;
    }
    let mut seen: BTreeMap<&str, usize> = BTreeMap::new();
    let kept: Vec<Case> = all
        .iter()
        .filter(|c| {
            let k = seen.entry(c.class).or_default();
            *k += 1;
            sizes[c.class] <= QUICK_CLASS_CAP || (*k - 1).is_multiple_of(QUICK_STRIDE)
        })
        .cloned()
        .collect();
    let floor = kept.len();
    (kept, floor)
}

#[test]
fn generated_fault_sweep() {
    let fx = Fixture::new();
    let (all, at_least) = for_profile(cases(&fx));
    let tally = Mutex::new(Tally::default());
    let next = AtomicUsize::new(0);
    let workers = std::thread::available_parallelism().map_or(2, usize::from) * 2;
    let start = Instant::now();
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| {
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    let Some(c) = all.get(k) else { break };
                    run_case(c, &tally);
                }
            });
        }
    });
    let t = tally.into_inner().unwrap();
    let _ = std::fs::remove_dir_all(&fx.dir);
    println!(
        "fault sweep: {} cases in {:.1} s: {} ok, {} errors ({} unclear = {:.2}%), {} panics, \
         {} timeouts, {} partial outputs, {} silent wrong results",
        t.cases,
        start.elapsed().as_secs_f64(),
        t.ok,
        t.errors,
        t.unclear.len(),
        100.0 * t.unclear.len() as f64 / t.cases as f64,
        t.panics.len(),
        t.timeouts.len(),
        t.partial.len(),
        t.silent.len()
    );
    println!("by class: {:?}", t.by_class);
    for (what, list) in [
        ("PANIC", &t.panics),
        ("TIMEOUT", &t.timeouts),
        ("PARTIAL", &t.partial),
        ("SILENT", &t.silent),
        ("UNCLEAR", &t.unclear),
    ] {
        for l in list.iter().take(if what == "UNCLEAR" { 200 } else { 15 }) {
            println!("{what}: {l}");
        }
    }
    assert!(t.cases >= at_least, "only {} cases", t.cases);
    assert!(t.panics.is_empty(), "{} panics", t.panics.len());
    assert!(t.timeouts.is_empty(), "{} timeouts", t.timeouts.len());
    assert!(t.partial.is_empty(), "{} partial outputs", t.partial.len());
    assert!(
        t.silent.is_empty(),
        "{} silent wrong results",
        t.silent.len()
    );
    assert!(
        t.unclear.len() * 100 < t.cases,
        "{} unclear messages of {}",
        t.unclear.len(),
        t.cases
    );
}

/// `qi`'s documented exit statuses: 1 when Newton does not converge (the
/// JSON still comes, with `"converged": false`), 2 for bad input, 0 on
/// success.
#[test]
fn qi_newton_failure_exits_1_and_bad_input_2() {
    let dir = std::env::temp_dir().join(format!("splinelab_qi_exit_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("qi.json");
    std::fs::write(&file, QI_DOC).unwrap();
    let run = |extra: &[&str]| {
        Command::new(BIN)
            .arg("qi")
            .arg("--input")
            .arg(&file)
            .args(extra)
            .output()
            .unwrap()
    };
    let failed = run(&["--max-iter", "1", "--json"]);
    assert_eq!(failed.status.code(), Some(1));
    let json: serde_json::Value = serde_json::from_slice(&failed.stdout).unwrap();
    assert_eq!(json["converged"], serde_json::json!(false));
    assert!(String::from_utf8_lossy(&failed.stderr).starts_with("error:"));
    assert_eq!(run(&["--max-iter", "1"]).status.code(), Some(1));
    assert_eq!(run(&["--max-iter", "50"]).status.code(), Some(0));
    assert_eq!(run(&["--max-iter", "0"]).status.code(), Some(2));
    assert_eq!(run(&["--max-iter", "-1"]).status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}
