//! Report section "small_calls" (issue 50): splinelab's time over scipy's
//! for the small calls loops make by the thousand (8² to 128², 16³ and
//! 32³), as `python/bench/small_calls.py` measured them. The report does
//! not run Python or scipy: it reads the committed run
//! (`python/bench/small_calls/after.json`, compiled in) and states where it
//! came from (command, date, commit, machine load).

use super::{Figure, ReportError, Section};
use crate::chart::{Chart, GREY, Series, line_chart};
use crate::error::CliError;
use crate::html::{escape, num, paragraph, table};
use serde::Deserialize;
use serde_json::{Value, json};

/// The committed run, as `small_calls.py --json` wrote it.
const RUN: &str = include_str!("../../../python/bench/small_calls/after.json");

/// The eight functions, in the benchmark's order.
const FUNCS: [&str; 8] = [
    "spline_filter1d",
    "spline_filter",
    "map_coordinates",
    "affine_transform",
    "shift",
    "zoom",
    "rotate",
    "geometric_transform",
];

/// One timed case of the run.
#[derive(Debug, Clone, Deserialize)]
pub struct Case {
    /// The scipy.ndimage function.
    pub function: String,
    /// The input's shape.
    pub shape: Vec<usize>,
    /// splinelab's time over scipy's (min of the rounds each).
    pub ratio: f64,
}

/// The run: its cases, its fixed cost and where it came from.
#[derive(Debug, Clone, Deserialize)]
pub struct Run {
    /// Every case.
    pub cases: Vec<Case>,
    /// `fixed_cost.default`: one point on 8², order 1 (scipy_us, splinelab_us).
    pub fixed_cost: Value,
    /// Command, date, commit, machine and load (absent in older runs).
    #[serde(default)]
    pub provenance: Value,
    /// scipy's version.
    pub scipy: String,
    /// Rounds per case (min of).
    pub rounds: usize,
}

/// `8x8`, `16x16x16`.
fn shape_name(shape: &[usize]) -> String {
    shape
        .iter()
        .map(usize::to_string)
        .collect::<Vec<_>>()
        .join("x")
}

/// The run's shapes, 2-D first, each by its number of samples.
fn shapes(run: &Run) -> Vec<Vec<usize>> {
    let mut s: Vec<Vec<usize>> = run.cases.iter().map(|c| c.shape.clone()).collect();
    s.sort_by_key(|s| (s.len(), s.iter().product::<usize>()));
    s.dedup();
    s
}

fn ratios<'a>(run: &'a Run, shape: &'a [usize]) -> impl Iterator<Item = &'a Case> {
    run.cases.iter().filter(move |c| c.shape == shape)
}

/// The median of `v` (NaN when empty).
fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

fn largest(v: impl Iterator<Item = f64>) -> f64 {
    v.fold(f64::NAN, f64::max)
}

/// `(samples, value)` per shape of `dims` dimensions.
fn by_size(run: &Run, dims: usize, stat: impl Fn(Vec<f64>) -> f64) -> Vec<(f64, f64)> {
    shapes(run)
        .into_iter()
        .filter(|s| s.len() == dims)
        .map(|s| {
            let v = ratios(run, &s).map(|c| c.ratio).collect();
            (s.iter().product::<usize>() as f64, stat(v))
        })
        .filter(|(_, y)| y.is_finite())
        .collect()
}

/// The line at ratio 1 (scipy's time) across the run's sizes.
fn parity_line(run: &Run) -> Series {
    let n: Vec<f64> = shapes(run)
        .iter()
        .map(|s| s.iter().product::<usize>() as f64)
        .collect();
    let (lo, hi) = n
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), &x| (l.min(x), h.max(x)));
    Series::line("scipy's time (ratio 1)", vec![(lo, 1.0), (hi, 1.0)]).with_color(GREY)
}

fn overall_chart(run: &Run) -> Chart {
    let max = |v: Vec<f64>| largest(v.into_iter());
    let series = vec![
        Series::line_points("largest ratio, 2-D (8² … 128²)", by_size(run, 2, max)),
        Series::line_points("median ratio, 2-D", by_size(run, 2, median)),
        Series::points("largest ratio, 3-D (16³, 32³)", by_size(run, 3, max)),
        Series::points("median ratio, 3-D", by_size(run, 3, median)),
        parity_line(run),
    ];
    line_chart(
        "small_calls_ratio",
        "Small calls: splinelab's time over scipy's, by array size",
        "samples in the array",
        "time ratio splinelab / scipy",
        true,
        series,
        "Over the eight functions, orders 0, 1, 3, 5, float64 and float32, default threads and one thread: \
         below the grey line splinelab is the faster. The fixed cost of a call decides the smallest sizes.",
    )
    .with_log_x()
}

