//! Bernstein–Vandermonde matrices and the node families they are sampled at.
//!
//! Seed 001 (Maeno–Okada–Toriwaki) eq 2–3: sampling a degree-`n` Bézier
//! patch at `(n+1)²` parameter pairs gives the square system `R̃ = B̃ P̃`; for
//! samples on a grid `u_a × v_b` the matrix `B̃` is the Kronecker product
//! `B_u ⊗ B_v` of two univariate Bernstein–Vandermonde matrices.

use crate::bernstein::basis::bernstein_basis;
use crate::scalar::Real;
use crate::validation::{InputError, degree_at_least};
use nalgebra::DMatrix;
use rug::Rational;

/// Errors from building Vandermonde-type matrices.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VandermondeError {
    /// The degree is below 1.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A node family name that is not one of the known families.
    #[error(
        "unknown node family '{0}' (expected equispaced, chebyshev-lobatto or chebyshev-gauss)"
    )]
    UnknownNodes(String),
    /// More nodes than can be stored.
    #[error("degree {0} needs more nodes than can be stored")]
    DegreeTooLarge(usize),
}

/// Where on `[0, 1]` the `n + 1` interpolation nodes `t_0 < … < t_n` sit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
#[derive(strum::VariantArray, strum::IntoStaticStr)]
#[strum(serialize_all = "kebab-case")]
pub enum NodeFamily {
    /// `t_j = j/n`.
    Equispaced,
    /// Chebyshev extreme points mapped to `[0, 1]`: `t_j = (1 − cos(πj/n))/2`.
    ChebyshevLobatto,
    /// Chebyshev zeros mapped to `[0, 1]`: `t_j = (1 − cos(π(2j+1)/(2n+2)))/2`.
    ChebyshevGauss,
}

impl NodeFamily {
    /// The `n + 1` nodes in the working precision, increasing.
    ///
    /// The Chebyshev families use the identity `(1 − cos 2θ)/2 = sin² θ`:
    /// the left-hand side cancels catastrophically near `t = 0`, the
    /// right-hand side keeps every node to a few units of roundoff relative.
    /// Equispaced nodes are correctly rounded from the exact `j/n`.
    /// Test: `vandermonde.rs::tests::chebyshev_nodes_match_the_cosine_definition_in_high_precision`.
    /// **Source**: the Chebyshev nodes of the conditioning studies; the
    /// identity as in Higham, 2nd ed., §1.7 (avoiding subtractive cancellation).
    pub fn nodes<T: Real>(self, n: usize) -> Result<Vec<T>, VandermondeError> {
        degree_at_least("a node family", 1, n)?;
        let mut nodes = Vec::new();
        if n.checked_add(1)
            .is_none_or(|k| nodes.try_reserve_exact(k).is_err())
        {
            return Err(VandermondeError::DegreeTooLarge(n));
        }
        let sin_sq = |num: usize, den: usize| {
            let theta = T::pi() * T::from_int(num as i64) / T::from_int(den as i64);
            let s = theta.sin();
            s.clone() * s
        };
        nodes.extend((0..=n).map(|j| match self {
            NodeFamily::Equispaced => T::from_rational(&Rational::from((j as i64, n as i64))),
            NodeFamily::ChebyshevLobatto => sin_sq(j, 2 * n),
            NodeFamily::ChebyshevGauss => sin_sq(2 * j + 1, 4 * n + 4),
        }));
        Ok(nodes)
    }

    /// The nodes as exact rationals, where they are rational (equispaced
    /// only); `None` for the Chebyshev families.
    pub fn exact_nodes(self, n: usize) -> Option<Vec<Rational>> {
        (self == NodeFamily::Equispaced && n > 0).then(|| {
            (0..=n)
                .map(|j| Rational::from((j as i64, n as i64)))
                .collect()
        })
    }
}

crate::named_enum!(NodeFamily, "node family", VandermondeError, |s: &str| {
    VandermondeError::UnknownNodes(s.to_string())
});

