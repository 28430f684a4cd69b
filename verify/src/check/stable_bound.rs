//! The error a backward-stable computation would make: the per-element
//! bound behind `check`'s default verdict.
//!
//! A user's result is judged against what the *problem* allows, not against
//! a fixed number of ulps: an element passes when its error is at most
//! [`BOUND_FACTOR`] times the bound below, computed from the user's exact
//! inputs. Everything here is a magnitude (sums of non-negative terms), so it
//! is computed in `f64`: each bound is accurate to a relative `O(n·u)`,
//! far inside the factor [`BOUND_FACTOR`] (it is a yardstick, not a
//! reference value).
//!
//! # Prefilter (the banded system `B c = s`)
//!
//! A backward-stable solve returns `ĉ` with `(B + ΔB) ĉ = s`,
//! `|ΔB| ≤ ε |B|`, hence (Higham, *Accuracy and Stability of Numerical
//! Algorithms*, 2nd ed., §7.2, componentwise perturbation theory: the Skeel
//! condition) `|ĉ − c| ≤ ε |B⁻¹| |B| |c|` to first order. The constant:
//! Gaussian elimination without pivoting of a matrix with half-bandwidth `q`
//! forms inner products of at most `w = q + 1` terms, so Higham's
//! Theorem 9.4 (`|ΔA| ≤ γ_{3n} |L̂||Û|`) holds with `n` replaced by `w`:
//! `|ΔB| ≤ γ_{3w} |L̂||Û|`. The folded interpolation matrix of a B-spline is
//! totally nonnegative (a collocation matrix; Karlin 1968, de Boor–Pinkus
//! 1977), so its factors are nonnegative, `|L̂||Û| = |L̂Û| ≤ |B|/(1 − γ_w)`
//! (de Boor–Pinkus; Higham §9.3 for totally nonnegative matrices). The entries `β(j)` are
//! rational and enter rounded, one more `u|B|`; so
//!
//! `bound_k = γ_{3w+1}/(1 − γ_w) · (|B⁻¹| |B| |c|)_k + u |c_k|`,
//!
//! the last term being the rounding of the exact answer to the user's
//! format. The factors' nonnegativity is checked by the unit test
//! `interpolation_matrices_have_nonnegative_lu_factors` (degrees 1–15, the
//! three filter rules). For `grid-wrap` (a circulant) the same constant is
//! used as the backward error of a stable periodic solve.
//!
//! `|B⁻¹|` is dense but never formed: the inverse of the infinite Toeplitz
//! matrix is `h = G · (h_1 ∗ … ∗ h_q)`, `h_r(k) = z_r^{|k|} / (1 − z_r²)`,
//! `G = Π (1 − z_r)²`, over the poles `z_r ∈ (−1, 0)`; every `h_r` has the
//! sign `(−1)^k`, so `|h| = G · (|h_1| ∗ … ∗ |h_q|)` exactly. The finite
//! matrix of a symmetric or periodic mode is the infinite one folded, so
//! `(B⁻¹)_{kj} = Σ_{m ∈ e⁻¹(j)} h(k − m)` and
//! `(|B⁻¹| y)_k ≤ (|h| ∗ ext(y))_k`, with equality for `mirror` (all images
//! of `j` have the parity of `j`). `ext(y)` is periodic (period `2n − 2`,
//! `2n` or `n`), and each `|h_r|` is applied to one period by a causal and
//! an anti-causal first-order recursion started from the exact geometric sum
//! over the period: `O(n q)` for the whole bound.
//!
//! # Interpolated values
//!
//! `f(x) = Σ_j c_j W_j(x)`, `W_j` the tensor product of `β(x_a − j_a)`. A
//! stable evaluation computes each weight by the Cox–de Boor recursion
//! (non-negative terms for the fractional part in `[0, 1)`: 5 roundings per
//! level, `d` levels, relative error `γ_{5d}`), multiplies `D` of them and
//! sums `(d + 1)^D` terms axis by axis (`γ_{D(d+1)}`); the whole is within
//! `γ_{m}`, `m = D(6d + 2)`, of `Σ_j |c_j| |W_j(x)|` (Higham §3.1, eq. 3.5,
//! for a sum of products). scipy forms the last weight of each axis as
//! `1 − Σ others`, exact to an absolute `γ` only (the weights sum to 1), so
//! `γ_m Σ_a Σ_j |c_j| |W_j^(a)(x)|` is added, `W^(a)` the product with axis
//! `a`'s weights replaced by 1 (without it a point in the tail of a
//! B-spline, a value `10⁻¹²` of the data, failed at 10× its bound on
//! scipy's own output, `interp/f2_d3_grid-constant.npy` index 39). The coefficients' own errors (the bound above,
//! per axis, carried through the later axes by `|B_a⁻¹|`) enter through the
//! weights: `Σ_j |W_j(x)| bound_j`. Where the evaluation must first
//! shift or fold the coordinate (scipy's `x + 12` of `nearest` and
//! `grid-constant`, a point outside the grid), that rounding, `u·|x′|` per
//! axis, is carried by the derivative: `u |x′_a| Σ_j |c_j| |∂_a W_j(x)|`.

