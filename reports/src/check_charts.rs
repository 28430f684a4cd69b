//! The charts of a check's page: each element's error against its index,
//! against `K` × its stable bound, and (for `cond`) against the condition
//! number. Presentation only: drawn from verify's [`CheckSummary`], used by
//! the command line's `--out` page and by the report's check section.

use crate::chart::{Chart, Series, Style, line_chart};
use crate::html::num;
use splinelab_verify::check::{CheckSummary, ElementError, Region};

/// Points drawn at most per chart: longer arrays are binned (max per bin).
pub const MAX_CHART_POINTS: usize = 4000;

/// Errors below this are drawn at it on the log axis.
pub const ULPS_FLOOR: f64 = 1e-3;

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
    binned_max(&pts)
}

/// At most [`MAX_CHART_POINTS`] points: consecutive bins of `pts`, each
/// drawn as its point of largest value (an error peak is never averaged away).
fn binned_max(pts: &[(f64, f64)]) -> Vec<(f64, f64)> {
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
        binned_max(&pts)
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
