//! Report section: quaternion-integral curves, G2 interpolation by Newton
//! (seed 004).

use super::projection::{X_LABEL, Y_LABEL, project};
use super::{Figure, Profile, ReportError, Section};
use crate::chart::{Chart, Series};
use crate::html::{escape, num, paragraph, table};
use serde_json::json;
use splinelab_verify::qi::{
    ConvergenceRun, CurvaturePlot, Curve3d, IterationRow, QiParams, QiStudy, RandomStudy, run_qi,
};

use crate::chart::line_chart as chart;

fn label(r: &ConvergenceRun) -> String {
    format!(
        "{} {}{}",
        r.case,
        r.precision,
        if r.damped { " damped" } else { "" }
    )
}

/// log10 of the residuals on a linear axis: MPFR residuals go below f64's range.
fn residual_chart(runs: &[ConvergenceRun]) -> Chart {
    let series = runs
        .iter()
        .filter(|r| !r.damped)
        .map(|r| {
            let pts = r
                .log10_residuals
                .iter()
                .enumerate()
                .filter_map(|(k, l)| l.map(|l| (k as f64, l)))
                .collect();
            Series::line_points(label(r), pts)
        })
        .collect();
    chart(
        "qi_residuals",
        "Newton residual ‖F(x_k)‖₂ per iteration",
        "iteration k",
        "log10 ‖F(x_k)‖₂",
        false,
        series,
        "Each MPFR run doubles its correct digits per step (1e-5, 1e-10, 1e-20, 1e-40, …) down to its own \
         rounding level; f64 stops at ~1e-15.",
    )
}

fn order_chart(runs: &[ConvergenceRun]) -> Chart {
    let mut series: Vec<Series> = runs
        .iter()
        .filter(|r| !r.damped && r.bits > 53)
        .map(|r| {
            let pts = r
                .observed_orders
                .iter()
                .enumerate()
                .filter_map(|(k, p)| p.map(|p| (k as f64 + 1.0, p)))
                .collect();
            Series::line_points(label(r), pts)
        })
        .collect();
    let kmax = runs
        .iter()
        .map(|r| r.log10_residuals.len())
        .max()
        .unwrap_or(2) as f64;
    series.push(Series::line("order 2", vec![(1.0, 2.0), (kmax, 2.0)]));
    chart(
        "qi_observed_order",
        "Observed order log(r_{k+1}/r_k) / log(r_k/r_{k−1})",
        "iteration k",
        "observed order",
        false,
        series,
        "The estimate approaches 2 (quadratic convergence) until the residual reaches the rounding floor \
         of the precision, where the last value drops.",
    )
}

fn iterations_chart(rows: &[IterationRow]) -> Chart {
    let mut series = Vec::new();
    for fam in ["helix", "circle", "wave"] {
        for damped in [false, true] {
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.family == fam && r.damped == damped && r.converged)
                .map(|r| (r.points as f64, r.iterations as f64))
                .collect();
            let name = format!("{fam}{}", if damped { " damped" } else { "" });
            series.push(if damped {
                Series::points(name, pts)
            } else {
                Series::line(name, pts)
            });
        }
    }
    chart(
        "qi_iterations_vs_n",
        "Newton iterations against the number of points (f64)",
        "number of points",
        "iterations",
        false,
        series,
        "Converged runs only; failures are listed in the table below. The count does not grow with n for \
         smooth data.",
    )
}

fn success_chart(r: &RandomStudy) -> Chart {
    let pts = |bins: &[(f64, usize, f64, f64)], w: f64, damped: bool| {
        bins.iter()
            .map(|b| (b.0 + w / 2.0, if damped { b.3 } else { b.2 }))
            .collect::<Vec<_>>()
    };
    chart(
        "qi_success_rate",
        "Success rate on random point sets",
        "bin centre (degrees)",
        "success rate",
        false,
        vec![
            Series::line_points(
                "plain, by largest turning angle",
                pts(&r.by_turn, 30.0, false),
            ),
            Series::line_points(
                "damped, by largest turning angle",
                pts(&r.by_turn, 30.0, true),
            ),
            Series::line_points(
                "plain, by smallest chord angle to ±v_x",
                pts(&r.by_pole_angle, 15.0, false),
            ),
            Series::line_points(
                "damped, by smallest chord angle to ±v_x",
                pts(&r.by_pole_angle, 15.0, true),
            ),
        ],
        "Random walks (4–8 points). Success = Newton converged and the independent re-integration hits every \
         point to 1e-12. Failures concentrate where a chord runs close to ±v_x, the poles of the (α, β) chart.",
    )
}

