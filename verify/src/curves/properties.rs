//! The verified properties table: every construction in f64 and MPFR on
//! random cases, its worst error against the documented bound.

use super::cases::{random_point, study_arcs};
use super::measure::*;
use super::{CurvesStudyError, err};
use crate::rng::SplitMix64;
use nalgebra::{Vector2, Vector3};
use serde::{Deserialize, Serialize};
use splinelab::bspline::de_boor::BSpline;
use splinelab::bspline::knots::KnotVector;
use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
use splinelab::curves::hermite::Hermite;
use splinelab::curves::rational_bezier::RationalBezier;
use splinelab::scalar::prelude::*;
use splinelab::surface_deformation::patch::Patch;

/// One verified property with its measured worst error.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PropertyRow {
    /// The construction (`hermite`, `rational`, …).
    pub part: String,
    /// What is checked and against which reference.
    pub property: String,
    /// `f64` or `mp128`.
    pub precision: String,
    /// Worst error in units of `u` of that precision (relative to the data scale).
    pub worst_u: f64,
    /// The bound the tests assert, in the same unit.
    pub bound_u: f64,
    /// Number of cases measured.
    pub cases: usize,
}

/// The documented bounds (units of `u`) the tests assert and the table shows.
pub mod bounds {
    /// Hermite end values / derivatives / Bézier agreement.
    pub const HERMITE: f64 = 32.0;
    /// Circle / NURBS circle radial error in f64 (the 4 ulps of 1 = 8u).
    pub const CIRCLE_F64: f64 = 8.0;
    /// Circle radial error in MPFR: `2^(−BITS+8)` relative.
    pub const CIRCLE_MP: f64 = 256.0;
    /// Degree elevation.
    pub const ELEVATION: f64 = 64.0;
    /// Catmull–Rom interpolation, C¹ jump and tangent.
    pub const CATMULL_ROM: f64 = 256.0;
    /// de Boor vs Cox–de Boor, B-spline vs Bézier, patch vs NURBS.
    pub const BSPLINE: f64 = 64.0;
}

fn row(
    part: &str,
    property: &str,
    precision: &str,
    worst_u: f64,
    bound_u: f64,
    cases: usize,
) -> PropertyRow {
    PropertyRow {
        part: part.into(),
        property: property.into(),
        precision: precision.into(),
        worst_u,
        bound_u,
        cases,
    }
}

/// The worst errors over the random cases, per construction.
#[derive(Default)]
struct Worst {
    hermite: HermiteErrors,
    elevation: f64,
    catmull_rom: CatmullRomErrors,
    de_boor: f64,
    bezier_knots: f64,
    hodograph: f64,
    patch: f64,
}

impl Worst {
    /// One random case of every construction. The draws from `rng` come in
    /// a fixed order: the table's figures (and the baseline) depend on it.
    fn case<T: Real>(&mut self, rng: &mut SplitMix64, case: usize) -> Result<(), CurvesStudyError> {
        self.hermite::<T>(rng)?;
        let pts = self.rational::<T>(rng, case)?;
        self.catmull_rom::<T>(rng, case)?;
        self.bspline::<T>(rng, case)?;
        let (a, b) = bspline_vs_bezier(&pts)?;
        self.bezier_knots = self.bezier_knots.max(a);
        self.hodograph = self.hodograph.max(b);
        if case < PATCH_CASES {
            let net: Vec<Vector3<T>> = (0..16).map(|_| random_point(rng, 4.0)).collect();
            self.patch = self
                .patch
                .max(patch_vs_nurbs(&Patch::new(3, net).map_err(err)?)?);
        }
        Ok(())
    }

    fn hermite<T: Real>(&mut self, rng: &mut SplitMix64) -> Result<(), CurvesStudyError> {
        let seg = Hermite::<T, 3>::new(
            random_point(rng, 4.0),
            random_point(rng, 4.0),
            random_point(rng, 8.0),
            random_point(rng, 8.0),
        )
        .map_err(err)?;
        let (w, e) = (&mut self.hermite, hermite_errors(&seg)?);
        w.end_values = w.end_values.max(e.end_values);
        w.end_derivatives = w.end_derivatives.max(e.end_derivatives);
        w.bezier_agreement = w.bezier_agreement.max(e.bezier_agreement);
        w.conversion_derivatives = w.conversion_derivatives.max(e.conversion_derivatives);
        Ok(())
    }

    /// A rational Bézier curve of degree 2..6 elevated twice; returns its
    /// control points (reused as a B-spline with Bézier knots).
    fn rational<T: Real>(
        &mut self,
        rng: &mut SplitMix64,
        case: usize,
    ) -> Result<Vec<Vector2<T>>, CurvesStudyError> {
        let deg = 2 + case % 5;
        let pts: Vec<Vector2<T>> = (0..=deg).map(|_| random_point(rng, 4.0)).collect();
        let w: Vec<T> = (0..=deg)
            .map(|_| T::from_f64_exact(0.25 + rng.dyadic(1.0).abs() * 3.75))
            .collect();
        let curve = RationalBezier::new(pts.clone(), w).map_err(err)?;
        self.elevation = self.elevation.max(elevation_error(&curve)?);
        Ok(pts)
    }

