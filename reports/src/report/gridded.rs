//! Report section "gridded" (issue 49): the exact not-a-knot
//! tensor-product spline on a rectilinear grid
//! (`splinelab::gridded::GridSpline`, what scipy.interpolate's
//! `RegularGridInterpolator(method="cubic" | "quintic")` and `interpn`
//! fit): its construction time and memory against the grid size, and its
//! error against the exact spline (the 256-bit MPFR twin on the same data)
//! beside the bound it states. The study is
//! `splinelab_verify::gridded`.

use super::{Figure, Profile, ReportError, Section, TIME_BAND};
use crate::chart::{Chart, GREY, Series, line_chart};
use crate::error::CliError;
use crate::html::{num, paragraph, table};
use serde_json::json;
use splinelab::gridded::grid_spline::LANES;
use splinelab_verify::gridded::{
    AccuracyRow, CostCase, CostRow, GriddedData, GriddedParams, run_gridded,
};

const MB: f64 = 1048576.0;

/// One colour per cost case or degree, shared by its line and its markers
/// (matplotlib's first three, as the chart palette starts).
const COLORS: [u32; 3] = [0x1f77b4, 0xff7f0e, 0x2ca02c];

fn color(i: usize) -> u32 {
    COLORS[i % COLORS.len()]
}

/// Three significant digits, short: `5.9`, `148`, `1.26e5`, `3.55e-14`.
fn sig3(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return num(x);
    }
    let e = x.abs().log10().floor() as i32;
    if (-2..4).contains(&e) {
        let decimals = (2 - e).max(0) as usize;
        let t = format!("{x:.decimals$}");
        if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            t
        }
    } else {
        let t = format!("{x:.2e}");
        let (m, exp) = t.split_once('e').unwrap_or((&t, "0"));
        let m = if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.')
        } else {
            m
        };
        format!("{m}e{exp}")
    }
}

/// `d3_k3`: a cost case's key in figure names.
fn key(dims: usize, degree: usize) -> String {
    format!("d{dims}_k{degree}")
}

/// `3-D cubic`.
fn label(dims: usize, degree: usize) -> String {
    let name = match degree {
        1 => "linear".to_string(),
        3 => "cubic".to_string(),
        5 => "quintic".to_string(),
        k => format!("degree {k}"),
    };
    format!("{dims}-D {name}")
}

fn rows_of<'a>(d: &'a GriddedData, c: &CostCase) -> impl Iterator<Item = &'a CostRow> {
    let (dims, degree) = (c.dims, c.degree);
    d.cost
        .iter()
        .filter(move |r| r.dims == dims && r.degree == degree)
}

fn time_chart(d: &GriddedData) -> Chart {
    let series = d
        .params
        .cost_cases
        .iter()
        .enumerate()
        .map(|(i, c)| {
            Series::line_points(
                label(c.dims, c.degree),
                rows_of(d, c)
                    .map(|r| (r.points as f64, r.build_s))
                    .collect(),
            )
            .with_color(color(i))
        })
        .collect();
    line_chart(
        "gridded_build_time",
        "GridSpline::interpolate: construction time vs grid size",
        "grid points N",
        "seconds (median)",
        true,
        series,
        "The exact not-a-knot spline on jittered (non-uniform) grids: one banded solve per grid line along \
         each axis, so the time grows as N (a slope of 1 on these axes) once the threads have enough lines.",
    )
    .with_log_x()
}

fn memory_chart(d: &GriddedData) -> Chart {
    let mut series: Vec<Series> = Vec::new();
    if let Some(c) = d.params.cost_cases.first() {
        series.push(
            Series::line(
                "the values' bytes (f64, one value per point)",
                rows_of(d, c)
                    .map(|r| (r.points as f64, r.values_bytes as f64 / MB))
                    .collect(),
            )
            .with_color(GREY),
        );
    }
    for (i, c) in d.params.cost_cases.iter().enumerate() {
        series.push(
            Series::line(
                format!(
                    "{}: coefficients + blocks (allocated)",
                    label(c.dims, c.degree)
                ),
                rows_of(d, c)
                    .map(|r| (r.points as f64, r.stated_bytes as f64 / MB))
                    .collect(),
            )
            .with_color(color(i)),
        );
    }
    for (i, c) in d.params.cost_cases.iter().enumerate() {
        series.push(
            Series::points(
                format!("{}: peak resident, measured", label(c.dims, c.degree)),
                rows_of(d, c)
                    .filter(|r| r.peak_bytes > 0)
                    .map(|r| (r.points as f64, r.peak_bytes as f64 / MB))
                    .collect(),
            )
            .with_color(color(i)),
        );
    }
    series.retain(|s| !s.points.is_empty());
    line_chart(
        "gridded_build_memory",
        "GridSpline::interpolate: work memory vs grid size",
        "grid points N",
        "MB",
        true,
        series,
        &format!(
            "Lines: what a build allocates, the coefficient array the spline keeps (one scalar per value) plus one \
             block of n × {LANES} lines per thread. Markers: the peak anonymous resident memory of one build above \
             the start, sampled every millisecond; it sees only pages new to the process (glibc serves blocks under \
             32 MiB from memory freed earlier), so small builds show below the line or not at all (0 measured). The \
             3-D cubic and quintic lines coincide (the same grids)."
        ),
    )
    .with_log_x()
}