use super::CheckError;
use super::format::UserFormat;
use super::interpolation_conditions::{Mode, interpolation_coefficients, scipy_filter_rule};
use splinelab::sspline::SplineFamily;
use splinelab::sspline::euler_frobenius::poles;
use splinelab::sspline::node_values::node_values_exact;

/// `K`: an element passes when its error is at most `K` times its stable
/// bound. The bounds are worst-case (every rounding error aligned), so a
/// correct implementation sits well below 1 (scipy's filters: excess ≤ 0.4
/// on the committed fixtures, `verify/tests/it/check_stable_bound.rs`); 8
/// leaves room for an algorithm with somewhat larger constants (a recursive
/// filter instead of an LU) while an error of 10× what the conditioning
/// explains is a defect.
pub const BOUND_FACTOR: f64 = 8.0;

/// The unit roundoff `u = 2^−bits` of the user's format.
pub fn unit_roundoff(format: UserFormat) -> f64 {
    (-(format.bits() as f64)).exp2()
}

/// Higham's `γ_k = k u / (1 − k u)` (infinite when `k u ≥ 1`).
pub fn gamma(k: usize, format: UserFormat) -> f64 {
    let ku = k as f64 * unit_roundoff(format);
    if ku < 1.0 {
        ku / (1.0 - ku)
    } else {
        f64::INFINITY
    }
}

/// The constant of the banded solve with half-bandwidth `q`:
/// `γ_{3w+1} / (1 − γ_w)`, `w = q + 1` (module documentation).
pub fn solve_constant(q: usize, format: UserFormat) -> f64 {
    gamma(3 * (q + 1) + 1, format) / (1.0 - gamma(q + 1, format))
}

/// The constant of a `D`-dimensional evaluation of degree `d`: `γ_{D(6d+2)}`.
pub fn eval_constant(d: usize, dims: usize, format: UserFormat) -> f64 {
    gamma(dims * (6 * d + 2), format)
}

/// `|B|` and the bound of `|B⁻¹|` of one line's interpolation matrix.
#[derive(Debug, Clone)]
pub struct LineOperators {
    /// `β(−q..=q)` in f64 (non-negative).
    beta: Vec<f64>,
    /// The pole magnitudes `|z_r|`.
    rho: Vec<f64>,
    /// `G = Π (1 + |z_r|)²`.
    gain: f64,
}

impl LineOperators {
    /// The operators of `family` (poles from core's Euler–Frobenius roots,
    /// node values exact then rounded).
    pub fn new(family: &SplineFamily) -> Result<Self, CheckError> {
        let beta: Vec<f64> = node_values_exact(family)?
            .iter()
            .map(|b| b.to_f64())
            .collect();
        let rho: Vec<f64> = poles::<f64>(family)?.iter().map(|z| z.abs()).collect();
        let gain = rho.iter().map(|p| (1.0 + p) * (1.0 + p)).product();
        Ok(LineOperators { beta, rho, gain })
    }

    /// Half-bandwidth `q`.
    pub fn q(&self) -> usize {
        self.beta.len() / 2
    }

    /// `(|B| |x|)_k = Σ_l β_l |x_{e(k + l − q)}|` for the filter rule `mode`.
    pub fn abs_band(&self, x: &[f64], mode: Mode) -> Vec<f64> {
        let (n, q) = (x.len(), self.q() as i64);
        (0..n as i64)
            .map(|k| {
                self.beta
                    .iter()
                    .enumerate()
                    .filter_map(|(l, b)| {
                        let j = mode.fold(k + l as i64 - q, n)?;
                        Some(b * x[j].abs())
                    })
                    .sum()
            })
            .collect()
    }

