//! A generated sweep of hostile `.npy` files through every command that reads
//! arrays (`prefilter`, `interpolate`, each `check` kind), in every array
//! slot: headers that lie both ways about the body (more, fewer bytes),
//! huge claims (10¹² elements, products past 2⁶⁴), object/pickle, string,
//! structured and other foreign dtypes, both byte orders, Fortran order,
//! truncated prefixes, headers and bodies, bad magic and versions, code and
//! expressions in the header dictionary, non-ASCII and control characters,
//! deep nesting and header lengths up to 4 GiB.
//!
//! The commands run in this process (the CLI's own `parse_args` and `run`),
//! so thousands of cases take seconds; an abort (an allocation of the
//! claimed size) would end the test process, which fails the test. A small
//! sample also runs through the built binary, asserting that the process
//! exits 0, 1 or 2 and is never ended by a signal.
//!
//! Each case asserts: no panic; an error for every malformed file, with
//! exit status 2 and a one-line message that names the file and stays short
//! and printable; no output file or folder left behind by a failed run.

use splinelab_reports::cli::{parse_args, run};
use splinelab_reports::error::CliError;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

/// Element types written into headers: ours (both byte orders) and foreign.
const DESCRS: &[&str] = &[
    "'<f8'",
    "'>f8'",
    "'<f4'",
    "'>f4'",
    "'|O'",
    "'<i8'",
    "'<c16'",
    "'|b1'",
    "'<f2'",
    "'<U3'",
    "'|V16'",
    "'=f8'",
    "[('a', '<f8'), ('b', '<f8')]",
    "__import__('os').system('true')",
    "'<f\u{e9}'",
];

/// Shapes written into headers, with the element count when it is one.
const SHAPES: &[(&str, Option<u128>)] = &[
    ("(6,)", Some(6)),
    ("(2, 3)", Some(6)),
    ("(1000000000000,)", Some(1_000_000_000_000)),
    ("(4294967296, 4294967296, 2)", Some(1 << 65)),
    ("()", Some(1)),
    ("(0,)", Some(0)),
    ("(-1,)", None),
    ("(10**12,)", None),
    ("(2.5,)", None),
    ("[6]", None),
];

/// How the body relates to the header's claim.
#[derive(Clone, Copy, Debug)]
enum Body {
    Exact,
    OneShort,
    OneLong,
    Empty,
}

const BODIES: &[Body] = &[Body::Exact, Body::OneShort, Body::OneLong, Body::Empty];

/// Bytes of one element of `descr` (0 when it is not a plain number type).
fn item_size(descr: &str) -> usize {
    match descr {
        "'<f8'" | "'>f8'" | "'<i8'" | "'=f8'" => 8,
        "'<f4'" | "'>f4'" => 4,
        "'<c16'" | "'|V16'" => 16,
        "'|b1'" => 1,
        "'<f2'" => 2,
        "'<U3'" => 12,
        _ => 8,
    }
}

/// Whether our reader must accept the element type.
fn ours(descr: &str) -> bool {
    matches!(descr, "'<f8'" | "'>f8'" | "'<f4'" | "'>f4'")
}

/// A `.npy` file: `version` prefix, the header dictionary `dict` padded to
/// 64 bytes as numpy does, then `body`.
fn npy(version: u8, dict: &str, body: &[u8]) -> Vec<u8> {
    let mut header = dict.as_bytes().to_vec();
    let prefix = if version == 1 { 10 } else { 12 };
    while !(prefix + header.len() + 1).is_multiple_of(64) {
        header.push(b' ');
    }
    header.push(b'\n');
    let mut out = b"\x93NUMPY".to_vec();
    out.extend([version, 0]);
    if version == 1 {
        out.extend((header.len() as u16).to_le_bytes());
    } else {
        out.extend((header.len() as u32).to_le_bytes());
    }
    out.extend(header);
    out.extend(body);
    out
}

fn dict(descr: &str, fortran: &str, shape: &str) -> String {
    format!("{{'descr': {descr}, 'fortran_order': {fortran}, 'shape': {shape}, }}")
}

