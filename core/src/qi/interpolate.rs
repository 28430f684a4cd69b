//! G2 interpolation of 3D points by quadratic QI segments (seed 004 §3):
//! validation, end conditions, starting guess, quadrature order, Newton.
//!
//! **Procedure.**
//! 1. Validate: `≥ 3` finite points, no two consecutive points equal at
//!    working precision, valid options.
//! 2. End tangents: the user's, or the circles through the first and the
//!    last three points ([`super::circle_tangent`]).
//! 3. Starting guess ("cubic-spline-like"): the clamped chord-length cubic
//!    spline with unit end slopes; its unit tangent at each point and at
//!    each piece's mid-parameter gives, through the chart of
//!    [`super::tangent`] (branch: principal angles for the start tangent,
//!    then nearest representative along the sequence), `α_{i,0}`, `α_{i,2}`
//!    and `α_{i,1} = 2α(½) − (α_{i,0} + α_{i,2})/2` (same for β); `l_i` is the
//!    spline piece's arc length. The end angles of the system are the
//!    first and last angles of this sequence.
//! 4. Quadrature: the smallest `m = m₀·2^k` whose doubling estimate
//!    `max_i |l_i(Q_m − Q_2m)(T)| / h ≤ quad_tol` on the guess.
//! 5. Newton ([`super::newton`]) on [`super::g2_system::G2System`] to
//!    `‖F‖₂ ≤ tol`. The doubling estimate is re-checked on the solution; if
//!    it fails, `m` doubles and Newton continues (history appended).
//!
//! **Error behaviour.** On success each segment end misses the next point
//! by at most `h (tol + quad_tol)` up to rounding, where `h` is the mean
//! chord; the G1/G2/end equations hold to `tol`. The verify crate measures
//! this by re-integrating the returned angles at higher precision.

use super::circle_tangent::{end_tangent, start_tangent};
use super::cubic_spline::{ClampedCubicSpline, Parameterization};
use super::g2_system::{EndAngles, G2System, pack, unpack};
use super::newton::{Iteration, NewtonOptions, newton};
use super::segment::QiSegment;
use super::tangent::{nearest_angles, principal_angles, unit_direction};
use super::{QiError, finite_positive};
use crate::param_curve::{OutOfDomain, ParamCurve, ParamCurveDeriv, check_domain};
use crate::quadrature::{GaussLegendre, choose_order};
use crate::scalar::Real;
use crate::validation::{at_least, finite_points};
use nalgebra::Vector3;

/// Options of [`interpolate`]; [`QiOptions::default`] gives the documented
/// defaults for the scalar type.
#[derive(Debug, Clone, PartialEq)]
pub struct QiOptions<T> {
    /// Newton stops at `‖F‖₂ ≤ tol` (default `2¹² u`, `u` the unit roundoff).
    pub tol: T,
    /// Accepted quadrature error estimate, relative to the mean chord
    /// (default `2⁸ u`).
    pub quad_tol: T,
    /// Maximum number of Newton steps in total (default 50).
    pub max_iter: usize,
    /// Damped (line-search) Newton instead of plain Newton (default false).
    pub damped: bool,
    /// Start tangent direction (default: circle through the first 3 points).
    pub start_tangent: Option<Vector3<T>>,
    /// End tangent direction (default: circle through the last 3 points).
    pub end_tangent: Option<Vector3<T>>,
    /// First quadrature order tried (default 8).
    pub min_quad_order: usize,
    /// Largest quadrature order allowed (default 2048).
    pub max_quad_order: usize,
}

impl<T: Real> Default for QiOptions<T> {
    fn default() -> Self {
        QiOptions {
            tol: T::unit_roundoff().scale_by_pow2(12),
            quad_tol: T::unit_roundoff().scale_by_pow2(8),
            max_iter: 50,
            damped: false,
            start_tangent: None,
            end_tangent: None,
            min_quad_order: 8,
            max_quad_order: 2048,
        }
    }
}

/// A converged interpolant with everything needed to reproduce it.
#[derive(Debug, Clone, PartialEq)]
pub struct QiInterpolation<T: Real> {
    /// The interpolated points `P_0..P_n`.
    pub points: Vec<Vector3<T>>,
    /// The `n` segments, paper convention (segment `i` starts at `P_i`).
    pub segments: Vec<QiSegment<T>>,
    /// The starting guess (same layout).
    pub start_guess: Vec<QiSegment<T>>,
    /// End angles `(α_{0,0}, β_{0,0}, α_{n−1,2}, β_{n−1,2})` imposed.
    pub end_angles: EndAngles<T>,
    /// Newton history: one record per iterate, `x_0` first.
    pub history: Vec<Iteration<T>>,
    /// Residual scale `h` (mean chord length).
    pub scale: T,
    /// The Gauss–Legendre rule of the final system.
    pub rule: GaussLegendre<T>,
    /// Doubling estimate of its error at the solution (relative to `h`).
    pub quad_error: T,
}

