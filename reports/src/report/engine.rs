//! Report section "engine": the N-D interpolation engine against
//! scipy.ndimage's committed outputs (verify/fixtures/scipy, made once by
//! make_fixtures.py with scipy 1.17.1), the N-D prefilter's accuracy on
//! those fixtures against 256-bit MPFR beside scipy's own (agreement is not
//! accuracy), the truncated route against its
//! certified bound, the interpolation residual at high degree in MPFR
//! (judged from exact node values), missing data (scipy's all-NaN zoom
//! beside the `local` NaN policy, [`nan`]), and in-process prefilter
//! throughput.

mod nan;

use super::{Figure, Profile, ReportError, Section, TIME_BAND};
use crate::array_io::read_samples;
use crate::chart::{Chart, Series, line_chart};
use crate::error::CliError;
use crate::html::{num, paragraph, table};
use ndarray::{Array2, ArrayD};
use serde_json::json;
use splinelab::prelude::*;
use splinelab_verify::interpolation_residual::residual;
use splinelab_verify::metrics::ulps_of_max;
use splinelab_verify::nd_prefilter::fixture_case;
use splinelab_verify::rng::SplitMix64;
use splinelab_verify::timing::{try_median_ns, try_median_ns_fresh};
use std::path::PathBuf;

/// scipy's `cval` in the fixtures.
const CVAL: f64 = 0.7;

fn fixture(name: &str) -> Result<ArrayD<f64>, ReportError> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../verify/fixtures/scipy")
        .join(format!("{name}.npy"));
    Ok(read_samples(&path)?.0)
}

fn num_err(e: NdimageError) -> CliError {
    CliError::numerical(e)
}

fn line_filter<T: Real>(
    degree: u32,
    mode: Mode,
    route: Route,
) -> Result<LineFilter<T>, ReportError> {
    LineFilter::new(&SplineFamily::Order(degree + 1), mode, CVAL, route).map_err(num_err)
}

/// Worst ulps (of max|reference|) of `spline_filter1d`, `spline_filter` and
/// `map_coordinates` over the fixtures. scipy's `reflect` prefilter is
/// wrong on lines shorter than ~20 samples, so `reflect` is
/// compared on the 37-sample line only.
fn scipy_worst() -> Result<[f64; 3], ReportError> {
    let mut worst = [0.0f64; 3];
    for mode in Mode::ALL {
        for d in 2..=5u32 {
            let f = line_filter::<f64>(d, mode, Route::Exact)?;
            let mut x1 = fixture("x1")?;
            spline_filter1d(&mut x1, 0, &f).map_err(num_err)?;
            worst[0] = worst[0].max(ulps_of_max(x1.iter(), &fixture(&format!("f1_{mode}_{d}"))?));
            if mode == Mode::Reflect {
                continue;
            }
            let mut x2 = fixture("x2")?;
            spline_filter1d(&mut x2, 0, &f).map_err(num_err)?;
            worst[0] = worst[0].max(ulps_of_max(x2.iter(), &fixture(&format!("g2_{mode}_{d}"))?));
            for k in [2, 3] {
                let mut x = fixture(&format!("x{k}"))?;
                spline_filter(&mut x, &f).map_err(num_err)?;
                worst[1] = worst[1].max(ulps_of_max(
                    x.iter(),
                    &fixture(&format!("f{k}_{mode}_{d}"))?,
                ));
            }
        }
        for k in 1..=3 {
            let x = fixture(&format!("x{k}"))?;
            let p: Array2<f64> = fixture(&format!("p{k}_{mode}"))?
                .into_dimensionality()
                .map_err(CliError::numerical)?;
            for d in 1..=5u32 {
                if mode == Mode::Reflect && k > 1 && d > 1 {
                    continue;
                }
                let opts = Options {
                    cval: CVAL,
                    ..Options::new(d, mode)
                };
                let got: Vec<f64> = map_coordinates(&x, p.t(), opts).map_err(num_err)?;
                let want = fixture(&format!("m{k}_{mode}_{d}"))?;
                worst[2] = worst[2].max(ulps_of_max(got.iter(), &want));
            }
        }
    }
    Ok(worst)
}