/// The Bernstein–Vandermonde matrix `A_{ji} = B_i^n(t_j)` (row `j` = node,
/// column `i` = basis function), `(n+1) × (n+1)` for `n + 1` nodes.
///
/// Seed 001 eq 2 in one variable. **Cost**: `O(n²)` per row by
/// [`bernstein_basis`]; **accuracy**: every entry within `γ_{2n}` relative for
/// nodes in `[0, 1]`.
///
/// ```
/// use splinelab::surface_deformation::vandermonde::bernstein_vandermonde;
/// let a = bernstein_vandermonde(&[0.0f64, 0.5, 1.0]);
/// assert_eq!(a[(1, 1)], 0.5);
/// ```
///
/// ```
/// use splinelab::surface_deformation::vandermonde::bernstein_vandermonde;
/// // In MPFR, nodes 0, 1/3, 1: row 1 is (B_0^2, B_1^2, B_2^2)(1/3) = (4/9, 4/9, 1/9).
/// use splinelab::scalar::{Mp, Real};
/// type M = Mp<128>;
/// let a = bernstein_vandermonde(&[M::from_int(0), M::from_int(1) / M::from_int(3), M::from_int(1)]);
/// for (i, num) in [4, 4, 1].into_iter().enumerate() {
///     assert!((a[(1, i)].clone() - M::from_int(num) / M::from_int(9)).to_f64().abs() < 1e-37);
/// }
/// ```
pub fn bernstein_vandermonde<T: Real>(nodes: &[T]) -> DMatrix<T> {
    let n = nodes.len().saturating_sub(1);
    let rows: Vec<Vec<T>> = nodes.iter().map(|t| bernstein_basis(n, t)).collect();
    DMatrix::from_fn(nodes.len(), n + 1, |j, i| rows[j][i].clone())
}

/// The monomial Vandermonde matrix `V_{ji} = t_jᶦ`, for comparison with the
/// Bernstein basis at the same nodes. **Cost** `O(n²)`; entries by repeated
/// multiplication, relative error `≤ γ_i`.
pub fn monomial_vandermonde<T: Real>(nodes: &[T]) -> DMatrix<T> {
    let n = nodes.len();
    let mut v = DMatrix::from_element(n, n, T::one());
    for j in 0..n {
        for i in 1..n {
            v[(j, i)] = v[(j, i - 1)].clone() * &nodes[j];
        }
    }
    v
}

/// The tensor Bernstein–Vandermonde matrix `B̃ = B_u ⊗ B_v` of seed 001 eq 2
/// for samples on the grid `u_a × v_b`: row `a(n+1) + b` holds
/// `B_i(u_a) B_j(v_b)` in column `i(n+1) + j` (the paper's ordering
/// `P_00 … P_0n P_10 … P_nn`).
///
/// **Cost**: `O(n⁴)` entries. Because it is a Kronecker product its singular
/// values are the products `σ_i(B_u) σ_j(B_v)`, so
/// `cond₂(B̃) = cond₂(B_u) · cond₂(B_v)` (and the same for `cond_∞`).
pub fn tensor_bernstein_vandermonde<T: Real>(u: &[T], v: &[T]) -> DMatrix<T> {
    bernstein_vandermonde(u).kronecker(&bernstein_vandermonde(v))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bernstein::basis::bernstein;
    use crate::scalar::prelude::*;

    #[test]
    fn kronecker_equals_row_by_row_definition_of_eq_2() {
        // Exact rationals: both constructions must agree to the bit.
        let n = 4usize;
        let u: Vec<f64> = NodeFamily::Equispaced.nodes(n).unwrap();
        let v: Vec<f64> = NodeFamily::ChebyshevGauss.nodes(n).unwrap();
        let tensor = tensor_bernstein_vandermonde(&u, &v);
        for (a, ua) in u.iter().enumerate() {
            for (b, vb) in v.iter().enumerate() {
                for i in 0..=n {
                    for j in 0..=n {
                        let row = a * (n + 1) + b;
                        let col = i * (n + 1) + j;
                        let direct =
                            bernstein(n as u32, i as u32, ua) * bernstein(n as u32, j as u32, vb);
                        let got = tensor[(row, col)];
                        assert!((got - direct).abs() <= 1e-14 * direct.abs().max(1e-300));
                    }
                }
            }
        }
    }

    #[test]
    fn node_names_round_trip_and_unknown_is_an_error() {
        for f in NodeFamily::all() {
            assert_eq!(f.name().parse::<NodeFamily>().unwrap(), f);
        }
        assert!(matches!(
            "chebyshev".parse::<NodeFamily>(),
            Err(VandermondeError::UnknownNodes(_))
        ));
        assert!(NodeFamily::Equispaced.nodes::<f64>(0).is_err());
    }

    #[test]
    fn chebyshev_nodes_match_the_cosine_definition_in_high_precision() {
        use crate::scalar::Mp;
        type M = Mp<300>;
        let n = 12;
        let got: Vec<f64> = NodeFamily::ChebyshevLobatto.nodes(n).unwrap();
        for (j, t) in got.iter().enumerate() {
            let theta = M::pi() * M::from_int(j as i64) / M::from_int(n as i64);
            let want = ((M::one() - theta.cos()) / M::from_int(2)).to_f64();
            // sin² form: within 4 ulps of the correctly rounded value.
            assert!(
                (t - want).abs() <= 4.0 * f64::EPSILON * want,
                "j={j}: {t} vs {want}"
            );
        }
    }
}
