//! Report section "check": `splinelab check` run on committed third-party
//! fixtures — scipy 1.17.1's `spline_filter1d` (degrees 2–5, modes mirror,
//! reflect, grid-wrap, and float32), `map_coordinates` (1-D degrees 2, 3, 5
//! and 2-D cubic, all five modes), `BSpline.insert_knot`, and numpy's
//! `linalg.cond` of Vandermonde matrices — made once by
//! verify/fixtures/scipy/make_check_fixtures.py (no Python at report time),
//! plus `cond` on closed forms.

use super::{Figure, Profile, ReportError, Section};
use crate::array_io::interp_input;
use crate::array_io::read_1d;
use crate::check_charts::{cond_chart, error_chart};
use crate::html::{num, paragraph, table};
use crate::input::read_json;
use serde_json::{Value, json};
use splinelab_verify::check::cond::{CondInput, Norm, check_cond};
use splinelab_verify::check::interp::check_interp;
use splinelab_verify::check::knot_insertion::check_knot_insertion;
use splinelab_verify::check::prefilter::{PrefilterInput, check_prefilter, family_of_degree};
use splinelab_verify::check::rational_bspline::RationalBSpline;
use splinelab_verify::check::{CheckSummary, EXACT_MODES, Mode, UserFormat};
use splinelab_verify::conditioning::Basis;
use std::path::PathBuf;

fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../verify/fixtures/scipy")
}

fn prefilter_case(degree: usize, mode: Mode, f32: bool) -> Result<CheckSummary, ReportError> {
    let dir = fixtures().join("prefilter");
    let suffix = if f32 { "_f32" } else { "" };
    let (samples, _) = read_1d(&dir.join(format!("samples{suffix}.npy")))?;
    let (user, format) = read_1d(&dir.join(format!("d{degree}_{}{suffix}.npy", mode.name())))?;
    Ok(check_prefilter(&PrefilterInput {
        samples,
        user,
        format,
        family: family_of_degree(degree)?,
        mode,
        max_ulps: None,
    })?)
}

fn spline(v: &Value) -> Result<RationalBSpline, ReportError> {
    let list = |k: &str| -> Vec<f64> {
        v[k].as_array()
            .map(|a| a.iter().filter_map(Value::as_f64).collect())
            .unwrap_or_default()
    };
    let k = v["k"].as_u64().unwrap_or(0) as usize;
    Ok(RationalBSpline::from_f64(&list("t"), &list("c"), k)?)
}

/// The section's figures and summary entries, gathered part by part.
#[derive(Default)]
struct Gathered {
    figures: Vec<Figure>,
    summary: Vec<Value>,
}

impl Gathered {
    /// A region-summarised case (prefilter, interp): its figures
    /// `check.{family}.{name}.median_ulps` and `.max_ulps_scaled`, its
    /// summary entry, and its table row: `lead`, then reference bits,
    /// median, boundary max, interior max and max in ulps of the scale.
    fn region_case(
        &mut self,
        family: &str,
        name: &str,
        lead: Vec<String>,
        s: &CheckSummary,
    ) -> Vec<String> {
        let regions = s.regions.clone().unwrap_or_default();
        let (b, i) = (&regions["boundary"], &regions["interior"]);
        for (what, v) in [
            ("median_ulps", s.median_ulps),
            ("max_ulps_scaled", s.max_ulps_scaled),
        ] {
            let name = format!("check.{family}.{name}.{what}");
            self.figures.push(Figure::error(name, v, "ulps", 0.5));
        }
        self.summary.push(json!({"case": name, "median_ulps": s.median_ulps, "boundary_max_ulps": b.max_ulps,
            "interior_max_ulps": i.max_ulps, "max_ulps_scaled": s.max_ulps_scaled, "reference_bits": s.reference_bits}));
        let bits = s.reference_bits.map_or("-".into(), |b| b.to_string());
        let stats = [s.median_ulps, b.max_ulps, i.max_ulps, s.max_ulps_scaled].map(num);
        lead.into_iter().chain([bits]).chain(stats).collect()
    }

    /// A `cond` case: figures `check.cond.{name}.median_ulps` and
    /// `.max_ulps`, its summary entry and its table row.
    fn cond_case(&mut self, name: &str, s: &CheckSummary) -> Vec<String> {
        let worst = s.worst.as_ref().map_or(f64::NAN, |w| w.ulps);
        let cond_max = s.elements.iter().map(|e| e.reference).fold(0.0, f64::max);
        for (what, v) in [("median_ulps", s.median_ulps), ("max_ulps", worst)] {
            let name = format!("check.cond.{name}.{what}");
            self.figures.push(Figure::error(name, v, "ulps", 0.5));
        }
        self.summary.push(
            json!({"case": format!("cond_{name}"), "median_ulps": s.median_ulps,
            "max_ulps": worst, "cond_max": cond_max, "reference_bits": s.reference_bits}),
        );
        vec![
            name.into(),
            s.n.to_string(),
            num(cond_max),
            s.reference_bits.map_or("-".into(), |b| b.to_string()),
            num(s.median_ulps),
            num(worst),
        ]
    }
}

