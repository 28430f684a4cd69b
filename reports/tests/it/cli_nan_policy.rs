//! `--nan-policy` of `splinelab prefilter`, `interpolate` and `resample`
//! through the real binary (issue 37), on `.npy` samples holding NaN and
//! ±inf. The NaN pattern of every result is checked against a reference
//! written here, by brute force: the scipy modes' extension rule (each
//! index outside the grid folded to the sample it repeats), scipy's window
//! of `d + 1` coefficients per axis, and
//! - `propagate`: every line through a missing sample along each filtered
//!   axis (so, after filtering every axis at degree ≥ 2, everything);
//! - `local`: the box of half-width `n = nan_reach(d, tol) − (⌊d/2⌋ + 1)`
//!   (the certified prefilter half-width) around each missing sample,
//!   folded by the mode, then the window; no prefilter (degrees 0, 1):
//!   the window alone.
//!
//! The finite values of `local` are checked against the exact spline of
//! two fillings of the missing samples (`±max|finite|`, exact route, no
//! NaN), within the bound the run prints. Bad input: an unknown policy and
//! `raise` on a missing sample fail with exit status 2 and a clear message,
//! leaving no file; `local` without `--tol` runs at 1e-12 (the Python
//! package's default) and says so.

use crate::common::{self, splinelab as run, stdout_ok as ok};
use ndarray::{ArrayD, Dimension, IxDyn};
use ndarray_npy::{ReadNpyExt, WriteNpyExt};
use splinelab::prelude::nan_reach;
use std::path::{Path, PathBuf};

const MODES: [&str; 5] = ["mirror", "reflect", "grid-wrap", "nearest", "grid-constant"];
/// The tests' tolerance: the cubic's reach is 10 samples, leaving finite
/// outputs on a 30 × 33 grid.
const TOL: f64 = 1e-4;
const SHAPE: [usize; 2] = [30, 33];
/// NaN inside, +inf at a corner, −inf on an edge.
const MISSING: [([usize; 2], f64); 3] = [
    ([5, 7], f64::NAN),
    ([29, 0], f64::INFINITY),
    ([14, 32], f64::NEG_INFINITY),
];

fn tmpdir(tag: &str) -> PathBuf {
    common::tmpdir("cli_nan", tag)
}

fn read(path: &Path) -> ArrayD<f64> {
    ArrayD::<f64>::read_npy(std::fs::File::open(path).unwrap()).unwrap()
}

fn write(path: &Path, a: &ArrayD<f64>) {
    a.write_npy(std::fs::File::create(path).unwrap()).unwrap();
}

/// A smooth field on `SHAPE` with `MISSING` set, and its largest finite |s|.
fn samples() -> (ArrayD<f64>, f64) {
    let mut a = ArrayD::from_shape_fn(IxDyn(&SHAPE), |i| {
        let (x, y) = (i[0] as f64, i[1] as f64);
        (x / 4.0).sin() * (y / 6.0).cos() + 0.01 * x
    });
    let m = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (at, v) in MISSING {
        a[&at[..]] = v;
    }
    (a, m)
}

/// A fresh folder holding `a.npy` = [`samples`]: (folder, samples, max
/// finite |s|, the file).
fn setup(tag: &str) -> (PathBuf, ArrayD<f64>, f64, PathBuf) {
    let dir = tmpdir(tag);
    let (a, m) = samples();
    let input = dir.join("a.npy");
    write(&input, &a);
    (dir, a, m, input)
}

/// The sample a scipy mode repeats at index `t` of an axis of `len`
/// (`None`: grid-constant's constant, never missing).
fn fold(t: i64, len: usize, mode: &str) -> Option<usize> {
    let n = len as i64;
    let inside = |i: i64| Some(i as usize);
    match mode {
        _ if (0..n).contains(&t) => inside(t),
        "mirror" if n == 1 => Some(0),
        "mirror" => {
            let r = t.rem_euclid(2 * n - 2);
            inside(if r < n { r } else { 2 * n - 2 - r })
        }
        "reflect" => {
            let r = t.rem_euclid(2 * n);
            inside(if r < n { r } else { 2 * n - 1 - r })
        }
        "grid-wrap" => inside(t.rem_euclid(n)),
        "nearest" => inside(t.clamp(0, n - 1)),
        _ => None,
    }
}