fn function_chart(run: &Run) -> Chart {
    let mut series: Vec<Series> = FUNCS
        .iter()
        .map(|f| {
            let pts = shapes(run)
                .into_iter()
                .filter(|s| s.len() == 2)
                .map(|s| {
                    let r = largest(
                        ratios(run, &s)
                            .filter(|c| c.function == *f)
                            .map(|c| c.ratio),
                    );
                    (s.iter().product::<usize>() as f64, r)
                })
                .filter(|(_, r)| r.is_finite())
                .collect();
            Series::line_points(*f, pts)
        })
        .filter(|s| !s.points.is_empty())
        .collect();
    series.push(parity_line(run));
    line_chart(
        "small_calls_ratio_by_function",
        "Small calls: the largest ratio per function, 2-D arrays",
        "samples in the array (8² … 128²)",
        "largest time ratio splinelab / scipy",
        true,
        series,
        "Each point is the function's slowest case at that size (over orders, dtypes, point counts and threads).",
    )
    .with_log_x()
}

fn ratio_table(run: &Run) -> String {
    let shapes = shapes(run);
    let mut header = vec!["function".to_string()];
    header.extend(shapes.iter().map(|s| shape_name(s)));
    let cell = |v: f64| if v.is_finite() { num(v) } else { "—".into() };
    let mut rows: Vec<Vec<String>> = FUNCS
        .iter()
        .map(|f| {
            let mut row = vec![f.to_string()];
            row.extend(shapes.iter().map(|s| {
                cell(largest(
                    ratios(run, s).filter(|c| c.function == *f).map(|c| c.ratio),
                ))
            }));
            row
        })
        .collect();
    let mut med = vec!["median, all functions".to_string()];
    med.extend(
        shapes
            .iter()
            .map(|s| cell(median(ratios(run, s).map(|c| c.ratio).collect()))),
    );
    rows.push(med);
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    table(
        "The largest time ratio splinelab / scipy per function and size (over orders, dtypes, points, threads)",
        &header,
        &rows,
    )
}

fn count_above(run: &Run, limit: f64) -> usize {
    run.cases.iter().filter(|c| c.ratio > limit).count()
}

fn fixed_cost(run: &Run) -> Option<(f64, f64)> {
    let f = run.fixed_cost.get("default")?;
    Some((
        f.get("scipy_us")?.as_f64()?,
        f.get("splinelab_us")?.as_f64()?,
    ))
}

