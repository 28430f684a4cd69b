//! Solving Bernstein–Vandermonde systems `A c = r`, `A_{ji} = B_i^n(t_j)`,
//! and their tensor (Kronecker) form `B̃ = B_u ⊗ B_v` of seed 001 eq 2–3.
//!
//! Three solvers for the tensor system `B̃ x = r` ([`TensorSolver`]):
//!
//! * [`TensorSolver::FullLu`]: nalgebra LU with partial pivoting on the
//!   assembled `(m+1)(n+1)` square matrix; `O(n⁶)` for `m = n`.
//! * [`TensorSolver::KroneckerLu`]: the Kronecker identity
//!   `(B_u ⊗ B_v) vec(X) = vec(B_u X B_vᵀ)`, so `X = B_u⁻¹ R B_v⁻ᵀ`: one LU per
//!   direction and `n + 1` univariate solves per direction; `O(n³)`.
//! * [`TensorSolver::KroneckerMarcoMartinez`]: the same with each univariate
//!   solve done by [`BvBidiagonal`] (Marco–Martínez), `O(n²)` per solve.
//!
//! # The Marco–Martínez factorisation
//!
//! A. Marco, J.-J. Martínez, *A fast and accurate algorithm for solving
//! Bernstein–Vandermonde linear systems*, Linear Algebra Appl. 422 (2007)
//! 616–628. For `0 ≤ t_0 < … < t_n ≤ 1` the matrix `A` is totally positive
//! and has the Neville-elimination factorisation
//! `A = E_0⁻¹ ⋯ E_{n−1}⁻¹ · D · (Ẽ_0ᵀ ⋯ Ẽ_{n−1}ᵀ)⁻¹`, where `E_j` is unit lower
//! bidiagonal with `−m_{ij}` at `(i, i−1)` for `i > j`, `Ẽ_j` the same with the
//! multipliers `m̃_{ij}` of the Neville elimination of `Aᵀ`, and `D` holds the
//! pivots `p_ii`. The derivation used here (written out so it can be checked;
//! the tests compare every entry with an exact rational Neville elimination):
//!
//! `A = diag((1−t_j)ⁿ) · V(x) · diag(C(n,i))` with `x_j = t_j/(1−t_j)` and
//! `V(x)` the monomial Vandermonde matrix, so a minor of `A` on consecutive
//! rows `r..r+k` and the first `k+1` columns is
//! `Δ(r,k) = Π_a (1−t_a)^{n−k} · Π_{l≤k} C(n,l) · Π_{a<b} (t_b − t_a)`
//! (use `x_b − x_a = (t_b − t_a)/((1−t_a)(1−t_b))`). Gasca–Peña's
//! `m_{ij} = Δ(i−j,j) Δ(i−j−1,j−1) / (Δ(i−j−1,j) Δ(i−j,j−1))` and
//! `p_ii = Δ(0,i)/Δ(0,i−1)` then reduce to, for `0 ≤ j < i ≤ n`,
//!
//! ```text
//! m_ij = q_i^{n−j} · (1−t_{i−j−1})/(1−t_{i−1}) · Π_{a=i−j}^{i−1} (t_i − t_a) / Π_{a=i−j−1}^{i−2} (t_{i−1} − t_a),
//!        q_i = (1−t_i)/(1−t_{i−1}),
//! m̃_ij = (n−i+1)/i · t_j/(1−t_j),
//! p_ii = C(n,i) (1−t_i)^{n−i} Π_{a<i} (t_i − t_a)/(1−t_a).
//! ```
//!
//! The only subtractions are `t_i − t_a` and `1 − t_a` of the *input* nodes,
//! so every entry is computed to a relative error of a few `n u`; the
//! `m_ij` follow in `O(n²)` total from the ratio
//! `ρ_{i,j+1}/ρ_{ij} = (1−t_{i−j−2})(t_i − t_{i−j−1}) / ((1−t_{i−j−1})(t_{i−1} − t_{i−j−2}))`.
//!
//! **Endpoints.** Equispaced and Chebyshev–Lobatto nodes include `t_0 = 0`
//! and `t_n = 1`, where `x_n = ∞` and the paper's `0 < t_0`, `t_n < 1` fail.
//! The formulas above never divide by `1 − t_n` (only `1 − t_a` with
//! `a ≤ n−1` appears in a denominator, and `m̃_ij` uses `x_j` with `j < n`),
//! and with Neville's convention "multiplier 0 when the entry to eliminate is
//! already 0" they remain exact: `t_n = 1` gives `q_n = 0`, hence `m_nj = 0`
//! (row `n` of `A` is `e_nᵀ`, nothing to eliminate) and `p_nn = 1`; `t_0 = 0`
//! gives `x_0 = 0`, hence `m̃_i0 = 0` (column 0 of `Aᵀ` is `e_0`). This is the
//! limit `t_0 → 0⁺`, `t_n → 1⁻` of the interior case (every entry is
//! continuous there). Reducing the system by the known rows `c_0 = r_0`,
//! `c_n = r_n` instead would subtract `r_0 B_0(t_j)` from like-signed data and
//! destroy the accuracy for sign-alternating right-hand sides; the direct
//! treatment keeps it.
//!
//! **Accuracy** (the reason for the method): `A⁻¹` has the checkerboard sign
//! pattern, all multipliers and pivots are positive, so for a
//! sign-alternating right-hand side (`(−1)ʲ r_j ≥ 0`) every update
//! `r_i − m r_{i−1}` adds two like-signed magnitudes: no cancellation, and each
//! component of the solution has a relative error `O(n²u)` whatever
//! `cond(A)`. For general data the error is bounded by `O(n²u)·‖|A⁻¹||r|‖`
//! componentwise, usually far below `cond(A)·u`.

