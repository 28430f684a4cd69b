//! The unit tangent of a QI curve as a function of `(α, β)`, its partial
//! derivatives, and the inverse chart (direction → angles) with an explicit
//! branch rule.
//!
//! **Closed form.** With `q = cos β + u sin β`, `u = (0, cos α, sin α)` a unit
//! axis, `q v q⁻¹` is the rotation of `v` by the angle `2β` about `u`
//! (Rodrigues). For `v = v_x = (1, 0, 0)`, `u · v_x = 0` and
//! `u × v_x = (0, sin α, −cos α)`, hence
//!
//! `T(α, β) = (cos 2β, sin α sin 2β, −cos α sin 2β)`.
//!
//! **Partials.** `∂T/∂α = (0, cos α sin 2β, sin α sin 2β)`,
//! `∂T/∂β = (−2 sin 2β, 2 sin α cos 2β, −2 cos α cos 2β)`; they are orthogonal,
//! with norms `|sin 2β|` and `2`. This is why the paper's G2 condition (eq 21)
//! reduces to continuity of `α'/l` and `β'/l` (eq 22).
//!
//! **Branches.** `T` is invariant under `β → β + π` and under
//! `(α, β) → (α + π, −β)`, and `α` is free when `sin 2β = 0` (`T = ±v_x`, the
//! poles of the chart). [`principal_angles`] returns `β ∈ [0, π/2]`,
//! `α = atan2(d_y, −d_z) ∈ (−π, π]` (and `α = 0` at a pole);
//! [`nearest_angles`] returns, among all representatives of a direction,
//! the one nearest (Euclidean in `(α, β)`) to a previous pair, keeping `α` at
//! the previous value at a pole. The interpolation chooses the start
//! tangent's principal angles and continues every later direction with
//! [`nearest_angles`], so the branch is reproducible from the points alone.

use super::{QiError, finite_positive};
use crate::scalar::Real;
use nalgebra::Vector3;

/// `T(α, β) = (cos 2β, sin α sin 2β, −cos α sin 2β)` = `q v_x q⁻¹` with the
/// paper's `q(α, β)` (seed 004 eq 3–4, 16). Unit length for all real inputs.
///
/// Cost: two `sin_cos`. Accuracy: each component within a few ulps
/// (products of correctly rounded sin/cos; no cancellation).
///
/// ```
/// use splinelab::qi::tangent::tangent;
/// let t = tangent(&0.0f64, &0.0f64);
/// assert_eq!((t.x, t.y, t.z), (1.0, 0.0, 0.0));
/// ```
pub fn tangent<T: Real>(alpha: &T, beta: &T) -> Vector3<T> {
    TangentJet::new(alpha, beta).t
}

/// `T` and its partial derivatives at one `(α, β)`; see the module doc for
/// the formulas. Shared by the residual and the exact Jacobian.
#[derive(Debug, Clone, PartialEq)]
pub struct TangentJet<T: Real> {
    /// `T(α, β)`.
    pub t: Vector3<T>,
    /// `∂T/∂α = (0, cos α sin 2β, sin α sin 2β)`.
    pub d_alpha: Vector3<T>,
    /// `∂T/∂β = (−2 sin 2β, 2 sin α cos 2β, −2 cos α cos 2β)`.
    pub d_beta: Vector3<T>,
    /// `sin 2β`, the norm factor of `∂T/∂α` (used by the curvature).
    pub sin_2beta: T,
}

impl<T: Real> TangentJet<T> {
    /// Evaluates `T`, `∂T/∂α`, `∂T/∂β` (cost: two `sin_cos`).
    /// **Accuracy**: equals the quaternion product `q v_x q⁻¹`
    /// (`tangent.rs::tests::closed_form_matches_quaternion_product_f64`); the
    /// partials match central differences (`partials_match_central_differences`).
    /// **Source**: seed 004 eq 16.
    pub fn new(alpha: &T, beta: &T) -> Self {
        let (sa, ca) = alpha.clone().sin_cos();
        let (s2, c2) = (beta.clone() + beta).sin_cos();
        let two = T::from_int(2);
        TangentJet {
            t: Vector3::new(c2.clone(), sa.clone() * &s2, -(ca.clone() * &s2)),
            d_alpha: Vector3::new(T::zero(), ca.clone() * &s2, sa.clone() * &s2),
            d_beta: Vector3::new(
                -(two.clone() * &s2),
                two.clone() * sa * c2.clone(),
                -(two * ca * c2),
            ),
            sin_2beta: s2,
        }
    }
}

/// The unit vector `d/|d|`, or an error for a zero or non-finite `d`.
pub fn unit_direction<T: Real>(d: &Vector3<T>, which: &'static str) -> Result<Vector3<T>, QiError> {
    let n = d.norm();
    if !d.iter().all(|c| c.is_finite()) || !finite_positive(&n) {
        return Err(QiError::InvalidTangent { which });
    }
    Ok(d / n)
}

/// Principal angles of a direction: `β = ½ atan2(√(d_y² + d_z²), d_x) ∈ [0, π/2]`,
/// `α = atan2(d_y, −d_z)` (`α = 0` when `d_y = d_z = 0`), so that
/// `T(α, β) = d/|d|`. The `atan2` form keeps full relative accuracy near the
/// poles, where `acos(d_x)` would not. Errors on zero or non-finite `d`.
pub fn principal_angles<T: Real>(d: &Vector3<T>) -> Result<(T, T), QiError> {
    let d = unit_direction(d, "direction")?;
    let rho = d.y.clone().hypot(d.z.clone());
    let beta = rho.clone().atan2(d.x.clone()) / T::from_int(2);
    let alpha = if rho > T::zero() {
        d.y.clone().atan2(-d.z.clone())
    } else {
        T::zero()
    };
    Ok((alpha, beta))
}

