//! The pytest plugin's session page (`pytest --splinelab-report DIR`:
//! `DIR/index.html`): every check of the session in one table, led by a
//! chart of each check's worst error against what its verdict allows, the
//! failures marked. Drawn with the report's chart code and page shell; the
//! plugin (python/splinelab/pytest_plugin.py) gathers the checks and writes
//! the files this returns (through the extension's `session_page`).

use crate::chart::{Chart, GREEN, GREY, RED, Series, line_chart};
use crate::error::CliError;
use crate::html::{escape, num};
use crate::page::{figure, machine_readable, page, verdict};
use crate::report::provenance::{provenance_html, run_provenance};
use serde::Deserialize;
use serde_json::Value;

/// One check of the session, as the plugin gathers it.
#[derive(Debug, Clone, Deserialize)]
pub struct SessionCheck {
    /// The check's label (its folder under `checks/`).
    pub label: String,
    /// Its page, relative to the session page.
    pub page: String,
    /// The check's JSON contract (its `summary.json`'s `check`).
    pub check: Value,
}

/// Ratios below this are drawn at it on the chart's log axis.
pub const RATIO_FLOOR: f64 = 1e-3;

/// Failed checks named one by one in the chart's legend; beyond this many
/// they share one series (the table names each).
const NAMED_FAILURES: usize = 8;

/// The worst error of a check over the error its verdict allows, the
/// binding gate when it has two: the worst excess over `K` × the stable
/// bound (`worst_excess.excess / bound_factor`) and the worst error over
/// `max_ulps` (`worst.ulps`, or knot insertion's `max_deviation_ulps`).
/// Above 1 the check fails. `None` for a check without either gate
/// (`cond` without `max_ulps`) or without a finite worst error.
pub fn over_allowed(check: &Value) -> Option<f64> {
    let f = |v: &Value| v.as_f64();
    let by_bound = f(&check["worst_excess"]["excess"])
        .zip(f(&check["bound_factor"]).filter(|k| *k > 0.0))
        .map(|(e, k)| e / k);
    let worst_ulps = f(&check["worst"]["ulps"]).or_else(|| f(&check["max_deviation_ulps"]));
    let by_ulps = worst_ulps
        .zip(f(&check["max_ulps"]).filter(|m| *m > 0.0))
        .map(|(u, m)| u / m);
    [by_bound, by_ulps]
        .into_iter()
        .flatten()
        .filter(|r| r.is_finite())
        .reduce(f64::max)
}

fn failed(check: &Value) -> bool {
    check["verdict"].as_str() != Some("pass")
}

/// The chart: one point per check (x its # in the table) at its
/// [`over_allowed`] ratio, a line at 1 (fail above), each failed check its
/// own series named after it. `None` when no check has a ratio.
fn worst_chart(checks: &[SessionCheck]) -> Option<Chart> {
    let ratios: Vec<(usize, &SessionCheck, f64)> = checks
        .iter()
        .enumerate()
        .filter_map(|(i, c)| Some((i + 1, c, over_allowed(&c.check)?)))
        .collect();
    if ratios.is_empty() {
        return None;
    }
    let point = |i: usize, r: f64| (i as f64, r.max(RATIO_FLOOR));
    let n = checks.len() as f64;
    let mut series = vec![
        Series::line("allowed (fail above 1)", vec![(1.0, 1.0), (n, 1.0)]).with_color(GREY),
        Series::points(
            "passed",
            ratios
                .iter()
                .filter(|(_, c, _)| !failed(&c.check))
                .map(|(i, _, r)| point(*i, *r))
                .collect(),
        )
        .with_color(GREEN),
    ];
    let failures: Vec<&(usize, &SessionCheck, f64)> =
        ratios.iter().filter(|(_, c, _)| failed(&c.check)).collect();
    if failures.len() <= NAMED_FAILURES {
        series.extend(failures.iter().map(|(i, c, r)| {
            Series::points(format!("FAILED #{i} {}", c.label), vec![point(*i, *r)]).with_color(RED)
        }));
    } else {
        series.push(
            Series::points(
                "FAILED (see the table)",
                failures.iter().map(|(i, _, r)| point(*i, *r)).collect(),
            )
            .with_color(RED),
        );
    }
    series.retain(|s| !s.points.is_empty());
    let undrawn = checks.len() - ratios.len();
    Some(line_chart(
        "session_worst_vs_allowed",
        "Each check's worst error over what its verdict allows",
        "check # (see the table)",
        "worst error / allowed",
        true,
        series,
        &format!(
            "Each check's worst error divided by the error its verdict allows: K × the stable bound \
             (worst excess / K) or --max-ulps (worst ulps / max_ulps), the larger; above 1 the check fails \
             (log scale; below {RATIO_FLOOR} drawn at it; {undrawn} check(s) without a bound or a finite \
             worst error not drawn)."
        ),
    ))
}

