//! Quaternions of the QI curve (seed 004, eq 3–4): the paper's
//! `q = cos β + v̂ sin β` with `v̂ = (0, 0, cos α, sin α)` and the rotation
//! `v ↦ q v q⁻¹`.
//!
//! nalgebra's [`Quaternion`] works for every [`Real`] (including `Mp`), so
//! it is used directly. Component order follows the paper: `(w, x, y, z)`
//! = `(scalar, i, j, k)`; nalgebra's `Quaternion::new(w, i, j, k)` takes the
//! same order.

use crate::scalar::Real;
use nalgebra::{Quaternion, Vector3};

/// The paper's quaternion (eq 3–4):
/// `q(α, β) = exp(v̂ β) = cos β + v̂ sin β`, `v̂ = (0, 0, cos α, sin α)`,
/// i.e. `(w, x, y, z) = (cos β, 0, cos α sin β, sin α sin β)`.
///
/// A unit quaternion for every real `α, β`. Cost: two `sin_cos`.
///
/// ```
/// use splinelab::qi::quaternion::paper_quaternion;
/// let q = paper_quaternion(&0.0f64, &0.0f64);
/// assert_eq!((q.w, q.i, q.j, q.k), (1.0, 0.0, 0.0, 0.0));
/// ```
///
/// ```
/// // In MPFR: α = 0 gives q = cos β + j sin β, the rotation by 2β about y,
/// // so q v_x q⁻¹ = (cos 2β, 0, ∓sin 2β) and |q| = 1.
/// use nalgebra::Vector3;
/// use splinelab::nalgebra::ComplexField;
/// use splinelab::qi::quaternion::{paper_quaternion, rotate};
/// use splinelab::scalar::{Mp, Real};
/// type M = Mp<200>;
/// let b = M::from_int(1) / M::from_int(5);
/// let q = paper_quaternion(&M::from_int(0), &b);
/// let d = rotate(&q, &Vector3::new(M::from_int(1), M::from_int(0), M::from_int(0)));
/// let two_b = b.clone() + b;
/// assert!((d[0].clone() - two_b.clone().cos()).to_f64().abs() < 1e-55);
/// assert!(d[1].to_f64().abs() < 1e-55);
/// assert!((d[2].clone() * d[2].clone() - two_b.clone().sin() * two_b.sin()).to_f64().abs() < 1e-55);
/// ```
pub fn paper_quaternion<T: Real>(alpha: &T, beta: &T) -> Quaternion<T> {
    let (sa, ca) = alpha.clone().sin_cos();
    let (sb, cb) = beta.clone().sin_cos();
    Quaternion::new(cb, T::zero(), ca * sb.clone(), sa * sb)
}

/// `q v q⁻¹` by two quaternion products with the pure quaternion
/// `(0, v)` and the inverse `q̄ / |q|²` (seed 004 eq 1). Works for any
/// non-zero `q`; for unit `q` it is the rotation by `q`.
///
/// Deliberately the plain product, not nalgebra's optimised
/// `UnitQuaternion` transform: it is the reference that the closed-form
/// tangent is tested against. Cost: 2 quaternion products (32 mul).
pub fn rotate<T: Real>(q: &Quaternion<T>, v: &Vector3<T>) -> Vector3<T> {
    let p = Quaternion::from_parts(T::zero(), v.clone());
    let norm2 = q.norm_squared();
    let inv = q.conjugate() / norm2;
    (q * p * inv).imag()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    #[allow(unused_imports)]
    use crate::scalar::prelude::*;

    #[test]
    fn paper_quaternion_is_unit_and_rotates_x_in_a_plane_orthogonal_to_axis() {
        let a = Mp::<128>::from_f64_exact(0.7);
        let b = Mp::<128>::from_f64_exact(-1.3);
        let q = paper_quaternion(&a, &b);
        let one = Mp::<128>::from_int(1);
        assert!((q.norm_squared() - one).abs() < Mp::<128>::unit_roundoff().scale_by_pow2(3));
        // The axis (0, cos α, sin α) is fixed by the rotation.
        let axis = Vector3::new(Mp::from_int(0), a.clone().cos(), a.clone().sin());
        let r = rotate(&q, &axis);
        assert!((r - axis).norm() < Mp::<128>::unit_roundoff().scale_by_pow2(4));
    }
}
