//! A curve as a chain of Bézier pieces: the capability [`ParamCurveBezier`]
//! that flattening ([`super::flatten`], [`super::greedy_flatten`]) needs
//! beyond [`ParamCurve`], after kurbo's small capability traits
//! (`ParamCurveDeriv`, `ParamCurveArclen`).
//!
//! Flattening with a *proven* distance bound needs the convex hull property:
//! a piece's control polygon encloses the piece. Every curve that is a chain
//! of polynomial or positive-weight rational pieces has it, once each piece
//! is written in Bézier form:
//!
//! | type | pieces | how |
//! |---|---|---|
//! | [`Bezier`] | one polynomial on `[0, 1]` | itself |
//! | [`Hermite`] | one cubic on `[0, 1]` | [`Hermite::to_bezier`] |
//! | [`RationalBezier`] | one rational on `[0, 1]` | itself (all weights `> 0`) |
//! | [`BSpline`] | one polynomial per knot span | Boehm insertion to multiplicity `k − 1` |
//! | [`NurbsCurve`] | one rational per knot span | the same on `(w_j Q_j, w_j)` |
//! | [`SsplineCurve`] | one polynomial per unit span | its B-spline view, clipped to its domain |
//! | [`CatmullRom`] | one cubic per segment | Hermite form from the end points and derivatives |
//!
//! **Source**: the Bézier form of a spline span by knot insertion (Boehm
//! 1980; Piegl & Tiller, *The NURBS Book*, §5.6, "decomposition"); the
//! Hermite–Bézier relation `P_1 = P_0 + h P'(t_0)/3` (seed 002).

use super::CurveError;
use super::catmull_rom::CatmullRom;
use super::hermite::Hermite;
use super::rational_bezier::RationalBezier;
use super::sspline_curve::SsplineCurve;
use crate::bernstein::bezier::{Bezier, subdivide};
use crate::bspline::de_boor::BSpline;
use crate::bspline::knot_insertion::InsertionError;
use crate::bspline::nurbs::NurbsCurve;
use crate::param_curve::ParamCurve;
use crate::scalar::Real;
use nalgebra::{SVector, Vector1};
use std::borrow::Cow;

/// The Bézier form of one piece: polynomial, or rational with positive weights.
#[derive(Clone, Debug, PartialEq)]
pub enum PieceForm<T: Real, const D: usize> {
    /// A polynomial Bézier curve.
    Polynomial(Bezier<T, D>),
    /// A rational Bézier curve whose weights are all `> 0` (so that it lies in
    /// the convex hull of its affine control points).
    Rational(RationalBezier<T, D>),
}

/// One piece of a curve: the curve on `span = [t_0, t_1]` is the Bézier
/// `form` at the local parameter `s = (t − t_0)/(t_1 − t_0) ∈ [0, 1]`.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierPiece<T: Real, const D: usize> {
    /// The curve's parameter interval `[t_0, t_1]` of this piece.
    pub span: (T, T),
    /// The piece in Bézier form over `s ∈ [0, 1]`.
    pub form: PieceForm<T, D>,
}

/// A curve that can write itself as a chain of Bézier pieces (module doc).
pub trait ParamCurveBezier<T: Real, const D: usize>: ParamCurve<T, D> {
    /// The pieces in parameter order, covering the curve's domain without
    /// gaps: `pieces[0].span.0` is the domain start, each piece's end its
    /// successor's start, the last end the domain end.
    fn bezier_pieces(&self) -> Result<Vec<BezierPiece<T, D>>, CurveError>;
}

impl<T: Real, const D: usize> BezierPiece<T, D> {
    /// The curve parameter of the local `s`: `t_0 + (t_1 − t_0) s`, the end
    /// `t_1` exactly at `s = 1` (on `[0, 1]` this is `s` itself, bit for bit).
    pub fn param(&self, s: &T) -> T {
        if *s == T::one() {
            return self.span.1.clone();
        }
        let (a, b) = &self.span;
        a.clone() + (b.clone() - a) * s.clone()
    }

    /// The piece's point at the local `s` (de Casteljau, projective for a
    /// rational piece).
    pub fn eval_local(&self, s: &T) -> Result<SVector<T, D>, CurveError> {
        match &self.form {
            PieceForm::Polynomial(b) => Ok(b.eval(s)?),
            PieceForm::Rational(r) => r.eval(s),
        }
    }

    /// The degree of the piece.
    pub fn degree(&self) -> usize {
        match &self.form {
            PieceForm::Polynomial(b) => b.degree(),
            PieceForm::Rational(r) => r.degree(),
        }
    }