/// One truncated-route measurement.
struct Truncation {
    degree: u32,
    tol: f64,
    n: usize,
    bound: f64,
    error: f64,
}

/// `max|D_truncated − D_exact| / max|s|` on a 2000-sample signal, mirror.
fn truncation(degree: u32, tol: f64, s: &[f64]) -> Result<Truncation, ReportError> {
    let exact = line_filter::<f64>(degree, Mode::Mirror, Route::Exact)?;
    let trunc = line_filter::<f64>(degree, Mode::Mirror, Route::Convolution { tol })?;
    let (mut a, mut b) = (s.to_vec(), s.to_vec());
    exact.apply(&mut a, &mut Vec::new());
    trunc.apply(&mut b, &mut Vec::new());
    let smax = s.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let error = a
        .iter()
        .zip(&b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / smax;
    Ok(Truncation {
        degree,
        tol,
        n: trunc.half_width().unwrap_or(0),
        bound: trunc.bound(),
        error,
    })
}

/// Relative interpolation residual `max_j |Σ D_i β(j−i) − s_j| / max|s|` of
/// the exact mirror coefficients computed in `T`, and `max|D|`.
fn residual_in<T: Real + Send + Sync>(degree: u32, s: &[f64]) -> Result<(f64, f64), ReportError> {
    let f = line_filter::<T>(degree, Mode::Mirror, Route::Exact)?;
    let mut c: Vec<T> = s.iter().map(|x| T::from_f64_exact(*x)).collect();
    f.apply(&mut c, &mut Vec::new());
    let smax = s.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let dmax = c.iter().fold(0.0f64, |m, x| m.max(x.to_f64().abs()));
    let r = residual(&c, s, degree + 1, Mode::Mirror)
        .ok_or_else(|| CliError::Numerical("residual: coefficients not representable".into()))?;
    Ok((r / smax, dmax))
}

/// Median seconds of a cubic mirror `spline_filter` of `data` (fresh copy each time).
fn seconds(data: &ArrayD<f64>, repeats: usize) -> Result<f64, ReportError> {
    let f = line_filter::<f64>(3, Mode::Mirror, Route::Exact)?;
    let ns = try_median_ns_fresh(
        repeats,
        1,
        || data.clone(),
        |a, _| spline_filter(a, &f).map_err(num_err),
    )?;
    Ok(ns * 1e-9)
}

/// Median seconds of the block-parallel cubic mirror prefilter of `s`
/// (blocks of a quarter of the samples per pool thread, at least 2^15, as
/// benches/src/bin/engine_peer.rs; tolerance 1e-15) into a reused buffer.
fn block_seconds(s: &[f64], repeats: usize) -> Result<f64, ReportError> {
    let b = BlockPrefilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, 1e-15)
        .map_err(num_err)?;
    let block = (s.len() / (4 * rayon::current_num_threads())).max(1 << 15);
    let mut out = vec![0.0; s.len()];
    let ns = try_median_ns(repeats, || {
        b.apply_into(s, &mut out, block).map_err(num_err)
    })?;
    Ok(ns * 1e-9)
}

/// Median seconds of `eval_many` of a 2-D cubic mirror interpolant of `data`
/// at `count` scattered points (the pseudo-random pattern of engine_peer's
/// `eval2d`, 1/100-sample steps), into a reused buffer.
fn eval_seconds(data: &ArrayD<f64>, count: usize, repeats: usize) -> Result<f64, ReportError> {
    let f = Interpolant::new(data, Options::new(3, Mode::Mirror)).map_err(num_err)?;
    let span = (data.shape()[0] - 1) * 100;
    let pts = Array2::from_shape_fn((count, 2), |(k, a)| {
        ((k * if a == 0 { 7919 } else { 104_729 }) % span) as f64 / 100.0
    });
    let mut out = vec![0.0; count];
    let ns = try_median_ns(repeats, || {
        f.eval_many(pts.view(), &mut out).map_err(num_err)
    })?;
    Ok(ns * 1e-9)
}