/// The table of checks, numbered as on the chart.
fn checks_table(checks: &[SessionCheck]) -> String {
    let mut s = String::from(
        "<div class=\"scroll\"><table><tr><th>#</th><th>check</th><th>kind</th><th>verdict</th>\
         <th>elements</th><th>worst (ulps)</th><th>worst / allowed</th><th>digits lost</th><th>data</th></tr>\n",
    );
    let opt = |v: Option<f64>| v.map_or("-".to_string(), num);
    for (i, c) in checks.iter().enumerate() {
        let k = &c.check;
        let folder = c.page.rsplit_once('/').map_or("", |(dir, _)| dir);
        let data = if folder.is_empty() {
            "-".to_string()
        } else {
            format!(
                "<a href=\"{}/summary.json\">summary.json</a>",
                escape(folder)
            )
        };
        s.push_str(&format!(
            "<tr><td>{}</td><td class=\"name\"><a href=\"{}\">{}</a></td><td>{}</td><td>{}</td>\
             <td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{data}</td></tr>\n",
            i + 1,
            escape(&c.page),
            escape(&c.label),
            escape(k["kind"].as_str().unwrap_or("-")),
            verdict(k["verdict"].as_str().unwrap_or("-")),
            k["n"].as_u64().map_or("-".into(), |n| n.to_string()),
            opt(k["worst"]["ulps"]
                .as_f64()
                .or_else(|| k["max_deviation_ulps"].as_f64())),
            opt(over_allowed(k)),
            opt(k["digits_lost"].as_f64()),
        ));
    }
    s.push_str("</table></div>\n");
    s
}

/// The session page's files, `(name, contents)`: `index.html` and the
/// chart's SVG (when a check has a ratio to draw).
pub fn session_files(checks: &[SessionCheck]) -> Result<Vec<(String, String)>, CliError> {
    let failures = checks.iter().filter(|c| failed(&c.check)).count();
    let headline = format!(
        "<p class=\"{}\">{} checks, {} failed.</p>\n",
        if failures == 0 { "pass" } else { "fail" },
        checks.len(),
        failures
    );
    let mut files = vec![];
    let chart = match worst_chart(checks) {
        Some(chart) => {
            let (html, svg) = figure(&chart)?;
            files.push((format!("{}.svg", chart.id), svg));
            html
        }
        None => "<p>No check of this session has an error bound to draw.</p>\n".into(),
    };
    let body = format!(
        "{headline}{chart}{}{}<p>Compare two sessions: <code>splinelab compare --baseline \
         OLD/summary.json --current summary.json --out DIR</code>.</p>\n{}",
        checks_table(checks),
        machine_readable(&[(
            "summary.json",
            "every check's figures, named LABEL.check.KIND.FIGURE, for splinelab compare"
        )]),
        provenance_html(&run_provenance())
    );
    files.push((
        "index.html".into(),
        page("splinelab checks of this test session", &body),
    ));
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn the_binding_gate_sets_the_ratio() {
        let c = json!({"worst_excess": {"excess": 4.0}, "bound_factor": 8.0,
                       "worst": {"ulps": 30.0}, "max_ulps": 10.0});
        assert_eq!(over_allowed(&c), Some(3.0));
        let c =
            json!({"worst_excess": {"excess": 4.0}, "bound_factor": 8.0, "worst": {"ulps": 30.0}});
        assert_eq!(over_allowed(&c), Some(0.5));
        let c = json!({"max_deviation_ulps": 2.0, "max_ulps": 8.0});
        assert_eq!(over_allowed(&c), Some(0.25));
        assert_eq!(over_allowed(&json!({"worst": {"ulps": 1.0}})), None);
    }
}