use super::vandermonde::bernstein_vandermonde;
use crate::scalar::Real;
use crate::validation::{InputError, at_least, finite_at, finite_entries};
use nalgebra::DMatrix;
use nalgebra::linalg::LU;
use rug::Rational;

/// Why a Bernstein–Vandermonde system could not be set up or solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BvError {
    /// No nodes, a node that is NaN or infinite, or a right-hand side entry
    /// that is.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A node lies outside `[0, 1]` (the Bézier parameter domain).
    #[error("node {index} = {value} is outside [0, 1]")]
    NodeOutOfRange {
        /// Position in the node list.
        index: usize,
        /// The offending value (as f64, for the message).
        value: f64,
    },
    /// Two nodes coincide: the matrix is singular.
    #[error("nodes {index} and {} coincide: the matrix is singular", index + 1)]
    RepeatedNode {
        /// The first of the two equal nodes.
        index: usize,
    },
    /// The nodes are not increasing (the factorisation needs them sorted;
    /// they are never reordered silently).
    #[error("node {} is smaller than node {index}: nodes must be increasing", index + 1)]
    NodesNotIncreasing {
        /// The node after which the order breaks.
        index: usize,
    },
    /// The right-hand side has the wrong number of rows.
    #[error("right-hand side has {got} rows, the system has {expected}")]
    SizeMismatch {
        /// Rows the system needs.
        expected: usize,
        /// Rows given.
        got: usize,
    },
    /// LU met a zero pivot: singular in the working precision.
    #[error("the matrix is singular in the working precision")]
    Singular,
}

/// Checks that `nodes` is non-empty, finite, inside `[0, 1]` and strictly
/// increasing — exactly the condition under which the Bernstein–Vandermonde
/// matrix is totally positive and nonsingular.
/// **Method**: comparisons only; exact. **Source**: total positivity of the
/// Bernstein–Vandermonde matrix, Marco & Martínez (2007).
pub fn check_nodes<T: Real>(nodes: &[T]) -> Result<(), BvError> {
    at_least("a Bernstein–Vandermonde system", 1, nodes.len())?;
    for (index, t) in nodes.iter().enumerate() {
        finite_at("node", index, t)?;
        if *t < T::zero() || *t > T::one() {
            return Err(BvError::NodeOutOfRange {
                index,
                value: t.to_f64(),
            });
        }
    }
    for (index, w) in nodes.windows(2).enumerate() {
        if w[0] == w[1] {
            return Err(BvError::RepeatedNode { index });
        }
        if w[1] < w[0] {
            return Err(BvError::NodesNotIncreasing { index });
        }
    }
    Ok(())
}

