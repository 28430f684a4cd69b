//! `splinelab prefilter`, `interpolate` and `width --emit` from the command
//! line, against independent references: the committed scipy 1.17.1
//! fixtures (verify/fixtures/scipy, made by make_fixtures.py there), the
//! interpolation condition in exact rationals for `--prec 256`, the cubic's
//! closed form `c_i = √3 (√3 − 2)^i` for emitted tables, and the system C
//! compiler and rustc reading the emitted source back.

use crate::common::{self, splinelab as run, stdout_ok as ok};
use ndarray::ArrayD;
use ndarray_npy::{ReadNpyExt, WriteNpyExt};
use rug::ops::Pow;
use rug::{Float, Rational};
use splinelab_verify::metrics::ulps_of_max;
use std::path::{Path, PathBuf};
use std::process::Command;

const MODES: [&str; 5] = ["mirror", "reflect", "grid-wrap", "nearest", "grid-constant"];
/// scipy's `cval` in the fixtures.
const CVAL: &str = "0.7";
/// Prefilter agreement, ulps of max|c| (as verify/tests/engine_scipy.rs).
const ULPS: f64 = 8.0;
/// map_coordinates agreement, ulps of max|value| (scipy's own error reaches ~70).
const MAP_ULPS: f64 = 96.0;

fn fixture(name: &str) -> PathBuf {
    [
        env!("CARGO_MANIFEST_DIR"),
        "..",
        "verify",
        "fixtures",
        "scipy",
        &format!("{name}.npy"),
    ]
    .iter()
    .collect()
}

fn read_f64(path: &Path) -> ArrayD<f64> {
    ArrayD::<f64>::read_npy(std::fs::File::open(path).unwrap()).unwrap()
}

fn tmpdir(tag: &str) -> PathBuf {
    common::tmpdir("cli_engine", tag)
}

/// Runs `cmd --input X <degree flag> --mode M --cval CVAL <rest…> --output
/// out` (the shape of every scipy-fixture run) and reads what it wrote.
fn engine_run(
    cmd: &str,
    input: &Path,
    degree: [&str; 2],
    mode: &str,
    rest: &[&str],
    out: &Path,
) -> ArrayD<f64> {
    let mut args = vec![
        cmd,
        "--input",
        input.to_str().unwrap(),
        degree[0],
        degree[1],
    ];
    args.extend(["--mode", mode, "--cval", CVAL]);
    args.extend(rest);
    args.extend(["--output", out.to_str().unwrap()]);
    ok(&args);
    read_f64(out)
}

/// max |a − b| / (ε max|b|).
fn ulps(a: &ArrayD<f64>, b: &ArrayD<f64>) -> f64 {
    assert_eq!(a.shape(), b.shape());
    ulps_of_max(a, b)
}