    /// An upper bound of `|B⁻¹| y` for `y ≥ 0` (exact for `mirror`): the
    /// kernel `|h|` applied to the mode's periodic extension of `y`.
    pub fn abs_inverse(&self, y: &[f64], mode: Mode) -> Vec<f64> {
        let n = y.len();
        let p = period(mode, n);
        let mut x: Vec<f64> = (0..p as i64)
            .map(|m| y[mode.fold(m, n).unwrap_or(0)])
            .collect();
        for &r in &self.rho {
            x = two_sided_geometric(&x, r);
        }
        x.truncate(n);
        x.iter().map(|v| v * self.gain).collect()
    }
}

/// The period of the extension of `n` samples (1 for a single sample).
fn period(mode: Mode, n: usize) -> usize {
    match mode {
        _ if n == 1 => 1,
        Mode::Mirror | Mode::GridConstant => 2 * n - 2,
        Mode::Reflect | Mode::Nearest => 2 * n,
        Mode::GridWrap => n,
    }
}

/// `Σ_m r^{|i − m|} x_m / (1 − r²)` for the periodic sequence of which `x`
/// is one period, `0 ≤ r < 1`: causal and anti-causal recursions, each
/// started from the exact geometric sum over one period.
fn two_sided_geometric(x: &[f64], r: f64) -> Vec<f64> {
    let p = x.len();
    let wrap = 1.0 / (1.0 - r.powi(p as i32));
    let mut causal = vec![0.0; p];
    let mut anti = vec![0.0; p];
    causal[0] = (0..p).rev().fold(0.0, |acc, m| acc * r + x[(p - m) % p]) * wrap;
    // acc over m = p−1..0 of r^m x_{−m}: Horner in r.
    for i in 1..p {
        causal[i] = x[i] + r * causal[i - 1];
    }
    anti[p - 1] = (0..p)
        .rev()
        .fold(0.0, |acc, m| acc * r + x[(p - 1 + m) % p])
        * wrap;
    for i in (0..p - 1).rev() {
        anti[i] = x[i] + r * anti[i + 1];
    }
    let s = 1.0 / (1.0 - r * r);
    (0..p).map(|i| (causal[i] + anti[i] - x[i]) * s).collect()
}

