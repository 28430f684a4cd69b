//! `splinelab interpolate` on the local route (issue 45): a `.npy` is
//! memory-mapped and only the windows are read. References: the engine's
//! global route (the whole-array interpolant, an independent computation)
//! within the local route's stated bound; a file above the input limit is
//! refused by the global route but evaluated by the local one.

use super::common::{cubic_at, stdout_ok, tmpdir};
use ndarray::{Array1, Array2};
use ndarray_npy::{read_npy, write_npy};
use splinelab::prelude::*;
use std::path::Path;
use std::process::{Command, Output};

fn setup(tag: &str) -> (std::path::PathBuf, Array2<f64>, Array2<f64>) {
    let dir = tmpdir("cli_local", tag);
    let data = Array2::from_shape_fn((600, 700), |(i, j)| {
        ((i * 31 + j * 17) % 97) as f64 / 48.5 - 1.0
    });
    let points = Array2::from_shape_fn((25, 2), |(k, a)| {
        let x = (k * 7919 + a * 104729) % 1000;
        x as f64 * if a == 0 { 0.6 } else { 0.7 } - 2.5
    });
    write_npy(dir.join("a.npy"), &data).unwrap();
    write_npy(dir.join("at.npy"), &points).unwrap();
    (dir, data, points)
}

fn global(data: &Array2<f64>, points: &Array2<f64>, mode: Mode) -> Vec<f64> {
    let f = Interpolant::new(data, Options::new(3, mode)).unwrap();
    let mut out = vec![0.0; points.nrows()];
    f.eval_many(points.view(), &mut out).unwrap();
    out
}

#[test]
fn a_memory_mapped_npy_takes_the_local_route_within_its_bound() {
    let (dir, data, points) = setup("route");
    let (input, at) = (dir.join("a.npy"), dir.join("at.npy"));
    for mode in ["mirror", "nearest", "grid-wrap"] {
        let out = dir.join(format!("v_{mode}.npy"));
        let text = stdout_ok(&cubic_at(&input, &at, mode, &out));
        assert!(
            text.contains("route            local (memory-mapped)"),
            "{text}"
        );
        let got: Array1<f64> = read_npy(&out).unwrap();
        let want = global(&data, &points, mode.parse().unwrap());
        // Cubic, tol=None: ((A + b)² − A²)·max|s| with b < 1e-16, plus rounding.
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w).abs() <= 1e-13, "{mode}: {g} vs {w}");
        }
    }
}

/// `splinelab interpolate` of `dir/a.npy` at `dir/<at>` into `dir/v.npy`,
/// under the input limit `limit` bytes (`None`: the default).
fn interpolate_with_limit(dir: &Path, at: &str, limit: Option<&str>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_splinelab"));
    match limit {
        Some(limit) => cmd.env("SPLINELAB_MAX_INPUT_BYTES", limit),
        None => cmd.env_remove("SPLINELAB_MAX_INPUT_BYTES"),
    };
    cmd.args([
        "interpolate",
        "--input",
        dir.join("a.npy").to_str().unwrap(),
        "--at",
        dir.join(at).to_str().unwrap(),
        "--degree",
        "3",
        "--output",
        dir.join("v.npy").to_str().unwrap(),
    ])
    .output()
    .unwrap()
}

#[test]
fn a_file_above_the_input_limit_is_read_only_where_the_windows_are() {
    let (dir, data, points) = setup("limit");
    let o = interpolate_with_limit(&dir, "at.npy", Some("100000"));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let got: Array1<f64> = read_npy(dir.join("v.npy")).unwrap();
    let want = global(&data, &points, Mode::Mirror);
    assert!(got.iter().zip(&want).all(|(g, w)| (g - w).abs() <= 1e-13));
}

/// 20000 points on the 600×700 array: the local route's floor (1 µs a
/// point, `C_POINT`) is five times the global prefilter's estimate (about
/// 4 ms), so the global route runs within the input limit, decided
/// without pricing every point (`LocalPlan::new_if_local`); above the
/// limit the local route still runs, at any cost.
#[test]
fn many_points_take_the_global_route_unless_the_file_is_above_the_limit() {
    let (dir, data, _) = setup("many");
    let points = Array2::from_shape_fn((20000, 2), |(k, a)| {
        let x = (k * 7919 + a * 104729) % 10007;
        x as f64 * if a == 0 { 0.06 } else { 0.07 } - 2.5
    });
    write_npy(dir.join("many.npy"), &points).unwrap();
    let want = global(&data, &points, Mode::Mirror);
    // 1 MB: the points' file (320 kB) within the limit, the array's (3.4 MB) above it.
    for (limit, local) in [(None, false), (Some("1000000"), true)] {
        let o = interpolate_with_limit(&dir, "many.npy", limit);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = String::from_utf8(o.stdout).unwrap();
        assert_eq!(
            text.contains("route            local (memory-mapped)"),
            local,
            "{limit:?}: {text}"
        );
        let got: Array1<f64> = read_npy(dir.join("v.npy")).unwrap();
        assert_eq!(got.len(), want.len());
        assert!(
            got.iter().zip(&want).all(|(g, w)| (g - w).abs() <= 1e-13),
            "{limit:?}"
        );
    }
}
