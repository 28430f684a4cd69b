//! Report section "update_cost": local S-spline edits against the global
//! cubic re-solve and knot insertion (seed 000's locality claim, seed 003),
//! the full build by truncated convolution against the recursive prefilter,
//! and pictures of the end conditions and of a locally edited surface.

use super::figure::{Better, Kind, slug};
use super::projection::{X_LABEL, Y_LABEL, project};
use super::{Figure, Profile, ReportError, Section, TIME_BAND};
use crate::chart::{Chart, Series, line_chart, xy};
use crate::error::CliError;
use crate::html::{num, paragraph, paragraph_with_code, table};
use serde_json::json;
use splinelab_verify::local_route::LocalRouteParams;
use splinelab_verify::update_cost::{
    BuildAccuracy, BuildRow, EditRow, Polyline, UpdateCostData, UpdateCostParams, Wireframe,
    run_update_cost,
};

fn lines(p: &[Polyline]) -> Vec<Series> {
    p.iter()
        .map(|l| Series::line(l.name.clone(), xy(&l.points)))
        .collect()
}

/// Wireframes in the report's 3-D view.
fn projected(w: &[Wireframe]) -> Vec<Series> {
    w.iter()
        .map(|l| {
            Series::line(
                l.name.clone(),
                l.points.iter().map(|p| project(*p)).collect(),
            )
        })
        .collect()
}

fn cost_chart(e: &[EditRow]) -> Chart {
    let s = |name: &str, f: fn(&EditRow) -> f64| {
        Series::line_points(name, e.iter().map(|r| (r.n as f64, f(r))).collect())
    };
    line_chart(
        "update_cost_vs_n",
        "Cost of one point edit vs data size N (cubic, free ends)",
        "data points N",
        "time per edit (ns)",
        true,
        vec![
            s("S-spline local shift (2n+1 axpys)", |r| r.local_ns),
            s("S-spline local recompute (bitwise = rebuild)", |r| {
                r.local_recompute_ns
            }),
            s("global natural cubic re-solve", |r| r.global_ns),
            s("Boehm knot insertion (copies the net)", |r| r.insertion_ns),
            s("Boehm knot insertion in place (O(k) + tail move)", |r| {
                r.insertion_in_place_ns
            }),
        ],
        "Local edits stay flat in N; the global re-solve and knot insertion into a new curve (which copies the control net) grow linearly; in-place insertion computes k − 1 points and moves the tail of the arrays once (a memmove, far cheaper per point).",
    )
    .with_log_x()
}