/// scipy's `map_coordinates` on the `dims`-D fixture at `degree`, `mode`.
fn interp_case(dims: usize, degree: usize, mode: Mode) -> Result<CheckSummary, ReportError> {
    let dir = fixtures().join("interp");
    let values = read_1d(&dir.join(format!("v{dims}_d{degree}_{}.npy", mode.name())))?;
    let samples = dir.join(format!("samples{dims}.npy"));
    let coords = dir.join(format!("coords{dims}.npy"));
    let input = interp_input(&samples, &coords, values, degree, mode, None)?;
    Ok(check_interp(&input)?)
}

/// The map_coordinates table rows (figures and summary into `g`).
fn interp_part(g: &mut Gathered) -> Result<Vec<Vec<String>>, ReportError> {
    let mut rows = vec![];
    for (dims, degree) in [(1, 2), (1, 3), (1, 5), (2, 3)] {
        for mode in Mode::ALL {
            let s = interp_case(dims, degree, mode)?;
            let name = format!("{dims}d_d{degree}_{}", mode.name());
            let lead = vec![format!("{dims}-D"), degree.to_string(), mode.name().into()];
            rows.push(g.region_case("scipy_map_coordinates", &name, lead, &s));
        }
    }
    Ok(rows)
}

/// numpy's `linalg.cond` on the committed node sets, one check per basis
/// and norm (the last one's chart of error against cond is kept).
fn numpy_cond(
    g: &mut Gathered,
    rows: &mut Vec<Vec<String>>,
) -> Result<Option<crate::chart::Chart>, ReportError> {
    let doc: Value = read_json(&fixtures().join("cond/numpy_cond.json"))?;
    let node_sets: Vec<Vec<f64>> = serde_json::from_value(doc["node_sets"].clone())
        .map_err(|e| crate::input::input_error(&fixtures().join("cond"), e.to_string()))?;
    let mut chart = None;
    for basis in [Basis::Monomial, Basis::Bernstein] {
        for norm in [Norm::Two, Norm::Inf] {
            let user: Vec<f64> = doc[basis.name()][norm.name()]
                .as_array()
                .map(|a| a.iter().map(|v| v.as_f64().unwrap_or(f64::NAN)).collect())
                .unwrap_or_default();
            let s = check_cond(&CondInput {
                node_sets: node_sets.clone(),
                basis,
                norm,
                user,
                format: UserFormat::F64,
                max_ulps: None,
            })?;
            let name = format!("numpy_{}_{}", basis.name(), norm.name());
            rows.push(g.cond_case(&name, &s));
            if (basis, norm) == (Basis::Monomial, Norm::Two) {
                chart = Some(cond_chart(&s));
            }
        }
    }
    Ok(chart)
}

/// Closed forms given as the user's values: monomial {0, 1} has
/// cond_∞ = 4 and cond₂ = φ² (V = [[1, 0], [1, 1]]); Bernstein {0, ½, 1}
/// has cond_∞ = 3. Their f64 roundings must check within half an ulp.
fn closed_form_cond(g: &mut Gathered, rows: &mut Vec<Vec<String>>) -> Result<(), ReportError> {
    let phi2 = (3.0 + 5f64.sqrt()) / 2.0;
    let cases = [
        (
            "monomial_01_inf",
            Basis::Monomial,
            Norm::Inf,
            vec![0.0, 1.0],
            4.0,
        ),
        (
            "monomial_01_2",
            Basis::Monomial,
            Norm::Two,
            vec![0.0, 1.0],
            phi2,
        ),
        (
            "bernstein_0h1_inf",
            Basis::Bernstein,
            Norm::Inf,
            vec![0.0, 0.5, 1.0],
            3.0,
        ),
    ];
    for (name, basis, norm, nodes, value) in cases {
        let s = check_cond(&CondInput {
            node_sets: vec![nodes],
            basis,
            norm,
            user: vec![value],
            format: UserFormat::F64,
            max_ulps: None,
        })?;
        rows.push(g.cond_case(&format!("closed_form_{name}"), &s));
    }
    Ok(())
}