fn curvature_chart(c: &CurvaturePlot) -> Chart {
    let v = |p: &[[f64; 2]]| p.iter().map(|q| (q[0], q[1])).collect::<Vec<_>>();
    chart(
        "qi_curvature_fig2",
        "Figure 2: curvature κ(s) of the QI interpolant vs cubic splines",
        "arc length s",
        "curvature κ",
        false,
        vec![
            Series::line("QI (3 quadratic segments, G2)", v(&c.qi)),
            Series::line("cubic spline, chord-length knots", v(&c.spline_chord)),
            Series::line("cubic spline, uniform knots", v(&c.spline_uniform)),
            Series::points("QI joints", c.qi_joints.iter().map(|&s| (s, 0.0)).collect()),
        ],
        "The paper's comparison on 4 points with the circle end tangents (unit slope for the splines). \
         The QI curvature is continuous (G2) and piecewise smooth.",
    )
}

/// The QI space curve and its data in the report's 3-D view.
fn curve_chart(c: &Curve3d) -> Chart {
    let proj = |p: &[f64; 3]| project(*p);
    chart(
        "qi_curve_3d",
        &format!("{}: QI interpolant (oblique view)", c.case),
        X_LABEL,
        Y_LABEL,
        false,
        vec![
            Series::line("QI curve", c.samples.iter().map(proj).collect()),
            Series::points("data points", c.points.iter().map(proj).collect()),
        ],
        "Oblique view of the interpolating curve and its data points.",
    )
}

fn last_log(r: &ConvergenceRun) -> Option<f64> {
    r.log10_residuals.last().copied().flatten()
}

fn convergence_table(runs: &[ConvergenceRun]) -> String {
    let rows: Vec<Vec<String>> = runs
        .iter()
        .map(|r| {
            let check = r.check.as_ref();
            vec![
                r.case.clone(),
                r.precision.clone(),
                if r.damped { "yes" } else { "no" }.into(),
                r.converged.to_string(),
                r.iterations.to_string(),
                r.residuals.last().cloned().unwrap_or_default(),
                r.observed_orders
                    .iter()
                    .flatten()
                    .map(|p| format!("{p:.2}"))
                    .collect::<Vec<_>>()
                    .join(" "),
                r.quad_order.map_or("-".into(), |m| m.to_string()),
                check.map_or("-".into(), |c| num(c.max_end_error)),
                check.map_or("-".into(), |c| num(c.max_g1_error)),
                check.map_or("-".into(), |c| num(c.max_g2_error)),
                r.failure.clone().unwrap_or_default(),
            ]
        })
        .collect();
    table(
        "Newton convergence; the last three columns re-integrate the result at twice the precision",
        &[
            "points",
            "precision",
            "damped",
            "converged",
            "iterations",
            "final ‖F‖₂",
            "observed orders",
            "Gauss order",
            "end error / diam",
            "G1 |ΔT|",
            "G2 h|Δκ⃗|",
            "failure",
        ],
        &rows,
    )
}

fn failures_table(study: &QiStudy) -> String {
    let mut rows: Vec<Vec<String>> = Vec::new();
    for (variant, map) in [
        ("plain", &study.random.plain_failures),
        ("damped", &study.random.damped_failures),
    ] {
        for (reason, count) in map {
            rows.push(vec![variant.into(), reason.clone(), count.to_string()]);
        }
    }
    for r in study.iterations_vs_n.iter().filter(|r| !r.converged) {
        rows.push(vec![
            format!(
                "{} {} points{}",
                r.family,
                r.points,
                if r.damped { " damped" } else { "" }
            ),
            r.failure.clone().unwrap_or_default(),
            "1".into(),
        ]);
    }
    if rows.is_empty() {
        return paragraph("No failures.");
    }
    table(
        "Failures, by reason (none hidden)",
        &["run", "reason", "count"],
        &rows,
    )
}

fn random_examples(r: &RandomStudy) -> String {
    let rows: Vec<Vec<String>> = r
        .rows
        .iter()
        .filter(|x| !x.plain.success || !x.damped.success)
        .take(15)
        .map(|x| {
            vec![
                x.seed.to_string(),
                x.points.to_string(),
                format!("{:.0}", x.max_turn_deg),
                format!("{:.1}", x.pole_angle_deg),
                x.plain.reason.clone().unwrap_or("ok".into()),
                x.damped.reason.clone().unwrap_or("ok".into()),
            ]
        })
        .collect();
    if rows.is_empty() {
        return String::new();
    }
    table(
        "Failing random sets (first 15; seeds reproduce them with splinelab_verify::qi::random_walk)",
        &[
            "seed",
            "points",
            "max turn °",
            "min chord angle to ±v_x °",
            "plain",
            "damped",
        ],
        &rows,
    )
}