fn accuracy_chart(d: &GriddedData) -> Chart {
    let mut series = Vec::new();
    for (i, &k) in d.params.accuracy_degrees.iter().enumerate() {
        let rows: Vec<&AccuracyRow> = d.accuracy.iter().filter(|r| r.degree == k).collect();
        series.push(
            Series::line(
                format!("degree {k}: stated bound, error_bound()"),
                rows.iter().map(|r| (r.min_gap, r.bound)).collect(),
            )
            .with_color(color(i)),
        );
        series.push(
            Series::line_points(
                format!("degree {k}: measured max |f64 − MPFR|"),
                rows.iter()
                    .filter(|r| r.error > 0.0)
                    .map(|r| (r.min_gap, r.error))
                    .collect(),
            )
            .with_color(color(i)),
        );
    }
    series.retain(|s| !s.points.is_empty());
    let shape = d
        .params
        .accuracy_shape
        .iter()
        .map(usize::to_string)
        .collect::<Vec<_>>()
        .join("×");
    line_chart(
        "gridded_error_vs_gap",
        &format!("{shape} grid, random values: error against the exact spline vs closest node pair"),
        "closest pair of nodes on every axis",
        "absolute error",
        true,
        series,
        "The f64 spline against its 256-bit MPFR twin on the same nodes and values, at random points, beside \
         the error_bound() the f64 build states: the bound sits above every measured error.",
    )
    .with_log_x()
}

fn cost_table(d: &GriddedData) -> String {
    let rows: Vec<Vec<String>> = d
        .cost
        .iter()
        .map(|r| {
            vec![
                label(r.dims, r.degree),
                r.shape
                    .iter()
                    .map(usize::to_string)
                    .collect::<Vec<_>>()
                    .join("×"),
                r.points.to_string(),
                num(r.build_s * 1e3),
                num(r.ns_per_point),
                num(r.values_bytes as f64 / MB),
                num(r.coefficient_bytes as f64 / r.values_bytes as f64),
                num(r.block_bytes as f64 / MB),
                num(r.stated_bytes as f64 / r.values_bytes as f64),
                num(r.peak_bytes as f64 / MB),
            ]
        })
        .collect();
    table(
        &format!(
            "Construction of GridSpline<f64> (one value per point, {} threads): median time, the memory it \
             allocates (coefficients and one block of lines per thread) and the peak anonymous memory of one build \
             above the start (a lower bound: it misses pages the allocator reuses)",
            d.threads
        ),
        &[
            "spline",
            "grid",
            "points N",
            "build ms",
            "ns / point",
            "values MB",
            "coefficients / values",
            "blocks MB",
            "allocated / values",
            "peak resident MB (lower bound)",
        ],
        &rows,
    )
}

fn accuracy_table(d: &GriddedData) -> String {
    let rows: Vec<Vec<String>> = d
        .accuracy
        .iter()
        .map(|r| {
            vec![
                r.degree.to_string(),
                sig3(r.min_gap),
                r.kappas
                    .iter()
                    .map(|k| sig3(*k))
                    .collect::<Vec<_>>()
                    .join(" / "),
                sig3(r.max_coefficient),
                format!(
                    "{} ≤ {}",
                    sig3(r.coefficient_error),
                    sig3(r.coefficient_bound)
                ),
                sig3(r.max_value),
                sig3(r.error),
                sig3(r.bound),
                sig3(r.bound / r.error),
                format!("{:.1}", r.digits()),
            ]
        })
        .collect();
    table(
        &format!(
            "GridSpline<f64> against GridSpline<Mp<256>> on the same f64 nodes and values ({} random points per \
             grid, half of them around the closest pairs): the errors beside the stated bounds",
            d.params.accuracy_points
        ),
        &[
            "degree",
            "closest pair",
            "κ per axis",
            "max |c|",
            "max |ĉ − c| ≤ coefficient_error()",
            "max |s|",
            "max |ŝ − s|",
            "error_bound()",
            "bound / error",
            "digits of max |s|",
        ],
        &rows,
    )
}