/// The representative `(α, β)` of direction `d` nearest to `(α_p, β_p)`:
/// among `(α₀ + 2kπ, β₀ + mπ)` and `(α₀ + π + 2kπ, −β₀ + mπ)` built from the
/// principal angles `(α₀, β₀)`, the one with least `(α − α_p)² + (β − β_p)²`;
/// at a pole (`d ∥ v_x`) `α = α_p`. Cost: a few roundings and `atan2`s.
/// **Accuracy**: `T(α, β)` reproduces `d` within `1e-14` in f64
/// (`tangent.rs::tests::angles_invert_the_tangent_on_every_branch`).
/// **Source**: the `(α, β)` parametrisation of seed 004 eqs 3–4 and 16.
pub fn nearest_angles<T: Real>(d: &Vector3<T>, prev: (&T, &T)) -> Result<(T, T), QiError> {
    let (a0, b0) = principal_angles(d)?;
    let at_pole = d.y.is_zero() && d.z.is_zero();
    let pi = T::pi();
    let two_pi = T::two_pi();
    let fit = |a: T, b: T| {
        let a = if at_pole {
            prev.0.clone()
        } else {
            a.clone() + two_pi.clone() * ((prev.0.clone() - a) / two_pi.clone()).round()
        };
        let b = b.clone() + pi.clone() * ((prev.1.clone() - b) / pi.clone()).round();
        let da = a.clone() - prev.0.clone();
        let db = b.clone() - prev.1.clone();
        (da.clone() * da + db.clone() * db, a, b)
    };
    let (c1, a1, b1) = fit(a0.clone(), b0.clone());
    let (c2, a2, b2) = fit(a0 + pi.clone(), -b0);
    Ok(if c2 < c1 { (a2, b2) } else { (a1, b1) })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::qi::quaternion::{paper_quaternion, rotate};
    use crate::scalar::Mp;
    #[allow(unused_imports)]
    use crate::scalar::prelude::*;

    fn grid<T: Real>() -> Vec<(T, T)> {
        let mut v = Vec::new();
        for i in -6..=6 {
            for j in -6..=6 {
                v.push((
                    T::from_f64_exact(i as f64 * 0.61),
                    T::from_f64_exact(j as f64 * 0.37),
                ));
            }
        }
        v
    }

    /// Closed form vs the quaternion product `q v_x q⁻¹` (an independent
    /// code path: nalgebra's Hamilton product and inverse).
    fn closed_form_matches_quaternion_product<T: Real>() {
        let vx = Vector3::new(T::one(), T::zero(), T::zero());
        for (a, b) in grid::<T>() {
            let r = rotate(&paper_quaternion(&a, &b), &vx);
            let t = tangent(&a, &b);
            let err = (r - t).norm();
            assert!(
                err <= T::unit_roundoff().scale_by_pow2(5),
                "α={a:?} β={b:?}"
            );
        }
    }

    #[test]
    fn closed_form_matches_quaternion_product_f64() {
        closed_form_matches_quaternion_product::<f64>();
    }

    #[test]
    fn closed_form_matches_quaternion_product_mp() {
        closed_form_matches_quaternion_product::<Mp<256>>();
    }

    /// Partials vs central differences in Mp<512> (step 2^-100: truncation
    /// error ~2^-200, far below the 2^-150 bound checked).
    #[test]
    fn partials_match_central_differences() {
        type M = Mp<512>;
        let h = M::from_int(1).scale_by_pow2(-100);
        for (a, b) in grid::<M>() {
            let j = TangentJet::new(&a, &b);
            let da = (tangent(&(a.clone() + &h), &b) - tangent(&(a.clone() - &h), &b))
                / (h.clone() + &h);
            let db = (tangent(&a, &(b.clone() + &h)) - tangent(&a, &(b.clone() - &h)))
                / (h.clone() + &h);
            let tol = M::from_int(1).scale_by_pow2(-150);
            assert!((da - j.d_alpha.clone()).norm() < tol);
            assert!((db - j.d_beta.clone()).norm() < tol);
            assert!(j.d_alpha.dot(&j.d_beta).abs() < tol);
        }
    }

    #[test]
    fn angles_invert_the_tangent_on_every_branch() {
        let prev = (7.0f64, -2.0f64);
        for (a, b) in grid::<f64>() {
            let d = tangent(&a, &b);
            let (pa, pb) = principal_angles(&d).unwrap();
            assert!((0.0..=std::f64::consts::FRAC_PI_2).contains(&pb));
            assert!((tangent(&pa, &pb) - d).norm() < 1e-15);
            let (na, nb) = nearest_angles(&d, (&prev.0, &prev.1)).unwrap();
            assert!((tangent(&na, &nb) - d).norm() < 1e-14);
            assert!((na - prev.0).abs() <= std::f64::consts::PI + 1e-12);
        }
        // A planar curve crossing the pole keeps α and lets β change sign.
        let d = Vector3::new(1.0, 0.0, 0.0);
        assert_eq!(nearest_angles(&d, (&1.5, &0.01)).unwrap(), (1.5, 0.0));
        let d = tangent(&1.5, &-0.01);
        let (a, b) = nearest_angles(&d, (&1.5, &0.0)).unwrap();
        assert!((a - 1.5).abs() < 1e-12 && (b + 0.01).abs() < 1e-12);
    }

    #[test]
    fn bad_directions_are_errors() {
        let z = Vector3::new(0.0, 0.0, 0.0);
        assert!(principal_angles(&z).is_err());
        let n = Vector3::new(f64::NAN, 1.0, 0.0);
        assert!(principal_angles(&n).is_err());
        let i = Vector3::new(f64::INFINITY, 1.0, 0.0);
        assert!(principal_angles(&i).is_err());
    }
}