/// One hostile file: its bytes and whether it is a well-formed f64/f32
/// array (which a command may then accept or refuse on its merits).
struct Hostile {
    name: String,
    bytes: Vec<u8>,
    well_formed: bool,
}

/// The generated files: every element type × shape × body (both layouts
/// alternating, both header versions alternating), then the special cases.
fn hostile_files() -> Vec<Hostile> {
    let mut out = vec![];
    let mut k = 0usize;
    for descr in DESCRS {
        for (shape, count) in SHAPES {
            for body in BODIES {
                k += 1;
                let fortran = if k.is_multiple_of(2) { "True" } else { "False" };
                let claim = count.map(|c| c * item_size(descr) as u128);
                // Bodies are at most a few KiB whatever the claim: 0x3F bytes
                // are finite numbers in either byte order and width.
                let exact = claim.filter(|&c| c <= 4096).map(|c| c as usize);
                let len = match (body, exact) {
                    (Body::Exact, Some(c)) => c,
                    (Body::Exact, None) => 16,
                    (Body::OneShort, Some(c)) => c.saturating_sub(1),
                    (Body::OneShort, None) => 15,
                    (Body::OneLong, Some(c)) => c + 1,
                    (Body::OneLong, None) => 17,
                    (Body::Empty, _) => 0,
                };
                let well_formed =
                    ours(descr) && exact == Some(len) && !matches!(shape, s if s.contains("-1"));
                out.push(Hostile {
                    name: format!("g{k}"),
                    bytes: npy(
                        1 + (k % 2) as u8,
                        &dict(descr, fortran, shape),
                        &vec![0x3F; len],
                    ),
                    well_formed,
                });
            }
        }
    }
    out.extend(special_files());
    out
}

