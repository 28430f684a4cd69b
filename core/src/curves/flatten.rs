//! Drawing a curve as a polyline (seed 002, "ベジエ曲線の描画方法"):
//! method 1, uniform parameter sampling; method 2, adaptive sampling that
//! subdivides by de Casteljau while the control polygon is not flat.
//!
//! Any curve flattens: uniform sampling and the measured deviation need only
//! [`ParamCurve`]; the adaptive methods with a proven bound need the curve's
//! Bézier pieces ([`ParamCurveBezier`]: Bézier, Hermite, rational Bézier,
//! B-spline, NURBS, S-spline and Catmull–Rom curves), each piece flattened in
//! its own local parameter and the vertices reported in the curve's.
//!
//! **The guarantee of method 2.** A Bézier curve lies in the convex hull of
//! its control points. If every control point is within `ε` of the chord
//! segment `[P_0, P_n]`, the hull is within `ε` of it too (the
//! `ε`-neighbourhood of a segment is convex), hence so is the curve. The
//! adaptive polyline is the chain of chords of sub-curves that passed this
//! test, so **every point of the curve is within `ε` of the polyline** —
//! a bound, not an estimate (up to the rounding floor of
//! [`rounding_floor`]). A rational piece with positive weights lies in the
//! hull of its affine control points too, and subdivides exactly in
//! homogeneous coordinates.

use super::CurveError;
use super::bezier_pieces::{BezierPiece, ParamCurveBezier, scale_and_degree};
use crate::bernstein::bezier::Bezier;
use crate::param_curve::ParamCurve;
use crate::scalar::Real;
use nalgebra::SVector;

/// Deepest subdivision before [`flatten`] gives up (`2⁻⁶⁰` of the parameter range).
pub const MAX_DEPTH: usize = 60;

/// Largest segment count [`uniform_segments`] tries (`2²⁴`).
pub const MAX_UNIFORM_SEGMENTS: usize = 1 << 24;

/// A polyline approximating a curve: vertices `points[j] ≈ P(params[j])`,
/// `params` increasing over the curve's domain (from 0 to 1 for a Bézier curve).
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline<T: Real, const D: usize> {
    /// Curve parameters of the vertices.
    pub params: Vec<T>,
    /// The vertices.
    pub points: Vec<SVector<T, D>>,
}

impl<T: Real, const D: usize> Polyline<T, D> {
    /// Number of segments (vertices − 1).
    pub fn segments(&self) -> usize {
        self.points.len().saturating_sub(1)
    }
}

/// Euclidean distance from `p` to the segment `[a, b]` (to `a` if `a = b`).
///
/// **Method**: clamp the projection parameter `s = (p − a)·(b − a)/|b − a|²`
/// to `[0, 1]`. **Cost** `O(D)`. **Accuracy**: a few ulps of `max(|p − a|, |b − a|)`.
///
/// **Source**: the orthogonal projection onto a segment (Eberly, *Geometric Tools*, §6.1);
/// used by seed 002's drawing by sampling.
pub fn segment_distance<T: Real, const D: usize>(
    p: &SVector<T, D>,
    a: &SVector<T, D>,
    b: &SVector<T, D>,
) -> T {
    let ab = b - a;
    let ap = p - a;
    let len2 = ab.norm_squared();
    if len2.is_zero() {
        return ap.norm();
    }
    let s = (ap.dot(&ab) / len2).clamp(T::zero(), T::one());
    (ap - ab * s).norm()
}

/// Flatness of a control polygon: `max_i dist(P_i, [P_0, P_n])`, which by
/// the convex hull property bounds the distance of the whole curve from its
/// chord (module doc). 0 for degree ≤ 1. **Cost** `O(nD)`.
pub fn flatness<T: Real, const D: usize>(points: &[SVector<T, D>]) -> T {
    let (a, b) = (&points[0], &points[points.len() - 1]);
    points
        .iter()
        .map(|p| segment_distance(p, a, b))
        .fold(T::zero(), |m, d| m.max(d))
}

