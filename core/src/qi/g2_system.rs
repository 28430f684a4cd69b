//! The G2 interpolation system of seed 004 (eq 18–22) with its exact
//! Jacobian.
//!
//! **Unknowns** (`7n` for `n` segments, eq after 15): per segment `i`,
//! `x[7i..7i+3] = α_{i,0..2}`, `x[7i+3..7i+6] = β_{i,0..2}`, `x[7i+6] = l_i`.
//!
//! **Equations** (`7n`), all dimensionless (`h` = mean chord length):
//! - G0 (eq 18), rows `3i..3i+3`: `(l_i Σ_k w_k T(α_i(t_k), β_i(t_k)) − (P_{i+1} − P_i)) / h`;
//! - G1 (eq 20), rows `3n + 2i, +1`: `α_{i+1,0} − α_{i,2}`, `β_{i+1,0} − β_{i,2}`;
//! - G2 (eq 22, multiplied by `l_i l_{i+1}/h` to stay polynomial in `l`),
//!   rows `3n + 2(n−1) + 2i, +1`:
//!   `((α_{i+1,1} − α_{i+1,0}) l_i − (α_{i,2} − α_{i,1}) l_{i+1}) / h`, same for β;
//! - end tangents (§3 end), the last 4 rows: `α_{0,0} − α_s`, `β_{0,0} − β_s`,
//!   `α_{n−1,2} − α_e`, `β_{n−1,2} − β_e`.
//!
//! **Jacobian.** The G0 block differentiates under the integral sign and
//! uses the same Gauss rule: `∂/∂α_{i,j} = (l_i/h) Σ_k w_k B_{2,j}(t_k) ∂T/∂α`,
//! likewise for β, and `∂/∂l_i = Σ_k w_k T / h`. This is the exact Jacobian
//! of the discretised system, which is what Newton needs for quadratic
//! convergence. The other blocks are linear or bilinear and exact.
//! Cost of one evaluation: `n m` tangent jets (`m` = rule order) plus
//! `O(n)`; the matrix is stored dense (`49n²` entries).

use super::newton::NonlinearSystem;
use super::segment::QiSegment;
use super::tangent::TangentJet;
use crate::bernstein::basis::bernstein_basis;
use crate::quadrature::GaussLegendre;
use crate::scalar::Real;
use nalgebra::{DMatrix, DVector, Vector3};

/// End tangent angles `(α_{0,0}, β_{0,0}, α_{n−1,2}, β_{n−1,2})`.
pub type EndAngles<T> = [T; 4];

/// The system for fixed points, end angles and quadrature rule.
#[derive(Debug, Clone)]
pub struct G2System<'a, T: Real> {
    points: &'a [Vector3<T>],
    scale: T,
    ends: EndAngles<T>,
    rule: GaussLegendre<T>,
    basis: Vec<Vec<T>>,
}

/// Index of `α_{i,j}` in the unknown vector.
pub fn alpha_index(i: usize, j: usize) -> usize {
    7 * i + j
}
/// Index of `β_{i,j}`.
pub fn beta_index(i: usize, j: usize) -> usize {
    7 * i + 3 + j
}
/// Index of `l_i`.
pub fn length_index(i: usize) -> usize {
    7 * i + 6
}

/// Packs segments into the unknown vector (module doc layout).
pub fn pack<T: Real>(segments: &[QiSegment<T>]) -> DVector<T> {
    let mut x = DVector::from_element(7 * segments.len(), T::zero());
    for (i, s) in segments.iter().enumerate() {
        for j in 0..3 {
            x[alpha_index(i, j)] = s.alpha[j].clone();
            x[beta_index(i, j)] = s.beta[j].clone();
        }
        x[length_index(i)] = s.length.clone();
    }
    x
}

