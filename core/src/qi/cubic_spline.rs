//! The clamped C² cubic spline through 3D points: the comparison curve of
//! the paper's Figure 2 (seed 004 §4) and the source of the Newton starting
//! guess.
//!
//! **Method.** Knots `u_0 < … < u_n` (uniform `u_i = i` or chord length
//! `u_i − u_{i−1} = |P_i − P_{i−1}|`); on each interval a cubic Hermite
//! piece with slopes `m_i`. C² continuity at interior knots gives the
//! tridiagonal system (de Boor, *A Practical Guide to Splines*, ch. IV)
//!
//! `Δ_i m_{i−1} + 2(Δ_{i−1} + Δ_i) m_i + Δ_{i−1} m_{i+1} = 3(Δ_i δ_{i−1} + Δ_{i−1} δ_i)`,
//!
//! `Δ_i = u_{i+1} − u_i`, `δ_i = (P_{i+1} − P_i)/Δ_i`, with the clamped end
//! slopes `m_0`, `m_n` given. The matrix is strictly diagonally dominant, so
//! elimination without pivoting (Thomas) is stable; cost `O(n)`.
//!
//! The paper clamps the spline with the circle tangents "of magnitude 1";
//! with chord-length knots the parameter is close to arc length, so a unit
//! slope is natural; with uniform knots it is not, which is what makes the
//! paper's spline curvature spike at the end (both are offered).

use super::{QiError, finite_positive};
use crate::param_curve::{OutOfDomain, ParamCurve, ParamCurveDeriv, check_domain};
use crate::scalar::Real;
use crate::validation::{at_least, finite_points};
use nalgebra::Vector3;

/// How the spline's knots are placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Parameterization {
    /// `u_i = i`.
    Uniform,
    /// `u_i − u_{i−1} = |P_i − P_{i−1}|`.
    ChordLength,
}

/// A clamped cubic spline in Hermite form.
#[derive(Debug, Clone, PartialEq)]
pub struct ClampedCubicSpline<T: Real> {
    knots: Vec<T>,
    points: Vec<Vector3<T>>,
    slopes: Vec<Vector3<T>>,
}

impl<T: Real> ClampedCubicSpline<T> {
    /// Builds the spline through `points` (≥ 2, finite, distinct consecutive
    /// under chord-length parameterisation) with finite
    /// end slopes `d_start = S'(u_0)`, `d_end = S'(u_n)` (derivatives with
    /// respect to the knot parameter). See the module doc for the method.
    /// **Accuracy**: reproduces cubic polynomials
    /// (`cubic_spline.rs::tests::reproduces_cubic_polynomials`). **Source**: seed
    /// 004 Figure 2 (the comparison curve); de Boor, *A Practical Guide to Splines*, ch. IV.
    pub fn new(
        points: &[Vector3<T>],
        param: Parameterization,
        d_start: &Vector3<T>,
        d_end: &Vector3<T>,
    ) -> Result<Self, QiError> {
        at_least("a clamped cubic spline", 2, points.len())?;
        finite_points("point", points)?;
        for (which, d) in [("start", d_start), ("end", d_end)] {
            if !d.iter().all(|c| c.is_finite()) {
                return Err(QiError::InvalidTangent { which });
            }
        }
        let mut knots = vec![T::zero()];
        for (i, w) in points.windows(2).enumerate() {
            let d = match param {
                Parameterization::Uniform => T::one(),
                Parameterization::ChordLength => (&w[1] - &w[0]).norm(),
            };
            if !finite_positive(&d) {
                return Err(QiError::CoincidentPoints { index: i });
            }
            let last = knots[i].clone();
            knots.push(last + d);
        }
        let slopes = solve_slopes(&knots, points, d_start, d_end);
        Ok(ClampedCubicSpline {
            knots,
            points: points.to_vec(),
            slopes,
        })
    }

    /// Number of pieces `n`.
    pub fn pieces(&self) -> usize {
        self.points.len() - 1
    }

    /// Knot values `u_0..u_n`.
    pub fn knots(&self) -> &[T] {
        &self.knots
    }

