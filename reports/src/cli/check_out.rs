//! `check --out DIR`: an HTML page with SVG charts (the error against
//! index, against the stable bound), the per-element `reference.npy`,
//! `error.npy` and `bound.npy`, and a `summary.json`
//! whose `figures` `splinelab compare` accepts. The directory is built
//! beside its destination and renamed into place, so a reader never sees a
//! half-written one.

use super::check::Outcome;
use crate::array_io::write_npy_f64;
use crate::chart::{Chart, Series, Style, line_chart};
use crate::error::CliError;
use crate::html::{escape, num, paragraph, table};
use crate::report::Figure;
use serde_json::{Value, json};
use splinelab_verify::check::{CheckSummary, ElementError, Region};
use std::path::{Path, PathBuf};

/// Points drawn at most per chart: longer arrays are binned (max per bin).
pub const MAX_CHART_POINTS: usize = 4000;

/// Errors below this are drawn at it on the log axis.
pub const ULPS_FLOOR: f64 = 1e-3;

/// The headline figures of a check, named `check.<kind>.…`: every figure
/// is always written, so `compare` sees the same set whatever the data.
/// Errors are over the finite user values (`max_ulps` is the finite
/// maximum, 0 if there is none); the non-finite values and the elements
/// over `--max-ulps` are figures of their own (counts, lower is better), so
/// a NaN that appears is a named regression instead of a missing figure.
pub fn figures(o: &Outcome) -> Vec<Figure> {
    match o {
        Outcome::Elements(s) => element_figures(s),
        Outcome::Insertion(s) => vec![
            Figure::error(
                "check.knot-insertion.max_deviation_ulps",
                finite_or(s.max_deviation_ulps, f64::MAX),
                "ulps",
                0.5,
            ),
            Figure::error(
                "check.knot-insertion.max_deviation_rel",
                finite_or(s.max_deviation_rel, f64::MAX),
                "relative error",
                1e-16,
            ),
        ],
    }
}

fn finite_or(v: f64, or: f64) -> f64 {
    if v.is_finite() { v } else { or }
}

/// `(max, median)` of the finite errors among `ulps` (0 for none).
fn finite_stats(ulps: impl Iterator<Item = f64>) -> (f64, f64) {
    let mut u: Vec<f64> = ulps.filter(|x| x.is_finite()).collect();
    u.sort_by(f64::total_cmp);
    let median = match u.len() {
        0 => 0.0,
        n if n % 2 == 1 => u[n / 2],
        n => 0.5 * (u[n / 2 - 1] + u[n / 2]),
    };
    (u.last().copied().unwrap_or(0.0), median)
}

fn element_figures(s: &CheckSummary) -> Vec<Figure> {
    let k = &s.kind;
    let (max, median) = finite_stats(s.elements.iter().map(|e| e.ulps));
    let mut f = vec![
        Figure::digits(
            format!("check.{k}.digits_min"),
            finite_or(s.digits_min, 0.0),
            "digits",
            0.1,
        ),
        Figure::error(format!("check.{k}.max_ulps"), max, "ulps", 0.5),
        Figure::error(format!("check.{k}.median_ulps"), median, "ulps", 0.5),
        Figure::error(
            format!("check.{k}.non_finite"),
            s.non_finite as f64,
            "elements",
            0.5,
        ),
        Figure::error(
            format!("check.{k}.failed"),
            s.failed as f64,
            "elements",
            0.5,
        ),
        Figure::error(
            format!("check.{k}.over_bound"),
            s.over_bound as f64,
            "elements",
            0.5,
        ),
        Figure::error(
            format!("check.{k}.worst_excess"),
            finite_or(s.worst_excess.as_ref().map_or(0.0, |w| w.excess), f64::MAX),
            "error / stable bound",
            0.5,
        ),
    ];
    for name in s.regions.iter().flat_map(|r| r.keys()) {
        let (rmax, _) = finite_stats(
            s.elements
                .iter()
                .filter(|e| e.region.map(Region::name) == Some(name.as_str()))
                .map(|e| e.ulps),
        );
        f.push(Figure::error(
            format!("check.{k}.{name}.max_ulps"),
            rmax,
            "ulps",
            0.5,
        ));
    }
    f
}