fn check_rhs<T: Real>(rhs: &DMatrix<T>, expected: usize) -> Result<(), BvError> {
    if rhs.nrows() != expected {
        return Err(BvError::SizeMismatch {
            expected,
            got: rhs.nrows(),
        });
    }
    Ok(finite_entries("right-hand side", rhs)?)
}

/// The Marco–Martínez bidiagonal factorisation of the inverse of a
/// Bernstein–Vandermonde matrix (see the [module docs](self) for the
/// formulas, their derivation and the endpoint treatment).
///
/// **Cost**: `O(n²)` to build from the nodes, `n² + n + 1` multiply–adds per
/// right-hand side in [`BvBidiagonal::solve_in_place`].
/// **Accuracy**: every multiplier and pivot to relative error `O(n u)` (no
/// subtraction except of input data); solutions to componentwise relative
/// error `O(n² u)` for sign-alternating data, independent of `cond(A)`.
///
/// ```
/// use splinelab::surface_deformation::bv_solve::BvBidiagonal;
/// // p(t) = t at nodes 0, ½, 1: the Bézier coefficients of t are (0, ½, 1).
/// let bd = BvBidiagonal::new(&[0.0f64, 0.5, 1.0]).unwrap();
/// let mut r = vec![0.0, 0.5, 1.0];
/// bd.solve_in_place(&mut r);
/// assert_eq!(r, vec![0.0, 0.5, 1.0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BvBidiagonal<T> {
    /// `lower[i][j] = m_ij`, `0 ≤ j < i ≤ n` (row 0 empty).
    lower: Vec<Vec<T>>,
    /// `upper[i][j] = m̃_ij`, `0 ≤ j < i ≤ n`.
    upper: Vec<Vec<T>>,
    /// `p_ii`, `0 ≤ i ≤ n`.
    pivots: Vec<T>,
}

impl<T: Real> BvBidiagonal<T> {
    /// Builds the factorisation for the nodes `t_0 < … < t_n` in `[0, 1]`
    /// (degree `n = nodes.len() − 1`). Errors if [`check_nodes`] fails.
    /// **Method**: the closed-form bidiagonal factorisation (Neville elimination)
    /// of Marco & Martínez (2007); it equals exact Neville elimination
    /// (`bv_solve.rs::tests::closed_form_factorisation_equals_exact_neville_elimination`).
    pub fn new(nodes: &[T]) -> Result<Self, BvError> {
        check_nodes(nodes)?;
        let n = nodes.len() - 1;
        let t = nodes;
        let om: Vec<T> = t.iter().map(|x| T::one() - x.clone()).collect();
        let mut lower = vec![Vec::new()];
        for i in 1..=n {
            lower.push(lower_row(t, &om, n, i));
        }
        // x_j = t_j/(1 − t_j) for j < n (t_n may be 1 and is never needed).
        let x: Vec<T> = (0..n).map(|j| t[j].clone() / &om[j]).collect();
        let upper = (0..=n)
            .map(|i| {
                if i == 0 {
                    return Vec::new();
                }
                let ratio = T::from_rational(&Rational::from(((n - i + 1) as i64, i as i64)));
                x[..i].iter().map(|xj| ratio.clone() * xj).collect()
            })
            .collect();
        let pivots = (0..=n).map(|i| pivot(t, &om, n, i)).collect();
        Ok(BvBidiagonal {
            lower,
            upper,
            pivots,
        })
    }