    /// The control net as subdivision works on it.
    pub(crate) fn net(&self) -> Net<T, D> {
        match &self.form {
            PieceForm::Polynomial(b) => Net {
                num: b.points().to_vec(),
                weights: None,
            },
            PieceForm::Rational(r) => Net {
                num: r.homogeneous().to_vec(),
                weights: Some(r.weights().to_vec()),
            },
        }
    }
}

/// A control net being subdivided: the points (for a rational piece the
/// homogeneous `w_i P_i`) and, for a rational piece, the weights.
#[derive(Clone, Debug)]
pub(crate) struct Net<T: Real, const D: usize> {
    /// Control points, or homogeneous numerators `w_i P_i`.
    pub num: Vec<SVector<T, D>>,
    /// The weights of a rational net.
    pub weights: Option<Vec<T>>,
}

impl<T: Real, const D: usize> Net<T, D> {
    /// The two halves of the net at `s`, by de Casteljau subdivision of the
    /// points and the weights alike (the same affine steps: projective de
    /// Casteljau for a rational net). **Accuracy**: that of
    /// [`subdivide`] (`γ_{3n} max|P_i|` per coordinate, exact over the
    /// rationals). **Source**: Farin, *Curves and Surfaces for CAGD*, §13
    /// (rational subdivision); seed 002.
    pub fn split(&self, s: &T) -> Result<(Self, Self), CurveError> {
        let (l, r) = subdivide(&self.num, s)?;
        let (wl, wr) = match &self.weights {
            None => (None, None),
            Some(w) => {
                let (wl, wr) = subdivide(w, s)?;
                (Some(wl), Some(wr))
            }
        };
        Ok((
            Net {
                num: l,
                weights: wl,
            },
            Net {
                num: r,
                weights: wr,
            },
        ))
    }

    /// The affine control points, whose convex hull holds the piece
    /// (the points themselves for a polynomial net, `w_i P_i / w_i` otherwise,
    /// computed by one division per coordinate: within `u` relative of the
    /// stored homogeneous point's projection). **Source**: the convex hull
    /// property of rational Bézier curves with positive weights (Piegl &
    /// Tiller, *The NURBS Book*, §1.5).
    pub fn polygon(&self) -> Cow<'_, [SVector<T, D>]> {
        match &self.weights {
            None => Cow::Borrowed(&self.num),
            Some(w) => Cow::Owned(self.num.iter().zip(w).map(|(h, w)| h / w.clone()).collect()),
        }
    }

    /// Whether the net is rational.
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }
}

/// `max_i ‖P_i‖_∞` over every piece's affine control points, times
/// `max w / min w` for a rational piece (the homogeneous subdivision rounds
/// relative to `|w_i P_i|` and the projection divides by the smallest
/// weight); and the largest degree (at least 1).
pub(crate) fn scale_and_degree<T: Real, const D: usize>(
    pieces: &[BezierPiece<T, D>],
) -> (T, usize) {
    let mut scale = T::zero();
    let mut degree = 1;
    for piece in pieces {
        let net = piece.net();
        let size = net
            .polygon()
            .iter()
            .flat_map(|p| p.iter())
            .fold(T::zero(), |m, x| m.max(x.clone().abs()));
        let ratio = match &net.weights {
            None => T::one(),
            Some(w) => {
                let hi = w.iter().fold(T::zero(), |m, x| m.max(x.clone()));
                let lo = w.iter().fold(hi.clone(), |m, x| m.min(x.clone()));
                hi / lo
            }
        };
        scale = scale.max(size * ratio);
        degree = degree.max(piece.degree());
    }
    (scale, degree)
}

fn whole<T: Real, const D: usize>(form: PieceForm<T, D>) -> Vec<BezierPiece<T, D>> {
    vec![BezierPiece {
        span: (T::zero(), T::one()),
        form,
    }]
}

impl<T: Real, const D: usize> ParamCurveBezier<T, D> for Bezier<T, D> {
    /// One polynomial piece on `[0, 1]`: the curve itself.
    fn bezier_pieces(&self) -> Result<Vec<BezierPiece<T, D>>, CurveError> {
        Ok(whole(PieceForm::Polynomial(self.clone())))
    }
}

impl<T: Real, const D: usize> ParamCurveBezier<T, D> for Hermite<T, D> {
    /// One cubic piece on `[0, 1]` ([`Hermite::to_bezier`]).
    fn bezier_pieces(&self) -> Result<Vec<BezierPiece<T, D>>, CurveError> {
        Ok(whole(PieceForm::Polynomial(self.to_bezier()?)))
    }
}

impl<T: Real, const D: usize> ParamCurveBezier<T, D> for RationalBezier<T, D> {
    /// One rational piece on `[0, 1]`. A zero interior weight (a control
    /// point at infinity) has no convex hull: [`CurveError::BadWeight`].
    fn bezier_pieces(&self) -> Result<Vec<BezierPiece<T, D>>, CurveError> {
        if let Some(index) = self.weights().iter().position(|w| *w <= T::zero()) {
            return Err(CurveError::BadWeight {
                index,
                value: self.weights()[index].to_f64(),
            });
        }
        Ok(whole(PieceForm::Rational(self.clone())))
    }
}

