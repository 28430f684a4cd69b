//! One construction of seed 002 measured against an independent reference
//! (the exact data, a second algorithm or a closed form), in units of `u`
//! relative to the scale of the data.

use super::cases::frac;
use super::{CurvesStudyError, err};
use crate::flatten_reference::deviation_in_mpfr;
use crate::metrics::{dist_ref, fl, in_u, radial_error_u, ref_prec, scale};
use nalgebra::{SVector, Vector2, Vector3};
use rug::Float;
use serde::{Deserialize, Serialize};
use splinelab::bernstein::bezier::Bezier;
use splinelab::bspline::de_boor::BSpline;
use splinelab::bspline::knots::KnotVector;
use splinelab::bspline::nurbs::{NurbsCurve, NurbsSurface};
use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
use splinelab::curves::flatten::flatten;
use splinelab::curves::hermite::Hermite;
use splinelab::curves::rational_bezier::RationalBezier;
use splinelab::scalar::prelude::*;
use splinelab::surface_deformation::patch::Patch;

/// Worst errors of cubic Hermite segments, in units of `u` relative to the
/// data scale: end values, end derivatives, and Hermite vs its Bézier form
/// evaluated by de Casteljau at 17 parameters.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct HermiteErrors {
    /// `max |x(0) − x_0|, |x(1) − x_1|`.
    pub end_values: f64,
    /// `max |x'(0) − x'_0|, |x'(1) − x'_1|`.
    pub end_derivatives: f64,
    /// `max_t |Hermite(t) − Bézier(t)|`.
    pub bezier_agreement: f64,
    /// `max |3(P_1 − P_0) − x'_0|, |3(P_3 − P_2) − x'_1|` after conversion.
    pub conversion_derivatives: f64,
}

/// Measures [`HermiteErrors`] for one segment.
pub fn hermite_errors<T: Real, const D: usize>(
    h: &Hermite<T, D>,
) -> Result<HermiteErrors, CurvesStudyError> {
    let (p0, p1, d0, d1) = h.ends();
    let s = scale(&[p0.clone(), p1.clone(), d0.clone(), d1.clone()]);
    let e = |a: &SVector<T, D>, b: &SVector<T, D>| in_u::<T>(&dist_ref(a, b), s);
    let (z, o) = (T::zero(), T::one());
    let bez = h.to_bezier().map_err(err)?;
    let back = Hermite::from_bezier(&bez).map_err(err)?;
    let (_, _, bd0, bd1) = back.ends();
    let mut agree = 0.0f64;
    for j in 0..=16 {
        let t = frac::<T>(j, 16);
        agree = agree.max(e(&h.eval(&t), &bez.eval(&t).map_err(err)?));
    }
    Ok(HermiteErrors {
        end_values: e(&h.eval(&z), p0).max(e(&h.eval(&o), p1)),
        end_derivatives: e(&h.derivative(&z), d0).max(e(&h.derivative(&o), d1)),
        bezier_agreement: agree,
        conversion_derivatives: e(bd0, d0).max(e(bd1, d1)),
    })
}

/// Worst radial error (units of `u`) of the quadratic rational arc of the
/// unit circle from `start` through `sweep` at `samples + 1` parameters.
pub fn arc_error<T: Real>(start: &T, sweep: &T, samples: usize) -> Result<f64, CurvesStudyError> {
    let c = Vector2::zeros();
    let arc = RationalBezier::circular_arc(&c, &T::one(), start, sweep).map_err(err)?;
    let mut worst = 0.0f64;
    for j in 0..=samples {
        let p = arc.eval(&frac::<T>(j, samples)).map_err(err)?;
        worst = worst.max(radial_error_u(&p, &c, &T::one()));
    }
    Ok(worst)
}

/// Worst radial error (units of `u`) of the NURBS unit circle at
/// `samples + 1` parameters, and of the cylinder `r = 1`, `h = 2` on a
/// `samples × 4` grid (distance from the axis, and `|z − 2v|`).
pub fn nurbs_circle_errors<T: Real>(samples: usize) -> Result<(f64, f64), CurvesStudyError> {
    let c = Vector2::zeros();
    let circle = NurbsCurve::circle(&c, &T::one()).map_err(err)?;
    let mut worst_circle = 0.0f64;
    for j in 0..=samples {
        let p = circle.eval(&frac::<T>(j, samples)).map_err(err)?;
        worst_circle = worst_circle.max(radial_error_u(&p, &c, &T::one()));
    }
    let cyl = NurbsSurface::cylinder(&T::one(), &T::from_int(2)).map_err(err)?;
    let mut worst_cyl = 0.0f64;
    for j in 0..=samples {
        for i in 0..=4 {
            let (u, v) = (frac::<T>(j, samples), frac::<T>(i, 4));
            let p = cyl.eval(&u, &v).map_err(err)?;
            let xy = Vector2::new(p.x.clone(), p.y.clone());
            let z_err = in_u::<T>(&(fl(&p.z) - fl(&v) * 2u32).abs(), 2.0);
            worst_cyl = worst_cyl.max(radial_error_u(&xy, &c, &T::one())).max(z_err);
        }
    }
    Ok((worst_circle, worst_cyl))
}