/// The smallest tolerance [`flatten`] accepts for `curve`:
/// `2⁸ · n · u · max_i ‖P_i‖_∞` (`u` the unit roundoff, at least one `u`),
/// `n` the largest degree and `P_i` the control points of every Bézier piece
/// (times `max w / min w` for a rational piece).
/// Each level of de Casteljau subdivision perturbs the sub-polygon by at most
/// `γ_{3n} max|P_i|` per coordinate; over ≲ 40 levels and the flatness
/// computation that stays below this floor, so a tolerance above it is
/// honoured up to a relative `O(2⁻⁴)` slack in the worst case and typically
/// to a few ulps. **Errors**: the curve's pieces cannot be formed.
///
/// ```
/// use nalgebra::Vector2;
/// use splinelab::bernstein::bezier::Bezier;
/// use splinelab::curves::flatten::rounding_floor;
/// let c = Bezier::new(vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 2.0),
///                          Vector2::new(2.0, 0.0)]).unwrap();
/// // 2⁸ · 2 · 2⁻⁵³ · 2
/// assert_eq!(rounding_floor(&c).unwrap(), 2f64.powi(-43));
/// ```
pub fn rounding_floor<T: Real, const D: usize, C: ParamCurveBezier<T, D> + ?Sized>(
    curve: &C,
) -> Result<T, CurveError> {
    Ok(pieces_floor(&curve.bezier_pieces()?))
}

/// [`rounding_floor`] of the pieces.
pub(crate) fn pieces_floor<T: Real, const D: usize>(pieces: &[BezierPiece<T, D>]) -> T {
    let (scale, degree) = scale_and_degree(pieces);
    let n = T::from_int(degree as i64);
    (scale * n).max(T::one()) * T::unit_roundoff().scale_by_pow2(8)
}

/// Rejects a tolerance that is not finite, not positive, or below the
/// [`rounding_floor`] of `pieces`.
pub(crate) fn check_tol<T: Real, const D: usize>(
    pieces: &[BezierPiece<T, D>],
    tol: &T,
) -> Result<(), CurveError> {
    if !tol.is_finite() || *tol <= T::zero() {
        return Err(CurveError::OutOfRange {
            name: "tolerance",
            value: tol.to_f64(),
            range: "(0, ∞)",
        });
    }
    let floor = pieces_floor(pieces);
    if *tol < floor {
        return Err(CurveError::ToleranceBelowRounding {
            tol: tol.to_f64(),
            floor: floor.to_f64(),
        });
    }
    Ok(())
}

/// The curve's pieces, checked non-empty, and `tol` checked against them.
pub(crate) fn checked_pieces<T: Real, const D: usize, C: ParamCurveBezier<T, D> + ?Sized>(
    curve: &C,
    tol: &T,
) -> Result<Vec<BezierPiece<T, D>>, CurveError> {
    let pieces = curve.bezier_pieces()?;
    if pieces.is_empty() {
        return Err(CurveError::OutOfRange {
            name: "Bézier pieces",
            value: 0.0,
            range: "at least one",
        });
    }
    check_tol(&pieces, tol)?;
    Ok(pieces)
}