/// Runs the checks and presents them.
pub fn section(_profile: &Profile) -> Result<Section, ReportError> {
    let mut g = Gathered::default();
    let mut rows = vec![];
    let mut cases: Vec<(usize, Mode, bool)> = (2..=5)
        .flat_map(|d| EXACT_MODES.into_iter().map(move |m| (d, m, false)))
        .collect();
    cases.push((3, Mode::Mirror, true));
    let mut chart = None;
    for (d, mode, f32) in cases {
        let s = prefilter_case(d, mode, f32)?;
        let name = format!("d{d}_{}{}", mode.name(), if f32 { "_f32" } else { "" });
        let lead = vec![d.to_string(), mode.name().into(), s.format.name().into()];
        rows.push(g.region_case("scipy_prefilter", &name, lead, &s));
        if (d, mode, f32) == (3, Mode::Mirror, false) {
            chart = Some(error_chart(&s));
        }
    }
    let interp_rows = interp_part(&mut g)?;
    let mut cond_rows = vec![];
    let cond_chart = numpy_cond(&mut g, &mut cond_rows)?;
    closed_form_cond(&mut g, &mut cond_rows)?;
    let ki: Value = read_json(&fixtures().join("knot_insertion.json"))?;
    let mut ki_rows = vec![];
    for (name, case) in ki["cases"].as_object().into_iter().flatten() {
        let s = check_knot_insertion(
            &spline(&case["before"])?,
            &spline(&case["after"])?,
            UserFormat::F64,
            None,
        )?;
        ki_rows.push(vec![
            name.clone(),
            num(case["x"].as_f64().unwrap_or(f64::NAN)),
            num(s.max_deviation),
            num(s.worst_x),
            s.identical.to_string(),
            s.verdict.clone(),
        ]);
        g.figures.push(Figure::error(
            format!("check.scipy_insert_knot.{name}.max_deviation"),
            s.max_deviation,
            "absolute error",
            1e-15,
        ));
        g.summary
            .push(json!({"case": name, "max_deviation": s.max_deviation, "verdict": s.verdict}));
    }
    let html = paragraph(
        "splinelab check run on scipy 1.17.1's own outputs (committed fixtures, 200 standard-normal samples). \
         The reference solves the interpolation conditions with the mode's extension directly in MPFR (banded LU), \
         certified by agreement of p and p + 64 bits. Errors are in ulps of each coefficient; 'scaled' counts the \
         largest absolute error in ulps of max |D|: scipy's recursive filter makes absolute errors, so small \
         coefficients show large per-element ulps while the scaled figure stays near 1.",
    ) + &table(
        "scipy.ndimage.spline_filter1d against the certified reference",
        &[
            "degree",
            "mode",
            "format",
            "ref. bits",
            "median ulps",
            "boundary max",
            "interior max",
            "max ulps of max|D|",
        ],
        &rows,
    ) + &paragraph(
        "scipy.ndimage.map_coordinates (prefilter on) at 80 points per case (60 from 1.5 samples before the grid \
         to 0.5 after it, 20 in the middle fifth), 200 samples (1-D) or 64 × 64 (2-D). The reference solves the \
         interpolation conditions per axis in MPFR and sums with exact rational B-spline weights; for nearest and \
         grid-constant it follows scipy's convention (samples padded by 12, the padded array filtered with the \
         reflect or mirror rule, evaluated at x + 12), which differs from the exact spline of the infinitely \
         extended signal. scipy rounds x + 12 in f64: that rounding is the whole of its larger 'scaled' errors \
         in those two modes (checked in verify/tests/it/check_interp.rs).",
    ) + &table(
        "scipy.ndimage.map_coordinates against the certified reference",
        &[
            "axes",
            "degree",
            "mode",
            "ref. bits",
            "median ulps",
            "boundary max",
            "interior max",
            "max ulps of max|f|",
        ],
        &interp_rows,
    ) + &paragraph(
        "Condition numbers: numpy.linalg.cond (2-norm by SVD, inf-norm by inverse) of the monomial and Bernstein \
         Vandermonde matrices formed in f64 on np.linspace(0, 1, m), m = 3..12, against cond of the exact nodes' \
         matrix in MPFR (certified by p / p + 64 agreement); numpy's error includes the rounding of the matrix \
         entries, amplified by the conditioning. Closed forms given as values must check within half an ulp.",
    ) + &table(
        "check cond: numpy.linalg.cond and closed forms",
        &[
            "case",
            "sets",
            "largest cond",
            "ref. bits",
            "median ulps",
            "max ulps",
        ],
        &cond_rows,
    ) + &paragraph(
        "BSpline.insert_knot: the curve before and after must be the same; judged exactly in rational arithmetic \
         with scipy's evaluation convention on the original base interval. scipy 1.17.1 at the right end of a \
         clamped cubic adds a fifth knot there and changes the value at the end point.",
    ) + &table(
        "scipy.interpolate.BSpline.insert_knot",
        &[
            "case",
            "x inserted",
            "max deviation",
            "at x",
            "identical",
            "verdict",
        ],
        &ki_rows,
    );
    Ok(Section {
        id: "check",
        title: "Checking third-party results: scipy's prefilter, map_coordinates and knot insertion, numpy's cond".into(),
        html,
        charts: chart.into_iter().chain(cond_chart).collect(),
        summary: json!(g.summary),
        figures: g.figures,
    })
}
