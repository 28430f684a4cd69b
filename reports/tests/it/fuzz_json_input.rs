//! A proptest-driven fuzz harness for the JSON input parsers of
//! `bezier-eval`, `qi`, `flatten` and `deform`: random bytes, random
//! mutations and truncations of valid input files, random JSON values of
//! random shapes, and the commands' own keys holding random values. Each
//! text goes through the command's parser and, when it parses, through the
//! command's f64 computation. Nothing may panic (proptest fails the case);
//! a parse failure must be a `CliError::Input` naming the file; a result
//! may not carry a NaN (serde_json writes one as `null`); an accepted
//! deformation reports the residual an independent MPFR evaluation finds.

use nalgebra::Vector3;
use proptest::prelude::*;
use serde_json::{Value, json};
use splinelab::scalar::prelude::*;
use splinelab::surface_deformation::inverse_mapping::SampleGrid;
use splinelab::surface_deformation::patch::{Patch, PatchGrid};
use splinelab_reports::cli::prec::Prec;
use splinelab_reports::cli::{bezier_eval, deform, flatten, qi};
use splinelab_reports::error::CliError;
use splinelab_verify::bezier_eval::Method;
use std::path::{Path, PathBuf};

/// Cases per property.
const CASES: u32 = 256;

/// The file name every parse error must carry.
const FILE: &str = "fuzz-input.json";

fn file() -> &'static Path {
    Path::new(FILE)
}

/// A parse result is the value or an input error about [`FILE`].
fn parsed<T>(r: Result<T, CliError>) -> Result<Option<T>, TestCaseError> {
    match r {
        Ok(v) => Ok(Some(v)),
        Err(CliError::Input { path, why }) => {
            prop_assert_eq!(path, PathBuf::from(FILE));
            prop_assert!(!why.is_empty());
            Ok(None)
        }
        Err(e) => Err(TestCaseError::fail(format!("not an input error: {e:?}"))),
    }
}

/// No `null` anywhere in `v` (a NaN or infinity turned into JSON).
fn no_null(v: &Value) -> Result<(), TestCaseError> {
    match v {
        Value::Null => Err(TestCaseError::fail("a null (NaN) in the output")),
        Value::Array(a) => a.iter().try_for_each(no_null),
        Value::Object(m) => m.values().try_for_each(no_null),
        _ => Ok(()),
    }
}

/// A decimal string of a finite number (never "NaN" or "inf").
fn finite(s: &str) -> Result<(), TestCaseError> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(()),
        _ => Err(TestCaseError::fail(format!("not a finite number: {s}"))),
    }
}

fn fuzz_bezier_eval(text: &str) -> Result<(), TestCaseError> {
    let Some(input) = parsed(bezier_eval::parse_input(file(), text))? else {
        return Ok(());
    };
    // Degree ≤ 10⁴ is accepted; keep the fuzzer fast with small ones.
    if input.coeffs.len() > 64 || input.t.len() > 64 {
        return Ok(());
    }
    for method in Method::all() {
        if let Ok(rows) = bezier_eval::evaluate::<f64>(&input, method, Prec::F64) {
            for r in rows {
                finite(&r.value)?;
                finite(&r.bound)?;
            }
        }
    }
    Ok(())
}

fn fuzz_qi(text: &str) -> Result<(), TestCaseError> {
    let Some(input) = parsed(qi::parse_input(file(), text))? else {
        return Ok(());
    };
    if input.points.len() > 8 {
        return Ok(());
    }
    let args = qi::QiArgs {
        input: PathBuf::from(FILE),
        prec: Prec::F64,
        damped: input.points.len() % 2 == 0,
        max_iter: 30,
        json: true,
        budget: Default::default(),
    };
    if let Ok((obj, None)) = qi::solve::<f64>(&input, &args) {
        no_null(&obj)?;
    }
    Ok(())
}