/// Inserts every distinct knot value of `knots` within `[lo, hi]`, and `lo`,
/// `hi` themselves, until each has multiplicity at least `k − 1`; applies
/// the same insertions to `weights` (a NURBS's weights, sharing the knots).
fn decompose<T: Real, const D: usize>(
    curve: &mut BSpline<T, D>,
    weights: &mut Option<BSpline<T, 1>>,
    lo: &T,
    hi: &T,
) -> Result<(), CurveError> {
    let p = curve.order() - 1;
    let mut values: Vec<T> = curve
        .knots()
        .as_slice()
        .iter()
        .filter(|u| *u >= lo && *u <= hi)
        .cloned()
        .collect();
    values.push(lo.clone());
    values.push(hi.clone());
    values.dedup();
    for u in &values {
        while curve.knots().multiplicity(u) < p {
            curve.insert_knot_in_place(u).map_err(insertion)?;
            if let Some(w) = weights.as_mut() {
                w.insert_knot_in_place(u).map_err(insertion)?;
            }
        }
    }
    Ok(())
}

/// Knot insertion inside the domain below full multiplicity cannot fail
/// but through the curve's own validation.
fn insertion(e: InsertionError) -> CurveError {
    match e {
        InsertionError::BSpline(b) => CurveError::BSpline(b),
        InsertionError::OutOfDomain { u, .. } | InsertionError::FullMultiplicity { u, .. } => {
            CurveError::OutOfRange {
                name: "knot",
                value: u,
                range: "the domain, below full multiplicity",
            }
        }
    }
}

/// The Bézier pieces of a B-spline (with `weights`: of the NURBS whose
/// homogeneous B-spline it is) on `[lo, hi]` within its domain: after
/// [`decompose`], span `[t_j, t_{j+1}]` has the Bézier points
/// `Q_{j−k+1..=j}` (their blossoms `blossom(t_j^{k−1−r} t_{j+1}^r)`).
fn spline_pieces<T: Real, const D: usize>(
    curve: &BSpline<T, D>,
    weights: Option<&BSpline<T, 1>>,
    lo: &T,
    hi: &T,
) -> Result<Vec<BezierPiece<T, D>>, CurveError> {
    let mut c = curve.clone();
    let mut w = weights.cloned();
    decompose(&mut c, &mut w, lo, hi)?;
    let p = c.order() - 1;
    let t = c.knots().as_slice();
    let mut pieces = Vec::new();
    for j in p..c.points().len() {
        if !(t[j] < t[j + 1] && t[j] >= *lo && t[j + 1] <= *hi) {
            continue;
        }
        let num = c.points()[j - p..=j].to_vec();
        let form = match &w {
            None => PieceForm::Polynomial(Bezier::new(num)?),
            Some(w) => PieceForm::Rational(RationalBezier::from_homogeneous(
                num,
                w.points()[j - p..=j].iter().map(|x| x[0].clone()).collect(),
            )?),
        };
        pieces.push(BezierPiece {
            span: (t[j].clone(), t[j + 1].clone()),
            form,
        });
    }
    Ok(pieces)
}

impl<T: Real, const D: usize> ParamCurveBezier<T, D> for BSpline<T, D> {
    /// One polynomial piece per non-empty knot span of the domain, by Boehm
    /// insertion of every knot to multiplicity `k − 1` (module doc).
    /// **Cost** `O(s·k·(n + s k))` for `s` spans.
    fn bezier_pieces(&self) -> Result<Vec<BezierPiece<T, D>>, CurveError> {
        let (lo, hi) = self.domain();
        spline_pieces(self, None, &lo, &hi)
    }
}

impl<T: Real, const D: usize> ParamCurveBezier<T, D> for NurbsCurve<T, D> {
    /// One rational piece per non-empty knot span: the homogeneous points and
    /// the weights decomposed by the same insertions (positive weights stay
    /// positive: every inserted weight is a convex combination).
    fn bezier_pieces(&self) -> Result<Vec<BezierPiece<T, D>>, CurveError> {
        let h = self.homogeneous();
        let w = BSpline::new(
            h.order(),
            self.weights()
                .iter()
                .map(|x| Vector1::new(x.clone()))
                .collect(),
            h.knots().clone(),
        )?;
        let (lo, hi) = h.domain();
        spline_pieces(h, Some(&w), &lo, &hi)
    }
}