/// Adaptive flattening (seed 002 method 2): split at `s = ½` by de Casteljau
/// ([`subdivide`](crate::bernstein::bezier::subdivide)) until each piece's
/// control polygon has [`flatness`] `≤ tol`; the polyline joins the pieces'
/// end points. A curve of several Bézier pieces ([`ParamCurveBezier`]) is
/// flattened piece by piece, the vertices' parameters mapped to the curve's.
///
/// **Guarantee**: every point of the curve is within `tol` of the polyline
/// (convex hull property, module doc), for `tol ≥` [`rounding_floor`].
/// **Cost**: `O(n²D)` per piece; the piece count grows like
/// `√(‖Δ²P‖/tol)` as flatness shrinks by ≈ 4 per halving.
/// **Errors**: `tol` not finite or `≤ 0`; below the rounding floor;
/// more than [`MAX_DEPTH`] levels.
///
/// **Accuracy**: judged in 256-bit MPFR for Bézier, NURBS, Catmull–Rom and
/// S-spline curves by `verify/tests/it/curves_flatten_any.rs`. **Source**: seed 002
/// method 2; the convex hull property (Farin, *Curves and Surfaces for CAGD*, §3).
///
/// ```
/// use nalgebra::Vector2;
/// use splinelab::bernstein::bezier::Bezier;
/// use splinelab::curves::flatten::flatten;
/// let c = Bezier::new(vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 2.0),
///                          Vector2::new(2.0, 0.0)]).unwrap();
/// let poly = flatten(&c, &0.1).unwrap();
/// assert_eq!(poly.points[0], Vector2::new(0.0, 0.0));
/// assert_eq!(*poly.points.last().unwrap(), Vector2::new(2.0, 0.0));
/// ```
///
/// ```
/// // The exact NURBS circle in MPFR: every vertex on the circle, and the
/// // curve within tol of the polyline (the sagitta of the longest chord).
/// use nalgebra::Vector2;
/// use splinelab::bspline::nurbs::NurbsCurve;
/// use splinelab::curves::flatten::{flatten, max_deviation};
/// use splinelab::scalar::prelude::*;
/// type M = Mp<128>;
/// let c = NurbsCurve::circle(&Vector2::new(M::zero(), M::zero()), &M::one()).unwrap();
/// let tol = M::from_f64_exact(1e-6);
/// let poly = flatten(&c, &tol).unwrap();
/// for p in &poly.points {
///     assert!((p.norm() - M::one()).abs().to_f64() < 1e-35);
/// }
/// assert!(max_deviation(&c, &poly, 16).unwrap() <= tol);
/// ```
pub fn flatten<T: Real, const D: usize, C: ParamCurveBezier<T, D> + ?Sized>(
    curve: &C,
    tol: &T,
) -> Result<Polyline<T, D>, CurveError> {
    piece_by_piece(curve, tol, subdivide_piece)
}

/// What flattening one piece does: append the vertices after the piece's
/// start (which the polyline already ends with).
pub(crate) type PieceFlattener<T, const D: usize> =
    fn(&BezierPiece<T, D>, &T, &mut Polyline<T, D>) -> Result<(), CurveError>;

/// The polyline of `curve` at `tol`, started at the curve's first point and
/// extended by `each` over every Bézier piece in turn (tolerance checked
/// against the pieces' [`rounding_floor`] first).
pub(crate) fn piece_by_piece<T: Real, const D: usize, C: ParamCurveBezier<T, D> + ?Sized>(
    curve: &C,
    tol: &T,
    each: PieceFlattener<T, D>,
) -> Result<Polyline<T, D>, CurveError> {
    let pieces = checked_pieces(curve, tol)?;
    let mut poly = Polyline {
        params: vec![pieces[0].span.0.clone()],
        points: vec![pieces[0].net().polygon()[0].clone()],
    };
    for piece in &pieces {
        each(piece, tol, &mut poly)?;
    }
    Ok(poly)
}

/// Appends to `poly` the end points of the flat sub-pieces of `piece`
/// (all but its start, which `poly` already ends with).
fn subdivide_piece<T: Real, const D: usize>(
    piece: &BezierPiece<T, D>,
    tol: &T,
    poly: &mut Polyline<T, D>,
) -> Result<(), CurveError> {
    let half = T::one() / T::from_int(2);
    // Pieces still to examine, the leftmost on top: (s0, s1, depth, control net).
    let mut stack = vec![(T::zero(), T::one(), 0usize, piece.net())];
    while let Some((s0, s1, depth, net)) = stack.pop() {
        let polygon = net.polygon();
        if flatness(&polygon) <= *tol {
            poly.params.push(piece.param(&s1));
            poly.points.push(polygon[polygon.len() - 1].clone());
            continue;
        }
        if depth >= MAX_DEPTH {
            return Err(CurveError::DepthExceeded(MAX_DEPTH));
        }
        let (left, right) = net.split(&half)?;
        let sm = (s0.clone() + &s1) * half.clone();
        stack.push((sm.clone(), s1, depth + 1, right));
        stack.push((s0, sm, depth + 1, left));
    }
    Ok(())
}