impl<T: Real> QiInterpolation<T> {
    /// Number of Newton steps taken.
    pub fn iterations(&self) -> usize {
        self.history.len() - 1
    }

    /// `‖F(x_k)‖₂` for every iterate.
    pub fn residuals(&self) -> Vec<T> {
        self.history.iter().map(|h| h.residual.clone()).collect()
    }

    /// `C_i(t)` with the stored rule (`t ∈ [0, 1]`).
    pub fn point(&self, i: usize, t: &T) -> Vector3<T> {
        &self.points[i] + self.segments[i].displacement(t, &self.rule)
    }
}

/// Interpolates `points` by `n = points.len() − 1` quadratic QI segments
/// with G2 joins by Newton–Raphson on the G0/G1/G2 system (seed 004
/// eqs 18–22); see the module doc for the procedure.
///
/// **Accuracy**: the fit hits every point to `1e-12` relative in f64 and to
/// `2^{−236}` in `Mp<256>`, with G1/G2 joins to `tol`
/// (`verify/tests/it/qi_interpolation.rs::f64_fits_hit_every_point_to_1e_12_relative_with_g1_g2_joins`,
/// `mp256_fits_hit_every_point_to_2_pow_minus_236`).
///
/// Cost: per Newton step one dense `7n × 7n` LU (`≈ 230 n³` flops) and
/// `n m` tangent evaluations; typically 4–7 steps in f64 on smooth data.
///
/// Errors: [`QiError::Input`] (too few or non-finite points),
/// [`QiError::CoincidentPoints`], [`QiError::InvalidTangent`],
/// [`QiError::InvalidOption`], [`QiError::Quadrature`], and
/// [`QiError::NotConverged`] carrying the residual history.
///
/// ```
/// use nalgebra::Vector3;
/// use splinelab::qi::{interpolate, QiOptions};
/// let pts: Vec<_> = (0..4)
///     .map(|k| { let t = k as f64 * 0.6; Vector3::new(t.cos(), t.sin(), 0.3 * t) })
///     .collect();
/// let fit = interpolate(&pts, &QiOptions::default()).unwrap();
/// assert_eq!(fit.segments.len(), 3);
/// assert!(fit.residuals().last().unwrap() <= &QiOptions::<f64>::default().tol);
/// ```
pub fn interpolate<T: Real>(
    points: &[Vector3<T>],
    opts: &QiOptions<T>,
) -> Result<QiInterpolation<T>, QiError> {
    validate_options(opts)?;
    let scale = validate_points(points)?;
    let n = points.len() - 1;
    let t0 = match &opts.start_tangent {
        Some(d) => unit_direction(d, "start")?,
        None => start_tangent(&points[0], &points[1], &points[2])?,
    };
    let t1 = match &opts.end_tangent {
        Some(d) => unit_direction(d, "end")?,
        None => end_tangent(&points[n - 2], &points[n - 1], &points[n])?,
    };
    let (guess, ends) = start_guess(points, &t0, &t1)?;
    let (mut rule, _) = choose_order(
        opts.min_quad_order,
        opts.max_quad_order,
        &opts.quad_tol,
        |a, b| quadrature_gap(&guess, a, b, &scale),
    )?;
    let mut x = pack(&guess);
    let mut history: Vec<Iteration<T>> = Vec::new();
    loop {
        let sys = G2System::new(points, scale.clone(), ends.clone(), rule.clone());
        let used = history.len().saturating_sub(1);
        let nopts = NewtonOptions {
            tol: opts.tol.clone(),
            max_iter: opts.max_iter.saturating_sub(used),
            damped: opts.damped,
        };
        let run = newton(&sys, x, &nopts);
        history.extend(run.history);
        x = run.x;
        if let Some(reason) = run.failure {
            return Err(not_converged(reason, &history));
        }
        let segments = unpack(&x);
        let doubled = GaussLegendre::new(2 * rule.order())?;
        let est = quadrature_gap(&segments, &rule, &doubled, &scale);
        if est <= opts.quad_tol {
            return Ok(QiInterpolation {
                points: points.to_vec(),
                segments,
                start_guess: guess,
                end_angles: ends,
                history,
                scale,
                rule,
                quad_error: est,
            });
        }
        if 2 * rule.order() > opts.max_quad_order {
            return Err(QiError::Quadrature(
                crate::quadrature::QuadratureError::ToleranceNotMet {
                    order: 2 * rule.order(),
                    estimate: est.to_f64(),
                    tol: opts.quad_tol.to_f64(),
                },
            ));
        }
        rule = doubled;
    }
}