fn fuzz_flatten(text: &str) -> Result<(), TestCaseError> {
    let Some(points) = parsed(flatten::parse_points(file(), text))? else {
        return Ok(());
    };
    if points.len() > 16 {
        return Ok(());
    }
    let methods = [
        flatten::FlattenMethod::Greedy,
        flatten::FlattenMethod::Subdivision,
    ];
    for (tol, method) in [1e-1, 1e-4]
        .into_iter()
        .flat_map(|t| methods.map(|m| (t, m)))
    {
        if let Ok(out) = flatten::flatten_points(&points, tol, method, true) {
            no_null(&out)?;
            // The contract: within the tolerance itself (the polyline aims
            // inside it by the evaluation's error bound).
            prop_assert!(out["max_deviation"].as_f64().unwrap() <= tol);
        }
    }
    Ok(())
}

fn fuzz_deform(text: &str) -> Result<(), TestCaseError> {
    let Some(input) = parsed(deform::parse_input(file(), text))? else {
        return Ok(());
    };
    if input.degree > 6 || input.patches.len() > 4 {
        return Ok(());
    }
    let Ok(out) = deform::compute(input.clone(), file()) else {
        return Ok(());
    };
    // The reported residual is checked against the same distance computed
    // independently in 256-bit MPFR from the f64 inputs and the deformed
    // control points (exact widening): they differ only by the f64
    // evaluation's rounding, `≤ 64 (n + 1)² u · scale`.
    let (indep, scale) = mpfr_residual(&input, out.deformed(), out.samples());
    let n = input.degree as f64;
    let slack = 64.0 * (n + 1.0) * (n + 1.0) * f64::EPSILON * scale;
    prop_assert!(
        (out.residual() - indep).abs() <= slack,
        "reported residual {} vs independent {indep} (slack {slack})",
        out.residual()
    );
    Ok(())
}

/// `(max |R'(u_a, v_b) − R(u_a, v_b) − F_ab|, max |coordinate|)` in 256-bit
/// MPFR over every patch and sample (samples `u`-major, as the flows).
fn mpfr_residual(
    input: &deform::DeformInput,
    deformed: &PatchGrid<f64>,
    samples: &SampleGrid<f64>,
) -> (f64, f64) {
    type M = Mp<256>;
    let widen = |p: &[Vector3<f64>]| -> Vec<Vector3<M>> {
        p.iter().map(|q| q.map(M::from_f64_exact)).collect()
    };
    let (mut worst, mut scale) = (0f64, 0f64);
    for (k, after) in deformed.patches().iter().enumerate() {
        let before: Vec<Vector3<f64>> =
            input.patches[k].iter().map(|c| Vector3::from(*c)).collect();
        let pb = Patch::new(input.degree, widen(&before)).unwrap();
        let pa = Patch::new(input.degree, widen(after.control())).unwrap();
        let mut j = 0;
        for u in samples.u() {
            for v in samples.v() {
                let (u, v) = (M::from_f64_exact(*u), M::from_f64_exact(*v));
                let f = Vector3::from(input.flow[k][j]).map(M::from_f64_exact);
                let d = pa.eval(&u, &v).unwrap() - pb.eval(&u, &v).unwrap() - f;
                worst = worst.max(d.norm().to_f64());
                j += 1;
            }
        }
        for q in before.iter().chain(after.control()) {
            scale = scale.max(q.amax());
        }
        scale = scale.max(
            input.flow[k]
                .iter()
                .flatten()
                .fold(0.0, |a, x| a.max(x.abs())),
        );
    }
    (worst, scale)
}

/// Every parser (and computation) on one text.
fn fuzz_all(text: &str) -> Result<(), TestCaseError> {
    fuzz_bezier_eval(text)?;
    fuzz_qi(text)?;
    fuzz_flatten(text)?;
    fuzz_deform(text)
}

