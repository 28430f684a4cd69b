//! `splinelab cond` end to end: the JSON contract against a closed form, and
//! bad input rejected with a message and a non-zero exit, never a panic.

use crate::common;
use common::{json_ok, splinelab};
use rug::Float;
use serde_json::Value;

#[test]
fn degree_2_equispaced_matches_the_closed_form_to_all_printed_digits() {
    // A = [[1,0,0],[¼,½,¼],[0,0,1]]: AᵀA has eigenvalues 1 and (11 ± √57)/16,
    // so cond₂ = √(λ_max/λ_min) = (11 + √57)/8; A⁻¹ = [[1,0,0],[−½,2,−½],[0,0,1]] gives cond_∞ = 3.
    let out = splinelab(&[
        "cond",
        "--degree",
        "2",
        "--nodes",
        "equispaced",
        "--prec",
        "256",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "degree", "nodes", "basis", "tensor", "prec", "cond2", "cond_inf",
    ] {
        assert!(v.get(key).is_some(), "missing key {key}");
    }
    let cond2 = v["cond2"].as_str().unwrap();
    let digits = cond2.chars().filter(|c| c.is_ascii_digit()).count();
    assert!(digits >= 30, "{cond2}");
    let got = Float::with_val(512, Float::parse(cond2).unwrap());
    let want: Float = (Float::with_val(512, 57).sqrt() + 11) / 8;
    let rel = (Float::with_val(512, &got - &want) / &want).abs();
    assert!(rel < 1e-70, "{got} vs {want}");
    let cinf = Float::with_val(512, Float::parse(v["cond_inf"].as_str().unwrap()).unwrap());
    assert!(Float::with_val(512, cinf - 3).abs() < 1e-70);
}

#[test]
fn bad_input_is_a_clear_error_with_non_zero_exit() {
    // Command lines (words split at spaces) and what the error must name.
    let cases: &[(&str, &str)] = &[
        ("cond --degree 0 --nodes equispaced", "--degree"),
        ("cond --degree 501 --nodes equispaced", "--degree"),
        ("cond --degree -3 --nodes equispaced", "--degree"),
        ("cond --degree 5 --nodes chebyshev", "unknown node family"),
        (
            "cond --degree 5 --nodes equispaced --prec 15",
            "out of range: accepted 16..=2048",
        ),
        (
            "cond --degree 5 --nodes equispaced --prec 1000001",
            "out of range: accepted 16..=2048",
        ),
        ("cond --degree 5 --nodes equispaced --prec f32", "--prec"),
        (
            "cond --degree 5 --nodes equispaced --basis hermite",
            "--basis",
        ),
        ("cond --nodes equispaced", "--degree"),
    ];
    for (line, needle) in cases {
        let args: Vec<&str> = line.split(' ').collect();
        let out = splinelab(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?} printed a result");
    }
}

#[test]
fn help_explains_every_option() {
    let out = splinelab(&["cond", "--help"]);
    let text = String::from_utf8_lossy(&out.stdout);
    for opt in [
        "--degree", "--nodes", "--basis", "--tensor", "--prec", "--json",
    ] {
        assert!(text.contains(opt), "cond --help lacks {opt}");
    }
}

fn cond2_of(v: &Value) -> Float {
    Float::with_val(512, Float::parse(v["cond2"].as_str().unwrap()).unwrap())
}

/// Correct significant digits of `got` against `want`.
fn digits(got: &Float, want: &Float) -> f64 {
    let rel = Float::with_val(512, got - want).abs() / want;
    if rel.is_zero() {
        f64::INFINITY
    } else {
        -rel.log10().to_f64()
    }
}

#[test]
fn the_trust_estimate_never_promises_more_digits_than_a_512_bit_run_confirms() {
    // Monomial Vandermonde matrices on equispaced nodes: cond₂ from 5e3 to 7e9.
    for degree in ["5", "8", "12"] {
        let base = [
            "cond",
            "--degree",
            degree,
            "--nodes",
            "equispaced",
            "--basis",
            "monomial",
        ];
        let f64_run = json_ok(&[&base[..], &["--json"]].concat());
        let reference = cond2_of(&json_ok(
            &[&base[..], &["--prec", "512", "--json"]].concat(),
        ));
        let got = digits(&cond2_of(&f64_run), &reference);
        let promised = f64_run["digits_estimate"].as_f64().unwrap();
        assert!(
            promised < 16.0 && got >= promised,
            "degree {degree}: {got} < {promised}"
        );
        // The suggested precision delivers every f64 digit.
        let bits = f64_run["suggested_prec"].as_u64().unwrap().to_string();
        let suggested = json_ok(&[&base[..], &["--prec", &bits, "--json"]].concat());
        assert!(
            digits(&cond2_of(&suggested), &reference) >= 17.0,
            "degree {degree} at {bits}"
        );
    }
}

#[test]
fn a_matrix_singular_in_f64_names_a_precision_that_resolves_it() {
    let base = [
        "cond",
        "--degree",
        "20",
        "--nodes",
        "equispaced",
        "--basis",
        "monomial",
    ];
    let out = splinelab(&base);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("try --prec 128"), "{err}");
    let resolved = json_ok(&[&base[..], &["--prec", "128", "--json"]].concat());
    let reference = cond2_of(&json_ok(
        &[&base[..], &["--prec", "512", "--json"]].concat(),
    ));
    // cond₂ ≈ 8.9e16 > 1/u: beyond f64, resolved at 128 bits to what the estimate says.
    let got = digits(&cond2_of(&resolved), &reference);
    assert!(
        got >= resolved["digits_estimate"].as_f64().unwrap() && got > 15.0,
        "{got}"
    );
}
