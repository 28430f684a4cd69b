//! The curves study as report data: the properties table in f64 and MPFR,
//! the flattening comparison and the gallery.

use super::cases::{flatten_test_curves, loop_example};
use super::gallery::{Sampled, gallery, to_xy};
use super::properties::{PropertyRow, properties};
use super::{CurvesStudyError, err};
use crate::flatten_reference::{deviation_in_mpfr, greedy_reference_segments};
use nalgebra::Vector2;
use serde::{Deserialize, Serialize};
use splinelab::bernstein::bezier::Bezier;
use splinelab::curves::flatten::{flatten, max_deviation, uniform_polyline, uniform_segments};
use splinelab::curves::greedy_flatten::flatten_greedy;
use splinelab::scalar::prelude::*;

/// Samples per polyline segment when measuring deviations.
pub const DEVIATION_SAMPLES: usize = 32;

/// Parameters of [`run_curves`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct CurvesParams {
    /// Fewer random cases.
    pub quick: bool,
}

/// One row of the flattening comparison.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FlattenRow {
    /// Test curve name.
    pub curve: String,
    /// Its degree.
    pub degree: usize,
    /// The tolerance.
    pub tol: f64,
    /// Adaptive (method 2) segment count.
    pub adaptive_segments: usize,
    /// Measured deviation of the adaptive polyline (≤ tol guaranteed).
    pub adaptive_deviation: f64,
    /// Uniform (method 1) segment count for the same maximum deviation.
    pub uniform_segments: usize,
    /// Greedy longest-chord flattening with the proven bound
    /// ([`splinelab::curves::greedy_flatten::flatten_greedy`]): segment count.
    pub greedy_segments: usize,
    /// Its deviation, judged independently in 256-bit MPFR
    /// ([`crate::flatten_reference::deviation_in_mpfr`]).
    pub greedy_deviation: f64,
    /// The greedy optimum by a sampled distance (the fewest chords any
    /// method can use, slightly optimistic:
    /// [`crate::flatten_reference::greedy_reference_segments`]).
    pub optimum_segments: usize,
}

/// Everything the report's curve gallery shows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurvesData {
    /// The verified properties.
    pub properties: Vec<PropertyRow>,
    /// Data points of the Catmull–Rom gallery.
    pub cr_points: Vec<[f64; 2]>,
    /// Catmull–Rom α = 0, ½, 1 through `cr_points`.
    pub catmull_rom: Vec<Sampled>,
    /// The loop counter-example: points, uniform and centripetal segments.
    pub loop_points: Vec<[f64; 2]>,
    /// The loop example curves.
    pub loop_curves: Vec<Sampled>,
    /// Whether uniform / centripetal self-intersect on the loop example.
    pub loop_self_intersects: (bool, bool),
    /// Rational arcs and the NURBS circle, sampled.
    pub circles: Vec<Sampled>,
    /// The flattening comparison.
    pub flatten: Vec<FlattenRow>,
    /// Adaptive and uniform polylines of the cubic at the gallery tolerance.
    pub flatten_polylines: Vec<Sampled>,
    /// The gallery tolerance of `flatten_polylines`.
    pub gallery_tol: f64,
}

fn bezier_f64(points: &[[f64; 2]]) -> Result<Bezier<f64, 2>, CurvesStudyError> {
    Bezier::new(points.iter().map(|p| Vector2::new(p[0], p[1])).collect()).map_err(err)
}

/// Samples per chord when judging the greedy polyline in MPFR and when
/// searching the sampled optimum.
const GREEDY_JUDGE_SAMPLES: usize = 32;

fn flatten_rows(tols: &[f64]) -> Result<Vec<FlattenRow>, CurvesStudyError> {
    let mut rows = Vec::new();
    for (name, pts) in flatten_test_curves() {
        let c = bezier_f64(&pts)?;
        for &tol in tols {
            let poly = flatten(&c, &tol).map_err(err)?;
            let greedy = flatten_greedy(&c, &tol).map_err(err)?;
            rows.push(FlattenRow {
                curve: name.clone(),
                degree: c.degree(),
                tol,
                adaptive_segments: poly.segments(),
                adaptive_deviation: max_deviation(&c, &poly, DEVIATION_SAMPLES).map_err(err)?,
                uniform_segments: uniform_segments(&c, &tol, DEVIATION_SAMPLES).map_err(err)?,
                greedy_segments: greedy.segments(),
                greedy_deviation: deviation_in_mpfr(&c, &greedy, GREEDY_JUDGE_SAMPLES)
                    .map_err(err)?,
                optimum_segments: greedy_reference_segments(&c, tol, GREEDY_JUDGE_SAMPLES)
                    .map_err(err)?,
            });
        }
    }
    Ok(rows)
}

/// Runs the whole study: properties in f64 and MPFR (128 bits), the gallery
/// curves, and the flattening comparison at tol 1e-3 and 1e-6.
pub fn run_curves(params: &CurvesParams) -> Result<CurvesData, CurvesStudyError> {
    let cases = if params.quick { 24 } else { 200 };
    let mut props = properties::<f64>(cases)?;
    props.extend(properties::<Mp<128>>(cases / 4)?);
    let flatten_table = flatten_rows(&[1e-3, 1e-6])?;
    let gallery_tol = 2e-2;
    let cubic = bezier_f64(&flatten_test_curves()[0].1)?;
    let adaptive = flatten(&cubic, &gallery_tol).map_err(err)?;
    let m = uniform_segments(&cubic, &gallery_tol, DEVIATION_SAMPLES).map_err(err)?;
    let uniform = uniform_polyline(&cubic, m).map_err(err)?;
    let flatten_polylines = vec![
        Sampled {
            name: format!("adaptive: {} segments", adaptive.segments()),
            points: adaptive.points.iter().map(to_xy).collect(),
        },
        Sampled {
            name: format!("uniform: {} segments", uniform.segments()),
            points: uniform.points.iter().map(to_xy).collect(),
        },
    ];
    let (cr_points, catmull_rom, loop_curves, loop_self_intersects, circles) = gallery()?;
    Ok(CurvesData {
        properties: props,
        cr_points,
        catmull_rom,
        loop_points: loop_example::<f64>().iter().map(to_xy).collect(),
        loop_curves,
        loop_self_intersects,
        circles,
        flatten: flatten_table,
        flatten_polylines,
        gallery_tol,
    })
}
