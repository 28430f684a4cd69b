//! References for judging flattening: the greedy longest-step optimum with a
//! sampled distance check (the count the near-optimal method is measured
//! against), and the deviation of a polyline judged independently in 256-bit
//! MPFR.

use nalgebra::SVector;
use splinelab::bernstein::bezier::Bezier;
use splinelab::bspline::de_boor::BSplineError;
use splinelab::bspline::knots::KnotVector;
use splinelab::bspline::nurbs::NurbsCurve;
use splinelab::curves::CurveError;
use splinelab::curves::flatten::{Polyline, segment_distance};
use splinelab::param_curve::ParamCurve;
use splinelab::scalar::prelude::*;

/// Bisection steps of [`greedy_reference_segments`] per chord (the step is
/// found to `2⁻⁴⁰` of its bracket).
const REFERENCE_BISECTIONS: usize = 40;

/// Largest sampled distance of `curve` on `[t0, t1]` (`samples` interior
/// points) to the chord `[P(t0), P(t1)]`.
fn sampled_chord_distance<const D: usize>(
    curve: &Bezier<f64, D>,
    t0: f64,
    t1: f64,
    samples: usize,
) -> Result<f64, CurveError> {
    let (a, b) = (curve.eval(&t0)?, curve.eval(&t1)?);
    let mut worst = 0.0f64;
    for i in 1..=samples {
        let t = t0 + (t1 - t0) * i as f64 / (samples + 1) as f64;
        worst = worst.max(segment_distance(&curve.eval(&t)?, &a, &b));
    }
    Ok(worst)
}

