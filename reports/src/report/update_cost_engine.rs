//! The engine part of section "update_cost" (issue 45): the local route
//! against the global one on a memory-mapped array (time and memory against
//! the number of points, the crossover marked) and the local update against
//! a full prefilter (time against the number of changed samples), with
//! scipy's figures on the same sizes measured once by
//! `python/bench/local_route.py --report-json` and committed
//! (`verify/fixtures/scipy/local_route.json`: the report does not run scipy).

use super::figure::{Better, Kind};
use super::{Figure, ReportError, TIME_BAND};
use crate::chart::{Chart, Series, line_chart};
use crate::error::CliError;
use crate::html::{num, paragraph, table};
use serde_json::{Value, json};
use splinelab_verify::local_route::{LocalRouteData, LocalRouteParams, run_local_route};
use std::path::PathBuf;

/// scipy's committed figures for an array `side` (`None` where absent).
fn scipy(side: usize, key: &str) -> Option<f64> {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../verify/fixtures/scipy/local_route.json");
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()?;
    doc.get(side.to_string())?.get(key)?.as_f64()
}

fn points_chart(d: &LocalRouteData) -> Chart {
    let s = |name: &str, f: fn(&Row) -> f64| {
        Series::line_points(name, d.points.iter().map(|r| (r.k as f64, f(r))).collect())
    };
    let mut series = vec![
        s("local route (s)", |r| r.local_s),
        s("global route (s)", |r| r.global_s),
    ];
    if let Some(t) = scipy(d.params.side, "map_coordinates_1000_s") {
        series.push(Series::points("scipy, 1000 points (s)", vec![(1000.0, t)]));
    }
    if let Some(k) = d.crossover {
        let times = d.points.iter().flat_map(|r| [r.global_s, r.local_s]);
        let (low, top) = times.fold((f64::INFINITY, 0.0f64), |(l, t), x| (l.min(x), t.max(x)));
        series.push(Series::line(
            format!("crossover ({k} points)"),
            vec![(k as f64, low), (k as f64, top)],
        ));
    }
    line_chart(
        "update_cost_engine_points",
        &format!(
            "Cubic map_coordinates on a memory-mapped {0}×{0} float64 array: time vs points",
            d.params.side
        ),
        "random points",
        "seconds (min of runs)",
        true,
        series,
        "The local route reads each tile's samples with the certified margin; the global route prefilters the \
         whole array first. The vertical line marks the first measured count at which the global route was faster.",
    )
    .with_log_x()
}

type Row = splinelab_verify::local_route::PointsRow;

fn points_table(d: &LocalRouteData) -> String {
    let total = (d.params.side * d.params.side) as f64;
    let rows: Vec<Vec<String>> = d
        .points
        .iter()
        .map(|r| {
            vec![
                r.k.to_string(),
                num(r.local_s * 1e3),
                num(r.local_bytes as f64 / 1048576.0),
                num(r.samples_read as f64 / total),
                num(r.global_s * 1e3),
                num(r.global_bytes as f64 / 1048576.0),
                r.chosen.to_string(),
            ]
        })
        .collect();
    table(
        "Time (ms) and peak anonymous memory (MB) of map_coordinates on the memory-mapped array",
        &[
            "points",
            "local ms",
            "local MB",
            "samples read / size",
            "global ms",
            "global MB",
            "cost rule picks",
        ],
        &rows,
    )
}

fn update_table(d: &LocalRouteData) -> String {
    let rows: Vec<Vec<String>> = d
        .updates
        .iter()
        .map(|r| {
            vec![
                r.changed.to_string(),
                num(r.update_s * 1e3),
                r.coefficients.to_string(),
                num(d.full_prefilter_s / r.update_s),
            ]
        })
        .collect();
    let scipy_filter = scipy(d.params.update_side, "spline_filter_s")
        .map_or("not measured".to_string(), |s| {
            format!("{} ms", num(s * 1e3))
        });
    let mut html = table(
        &format!(
            "Interpolant.update of scattered samples in a {0}×{0} cubic (every tile cached) against a full \
             prefilter ({1} ms; scipy's spline_filter: {scipy_filter})",
            d.params.update_side,
            num(d.full_prefilter_s * 1e3)
        ),
        &[
            "changed samples",
            "update ms",
            "coefficients recomputed",
            "full prefilter / update",
        ],
        &rows,
    );
    html.push_str(&paragraph(&format!(
        "After every update, the values at 2000 random points against a fresh interpolant of the changed samples: \
         max difference {} (0: bit for bit).",
        num(d.update_vs_rebuild)
    )));
    html
}