fn text(d: &GriddedData) -> String {
    let mut html = paragraph(
        "GridSpline is the exact not-a-knot tensor-product spline through values on a rectilinear grid, as \
         scipy.interpolate's RegularGridInterpolator(method=\"cubic\" | \"quintic\") and interpn define it (scipy \
         approximates it with an iterative sparse solve, gcrotmk to atol = 1e-6). The collocation matrix is a \
         Kronecker product of 1-D banded matrices, so the coefficients come from one banded LU solve per grid line \
         along each axis in turn: O(N) time, the coefficient array plus one block of lines per thread of memory. \
         The grids below are jittered (gaps uniform in [0.5, 1.5) on every axis, no axis uniform), the values \
         random in [−1, 1).",
    );
    let largest = d
        .params
        .cost_cases
        .iter()
        .filter_map(|c| rows_of(d, c).last())
        .map(|r| {
            format!(
                "{} on {} points: {} s ({} ns per point), {}× the values' bytes allocated",
                label(r.dims, r.degree),
                r.points,
                num(r.build_s),
                num(r.ns_per_point),
                num(r.stated_bytes as f64 / r.values_bytes as f64)
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    html.push_str(&paragraph(&format!("Largest grids: {largest}.")));
    let worst = d
        .accuracy
        .iter()
        .map(AccuracyRow::error_over_bound)
        .fold(0.0f64, f64::max);
    let loosest = d
        .accuracy
        .iter()
        .filter(|r| r.error > 0.0)
        .map(|r| r.bound / r.error)
        .fold(0.0f64, f64::max);
    html.push_str(&paragraph(&format!(
        "Accuracy: the f64 spline against its 256-bit MPFR twin (the exact spline of the same f64 nodes and \
         values, to about 2^−256). The bound error_bound() = Σ_a κ_a (γ_3w G_a + γ_3k) M_a Π_(b>a) κ_b + the \
         evaluation's rounding holds on every grid (largest error / bound: {}); it is at most {}× the measured \
         error. κ_a grows as the closest pair of nodes closes in; the coefficients (and the spline between the \
         close nodes) grow with it, which the bound follows through M_a.",
        num(worst),
        num(loosest)
    )));
    let growth = d.accuracy.iter().map(|r| r.growth).fold(0.0f64, f64::max);
    let pivoted = d.accuracy.iter().filter(|r| r.pivoted).count();
    html.push_str(&paragraph(&format!(
        "The 1-D collocation matrices are totally nonnegative, so their LU needs no pivoting: the largest growth \
         G_a over these grids is {}, and {pivoted} of the {} grids exchanged rows. The digits column is \
         −log10(max |ŝ − s| / max |s|).",
        num(growth),
        d.accuracy.len()
    )));
    html.push_str(&cost_table(d));
    html.push_str(&accuracy_table(d));
    html
}

fn figures(d: &GriddedData) -> Vec<Figure> {
    let mut f = Vec::new();
    for c in &d.params.cost_cases {
        if let Some(r) = rows_of(d, c).last() {
            f.push(
                Figure::cost(
                    format!("gridded.build_ns_per_point.{}", key(c.dims, c.degree)),
                    r.ns_per_point,
                    "ns",
                    TIME_BAND,
                )
                .with_floor(1.0),
            );
            // From the sizes the build allocates (the thread count moves
            // it a little): gated (unit "ratio"). The measured peak is a
            // lower bound only (see CostRow::peak_bytes): shown, not a figure.
            f.push(
                Figure::cost(
                    format!("gridded.work_over_values.{}", key(c.dims, c.degree)),
                    r.stated_bytes as f64 / r.values_bytes as f64,
                    "ratio",
                    TIME_BAND,
                )
                .with_floor(1.0),
            );
        }
    }
    // The accuracy grids are the same in every profile.
    let fixed = |fig: Figure| fig.measured_over("fixed cases");
    f.push(fixed(Figure::error(
        "gridded.error_over_bound",
        d.accuracy
            .iter()
            .map(AccuracyRow::error_over_bound)
            .fold(0.0, f64::max),
        "ratio",
        1.0,
    )));
    for r in &d.accuracy {
        f.push(fixed(Figure::digits(
            format!("gridded.digits.k{}.gap{:e}", r.degree, r.min_gap),
            r.digits(),
            "digits",
            1.0,
        )));
    }
    f
}

/// Runs the gridded-spline study and presents it.
pub fn section(profile: &Profile) -> Result<Section, ReportError> {
    let params = profile.params(GriddedParams::quick, GriddedParams::full);
    let d = run_gridded(&params).map_err(CliError::numerical)?;
    Ok(Section {
        id: "gridded",
        title: "Gridded splines (RegularGridInterpolator): construction cost and accuracy".into(),
        html: text(&d),
        charts: vec![time_chart(&d), memory_chart(&d), accuracy_chart(&d)],
        summary: json!({
            "threads": d.threads,
            "cost": d.cost,
            "accuracy": d.accuracy,
            "params": d.params,
        }),
        figures: figures(&d),
    })
}