fn not_converged<T: Real>(reason: super::NewtonFailure, history: &[Iteration<T>]) -> QiError {
    QiError::NotConverged {
        reason,
        residuals: history.iter().map(|h| h.residual.to_f64()).collect(),
        steps: history
            .iter()
            .filter_map(|h| h.step.as_ref().map(|s| s.to_f64()))
            .collect(),
    }
}

/// `max_i |end displacement by rule a − by rule b| / h`.
fn quadrature_gap<T: Real>(
    segments: &[QiSegment<T>],
    a: &GaussLegendre<T>,
    b: &GaussLegendre<T>,
    scale: &T,
) -> T {
    segments.iter().fold(T::zero(), |acc, s| {
        let d = (s.end_displacement(a) - s.end_displacement(b)).norm() / scale.clone();
        if d > acc || !d.is_finite() { d } else { acc }
    })
}

fn validate_options<T: Real>(opts: &QiOptions<T>) -> Result<(), QiError> {
    let positive = |v: &T| v.is_finite() && *v > T::zero();
    if !positive(&opts.tol) {
        return Err(QiError::InvalidOption {
            name: "tol",
            why: format!("must be positive and finite, got {}", opts.tol.to_f64()),
        });
    }
    if !positive(&opts.quad_tol) {
        return Err(QiError::InvalidOption {
            name: "quad_tol",
            why: format!(
                "must be positive and finite, got {}",
                opts.quad_tol.to_f64()
            ),
        });
    }
    let doubled = opts.min_quad_order.checked_mul(2);
    if opts.min_quad_order == 0 || doubled.is_none_or(|d| d > opts.max_quad_order) {
        return Err(QiError::InvalidOption {
            name: "min_quad_order",
            why: "need 1 ≤ 2·min_quad_order ≤ max_quad_order".into(),
        });
    }
    Ok(())
}

/// Checks the points; returns the mean chord length `h`.
fn validate_points<T: Real>(points: &[Vector3<T>]) -> Result<T, QiError> {
    at_least("QI interpolation", 3, points.len())?;
    finite_points("point", points)?;
    let mut total = T::zero();
    for (index, w) in points.windows(2).enumerate() {
        let d = (&w[1] - &w[0]).norm();
        // Equal at working precision: the chord is below a few ulps of the
        // coordinates' magnitude.
        let mag = w[0].amax().max(w[1].amax());
        if !finite_positive(&(d.clone() - mag * T::unit_roundoff().scale_by_pow2(4))) {
            return Err(QiError::CoincidentPoints { index });
        }
        total += d;
    }
    Ok(total / T::from_int(points.len() as i64 - 1))
}

/// The spline-based starting guess and the end angles (module doc, step 3).
fn start_guess<T: Real>(
    points: &[Vector3<T>],
    t0: &Vector3<T>,
    t1: &Vector3<T>,
) -> Result<(Vec<QiSegment<T>>, EndAngles<T>), QiError> {
    let spline = ClampedCubicSpline::new(points, Parameterization::ChordLength, t0, t1)?;
    let n = spline.pieces();
    let half = T::from_f64_exact(0.5);
    // Directions in order: P_0, mid_0, P_1, mid_1, …, P_n (ends exact).
    let mut dirs = Vec::with_capacity(2 * n + 1);
    for i in 0..n {
        dirs.push(if i == 0 {
            t0.clone()
        } else {
            spline.slopes()[i].clone()
        });
        dirs.push(spline.jet(i, &half)[1].clone());
    }
    dirs.push(t1.clone());
    let mut angles = Vec::with_capacity(dirs.len());
    angles.push(principal_angles(&dirs[0])?);
    for d in &dirs[1..] {
        let (pa, pb) = angles.last().expect("non-empty").clone();
        angles.push(nearest_angles(d, (&pa, &pb))?);
    }
    let rule = GaussLegendre::<T>::new(16)?;
    let segments = (0..n)
        .map(|i| {
            let (a0, b0) = angles[2 * i].clone();
            let (am, bm) = angles[2 * i + 1].clone();
            let (a2, b2) = angles[2 * i + 2].clone();
            let mid =
                |c0: &T, cm: T, c2: &T| cm * T::from_int(2) - (c0.clone() + c2) * half.clone();
            let length = rule.integrate(|t| spline.jet(i, t)[1].norm())
                * (spline.knots()[i + 1].clone() - spline.knots()[i].clone());
            QiSegment {
                alpha: [a0.clone(), mid(&a0, am, &a2), a2],
                beta: [b0.clone(), mid(&b0, bm, &b2), b2],
                length,
            }
        })
        .collect();
    let (ae, be) = angles[2 * n].clone();
    let (a_s, b_s) = angles[0].clone();
    Ok((segments, [a_s, b_s, ae, be]))
}