/// Unpacks the unknown vector into segments.
pub fn unpack<T: Real>(x: &DVector<T>) -> Vec<QiSegment<T>> {
    (0..x.len() / 7)
        .map(|i| QiSegment {
            alpha: std::array::from_fn(|j| x[alpha_index(i, j)].clone()),
            beta: std::array::from_fn(|j| x[beta_index(i, j)].clone()),
            length: x[length_index(i)].clone(),
        })
        .collect()
}

impl<'a, T: Real> G2System<'a, T> {
    /// The system for `points` (≥ 3, validated by the caller), end angles,
    /// residual scale `h > 0` and rule.
    /// **Accuracy**: its Jacobian agrees with central differences
    /// (`g2_system.rs::tests::jacobian_matches_central_differences`). **Source**:
    /// seed 004 eqs 18–22.
    pub fn new(
        points: &'a [Vector3<T>],
        scale: T,
        ends: EndAngles<T>,
        rule: GaussLegendre<T>,
    ) -> Self {
        let basis = rule.nodes().iter().map(|t| bernstein_basis(2, t)).collect();
        G2System {
            points,
            scale,
            ends,
            rule,
            basis,
        }
    }

    /// Number of segments `n`.
    pub fn segments(&self) -> usize {
        self.points.len() - 1
    }

    /// The quadrature rule in use.
    pub fn rule(&self) -> &GaussLegendre<T> {
        &self.rule
    }

    /// G0 residual of segment `i` and, if asked, its 3×7 Jacobian block.
    fn g0_block(&self, x: &DVector<T>, i: usize, jac: Option<&mut DMatrix<T>>) -> Vector3<T> {
        let l = x[length_index(i)].clone();
        let mut sum = Vector3::new(T::zero(), T::zero(), T::zero());
        let mut d_a: [Vector3<T>; 3] = std::array::from_fn(|_| sum.clone());
        let mut d_b = d_a.clone();
        for (k, w) in self.rule.weights().iter().enumerate() {
            let b = &self.basis[k];
            let comb = |c0: usize| (0..3).fold(T::zero(), |acc, j| acc + x[c0 + j].clone() * &b[j]);
            let jet = TangentJet::new(&comb(alpha_index(i, 0)), &comb(beta_index(i, 0)));
            sum += &jet.t * w.clone();
            if jac.is_some() {
                for j in 0..3 {
                    let wb = w.clone() * &b[j];
                    d_a[j] += &jet.d_alpha * wb.clone();
                    d_b[j] += &jet.d_beta * wb;
                }
            }
        }
        if let Some(jm) = jac {
            let lh = l.clone() / &self.scale;
            for c in 0..3 {
                let row = 3 * i + c;
                for j in 0..3 {
                    jm[(row, alpha_index(i, j))] = d_a[j][c].clone() * &lh;
                    jm[(row, beta_index(i, j))] = d_b[j][c].clone() * &lh;
                }
                jm[(row, length_index(i))] = sum[c].clone() / &self.scale;
            }
        }
        let chord = &self.points[i + 1] - &self.points[i];
        (sum * l - chord) / self.scale.clone()
    }