/// Bins `(index, ulps)` to at most [`MAX_CHART_POINTS`] points per region
/// (every element when `any`)
/// (the largest error of each bin), floored at [`ULPS_FLOOR`], non-finite
/// values left out (they are counted in the caption).
fn series_of(s: &CheckSummary, region: Option<Region>, any: bool) -> Vec<(f64, f64)> {
    let pts: Vec<(f64, f64)> = s
        .elements
        .iter()
        .filter(|e| (any || e.region == region) && e.ulps.is_finite())
        .map(|e| (e.index as f64, e.ulps.max(ULPS_FLOOR)))
        .collect();
    let bin = pts.len().div_ceil(MAX_CHART_POINTS).max(1);
    pts.chunks(bin)
        .map(|c| {
            c.iter()
                .copied()
                .fold((c[0].0, 0.0), |a, p| if p.1 > a.1 { p } else { a })
        })
        .collect()
}

/// The error-against-index chart. Where the boundary zone is a range of
/// indices (`prefilter`: the first and last `h`) it is a shaded band under
/// the points; where it is not (`interp`: points near an edge) the
/// boundary points are their own series.
pub fn error_chart(s: &CheckSummary) -> Chart {
    let n = s.n as f64;
    let mut series = vec![];
    match (s.horizon, s.kind.as_str()) {
        (Some(h), "prefilter") => {
            let h = (h as f64).min(n / 2.0);
            series.push(Series::band(
                "boundary zone",
                vec![(-0.5, h - 0.5), (n - h - 0.5, n - 0.5)],
            ));
            series.push(Series::points("elements", series_of(s, None, true)));
        }
        (Some(_), _) => {
            for (r, name) in [
                (Region::Boundary, "boundary zone"),
                (Region::Interior, "interior"),
            ] {
                series.push(Series::points(name, series_of(s, Some(r), false)));
            }
        }
        (None, _) => series.push(Series::points("all elements", series_of(s, None, true))),
    }
    series.retain(|x| !x.points.is_empty());
    if series.iter().all(|x| x.style == Style::Band) {
        series.clear();
    }
    let caption = format!(
        "Error of each element in ulps of {} (log scale; below {ULPS_FLOOR} drawn at {ULPS_FLOOR}; {} non-finite values not drawn{}).",
        s.format.name(),
        s.non_finite,
        s.horizon
            .map(|h| match s.kind.as_str() {
                "interp" => format!("; boundary zone: points within {h} samples of an edge"),
                _ => format!("; boundary zone: the first and last {h} elements"),
            })
            .unwrap_or_default()
    );
    line_chart(
        "check_error_vs_index",
        &format!("check {}: error against index", s.kind),
        "index",
        "error (ulps)",
        true,
        series,
        &caption,
    )
}

/// Each element's absolute error beside `K` × its stable bound (log
/// scale, binned like [`error_chart`]): points above the line are the
/// elements the default verdict fails.
pub fn bound_chart(s: &CheckSummary) -> Chart {
    let k = s.bound_factor.unwrap_or(1.0);
    let floor = s
        .elements
        .iter()
        .filter_map(|e| e.bound)
        .filter(|b| *b > 0.0)
        .fold(f64::INFINITY, f64::min);
    let floor = if floor.is_finite() {
        floor * 1e-3
    } else {
        1e-300
    };
    let pick = |f: &dyn Fn(&ElementError) -> Option<f64>| -> Vec<(f64, f64)> {
        let pts: Vec<(f64, f64)> = s
            .elements
            .iter()
            .filter_map(|e| Some((e.index as f64, f(e)?)))
            .filter(|(_, v)| v.is_finite())
            .map(|(i, v)| (i, v.max(floor)))
            .collect();
        let bin = pts.len().div_ceil(MAX_CHART_POINTS).max(1);
        pts.chunks(bin)
            .map(|c| {
                c.iter()
                    .copied()
                    .fold((c[0].0, 0.0), |a, p| if p.1 > a.1 { p } else { a })
            })
            .collect()
    };
    let series = vec![
        Series::line(format!("{k} × stable bound"), pick(&|e| Some(k * e.bound?))),
        Series::points("|error|", pick(&|e| Some(e.abs))),
    ];
    line_chart(
        "check_error_vs_bound",
        &format!("check {}: error against the stable bound", s.kind),
        "index",
        "absolute error",
        true,
        series,
        &format!(
            "Absolute error of each element and {k} × the error a backward-stable computation would make there (log scale; below {floor:.1e} drawn at it; {} elements over, worst excess {}).",
            s.over_bound,
            s.worst_excess
                .as_ref()
                .map_or("-".into(), |w| num(w.excess))
        ),
    )
}