impl<T: Real, const D: usize> ParamCurveBezier<T, D> for SsplineCurve<T, D> {
    /// The pieces of its B-spline view ([`SsplineCurve::to_bspline`], B-spline
    /// families only) on its own domain `[0, ν − 1]`.
    fn bezier_pieces(&self) -> Result<Vec<BezierPiece<T, D>>, CurveError> {
        let (lo, hi) = ParamCurve::domain(self);
        spline_pieces(&self.to_bspline()?, None, &lo, &hi)
    }
}

impl<T: Real, const D: usize> ParamCurveBezier<T, D> for CatmullRom<T, D> {
    /// One cubic per segment `[k_s, k_{s+1}]`, from the end points and
    /// derivatives: `P_1 = P(k_s) + h P'(k_s)/3`, `P_2 = P(k_{s+1}) − h P'(k_{s+1})/3`
    /// (each segment of the Barry–Goldman pyramid is a cubic in `t`).
    fn bezier_pieces(&self) -> Result<Vec<BezierPiece<T, D>>, CurveError> {
        let k = self.knots();
        let three = T::from_int(3);
        (0..self.segment_count())
            .map(|s| {
                let (p0, d0) = self.eval_segment(s, &T::zero())?;
                let (p3, d3) = self.eval_segment(s, &T::one())?;
                let third = (k[s + 1].clone() - &k[s]) / three.clone();
                let p1 = &p0 + d0 * third.clone();
                let p2 = &p3 - d3 * third;
                Ok(BezierPiece {
                    span: (k[s].clone(), k[s + 1].clone()),
                    form: PieceForm::Polynomial(Bezier::new(vec![p0, p1, p2, p3])?),
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bspline::knots::KnotVector;
    use nalgebra::Vector2;

    /// Each piece, evaluated at local `s`, is the curve at `param(s)`.
    fn agree<C: ParamCurveBezier<f64, 2>>(curve: &C, tol: f64)
    where
        CurveError: From<C::Error>,
    {
        let pieces = curve.bezier_pieces().unwrap();
        let (lo, hi) = curve.domain();
        assert_eq!(
            (pieces[0].span.0, pieces[pieces.len() - 1].span.1),
            (lo, hi)
        );
        for w in pieces.windows(2) {
            assert_eq!(w[0].span.1, w[1].span.0);
        }
        for piece in &pieces {
            for i in 0..=8 {
                let s = i as f64 / 8.0;
                let want = curve
                    .eval(&piece.param(&s))
                    .map_err(CurveError::from)
                    .unwrap();
                let got = piece.eval_local(&s).unwrap();
                assert!((got - want).norm() <= tol, "{got} vs {want}");
            }
        }
    }

    #[test]
    fn spline_pieces_are_the_spline() {
        let q: Vec<_> = [
            (0.0, 0.0),
            (1.0, 2.0),
            (3.0, 2.0),
            (4.0, 0.0),
            (5.0, 1.0),
            (6.0, -1.0),
        ]
        .iter()
        .map(|&(x, y)| Vector2::new(x, y))
        .collect();
        // Unclamped cubic: the domain ends are inserted too.
        let knots = KnotVector::new((0..10).map(f64::from).collect()).unwrap();
        let b = BSpline::new(4, q.clone(), knots.clone()).unwrap();
        assert_eq!(b.bezier_pieces().unwrap().len(), 3);
        agree(&b, 1e-14);
        let w = vec![1.0, 2.0, 0.5, 1.0, 3.0, 1.0];
        agree(&NurbsCurve::new(4, q, w, knots).unwrap(), 1e-14);
        agree(
            &NurbsCurve::circle(&Vector2::new(0.0, 0.0), &1.0).unwrap(),
            1e-15,
        );
    }

    #[test]
    fn catmull_rom_segments_are_cubics() {
        use super::super::catmull_rom::Spacing;
        let pts = vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(2.0, 1.0),
            Vector2::new(4.0, -1.0),
            Vector2::new(5.0, 0.5),
        ];
        for spacing in [Spacing::Uniform, Spacing::Centripetal, Spacing::Chordal] {
            agree(
                &CatmullRom::new(pts.clone(), spacing, false).unwrap(),
                1e-14,
            );
            agree(&CatmullRom::new(pts.clone(), spacing, true).unwrap(), 1e-14);
        }
    }

    #[test]
    fn a_point_at_infinity_has_no_pieces() {
        let r = RationalBezier::from_homogeneous(
            vec![
                Vector2::new(1.0, 0.0),
                Vector2::new(0.0, 1.0),
                Vector2::new(-1.0, 0.0),
            ],
            vec![1.0, 0.0, 1.0],
        )
        .unwrap();
        assert!(matches!(
            r.bezier_pieces(),
            Err(CurveError::BadWeight { index: 1, .. })
        ));
    }
}