/// The greedy optimum: from `t = 0`, the longest chord whose sampled
/// distance (`samples` per chord) is `≤ tol`, found by bisection to `2⁻⁴⁰`
/// from a doubling bracket; returns the number of chords. Not a proof (a
/// sampled check can miss the peak by a relative `O(1/samples²)`), hence a
/// slightly optimistic reference: the fewest chords any method can use.
/// **Cost** `≈ 45 · samples` evaluations per chord.
pub fn greedy_reference_segments<const D: usize>(
    curve: &Bezier<f64, D>,
    tol: f64,
    samples: usize,
) -> Result<usize, CurveError> {
    let ok = |t0: f64, t1: f64| -> Result<bool, CurveError> {
        Ok(sampled_chord_distance(curve, t0, t1, samples)? <= tol)
    };
    let (mut t0, mut count) = (0.0f64, 0usize);
    while t0 < 1.0 {
        count += 1;
        if ok(t0, 1.0)? {
            break;
        }
        let (mut lo, mut hi) = (0.0, 1.0 - t0);
        for _ in 0..REFERENCE_BISECTIONS {
            let mid = 0.5 * (lo + hi);
            if ok(t0, t0 + mid)? {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        if lo == 0.0 {
            return Err(CurveError::DepthExceeded(REFERENCE_BISECTIONS));
        }
        t0 += lo;
    }
    Ok(count)
}

/// The largest distance from the curve to a polyline, judged in 256-bit
/// MPFR independently of core's sampled `max_deviation`: the curve's control
/// points and each chord's vertices are lifted exactly (`T` has at most 256
/// bits: f64 or `Mp<B ≤ 256>`), the curve is evaluated in MPFR at `samples`
/// interior points of every chord's parameter interval (and at the
/// vertices' parameters), and each point's distance to its own chord is
/// taken in MPFR. Returned as f64, rounded up.
pub fn deviation_in_mpfr<T: Real, const D: usize>(
    curve: &Bezier<T, D>,
    poly: &Polyline<T, D>,
    samples: usize,
) -> Result<f64, CurveError> {
    type M = Mp<256>;
    debug_assert!(T::BITS <= M::BITS, "the lift to 256 bits must be exact");
    let lift = |p: &SVector<T, D>| p.map(|x| x.convert::<M>());
    let exact = Bezier::new(curve.points().iter().map(lift).collect())?;
    let mut worst = M::zero();
    for j in 0..poly.segments() {
        let (t0, t1) = (
            poly.params[j].convert::<M>(),
            poly.params[j + 1].convert::<M>(),
        );
        let (a, b) = (lift(&poly.points[j]), lift(&poly.points[j + 1]));
        for i in 0..=samples + 1 {
            let s = M::from_int(i as i64) / M::from_int(samples as i64 + 1);
            let t = t0.clone() + (t1.clone() - t0.clone()) * s;
            worst = worst.max(segment_distance(&exact.eval(&t)?, &a, &b));
        }
    }
    Ok(worst.to_f64() * (1.0 + f64::EPSILON))
}

/// The largest distance from a curve of any type to an f64 polyline, judged
/// in 256-bit MPFR: `exact` is the curve rebuilt in `Mp<256>` from the same
/// f64 data (lifted exactly), evaluated by its own `eval` at the vertices'
/// parameters and `samples` interior points of every chord's parameter
/// interval; each point's distance to its own chord (vertices lifted
/// exactly) is taken in MPFR. Returned as f64, rounded up.
///
/// What it judges is the f64 data's curve, not the f64 code's rounding:
/// where the type computes derived data (Catmull–Rom's chord-length knots),
/// the MPFR curve uses the exact values, a difference of a few ulps of the
/// coordinates.
pub fn deviation_of_curve_in_mpfr<C, const D: usize>(
    exact: &C,
    poly: &Polyline<f64, D>,
    samples: usize,
) -> Result<f64, C::Error>
where
    C: ParamCurve<Mp<256>, D>,
{
    type M = Mp<256>;
    let lift = lift256::<D>;
    let (lo, hi) = exact.domain();
    let mut worst = M::zero();
    for j in 0..poly.segments() {
        let (t0, t1) = (
            M::from_f64_exact(poly.params[j]),
            M::from_f64_exact(poly.params[j + 1]),
        );
        let (a, b) = (lift(&poly.points[j]), lift(&poly.points[j + 1]));
        for i in 0..=samples + 1 {
            let s = M::from_int(i as i64) / M::from_int(samples as i64 + 1);
            // Clamped: the f64 vertex parameters may round past the exact ends.
            let t = (t0.clone() + (t1.clone() - t0.clone()) * s).clamp(lo.clone(), hi.clone());
            worst = worst.max(segment_distance(&exact.eval(&t)?, &a, &b));
        }
    }
    Ok(worst.to_f64() * (1.0 + f64::EPSILON))
}

/// An f64 point lifted to `Mp<256>` (exactly).
pub fn lift256<const D: usize>(p: &SVector<f64, D>) -> SVector<Mp<256>, D> {
    p.map(Mp::<256>::from_f64_exact)
}

/// The same NURBS curve in `Mp<256>`: its homogeneous points, weights and
/// knots lifted exactly, so that the twin is the f64 curve's exact value.
pub fn nurbs_twin<const D: usize>(
    curve: &NurbsCurve<f64, D>,
) -> Result<NurbsCurve<Mp<256>, D>, BSplineError> {
    let lift = |x: &f64| Mp::<256>::from_f64_exact(*x);
    let h = curve.homogeneous();
    NurbsCurve::from_homogeneous(
        h.order(),
        h.points().iter().map(lift256).collect(),
        curve.weights().iter().map(lift).collect(),
        KnotVector::new(h.knots().as_slice().iter().map(lift).collect())?,
    )
}

/// The NURBS curve of order `order` with affine points `points`, weights and
/// knots (f64; the homogeneous points `w_j Q_j` rounded once), and its
/// [`nurbs_twin`].
pub fn nurbs_with_twin<const D: usize>(
    order: usize,
    points: &[SVector<f64, D>],
    weights: &[f64],
    knots: &[f64],
) -> Result<(NurbsCurve<f64, D>, NurbsCurve<Mp<256>, D>), BSplineError> {
    let knots = KnotVector::new(knots.to_vec())?;
    let curve = NurbsCurve::new(order, points.to_vec(), weights.to_vec(), knots)?;
    let twin = nurbs_twin(&curve)?;
    Ok((curve, twin))
}