/// Worst distance (units of `u`, relative to the control-point scale)
/// between a rational Bézier curve and its twice degree-elevated form at 33
/// parameters.
pub fn elevation_error<T: Real, const D: usize>(
    c: &RationalBezier<T, D>,
) -> Result<f64, CurvesStudyError> {
    let e = c.elevate().elevate();
    let pts: Vec<_> = (0..=c.degree()).filter_map(|i| c.point(i)).collect();
    let s = scale(&pts);
    let mut worst = 0.0f64;
    for j in 0..=32 {
        let t = frac::<T>(j, 32);
        let d = dist_ref(&c.eval(&t).map_err(err)?, &e.eval(&t).map_err(err)?);
        worst = worst.max(in_u::<T>(&d, s));
    }
    Ok(worst)
}

/// Catmull–Rom errors in units of `u` relative to the data scale:
/// interpolation at every knot, the C¹ jump between adjacent segments, and
/// the tangent at each interior knot against seed 002's closed form
/// `(P_k − P_{k−1})/a − (P_{k+1} − P_{k−1})/(a + b) + (P_{k+1} − P_k)/b`
/// (derivative of the level-2 quadratic at `t_k`, evaluated in the
/// reference precision with `a`, `b` the exact chord powers).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct CatmullRomErrors {
    /// `max |C(t_k) − P_k|`.
    pub interpolation: f64,
    /// `max |C'_left(t_k) − C'_right(t_k)|` over interior knots.
    pub c1_jump: f64,
    /// `max |C'(t_k) − closed form|`.
    pub tangent: f64,
}

fn interval_ref<T: Real, const D: usize>(
    a: &SVector<T, D>,
    b: &SVector<T, D>,
    s: Spacing,
) -> Float {
    let d = dist_ref(a, b);
    match s {
        Spacing::Uniform => Float::with_val(ref_prec::<T>(), 1),
        Spacing::Centripetal => d.sqrt(),
        Spacing::Chordal => d,
    }
}

/// Measures [`CatmullRomErrors`].
pub fn catmull_rom_errors<T: Real, const D: usize>(
    c: &CatmullRom<T, D>,
) -> Result<CatmullRomErrors, CurvesStudyError> {
    let pts = c.points();
    let n = pts.len();
    let s = scale(pts);
    let mut out = CatmullRomErrors::default();
    let p = ref_prec::<T>();
    let mut dscale = 0.0f64;
    let mut tangent_err = Vec::new();
    for seg in 0..c.segment_count() {
        let k = if c.is_closed() { seg } else { seg + 1 };
        let (start, d_start) = c.eval_segment(seg, &T::zero()).map_err(err)?;
        let (end, d_end) = c.eval_segment(seg, &T::one()).map_err(err)?;
        out.interpolation = out
            .interpolation
            .max(in_u::<T>(&dist_ref(&start, &pts[k % n]), s))
            .max(in_u::<T>(&dist_ref(&end, &pts[(k + 1) % n]), s));
        dscale = dscale.max(scale(&[d_start.clone(), d_end.clone()]));
        if seg + 1 < c.segment_count() || c.is_closed() {
            let next = (seg + 1) % c.segment_count();
            let (_, d_next) = c.eval_segment(next, &T::zero()).map_err(err)?;
            tangent_err.push((dist_ref(&d_end, &d_next), None));
        }
        // Closed-form tangent at P_k.
        let (pm, pk, pp) = (&pts[(k + n - 1) % n], &pts[k % n], &pts[(k + 1) % n]);
        let (a, b) = (
            interval_ref(pm, pk, c.spacing()),
            interval_ref(pk, pp, c.spacing()),
        );
        let ab = Float::with_val(p, &a + &b);
        let mut d2 = Float::with_val(p, 0);
        for i in 0..D {
            let (xm, xk, xp) = (fl(&pm[i]), fl(&pk[i]), fl(&pp[i]));
            let m = Float::with_val(p, &xk - &xm) / &a - Float::with_val(p, &xp - &xm) / &ab
                + Float::with_val(p, &xp - &xk) / &b;
            let diff = Float::with_val(p, m - fl(&d_start[i]));
            d2 += diff.square();
        }
        tangent_err.push((Float::with_val(p, 0), Some(d2.sqrt())));
    }
    let ds = dscale.max(1e-300);
    for (jump, tan) in tangent_err {
        out.c1_jump = out.c1_jump.max(in_u::<T>(&jump, ds));
        if let Some(t) = tan {
            out.tangent = out.tangent.max(in_u::<T>(&t, ds));
        }
    }
    Ok(out)
}

/// The flatness guarantee measured independently of core: the largest
/// distance from the curve to the polyline, judged in 256-bit MPFR at
/// `samples` points per segment ([`deviation_in_mpfr`]), divided by `tol`
/// (must be ≤ 1), and the number of segments.
pub fn flatten_excess<T: Real, const D: usize>(
    curve: &Bezier<T, D>,
    tol: &T,
    samples: usize,
) -> Result<(f64, usize), CurvesStudyError> {
    let poly = flatten(curve, tol).map_err(err)?;
    let dev = deviation_in_mpfr(curve, &poly, samples).map_err(err)?;
    Ok((dev / tol.to_f64(), poly.segments()))
}

