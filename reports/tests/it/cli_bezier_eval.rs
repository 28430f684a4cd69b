//! `splinelab bezier-eval` end to end: `--reference` against a closed form,
//! and one JSON schema in every precision.

use crate::common;
use common::json_ok;
use rug::{Float, Rational};
use serde_json::Value;

/// `(1 − 2t)^n = ((1 − t) − t)^n` has the Bernstein coefficients `(−1)^i`.
/// Written to a fresh file per call (tests run in parallel).
fn alternating_input(n: usize, t: &[f64]) -> String {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let coeffs: Vec<f64> = (0..=n)
        .map(|i| if i % 2 == 0 { 1.0 } else { -1.0 })
        .collect();
    let dir = std::env::temp_dir().join(format!("splinelab_cli_bezier_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("input{k}.json"));
    let doc = serde_json::json!({"coeffs": coeffs, "t": t});
    std::fs::write(&path, doc.to_string()).unwrap();
    path.to_string_lossy().into_owned()
}

fn parse(v: &Value) -> Float {
    Float::with_val(
        1024,
        Float::parse(v.as_str().expect("a decimal string")).unwrap(),
    )
}

/// `(1 − 2t)^n` of the double `t`, exactly.
fn closed_form(n: usize, t: f64) -> Rational {
    let base = Rational::from(1) - Rational::from(2) * Rational::from_f64(t).unwrap();
    let mut p = Rational::from(1);
    for _ in 0..n {
        p *= &base;
    }
    p
}

#[test]
fn reference_and_digits_agree_with_the_closed_form() {
    let (n, ts) = (20, [0.1, 0.3, 0.45, 0.49]);
    let input = alternating_input(n, &ts);
    let path = input.as_str();
    for (method, prec) in [
        ("decasteljau", "f64"),
        ("power", "f64"),
        ("power", "128"),
        ("vs", "256"),
    ] {
        let v = json_ok(&[
            "bezier-eval",
            "--input",
            path,
            "--method",
            method,
            "--prec",
            prec,
            "--reference",
            "--json",
        ]);
        for (j, &t) in ts.iter().enumerate() {
            let exact = Float::with_val(1024, &closed_form(n, t));
            let reference = parse(&v["reference"][j]);
            let rel_ref = Float::with_val(1024, &reference - &exact).abs() / exact.clone().abs();
            assert!(
                rel_ref < 1e-15,
                "{method} {prec} t={t}: reference {reference}"
            );
            // The digits follow from the printed value and the closed form.
            let value = parse(&v["values"][j]);
            let rel = Float::with_val(1024, &value - &exact).abs() / exact.clone().abs();
            let got = v["digits"][j].as_f64().unwrap();
            let want = if rel.is_zero() {
                f64::INFINITY
            } else {
                -rel.log10().to_f64()
            };
            // Clamped to 0 ..= the digits the precision carries.
            let carried = match prec {
                "f64" => 17.0,
                b => (b.parse::<f64>().unwrap() * 2f64.log10()).ceil() + 1.0,
            };
            let want = want.clamp(0.0, carried);
            assert!(
                (want - got).abs() <= 0.05,
                "{method} {prec} t={t}: digits {got}, the value has {want}"
            );
            // The running bound covers the true error.
            let bound = parse(&v["bounds"][j]);
            assert!(
                Float::with_val(1024, &value - &exact).abs() <= bound,
                "{method} {prec} t={t}"
            );
        }
    }
}

#[test]
fn near_the_root_the_power_form_loses_what_de_casteljau_keeps() {
    // At t = 0.45, (1 − 2t)^20 = 1e−20 while the monomial coefficients reach 2^20·C(20,10).
    let input = alternating_input(20, &[0.45]);
    let path = input.as_str();
    let digits = |m: &str| {
        json_ok(&[
            "bezier-eval",
            "--input",
            path,
            "--method",
            m,
            "--reference",
            "--json",
        ])["digits_min"]
            .as_f64()
            .unwrap()
    };
    let (dc, pw) = (digits("decasteljau"), digits("power"));
    assert!(dc > 10.0 && pw < 3.0, "de Casteljau {dc}, power {pw}");
}

#[test]
fn one_schema_in_every_precision() {
    let input = alternating_input(5, &[0.25, 1.5]);
    let path = input.as_str();
    let keys = |v: &Value| v.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
    let a = json_ok(&[
        "bezier-eval",
        "--input",
        path,
        "--method",
        "decasteljau",
        "--json",
    ]);
    let b = json_ok(&[
        "bezier-eval",
        "--input",
        path,
        "--method",
        "decasteljau",
        "--prec",
        "200",
        "--json",
    ]);
    assert_eq!(keys(&a), keys(&b));
    for v in [&a, &b] {
        for key in ["values", "bounds"] {
            assert!(
                v[key].as_array().unwrap().iter().all(Value::is_string),
                "{key}: {v}"
            );
        }
    }
    assert_eq!(a["extrapolated"], serde_json::json!([false, true]));
}
