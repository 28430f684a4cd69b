//! Report section: S-spline coefficients, truncation errors and recommended
//! truncation widths (seed 000).

use super::{Figure, Profile, ReportError, Section};
use crate::chart::{Chart, Series};
use crate::error::CliError;
use crate::html::{num, paragraph, table};
use serde_json::json;
use splinelab_verify::sspline::{
    MP_BITS, MethodAccuracy, SsplineParams, SsplineStudy, WidthRow, run_sspline,
};

use crate::chart::line_chart as chart;

fn positive(points: impl Iterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    points.filter(|(_, y)| *y > 0.0 && y.is_finite()).collect()
}

fn decay_chart(s: &SsplineStudy) -> Chart {
    let series = s
        .decay
        .iter()
        .filter(|d| d.points.len() > 1)
        .map(|d| {
            Series::line(
                format!("m = {}", d.order),
                positive(d.points.iter().map(|(n, c)| (*n as f64, *c))),
            )
        })
        .collect();
    chart(
        "sspline_coeff_decay",
        "|c_n| against n, B-spline orders (512-bit MPFR)",
        "n",
        "|c_n|",
        true,
        series,
        "Geometric decay at the rate of the dominant pole: higher orders need far wider truncations.",
    )
}

fn error_charts(s: &SsplineStudy) -> Vec<Chart> {
    let mut charts = Vec::new();
    if let Some(cubic) = s.errors.first() {
        let pick = |f: fn(&splinelab_verify::sspline::ErrorRow) -> f64| {
            positive(cubic.rows.iter().map(|r| (r.n as f64, f(r))))
        };
        charts.push(chart(
            "sspline_errors_cubic",
            "Truncation error measures, cubic (m = 4)",
            "half-width n",
            "error",
            true,
            vec![
                Series::line_points("|c_n| (paper)", pick(|r| r.coeff)),
                Series::line_points("knot max_j |S_n(j) − δ_0j|", pick(|r| r.knot)),
                Series::line_points("uniform sup_x Σ_k |S − S_n|", pick(|r| r.uniform)),
                Series::line("tail bound", pick(|r| r.bound)),
            ],
            "knot ≤ uniform ≤ bound at every n; |c_n| sits above the uniform error by a constant factor.",
        ));
    }
    let mut series = Vec::new();
    for curve in &s.errors {
        series.push(Series::line_points(
            format!("uniform, {}", curve.family),
            positive(curve.rows.iter().map(|r| (r.n as f64, r.uniform))),
        ));
        series.push(Series::line(
            format!("|c_n|, {}", curve.family),
            positive(curve.rows.iter().map(|r| (r.n as f64, r.coeff))),
        ));
    }
    charts.push(chart(
        "sspline_errors_tension",
        "Uniform truncation error and |c_n| for Beta2 tensions",
        "half-width n",
        "error",
        true,
        series,
        "Tension β2 shrinks the pole |ξ_0| = 4/((β2+8)+√((β2+4)(β2+12))), so the basis localises.",
    ));
    charts
}

fn shape_chart(s: &SsplineStudy) -> Chart {
    let series = s
        .shapes
        .iter()
        .map(|sh| {
            Series::line(
                format!("β2 = {} (n = {})", sh.tension, sh.n),
                sh.points.clone(),
            )
        })
        .collect();
    chart(
        "sspline_basis_shapes",
        "S_{0,4}(x, β2) truncated at |c_n| < 1e-3 (paper's Figure 1)",
        "x",
        "S(x)",
        false,
        series,
        "Higher tension narrows the basis and damps its oscillation; all interpolate δ_0j at the integers.",
    )
}

fn digits_chart(s: &SsplineStudy) -> Chart {
    let mut series = Vec::new();
    for method in [
        "partial-fractions",
        "recursive-filter",
        "toeplitz-solve",
        "production",
    ] {
        let pts = s
            .accuracy
            .iter()
            .filter(|a| a.method == method)
            .filter_map(|a| a.f64_digits_lost.map(|d| (a.order as f64, d)))
            .collect();
        series.push(Series::line_points(method, pts));
    }
    chart(
        "sspline_f64_digits_lost",
        "Decimal digits lost in f64 by each coefficient method (c_0..c_60)",
        "order m",
        "log10(max ulps)",
        false,
        series,
        "Pure-f64 routes lose log10(i·cond) digits: the pole's rounding is amplified i-fold in ξ^i; \
         the production route (≥128 guard bits, rounded once) stays at 0.5 ulp.",
    )
}

fn mp_chart(s: &SsplineStudy) -> Chart {
    let mut series = Vec::new();
    for method in ["partial-fractions", "recursive-filter", "toeplitz-solve"] {
        let rows = || s.accuracy.iter().filter(move |a| a.method == method);
        series.push(Series::line_points(
            format!("{method}, raw bits"),
            rows().map(|a| (a.order as f64, a.mp_bits)).collect(),
        ));
        series.push(Series::line(
            format!("{method}, bits vs cond"),
            rows()
                .map(|a| (a.order as f64, a.mp_bits_conditioned))
                .collect(),
        ));
    }
    chart(
        "sspline_mp_bits",
        "Correct bits of c_0..c_60 in 192-bit MPFR",
        "order m",
        "bits",
        false,
        series,
        "Raw bits fall by log2(cond_i), the componentwise condition under node-value rounding; \
         relative to cond_i every method keeps the working precision.",
    )
}

