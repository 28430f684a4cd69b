//! The curves of seed 002 measured against independent references: cubic
//! Hermite ↔ Bézier, rational circular arcs and degree elevation, NURBS
//! circle and cylinder, Catmull–Rom interpolation and C¹ continuity, adaptive
//! vs uniform flattening, de Boor vs Cox–de Boor, B-spline vs Bézier patch.
//!
//! Every error is computed in MPFR at `2·BITS + 64` bits from the exact
//! values of the computed result (so the measurement adds no rounding of
//! its own) and reported **in units of the unit roundoff `u` of the
//! precision under test**, relative to the scale of the data, so that f64
//! and MPFR rows are comparable and can be checked against the documented
//! bounds.

use crate::flatten_reference::{deviation_in_mpfr, greedy_reference_segments};
use nalgebra::{SVector, Vector2, Vector3};
use rug::Float;
use serde::{Deserialize, Serialize};
use splinelab::bernstein::bezier::Bezier;
use splinelab::bspline::de_boor::BSpline;
use splinelab::bspline::knots::KnotVector;
use splinelab::bspline::nurbs::{NurbsCurve, NurbsSurface};
use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
use splinelab::curves::flatten::{flatten, max_deviation, uniform_polyline, uniform_segments};
use splinelab::curves::greedy_flatten::flatten_greedy;
use splinelab::curves::hermite::Hermite;
use splinelab::curves::rational_bezier::RationalBezier;
use splinelab::scalar::prelude::*;
use splinelab::surface_deformation::patch::Patch;

/// Why a curves measurement failed (a core error, reported as text).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("curves study: {0}")]
pub struct CurvesStudyError(pub String);

fn err(e: impl std::fmt::Display) -> CurvesStudyError {
    CurvesStudyError(e.to_string())
}

// ---- reference arithmetic -------------------------------------------------

/// Precision of the references for `T`: `2·BITS + 64`.
pub fn ref_prec<T: Real>() -> u32 {
    2 * T::BITS + 64
}

/// `x` as an MPFR float of the reference precision (exact).
pub fn fl<T: Real>(x: &T) -> Float {
    Float::with_val(ref_prec::<T>(), x.to_float())
}

/// `‖a − b‖₂` in the reference precision from the exact values of `a`, `b`.
pub fn dist_ref<T: Real, const D: usize>(a: &SVector<T, D>, b: &SVector<T, D>) -> Float {
    let p = ref_prec::<T>();
    let mut s = Float::with_val(p, 0);
    for (x, y) in a.iter().zip(b.iter()) {
        let d = Float::with_val(p, fl(x) - fl(y));
        s += d.square();
    }
    s.sqrt()
}

/// `‖a‖_∞` over a set of points (the data scale), as f64, at least 1e-300.
pub fn scale<T: Real, const D: usize>(points: &[SVector<T, D>]) -> f64 {
    points
        .iter()
        .flat_map(|p| p.iter())
        .map(|x| x.to_f64().abs())
        .fold(1e-300, f64::max)
}

/// An error in units of `u` of `T` relative to `scale`.
pub fn in_u<T: Real>(err: &Float, scale: f64) -> f64 {
    (err.clone() / scale / T::unit_roundoff().to_float()).to_f64()
}

/// `|‖p − c‖ − r| / r` in units of `u` (computed in the reference precision).
pub fn radial_error_u<T: Real, const D: usize>(p: &SVector<T, D>, c: &SVector<T, D>, r: &T) -> f64 {
    let d = dist_ref(p, c) - fl(r);
    in_u::<T>(&d.abs(), r.to_f64())
}

// ---- deterministic inputs -------------------------------------------------

use crate::rng::SplitMix64;

/// A random point with dyadic coordinates in `[−range, range]`.
fn random_point<T: Real, const D: usize>(rng: &mut SplitMix64, range: f64) -> SVector<T, D> {
    SVector::from_fn(|_, _| T::from_f64_exact(rng.dyadic(range)))
}

/// `j / m` in `T` (correctly rounded).
pub fn frac<T: Real>(j: usize, m: usize) -> T {
    T::from_int(j as i64) / T::from_int(m as i64)
}

// ---- measurements ---------------------------------------------------------

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