    /// Slopes `m_i = S'(u_i)`.
    pub fn slopes(&self) -> &[Vector3<T>] {
        &self.slopes
    }

    /// `(S, dS/du, d²S/du²)` on piece `i` at local `t ∈ [0, 1]`
    /// (`u = u_i + t Δ_i`), from the cubic Hermite basis. Cost: ~60 flops.
    /// **Accuracy**: exact on cubics to rounding
    /// (`cubic_spline.rs::tests::reproduces_cubic_polynomials`). **Source**: de Boor,
    /// *A Practical Guide to Splines*, ch. IV (Hermite form).
    pub fn jet(&self, i: usize, t: &T) -> [Vector3<T>; 3] {
        let dl = self.knots[i + 1].clone() - self.knots[i].clone();
        let (p0, p1) = (&self.points[i], &self.points[i + 1]);
        let m0 = &self.slopes[i] * dl.clone();
        let m1 = &self.slopes[i + 1] * dl.clone();
        let c = |k: i64| T::from_int(k);
        let t2 = t.clone() * t;
        let t3 = t2.clone() * t;
        let h = [
            c(2) * t3.clone() - c(3) * t2.clone() + c(1),
            t3.clone() - c(2) * t2.clone() + t,
            c(3) * t2.clone() - c(2) * t3.clone(),
            t3 - t2.clone(),
        ];
        let dh = [
            c(6) * t2.clone() - c(6) * t.clone(),
            c(3) * t2.clone() - c(4) * t.clone() + c(1),
            c(6) * t.clone() - c(6) * t2.clone(),
            c(3) * t2 - c(2) * t.clone(),
        ];
        let ddh = [
            c(12) * t.clone() - c(6),
            c(6) * t.clone() - c(4),
            c(6) - c(12) * t.clone(),
            c(6) * t.clone() - c(2),
        ];
        let comb = |w: &[T; 4]| {
            p0 * w[0].clone() + &m0 * w[1].clone() + p1 * w[2].clone() + &m1 * w[3].clone()
        };
        [
            comb(&h),
            comb(&dh) / dl.clone(),
            comb(&ddh) / (dl.clone() * dl),
        ]
    }

    /// Curvature `|S' × S''| / |S'|³` on piece `i` at local `t`
    /// (independent of the parameterisation).
    pub fn curvature(&self, i: usize, t: &T) -> T {
        let [_, d1, d2] = self.jet(i, t);
        let sp = d1.norm();
        d1.cross(&d2).norm() / (sp.clone() * &sp * sp)
    }
}

/// Thomas algorithm for the clamped-slope system (module doc), all three
/// coordinates at once.
fn solve_slopes<T: Real>(
    u: &[T],
    p: &[Vector3<T>],
    d_start: &Vector3<T>,
    d_end: &Vector3<T>,
) -> Vec<Vector3<T>> {
    let n = p.len() - 1;
    let mut m = vec![d_start.clone(); n + 1];
    m[n] = d_end.clone();
    if n < 2 {
        return m;
    }
    let dl: Vec<T> = (0..n).map(|i| u[i + 1].clone() - &u[i]).collect();
    let delta: Vec<Vector3<T>> = (0..n)
        .map(|i| (&p[i + 1] - &p[i]) / dl[i].clone())
        .collect();
    let three = T::from_int(3);
    // Unknowns m_1..m_{n−1}: sub a_i, diag b_i, super c_i, rhs r_i.
    let mut c_prime: Vec<T> = Vec::with_capacity(n);
    let mut r_prime: Vec<Vector3<T>> = Vec::with_capacity(n);
    for i in 1..n {
        let a = dl[i].clone();
        let b = (dl[i - 1].clone() + &dl[i]) * T::from_int(2);
        let c = dl[i - 1].clone();
        let mut r = (&delta[i - 1] * dl[i].clone() + &delta[i] * dl[i - 1].clone()) * three.clone();
        if i == 1 {
            r -= d_start * a.clone();
        }
        if i == n - 1 {
            r -= d_end * c.clone();
        }
        let (denom, r) = if i == 1 {
            (b, r)
        } else {
            let cp: T = c_prime[i - 2].clone();
            let rp: Vector3<T> = r_prime[i - 2].clone();
            (b - a.clone() * cp, r - rp * a)
        };
        c_prime.push(c / denom.clone());
        r_prime.push(r / denom);
    }
    m[n - 1] = r_prime[n - 2].clone();
    for i in (1..n - 1).rev() {
        m[i] = &r_prime[i - 1] - &m[i + 1] * c_prime[i - 1].clone();
    }
    m
}