/// A valid degree-1 `deform` input (one bilinear patch lifted by 1) and a
/// degree-3 one with explicit samples.
fn deform_seeds() -> [String; 2] {
    let bilinear: Vec<[f64; 3]> = (0..4)
        .map(|k| [(k / 2) as f64, (k % 2) as f64, 0.0])
        .collect();
    let bicubic: Vec<[f64; 3]> = (0..16)
        .map(|k| [(k / 4) as f64 / 3.0, (k % 4) as f64 / 3.0, 0.0])
        .collect();
    let lift = |n: usize| vec![[0.0, 0.0, 0.5]; n];
    [
        json!({"degree": 1, "nu": 1, "nv": 1, "patches": [bilinear],
               "samples": {"family": "equispaced"}, "flow": [lift(4)], "correct": false})
        .to_string(),
        json!({"degree": 3, "nu": 1, "nv": 1, "patches": [bicubic],
               "samples": {"u": [0, 0.25, 0.75, 1], "v": [0, 0.3, 0.6, 1]},
               "flow": [lift(16)], "solver": "full-lu", "correct": true})
        .to_string(),
    ]
}

/// Valid input files of the four commands (their formats are in each
/// command's doc).
fn seeds() -> Vec<String> {
    let mut v: Vec<String> = [
        r#"{"coeffs": [1, -2.5, 3e-3, 0.1], "t": [0, 0.25, 0.5, 1, 1.5, -0.5]}"#,
        r#"{"coeffs": [1], "t": [0.5]}"#,
        r#"{"points": [[0, 0, 0], [1, 0, 0.5], [1, 1, 1], [0, 1, 1.5]]}"#,
        r#"{"points": [[1, 0, 0], [0, 1, "0.1"], [-1, 0, "1e-3"]], "start_tangent": [0, 1, 0], "end_tangent": [0, -1, 0]}"#,
        r#"{"points": [[0, 0], [1, 2], [2, 0]]}"#,
        r#"{"points": [[1, 0, 0], [1, 1, 0.5], [0, 1, 1], [-1, 1, 1.5]]}"#,
    ]
    .map(String::from)
    .to_vec();
    v.extend(deform_seeds());
    v
}

/// Tokens a mutation may splice in: specials JSON cannot hold, values at the
/// edges of f64 and usize, wrong types, structure.
const TOKENS: &[&str] = &[
    "1e999",
    "-1e400",
    "1e-400",
    "-0",
    "0",
    "1",
    "2",
    "31",
    "1e308",
    "5e-324",
    "18446744073709551616",
    "-1",
    "0.5",
    "\"NaN\"",
    "\"inf\"",
    "\"0.1\"",
    "\"x\"",
    "null",
    "true",
    "[]",
    "{}",
    "[0,0]",
    "[0,0,0]",
    "[[0,0,0]]",
    ",",
    ":",
    "[",
    "]",
    "{",
    "}",
    "\"",
    "\\",
    "\u{0}",
    "\u{feff}",
    "é",
];