/// One part of the section: its HTML, its summary JSON and its figures.
struct Part {
    html: String,
    json: serde_json::Value,
    figures: Vec<Figure>,
    charts: Vec<Chart>,
}

/// What a part shows: a paragraph, then its table.
struct Shown<'a> {
    intro: &'a str,
    title: &'a str,
    headers: &'a [&'a str],
    rows: Vec<Vec<String>>,
}

impl Part {
    /// A part of a paragraph and a table, with its summary and figures (no chart).
    fn tabled(shown: Shown, json: serde_json::Value, figures: Vec<Figure>) -> Part {
        Part {
            html: paragraph(shown.intro) + &table(shown.title, shown.headers, &shown.rows),
            json,
            figures,
            charts: vec![],
        }
    }
}

/// Agreement with scipy's committed outputs, in ulps of max|reference|.
fn scipy_part() -> Result<Part, ReportError> {
    let [f1d, fnd, map] = scipy_worst()?;
    let figures = [
        ("spline_filter1d", f1d),
        ("spline_filter", fnd),
        ("map_coordinates", map),
    ]
    .into_iter()
    .map(|(name, v)| Figure::error(format!("engine.scipy.{name}.worst_ulps"), v, "ulps", 0.5))
    .collect();
    let rows = vec![
        vec![
            "spline_filter1d (1-D; 2-D axis 0)".into(),
            "2–5".into(),
            num(f1d),
        ],
        vec!["spline_filter (2-D, 3-D)".into(), "2–5".into(), num(fnd)],
        vec![
            "map_coordinates (1-D, 2-D, 3-D)".into(),
            "1–5".into(),
            num(map),
        ],
    ];
    let json = json!({"spline_filter1d": f1d, "spline_filter": fnd, "map_coordinates": map});
    Ok(Part::tabled(
        Shown {
            intro: "The N-D engine (splinelab prefilter / interpolate, and the library's spline_filter, spline_filter1d, \
         map_coordinates) against scipy 1.17.1's own outputs (committed fixtures), in ulps of the largest \
         reference value. scipy's reflect prefilter starts its recursion from a truncated sum and is off \
         (5e-9 for a cubic on 7 samples) on lines shorter than about 20 samples, so reflect is compared on \
         the 37-sample line only; map_coordinates differences up to ~70 ulps are scipy's own: for \
         nearest and grid-constant it pads 12 samples and filters the padded line instead of computing \
         the exact spline of the extended signal. Agreement is not accuracy: the next table judges both \
         against 256-bit MPFR.",
            title: "Agreement with scipy.ndimage",
            headers: &["function", "degrees", "worst ulps of max|ref|"],
            rows,
        },
        json,
        figures,
    ))
}

/// One mode and degree of the fixtures' `spline_filter` against 256-bit
/// MPFR: the worst over x2 and x3, in ulps of max|D*| of each format.
struct MpfrRow {
    mode: Mode,
    degree: u32,
    f64: f64,
    f32: f64,
    scipy: f64,
}

/// One column of [`MpfrRow`] (ours f64, ours f32, scipy).
type Column = fn(&MpfrRow) -> f64;