fn provenance_text(run: &Run) -> String {
    let p = &run.provenance;
    let s = |k: &str| {
        p.get(k)
            .and_then(Value::as_str)
            .unwrap_or("not recorded")
            .to_string()
    };
    let load = |k: &str| {
        p.get(k)
            .and_then(Value::as_array)
            .map(|v| {
                v.iter()
                    .map(|x| x.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            })
            .unwrap_or_else(|| "not recorded".into())
    };
    format!(
        "Measured by <code>{}</code> on {} at commit {} ({}; load average over 1, 5, 15 minutes {} before \
         and {} after), scipy {}, min of {} rounds per case. The report reads this committed run \
         (python/bench/small_calls/after.json); it does not run Python.",
        escape(&s("command")),
        escape(&s("date")),
        escape(&s("commit")),
        escape(&s("machine")),
        escape(&load("load_before")),
        escape(&load("load_after")),
        escape(&run.scipy),
        run.rounds
    )
}

fn text(run: &Run) -> String {
    let all: Vec<f64> = run.cases.iter().map(|c| c.ratio).collect();
    let mut html = paragraph(&format!(
        "scipy.ndimage's eight interpolation calls on small arrays, the calls that loops make by the \
         thousand, timed against scipy 1.17.1 in one process (alternated, min of the rounds). Of {} cases, \
         {} take longer than scipy's (ratio above 1) and {} more than 5 % longer; median ratio {}, largest {}.",
        all.len(),
        count_above(run, 1.0),
        count_above(run, 1.05),
        num(median(all.clone())),
        num(largest(all.into_iter()))
    ));
    if let Some((theirs, ours)) = fixed_cost(run) {
        html.push_str(&paragraph(&format!(
            "The fixed cost of a call (map_coordinates, one point on 8², order 1, float64, default threads): \
             scipy {} µs, splinelab {} µs.",
            num(theirs),
            num(ours)
        )));
    }
    html.push_str(&format!("<p>{}</p>\n", provenance_text(run)));
    html.push_str(&ratio_table(run));
    html
}

/// Cost figures of the committed run: they move only when it is rerun and
/// committed, so a narrow band (a quarter) flags a rerun that got slower.
fn figures(run: &Run) -> Vec<Figure> {
    const BAND: f64 = 1.25;
    let all: Vec<f64> = run.cases.iter().map(|c| c.ratio).collect();
    let mut f = vec![
        Figure::cost(
            "small_calls.max_ratio",
            largest(all.iter().copied()),
            "ratio",
            BAND,
        ),
        Figure::cost("small_calls.median_ratio", median(all), "ratio", BAND),
        Figure::cost(
            "small_calls.cases_above_1",
            count_above(run, 1.0) as f64,
            "cases",
            BAND,
        )
        .with_floor(10.0),
        Figure::cost(
            "small_calls.cases_above_1_05",
            count_above(run, 1.05) as f64,
            "cases",
            BAND,
        )
        .with_floor(10.0),
    ];
    if let Some((theirs, ours)) = fixed_cost(run) {
        f.push(Figure::cost(
            "small_calls.fixed_cost_ratio",
            ours / theirs,
            "ratio",
            BAND,
        ));
    }
    for s in shapes(run) {
        let r = largest(ratios(run, &s).map(|c| c.ratio));
        f.push(Figure::cost(
            format!("small_calls.max_ratio.s{}", shape_name(&s)),
            r,
            "ratio",
            BAND,
        ));
    }
    f.into_iter().filter(|f| f.value.is_finite()).collect()
}

/// The committed run, parsed.
pub fn committed_run() -> Result<Run, CliError> {
    serde_json::from_str(RUN)
        .map_err(|e| CliError::Numerical(format!("python/bench/small_calls/after.json: {e}")))
}

/// Presents the committed small-call run.
pub fn section(_profile: &super::Profile) -> Result<Section, ReportError> {
    let run = committed_run()?;
    Ok(Section {
        id: "small_calls",
        title: "Small calls against scipy (issue 50)".into(),
        html: text(&run),
        charts: vec![overall_chart(&run), function_chart(&run)],
        summary: json!({
            "cases": run.cases.len(),
            "cases_above_1": count_above(&run, 1.0),
            "cases_above_1_05": count_above(&run, 1.05),
            "fixed_cost": run.fixed_cost,
            "provenance": run.provenance,
            "source": "python/bench/small_calls/after.json",
        }),
        figures: figures(&run),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(function: &str, shape: &[usize], ratio: f64) -> Case {
        Case {
            function: function.into(),
            shape: shape.to_vec(),
            ratio,
        }
    }

    fn run(cases: Vec<Case>) -> Run {
        Run {
            cases,
            fixed_cost: json!({"default": {"scipy_us": 4.0, "splinelab_us": 3.0}}),
            provenance: Value::Null,
            scipy: "1.17.1".into(),
            rounds: 7,
        }
    }

    #[test]
    fn figures_are_the_largest_and_median_ratios_by_size() {
        let r = run(vec![
            case("shift", &[8, 8], 1.5),
            case("zoom", &[8, 8], 0.5),
            case("shift", &[16, 16], 0.9),
            case("rotate", &[16, 16, 16], 0.25),
        ]);
        let f = figures(&r);
        let get = |n: &str| f.iter().find(|f| f.name == n).map(|f| f.value);
        assert_eq!(get("small_calls.max_ratio"), Some(1.5));
        // The median of 0.25, 0.5, 0.9, 1.5.
        assert_eq!(get("small_calls.median_ratio"), Some(0.7));
        assert_eq!(get("small_calls.cases_above_1"), Some(1.0));
        assert_eq!(get("small_calls.max_ratio.s8x8"), Some(1.5));
        assert_eq!(get("small_calls.max_ratio.s16x16x16"), Some(0.25));
        assert_eq!(get("small_calls.fixed_cost_ratio"), Some(0.75));
        // 2-D shapes first, each by its samples, then the 3-D ones.
        assert_eq!(shapes(&r), vec![vec![8, 8], vec![16, 16], vec![16, 16, 16]]);
        assert_eq!(by_size(&r, 2, median), vec![(64.0, 1.0), (256.0, 0.9)]);
    }

    #[test]
    fn the_committed_run_parses_and_states_where_it_came_from() {
        let r = committed_run().expect("after.json parses");
        assert!(r.cases.len() > 100, "{} cases", r.cases.len());
        assert!(r.cases.iter().all(|c| c.ratio.is_finite() && c.ratio > 0.0));
        for key in ["command", "date", "commit"] {
            assert!(
                r.provenance.get(key).and_then(Value::as_str).is_some(),
                "{key}"
            );
        }
    }
}
