//! Report section: Bernstein–Vandermonde conditioning (seed 001 eq 2–3).

use super::{Figure, Profile, ReportError, Section};
use crate::chart::{Chart, Series, line_chart};
use crate::error::CliError;
use crate::html::{num, paragraph, table};
use serde_json::json;
use splinelab::surface_deformation::vandermonde::NodeFamily;
use splinelab_verify::conditioning::{Basis, CondRow, REF_BITS, run_conditioning};

const HEADLINE_DEGREES: [usize; 3] = [10, 20, 30];

fn series<'a>(
    rows: &'a [CondRow],
    basis: Basis,
    nodes: NodeFamily,
) -> impl Iterator<Item = &'a CondRow> + 'a {
    rows.iter()
        .filter(move |r| r.case.basis == basis && r.case.nodes == nodes)
}

fn chart(
    id: &str,
    title: &str,
    y_label: &str,
    y_log: bool,
    series: Vec<Series>,
    caption: &str,
) -> Chart {
    line_chart(id, title, "degree n", y_label, y_log, series, caption)
}

fn cond_chart(rows: &[CondRow]) -> Chart {
    let mut s = Vec::new();
    for basis in [Basis::Bernstein, Basis::Monomial] {
        for nodes in NodeFamily::all() {
            let pts = series(rows, basis, nodes)
                .map(|r| (r.case.degree as f64, r.cond2_ref_f64))
                .collect();
            s.push(Series::line(format!("{} / {}", basis.name(), nodes), pts));
        }
    }
    chart(
        "cond_vs_degree",
        "cond₂ of Vandermonde matrices (MPFR reference)",
        "cond₂",
        true,
        s,
        "cond₂ against degree for each node family, Bernstein vs monomial basis, computed in 256-bit MPFR.",
    )
}

fn f64_vs_mpfr_chart(rows: &[CondRow]) -> Chart {
    let mut s = Vec::new();
    for basis in [Basis::Bernstein, Basis::Monomial] {
        let nodes = NodeFamily::Equispaced;
        s.push(Series::line(
            format!("{} MPFR", basis.name()),
            series(rows, basis, nodes)
                .map(|r| (r.case.degree as f64, r.cond2_ref_f64))
                .collect(),
        ));
        s.push(Series::points(
            format!("{} f64", basis.name()),
            series(rows, basis, nodes)
                .filter(|r| r.cond2_f64.is_finite())
                .map(|r| (r.case.degree as f64, r.cond2_f64))
                .collect(),
        ));
    }
    chart(
        "cond_f64_vs_mpfr",
        "cond₂ at equispaced nodes: f64 SVD vs MPFR",
        "cond₂",
        true,
        s,
        "Where the f64 markers leave the MPFR line, the f64 SVD no longer resolves σ_min: its cond₂ is wrong.",
    )
}

fn digits_chart(rows: &[CondRow]) -> Chart {
    let mut s = Vec::new();
    for basis in [Basis::Bernstein, Basis::Monomial] {
        for nodes in NodeFamily::all() {
            let pts = series(rows, basis, nodes)
                .map(|r| (r.case.degree as f64, r.cond2_digits))
                .collect();
            s.push(Series::line_points(
                format!("{} / {}", basis.name(), nodes),
                pts,
            ));
        }
    }
    s.push(Series::line(
        "worst-case prediction, bernstein / equispaced",
        series(rows, Basis::Bernstein, NodeFamily::Equispaced)
            .map(|r| (r.case.degree as f64, r.cond2_digits_predicted))
            .collect(),
    ));
    chart(
        "cond_f64_digits",
        "Decimal digits of cond₂ that f64 gets right",
        "correct digits",
        false,
        s,
        "Digits shared by the f64 cond₂ and the MPFR value; the prediction is −log10((n+1)·u·cond₂).",
    )
}

fn digits_table(rows: &[CondRow], degrees: &[usize]) -> String {
    let body: Vec<Vec<String>> = rows
        .iter()
        .filter(|r| degrees.contains(&r.case.degree))
        .map(|r| {
            vec![
                r.case.basis.name().into(),
                r.case.nodes.name().into(),
                r.case.degree.to_string(),
                r.cond2_ref[..r.cond2_ref.len().min(22)].to_string(),
                num(r.cond2_f64),
                format!("{:.1}", r.cond2_digits),
                format!("{:.1}", r.cond2_digits_predicted),
                format!("{:.1}", r.cond_inf_digits),
            ]
        })
        .collect();
    table(
        "Digits lost: f64 against the 256-bit MPFR reference",
        &[
            "basis",
            "nodes",
            "n",
            "cond₂ (MPFR)",
            "cond₂ (f64)",
            "f64 digits",
            "predicted",
            "cond_∞ f64 digits",
        ],
        &body,
    )
}

fn headline(rows: &[CondRow]) -> serde_json::Value {
    let mut out = serde_json::Map::new();
    for nodes in NodeFamily::all() {
        let picked: Vec<_> = series(rows, Basis::Bernstein, nodes)
            .filter(|r| HEADLINE_DEGREES.contains(&r.case.degree))
            .map(|r| json!({"degree": r.case.degree, "cond2": r.cond2_ref, "f64_digits": r.cond2_digits}))
            .collect();
        out.insert(nodes.name().into(), json!(picked));
    }
    json!({"reference_bits": REF_BITS, "bernstein": out})
}

/// The f64 digits of cond₂ at the headline degrees, per basis and family.
/// The f64 SVD is deterministic, so the slack only absorbs platform libm
/// differences in the Chebyshev nodes.
fn figures(rows: &[CondRow]) -> Vec<Figure> {
    rows.iter()
        .filter(|r| HEADLINE_DEGREES.contains(&r.case.degree))
        .map(|r| {
            let name = format!(
                "conditioning.cond2_f64_digits.{}.{}.n{}",
                r.case.basis.name(),
                r.case.nodes,
                r.case.degree
            );
            Figure::digits(name, r.cond2_digits, "digits", 0.5)
        })
        .collect()
}

/// Runs the conditioning study (degrees 1..30, both bases, all node
/// families) and presents it.
pub fn section(profile: &Profile) -> Result<Section, ReportError> {
    // The whole sweep takes well under a second: the quick profile keeps it.
    let _ = profile.quick;
    let degrees: Vec<usize> = (1..=30).collect();
    let rows = run_conditioning(&degrees).map_err(CliError::numerical)?;
    let mut html = paragraph(
        "Seed 001 samples a degree-n Bézier patch at (n+1)² points and inverts the Bernstein–Vandermonde \
         matrix B̃ = B_u ⊗ B_v (eq 2–3). How accurately that can be done is governed by cond(B̃) = \
         cond(B_u)·cond(B_v). Each condition number below is computed twice: in f64, and in 256-bit MPFR \
         from nodes computed in MPFR. The MPFR value is the reference; the tables give the digits the f64 \
         value shares with it, next to the −log10((n+1)·u·cond₂) that backward-error analysis predicts.",
    );
    html.push_str(&digits_table(&rows, &HEADLINE_DEGREES));
    Ok(Section {
        id: "conditioning",
        title: "Bernstein–Vandermonde conditioning".into(),
        html,
        charts: vec![
            cond_chart(&rows),
            f64_vs_mpfr_chart(&rows),
            digits_chart(&rows),
        ],
        summary: headline(&rows),
        figures: figures(&rows),
    })
}
