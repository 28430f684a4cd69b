//! The report's curve gallery as data: Catmull–Rom curves for the three
//! spacings, the loop counter-example with its self-intersection test,
//! circles. (Drawing is the report's business.)

use super::cases::{frac, loop_example};
use super::{CurvesStudyError, err};
use nalgebra::Vector2;
use serde::{Deserialize, Serialize};
use splinelab::bspline::nurbs::NurbsCurve;
use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
use splinelab::curves::rational_bezier::RationalBezier;
use splinelab::scalar::prelude::*;

/// A named polyline for the gallery.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sampled {
    /// Legend name.
    pub name: String,
    /// The points.
    pub points: Vec<[f64; 2]>,
}

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether two non-adjacent edges of the polyline cross (proper crossing).
pub fn polyline_self_intersects(p: &[[f64; 2]]) -> bool {
    let m = p.len().saturating_sub(1);
    for i in 0..m {
        for j in i + 2..m {
            let (a, b, c, d) = (p[i], p[i + 1], p[j], p[j + 1]);
            let (o1, o2) = (orient(a, b, c), orient(a, b, d));
            let (o3, o4) = (orient(c, d, a), orient(c, d, b));
            if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
                return true;
            }
        }
    }
    false
}

/// Samples the segments of a Catmull–Rom spline, `per_segment` steps each.
pub fn sample_catmull_rom<T: Real>(
    c: &CatmullRom<T, 2>,
    per_segment: usize,
) -> Result<Vec<[f64; 2]>, CurvesStudyError> {
    let mut out = Vec::new();
    for s in 0..c.segment_count() {
        for j in 0..=per_segment {
            if s > 0 && j == 0 {
                continue;
            }
            let (p, _) = c.eval_segment(s, &frac::<T>(j, per_segment)).map_err(err)?;
            out.push([p.x.to_f64(), p.y.to_f64()]);
        }
    }
    Ok(out)
}

pub(super) fn to_xy<T: Real>(p: &Vector2<T>) -> [f64; 2] {
    [p.x.to_f64(), p.y.to_f64()]
}

/// The gallery curves: Catmull–Rom data and curves, loop curves with their
/// self-intersection flags, circles.
pub(super) type Gallery = (
    Vec<[f64; 2]>,
    Vec<Sampled>,
    Vec<Sampled>,
    (bool, bool),
    Vec<Sampled>,
);

pub(super) fn gallery() -> Result<Gallery, CurvesStudyError> {
    let cr_points: Vec<[f64; 2]> = vec![
        [0.0, 0.0],
        [1.0, 3.0],
        [1.5, 3.2],
        [6.0, 0.0],
        [6.3, -0.8],
        [9.0, 2.0],
        [12.0, 0.0],
    ];
    let v: Vec<Vector2<f64>> = cr_points.iter().map(|p| Vector2::new(p[0], p[1])).collect();
    let mut catmull_rom = Vec::new();
    for s in Spacing::ALL {
        let c = CatmullRom::new(v.clone(), s, false).map_err(err)?;
        catmull_rom.push(Sampled {
            name: format!("α = {} ({})", s.alpha(), s.name()),
            points: sample_catmull_rom(&c, 48)?,
        });
    }
    let lp = loop_example::<f64>();
    let mut loop_curves = Vec::new();
    let mut crosses = Vec::new();
    for s in [Spacing::Uniform, Spacing::Centripetal] {
        let c = CatmullRom::new(lp.clone(), s, false).map_err(err)?;
        let pts = sample_catmull_rom(&c, 400)?;
        crosses.push(polyline_self_intersects(&pts));
        loop_curves.push(Sampled {
            name: format!("{} (α = {})", s.name(), s.alpha()),
            points: pts,
        });
    }
    let mut circles = Vec::new();
    for (k, &(start, sweep)) in [
        (0.0, std::f64::consts::PI),
        (std::f64::consts::PI, std::f64::consts::FRAC_PI_2),
    ]
    .iter()
    .enumerate()
    {
        let arc =
            RationalBezier::circular_arc(&Vector2::zeros(), &1.0, &start, &sweep).map_err(err)?;
        let pts = (0..=64)
            .map(|j| arc.eval(&(j as f64 / 64.0)).map(|p| to_xy(&p)))
            .collect::<Result<_, _>>()
            .map_err(err)?;
        let deg = [180, 90][k];
        circles.push(Sampled {
            name: format!("rational quadratic arc {deg}° (w = cos {}°)", deg / 2),
            points: pts,
        });
    }
    let nc = NurbsCurve::circle(&Vector2::new(0.0, 0.0), &1.25).map_err(err)?;
    let pts = (0..=128)
        .map(|j| nc.eval(&(j as f64 / 128.0)).map(|p| to_xy(&p)))
        .collect::<Result<_, _>>()
        .map_err(err)?;
    circles.push(Sampled {
        name: "NURBS circle r = 1.25 (9 points)".into(),
        points: pts,
    });
    Ok((
        cr_points,
        catmull_rom,
        loop_curves,
        (crosses[0], crosses[1]),
        circles,
    ))
}