/// The per-element arrays of `--out`: `reference.npy` (the reference
/// rounded to f64), `error.npy` (`|value − reference|`, infinite for a
/// non-finite value) and `bound.npy` (the stable bound, NaN where the kind
/// has none), each of shape `(n,)` in the user's element order.
fn element_arrays(s: &CheckSummary) -> Result<Vec<(String, Vec<u8>)>, CliError> {
    let n = s.elements.len();
    let column = |f: &dyn Fn(&ElementError) -> f64| s.elements.iter().map(f).collect::<Vec<f64>>();
    Ok(vec![
        (
            "reference.npy".into(),
            write_npy_f64(&[n], column(&|e| e.reference))?,
        ),
        ("error.npy".into(), write_npy_f64(&[n], column(&|e| e.abs))?),
        (
            "bound.npy".into(),
            write_npy_f64(&[n], column(&|e| e.bound.unwrap_or(f64::NAN)))?,
        ),
    ])
}

/// For `cond`: each element's error against its (reference) condition
/// number, both on log axes — the picture of how a user's digits fall as
/// the matrix gets worse.
pub fn cond_chart(s: &CheckSummary) -> Chart {
    let pts: Vec<(f64, f64)> = s
        .elements
        .iter()
        .filter(|e| e.ulps.is_finite() && e.reference.is_finite() && e.reference > 0.0)
        .map(|e| (e.reference, e.ulps.max(ULPS_FLOOR)))
        .collect();
    line_chart(
        "check_error_vs_cond",
        "check cond: error against the condition number",
        "condition number (reference)",
        "error (ulps)",
        true,
        vec![Series::points("user's condition numbers", pts)],
        &format!(
            "Error of each condition number in ulps of {} against the reference value (log-log; below {ULPS_FLOOR} drawn at {ULPS_FLOOR}; {} non-finite values not drawn).",
            s.format.name(),
            s.non_finite
        ),
    )
    .with_log_x()
}

fn body(o: &Outcome) -> String {
    match o {
        Outcome::Insertion(s) => {
            let rows = vec![
                vec!["verdict".into(), s.verdict.clone()],
                vec!["max deviation".into(), num(s.max_deviation)],
                vec![
                    "max deviation (relative to max |c|)".into(),
                    num(s.max_deviation_rel),
                ],
                vec!["in ulps of the scale".into(), num(s.max_deviation_ulps)],
                vec!["at x".into(), num(s.worst_x)],
                vec!["curves identical (exact)".into(), s.identical.to_string()],
            ];
            paragraph(&s.reference) + &table("Knot insertion", &["", ""], &rows)
        }
        Outcome::Elements(s) => {
            let mut rows = vec![vec![
                "all".into(),
                s.n.to_string(),
                s.worst.as_ref().map_or("-".into(), |w| num(w.ulps)),
                num(s.median_ulps),
            ]];
            for (name, r) in s.regions.iter().flatten() {
                rows.push(vec![
                    name.clone(),
                    r.count.to_string(),
                    num(r.max_ulps),
                    num(r.median_ulps),
                ]);
            }
            let worst = s.worst.as_ref().map_or(String::new(), |w| {
                format!(
                    "Worst element: index {}, {} ulps, relative error {}, absolute error {}{}. ",
                    w.index,
                    num(w.ulps),
                    num(w.rel),
                    num(w.abs),
                    w.region
                        .map(|r| format!(" ({})", r.name()))
                        .unwrap_or_default()
                )
            });
            let basis = match (&s.worst_excess, &s.no_verdict_reason) {
                (Some(w), _) => format!(
                    " Stable bound ({}): worst excess {} at index {}, {} digits lost beyond the conditioning, {} elements over {} × the bound.",
                    s.stable_bound.clone().unwrap_or_default(),
                    num(w.excess),
                    w.index,
                    num(s.digits_lost.unwrap_or(0.0)),
                    s.over_bound,
                    num(s.bound_factor.unwrap_or(1.0))
                ),
                (None, Some(why)) => format!(" No stable-bound verdict: {why}."),
                (None, None) => String::new(),
            };
            paragraph(&format!(
                "Verdict: {}. Reference: {}. {worst}Correct digits ≥ {:.2}; {} non-finite values; {} elements over --max-ulps.{basis} Per element: reference.npy, error.npy, bound.npy.",
                s.verdict, s.reference, s.digits_min, s.non_finite, s.failed
            )) + &table(
                &format!("Errors in ulps of {}", s.format.name()),
                &["region", "elements", "max ulps", "median ulps"],
                &rows,
            )
        }
    }
}