/// Every mode and degree 2–5 of the fixtures x2 (9×11) and x3 (5×6×7):
/// the engine's `spline_filter` in f64 and f32 and scipy's committed
/// output, each against the same 256-bit MPFR reference
/// (`splinelab_verify::nd_prefilter`).
fn mpfr_rows() -> Result<Vec<MpfrRow>, ReportError> {
    let xs = [(2, fixture("x2")?), (3, fixture("x3")?)];
    let mut rows = vec![];
    for mode in Mode::ALL {
        for degree in 2..=5u32 {
            let mut row = MpfrRow {
                mode,
                degree,
                f64: 0.0,
                f32: 0.0,
                scipy: 0.0,
            };
            for (k, x) in &xs {
                let scipy = fixture(&format!("f{k}_{mode}_{degree}"))?;
                let case = fixture_case(x, &scipy, degree, mode, CVAL).map_err(num_err)?;
                row.f64 = row.f64.max(case.f64.error);
                row.f32 = row.f32.max(case.f32.error);
                row.scipy = row.scipy.max(case.scipy);
            }
            rows.push(row);
        }
    }
    Ok(rows)
}

/// Accuracy of the N-D prefilter against MPFR, ours beside scipy's: a
/// figure per degree and format (the worst over the modes; scipy's without
/// `reflect`, which it gets wrong on short lines).
fn mpfr_part() -> Result<Part, ReportError> {
    let rows = mpfr_rows()?;
    let worst = |degree: u32, pick: Column, reflect: bool| {
        rows.iter()
            .filter(|r| r.degree == degree && (reflect || r.mode != Mode::Reflect))
            .map(pick)
            .fold(0.0f64, f64::max)
    };
    let columns: [(&str, Column, bool); 3] = [
        ("f64", |r| r.f64, true),
        ("f32", |r| r.f32, true),
        ("scipy", |r| r.scipy, false),
    ];
    let (mut figures, mut summary, mut table_rows) = (vec![], serde_json::Map::new(), vec![]);
    for (name, pick, reflect) in columns {
        let mut per_degree = serde_json::Map::new();
        for degree in 2..=5u32 {
            let v = worst(degree, pick, reflect);
            per_degree.insert(format!("d{degree}"), json!(v));
            figures.push(Figure::error(
                format!("engine.mpfr.spline_filter.{name}.d{degree}.worst_ulps"),
                v,
                "ulps",
                0.5,
            ));
        }
        summary.insert(name.into(), serde_json::Value::Object(per_degree));
    }
    for r in &rows {
        let scipy = if r.mode == Mode::Reflect {
            format!("{} (short-line defect)", num(r.scipy))
        } else {
            num(r.scipy)
        };
        table_rows.push(vec![
            r.mode.to_string(),
            r.degree.to_string(),
            num(r.f64),
            scipy,
            num(r.f32),
        ]);
    }
    for degree in 2..=5u32 {
        table_rows.push(vec![
            "worst (scipy: without reflect)".into(),
            degree.to_string(),
            num(worst(degree, |r| r.f64, true)),
            num(worst(degree, |r| r.scipy, false)),
            num(worst(degree, |r| r.f32, true)),
        ]);
    }
    let cases: Vec<_> = rows
        .iter()
        .map(|r| json!({"mode": r.mode.to_string(), "degree": r.degree, "f64": r.f64, "f32": r.f32, "scipy": r.scipy}))
        .collect();
    let json = json!({"worst": summary, "cases": cases});
    Ok(Part::tabled(
        Shown {
            intro: "Agreement with scipy is not accuracy: two results can each be a few ulps off the exact \
         coefficients in different directions. Here the same fixtures' spline_filter (x2, 9×11; x3, 5×6×7; \
         worst of the two) are judged against the exact coefficients, computed in 256-bit MPFR by the same \
         recursive filter run line by line along each axis: the engine in f64, in f32 (samples rounded to f32, f32 ulps), and scipy 1.17.1's \
         committed f64 output, all in ulps of the largest reference value. scipy's reflect outputs start short \
         lines from a truncated sum (left out of its worst). The contract, every mode and degree 2–5 in f64 and \
         f32 within 64 u D A^D max(|s|, |cval|) of the reference, is verify/tests/it/nd_prefilter_mpfr.rs.",
            title: "N-D prefilter against 256-bit MPFR: ours and scipy's",
            headers: &[
                "mode",
                "degree",
                "ours f64 (ulps of max|D*|)",
                "scipy f64",
                "ours f32 (f32 ulps)",
            ],
            rows: table_rows,
        },
        json,
        figures,
    ))
}

