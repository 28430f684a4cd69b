//! `check --out DIR`: an HTML page with SVG charts (the error against
//! index, against the stable bound), the per-element `reference.npy`,
//! `error.npy` and `bound.npy`, and a `summary.json`
//! whose `figures` `splinelab compare` accepts. The directory is built
//! beside its destination and renamed into place, so a reader never sees a
//! half-written one.

use crate::array_io::write_npy_f64;
use crate::check_charts::{bound_chart, cond_chart, error_chart};
use crate::error::CliError;
use crate::html::{escape, num, paragraph, table};
use crate::page::{figure, machine_readable, page, verdict_class};
use crate::report::Figure;
use crate::report::provenance::{provenance_html, run_provenance};
use serde_json::{Value, json};
use splinelab_verify::check::{CheckSummary, ElementError, Outcome, Region};
use std::path::{Path, PathBuf};

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
    let mid = |k: usize| u.get(k).copied().unwrap_or(0.0);
    let median = match u.len() {
        0 => 0.0,
        n if n % 2 == 1 => mid(n / 2),
        n => 0.5 * (mid(n / 2 - 1) + mid(n / 2)),
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
                    s.bound_factor.unwrap_or(1.0)
                ),
                (None, Some(why)) => format!(" No stable-bound verdict: {why}."),
                (None, None) => String::new(),
            };
            paragraph(&format!(
                "Reference: {}. {worst}Correct digits ≥ {:.2}; {} non-finite values; {} elements over --max-ulps.{basis}",
                s.reference, s.digits_min, s.non_finite, s.failed
            )) + &table(
                &format!("Errors in ulps of {}", s.format.name()),
                &["region", "elements", "max ulps", "median ulps"],
                &rows,
            )
        }
    }
}

/// The verdict line at the top of the page, in its colour: the command
/// line's first line (`check prefilter: pass (8 elements, f64 ulps)`).
fn headline(o: &Outcome) -> String {
    let (kind, verdict, what) = match o {
        Outcome::Elements(s) => (
            s.kind.as_str(),
            s.verdict.as_str(),
            format!("{} elements, {} ulps", s.n, s.format.name()),
        ),
        Outcome::Insertion(s) => ("knot-insertion", s.verdict.as_str(), "one curve".into()),
    };
    format!(
        "<p class=\"{}\">check {}: {} ({})</p>\n",
        verdict_class(verdict),
        escape(kind),
        escape(verdict),
        escape(&what)
    )
}

/// The machine-readable files of the folder, with what each holds.
fn data_files(o: &Outcome) -> Vec<(&'static str, &'static str)> {
    let mut files = vec![(
        "summary.json",
        "the check and its figures, for splinelab compare",
    )];
    if let Outcome::Elements(_) = o {
        files.extend([
            ("reference.npy", "the reference per element"),
            ("error.npy", "|value − reference|"),
            ("bound.npy", "the stable bound, NaN without one"),
        ]);
    }
    files
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
            let (figure, svg) = figure(&chart)?;
            html.push_str(&figure);
            out.push((format!("{}.svg", chart.id), svg.into_bytes()));
        }
    }
    let kind = json.get("kind").and_then(Value::as_str).unwrap_or("check");
    let page = page(
        &format!("splinelab check {kind}"),
        &format!(
            "{}{html}{}{}",
            headline(o),
            machine_readable(&data_files(o)),
            provenance_html(&run_provenance())
        ),
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