/// Renders the page and the files of the directory, in memory.
fn files(o: &Outcome, json: &Value) -> Result<Vec<(String, Vec<u8>)>, CliError> {
    let mut out: Vec<(String, Vec<u8>)> = vec![];
    let mut html = body(o);
    if let Outcome::Elements(s) = o {
        let mut charts = vec![error_chart(s)];
        if s.worst_excess.is_some() {
            charts.push(bound_chart(s));
        }
        if s.kind == "cond" {
            charts.push(cond_chart(s));
        }
        out.extend(element_arrays(s)?);
        for chart in charts
            .into_iter()
            .filter(|c| c.series.iter().any(|x| !x.points.is_empty()))
        {
            let svg = chart
                .render_svg()
                .map_err(|e| CliError::Chart(chart.id.clone(), e.to_string()))?;
            html.push_str(&format!(
                "<figure>{svg}<figcaption>{} (<a href=\"{}.svg\">SVG</a>)</figcaption></figure>\n",
                escape(&chart.caption),
                chart.id
            ));
            out.push((format!("{}.svg", chart.id), svg.into_bytes()));
        }
    }
    let kind = json.get("kind").and_then(Value::as_str).unwrap_or("check");
    let page = format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>splinelab check {k}</title></head>\
         <body>\n<h1>splinelab check {k}</h1>\n{html}<p>Machine-readable: <a href=\"summary.json\">summary.json</a>.</p></body></html>\n",
        k = escape(kind)
    );
    out.push(("index.html".into(), page.into_bytes()));
    let summary = json!({"check": json, "figures": figures(o)});
    out.push((
        "summary.json".into(),
        serde_json::to_string_pretty(&summary)
            .map_err(CliError::numerical)?
            .into_bytes(),
    ));
    Ok(out)
}

fn io(path: &Path) -> impl Fn(std::io::Error) -> CliError + '_ {
    move |source| CliError::Output {
        path: path.to_path_buf(),
        source,
    }
}

/// `PARENT/.NAME.SUFFIXPID`, beside `dir`.
fn beside(dir: &Path, suffix: &str) -> PathBuf {
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    dir.with_file_name(format!(".{name}.{suffix}{}", std::process::id()))
}

/// Writes the page, charts and summary into `dir`: built in a temporary
/// directory beside it, then renamed into place (an existing `dir` is moved
/// aside first and removed after).
pub fn write_check_dir(dir: &Path, o: &Outcome, json: &Value) -> Result<(), CliError> {
    let files = files(o, json)?;
    let tmp = beside(dir, "tmp");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).map_err(io(&tmp))?;
    let written = files.iter().try_for_each(|(name, text)| {
        std::fs::write(tmp.join(name), text).map_err(io(&tmp.join(name)))
    });
    if let Err(e) = written {
        let _ = std::fs::remove_dir_all(&tmp);
        return Err(e);
    }
    let old = beside(dir, "old");
    let had = dir.is_dir();
    if had {
        std::fs::rename(dir, &old).map_err(io(dir))?;
    }
    if let Err(e) = std::fs::rename(&tmp, dir) {
        if had {
            let _ = std::fs::rename(&old, dir);
        }
        let _ = std::fs::remove_dir_all(&tmp);
        return Err(io(dir)(e));
    }
    if had {
        let _ = std::fs::remove_dir_all(&old);
    }
    Ok(())
}