/// The QI curve on `[0, n]`: segment `i` on `[i, i + 1]`.
impl<T: Real> ParamCurve<T, 3> for QiInterpolation<T> {
    type Error = OutOfDomain;
    fn domain(&self) -> (T, T) {
        (T::zero(), T::from_int(self.segments.len() as i64))
    }
    fn eval(&self, t: &T) -> Result<Vector3<T>, OutOfDomain> {
        let (i, tau) = self.segment_at(t)?;
        Ok(self.point(i, &tau))
    }
}

impl<T: Real> ParamCurveDeriv<T, 3> for QiInterpolation<T> {
    /// `l_i T_i(τ)`: each segment has speed `l_i` in its local parameter.
    fn deriv(&self, t: &T) -> Result<Vector3<T>, OutOfDomain> {
        let (i, tau) = self.segment_at(t)?;
        let s = &self.segments[i];
        Ok(s.tangent_at(&tau) * s.length.clone())
    }
    /// The segment joins `1, …, n − 1`.
    fn breakpoints(&self) -> Vec<T> {
        (1..self.segments.len())
            .map(|i| T::from_int(i as i64))
            .collect()
    }
}

impl<T: Real> QiInterpolation<T> {
    fn segment_at(&self, t: &T) -> Result<(usize, T), OutOfDomain> {
        let (lo, hi) = ParamCurve::domain(self);
        check_domain(t, &lo, &hi)?;
        let i = (t.clone().floor().to_f64() as usize).min(self.segments.len() - 1);
        Ok((i, t.clone() - T::from_int(i as i64)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[allow(unused_imports)]
    use crate::scalar::prelude::*;
    use crate::validation::InputError;

    fn helix(n: usize) -> Vec<Vector3<f64>> {
        (0..n)
            .map(|k| {
                let t = k as f64 * 0.5;
                Vector3::new(t.cos(), t.sin(), 0.4 * t)
            })
            .collect()
    }

    #[test]
    fn bad_inputs_are_typed_errors() {
        let o = QiOptions::<f64>::default();
        assert_eq!(
            interpolate(&helix(2), &o).unwrap_err(),
            QiError::Input(InputError::TooFewPoints {
                what: "QI interpolation",
                needed: 3,
                got: 2
            })
        );
        let mut p = helix(5);
        p[3].y = f64::NAN;
        assert_eq!(
            interpolate(&p, &o).unwrap_err(),
            QiError::Input(InputError::NonFiniteAt {
                what: "point",
                index: 3
            })
        );
        let mut p = helix(5);
        p[2].z = f64::INFINITY;
        assert_eq!(
            interpolate(&p, &o).unwrap_err(),
            QiError::Input(InputError::NonFiniteAt {
                what: "point",
                index: 2
            })
        );
        let mut p = helix(5);
        p[2] = p[1];
        assert_eq!(
            interpolate(&p, &o).unwrap_err(),
            QiError::CoincidentPoints { index: 1 }
        );
        let o2 = QiOptions {
            start_tangent: Some(Vector3::zeros()),
            ..o.clone()
        };
        assert!(matches!(
            interpolate(&helix(5), &o2),
            Err(QiError::InvalidTangent { .. })
        ));
        let o3 = QiOptions {
            tol: -1.0,
            ..o.clone()
        };
        assert!(matches!(
            interpolate(&helix(5), &o3),
            Err(QiError::InvalidOption { .. })
        ));
        let o4 = QiOptions { max_iter: 1, ..o };
        match interpolate(&helix(8), &o4) {
            Err(QiError::NotConverged {
                reason, residuals, ..
            }) => {
                assert_eq!(reason, super::super::NewtonFailure::IterationLimit);
                assert_eq!(residuals.len(), 2);
            }
            other => panic!("expected NotConverged, got {other:?}"),
        }
    }
}