fn build_chart(b: &[BuildRow]) -> Chart {
    let mut keys: Vec<(String, String)> = Vec::new();
    for r in b {
        let k = (r.family.clone(), r.method.clone());
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    let series = keys
        .iter()
        .map(|(f, m)| {
            let pts = b
                .iter()
                .filter(|r| (&r.family, &r.method) == (f, m))
                .map(|r| (r.n as f64, r.samples_per_s))
                .collect();
            Series::line_points(format!("{f}, {m}"), pts)
        })
        .collect();
    line_chart(
        "update_cost_full_build",
        "Full build of the coefficients from N samples (f64, mirror ends)",
        "samples N",
        "samples per second",
        true,
        series,
        "Throughput of the exact recursive prefilter against the truncated convolution at two widths.",
    )
    .with_log_x()
}

fn picture_charts(d: &UpdateCostData) -> Vec<Chart> {
    let mut ends = lines(&d.end_conditions);
    ends.push(Series::points("data points", xy(&d.end_condition_data)));
    vec![
        line_chart(
            "update_cost_end_conditions",
            &format!(
                "Cubic S-spline (n = {}) through 8 points: the three end conditions",
                d.half_width
            ),
            "x",
            "y",
            false,
            ends,
            "Free ends repeat the end points, periodic closes the curve, the tangent rule reflects the data so that Q'(0) = C_n T₀ and Q'(ν−1) = C_n T₁.",
        ),
        line_chart(
            "update_cost_surface_edit",
            &format!(
                "{0}×{0} S-spline surface, one data point moved: {1} control points change",
                d.surface.side, d.surface.changed_control_points
            ),
            X_LABEL,
            Y_LABEL,
            false,
            projected(&d.surface.wireframes),
            "Oblique wireframe before (drawn on top) and after the edit: the changed surface shows only within the (2n + 1)² support around the moved point.",
        ),
    ]
}

fn edit_table(e: &[EditRow]) -> String {
    let rows: Vec<Vec<String>> = e
        .iter()
        .map(|r| {
            vec![
                r.n.to_string(),
                num(r.local_ns),
                num(r.local_recompute_ns),
                num(r.global_ns),
                num(r.insertion_ns),
                num(r.insertion_in_place_ns),
                num(r.global_ns / r.local_ns),
            ]
        })
        .collect();
    table(
        "Median time of one point edit (ns), in-process",
        &[
            "N",
            "local shift",
            "local recompute",
            "global re-solve",
            "knot insertion (copy)",
            "knot insertion (in place)",
            "global / local",
        ],
        &rows,
    )
}

fn build_table(b: &[BuildRow], a: &[BuildAccuracy]) -> String {
    let top = b.iter().map(|r| r.n).max().unwrap_or(0);
    let rows: Vec<Vec<String>> = a
        .iter()
        .map(|x| {
            let speed = b
                .iter()
                .find(|r| r.n == top && r.family == x.family && r.method == x.method)
                .map_or(String::from("–"), |r| num(r.samples_per_s));
            vec![
                x.family.clone(),
                x.method.clone(),
                x.half_width.to_string(),
                num(x.error_u),
                num(x.tail_u),
                speed,
            ]
        })
        .collect();
    table(
        &format!(
            "Full build: error against the 256-bit MPFR build (units of u, relative to ‖1/V‖₁ max|s|) and throughput at N = {top}"
        ),
        &[
            "family",
            "method",
            "n",
            "error / u",
            "truncation bound / u",
            "samples/s",
        ],
        &rows,
    )
}

fn figures(d: &UpdateCostData) -> Vec<Figure> {
    let mut f = Vec::new();
    for r in &d.edits {
        f.push(
            Figure::cost(
                format!("update_cost.local_ns.N{}", r.n),
                r.local_ns,
                "ns",
                TIME_BAND,
            )
            .with_floor(100.0),
        );
        f.push(
            Figure::cost(
                format!("update_cost.global_ns.N{}", r.n),
                r.global_ns,
                "ns",
                TIME_BAND,
            )
            .with_floor(1e3),
        );
    }
    let local: Vec<f64> = d.edits.iter().map(|r| r.local_ns).collect();
    let (lo, hi) = local
        .iter()
        .fold((f64::INFINITY, 0f64), |(a, b), &x| (a.min(x), b.max(x)));
    f.push(
        Figure::cost(
            "update_cost.local_max_over_min",
            hi / lo,
            "ratio",
            TIME_BAND,
        )
        .with_floor(1.0),
    );
    if let Some(r) = d.edits.last() {
        let speedup = r.global_ns / r.local_ns;
        f.push(Figure::new(
            format!("update_cost.global_over_local.N{}", r.n),
            speedup,
            Kind::Cost,
            "ratio",
            Better::Higher,
            TIME_BAND,
        ));
    }
    for a in &d.accuracy {
        f.push(Figure::error(
            format!("update_cost.build_error.{}.{}", a.family, slug(&a.method)),
            a.error_u,
            "u",
            1.0,
        ));
    }
    f.push(Figure::error(
        "update_cost.move_vs_rebuild",
        d.move_vs_rebuild,
        "absolute",
        0.0,
    ));
    f.push(Figure::error(
        "update_cost.shift_vs_rebuild",
        d.shift_vs_rebuild_u,
        "u",
        1.0,
    ));
    let expected = (2 * d.half_width + 1).pow(2) as f64;
    f.push(Figure::error(
        "update_cost.surface_changed_minus_expected",
        (d.surface.changed_control_points as f64 - expected).abs(),
        "control points",
        0.0,
    ));
    f
}

fn text(d: &UpdateCostData) -> String {
    let mut html = paragraph_with_code(&format!(
        "The truncated S-spline (seed 000 eq 20) holds the curve as a B-spline with control points D = c ⋆ P, so \
         moving one data point changes only the 2n + 1 control points it touches (here n = {} from the width \
         chooser at ε = {:e}, uniform criterion); a surface edit changes (2n + 1)². The global natural cubic \
         spline must re-solve its tridiagonal system. Boehm knot insertion (seed 003) into a new curve copies \
         the control net; in place (`insert_knot_in_place`) it costs k − 1 affine combinations, two binary \
         searches and one move of the arrays' tail. Timings are in-process medians of {} repeats on this \
         machine; the rigorous figures are the criterion benches: \
         `scripts/bench.sh --bench update_cost`, `--bench knot_insertion` (against scipy's \
         `BSpline.insert_knot` by `benches/scipy/insert_knot.py`) and `--bench full_build`.",
        d.half_width, d.params.tol, d.params.repeats
    ));
    html.push_str(&edit_table(&d.edits));
    html.push_str(&paragraph(&format!(
        "Local edits against a rebuild from the edited data (200 points, 50 random edits): move_point differs by \
         {} (bitwise equal when 0); the paper's shift update by {} u of ‖c‖₁ max|P|. The surface edit changed {} \
         control points, (2n + 1)² = {}.",
        num(d.move_vs_rebuild),
        num(d.shift_vs_rebuild_u),
        d.surface.changed_control_points,
        (2 * d.half_width + 1).pow(2)
    )));
    html.push_str(&paragraph(
        "Full build (what scipy.ndimage.spline_filter1d does): the exact recursive prefilter runs a causal and an \
         anti-causal first-order recursion per pole (Unser 1993) — 4p + 1 flops per sample but a serial \
         dependency chain; the truncated convolution costs n + 1 multiplications per sample, every output \
         independent. Accuracy is measured against the same build in 256-bit MPFR on the same f64 samples.",
    ));
    html.push_str(&build_table(&d.builds, &d.accuracy));
    html
}

/// Runs the update-cost study and presents it.
pub fn section(profile: &Profile) -> Result<Section, ReportError> {
    let params = profile.params(UpdateCostParams::quick, UpdateCostParams::full);
    let d = run_update_cost(&params).map_err(CliError::numerical)?;
    let mut charts = vec![cost_chart(&d.edits), build_chart(&d.builds)];
    charts.extend(picture_charts(&d));
    let local = profile.params(LocalRouteParams::quick, LocalRouteParams::full);
    let (engine_html, engine_charts, engine_summary, engine_figures) =
        super::update_cost_engine::part(local)?;
    charts.extend(engine_charts);
    let mut figures = figures(&d);
    figures.extend(engine_figures);
    Ok(Section {
        id: "update_cost",
        title: "Local vs global update cost, and the full build".into(),
        html: text(&d) + &engine_html,
        charts,
        summary: json!({
            "engine": engine_summary,
            "n": d.edits.iter().map(|r| r.n).collect::<Vec<_>>(),
            "local_ns": d.edits.iter().map(|r| r.local_ns).collect::<Vec<_>>(),
            "global_ns": d.edits.iter().map(|r| r.global_ns).collect::<Vec<_>>(),
            "local_recompute_ns": d.edits.iter().map(|r| r.local_recompute_ns).collect::<Vec<_>>(),
            "insertion_ns": d.edits.iter().map(|r| r.insertion_ns).collect::<Vec<_>>(),
            "insertion_in_place_ns": d.edits.iter().map(|r| r.insertion_in_place_ns).collect::<Vec<_>>(),
            "half_width": d.half_width,
            "builds": d.builds,
            "accuracy": d.accuracy,
            "move_vs_rebuild": d.move_vs_rebuild,
            "shift_vs_rebuild_u": d.shift_vs_rebuild_u,
            "surface_changed_control_points": d.surface.changed_control_points,
        }),
        figures,
    })
}