/// Hand-made faults of the container itself.
fn special_files() -> Vec<Hostile> {
    let good = npy(1, &dict("'<f8'", "False", "(6,)"), &[0x3F; 48]);
    let mut cases: Vec<(&str, Vec<u8>)> = vec![
        ("empty", vec![]),
        ("magic only", b"\x93NUMPY".to_vec()),
        ("bad magic", [b"\x93NUMPZ".as_slice(), &good[6..]].concat()),
        ("zip", b"PK\x03\x04 an npz is a zip".to_vec()),
        ("pickle", b"\x80\x04\x95 pickled object".to_vec()),
        ("version 0", [&good[..6], &[0, 0], &good[8..]].concat()),
        ("version 9", [&good[..6], &[9, 0], &good[8..]].concat()),
        ("no newline", good[..good.len() - 49].to_vec()),
        ("cut prefix", good[..9].to_vec()),
        ("cut header", good[..40].to_vec()),
        ("cut body", good[..good.len() - 3].to_vec()),
        (
            "code value",
            npy(
                1,
                "{'descr': '<f8', 'fortran_order': __import__('os'), 'shape': (6,)}",
                &[0x3F; 48],
            ),
        ),
        (
            "lambda",
            npy(
                1,
                "{'descr': (lambda: '<f8')(), 'fortran_order': False, 'shape': (6,)}",
                &[0; 48],
            ),
        ),
        ("not a dict", npy(1, "['<f8', False, (6,)]", &[0; 48])),
        (
            "extra key",
            npy(
                1,
                "{'descr': '<f8', 'fortran_order': False, 'shape': (6,), 'x': 1}",
                &[0; 48],
            ),
        ),
        (
            "missing shape",
            npy(1, "{'descr': '<f8', 'fortran_order': False}", &[0; 48]),
        ),
        (
            "fortran string",
            npy(1, &dict("'<f8'", "'yes'", "(6,)"), &[0; 48]),
        ),
        ("fortran int", npy(1, &dict("'<f8'", "1", "(6,)"), &[0; 48])),
        (
            "non-ascii v1",
            npy(
                1,
                &dict("'<f8'", "False", "(6,)").replace("descr", "d\u{e9}scr"),
                &[0; 48],
            ),
        ),
        (
            "non-ascii v3",
            npy(3, &dict("'\u{263a}'", "False", "(6,)"), &[0; 48]),
        ),
        (
            "control chars",
            npy(1, &dict("'\u{1b}[31m<f8'", "False", "(6,)"), &[0; 48]),
        ),
        ("nul", npy(1, &dict("'<f8\0'", "False", "(6,)"), &[0; 48])),
        (
            "deep nesting",
            npy(
                2,
                &dict(
                    &format!("{}'<f8'{}", "[".repeat(4000), "]".repeat(4000)),
                    "False",
                    "(6,)",
                ),
                &[0; 48],
            ),
        ),
        (
            "unbalanced",
            npy(1, "{'descr': '<f8', 'shape': ((((((", &[0; 48]),
        ),
    ];
    let mut huge_v2 = npy(2, "{}", &[]);
    huge_v2[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
    cases.push(("header_len 4 GiB", huge_v2));
    let mut long_v1 = npy(1, "{}", &[]);
    long_v1[8..10].copy_from_slice(&u16::MAX.to_le_bytes());
    cases.push(("header_len 64 KiB", long_v1));
    let big_header = dict("'<f8'", "False", &format!("(6,{})", " ".repeat(20_000)));
    cases.push(("header 20 kB", npy(2, &big_header, &[0; 48])));
    cases
        .into_iter()
        .enumerate()
        .map(|(i, (_, bytes))| Hostile {
            name: format!("s{i}"),
            bytes,
            well_formed: false,
        })
        .collect()
}

/// A command line, words split at spaces, with `{F}` where the hostile file
/// goes and `{O}` where the output goes; `folder` when `{O}` is a folder
/// (check's `--out`).
struct Slot {
    line: &'static str,
    folder: bool,
}

const SLOTS: &[Slot] = &[
    Slot {
        line: "prefilter --input {F} --degree 3 --output {O}",
        folder: false,
    },
    Slot {
        line: "interpolate --input {F} --degree 3 --at {pts} --output {O}",
        folder: false,
    },
    Slot {
        line: "interpolate --input {six} --degree 3 --at {F} --output {O}",
        folder: false,
    },
    Slot {
        line: "check prefilter --samples {F} --coeffs {six} --out {O}",
        folder: true,
    },
    Slot {
        line: "check prefilter --samples {six} --coeffs {F} --out {O}",
        folder: true,
    },
    Slot {
        line: "check interp --samples {F} --coords {pts} --values {pts} --out {O}",
        folder: true,
    },
    Slot {
        line: "check interp --samples {six} --coords {F} --values {pts} --out {O}",
        folder: true,
    },
    Slot {
        line: "check interp --samples {six} --coords {pts} --values {F} --out {O}",
        folder: true,
    },
    Slot {
        line: "check cond --nodes {F} --values {one} --out {O}",
        folder: true,
    },
    Slot {
        line: "check cond --nodes {six} --values {F} --out {O}",
        folder: true,
    },
    Slot {
        line: "check coeffs --order 4 --values {F} --out {O}",
        folder: true,
    },
    Slot {
        line: "check bspline-eval --knots {F} --coeffs {pts} --degree 1 --x {pts} --values {pts} --out {O}",
        folder: true,
    },
    Slot {
        line: "check bspline-eval --knots {knots} --coeffs {F} --degree 1 --x {pts} --values {pts} --out {O}",
        folder: true,
    },
    Slot {
        line: "check bspline-eval --knots {knots} --coeffs {pts} --degree 1 --x {F} --values {pts} --out {O}",
        folder: true,
    },
    Slot {
        line: "check bezier-eval --coeffs {F} --t {pts} --values {pts} --out {O}",
        folder: true,
    },
    Slot {
        line: "check bezier-eval --coeffs {pts} --t {F} --values {pts} --out {O}",
        folder: true,
    },
    Slot {
        line: "check bezier-eval --coeffs {pts} --t {pts} --values {F} --out {O}",
        folder: true,
    },
];

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sl_npy_sweep_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn f64_npy(shape: &str, xs: &[f64]) -> Vec<u8> {
    let body: Vec<u8> = xs.iter().flat_map(|x| x.to_le_bytes()).collect();
    npy(1, &dict("'<f8'", "False", shape), &body)
}

/// The valid companion files the slots name.
fn companions(dir: &Path) -> Vec<(&'static str, String)> {
    let files = [
        ("{six}", f64_npy("(6,)", &[0.5, -1.0, 2.0, 0.25, 3.0, 1.5])),
        ("{pts}", f64_npy("(3,)", &[0.25, 0.5, 0.75])),
        ("{one}", f64_npy("(1,)", &[3.0])),
        ("{knots}", f64_npy("(5,)", &[0.0, 0.0, 0.5, 1.0, 1.0])),
    ];
    files
        .into_iter()
        .map(|(key, bytes)| {
            let p = dir.join(format!("{}.npy", key.trim_matches(['{', '}'])));
            std::fs::write(&p, bytes).unwrap();
            (key, p.to_str().unwrap().to_string())
        })
        .collect()
}

/// What one case did: the exit status and, for an error, its message.
struct Outcome {
    code: u8,
    message: Option<String>,
}

fn run_in_process(args: &[String]) -> Result<Outcome, String> {
    let cli = parse_args(std::iter::once("splinelab".to_string()).chain(args.iter().cloned()))
        .map_err(|e| format!("usage error: {e}"))?;
    let ran = std::panic::catch_unwind(|| run(&cli.command)).map_err(|_| "PANIC".to_string())?;
    Ok(match ran {
        Ok(code) => Outcome {
            code: if code == ExitCode::SUCCESS { 0 } else { 1 },
            message: None,
        },
        Err(e) => Outcome {
            code: CliError::exit_code(&e),
            message: Some(e.to_string()),
        },
    })
}

/// A clear message: one line, printable, short, naming the file.
fn clear(message: &str, file: &str) -> bool {
    !message.contains('\n')
        && !message.chars().any(|c| c.is_control())
        && message.chars().count() <= 400
        && message.contains(file)
}

/// Whether a failed case left anything where its output goes.
fn left_behind(out: &Path) -> Vec<String> {
    let parent = out.parent().unwrap();
    let stem = out.file_name().unwrap().to_string_lossy().into_owned();
    std::fs::read_dir(parent)
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(&stem))
        .collect()
}