#[test]
fn prefilter_matches_scipy_fixtures() {
    let dir = tmpdir("pf");
    let out = dir.join("c.npy");
    let mut worst = 0.0f64;
    // (fixture, input, axis): reflect only on the 37-sample line, where
    // scipy's reflect rule is right (it is wrong on short lines).
    for (fx, input, axis) in [
        ("f1", "x1", None),
        ("g2", "x2", Some("0")),
        ("f2", "x2", None),
        ("f3", "x3", None),
    ] {
        for mode in MODES {
            if mode == "reflect" && fx != "f1" {
                continue;
            }
            for d in 2..=5 {
                let ds = d.to_string();
                let rest = axis.map_or(vec![], |a| vec!["--axis", a]);
                let got = engine_run(
                    "prefilter",
                    &fixture(input),
                    ["--degree", &ds],
                    mode,
                    &rest,
                    &out,
                );
                let u = ulps(&got, &read_f64(&fixture(&format!("{fx}_{mode}_{d}"))));
                assert!(u <= ULPS, "{fx} {mode} {d}: {u:.1} ulps");
                worst = worst.max(u);
            }
        }
    }
    eprintln!("prefilter CLI vs scipy: worst {worst:.2} ulps of max|c|");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn interpolate_matches_scipy_map_coordinates() {
    let dir = tmpdir("ip");
    let out = dir.join("v.npy");
    let mut worst = 0.0f64;
    for mode in MODES {
        for k in 1..=3 {
            for d in 1..=5u32 {
                if mode == "reflect" && k > 1 && d > 1 {
                    continue; // scipy's reflect prefilter is wrong on these short axes
                }
                let (x, p) = (fixture(&format!("x{k}")), fixture(&format!("p{k}_{mode}")));
                let ds = d.to_string();
                // Degree by scipy's order for some, by our order m for others.
                let m = (d + 1).to_string();
                let by = if d % 2 == 0 {
                    ["--degree", &ds]
                } else {
                    ["--order", &m]
                };
                let at = ["--at", p.to_str().unwrap()];
                let got = engine_run("interpolate", &x, by, mode, &at, &out);
                let want = read_f64(&fixture(&format!("m{k}_{mode}_{d}")));
                let u = ulps(&got, &want);
                assert!(u <= MAP_ULPS, "m{k} {mode} {d}: {u:.1} ulps");
                worst = worst.max(u);
            }
        }
    }
    eprintln!("interpolate CLI vs scipy: worst {worst:.2} ulps of max|value|");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Parses the decimal strings of a `--prec` JSON output exactly.
/// `interpolate --coeffs` (scipy's `prefilter=False`) at degrees 0..=5 in
/// every mode, and degree 0 without `--coeffs` (no prefilter at degree 0,
/// as in scipy), against scipy's map_coordinates on the `x{k}` arrays
/// taken as coefficients (fixtures `n{k}_{mode}_{d}` at points `q{k}`):
/// degree 0 bit for bit, others within the rounding of the sums.
#[test]
fn interpolate_given_coefficients_and_degree_0_match_scipy() {
    let dir = tmpdir("ipc");
    let out = dir.join("v.npy");
    let o = out.to_str().unwrap();
    for mode in MODES {
        for k in 1..=3 {
            let (x, q) = (fixture(&format!("x{k}")), fixture(&format!("q{k}")));
            for d in 0..=5u32 {
                let ds = d.to_string();
                let mut rest = vec!["--at", q.to_str().unwrap()];
                if d > 0 {
                    rest.push("--coeffs");
                }
                let got = engine_run("interpolate", &x, ["--degree", &ds], mode, &rest, &out);
                let want = read_f64(&fixture(&format!("n{k}_{mode}_{d}")));
                if d == 0 {
                    assert_eq!(got, want, "n{k} {mode} degree 0");
                } else {
                    let u = ulps(&got, &want);
                    assert!(u <= 16.0, "n{k} {mode} {d}: {u:.1} ulps");
                }
            }
        }
    }
    // --tol has no meaning without a prefilter: exit 2, no output left.
    std::fs::remove_file(&out).unwrap();
    let (x, q) = (fixture("x1"), fixture("q1"));
    let args = [
        "interpolate",
        "--input",
        x.to_str().unwrap(),
        "--degree",
        "3",
        "--coeffs",
        "--tol",
        "1e-8",
        "--at",
        q.to_str().unwrap(),
        "--output",
        o,
    ];
    let r = run(&args);
    assert_eq!(
        r.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&r.stderr)
    );
    assert!(String::from_utf8_lossy(&r.stderr).contains("--coeffs"));
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

fn json_values(path: &Path) -> (Vec<usize>, Vec<Rational>) {
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let shape = v["shape"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap() as usize)
        .collect();
    let values = v["values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let f = Float::parse(s.as_str().unwrap()).unwrap();
            Float::with_val(1024, f).to_rational().unwrap()
        })
        .collect();
    (shape, values)
}

/// The cubic interpolation condition `(c_{k−1} + 4 c_k + c_{k+1})/6 = s_k`
/// holds in exact rationals on the `--prec 256` output, to the digits
/// printed (far below any f64 error), for mirror and grid-wrap ends.
#[test]
fn prec_256_json_satisfies_the_cubic_condition_exactly() {
    let dir = tmpdir("prec");
    let out = dir.join("c.json");
    let x = fixture("x1");
    let s: Vec<f64> = read_f64(&x).iter().copied().collect();
    let n = s.len();
    for (mode, ext) in [("mirror", 0), ("grid-wrap", 1)] {
        ok(&[
            "prefilter",
            "--input",
            x.to_str().unwrap(),
            "--degree",
            "3",
            "--mode",
            mode,
            "--prec",
            "256",
            "--output",
            out.to_str().unwrap(),
        ]);
        let (shape, c) = json_values(&out);
        assert_eq!(shape, vec![n]);
        // Mirror: c_{−1} = c_1, c_n = c_{n−2}; grid-wrap: periodic.
        let at = |i: i64| -> &Rational {
            let k = if ext == 0 {
                let p = 2 * (n as i64 - 1);
                let r = i.rem_euclid(p);
                if r < n as i64 { r } else { p - r }
            } else {
                i.rem_euclid(n as i64)
            };
            &c[k as usize]
        };
        let mut worst = Rational::new();
        for k in 0..n as i64 {
            let sum = Rational::from(at(k - 1) + at(k + 1)) + Rational::from(4 * at(k));
            let r = sum / 6u32 - Rational::from_f64(s[k as usize]).unwrap();
            let r = r.abs();
            if r > worst {
                worst = r;
            }
        }
        let worst = worst.to_f64();
        assert!(worst < 1e-70, "{mode}: residual {worst:e}");
        eprintln!("--prec 256 cubic {mode}: exact residual {worst:e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `splinelab prefilter --degree 3 --mode mirror` of `input` into `out`
/// (`--prec p`, or `--compute float32` for `f32`, when given); its text
/// output.
fn prefilter_cubic_mirror(input: &Path, out: &Path, prec: Option<&str>) -> String {
    let mut args = vec![
        "prefilter",
        "--input",
        input.to_str().unwrap(),
        "--degree",
        "3",
        "--mode",
        "mirror",
        "--output",
        out.to_str().unwrap(),
    ];
    match prec {
        Some("f32") => args.extend(["--compute", "float32"]),
        Some(p) => args.extend(["--prec", p]),
        None => {}
    }
    ok(&args)
}

/// f32 in, f32 out: computed in f64 by default and rounded once, within
/// half an f32 ulp of max|c| (plus f64's rounding) of the same samples
/// filtered in 256-bit MPFR, each value within one ulp of its own;
/// `--compute float32` within a few f32 ulps (times the cubic's
/// amplification 3).
#[test]
fn f32_input_gives_f32_output_within_f32_ulps() {
    let dir = tmpdir("f32");
    let input = dir.join("x.npy");
    let x32 = read_f64(&fixture("x2")).mapv(|v| v as f32);
    x32.write_npy(std::fs::File::create(&input).unwrap())
        .unwrap();
    let (o64, o32, o256) = (
        dir.join("c64.npy"),
        dir.join("c32.npy"),
        dir.join("c256.json"),
    );
    for (out, prec, says) in [
        (&o64, None, "in f64"),
        (&o32, Some("f32"), "in f32"),
        (&o256, Some("256"), "in 256"),
    ] {
        let text = prefilter_cubic_mirror(&input, out, prec);
        assert!(text.contains(says), "{text}");
    }
    let (shape, want) = json_values(&o256);
    let max = want.iter().map(|w| w.to_f64().abs()).fold(0.0, f64::max);
    for (out, allowed) in [(&o64, 0.5 + 1e-6), (&o32, 16.0)] {
        let got = ArrayD::<f32>::read_npy(std::fs::File::open(out).unwrap()).unwrap();
        assert_eq!(got.shape(), &shape[..]);
        let err = got
            .iter()
            .zip(&want)
            .map(|(g, w)| (f64::from(*g) - w.to_f64()).abs())
            .fold(0.0, f64::max);
        let u = err / (max * f64::from(f32::EPSILON));
        assert!(u <= allowed, "{out:?}: {u} f32 ulps");
        eprintln!("f32 CLI prefilter ({out:?}) vs MPFR: {u:.2} f32 ulps of max|c|");
    }
    let got = ArrayD::<f32>::read_npy(std::fs::File::open(&o64).unwrap()).unwrap();
    for (g, w) in got.iter().zip(&want) {
        let w = w.to_f64();
        let ulp =
            f64::from((w as f32).abs()).max(f64::from(f32::MIN_POSITIVE)) * f64::from(f32::EPSILON);
        assert!((f64::from(*g) - w).abs() <= ulp, "{g} vs {w}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// scipy's float32 `spline_filter1d` (computed in f64 internally, cast to
/// f32; committed by verify/fixtures/scipy/make_check_fixtures.py): ours by
/// default and with `--prec f64` (computed in f64, rounded once to f32)
/// within one f32 ulp of max|c|, with `--compute float32` within a few.
#[test]
fn f32_prefilter_matches_scipy_float32_fixture() {
    let dir = tmpdir("f32scipy");
    let out = dir.join("c.npy");
    let x = fixture("prefilter/samples_f32");
    let want =
        ArrayD::<f32>::read_npy(std::fs::File::open(fixture("prefilter/d3_mirror_f32")).unwrap())
            .unwrap();
    let max = want.iter().fold(0.0f32, |m, v| m.max(v.abs()));
    for (prec, allowed) in [(None, 1.0), (Some("f32"), 8.0f32), (Some("f64"), 1.0)] {
        prefilter_cubic_mirror(&x, &out, prec);
        let got = ArrayD::<f32>::read_npy(std::fs::File::open(&out).unwrap()).unwrap();
        let err = got
            .iter()
            .zip(&want)
            .fold(0.0f32, |m, (g, w)| m.max((g - w).abs()));
        let u = err / (max * f32::EPSILON);
        assert!(u <= allowed, "{prec:?}: {u} f32 ulps of max|c|");
        eprintln!("f32 CLI ({prec:?}) vs scipy float32: {u:.2} f32 ulps of max|c|");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--tol`: the width and bound are printed, and the result stays within
/// bound·max|s| (per axis, 1-D here) of the exact one.
#[test]
fn truncated_prefilter_stays_within_its_printed_bound() {
    let dir = tmpdir("tol");
    let (exact, trunc) = (dir.join("e.npy"), dir.join("t.npy"));
    let x = fixture("x1");
    let xs = x.to_str().unwrap();
    ok(&[
        "prefilter",
        "--input",
        xs,
        "--degree",
        "5",
        "--output",
        exact.to_str().unwrap(),
    ]);
    for tol in ["1e-4", "1e-8"] {
        let text = ok(&[
            "prefilter",
            "--input",
            xs,
            "--degree",
            "5",
            "--tol",
            tol,
            "--output",
            trunc.to_str().unwrap(),
        ]);
        let line = text
            .lines()
            .find(|l| l.starts_with("bound per axis"))
            .unwrap();
        let bound: f64 = line.split_whitespace().nth(3).unwrap().parse().unwrap();
        assert!(bound < tol.parse::<f64>().unwrap() && bound > 0.0, "{text}");
        assert!(text.contains("half-width n ="), "{text}");
        let smax = read_f64(&x).iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = (&read_f64(&trunc) - &read_f64(&exact)).mapv(f64::abs);
        let worst = diff.iter().fold(0.0f64, |m, v| m.max(*v));
        assert!(
            worst <= bound * smax + 1e-14,
            "tol {tol}: {worst:e} > {bound:e}"
        );
        // 37 samples: the truncated route runs the exact recursion here
        // (difference 0, within the bound); its blocks, which differ, are
        // tested on long lines in verify/tests/engine_properties.rs.
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Degree 99 in f64 is refused with the estimate and a precision to use;
/// with that precision it runs.
#[test]
fn ill_conditioned_degree_suggests_a_precision() {
    let dir = tmpdir("ill");
    let out = dir.join("c.npy");
    let x = fixture("x1");
    let o = run(&[
        "prefilter",
        "--input",
        x.to_str().unwrap(),
        "--degree",
        "99",
        "--output",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("ill-conditioned") && err.contains("--prec"),
        "{err}"
    );
    assert!(!out.exists());
    let bits: u32 = err
        .split("--prec ")
        .nth(1)
        .and_then(|t| t.split(|c: char| !c.is_ascii_digit()).next())
        .and_then(|b| b.parse().ok())
        .unwrap();
    ok(&[
        "prefilter",
        "--input",
        x.to_str().unwrap(),
        "--degree",
        "99",
        "--prec",
        &bits.max(64).to_string(),
        "--output",
        out.to_str().unwrap(),
    ]);
    let c = read_f64(&out);
    assert!(c.iter().all(|v| v.is_finite()));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The cubic's c_i = √3 (√3 − 2)^i in 512-bit MPFR.
fn cubic_c(i: usize) -> Float {
    let s3 = Float::with_val(512, 3).sqrt();
    let r = Float::with_val(512, &s3 - 2u32);
    s3 * r.pow(i as u32)
}

/// The cubic table c_0..c_{count−1}, each rounded once to f64.
fn cubic_closed_form(count: usize) -> Vec<f64> {
    (0..count).map(|i| cubic_c(i).to_f64()).collect()
}

fn cc() -> Option<String> {
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    Command::new(&cc).arg("--version").output().ok().map(|_| cc)
}

/// The C header compiles; a program printing the table with %.17g gives
/// back exactly the correctly rounded closed-form values (cubic).
#[test]
fn emitted_c_header_compiles_and_reproduces_the_table() {
    let Some(cc) = cc() else {
        eprintln!("SKIPPED: no C compiler (cc) found; set CC to run this test");
        return;
    };
    let dir = tmpdir("c");
    let h = dir.join("tbl.h");
    ok(&[
        "width",
        "--order",
        "4",
        "--tol",
        "1e-10",
        "--emit",
        "c",
        "--name",
        "tbl",
        "--output",
        h.to_str().unwrap(),
    ]);
    let header = std::fs::read_to_string(&h).unwrap();
    for needle in [
        "splinelab",
        "#define TBL_HALF_WIDTH",
        "static const double tbl_coeffs[",
        "bound",
        "1e-10",
    ] {
        assert!(header.contains(needle), "{needle}: {header}");
    }
    let prog = dir.join("main.c");
    std::fs::write(
        &prog,
        "#include <stdio.h>\n#include \"tbl.h\"\nint main(void) {\n  for (int i = 0; i <= TBL_HALF_WIDTH; i++) printf(\"%.17g\\n\", tbl_coeffs[i]);\n  return 0;\n}\n",
    )
    .unwrap();
    let exe = dir.join("main");
    let o = Command::new(&cc)
        .args(["-std=c99", "-Wall", "-Werror", "-o"])
        .arg(&exe)
        .arg(&prog)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let printed = String::from_utf8(Command::new(&exe).output().unwrap().stdout).unwrap();
    let got: Vec<f64> = printed.lines().map(|l| l.parse().unwrap()).collect();
    let n: usize = header
        .split("#define TBL_HALF_WIDTH ")
        .nth(1)
        .and_then(|t| t.split_whitespace().next())
        .and_then(|t| t.parse().ok())
        .unwrap();
    assert_eq!(got.len(), n + 1);
    assert!(n > 10, "cubic at 1e-10 needs more than 10 coefficients");
    assert_eq!(got, cubic_closed_form(got.len()));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The Rust items compile with rustc and print back the closed form
/// exactly; the f32 table is the closed form rounded once to f32.
#[test]
fn emitted_rust_compiles_and_reproduces_the_table() {
    let dir = tmpdir("rs");
    let items = ok(&[
        "width", "--order", "4", "--tol", "1e-6", "--emit", "rust", "--name", "cubic",
    ]);
    assert!(
        items.contains("pub const CUBIC_HALF_WIDTH: usize"),
        "{items}"
    );
    let src = dir.join("main.rs");
    std::fs::write(
        &src,
        format!(
            "{items}\nfn main() {{\n    for c in CUBIC_COEFFS {{ println!(\"{{c:e}}\"); }}\n}}\n"
        ),
    )
    .unwrap();
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let exe = dir.join("main");
    let o = Command::new(&rustc)
        .args(["--edition", "2021", "-D", "warnings", "-o"])
        .arg(&exe)
        .arg(&src)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let printed = String::from_utf8(Command::new(&exe).output().unwrap().stdout).unwrap();
    let got: Vec<f64> = printed.lines().map(|l| l.parse().unwrap()).collect();
    assert_eq!(got, cubic_closed_form(got.len()));
    // f32: the closed form in MPFR rounded once to binary32.
    let npy = dir.join("c.npy");
    ok(&[
        "width",
        "--order",
        "4",
        "--tol",
        "1e-6",
        "--emit",
        "npy",
        "--dtype",
        "f32",
        "--output",
        npy.to_str().unwrap(),
    ]);
    let c32 = ArrayD::<f32>::read_npy(std::fs::File::open(&npy).unwrap()).unwrap();
    for (i, c) in c32.iter().enumerate() {
        assert_eq!(*c, cubic_c(i).to_f32(), "c_{i}");
    }
    assert_eq!(c32.len(), got.len());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Issue 17: the support radius has its unit, and a width met only by the
/// measured error says which number to trust and the certified width.
#[test]
fn width_explains_bound_above_tolerance() {
    for order in ["4", "8"] {
        for tol in ["1e-2", "1e-3", "1e-5", "1e-9"] {
            let args = ["width", "--order", order, "--tol", tol];
            let text = ok(&args);
            assert!(text.contains(" samples"), "{text}");
            let mut json_args = args.to_vec();
            json_args.push("--json");
            let v: serde_json::Value = serde_json::from_str(&ok(&json_args)).unwrap();
            assert_eq!(v["support_radius_unit"], "samples");
            let tol: f64 = tol.parse().unwrap();
            let above = v["bound"].as_f64().unwrap() >= tol;
            assert_eq!(v["bound_meets_tol"], !above);
            if above {
                assert!(text.contains("guarantees it from n ="), "{text}");
                assert!(v["certified_bound"].as_f64().unwrap() < tol);
                assert!(v["certified_n"].as_u64().unwrap() > v["n"].as_u64().unwrap());
            } else {
                assert!(v["certified_n"].is_null());
            }
        }
    }
}