/// The truncated route against the exact one and its certified bound.
fn truncation_part() -> Result<Part, ReportError> {
    let s = SplitMix64::new(7).signal(2000);
    let (mut rows, mut json_rows, mut figures) = (vec![], vec![], vec![]);
    for degree in [3u32, 5, 9] {
        for tol in [1e-4, 1e-8, 1e-12] {
            let t = truncation(degree, tol, &s)?;
            rows.push(vec![
                t.degree.to_string(),
                num(t.tol),
                t.n.to_string(),
                num(t.bound),
                num(t.error),
                num(t.error / t.bound),
            ]);
            json_rows.push(json!({"degree": t.degree, "tol": t.tol, "n": t.n, "bound": t.bound, "error": t.error}));
            if tol >= 1e-8 {
                figures.push(Figure::error(
                    format!("engine.truncated.d{degree}.tol{tol:e}.error_over_bound"),
                    t.error / t.bound,
                    "ratio",
                    0.05,
                ));
            }
        }
    }
    Ok(Part::tabled(
        Shown {
            intro: "Truncated prefilter (certified width for a tolerance) against the exact one, 2000 samples in [−1, 1), \
             mirror: the error must stay below the certified bound (ratio ≤ 1).",
            title: "Truncated vs exact",
            headers: &[
                "degree",
                "tol",
                "half-width n",
                "bound",
                "max error / max|s|",
                "error / bound",
            ],
            rows,
        },
        json!(json_rows),
        figures,
    ))
}

/// The interpolation residual at high degree, in MPFR and in f64.
fn residual_part(profile: &Profile) -> Result<Part, ReportError> {
    let degrees: &[u32] = profile.pick(&[7, 15, 31], &[7, 15, 31, 57, 99]);
    let s48 = SplitMix64::new(5).signal(48);
    let (mut rows, mut json_rows, mut figures) = (vec![], vec![], vec![]);
    for &degree in degrees {
        let (r256, _) = residual_in::<Mp<256>>(degree, &s48)?;
        let f64_res = if degree <= 31 {
            let (r, dmax) = residual_in::<f64>(degree, &s48)?;
            Some(r / (f64::EPSILON * dmax))
        } else {
            None
        };
        figures.push(Figure::digits(
            format!("engine.residual.mp256.d{degree}.digits"),
            -r256.log10(),
            "digits",
            1.0,
        ));
        if let Some(u) = f64_res {
            figures.push(Figure::error(
                format!("engine.residual.f64.d{degree}.eps_of_max_d"),
                u,
                "ε·max|D|",
                2.0,
            ));
        }
        rows.push(vec![
            degree.to_string(),
            num(r256),
            f64_res.map_or("refused (ill-conditioned)".into(), num),
        ]);
        json_rows
            .push(json!({"degree": degree, "mp256_relative": r256, "f64_eps_of_max_d": f64_res}));
    }
    Ok(Part::tabled(
        Shown {
            intro: "Interpolation residual max_j |Σ D_i β(j−i) − s_j| / max|s| at high degree, 48 samples, mirror, judged \
             in 512-bit MPFR from the exact node values; f64 in units of ε·max|D| (above degree 31 f64 is refused \
             as ill-conditioned).",
            title: "Interpolation residual",
            headers: &[
                "degree",
                "256-bit relative residual",
                "f64 residual / (ε·max|D|)",
            ],
            rows,
        },
        json!(json_rows),
        figures,
    ))
}