/// Uniform sampling (seed 002 method 1): the polyline through `P(t_j)`,
/// `t_j = a + (b − a) j/m`, `j = 0..m`, over the curve's domain `[a, b]`
/// (`t_m = b` exactly), each vertex by the curve's own evaluation. `m ≥ 1`.
///
/// **Accuracy**: each vertex that of `eval` (for a Bézier curve within de
/// Casteljau's `γ_{2n} max|P|` of the curve point, Farouki–Rajan 1987); the
/// chord error is [`uniform_segments_bound`]'s, tested in
/// `verify/tests/it/curves_flatten.rs::uniform_count_is_the_smallest_passing_count`.
/// **Source**: seed 002 method 1.
///
/// ```
/// use nalgebra::Vector2;
/// use splinelab::bernstein::bezier::Bezier;
/// use splinelab::curves::flatten::uniform_polyline;
/// let c = Bezier::new(vec![Vector2::new(0.0f64, 0.0), Vector2::new(2.0, 4.0)]).unwrap();
/// let poly = uniform_polyline(&c, 4).unwrap();
/// assert_eq!((poly.params[1], poly.points[1]), (0.25, Vector2::new(0.5, 1.0)));
/// ```
pub fn uniform_polyline<T: Real, const D: usize, C: ParamCurve<T, D> + ?Sized>(
    curve: &C,
    m: usize,
) -> Result<Polyline<T, D>, C::Error> {
    let m = m.max(1);
    let (a, b) = curve.domain();
    let params: Vec<T> = (0..=m)
        .map(|j| {
            if j == m {
                b.clone()
            } else {
                let s = T::from_int(j as i64) / T::from_int(m as i64);
                a.clone() + (b.clone() - &a) * s
            }
        })
        .collect();
    let points = params
        .iter()
        .map(|t| curve.eval(t))
        .collect::<Result<_, _>>()?;
    Ok(Polyline { params, points })
}

/// Measured deviation of a polyline from the curve: for every polyline
/// segment `j`, the curve is sampled at `samples` equally spaced parameters
/// strictly inside `[params[j], params[j+1]]` and the largest distance to
/// that segment is returned (the distance to the segment's own chord is an
/// upper bound of the distance to the whole polyline).
///
/// **Accuracy**: a sampled maximum — it can miss the true maximum by a
/// relative `O(1/samples²)` (the deviation is smooth with a quadratic peak).
/// **Cost**: `segments · samples` evaluations.
///
/// **Source**: seed 002 (uniform vs adaptive drawing); judged in 256-bit MPFR by
/// `reports/tests/it/cli_flatten.rs::at_1e_12_the_deviation_stays_within_the_tolerance_judged_in_mpfr`.
///
/// ```
/// use nalgebra::Vector2;
/// use splinelab::bernstein::bezier::Bezier;
/// use splinelab::curves::flatten::{max_deviation, uniform_polyline};
/// // P(t) = (2t, 4t(1−t)) against its one chord: the apex, 1 above it.
/// let c = Bezier::new(vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 2.0),
///                          Vector2::new(2.0, 0.0)]).unwrap();
/// assert_eq!(max_deviation(&c, &uniform_polyline(&c, 1).unwrap(), 3).unwrap(), 1.0);
/// ```
pub fn max_deviation<T: Real, const D: usize, C: ParamCurve<T, D> + ?Sized>(
    curve: &C,
    poly: &Polyline<T, D>,
    samples: usize,
) -> Result<T, C::Error> {
    let k = T::from_int(samples as i64 + 1);
    let mut worst = T::zero();
    for j in 0..poly.segments() {
        let (t0, t1) = (&poly.params[j], &poly.params[j + 1]);
        let (a, b) = (&poly.points[j], &poly.points[j + 1]);
        for i in 1..=samples {
            let t = t0.clone() + (t1.clone() - t0) * T::from_int(i as i64) / k.clone();
            worst = worst.max(segment_distance(&curve.eval(&t)?, a, b));
        }
    }
    Ok(worst)
}