/// One edit of a text.
#[derive(Debug, Clone)]
enum Edit {
    Truncate(usize),
    Delete(usize, usize),
    Insert(usize, &'static str),
    Replace(usize, usize, &'static str),
    Duplicate(usize, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    let token = proptest::sample::select(TOKENS);
    prop_oneof![
        any::<usize>().prop_map(Edit::Truncate),
        (any::<usize>(), 1..8usize).prop_map(|(a, n)| Edit::Delete(a, n)),
        (any::<usize>(), token.clone()).prop_map(|(a, t)| Edit::Insert(a, t)),
        (any::<usize>(), 1..6usize, token).prop_map(|(a, n, t)| Edit::Replace(a, n, t)),
        (any::<usize>(), 1..12usize).prop_map(|(a, n)| Edit::Duplicate(a, n)),
    ]
}

/// The char boundary at or below `k`, clamped to the text.
fn floor(s: &str, k: usize) -> usize {
    let mut k = k.min(s.len());
    while !s.is_char_boundary(k) {
        k -= 1;
    }
    k
}

fn apply(s: &mut String, e: &Edit) {
    let pick = |s: &str, a: usize| floor(s, a % (s.len() + 1));
    match *e {
        Edit::Truncate(a) => s.truncate(pick(s, a)),
        Edit::Insert(a, t) => s.insert_str(pick(s, a), t),
        Edit::Delete(a, n) | Edit::Replace(a, n, _) | Edit::Duplicate(a, n) => {
            let start = pick(s, a);
            let end = floor(s, start + n);
            match *e {
                Edit::Delete(..) => s.replace_range(start..end, ""),
                Edit::Replace(.., t) => s.replace_range(start..end, t),
                _ => {
                    let span = s[start..end].to_string();
                    s.insert_str(end, &span)
                }
            }
        }
    }
}

/// A random JSON value of random shape (depth ≤ 4).
fn json_value() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        any::<i64>().prop_map(|i| json!(i)),
        any::<f64>().prop_map(|x| json!(x)),
        (-3.0..3.0f64).prop_map(|x| json!(x)),
        "[a-z0-9.e+-]{0,8}".prop_map(Value::String),
        proptest::sample::select(vec!["nan", "inf", "-inf", "0.1", "1/3"]).prop_map(|s| json!(s)),
    ];
    leaf.prop_recursive(4, 64, 8, |inner| {
        prop_oneof![
            proptest::collection::vec(inner.clone(), 0..8).prop_map(Value::Array),
            proptest::collection::btree_map(key(), inner, 0..6)
                .prop_map(|m| Value::Object(m.into_iter().collect())),
        ]
    })
}

/// The keys the commands read, and a few others.
fn key() -> impl Strategy<Value = String> {
    proptest::sample::select(vec![
        "coeffs",
        "t",
        "points",
        "start_tangent",
        "end_tangent",
        "degree",
        "nu",
        "nv",
        "patches",
        "samples",
        "flow",
        "solver",
        "correct",
        "family",
        "u",
        "v",
        "x",
    ])
    .prop_map(String::from)
}

/// Every JSON pointer in `v` (the root included).
fn pointers(v: &Value, at: String, out: &mut Vec<String>) {
    match v {
        Value::Array(a) => a
            .iter()
            .enumerate()
            .for_each(|(i, x)| pointers(x, format!("{at}/{i}"), out)),
        Value::Object(m) => m
            .iter()
            .for_each(|(k, x)| pointers(x, format!("{at}/{k}"), out)),
        _ => {}
    }
    out.push(at);
}

/// The pointers of the numbers in `v`.
fn number_pointers(v: &Value) -> Vec<String> {
    let mut all = Vec::new();
    pointers(v, String::new(), &mut all);
    all.retain(|p| v.pointer(p).is_some_and(Value::is_number));
    all
}

/// A finite number of any magnitude, an edge value, or a small one.
fn number() -> impl Strategy<Value = Value> {
    use proptest::num::f64::{NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
    prop_oneof![
        (POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO).prop_map(|x| json!(x)),
        (-4.0..4.0f64).prop_map(|x| json!(x)),
        (0..40u64).prop_map(|n| json!(n)),
        proptest::sample::select(vec![json!(0), json!(1), json!(u64::MAX), json!(i64::MIN)]),
    ]
}

/// One structural edit of a parsed input.
#[derive(Debug, Clone)]
enum Tweak {
    /// Replace the node with a value.
    Set(usize, Value),
    /// Remove the node from its array or object.
    Remove(usize),
    /// Repeat the node in its array.
    Repeat(usize),
}

/// Numbers at the edges of what the commands accept, or any value.
fn replacement() -> impl Strategy<Value = Value> {
    let edge = proptest::sample::select(vec![
        json!(0),
        json!(-0.0),
        json!(1),
        json!(2),
        json!(3),
        json!(30),
        json!(31),
        json!(-1),
        json!(0.5),
        json!(1.5),
        json!(1e-300),
        json!(1e300),
        json!(f64::MAX),
        json!(5e-324),
        json!(u64::MAX),
        json!("nan"),
        json!("1e99999"),
        json!([]),
        json!([0.5, 0.5]),
    ]);
    prop_oneof![3 => edge, 1 => json_value()]
}

fn tweak() -> impl Strategy<Value = Tweak> {
    prop_oneof![
        3 => (any::<usize>(), replacement()).prop_map(|(i, v)| Tweak::Set(i, v)),
        1 => any::<usize>().prop_map(Tweak::Remove),
        1 => any::<usize>().prop_map(Tweak::Repeat),
    ]
}

/// Applies `t` to `doc` (a no-op where the node has no parent of the kind).
fn apply_tweak(doc: &mut Value, t: &Tweak) {
    let mut all = Vec::new();
    pointers(doc, String::new(), &mut all);
    let (Tweak::Set(i, _) | Tweak::Remove(i) | Tweak::Repeat(i)) = t;
    let at = all[i % all.len()].clone();
    let (parent, last) = at.rsplit_once('/').unwrap_or(("", ""));
    if let Tweak::Set(_, v) = t {
        *doc.pointer_mut(&at).expect("listed") = v.clone();
        return;
    }
    let Some(parent) = doc.pointer_mut(parent) else {
        return;
    };
    match (parent, last.parse::<usize>()) {
        (Value::Array(a), Ok(k)) if matches!(t, Tweak::Repeat(_)) => a.insert(k, a[k].clone()),
        (Value::Array(a), Ok(k)) => drop(a.remove(k)),
        (Value::Object(m), _) if matches!(t, Tweak::Remove(_)) => drop(m.remove(last)),
        _ => {}
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..256)) {
        fuzz_all(&String::from_utf8_lossy(&bytes))?;
    }

    #[test]
    fn mutated_valid_inputs_never_panic(
        seed in proptest::sample::select(seeds()),
        edits in proptest::collection::vec(edit(), 1..5),
    ) {
        let mut text = seed;
        for e in &edits {
            apply(&mut text, e);
        }
        fuzz_all(&text)?;
    }

    #[test]
    fn structurally_tweaked_valid_inputs_never_panic(
        seed in proptest::sample::select(seeds()),
        tweaks in proptest::collection::vec(tweak(), 1..4),
    ) {
        let mut doc: Value = serde_json::from_str(&seed).unwrap();
        for t in &tweaks {
            apply_tweak(&mut doc, t);
        }
        fuzz_all(&doc.to_string())?;
    }

    #[test]
    fn valid_inputs_with_numbers_replaced_never_panic(
        seed in proptest::sample::select(seeds()),
        changes in proptest::collection::vec((any::<usize>(), number()), 1..4),
    ) {
        let mut doc: Value = serde_json::from_str(&seed).unwrap();
        let numbers = number_pointers(&doc);
        for (i, x) in changes {
            *doc.pointer_mut(&numbers[i % numbers.len()]).expect("listed") = x;
        }
        fuzz_all(&doc.to_string())?;
    }

    #[test]
    fn random_json_values_never_panic(v in json_value()) {
        fuzz_all(&v.to_string())?;
    }

    #[test]
    fn command_keys_with_random_values_never_panic(
        m in proptest::collection::btree_map(key(), json_value(), 1..5),
    ) {
        fuzz_all(&Value::Object(m.into_iter().collect()).to_string())?;
    }
}

/// The seeds themselves are valid, so the mutations start from inputs that
/// reach the computations.
#[test]
fn the_seeds_parse() {
    let s = seeds();
    assert!(bezier_eval::parse_input(file(), &s[0]).is_ok());
    assert!(bezier_eval::parse_input(file(), &s[1]).is_ok());
    assert!(qi::parse_input(file(), &s[2]).is_ok());
    assert!(qi::parse_input(file(), &s[3]).is_ok());
    assert!(flatten::parse_points(file(), &s[4]).is_ok());
    assert!(flatten::parse_points(file(), &s[5]).is_ok());
    for d in &s[6..] {
        let input = deform::parse_input(file(), d).unwrap();
        assert!(deform::compute(input, file()).is_ok(), "{d}");
    }
}