/// Median seconds of a plain copy of `elements` f64 into a reused buffer:
/// the memory wall each route is measured against.
fn memcpy_seconds(elements: usize, repeats: usize) -> Result<f64, ReportError> {
    let src = vec![1.0f64; elements];
    let mut dst = vec![0.0f64; elements];
    let ns = try_median_ns(repeats, || {
        dst.copy_from_slice(std::hint::black_box(&src));
        Ok::<_, CliError>(())
    })?;
    Ok(ns * 1e-9)
}

/// One timed route at one size, beside a plain copy of the same bytes.
struct RouteTime {
    name: &'static str,
    label: String,
    seconds: f64,
    copy: f64,
    /// Samples filtered, or points evaluated.
    samples: usize,
    /// Bytes the copy moves: the array (filters) or the points' coordinates (evaluation).
    copy_bytes: usize,
}

/// The four routes at a 1-D size `n1` and a 2-D size `n2 × n2`.
fn route_times(n1: usize, n2: usize, reps: usize) -> Result<Vec<RouteTime>, ReportError> {
    let one = ArrayD::from_shape_vec(vec![n1], SplitMix64::new(1).signal(n1))
        .map_err(CliError::numerical)?;
    let two = ArrayD::from_shape_vec(vec![n2, n2], SplitMix64::new(2).signal(n2 * n2))
        .map_err(CliError::numerical)?;
    let points = n2 * n2;
    let threads = rayon::current_num_threads();
    // Each distinct copy timed once: the array (n1 serves both 1-D routes,
    // n2² the 2-D filter) or the evaluation's coordinates (2 per point).
    let (c1, c2, ce) = (
        memcpy_seconds(n1, reps)?,
        memcpy_seconds(points, reps)?,
        memcpy_seconds(2 * points, reps)?,
    );
    let timed = [
        (
            "filter1d_cubic",
            format!("1-D, {n1} samples"),
            seconds(&one, reps)?,
            n1,
            (c1, n1),
        ),
        (
            "filter2d_cubic",
            format!("2-D, {n2}×{n2}"),
            seconds(&two, reps)?,
            points,
            (c2, points),
        ),
        (
            "blocks1d_cubic",
            format!("1-D, {n1} samples, certified blocks ({threads} threads)"),
            block_seconds(one.as_slice().expect("standard layout"), reps)?,
            n1,
            (c1, n1),
        ),
        (
            "eval2d_cubic",
            format!("evaluation, {points} points on {n2}×{n2}"),
            eval_seconds(&two, points, reps)?,
            points,
            (ce, 2 * points),
        ),
    ];
    Ok(timed
        .into_iter()
        .map(
            |(name, label, seconds, samples, (copy, copied))| RouteTime {
                name,
                label,
                seconds,
                copy,
                samples,
                copy_bytes: 8 * copied,
            },
        )
        .collect())
}

/// Time / copy against the bytes moved, a line per route over the sizes
/// measured, with the wall (a plain copy: ratio 1) drawn across.
fn wall_chart(sizes: &[Vec<RouteTime>]) -> Chart {
    let mut series: Vec<Series> = sizes[0]
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let points = sizes
                .iter()
                .map(|at| (at[k].copy_bytes as f64 / 1e6, at[k].seconds / at[k].copy))
                .collect();
            Series::line_points(r.name, points)
        })
        .collect();
    let mb: Vec<f64> = sizes
        .iter()
        .flatten()
        .map(|r| r.copy_bytes as f64 / 1e6)
        .collect();
    let (lo, hi) = (
        mb.iter().cloned().fold(f64::INFINITY, f64::min),
        mb.iter().cloned().fold(0.0, f64::max),
    );
    series.push(Series::line(
        "plain copy of the same bytes",
        vec![(lo, 1.0), (hi, 1.0)],
    ));
    line_chart(
        "engine_time_over_copy",
        "Each route's time over a plain copy of the same bytes",
        "MB copied (the array, or the points' coordinates)",
        "time / copy",
        true,
        series,
        "How far each route is from the memory wall at each size: 1 would be as fast as copying the bytes \
         once; the certified blocks use every thread, the other routes as measured in the table.",
    )
    .with_log_x()
}