    /// The degree `n` (the system has `n + 1` unknowns).
    pub fn degree(&self) -> usize {
        self.pivots.len() - 1
    }

    /// The Neville multiplier `m_ij` of `A` (`0 ≤ j < i ≤ n`).
    pub fn lower_multiplier(&self, i: usize, j: usize) -> &T {
        &self.lower[i][j]
    }

    /// The Neville multiplier `m̃_ij` of `Aᵀ` (`0 ≤ j < i ≤ n`).
    pub fn upper_multiplier(&self, i: usize, j: usize) -> &T {
        &self.upper[i][j]
    }

    /// The pivot `p_ii`.
    pub fn pivot(&self, i: usize) -> &T {
        &self.pivots[i]
    }

    /// Overwrites `r` (length `n + 1`) with `A⁻¹ r`:
    /// `c = Ẽ_0ᵀ ⋯ Ẽ_{n−1}ᵀ D⁻¹ E_{n−1} ⋯ E_0 r`, i.e. `n` lower bidiagonal
    /// passes, a diagonal scaling and `n` upper bidiagonal passes.
    ///
    /// **Cost** `n(n+1)` multiply–adds and `n + 1` divisions. The length of
    /// `r` is the caller's contract (checked by the public tensor/1D entry
    /// points); a wrong length panics on indexing.
    /// **Accuracy**: a few ulps against exact rational solutions
    /// (`verify/tests/it/bv_solvers.rs::marco_martinez_matches_exact_rational_solutions_to_a_few_ulps`).
    /// **Source**: Marco & Martínez (2007); seed 001 eqs 2–3.
    ///
    /// ```
    /// // In MPFR at nodes 0, 1/3, 2/3, 1: p(t) = t³ has Bézier coefficients (0, 0, 0, 1).
    /// use splinelab::scalar::{Mp, Real};
    /// use splinelab::surface_deformation::bv_solve::BvBidiagonal;
    /// type M = Mp<128>;
    /// let t: Vec<M> = (0..4).map(|j| M::from_int(j) / M::from_int(3)).collect();
    /// let bd = BvBidiagonal::new(&t).unwrap();
    /// let mut r: Vec<M> = t.iter().map(|x| x.clone() * x.clone() * x.clone()).collect();
    /// bd.solve_in_place(&mut r);
    /// for (c, want) in r.iter().zip([0, 0, 0, 1]) {
    ///     assert!((c.clone() - M::from_int(want)).to_f64().abs() < 1e-36);
    /// }
    /// ```
    pub fn solve_in_place(&self, r: &mut [T]) {
        let n = self.degree();
        for j in 0..n {
            // Descending i: each update uses the previous pass's r_{i−1}.
            for i in (j + 1..=n).rev() {
                let d = self.lower[i][j].clone() * &r[i - 1];
                r[i] -= &d;
            }
        }
        for (ri, p) in r.iter_mut().zip(&self.pivots) {
            *ri /= p;
        }
        for j in (0..n).rev() {
            // Ascending i: r_i is still the previous pass's value when used.
            for i in j + 1..=n {
                let d = self.upper[i][j].clone() * &r[i];
                r[i - 1] -= &d;
            }
        }
    }
}

/// `m_i0 … m_{i,i−1}` by the `O(i)` recurrence of the module docs.
fn lower_row<T: Real>(t: &[T], om: &[T], n: usize, i: usize) -> Vec<T> {
    let q = om[i].clone() / &om[i - 1];
    // q^k for k = 0..=n by repeated multiplication (relative error ≤ k u).
    let mut qpow = Vec::with_capacity(n + 1);
    qpow.push(T::one());
    for k in 1..=n {
        let next = qpow[k - 1].clone() * &q;
        qpow.push(next);
    }
    let mut rho = T::one();
    let mut row = Vec::with_capacity(i);
    for j in 0..i {
        row.push(qpow[n - j].clone() * &rho);
        if j + 1 < i {
            let num = om[i - j - 2].clone() * (t[i].clone() - &t[i - j - 1]);
            let den = om[i - j - 1].clone() * (t[i - 1].clone() - &t[i - j - 2]);
            rho *= num / den;
        }
    }
    row
}

