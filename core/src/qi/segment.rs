//! One quadratic QI segment (seed 004 eq 8–13): control angles
//! `α_{i,0..2}`, `β_{i,0..2}` and arc length `l_i`.

use super::tangent::TangentJet;
use crate::bernstein::basis::bernstein_basis;
use crate::quadrature::GaussLegendre;
use crate::scalar::Real;
use nalgebra::Vector3;

/// A quadratic Bézier QI segment `C(t) = P + l ∫₀ᵗ T(α(τ), β(τ)) dτ` with
/// `α(t) = Σ_j α_j B_{2,j}(t)`, `β(t) = Σ_j β_j B_{2,j}(t)` (eq 9, 12–13).
/// The start point `P` is not stored: the segment is a displacement.
#[derive(Debug, Clone, PartialEq)]
pub struct QiSegment<T> {
    /// Bernstein coefficients of `α(t)` (radians).
    pub alpha: [T; 3],
    /// Bernstein coefficients of `β(t)` (radians).
    pub beta: [T; 3],
    /// Arc length `l` (the curve has speed `l` in `t`).
    pub length: T,
}

/// `Σ_j c_j B_{2,j}(t)` with the shared Bernstein basis.
fn bernstein2<T: Real>(c: &[T; 3], t: &T) -> T {
    let b = bernstein_basis(2, t);
    c.iter()
        .zip(b)
        .fold(T::zero(), |acc, (c, b)| acc + c.clone() * b)
}

/// Derivative of a quadratic in Bernstein form:
/// `2 Σ_j (c_{j+1} − c_j) B_{1,j}(t)`.
fn bernstein2_derivative<T: Real>(c: &[T; 3], t: &T) -> T {
    let b = bernstein_basis(1, t);
    let d0 = c[1].clone() - &c[0];
    let d1 = c[2].clone() - &c[1];
    T::from_int(2) * (d0 * b[0].clone() + d1 * b[1].clone())
}

impl<T: Real> QiSegment<T> {
    /// `α(t)`.
    pub fn alpha_at(&self, t: &T) -> T {
        bernstein2(&self.alpha, t)
    }

    /// `β(t)`.
    pub fn beta_at(&self, t: &T) -> T {
        bernstein2(&self.beta, t)
    }

    /// Unit tangent `dC/ds = T(α(t), β(t))` (eq 16).
    pub fn tangent_at(&self, t: &T) -> Vector3<T> {
        TangentJet::new(&self.alpha_at(t), &self.beta_at(t)).t
    }

    /// Curvature `κ = |dT/ds| = √(sin²2β · α'² + 4 β'²) / l`, exact from the
    /// orthogonality of `∂T/∂α` (norm `|sin 2β|`) and `∂T/∂β` (norm 2);
    /// `'` is `d/dt`. Cost: one `sin`, a few products; accurate to a few
    /// ulps relative.
    pub fn curvature_at(&self, t: &T) -> T {
        let s2 = (self.beta_at(t) * T::from_int(2)).sin();
        let da = bernstein2_derivative(&self.alpha, t);
        let db = bernstein2_derivative(&self.beta, t);
        let k2 = s2.clone() * s2 * da.clone() * da + T::from_int(4) * db.clone() * db;
        k2.sqrt() / self.length.clone()
    }

    /// Curvature vector `dT/ds = (∂T/∂α · α' + ∂T/∂β · β') / l` (`'` = `d/dt`);
    /// its norm is [`Self::curvature_at`]. Used to check G2 joins
    /// geometrically (eq 17, 21).
    pub fn curvature_vector_at(&self, t: &T) -> Vector3<T> {
        let jet = TangentJet::new(&self.alpha_at(t), &self.beta_at(t));
        let da = bernstein2_derivative(&self.alpha, t);
        let db = bernstein2_derivative(&self.beta, t);
        (jet.d_alpha * da + jet.d_beta * db) / self.length.clone()
    }

    /// `C(t) − P = l ∫₀ᵗ T dτ` by the given Gauss–Legendre rule mapped to
    /// `[0, t]` (eq 9). Cost: `m` tangent evaluations. Error: the rule's
    /// error for this entire integrand, which [`crate::qi::interpolate()`]
    /// controls by doubling; it only decreases for `t < 1`.
    pub fn displacement(&self, t: &T, rule: &GaussLegendre<T>) -> Vector3<T> {
        let mut acc = Vector3::new(T::zero(), T::zero(), T::zero());
        for (tau, w) in rule.nodes().iter().zip(rule.weights()) {
            let tt = t.clone() * tau;
            acc += self.tangent_at(&tt) * w.clone();
        }
        acc * (self.length.clone() * t)
    }

    /// `C(1) − P = l ∫₀¹ T dτ`.
    pub fn end_displacement(&self, rule: &GaussLegendre<T>) -> Vector3<T> {
        self.displacement(&T::one(), rule)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    #[allow(unused_imports)]
    use crate::scalar::prelude::*;

    /// A circle: β linear with slope b, α constant π/2 gives
    /// `T = (cos 2β, sin 2β, 0)`, a planar circle of radius `l/(2b)`:
    /// closed-form displacement and curvature `2b/l`.
    #[test]
    fn circular_arc_closed_form() {
        type M = Mp<256>;
        let half_pi = M::frac_pi_2();
        let b = M::from_f64_exact(0.75);
        let l = M::from_f64_exact(2.5);
        let seg = QiSegment {
            alpha: [half_pi.clone(), half_pi.clone(), half_pi],
            beta: [M::from_int(0), b.clone() / M::from_int(2), b.clone()],
            length: l.clone(),
        };
        let rule = GaussLegendre::new(40).unwrap();
        let d = seg.end_displacement(&rule);
        // ∫₀¹ (cos 2bt, sin 2bt) dt = (sin 2b, 1 − cos 2b)/(2b).
        let two_b = b.clone() * M::from_int(2);
        let ex = l.clone() * two_b.clone().sin() / two_b.clone();
        let ey = l.clone() * (M::from_int(1) - two_b.clone().cos()) / two_b.clone();
        let tol = M::unit_roundoff().scale_by_pow2(8);
        assert!((d.x.clone() - ex).abs() < tol);
        assert!((d.y.clone() - ey).abs() < tol);
        assert!(d.z.clone().abs() < tol);
        let k = seg.curvature_at(&M::from_f64_exact(0.3));
        assert!((k - two_b / l).abs() < tol);
    }
}