/// The coefficients (solved in f64, for their magnitudes) and the stable
/// bound of every coefficient of the tensor-product solve of `grid` (C
/// order, `shape`), axis by axis: after axis `a`,
/// `E ← |B_a⁻¹| E + c·|B_a⁻¹| |B_a| |X_a| + u |X_a|` along every line
/// (`X_a` the coefficients after axis `a`, `c` = [`solve_constant`]). `mode`
/// is mapped to scipy's filter rule. Cost `O(N q²)`. Held by a banded LU
/// in f64 and f32 within 1 × the bound, and at most about 10³ times its
/// error (`verify/tests/it/check_stable_bound.rs`).
///
/// ```
/// use splinelab_verify::check::prefilter::family_of_degree;
/// use splinelab_verify::check::stable_bound::solve_bound;
/// use splinelab_verify::check::{Mode, UserFormat};
/// let s = [1.0, -2.0, 0.5, 3.0, 1.0];
/// let family = family_of_degree(3)?;
/// let (c, bound) = solve_bound(&s, &[5], &family, Mode::Mirror, UserFormat::F64)?;
/// // At least the rounding of each coefficient, and a few ulps of the
/// // coefficients' scale (the cubic's ‖B⁻¹‖∞ is 3).
/// let u = f64::EPSILON / 2.0;
/// assert!(bound.iter().zip(&c).all(|(b, c)| *b >= u * c.abs() && *b < 1e-13));
/// # Ok::<(), splinelab_verify::check::CheckError>(())
/// ```
pub fn solve_bound(
    grid: &[f64],
    shape: &[usize],
    family: &SplineFamily,
    mode: Mode,
    format: UserFormat,
) -> Result<(Vec<f64>, Vec<f64>), CheckError> {
    let mode = scipy_filter_rule(mode);
    let ops = LineOperators::new(family)?;
    let c = solve_constant(ops.q(), format);
    let u = unit_roundoff(format);
    let mut x = grid.to_vec();
    let mut e = vec![0.0; grid.len()];
    for (a, &n) in shape.iter().enumerate() {
        let s: usize = shape[a + 1..].iter().product();
        let starts = (0..x.len()).filter(|k| (k / s).is_multiple_of(n));
        for start in starts {
            let idx: Vec<usize> = (0..n).map(|j| start + j * s).collect();
            let line: Vec<f64> = idx.iter().map(|&k| x[k]).collect();
            let solved = interpolation_coefficients(&line, family, mode)?;
            let carried = ops.abs_inverse(&idx.iter().map(|&k| e[k]).collect::<Vec<_>>(), mode);
            let own = ops.abs_inverse(&ops.abs_band(&solved, mode), mode);
            for (j, &k) in idx.iter().enumerate() {
                x[k] = solved[j];
                e[k] = carried[j] + c * own[j] + u * solved[j].abs();
            }
        }
    }
    Ok((x, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::interpolation_conditions::{EXACT_MODES, extend, family_of_degree};
    use nalgebra::DMatrix;

    /// The folded interpolation matrix, dense, in f64.
    fn dense(family: &SplineFamily, mode: Mode, n: usize) -> DMatrix<f64> {
        let ops = LineOperators::new(family).unwrap();
        let q = ops.q() as i64;
        let mut a = DMatrix::zeros(n, n);
        for j in 0..n {
            for (l, b) in ops.beta.iter().enumerate() {
                let k = extend(mode, j as i64 + l as i64 - q, n).unwrap();
                a[(j, k)] += b;
            }
        }
        a
    }

    #[test]
    fn abs_inverse_is_exact_for_mirror_and_an_upper_bound_otherwise() {
        // Against |inv(B)| y from a dense LU inverse, n = 1..=12 and 40.
        for d in [2, 3, 5, 7] {
            let family = family_of_degree(d).unwrap();
            let ops = LineOperators::new(&family).unwrap();
            for mode in EXACT_MODES {
                for n in (1..=12).chain([40]) {
                    let inv = dense(&family, mode, n).try_inverse().unwrap();
                    let y: Vec<f64> = (0..n).map(|i| 1.0 + ((i * 7) % 5) as f64).collect();
                    let got = ops.abs_inverse(&y, mode);
                    for k in 0..n {
                        let want: f64 = (0..n).map(|j| inv[(k, j)].abs() * y[j]).sum();
                        let rel = (got[k] - want) / want;
                        assert!(rel > -1e-12, "d{d} {mode} n{n} k{k}: {} < {want}", got[k]);
                        if mode == Mode::Mirror && n > 1 {
                            assert!(rel < 1e-12, "d{d} mirror n{n} k{k}: {} vs {want}", got[k]);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn interpolation_matrices_have_nonnegative_lu_factors() {
        // Total nonnegativity shows as L ≥ 0 and U ≥ 0 (elimination without
        // pivoting, in f64; entries below −1e-14 relative would be negative).
        for d in 1..=15 {
            let family = family_of_degree(d).unwrap();
            for mode in [Mode::Mirror, Mode::Reflect] {
                for n in [2, 3, 5, 8, 16, 33] {
                    let mut a = dense(&family, mode, n);
                    for k in 0..n {
                        for i in k + 1..n {
                            let l = a[(i, k)] / a[(k, k)];
                            for j in k..n {
                                let v = a[(k, j)];
                                a[(i, j)] -= l * v;
                            }
                            a[(i, k)] = l;
                        }
                    }
                    let min = a.iter().cloned().fold(f64::INFINITY, f64::min);
                    assert!(min > -1e-14, "d{d} {mode} n{n}: factor entry {min}");
                }
            }
        }
    }

    #[test]
    fn constants_are_highams_gammas() {
        let u = unit_roundoff(UserFormat::F64);
        assert_eq!(u, f64::EPSILON / 2.0);
        assert!((gamma(6, UserFormat::F64) / (6.0 * u) - 1.0).abs() < 1e-14);
        // Cubic: q = 1, w = 2: γ_7 / (1 − γ_2) ≈ 7u.
        let c = solve_constant(1, UserFormat::F64);
        assert!((c / (7.0 * u) - 1.0).abs() < 1e-14);
        assert_eq!(gamma(1 << 24, UserFormat::F32), f64::INFINITY);
    }
}