/// The arcs of the circle study: starts `kπ/7` (`k = 0..6`) and sweeps
/// `π/8, π/3, π/2, 2π/3, 5π/6, π` (up to 180°).
pub fn study_arcs<T: Real>() -> Vec<(T, T)> {
    let pi = T::pi();
    let sweeps = [(1, 8), (1, 3), (1, 2), (2, 3), (5, 6), (1, 1)];
    (0..7)
        .flat_map(|k| {
            let pi = pi.clone();
            sweeps
                .iter()
                .map(move |&(a, b)| (pi.clone() * frac::<T>(k, 7), pi.clone() * frac::<T>(a, b)))
        })
        .collect()
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

/// The flatness guarantee measured: the largest distance from `samples`
/// curve points per polyline segment to that segment, divided by `tol`
/// (must be ≤ 1), and the number of segments.
pub fn flatten_excess<T: Real, const D: usize>(
    curve: &Bezier<T, D>,
    tol: &T,
    samples: usize,
) -> Result<(f64, usize), CurvesStudyError> {
    let poly = flatten(curve, tol).map_err(err)?;
    let dev = max_deviation(curve, &poly, samples).map_err(err)?;
    Ok(((dev / tol.clone()).to_f64(), poly.segments()))
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

// ---- geometry helpers for the gallery ------------------------------------

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

/// The classic counter-example for uniform Catmull–Rom: the middle segment
/// from `(0, 0)` to `(1, 0)` with far outer points `(−11, −6)` and
/// `(12, −6)`. Uniform tangents `(P_2 − P_0)/2 = (6, 3)` and
/// `(P_3 − P_1)/2 = (6, −3)` give Bézier inner points `(2, 1)` and
/// `(−1, 1)`, which cross: the segment loops. Centripetal spacing shrinks
/// the tangents by the knot ratio and cannot loop (Yuksel–Schaefer–Keyser,
/// *Parameterization and applications of Catmull–Rom curves*, CAD 2011).
pub fn loop_example<T: Real>() -> Vec<Vector2<T>> {
    [(-11, -6), (0, 0), (1, 0), (12, -6)]
        .iter()
        .map(|&(x, y)| Vector2::new(T::from_int(x), T::from_int(y)))
        .collect()
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

// ---- the study ------------------------------------------------------------

/// The Bézier curves of the flattening comparison: a cubic S-curve and a
/// degree-10 zig-zag, both with dyadic control points.
pub fn flatten_test_curves() -> Vec<(String, Vec<[f64; 2]>)> {
    let cubic = vec![[0.0, 0.0], [1.0, 2.0], [3.0, -1.0], [4.0, 1.0]];
    let deg10 = (0..=10)
        .map(|i| {
            [
                i as f64,
                if i % 2 == 0 {
                    0.0
                } else {
                    1.0 + i as f64 / 8.0
                },
            ]
        })
        .collect();
    vec![("cubic".into(), cubic), ("degree-10".into(), deg10)]
}

/// Samples per polyline segment when measuring deviations.
pub const DEVIATION_SAMPLES: usize = 32;

/// Parameters of [`run_curves`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct CurvesParams {
    /// Fewer random cases.
    pub quick: bool,
}

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

/// A named polyline for the gallery.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sampled {
    /// Legend name.
    pub name: String,
    /// The points.
    pub points: Vec<[f64; 2]>,
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

fn properties<T: Real>(cases: usize) -> Result<Vec<PropertyRow>, CurvesStudyError> {
    let name = if T::BITS == 53 {
        "f64".to_string()
    } else {
        format!("mp{}", T::BITS)
    };
    let mut rng = SplitMix64::new(0x5EED_0002);
    let mut h = HermiteErrors::default();
    let (mut elev, mut cr, mut boor, mut bb, mut bd, mut patch) = (
        0.0f64,
        CatmullRomErrors::default(),
        0.0f64,
        0.0f64,
        0.0f64,
        0.0f64,
    );
    for case in 0..cases {
        let seg = Hermite::<T, 3>::new(
            random_point(&mut rng, 4.0),
            random_point(&mut rng, 4.0),
            random_point(&mut rng, 8.0),
            random_point(&mut rng, 8.0),
        )
        .map_err(err)?;
        let e = hermite_errors(&seg)?;
        h.end_values = h.end_values.max(e.end_values);
        h.end_derivatives = h.end_derivatives.max(e.end_derivatives);
        h.bezier_agreement = h.bezier_agreement.max(e.bezier_agreement);
        h.conversion_derivatives = h.conversion_derivatives.max(e.conversion_derivatives);
        let deg = 2 + case % 5;
        let pts: Vec<Vector2<T>> = (0..=deg).map(|_| random_point(&mut rng, 4.0)).collect();
        let w: Vec<T> = (0..=deg)
            .map(|_| T::from_f64_exact(0.25 + rng.dyadic(1.0).abs() * 3.75))
            .collect();
        elev = elev.max(elevation_error(
            &RationalBezier::new(pts.clone(), w).map_err(err)?,
        )?);
        let spacing = Spacing::ALL[case % 3];
        let cpts: Vec<Vector2<T>> = (0..6).map(|_| random_point(&mut rng, 4.0)).collect();
        if let Ok(c) = CatmullRom::new(cpts, spacing, case % 2 == 0) {
            let e = catmull_rom_errors(&c)?;
            cr.interpolation = cr.interpolation.max(e.interpolation);
            cr.c1_jump = cr.c1_jump.max(e.c1_jump);
            cr.tangent = cr.tangent.max(e.tangent);
        }
        let order = 2 + case % 4;
        let npts = order + 3;
        let mut knots: Vec<T> = (0..npts + order)
            .map(|_| T::from_f64_exact(rng.dyadic(4.0)))
            .collect();
        knots.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        let q: Vec<Vector2<T>> = (0..npts).map(|_| random_point(&mut rng, 4.0)).collect();
        if let Ok(c) = KnotVector::new(knots)
            .map_err(err)
            .and_then(|k| BSpline::new(order, q.clone(), k).map_err(err))
        {
            boor = boor.max(de_boor_vs_basis(&c, 16)?);
        }
        let (a, b) = bspline_vs_bezier(&pts)?;
        bb = bb.max(a);
        bd = bd.max(b);
        if case < 8 {
            let net: Vec<Vector3<T>> = (0..16).map(|_| random_point(&mut rng, 4.0)).collect();
            patch = patch.max(patch_vs_nurbs(&Patch::new(3, net).map_err(err)?)?);
        }
    }
    let arcs = study_arcs::<T>();
    let mut arc = 0.0f64;
    for (s, w) in &arcs {
        arc = arc.max(arc_error(s, w, 64)?);
    }
    let (nc, ncyl) = nurbs_circle_errors::<T>(64)?;
    let circle_bound = if T::BITS == 53 {
        bounds::CIRCLE_F64
    } else {
        bounds::CIRCLE_MP
    };
    use bounds::*;
    Ok(vec![
        row(
            "hermite",
            "end values x(0) = x₀, x(1) = x₁",
            &name,
            h.end_values,
            HERMITE,
            cases,
        ),
        row(
            "hermite",
            "end derivatives x'(0), x'(1)",
            &name,
            h.end_derivatives,
            HERMITE,
            cases,
        ),
        row(
            "hermite",
            "Hermite (Horner) = its Bézier form (de Casteljau)",
            &name,
            h.bezier_agreement,
            HERMITE,
            cases,
        ),
        row(
            "hermite",
            "Bézier → Hermite: 3(P₁−P₀) = x'₀, 3(P₃−P₂) = x'₁",
            &name,
            h.conversion_derivatives,
            HERMITE,
            cases,
        ),
        row(
            "rational",
            "arc |P(t)| = 1, sweeps ≤ 180°",
            &name,
            arc,
            circle_bound,
            arcs.len(),
        ),
        row(
            "rational",
            "degree elevation ×2 keeps the curve",
            &name,
            elev,
            ELEVATION,
            cases,
        ),
        row(
            "nurbs",
            "NURBS circle |P(t)| = 1",
            &name,
            nc,
            circle_bound,
            1,
        ),
        row(
            "nurbs",
            "NURBS cylinder: radius 1, z = 2v",
            &name,
            ncyl,
            circle_bound,
            1,
        ),
        row(
            "catmull-rom",
            "interpolation C(t_k) = P_k",
            &name,
            cr.interpolation,
            CATMULL_ROM,
            cases,
        ),
        row(
            "catmull-rom",
            "C¹: left = right derivative at knots",
            &name,
            cr.c1_jump,
            CATMULL_ROM,
            cases,
        ),
        row(
            "catmull-rom",
            "tangent = closed form q'_k(t_k)",
            &name,
            cr.tangent,
            CATMULL_ROM,
            cases,
        ),
        row(
            "bspline",
            "de Boor = Cox–de Boor basis sum",
            &name,
            boor,
            BSPLINE,
            cases,
        ),
        row(
            "bspline",
            "Bézier knots: de Boor = de Casteljau",
            &name,
            bb,
            BSPLINE,
            cases,
        ),
        row(
            "bspline",
            "Bézier knots: derivative = hodograph",
            &name,
            bd,
            BSPLINE,
            cases,
        ),
        row(
            "patch",
            "bicubic Bézier patch = NURBS surface",
            &name,
            patch,
            BSPLINE,
            cases.min(8),
        ),
    ])
}

fn to_xy<T: Real>(p: &Vector2<T>) -> [f64; 2] {
    [p.x.to_f64(), p.y.to_f64()]
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

/// The gallery curves: Catmull–Rom data and curves, loop curves with their
/// self-intersection flags, circles.
type Gallery = (
    Vec<[f64; 2]>,
    Vec<Sampled>,
    Vec<Sampled>,
    (bool, bool),
    Vec<Sampled>,
);

fn gallery() -> Result<Gallery, CurvesStudyError> {
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