/// Whether some index in `lo..=hi` repeats sample `j` of the axis.
fn hits(lo: i64, hi: i64, j: usize, len: usize, mode: &str) -> bool {
    (lo..=hi).any(|t| fold(t, len, mode) == Some(j))
}

fn missing_at(a: &ArrayD<f64>) -> Vec<Vec<usize>> {
    a.indexed_iter()
        .filter(|(_, x)| !x.is_finite())
        .map(|(i, _)| i.slice().to_vec())
        .collect()
}

/// The certified prefilter half-width: `nan_reach` less the spline's window.
fn half_width(degree: u32, tol: f64) -> i64 {
    (nan_reach(degree, tol).unwrap() - (degree as usize / 2 + 1)) as i64
}

/// scipy's window of output coordinate `x`: `lo..=lo + d`.
fn window(x: f64, degree: u32) -> (i64, i64) {
    let d = i64::from(degree);
    let lo = if degree % 2 == 1 {
        x.floor() as i64 - d / 2
    } else {
        (x + 0.5).floor() as i64 - d / 2
    };
    (lo, lo + d)
}

/// The reference pattern of an evaluation at `points` (one coordinate per
/// axis each): NaN where the window, widened by `n` (a prefilter's reach;
/// `None`: `propagate` with a prefilter, every line), meets a missing
/// sample on every axis.
fn eval_reference(
    a: &ArrayD<f64>,
    points: &[Vec<f64>],
    degree: u32,
    n: Option<i64>,
    mode: &str,
) -> Vec<bool> {
    let missing = missing_at(a);
    points
        .iter()
        .map(|x| match n {
            None => !missing.is_empty(),
            Some(n) => missing.iter().any(|j| {
                (0..x.len()).all(|ax| {
                    let (lo, hi) = window(x[ax], degree);
                    hits(lo - n, hi + n, j[ax], a.shape()[ax], mode)
                })
            }),
        })
        .collect()
}

/// The NaN pattern of `values`, asserting that degrees ≥ 2 write NaN (not
/// ±inf) where they write anything non-finite.
fn pattern(values: &[f64], degree: u32) -> Vec<bool> {
    if degree >= 2 {
        assert!(values.iter().all(|v| v.is_finite() || v.is_nan()));
    }
    values.iter().map(|v| !v.is_finite()).collect()
}

fn assert_pattern(got: &[bool], want: &[bool], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}");
    let wrong: Vec<usize> = (0..got.len()).filter(|&k| got[k] != want[k]).collect();
    assert!(
        wrong.is_empty(),
        "{what}: {} of {} differ (first at {}: got {}, want {}); {} NaN, reference {}",
        wrong.len(),
        got.len(),
        wrong[0],
        got[wrong[0]],
        want[wrong[0]],
        got.iter().filter(|b| **b).count(),
        want.iter().filter(|b| **b).count()
    );
    assert!(want.iter().any(|b| *b), "{what}: the reference has no NaN");
}