fn figures(d: &LocalRouteData) -> Vec<Figure> {
    let mut f = Vec::new();
    for r in &d.points {
        f.push(
            Figure::cost(
                format!("update_cost.engine.local_s.K{}", r.k),
                r.local_s,
                "s",
                TIME_BAND,
            )
            .with_floor(1e-4),
        );
        f.push(
            Figure::cost(
                format!("update_cost.engine.local_mb.K{}", r.k),
                r.local_bytes as f64 / 1048576.0,
                "MB",
                TIME_BAND,
            )
            .with_floor(8.0),
        );
    }
    if let Some(r) = d.points.last() {
        f.push(
            Figure::cost("update_cost.engine.global_s", r.global_s, "s", TIME_BAND)
                .with_floor(1e-2),
        );
    }
    for r in &d.updates {
        f.push(
            Figure::cost(
                format!("update_cost.engine.update_s.C{}", r.changed),
                r.update_s,
                "s",
                TIME_BAND,
            )
            .with_floor(1e-4),
        );
    }
    f.push(
        Figure::cost(
            "update_cost.engine.full_prefilter_s",
            d.full_prefilter_s,
            "s",
            TIME_BAND,
        )
        .with_floor(1e-2),
    );
    f.push(Figure::new(
        "update_cost.engine.crossover_points",
        d.crossover.unwrap_or(usize::MAX) as f64,
        Kind::Cost,
        "points",
        Better::Higher,
        TIME_BAND,
    ));
    f.push(Figure::error(
        "update_cost.engine.local_error_over_bound",
        d.error_over_bound,
        "ratio",
        1.0,
    ));
    f.push(Figure::error(
        "update_cost.engine.update_vs_rebuild",
        d.update_vs_rebuild,
        "absolute",
        0.0,
    ));
    f
}

/// The engine part: its HTML, charts, summary and figures.
pub fn part(
    params: LocalRouteParams,
) -> Result<(String, Vec<Chart>, Value, Vec<Figure>), ReportError> {
    let d = run_local_route(&params).map_err(CliError::numerical)?;
    let mut html = paragraph(&format!(
        "On the engine (issue 45): the local route computes the coefficients only of the tiles that hold points, \
         from the samples within the certified half-width ({} for the cubic at tol=None, below the global route's \
         own rounding), memory-mapped; the global route prefilters the whole array. Crossover: {}. Each local value \
         is within {} of the stated bound of the global route's (≤ 1).",
        d.half_width,
        d.crossover
            .map_or("none up to the largest count".to_string(), |k| format!(
                "{k} points"
            )),
        num(d.error_over_bound)
    ));
    html.push_str(&points_table(&d));
    if let (Some(t), Some(m)) = (
        scipy(d.params.side, "map_coordinates_1000_s"),
        scipy(d.params.side, "map_coordinates_1000_mb"),
    ) {
        html.push_str(&paragraph(&format!(
            "scipy 1.17.1 on the same array, 1000 points: {} ms and {} MB of anonymous memory (measured once by \
             python/bench/local_route.py --report-json, committed).",
            num(t * 1e3),
            num(m)
        )));
    }
    html.push_str(&update_table(&d));
    let summary = json!({
        "side": d.params.side,
        "half_width": d.half_width,
        "points": d.points,
        "crossover": d.crossover,
        "error_over_bound": d.error_over_bound,
        "updates": d.updates,
        "full_prefilter_s": d.full_prefilter_s,
        "update_vs_rebuild": d.update_vs_rebuild,
    });
    Ok((html, vec![points_chart(&d)], summary, figures(&d)))
}