/// Throughput of the routes, each beside a plain copy of the same bytes.
fn throughput_part(profile: &Profile) -> Result<Part, ReportError> {
    let (n1, n2, reps) = *profile.pick(&(100_000, 256, 3), &(1_000_000, 1024, 5));
    let sizes = [
        route_times(n1 / 4, n2 / 2, reps)?,
        route_times(n1, n2, reps)?,
    ];
    let cases = &sizes[1];
    let figures = cases
        .iter()
        .map(|r| {
            Figure::cost(
                format!("engine.throughput.{}.seconds", r.name),
                r.seconds,
                "s",
                TIME_BAND,
            )
            .with_floor(1e-3)
        })
        .collect();
    let rows: Vec<Vec<String>> = cases
        .iter()
        .map(|r| {
            vec![
                r.label.clone(),
                num(r.seconds),
                num(r.samples as f64 / r.seconds / 1e6),
                num(r.copy),
                num(r.seconds / r.copy),
            ]
        })
        .collect();
    let [t1, t2, tb, te] = [0, 1, 2, 3].map(|k| cases[k].seconds);
    let json = json!({"filter1d_seconds": t1, "n1": n1, "filter2d_seconds": t2, "n2": n2,
        "blocks1d_seconds": tb, "eval2d_seconds": te, "eval2d_points": n2 * n2,
        "memcpy_seconds": {"n1": cases[0].copy, "n2_squared": cases[1].copy, "eval2d_points": cases[3].copy}});
    let shown = Shown {
        intro: "In-process throughput of the cubic mirror prefilter, sequential per line and in certified blocks \
         (tolerance 1e-15), and of batch evaluation of the 2-D interpolant at scattered points (median wall \
         time, all threads; Msamples/s counts points for the evaluation), each beside a plain copy of the \
         same bytes on the same machine in the same run (the array for the filters, the points' coordinates \
         for the evaluation; one thread): time / copy says how far each route is from the memory wall. \
         Ratios to scipy: benches/peers/scipy_ratio.py.",
        title: "Prefilter and evaluation throughput",
        headers: &[
            "case",
            "seconds",
            "Msamples/s",
            "copy of the same bytes (s)",
            "time / copy",
        ],
        rows,
    };
    let mut part = Part::tabled(shown, json, figures);
    part.charts.push(wall_chart(&sizes));
    Ok(part)
}

/// Runs the engine studies and presents them.
pub fn section(profile: &Profile) -> Result<Section, ReportError> {
    let scipy = scipy_part()?;
    let mpfr = mpfr_part()?;
    let truncated = truncation_part()?;
    let residual = residual_part(profile)?;
    let missing = nan::part()?;
    let throughput = throughput_part(profile)?;
    let html = [&scipy, &mpfr, &truncated, &residual, &missing, &throughput]
        .iter()
        .map(|p| p.html.as_str())
        .collect();
    let summary = json!({
        "scipy_worst_ulps": scipy.json,
        "mpfr_spline_filter_ulps": mpfr.json,
        "truncated": truncated.json,
        "residual": residual.json,
        "nan_local": missing.json,
        "throughput": throughput.json,
    });
    let parts = [scipy, mpfr, truncated, residual, missing, throughput];
    let charts = parts.iter().flat_map(|p| p.charts.clone()).collect();
    let figures = parts.into_iter().flat_map(|p| p.figures).collect();
    Ok(Section {
        id: "engine",
        title: "The interpolation engine: scipy agreement, accuracy against MPFR, certified truncation, high degrees, missing data"
            .into(),
        html,
        charts,
        summary,
        figures,
    })
}