    fn catmull_rom<T: Real>(
        &mut self,
        rng: &mut SplitMix64,
        case: usize,
    ) -> Result<(), CurvesStudyError> {
        let spacing = Spacing::ALL[case % 3];
        let cpts: Vec<Vector2<T>> = (0..6).map(|_| random_point(rng, 4.0)).collect();
        // Coincident random points are refused by the constructor: skipped.
        if let Ok(c) = CatmullRom::new(cpts, spacing, case.is_multiple_of(2)) {
            let (w, e) = (&mut self.catmull_rom, catmull_rom_errors(&c)?);
            w.interpolation = w.interpolation.max(e.interpolation);
            w.c1_jump = w.c1_jump.max(e.c1_jump);
            w.tangent = w.tangent.max(e.tangent);
        }
        Ok(())
    }

    fn bspline<T: Real>(
        &mut self,
        rng: &mut SplitMix64,
        case: usize,
    ) -> Result<(), CurvesStudyError> {
        let order = 2 + case % 4;
        let npts = order + 3;
        let mut knots: Vec<T> = (0..npts + order)
            .map(|_| T::from_f64_exact(rng.dyadic(4.0)))
            .collect();
        knots.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        let q: Vec<Vector2<T>> = (0..npts).map(|_| random_point(rng, 4.0)).collect();
        // Knot vectors with too high a multiplicity are refused: skipped.
        if let Ok(c) = KnotVector::new(knots)
            .map_err(err)
            .and_then(|k| BSpline::new(order, q, k).map_err(err))
        {
            self.de_boor = self.de_boor.max(de_boor_vs_basis(&c, 16)?);
        }
        Ok(())
    }
}

/// Random patches per precision (each costs a NURBS surface evaluation grid).
const PATCH_CASES: usize = 8;

/// The worst errors of the circle constructions (not random): rational
/// arcs, NURBS circle, NURBS cylinder, and how many arcs were measured.
fn circles<T: Real>() -> Result<(f64, f64, f64, usize), CurvesStudyError> {
    let arcs = study_arcs::<T>();
    let mut arc = 0.0f64;
    for (s, w) in &arcs {
        arc = arc.max(arc_error(s, w, 64)?);
    }
    let (circle, cylinder) = nurbs_circle_errors::<T>(64)?;
    Ok((arc, circle, cylinder, arcs.len()))
}

/// The table rows of one precision `T` measured on `cases` random cases.
pub(super) fn properties<T: Real>(cases: usize) -> Result<Vec<PropertyRow>, CurvesStudyError> {
    let name = if T::BITS == 53 {
        "f64".to_string()
    } else {
        format!("mp{}", T::BITS)
    };
    let mut rng = SplitMix64::new(0x5EED_0002);
    let mut w = Worst::default();
    for case in 0..cases {
        w.case::<T>(&mut rng, case)?;
    }
    let (arc, circle, cylinder, arcs) = circles::<T>()?;
    use bounds::*;
    let circle_bound = if T::BITS == 53 { CIRCLE_F64 } else { CIRCLE_MP };
    let h = &w.hermite;
    let table: [(&str, &str, f64, f64, usize); 15] = [
        (
            "hermite",
            "end values x(0) = x₀, x(1) = x₁",
            h.end_values,
            HERMITE,
            cases,
        ),
        (
            "hermite",
            "end derivatives x'(0), x'(1)",
            h.end_derivatives,
            HERMITE,
            cases,
        ),
        (
            "hermite",
            "Hermite (Horner) = its Bézier form (de Casteljau)",
            h.bezier_agreement,
            HERMITE,
            cases,
        ),
        (
            "hermite",
            "Bézier → Hermite: 3(P₁−P₀) = x'₀, 3(P₃−P₂) = x'₁",
            h.conversion_derivatives,
            HERMITE,
            cases,
        ),
        (
            "rational",
            "arc |P(t)| = 1, sweeps ≤ 180°",
            arc,
            circle_bound,
            arcs,
        ),
        (
            "rational",
            "degree elevation ×2 keeps the curve",
            w.elevation,
            ELEVATION,
            cases,
        ),
        ("nurbs", "NURBS circle |P(t)| = 1", circle, circle_bound, 1),
        (
            "nurbs",
            "NURBS cylinder: radius 1, z = 2v",
            cylinder,
            circle_bound,
            1,
        ),
        (
            "catmull-rom",
            "interpolation C(t_k) = P_k",
            w.catmull_rom.interpolation,
            CATMULL_ROM,
            cases,
        ),
        (
            "catmull-rom",
            "C¹: left = right derivative at knots",
            w.catmull_rom.c1_jump,
            CATMULL_ROM,
            cases,
        ),
        (
            "catmull-rom",
            "tangent = closed form q'_k(t_k)",
            w.catmull_rom.tangent,
            CATMULL_ROM,
            cases,
        ),
        (
            "bspline",
            "de Boor = Cox–de Boor basis sum",
            w.de_boor,
            BSPLINE,
            cases,
        ),
        (
            "bspline",
            "Bézier knots: de Boor = de Casteljau",
            w.bezier_knots,
            BSPLINE,
            cases,
        ),
        (
            "bspline",
            "Bézier knots: derivative = hodograph",
            w.hodograph,
            BSPLINE,
            cases,
        ),
        (
            "patch",
            "bicubic Bézier patch = NURBS surface",
            w.patch,
            BSPLINE,
            cases.min(PATCH_CASES),
        ),
    ];
    Ok(table
        .into_iter()
        .map(|(part, property, worst, bound, n)| row(part, property, &name, worst, bound, n))
        .collect())
}