    /// `F(x)` and, if asked, `J(x)` (module doc).
    fn eval(&self, x: &DVector<T>, want_jac: bool) -> (DVector<T>, Option<DMatrix<T>>) {
        let n = self.segments();
        let dim = 7 * n;
        let mut f = DVector::from_element(dim, T::zero());
        let mut jac = want_jac.then(|| DMatrix::from_element(dim, dim, T::zero()));
        for i in 0..n {
            let r = self.g0_block(x, i, jac.as_mut());
            for c in 0..3 {
                f[3 * i + c] = r[c].clone();
            }
        }
        let h = self.scale.clone();
        let one = T::one();
        for i in 0..n.saturating_sub(1) {
            for (p, idx) in [
                (0, alpha_index as fn(usize, usize) -> usize),
                (1, beta_index),
            ] {
                // G1 (eq 20).
                let r1 = 3 * n + 2 * i + p;
                f[r1] = x[idx(i + 1, 0)].clone() - x[idx(i, 2)].clone();
                // G2 (eq 22), cross-multiplied.
                let r2 = 3 * n + 2 * (n - 1) + 2 * i + p;
                let (li, lj) = (x[length_index(i)].clone(), x[length_index(i + 1)].clone());
                let d_next = x[idx(i + 1, 1)].clone() - x[idx(i + 1, 0)].clone();
                let d_prev = x[idx(i, 2)].clone() - x[idx(i, 1)].clone();
                f[r2] = (d_next.clone() * &li - d_prev.clone() * &lj) / h.clone();
                if let Some(jm) = jac.as_mut() {
                    jm[(r1, idx(i + 1, 0))] = one.clone();
                    jm[(r1, idx(i, 2))] = -one.clone();
                    jm[(r2, idx(i + 1, 1))] = li.clone() / &h;
                    jm[(r2, idx(i + 1, 0))] = -li / h.clone();
                    jm[(r2, idx(i, 2))] = -lj.clone() / &h;
                    jm[(r2, idx(i, 1))] = lj / h.clone();
                    jm[(r2, length_index(i))] = d_next / h.clone();
                    jm[(r2, length_index(i + 1))] = -d_prev / h.clone();
                }
            }
        }
        let ends = [
            alpha_index(0, 0),
            beta_index(0, 0),
            alpha_index(n - 1, 2),
            beta_index(n - 1, 2),
        ];
        for (e, (col, target)) in ends.iter().zip(&self.ends).enumerate() {
            let row = dim - 4 + e;
            f[row] = x[*col].clone() - target;
            if let Some(jm) = jac.as_mut() {
                jm[(row, *col)] = one.clone();
            }
        }
        (f, jac)
    }
}

impl<T: Real> NonlinearSystem<T> for G2System<'_, T> {
    fn residual(&self, x: &DVector<T>) -> DVector<T> {
        self.eval(x, false).0
    }

    fn residual_and_jacobian(&self, x: &DVector<T>) -> (DVector<T>, DMatrix<T>) {
        let (f, j) = self.eval(x, true);
        (f, j.expect("requested"))
    }

    /// All lengths positive and finite.
    fn admissible(&self, x: &DVector<T>) -> bool {
        (0..self.segments()).all(|i| {
            let l = &x[length_index(i)];
            l.is_finite() && *l > T::zero()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    #[allow(unused_imports)]
    use crate::scalar::prelude::*;

    /// The analytic Jacobian against central differences of the residual
    /// in Mp<512> (step 2^-120, truncation ~2^-240): an independent check
    /// of every derivative formula.
    #[test]
    fn jacobian_matches_central_differences() {
        type M = Mp<512>;
        let p = |x: f64, y: f64, z: f64| {
            Vector3::new(
                M::from_f64_exact(x),
                M::from_f64_exact(y),
                M::from_f64_exact(z),
            )
        };
        let pts = vec![
            p(0.0, 0.0, 0.0),
            p(1.0, 0.5, 0.25),
            p(2.0, 0.0, 1.0),
            p(2.5, -1.0, 1.5),
        ];
        let ends = [0.3, 0.7, -0.4, 1.1].map(M::from_f64_exact);
        let sys = G2System::new(
            &pts,
            M::from_f64_exact(1.25),
            ends,
            GaussLegendre::new(12).unwrap(),
        );
        let x = DVector::from_fn(21, |k, _| {
            M::from_f64_exact(0.1 + 0.37 * ((k * 7 % 11) as f64) / 11.0)
        });
        let (_, jac) = sys.residual_and_jacobian(&x);
        let h = M::from_int(1).scale_by_pow2(-120);
        for c in 0..21 {
            let mut xp = x.clone();
            let mut xm = x.clone();
            xp[c] += h.clone();
            xm[c] -= h.clone();
            let col = (sys.residual(&xp) - sys.residual(&xm)) / (h.clone() + &h);
            let err = (col - jac.column(c)).norm();
            assert!(err < M::from_int(1).scale_by_pow2(-200), "column {c}");
        }
    }
}