/// `p_ii = C(n,i) (1−t_i)^{n−i} Π_{a<i} (t_i − t_a)/(1−t_a)`.
fn pivot<T: Real>(t: &[T], om: &[T], n: usize, i: usize) -> T {
    let binom = crate::bernstein::basis::binomial_real::<T>(n as u32, i as u32);
    let mut p = binom * om[i].clone().powi((n - i) as i32);
    for a in 0..i {
        p *= (t[i].clone() - &t[a]) / om[a].clone();
    }
    p
}

/// A univariate solver for `A c = r`, factorised once for many right-hand sides.
#[derive(Debug, Clone)]
pub enum Factorised<T: Real> {
    /// LU with partial pivoting of the assembled matrix.
    Lu(LU<T, nalgebra::Dyn, nalgebra::Dyn>),
    /// The Marco–Martínez bidiagonal factorisation.
    MarcoMartinez(BvBidiagonal<T>),
}

/// Which univariate method a [`Factorised`] uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method1d {
    /// Gaussian elimination with partial pivoting (nalgebra LU).
    Gepp,
    /// Marco–Martínez bidiagonal factorisation.
    MarcoMartinez,
}

impl<T: Real> Factorised<T> {
    /// Factorises the Bernstein–Vandermonde matrix at `nodes` by `method`.
    ///
    /// **Cost**: `O(n³)` for [`Method1d::Gepp`] (assembly `O(n²)` by the
    /// basis recurrence, then LU), `O(n²)` for [`Method1d::MarcoMartinez`].
    pub fn new(nodes: &[T], method: Method1d) -> Result<Self, BvError> {
        check_nodes(nodes)?;
        Ok(match method {
            Method1d::Gepp => Factorised::Lu(bernstein_vandermonde(nodes).lu()),
            Method1d::MarcoMartinez => Factorised::MarcoMartinez(BvBidiagonal::new(nodes)?),
        })
    }

    /// Overwrites `r` with `A⁻¹ r`. `Err(Singular)` if LU met a zero pivot.
    fn solve_slice(&self, r: &mut [T]) -> Result<(), BvError> {
        match self {
            Factorised::MarcoMartinez(bd) => {
                bd.solve_in_place(r);
                Ok(())
            }
            Factorised::Lu(lu) => {
                let mut b = nalgebra::DVector::from_column_slice(r);
                if !lu.solve_mut(&mut b) {
                    return Err(BvError::Singular);
                }
                r.clone_from_slice(b.as_slice());
                Ok(())
            }
        }
    }

    /// Solves `A C = R` column by column (`R` has `n + 1` rows).
    ///
    /// **Accuracy**: GEPP is backward stable (error `≈ cond(A)·u`);
    /// Marco–Martínez as documented on [`BvBidiagonal`].
    pub fn solve(&self, rhs: &DMatrix<T>) -> Result<DMatrix<T>, BvError> {
        let size = match self {
            Factorised::Lu(lu) => lu.u().nrows(),
            Factorised::MarcoMartinez(bd) => bd.degree() + 1,
        };
        check_rhs(rhs, size)?;
        let mut out = rhs.clone();
        for mut col in out.column_iter_mut() {
            let mut v: Vec<T> = col.iter().cloned().collect();
            self.solve_slice(&mut v)?;
            for (dst, src) in col.iter_mut().zip(v) {
                *dst = src;
            }
        }
        Ok(out)
    }
}