/// `prefilter`: `local` is the folded box of half-width n around each
/// missing sample along the filtered axes (its own line elsewhere);
/// `propagate` every line through one along each filtered axis; degree 1
/// (no prefilter) the missing samples alone. Every mode, degrees 1–5,
/// every axis and each axis alone.
#[test]
fn prefilter_nan_pattern_is_the_reference_dilation() {
    let (dir, a, _, input) = setup("pf");
    let out = dir.join("c.npy");
    let missing = missing_at(&a);
    for mode in MODES {
        for degree in 1..=5u32 {
            for axis in [None, Some(0usize), Some(1)] {
                for policy in ["propagate", "local"] {
                    let (d, tol) = (degree.to_string(), TOL.to_string());
                    let mut args = vec!["prefilter", "--input", input.to_str().unwrap()];
                    args.extend(["--degree", &d, "--mode", mode, "--nan-policy", policy]);
                    args.extend(["--tol", &tol, "--output", out.to_str().unwrap()]);
                    let ax = axis.map(|x| x.to_string());
                    if let Some(x) = &ax {
                        args.extend(["--axis", x]);
                    }
                    let stdout = ok(&args);
                    let c = read(&out);
                    let filtered = |k: usize| axis.is_none_or(|x| x == k);
                    let n = half_width(degree, TOL);
                    let want: Vec<bool> = c
                        .indexed_iter()
                        .map(|(i, _)| {
                            missing.iter().any(|j| {
                                (0..2).all(|k| match (filtered(k) && degree >= 2, policy) {
                                    (false, _) => i[k] == j[k],
                                    (true, "propagate") => true,
                                    (true, _) => {
                                        hits(i[k] as i64 - n, i[k] as i64 + n, j[k], SHAPE[k], mode)
                                    }
                                })
                            })
                        })
                        .collect();
                    let got = pattern(c.as_slice().unwrap(), degree);
                    let what = format!("{policy} {mode} d{degree} axis {axis:?}");
                    assert_pattern(&got, &want, &what);
                    let count = got.iter().filter(|b| **b).count();
                    assert!(
                        stdout.contains(&format!(
                            "{policy}: 3 samples not finite; {count} of {} coefficients NaN",
                            c.len()
                        )),
                        "{what}: {stdout}"
                    );
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Runs `cmd` (the subcommand and its own options) on `input` at
/// (degree, mode, policy), tol [`TOL`], and reads what it wrote to `out`.
fn run_eval(
    cmd: &[&str],
    input: &Path,
    out: &Path,
    (degree, mode, policy): (u32, &str, &str),
) -> ArrayD<f64> {
    let (d, tol) = (degree.to_string(), TOL.to_string());
    let mut args = cmd.to_vec();
    args.extend([
        "--input",
        input.to_str().unwrap(),
        "--degree",
        &d,
        "--mode",
        mode,
    ]);
    args.extend([
        "--nan-policy",
        policy,
        "--tol",
        &tol,
        "--output",
        out.to_str().unwrap(),
    ]);
    ok(&args);
    read(out)
}

/// The pattern of an evaluation `got` at `points` of samples `a` against
/// [`eval_reference`]: the prefilter's half-width under `local`, every
/// line under `propagate`, none without a prefilter (degrees 0, 1).
fn check_eval(
    got: &ArrayD<f64>,
    a: &ArrayD<f64>,
    points: &[Vec<f64>],
    (degree, mode, policy): (u32, &str, &str),
) {
    let n = match (policy, degree) {
        (_, 0 | 1) => Some(0),
        ("local", _) => Some(half_width(degree, TOL)),
        _ => None,
    };
    let want = eval_reference(a, points, degree, n, mode);
    let got = pattern(got.as_slice().unwrap(), degree);
    assert_pattern(&got, &want, &format!("{policy} {mode} d{degree}"));
}

/// Points every 3/8 sample across the grid (integers, halves and others).
fn grid_points() -> Vec<Vec<f64>> {
    let axis = |len: usize| -> Vec<f64> {
        (0..)
            .map(|k| k as f64 * 0.375)
            .take_while(|x| *x <= (len - 1) as f64)
            .collect()
    };
    let (xs, ys) = (axis(SHAPE[0]), axis(SHAPE[1]));
    xs.iter()
        .flat_map(|x| ys.iter().map(move |y| vec![*x, *y]))
        .collect()
}

/// `interpolate` at points: the pattern of both policies at degrees 0–5 in
/// every mode, and `local`'s finite values within the printed bound of the
/// exact spline of two fillings of the missing samples.
#[test]
fn interpolate_nan_pattern_and_local_values() {
    let (dir, a, m, input) = setup("interp");
    let points = grid_points();
    let flat: Vec<f64> = points.iter().flatten().copied().collect();
    let at = dir.join("p.npy");
    write(
        &at,
        &ArrayD::from_shape_vec(IxDyn(&[points.len(), 2]), flat).unwrap(),
    );
    let out = dir.join("v.npy");
    for mode in MODES {
        for degree in 0..=5u32 {
            for policy in ["propagate", "local"] {
                let cmd = ["interpolate", "--at", at.to_str().unwrap()];
                let got = run_eval(&cmd, &input, &out, (degree, mode, policy));
                check_eval(&got, &a, &points, (degree, mode, policy));
            }
        }
    }
    // Values: local beside the exact spline of the samples filled with ±m.
    for mode in MODES {
        // The cubic at the points into `out`, under `local` or `propagate`.
        let interpolate = |input: &Path, out: &Path, local: bool| {
            let mut v = common::cubic_at(input, &at, mode, out);
            if local {
                v.extend(["--nan-policy", "local", "--tol", "1e-4"]);
            }
            ok(&v)
        };
        let json = dir.join("v.json");
        interpolate(&input, &json, true);
        let doc: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        let bound = doc["local_bound"].as_f64().unwrap();
        assert_eq!(doc["nan_policy"], "local");
        assert_eq!(doc["missing_samples"], 3);
        assert_eq!(
            doc["nan_reach"].as_u64().unwrap(),
            nan_reach(3, TOL).unwrap() as u64
        );
        let local: Vec<f64> = doc["values"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s.as_str().unwrap().parse().unwrap())
            .collect();
        assert_eq!(
            doc["non_finite_outputs"].as_u64().unwrap() as usize,
            local.iter().filter(|v| v.is_nan()).count()
        );
        // The bound is the tail mass (≈ 4·A·b·m, A = 3, b < 1e-4), not zero.
        assert!(bound > 0.0 && bound < 12.0 * TOL * m, "{bound}");
        let mut worst = 0.0f64;
        for fill in [m, -m] {
            let filled = a.mapv(|x| if x.is_finite() { x } else { fill });
            let (fin, fout) = (dir.join("filled.npy"), dir.join("exact.npy"));
            write(&fin, &filled);
            interpolate(&fin, &fout, false);
            let exact = read(&fout);
            for (l, e) in local.iter().zip(exact.iter()) {
                if l.is_finite() {
                    worst = worst.max((l - e).abs());
                }
            }
        }
        assert!(worst <= bound, "{mode}: {worst:e} > bound {bound:e}");
        // The fillings differ by 2m at the missing samples: far from them
        // the exact splines agree only to the tail, which is what the bound
        // covers (so the check above is not vacuous).
        assert!(worst > 1e-3 * bound, "{mode}: {worst:e} vs {bound:e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `resample --zoom`: the pattern of both policies (scipy's zoom
/// coordinates, made here), in every mode at degrees 1–4.
#[test]
fn resample_nan_pattern_is_the_reference() {
    let (dir, a, _, input) = setup("resample");
    let out = dir.join("z.npy");
    let zoom = 1.6f64;
    let axes: Vec<Vec<f64>> = SHAPE
        .iter()
        .map(|&n| {
            let m = (n as f64 * zoom).round() as usize;
            (0..m)
                .map(|k| k as f64 * (n as f64 - 1.0) / (m as f64 - 1.0))
                .collect()
        })
        .collect();
    let points: Vec<Vec<f64>> = axes[0]
        .iter()
        .flat_map(|x| axes[1].iter().map(move |y| vec![*x, *y]))
        .collect();
    for mode in MODES {
        for degree in 1..=4u32 {
            for policy in ["propagate", "local"] {
                let z = run_eval(
                    &["resample", "--zoom", "1.6"],
                    &input,
                    &out,
                    (degree, mode, policy),
                );
                assert_eq!(z.shape(), [axes[0].len(), axes[1].len()]);
                check_eval(&z, &a, &points, (degree, mode, policy));
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An f32 input keeps f32 and the f64 run's pattern; 128-bit MPFR the
/// same pattern; the default policy is scipy's (`propagate`).
#[test]
fn f32_mpfr_and_the_default_policy_give_the_same_pattern() {
    let dir = tmpdir("types");
    let (a, _) = samples();
    let (input, input32) = (dir.join("a.npy"), dir.join("a32.npy"));
    write(&input, &a);
    a.mapv(|x| x as f32)
        .write_npy(std::fs::File::create(&input32).unwrap())
        .unwrap();
    let out = dir.join("c.npy");
    let pf = |input: &Path, extra: &[&str]| {
        let mut args = vec!["prefilter", "--input", input.to_str().unwrap()];
        args.extend(["--degree", "3", "--output", out.to_str().unwrap()]);
        args.extend(extra);
        ok(&args);
        let bytes = std::fs::read(&out).unwrap();
        let f32_file = String::from_utf8_lossy(&bytes[..64]).contains("<f4");
        let values: Vec<bool> = if f32_file {
            ArrayD::<f32>::read_npy(&bytes[..])
                .unwrap()
                .iter()
                .map(|v| !v.is_finite())
                .collect()
        } else {
            read(&out).iter().map(|v| !v.is_finite()).collect()
        };
        (f32_file, values)
    };
    let local = ["--nan-policy", "local", "--tol", "1e-4"];
    let (_, f64_local) = pf(&input, &local);
    let (is32, f32_local) = pf(&input32, &local);
    assert!(is32);
    assert_eq!(f32_local, f64_local);
    let (_, mp_local) = pf(&input, &[&local[..], &["--prec", "128"]].concat());
    assert_eq!(mp_local, f64_local);
    assert!(f64_local.iter().any(|b| !b) && f64_local.iter().any(|b| *b));
    // No flag: propagate, every coefficient NaN (scipy's spline_filter).
    let (_, default) = pf(&input, &[]);
    let (_, propagate) = pf(&input, &["--nan-policy", "propagate"]);
    assert_eq!(default, propagate);
    assert!(default.iter().all(|b| *b));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `local` without `--tol` runs at 1e-12 (the Python package's default
/// under nan_policy="local"): the same bytes as `--tol 1e-12`, and the
/// summary says which tolerance certified the reach.
#[test]
fn local_without_tol_is_local_at_1e_12() {
    let (dir, _, _, input) = setup("deftol");
    let (o1, o2) = (dir.join("1.npy"), dir.join("2.npy"));
    let run_to = |out: &Path, tol: &[&str]| {
        let mut args = vec!["resample", "--input", input.to_str().unwrap()];
        args.extend(["--zoom", "2", "--degree", "3", "--nan-policy", "local"]);
        args.extend(tol);
        args.extend(["--output", out.to_str().unwrap()]);
        ok(&args)
    };
    let stdout = run_to(&o1, &[]);
    run_to(&o2, &["--tol", "1e-12"]);
    assert_eq!(std::fs::read(&o1).unwrap(), std::fs::read(&o2).unwrap());
    let reach = nan_reach(3, 1e-12).unwrap();
    assert!(
        stdout.contains(&format!(
            "a missing sample reaches at most {reach} samples along each axis (certified for tol 1e-12)"
        )),
        "{stdout}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Bad input: an unknown policy (clap lists the engine's three names) and
/// `raise` on a missing sample (named by its index, the file too) both
/// exit with status 2 and write nothing; `raise` on finite samples runs.
#[test]
fn unknown_policy_and_raise_are_refused_clearly() {
    let (dir, a, _, input) = setup("bad");
    let finite = dir.join("finite.npy");
    write(&finite, &a.mapv(|x| if x.is_finite() { x } else { 0.0 }));
    let out = dir.join("o.npy");
    for cmd in [
        &["prefilter"][..],
        &["interpolate", "--at", input.to_str().unwrap()],
        &["resample", "--zoom", "2"],
    ] {
        let with = |input: &Path, policy: &str| {
            let mut args = cmd.to_vec();
            args.extend(["--input", input.to_str().unwrap(), "--degree", "3"]);
            args.extend(["--nan-policy", policy, "--output", out.to_str().unwrap()]);
            run(&args)
        };
        let o = with(&input, "omit");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{cmd:?}: {err}");
        assert!(
            err.contains("invalid value 'omit' for '--nan-policy")
                && err.contains("[possible values: propagate, raise, local]"),
            "{cmd:?}: {err}"
        );
        assert!(!out.exists());
        let o = with(&input, "raise");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{cmd:?}: {err}");
        assert_eq!(
            err.trim_end(),
            format!(
                "error: cannot read {}: sample [5, 7] is NaN (every sample must be finite)",
                input.display()
            ),
            "{cmd:?}"
        );
        assert!(!out.exists());
        if cmd[0] != "interpolate" {
            assert!(with(&finite, "raise").status.success(), "{cmd:?}");
            std::fs::remove_file(&out).unwrap();
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