/// The piece `i` and local `τ ∈ [0, 1]` of the global parameter `t` on the
/// knots `k` (the last piece takes `t = k_last`).
fn piece<T: Real>(k: &[T], t: &T) -> Result<(usize, T), OutOfDomain> {
    let last = k.len() - 1;
    check_domain(t, &k[0], &k[last])?;
    let i = k
        .partition_point(|x| x <= t)
        .saturating_sub(1)
        .min(last - 1);
    let tau = (t.clone() - &k[i]) / (k[i + 1].clone() - &k[i]);
    Ok((i, tau))
}

impl<T: Real> ParamCurve<T, 3> for ClampedCubicSpline<T> {
    type Error = OutOfDomain;
    fn domain(&self) -> (T, T) {
        let k = self.knots();
        (k[0].clone(), k[k.len() - 1].clone())
    }
    fn eval(&self, t: &T) -> Result<Vector3<T>, OutOfDomain> {
        let (i, tau) = piece(self.knots(), t)?;
        let [p, _, _] = self.jet(i, &tau);
        Ok(p)
    }
}

impl<T: Real> ParamCurveDeriv<T, 3> for ClampedCubicSpline<T> {
    fn deriv(&self, t: &T) -> Result<Vector3<T>, OutOfDomain> {
        let (i, tau) = piece(self.knots(), t)?;
        let [_, d, _] = self.jet(i, &tau);
        Ok(d)
    }
    fn breakpoints(&self) -> Vec<T> {
        let k = self.knots();
        crate::param_curve::interior(k, &k[0], &k[k.len() - 1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    #[allow(unused_imports)]
    use crate::scalar::prelude::*;

    /// A cubic polynomial curve is reproduced exactly (uniqueness of the
    /// clamped interpolant), for non-uniform knots: compare with the
    /// polynomial itself at interior parameters, in Mp<256>.
    #[test]
    fn reproduces_cubic_polynomials() {
        type M = Mp<256>;
        let f = |u: &M| {
            Vector3::new(
                u.clone() * u * u.clone() - u,
                M::from_int(2) * u.clone() * u + M::from_int(1),
                M::from_int(3) - u.clone(),
            )
        };
        let df = |u: &M| {
            Vector3::new(
                M::from_int(3) * u.clone() * u - M::from_int(1),
                M::from_int(4) * u.clone(),
                M::from_int(-1),
            )
        };
        // Uniform knots 0..5 on the polynomial's own parameter.
        let pts: Vec<_> = (0..6).map(|i| f(&M::from_int(i))).collect();
        let s = ClampedCubicSpline::new(
            &pts,
            Parameterization::Uniform,
            &df(&M::from_int(0)),
            &df(&M::from_int(5)),
        )
        .unwrap();
        let tol = M::unit_roundoff().scale_by_pow2(10);
        for i in 0..5 {
            let t = M::from_f64_exact(0.375);
            let [p, d, _] = s.jet(i, &t);
            let u = M::from_int(i as i64) + t;
            assert!((p - f(&u)).norm() < tol);
            assert!((d - df(&u)).norm() < tol);
        }
    }

    #[test]
    fn coincident_points_are_an_error() {
        let p = vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 0.0, 0.0)];
        let d = Vector3::new(1.0, 0.0, 0.0);
        assert!(ClampedCubicSpline::new(&p, Parameterization::ChordLength, &d, &d).is_err());
    }
}