/// Worst `|de Boor − Σ N_j Q_j|` (Cox–de Boor basis sum, a second
/// algorithm) in units of `u` over `samples + 1` parameters of the domain.
pub fn de_boor_vs_basis<T: Real, const D: usize>(
    c: &BSpline<T, D>,
    samples: usize,
) -> Result<f64, CurvesStudyError> {
    let s = scale(c.points());
    let (lo, hi) = c.domain();
    let mut worst = 0.0f64;
    for j in 0..=samples {
        let t = lo.clone() + (hi.clone() - lo.clone()) * frac::<T>(j, samples);
        let (span, n) = c.basis_functions(&t).map_err(err)?;
        let k = c.order();
        let sum = n
            .iter()
            .enumerate()
            .fold(SVector::<T, D>::zeros(), |acc, (i, ni)| {
                acc + &c.points()[span + 1 - k + i] * ni.clone()
            });
        worst = worst.max(in_u::<T>(&dist_ref(&c.eval(&t).map_err(err)?, &sum), s));
    }
    Ok(worst)
}

/// A clamped B-spline with Bézier knots `0^k 1^k` is the Bézier curve of the
/// same points: worst `|de Boor − de Casteljau|` and worst
/// `|B-spline derivative − n·hodograph|` (units of `u`) at `t = j/31`.
/// (With these knots de Boor's `α` equals `t`, so the two agree bit for bit
/// in practice: the check guards the span logic and the knot bookkeeping.)
pub fn bspline_vs_bezier<T: Real, const D: usize>(
    points: &[SVector<T, D>],
) -> Result<(f64, f64), CurvesStudyError> {
    let k = points.len();
    let knots = KnotVector::clamped_uniform(k, k).map_err(err)?;
    let b = BSpline::new(k, points.to_vec(), knots).map_err(err)?;
    let bez = Bezier::new(points.to_vec()).map_err(err)?;
    let n = T::from_int(k as i64 - 1);
    let hodo: Vec<_> = points
        .windows(2)
        .map(|w| (&w[1] - &w[0]) * n.clone())
        .collect();
    let hodo = Bezier::new(hodo).map_err(err)?;
    let s = scale(points);
    let (mut e0, mut e1) = (0.0f64, 0.0f64);
    for j in 0..=31 {
        let t = frac::<T>(j, 31);
        e0 = e0.max(in_u::<T>(
            &dist_ref(&b.eval(&t).map_err(err)?, &bez.eval(&t).map_err(err)?),
            s,
        ));
        let d = b.eval_derivative(&t, 1).map_err(err)?;
        e1 = e1.max(in_u::<T>(
            &dist_ref(&d, &hodo.eval(&t).map_err(err)?),
            s * (k as f64),
        ));
    }
    Ok((e0, e1))
}

/// A tensor Bézier patch ([`Patch`], reused from seed 001) against the
/// NURBS surface with Bézier knots and unit weights on the same net: worst
/// distance in units of `u` on the grid `(i/7, j/7)` (non-dyadic, so the
/// two algorithms round differently).
pub fn patch_vs_nurbs<T: Real>(patch: &Patch<T>) -> Result<f64, CurvesStudyError> {
    let n = patch.degree();
    let k = n + 1;
    let knots = || KnotVector::clamped_uniform(k, k).map_err(err);
    let surf = NurbsSurface::new(
        (k, k),
        (k, k),
        patch.control().to_vec(),
        vec![T::one(); k * k],
        (knots()?, knots()?),
    )
    .map_err(err)?;
    let s = scale(patch.control());
    let mut worst = 0.0f64;
    for i in 0..=7 {
        for j in 0..=7 {
            let (u, v) = (frac::<T>(i, 7), frac::<T>(j, 7));
            let a: Vector3<T> = patch.eval(&u, &v).map_err(err)?;
            worst = worst.max(in_u::<T>(
                &dist_ref(&a, &surf.eval(&u, &v).map_err(err)?),
                s,
            ));
        }
    }
    Ok(worst)
}

/// The smallest speed `|C'|` over dense samples of segment `seg`, relative
/// to the chord length of that segment (0 means a cusp).
pub fn min_relative_speed<T: Real>(
    c: &CatmullRom<T, 2>,
    seg: usize,
    samples: usize,
) -> Result<f64, CurvesStudyError> {
    let (a, _) = c.eval_segment(seg, &T::zero()).map_err(err)?;
    let (b, _) = c.eval_segment(seg, &T::one()).map_err(err)?;
    let dt = (c.knots()[seg + 1].clone() - c.knots()[seg].clone()).to_f64();
    let chord = (b - a).norm().to_f64();
    let mut worst = f64::INFINITY;
    for j in 0..=samples {
        let (_, d) = c.eval_segment(seg, &frac::<T>(j, samples)).map_err(err)?;
        worst = worst.min(d.norm().to_f64() * dt / chord);
    }
    Ok(worst)
}