#[test]
fn hostile_npy_files_in_every_array_slot_fail_cleanly_or_read_correctly() {
    let dir = scratch("inproc");
    let mut fill = companions(&dir);
    let files = hostile_files();
    let (mut cases, mut refused, mut accepted) = (0usize, 0usize, 0usize);
    let mut failures = vec![];
    for (i, h) in files.iter().enumerate() {
        let path = dir.join(format!("{}.npy", h.name));
        std::fs::write(&path, &h.bytes).unwrap();
        let file = path.to_str().unwrap().to_string();
        // Every file goes through 9 of the 17 slots, rotating, so each slot
        // sees about half the files.
        for s in 0..9 {
            let slot = &SLOTS[(i + 2 * s) % SLOTS.len()];
            let case_dir = dir.join(format!("c{i}_{s}"));
            std::fs::create_dir(&case_dir).unwrap();
            let out = if slot.folder {
                case_dir.join("out")
            } else {
                case_dir.join("r.npy")
            };
            fill.retain(|(k, _)| *k != "{F}" && *k != "{O}");
            fill.push(("{F}", file.clone()));
            fill.push(("{O}", out.to_str().unwrap().to_string()));
            let args: Vec<String> = slot
                .line
                .split(' ')
                .map(|a| {
                    fill.iter()
                        .find(|(k, _)| *k == a)
                        .map_or(a.to_string(), |(_, v)| v.clone())
                })
                .collect();
            cases += 1;
            let what = format!("{} [{}]", h.name, args.join(" "));
            match run_in_process(&args) {
                Err(e) => failures.push(format!("{what}: {e}")),
                Ok(Outcome {
                    code,
                    message: None,
                }) => {
                    accepted += 1;
                    if !h.well_formed {
                        failures.push(format!("{what}: malformed file accepted (exit {code})"));
                    }
                }
                Ok(Outcome {
                    code,
                    message: Some(m),
                }) => {
                    refused += 1;
                    if code != 2 {
                        failures.push(format!("{what}: exit {code}: {m}"));
                    }
                    if !h.well_formed && !clear(&m, &file) {
                        failures.push(format!("{what}: unclear message: {m}"));
                    }
                    let left = left_behind(&out);
                    if !left.is_empty() {
                        failures.push(format!("{what}: left {left:?}"));
                    }
                }
            }
        }
    }
    println!(
        "npy sweep: {} files, {cases} cases, {refused} refused, {accepted} accepted, {} failures",
        files.len(),
        failures.len()
    );
    assert!(cases >= 2000, "only {cases} cases");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The worst of the files through the real binary: the process must end by
/// itself with 2 (never a signal such as the abort of a failed 8 TB
/// allocation), print one `error:` line and leave no output.
#[test]
fn the_binary_refuses_huge_claims_and_broken_headers_without_a_signal() {
    let dir = scratch("bin");
    let files = [
        npy(1, &dict("'<f8'", "False", "(1000000000000,)"), &[0x3F; 192]),
        npy(1, &dict("'<f4'", "True", "(1000000, 1000000)"), &[0x3F; 16]),
        npy(2, &dict("'|O'", "False", "(6,)"), b"\x80\x04\x95 pickle"),
        npy(
            1,
            &dict("__import__('os').system('true')", "False", "(6,)"),
            &[0; 48],
        ),
        {
            let mut f = npy(2, "{}", &[]);
            f[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
            f
        },
    ];
    let bin = env!("CARGO_BIN_EXE_splinelab");
    let good = dir.join("six.npy");
    std::fs::write(&good, f64_npy("(6,)", &[0.5, -1.0, 2.0, 0.25, 3.0, 1.5])).unwrap();
    let good = good.to_str().unwrap();
    for (k, bytes) in files.iter().enumerate() {
        let f = dir.join(format!("h{k}.npy"));
        std::fs::write(&f, bytes).unwrap();
        let f = f.to_str().unwrap();
        let out = dir.join(format!("o{k}.npy"));
        let out = out.to_str().unwrap();
        for args in [
            vec!["prefilter", "--input", f, "--degree", "3", "--output", out],
            vec![
                "interpolate",
                "--input",
                f,
                "--degree",
                "3",
                "--at",
                good,
                "--output",
                out,
            ],
            vec!["check", "prefilter", "--samples", good, "--coeffs", f],
        ] {
            let run = Command::new(bin).args(&args).output().unwrap();
            let stderr = String::from_utf8_lossy(&run.stderr);
            assert_eq!(run.status.code(), Some(2), "{args:?}: {stderr}");
            assert!(
                stderr.starts_with("error: cannot read") && stderr.trim_end().lines().count() == 1,
                "{args:?}: {stderr}"
            );
            assert!(!Path::new(out).exists(), "{args:?} left {out}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Big-endian and Fortran-ordered files are read as numpy reads them: the
/// values in C order, bit for bit (the expected values are the ones the
/// bytes were made from, by hand, not by the reader).
#[test]
fn big_endian_and_fortran_order_files_read_the_values_numpy_would() {
    use splinelab_reports::array_io::read_array;
    let dir = scratch("orders");
    // Logical 2×3 array [[1, 2, 3], [4, 5, 6]] / 8.
    let c_order = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0].map(|x: f64| x / 8.0);
    let f_order = [1.0, 4.0, 2.0, 5.0, 3.0, 6.0].map(|x: f64| x / 8.0);
    let be: Vec<u8> = c_order.iter().flat_map(|x| x.to_be_bytes()).collect();
    let le_f: Vec<u8> = f_order.iter().flat_map(|x| x.to_le_bytes()).collect();
    let be_f32: Vec<u8> = f_order
        .iter()
        .flat_map(|&x| (x as f32).to_be_bytes())
        .collect();
    for (name, bytes) in [
        ("be.npy", npy(1, &dict("'>f8'", "False", "(2, 3)"), &be)),
        ("f.npy", npy(1, &dict("'<f8'", "True", "(2, 3)"), &le_f)),
        (
            "bef32.npy",
            npy(2, &dict("'>f4'", "True", "(2, 3)"), &be_f32),
        ),
    ] {
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        let a = read_array(&p).unwrap();
        assert_eq!(a.shape, vec![2, 3], "{name}");
        assert_eq!(a.data, c_order.to_vec(), "{name}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