/// Solves the univariate system `A c = r`, `A_{ji} = B_i^n(t_j)`, by `method`.
///
/// ```
/// use nalgebra::DMatrix;
/// use splinelab::surface_deformation::bv_solve::{Method1d, solve_1d};
/// let r = DMatrix::from_column_slice(3, 1, &[1.0f64, -1.0, 1.0]);
/// let c = solve_1d(&[0.0, 0.5, 1.0], &r, Method1d::MarcoMartinez).unwrap();
/// // p(½) = c0/4 + c1/2 + c2/4 = −1 with c0 = c2 = 1 gives c1 = −3.
/// assert_eq!(c.as_slice(), &[1.0, -3.0, 1.0]);
/// ```
pub fn solve_1d<T: Real>(
    nodes: &[T],
    rhs: &DMatrix<T>,
    method: Method1d,
) -> Result<DMatrix<T>, BvError> {
    Factorised::new(nodes, method)?.solve(rhs)
}

/// A solver for the tensor system `(B_u ⊗ B_v) x = r` of seed 001 eq 2–3.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
#[derive(strum::VariantArray, strum::IntoStaticStr)]
#[strum(serialize_all = "kebab-case")]
pub enum TensorSolver {
    /// (a) LU with partial pivoting of the assembled `(m+1)(n+1)` matrix, `O(n⁶)`.
    FullLu,
    /// (b) Kronecker structure with univariate GEPP, `O(n³)`.
    KroneckerLu,
    /// (c) Kronecker structure with univariate Marco–Martínez, `O(n³)`.
    KroneckerMarcoMartinez,
}

crate::named_enum!(TensorSolver, "solver");

/// Solves `(B_u ⊗ B_v) X = R` for every column of `R`.
///
/// Row `a(n_v+1) + b` of `R` is the sample at `(u_a, v_b)`; row `i(n_v+1) + j`
/// of the result is the coefficient of `B_i(u) B_j(v)` (the ordering of
/// seed 001 eq 2, and of [`tensor_bernstein_vandermonde`](super::vandermonde::tensor_bernstein_vandermonde)).
/// Any number of columns (e.g. 3 for the x, y, z of control points).
///
/// **Method**: [`TensorSolver`]. The Kronecker variants use
/// `(B_u ⊗ B_v) vec(X) = vec(B_u X B_vᵀ)` (row-major `vec`): each column of
/// the sample grid is solved with `B_u`, then each row of the result with `B_v`.
/// **Cost**: `O(n⁶)` (full LU) or `O(n³)` per right-hand-side column.
/// **Accuracy**: full LU and Kronecker–LU are backward stable, errors
/// `≈ cond(B_u)·cond(B_v)·u`; Kronecker–Marco–Martínez keeps `O(n²u)`
/// componentwise for checkerboard-signed data (both passes see
/// sign-alternating vectors, because `B_u⁻¹` has the checkerboard sign pattern).
///
/// ```
/// use nalgebra::DMatrix;
/// use splinelab::surface_deformation::bv_solve::{TensorSolver, solve_tensor};
/// let t = [0.0f64, 1.0];
/// // Bilinear patch: the samples at the corners are the control points.
/// let r = DMatrix::from_column_slice(4, 1, &[1.0, 2.0, 3.0, 4.0]);
/// let x = solve_tensor(&t, &t, &r, TensorSolver::KroneckerMarcoMartinez).unwrap();
/// assert_eq!(x.as_slice(), &[1.0, 2.0, 3.0, 4.0]);
/// ```
pub fn solve_tensor<T: Real>(
    u: &[T],
    v: &[T],
    rhs: &DMatrix<T>,
    solver: TensorSolver,
) -> Result<DMatrix<T>, BvError> {
    check_nodes(u)?;
    check_nodes(v)?;
    check_rhs(rhs, u.len() * v.len())?;
    match solver {
        TensorSolver::FullLu => {
            let a = super::vandermonde::tensor_bernstein_vandermonde(u, v);
            a.lu().solve(rhs).ok_or(BvError::Singular)
        }
        TensorSolver::KroneckerLu => kronecker(u, v, rhs, Method1d::Gepp),
        TensorSolver::KroneckerMarcoMartinez => kronecker(u, v, rhs, Method1d::MarcoMartinez),
    }
}