fn helix_note(runs: &[ConvergenceRun]) -> (String, serde_json::Value) {
    let picked: Vec<&ConvergenceRun> = runs
        .iter()
        .filter(|r| r.case == "helix-10" && !r.damped)
        .collect();
    let text = picked
        .iter()
        .map(|r| {
            format!(
                "{}: {} iterations, final ‖F‖₂ = {}",
                r.precision,
                r.iterations,
                r.residuals.last().cloned().unwrap_or_default()
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    let js = picked
        .iter()
        .map(|r| {
            json!({"precision": r.precision, "iterations": r.iterations, "final_residual": r.residuals.last(),
                   "max_end_error": r.check.as_ref().map(|c| c.max_end_error)})
        })
        .collect();
    (
        format!("Helix, 10 points — {text}."),
        serde_json::Value::Array(js),
    )
}

fn figures(study: &QiStudy) -> Vec<Figure> {
    let mut f = Vec::new();
    for r in study
        .convergence
        .iter()
        .filter(|r| r.case == "helix-10" && !r.damped && r.converged)
    {
        f.push(Figure::new(
            format!("qi.helix10.{}.iterations", r.precision),
            r.iterations as f64,
            super::figure::Kind::Cost,
            "iterations",
            super::figure::Better::Lower,
            1.5,
        ));
        if let Some(c) = &r.check {
            // Correct bits of the interpolation, −log2(end error), capped at the precision.
            let bits = if c.max_end_error > 0.0 {
                (-c.max_end_error.log2()).min(r.bits as f64)
            } else {
                r.bits as f64
            };
            f.push(Figure::digits(
                format!("qi.helix10.{}.end_error_bits", r.precision),
                bits,
                "bits",
                4.0,
            ));
        }
    }
    let n = study.random.sets.max(1) as f64;
    f.push(Figure::digits(
        "qi.random.plain_success_rate",
        study.random.plain_successes as f64 / n,
        "fraction",
        0.03,
    ));
    f.push(Figure::digits(
        "qi.random.damped_success_rate",
        study.random.damped_successes as f64 / n,
        "fraction",
        0.03,
    ));
    f
}

/// Runs the QI study (quick: 50 random sets, 13 sizes, no `Mp<1024>`;
/// full: 1,000 sets, n = 3..50, `Mp<1024>`) and presents it.
pub fn section(profile: &Profile) -> Result<Section, ReportError> {
    let params = profile.params(QiParams::quick, QiParams::full);
    let study = run_qi(&params);
    let (note, note_json) = helix_note(&study.convergence);
    let mut html = paragraph(
        "Seed 004 interpolates 3D points P_0..P_n by n quadratic quaternion-integral segments \
         C_i(t) = P_i + l_i ∫₀ᵗ q v_x q⁻¹ dτ with q = cos β + (0, 0, cos α, sin α) sin β and α, β quadratic \
         Bernstein polynomials: 7n unknowns, 7n − 4 G0/G1/G2 equations (eq 18–22) plus the end tangents of the \
         circles through the first and last three points. Newton's method uses the exact Jacobian of the \
         discretised system (derivatives under the integral, same Gauss–Legendre rule, nodes computed in the \
         working precision; the rule's order is chosen by doubling). Every converged fit is re-integrated at \
         twice the precision with a freshly chosen rule: that independent check gives the end-point, G1 and \
         G2 errors below.",
    );
    html.push_str(&paragraph(&note));
    html.push_str(&convergence_table(&study.convergence));
    let r = &study.random;
    html.push_str(&paragraph(&format!(
        "Random point sets: {} of {} succeed with plain Newton, {} with damped Newton.",
        r.plain_successes, r.sets, r.damped_successes
    )));
    html.push_str(&failures_table(&study));
    html.push_str(&random_examples(r));
    for e in &study.plot_errors {
        html.push_str(&format!("<p><b>Plot not drawn:</b> {}</p>\n", escape(e)));
    }
    let mut charts = vec![
        residual_chart(&study.convergence),
        order_chart(&study.convergence),
        iterations_chart(&study.iterations_vs_n),
        success_chart(r),
    ];
    if let Some(c) = &study.curvature {
        charts.push(curvature_chart(c));
    }
    if let Some(c) = &study.curve {
        charts.push(curve_chart(c));
    }
    let summary = json!({
        "helix10": note_json,
        "random": {"sets": r.sets, "plain_successes": r.plain_successes, "damped_successes": r.damped_successes,
                   "plain_failures": r.plain_failures, "damped_failures": r.damped_failures},
        "iterations_vs_n_failures": study.iterations_vs_n.iter().filter(|x| !x.converged).count(),
        "mp_final_log10_residual": study.convergence.iter().filter(|x| x.bits > 53)
            .map(|x| json!({"case": x.case, "precision": x.precision, "log10": last_log(x)})).collect::<Vec<_>>(),
        "curvature_max_joint_jump": study.curvature.as_ref().map(|c| c.qi_max_joint_jump),
    });
    Ok(Section {
        id: "qi",
        title: "Quaternion-integral curves: G2 interpolation by Newton".into(),
        html,
        charts,
        summary,
        figures: figures(&study),
    })
}