/// An a-priori upper bound of the segment count uniform sampling needs for
/// `tol`: `m* = √(n(n−1) max_i ‖Δ²P_i‖₂ / (8 tol))`, at least 1, not rounded
/// (it can exceed every `usize` for tiny tolerances).
///
/// **Derivation**: on a parameter interval of width `h = 1/m` the chord of
/// `P` deviates from the curve by at most `h²/8 · max‖P''‖` (the error of
/// linear interpolation, in any norm), and `P''` is the Bézier curve of
/// degree `n − 2` with control points `n(n−1)Δ²P_i`, so by the convex hull
/// property `‖P''‖ ≤ n(n−1) max_i ‖Δ²P_i‖`. Every `m ≥ m*` therefore meets
/// `tol` in exact arithmetic, and [`uniform_segments`] returns at most
/// `⌈m*⌉` up to rounding. **Cost** `O(nD)`. **Errors**: bad `tol` (as
/// [`flatten`]).
///
///
/// **Source**: the linear-interpolation error `h²/8 max|f''|` (de Boor, *A Practical Guide
/// to Splines*, ch. II) with the Bézier derivative's convex hull (seed 002).
///
/// ```
/// use nalgebra::Vector2;
/// use splinelab::bernstein::bezier::Bezier;
/// use splinelab::curves::flatten::uniform_segments_bound;
/// // P(t) = (2t, 4t(1−t)): Δ²P = (0, −4), so m* = √(2·4/(8·10⁻³)) = √1000.
/// let c = Bezier::new(vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 2.0),
///                          Vector2::new(2.0, 0.0)]).unwrap();
/// assert!((uniform_segments_bound(&c, &1e-3).unwrap() - 1000f64.sqrt()).abs() < 1e-12);
/// ```
pub fn uniform_segments_bound<T: Real, const D: usize>(
    curve: &Bezier<T, D>,
    tol: &T,
) -> Result<T, CurveError> {
    checked_pieces(curve, tol)?;
    let p = curve.points();
    let second = p
        .windows(3)
        .map(|w| (&w[2] - &w[1] * T::from_int(2) + &w[0]).norm())
        .fold(T::zero(), |m, d| m.max(d));
    let n = T::from_int(curve.degree() as i64);
    let m = (n.clone() * (n - T::one()) * second / (T::from_int(8) * tol.clone())).sqrt();
    Ok(m.max(T::one()))
}