fn kronecker<T: Real>(
    u: &[T],
    v: &[T],
    rhs: &DMatrix<T>,
    method: Method1d,
) -> Result<DMatrix<T>, BvError> {
    let (fu, fv) = (Factorised::new(u, method)?, Factorised::new(v, method)?);
    let (mu, mv) = (u.len(), v.len());
    let mut out = rhs.clone();
    for c in 0..rhs.ncols() {
        // Column b of the sample grid holds rhs[a·mv + b], a = 0..mu:
        // solve B_u along each column, then B_v along each row.
        let mut cols: Vec<Vec<T>> = (0..mv)
            .map(|b| (0..mu).map(|a| rhs[(a * mv + b, c)].clone()).collect())
            .collect();
        for col in &mut cols {
            fu.solve_slice(col)?;
        }
        for i in 0..mu {
            let mut row: Vec<T> = cols.iter().map(|col| col[i].clone()).collect();
            fv.solve_slice(&mut row)?;
            for (j, x) in row.into_iter().enumerate() {
                out[(i * mv + j, c)] = x;
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bernstein::basis::binomial;
    use crate::scalar::prelude::*;
    use crate::surface_deformation::vandermonde::NodeFamily;
    use rug::ops::Pow;

    /// `solve_in_place` as it was written before the borrowed-operand form.
    fn cloning_solve<T: Real>(f: &BvBidiagonal<T>, r: &mut [T]) {
        let n = f.degree();
        for j in 0..n {
            for i in (j + 1..=n).rev() {
                let d = f.lower[i][j].clone() * &r[i - 1];
                r[i] = r[i].clone() - d;
            }
        }
        for (ri, p) in r.iter_mut().zip(&f.pivots) {
            *ri = ri.clone() / p;
        }
        for j in (0..n).rev() {
            for i in j + 1..=n {
                let d = f.upper[i][j].clone() * &r[i];
                r[i - 1] = r[i - 1].clone() - d;
            }
        }
    }

    /// Marco–Martínez with borrowed operands equals the cloning form bit for
    /// bit, on every node family and random full-precision right-hand sides.
    fn solve_same_as_cloning_form<T: Real>() {
        let v: Vec<T> = crate::bernstein::affine_step::tests::values(64)
            .into_iter()
            .map(T::from_f64_exact)
            .collect();
        for family in NodeFamily::all() {
            for degree in [1, 5, 17] {
                let f = BvBidiagonal::new(&family.nodes::<T>(degree).unwrap()).unwrap();
                let mut a = v[..=degree].to_vec();
                let mut b = a.clone();
                f.solve_in_place(&mut a);
                cloning_solve(&f, &mut b);
                assert_eq!(a, b, "{family} degree {degree}");
            }
        }
    }

    #[test]
    fn borrowed_marco_martinez_is_bitwise_the_cloning_form() {
        solve_same_as_cloning_form::<f64>();
        solve_same_as_cloning_form::<Mp<24>>();
        solve_same_as_cloning_form::<Mp<113>>();
    }

    fn exact_bv(t: &[Rational]) -> Vec<Vec<Rational>> {
        let n = t.len() - 1;
        t.iter()
            .map(|tj| {
                (0..=n)
                    .map(|i| {
                        let om = Rational::from(1) - tj.clone();
                        Rational::from(binomial(n as u32, i as u32))
                            * tj.clone().pow(i as u32)
                            * om.pow((n - i) as u32)
                    })
                    .collect()
            })
            .collect()
    }

    /// Neville elimination in exact rationals: (multipliers m_ij, final matrix),
    /// with the convention m = 0 when the entry to eliminate is 0.
    fn neville(mut a: Vec<Vec<Rational>>) -> (Vec<Vec<Rational>>, Vec<Vec<Rational>>) {
        let n = a.len() - 1;
        let mut m = vec![vec![Rational::new(); n + 1]; n + 1];
        for j in 0..n {
            for i in (j + 1..=n).rev() {
                let mult = if a[i][j] == 0 {
                    Rational::new()
                } else {
                    a[i][j].clone() / a[i - 1][j].clone()
                };
                let (top, bottom) = a.split_at_mut(i);
                for (x, y) in bottom[0].iter_mut().zip(&top[i - 1]) {
                    *x -= mult.clone() * y;
                }
                m[i][j] = mult;
            }
        }
        (m, a)
    }

    fn close(got: &Mp<300>, want: &Rational) -> bool {
        let w = Mp::<300>::from_rational(want);
        let err = (got.clone() - &w).abs();
        err <= w.abs() * Mp::<300>::from_f64_exact(1e-80)
            || (want == &0 && err == Mp::<300>::from_int(0))
    }

    #[test]
    fn closed_form_factorisation_equals_exact_neville_elimination() {
        // Interior nodes, nodes with both endpoints, and an irregular set.
        let sets: Vec<Vec<Rational>> = vec![
            (0..=6).map(|j| Rational::from((2 * j + 1, 14))).collect(),
            NodeFamily::Equispaced.exact_nodes(7).unwrap(),
            vec![
                Rational::from((1, 9)),
                Rational::from((1, 3)),
                Rational::from((2, 5)),
                Rational::from(1),
            ],
            vec![
                Rational::from(0),
                Rational::from((1, 100)),
                Rational::from((99, 100)),
            ],
        ];
        for t in sets {
            let n = t.len() - 1;
            let a = exact_bv(&t);
            let (m, u) = neville(a.clone());
            let at: Vec<Vec<Rational>> = (0..=n)
                .map(|i| (0..=n).map(|j| a[j][i].clone()).collect())
                .collect();
            let (mt, _) = neville(at);
            let tm: Vec<Mp<300>> = t.iter().map(Mp::from_rational).collect();
            let bd = BvBidiagonal::new(&tm).unwrap();
            for i in 0..=n {
                assert!(close(bd.pivot(i), &u[i][i]), "pivot {i} of {t:?}");
                for j in 0..i {
                    assert!(
                        close(bd.lower_multiplier(i, j), &m[i][j]),
                        "m[{i}][{j}] of {t:?}"
                    );
                    assert!(
                        close(bd.upper_multiplier(i, j), &mt[i][j]),
                        "m~[{i}][{j}] of {t:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn bad_nodes_are_typed_errors() {
        let e = check_nodes::<f64>(&[]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "a Bernstein–Vandermonde system needs at least 1 point, got 0"
        );
        let at = InputError::NonFiniteAt {
            what: "node",
            index: 1,
        };
        assert_eq!(check_nodes(&[0.0, f64::NAN]), Err(BvError::Input(at)));
        // Checked in order: an earlier out-of-range node is reported first.
        assert!(matches!(
            check_nodes(&[1.5, f64::NAN]),
            Err(BvError::NodeOutOfRange { index: 0, .. })
        ));
        assert_eq!(
            check_nodes(&[0.0, 1.5]),
            Err(BvError::NodeOutOfRange {
                index: 1,
                value: 1.5
            })
        );
        assert_eq!(
            check_nodes(&[0.0, 0.5, 0.5]),
            Err(BvError::RepeatedNode { index: 1 })
        );
        assert_eq!(
            check_nodes(&[0.0, 0.6, 0.5]),
            Err(BvError::NodesNotIncreasing { index: 1 })
        );
        let r = DMatrix::from_element(2, 1, 1.0);
        assert_eq!(
            solve_1d(&[0.0, 0.5, 1.0], &r, Method1d::Gepp).unwrap_err(),
            BvError::SizeMismatch {
                expected: 3,
                got: 2
            }
        );
        let r = DMatrix::from_column_slice(2, 1, &[1.0, f64::INFINITY]);
        let e = solve_1d(&[0.0, 1.0], &r, Method1d::MarcoMartinez).unwrap_err();
        assert_eq!(e.to_string(), "right-hand side entry (1, 0) is not finite");
    }
}
