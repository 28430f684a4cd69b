//! End conditions of the QI interpolation (seed 004 §4): the tangent
//! directions of the circles through the first three and the last three
//! points.
//!
//! **Method.** Inversion about `A` (`x ↦ (x − A)/|x − A|²`) maps the circle
//! through `A, B, C` to the straight line through the images of `B` and `C`,
//! and a circle through the centre of inversion has its tangent at `A`
//! parallel to that line. So the tangent at `A`, oriented from `A` towards
//! `B`, is
//!
//! `t_A ∝ a/|a|² − b/|b|²`, `a = B − A`, `b = C − A`.
//!
//! No circumcentre is formed, so nothing divides by `|a × b|`: for collinear
//! `A, B, C` (in this order) the formula gives the chord direction, as the
//! issue asks, and it is continuous as the triple straightens.

use super::tangent::unit_direction;
use super::{QiError, finite_positive};
use crate::scalar::Real;
use nalgebra::Vector3;

/// Unit tangent at `A` of the circle through `A, B, C`, oriented towards
/// `B` along the arc `A → B → C` (collinear: the chord direction).
///
/// Cost: ~20 flops. Error: a few ulps relative to `|a|⁻¹` unless `B` and `C`
/// nearly coincide as seen from `A` (then the line through the images is
/// ill-determined and so is the circle). Errors when `A` coincides with `B`
/// or `C`, or when the direction vanishes (`B = C`).
///
/// Tested in `circle_tangent.rs::tests::tangent_is_perpendicular_to_radius`.
/// **Source**: seed 004's end-tangent rule (circle through the first three points).
///
/// ```
/// use nalgebra::Vector3;
/// use splinelab::qi::circle_tangent::start_tangent;
/// // Unit circle: A = (1,0,0), B = (0,1,0), C = (−1,0,0): tangent (0,1,0).
/// let t = start_tangent(&Vector3::new(1.0, 0.0, 0.0), &Vector3::new(0.0, 1.0, 0.0),
///                       &Vector3::new(-1.0, 0.0, 0.0)).unwrap();
/// assert!((t - Vector3::new(0.0, 1.0, 0.0)).norm() < 1e-15);
/// ```
pub fn start_tangent<T: Real>(
    a_pt: &Vector3<T>,
    b_pt: &Vector3<T>,
    c_pt: &Vector3<T>,
) -> Result<Vector3<T>, QiError> {
    let a = b_pt - a_pt;
    let b = c_pt - a_pt;
    let (na, nb) = (a.norm_squared(), b.norm_squared());
    if !finite_positive(&na) || !finite_positive(&nb) {
        return Err(QiError::InvalidTangent { which: "start" });
    }
    unit_direction(&(a / na - b / nb), "start")
}

/// Unit tangent at `C` of the circle through `A, B, C`, oriented in the
/// direction of travel `A → B → C`: the reversed [`start_tangent`] of
/// `C, B, A`. Same cost and error behaviour.
pub fn end_tangent<T: Real>(
    a_pt: &Vector3<T>,
    b_pt: &Vector3<T>,
    c_pt: &Vector3<T>,
) -> Result<Vector3<T>, QiError> {
    start_tangent(c_pt, b_pt, a_pt)
        .map(|t| -t)
        .map_err(|_| QiError::InvalidTangent { which: "end" })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    #[allow(unused_imports)]
    use crate::scalar::prelude::*;

    /// Against the circumcentre construction in Mp<256>: the tangent is
    /// orthogonal to `A − O` and to the plane normal, for a tilted circle.
    #[test]
    fn tangent_is_perpendicular_to_radius() {
        type M = Mp<256>;
        let f = |x: f64, y: f64, z: f64| {
            Vector3::new(
                M::from_f64_exact(x),
                M::from_f64_exact(y),
                M::from_f64_exact(z),
            )
        };
        let (a, b, c) = (f(0.3, -1.0, 2.0), f(1.5, 0.25, 1.0), f(2.0, 2.0, -0.5));
        // Circumcentre: O = A + ((|u|² v − |v|² u) × (u × v)) / (2 |u × v|²).
        let (u, v) = (&b - &a, &c - &a);
        let w = u.cross(&v);
        let o = &a
            + (v.clone() * u.norm_squared() - u.clone() * v.norm_squared()).cross(&w)
                / (w.norm_squared() * M::from_int(2));
        assert!(((&o - &b).norm() - (&o - &a).norm()).abs() < M::unit_roundoff().scale_by_pow2(8));
        let tol = M::unit_roundoff().scale_by_pow2(10);
        let t0 = start_tangent(&a, &b, &c).unwrap();
        assert!(t0.dot(&(&a - &o)).abs() < tol && t0.dot(&w).abs() < tol);
        assert!(t0.dot(&u) > M::from_int(0));
        let t1 = end_tangent(&a, &b, &c).unwrap();
        assert!(t1.dot(&(&c - &o)).abs() < tol && t1.dot(&w).abs() < tol);
        assert!(t1.dot(&(&c - &b)) > M::from_int(0));
    }

    #[test]
    fn collinear_gives_chord_and_coincident_is_error() {
        let p = |x: f64| Vector3::new(x, 2.0 * x, -x);
        let t = start_tangent(&p(0.0), &p(1.0), &p(3.0)).unwrap();
        let e = p(1.0) / p(1.0).norm();
        assert!((t - e).norm() < 1e-15);
        assert!(start_tangent(&p(0.0), &p(0.0), &p(1.0)).is_err());
        assert!(end_tangent(&p(0.0), &p(1.0), &p(1.0)).is_err());
    }
}