fn accuracy_table(rows: &[MethodAccuracy]) -> String {
    let body: Vec<Vec<String>> = rows
        .iter()
        .map(|a| {
            vec![
                a.order.to_string(),
                a.method.clone(),
                a.f64_max_ulps
                    .map_or_else(|| a.f64_failure.clone().unwrap_or_default(), num),
                a.f64_digits_lost.map_or("—".into(), |d| format!("{d:.2}")),
                format!("{:.1}", a.mp_bits),
                num(a.cond_max),
                format!("{:.1}", a.mp_bits_conditioned),
            ]
        })
        .collect();
    table(
        &format!(
            "Coefficient accuracy: f64 and {MP_BITS}-bit MPFR against 512-bit MPFR (c_0..c_60)"
        ),
        &[
            "m",
            "method",
            "f64 max ulps",
            "f64 digits lost",
            "MPFR bits",
            "max cond_i",
            "bits vs cond",
        ],
        &body,
    )
}

fn width_table(widths: &[WidthRow], tolerances: &[f64]) -> String {
    let mut families: Vec<&str> = Vec::new();
    for w in widths {
        if !families.contains(&w.family.as_str()) {
            families.push(&w.family);
        }
    }
    let body: Vec<Vec<String>> = families
        .iter()
        .map(|f| {
            let mut row = vec![f.to_string()];
            for tol in tolerances {
                let cell: Vec<String> = ["coeff", "knot", "uniform"]
                    .iter()
                    .filter_map(|c| {
                        widths
                            .iter()
                            .find(|w| w.family == *f && w.tol == *tol && w.criterion == *c)
                            .map(|w| w.n.to_string())
                    })
                    .collect();
                row.push(cell.join(" / "));
            }
            row
        })
        .collect();
    let header: Vec<String> = std::iter::once("family".to_string())
        .chain(tolerances.iter().map(|t| format!("ε = {t:e}")))
        .collect();
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    table(
        "Recommended half-width n (coeff / knot / uniform criterion)",
        &header,
        &body,
    )
}

fn first_order_losing_a_digit(s: &SsplineStudy, method: &str) -> Option<u32> {
    s.accuracy
        .iter()
        .filter(|a| a.method == method)
        .find(|a| a.f64_digits_lost.is_none_or(|d| d >= 1.0))
        .map(|a| a.order)
}

fn summary(s: &SsplineStudy) -> serde_json::Value {
    let losing: serde_json::Map<String, serde_json::Value> = [
        "partial-fractions",
        "recursive-filter",
        "toeplitz-solve",
        "production",
    ]
    .iter()
    .map(|m| (m.to_string(), json!(first_order_losing_a_digit(s, m))))
    .collect();
    json!({
        "widths": s.widths,
        "f64_saturation": s.saturation,
        "first_order_losing_a_f64_digit": losing,
        "production_f64_max_ulps": production_max_ulps(s),
    })
}

fn production_max_ulps(s: &SsplineStudy) -> f64 {
    s.accuracy
        .iter()
        .filter(|a| a.method == "production")
        .filter_map(|a| a.f64_max_ulps)
        .fold(0.0, f64::max)
}

fn figures(s: &SsplineStudy) -> Vec<Figure> {
    let mut out = vec![Figure::error(
        "sspline.production_f64_max_ulps",
        production_max_ulps(s),
        "ulps",
        0.5,
    )];
    let min_cond_bits = s
        .accuracy
        .iter()
        .map(|a| a.mp_bits_conditioned)
        .fold(f64::INFINITY, f64::min);
    if min_cond_bits.is_finite() {
        out.push(Figure::digits(
            "sspline.mp_bits_conditioned_min",
            min_cond_bits,
            "bits",
            2.0,
        ));
    }
    for w in s.widths.iter().filter(|w| w.family == "order 4") {
        out.push(Figure::error(
            format!("sspline.width.m4.{}.tol{:e}", w.criterion, w.tol),
            w.n as f64,
            "half-width",
            0.0,
        ));
    }
    out
}

/// Runs the S-spline study and presents it.
pub fn section(profile: &Profile) -> Result<Section, ReportError> {
    let params = profile.params(SsplineParams::quick, SsplineParams::full);
    let s = run_sspline(&params).map_err(CliError::numerical)?;
    let mut html = paragraph(
        "Seed 000 builds the cardinal interpolating spline S(x) = Σ c_i β(x − i), S(j) = δ_0j, on the \
         centred B-spline of order m or on the cubic Beta2-spline with tension β2, and truncates it at \
         half-width n. The coefficients c_i = Σ_r κ_r ξ_r^|i| come from the roots ξ_r ∈ (−1, 0) of the \
         Euler–Frobenius polynomial. They are computed by three independent methods (partial fractions, \
         recursive filter, banded Toeplitz solve) and a production route (partial fractions with ≥128 guard \
         bits, rounded once). The truncation is judged by the paper's |c_n|, by the knot interpolation \
         error, by the uniform error sup_x Σ_k |S − S_n| (the worst curve error for data |P| ≤ 1), and by \
         the analytic tail bound 2 Σ_r |κ_r| |ξ_r|^(n+1)/(1 − |ξ_r|).",
    );
    html.push_str(&width_table(&s.widths, &params.tolerances));
    let sat: Vec<Vec<String>> = s
        .saturation
        .iter()
        .map(|r| vec![r.family.clone(), r.n.to_string()])
        .collect();
    html.push_str(&table(
        "f64 saturation width: smallest n with tail bound ≤ 2^−54 (wider cannot change an f64 result)",
        &["family", "n"],
        &sat,
    ));
    html.push_str(&accuracy_table(&s.accuracy));
    let mut charts = vec![decay_chart(&s)];
    charts.extend(error_charts(&s));
    charts.push(shape_chart(&s));
    charts.push(digits_chart(&s));
    charts.push(mp_chart(&s));
    Ok(Section {
        id: "sspline",
        title: "S-spline coefficients and truncation widths".into(),
        html,
        charts,
        summary: summary(&s),
        figures: figures(&s),
    })
}