/// The number of equal parameter steps uniform sampling needs for the same
/// tolerance: the smallest `m` whose [`uniform_polyline`] has
/// [`max_deviation`] `≤ tol` (with `samples` per segment), found by doubling
/// `m = 1, 2, 4, …` and then bisecting between the last failing and the
/// first passing count. The deviation of uniform sampling decreases
/// (essentially monotonically, like `m⁻²`) with `m`; bisection assumes it.
///
/// **Cost**: `O(log m)` trials of `m · samples` evaluations.
/// **Errors**: bad `tol` (as [`flatten`]); more than [`MAX_UNIFORM_SEGMENTS`];
/// an evaluation's error.
///
/// **Accuracy**: the count is the smallest passing one up to the sampled deviation's
/// `O(1/samples²)`, tested in
/// `verify/tests/it/curves_flatten.rs::uniform_count_is_the_smallest_passing_count`.
/// **Source**: seed 002's uniform drawing, the count it needs.
pub fn uniform_segments<T: Real, const D: usize, C: ParamCurveBezier<T, D> + ?Sized>(
    curve: &C,
    tol: &T,
    samples: usize,
) -> Result<usize, CurveError>
where
    CurveError: From<C::Error>,
{
    checked_pieces(curve, tol)?;
    let passes = |m: usize| -> Result<bool, CurveError> {
        Ok(max_deviation(curve, &uniform_polyline(curve, m)?, samples)? <= *tol)
    };
    let mut hi = 1;
    while !passes(hi)? {
        if hi >= MAX_UNIFORM_SEGMENTS {
            return Err(CurveError::DepthExceeded(MAX_UNIFORM_SEGMENTS));
        }
        hi *= 2;
    }
    // Invariant: hi passes; lo fails (or is 0).
    let mut lo = hi / 2;
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if passes(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    #[test]
    fn segment_distance_closed_forms() {
        let (a, b) = (Vector2::new(0.0f64, 0.0), Vector2::new(4.0, 0.0));
        assert_eq!(segment_distance(&Vector2::new(1.0, 3.0), &a, &b), 3.0);
        assert_eq!(segment_distance(&Vector2::new(7.0, 4.0), &a, &b), 5.0);
        assert_eq!(segment_distance(&Vector2::new(3.0, 4.0), &a, &a), 5.0);
    }

    #[test]
    fn bad_tolerances_are_typed_errors() {
        let c = Bezier::new(vec![Vector2::new(0.0f64, 0.0), Vector2::new(1.0, 1.0)]).unwrap();
        for tol in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                flatten(&c, &tol),
                Err(CurveError::OutOfRange { .. })
            ));
        }
        assert!(matches!(
            flatten(&c, &1e-17),
            Err(CurveError::ToleranceBelowRounding { .. })
        ));
        // A straight line is flat at once: one segment.
        assert_eq!(flatten(&c, &1e-9).unwrap().segments(), 1);
    }

    #[test]
    fn parabola_counts_match_the_closed_form() {
        // P(t) = (2t, 4t(1−t)). On a piece of width h the middle control point
        // is 2h² above the chord midpoint (vertically) and the chord deviates
        // by h² (vertically); near t = ½ the chord is horizontal.
        let c = Bezier::new(vec![
            Vector2::new(0.0f64, 0.0),
            Vector2::new(1.0, 2.0),
            Vector2::new(2.0, 0.0),
        ])
        .unwrap();
        // Adaptive: every piece is flat at depth 6 (2·4⁻⁶ ≤ 1e-3 whatever its
        // tilt); the horizontal ones at t = ½ are not at depth 5 (2·4⁻⁵ > 1e-3).
        let poly = flatten(&c, &1e-3).unwrap();
        assert!(poly.segments() <= 64);
        let j = poly.params.iter().position(|t| *t == 0.5).unwrap();
        assert_eq!(
            (
                poly.params[j + 1] - poly.params[j],
                poly.params[j] - poly.params[j - 1]
            ),
            (1.0 / 64.0, 1.0 / 64.0)
        );
        // Uniform: for odd m the middle chord is horizontal with deviation 1/m²;
        // m = 31 fails (1/961 > 1e-3), m = 32 passes (deviation ≤ 1/1024).
        assert_eq!(uniform_segments(&c, &1e-3, 64).unwrap(), 32);
        // The a-priori bound √1000 ≈ 31.6 is within one segment of it.
        let bound = uniform_segments_bound(&c, &1e-3).unwrap();
        assert!(bound > 31.0 && bound < 32.0, "{bound}");
    }

    #[test]
    fn the_uniform_bound_is_never_beaten() {
        // A wiggly cubic and a degree-6 zigzag: the smallest passing m found
        // by search must not exceed the a-priori bound.
        let cubic = [(0.0, 0.0), (1.0, 3.0), (2.0, -3.0), (3.0, 0.0)];
        let zigzag: Vec<_> = (0..7).map(|k| (k as f64, (-1f64).powi(k))).collect();
        for pts in [cubic.to_vec(), zigzag] {
            let c = Bezier::new(pts.iter().map(|&(x, y)| Vector2::new(x, y)).collect()).unwrap();
            for tol in [1e-1, 1e-3, 1e-5] {
                let m = uniform_segments(&c, &tol, 64).unwrap() as f64;
                let bound = uniform_segments_bound(&c, &tol).unwrap();
                assert!(m <= bound.ceil(), "m = {m}, bound {bound}");
            }
        }
    }
}
