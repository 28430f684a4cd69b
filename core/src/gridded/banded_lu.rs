//! LU factors of a banded matrix, solved against many right-hand sides at
//! once: the 1-D collocation systems of [`super::grid_spline`].
//!
//! **Method.** Gaussian elimination on the band (Golub & Van Loan,
//! *Matrix Computations*, 4th ed., §4.3, Alg. 4.3.5), first without row
//! exchanges — the collocation matrix of B-splines at increasing nodes is
//! totally nonnegative (Karlin 1968; de Boor, *A Practical Guide to
//! Splines*, XIII), and for such matrices elimination without pivoting is
//! backward stable with `L, U ≥ 0` (de Boor & Pinkus 1977, *Backward error
//! analysis for totally positive linear systems*) — and, where a pivot
//! vanishes or the factors grow (rounding that left the matrix only nearly
//! totally nonnegative), again with partial pivoting as LAPACK's `gbtrf`
//! (the multipliers stored as applied, `U` with `kl + ku` superdiagonals).
//!
//! **Error.** The computed factors satisfy `A + ΔA = L̂Û` with
//! `|ΔA| ≤ γ_w |L̂||Û|`, and the solve `(A + ΔA') x̂ = b` with
//! `|ΔA'| ≤ γ_{3w} |L̂||Û|`, `w = kl + ku + 1` the longest inner product
//! (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed.,
//! Thm 9.3–9.4 for band matrices). [`BandedLu::growth`] is
//! `‖|L̂||Û|‖∞` (exact without pivoting; `‖L̂‖∞‖Û‖∞` with pivoting), the
//! factor the forward error bound of [`super::grid_spline`] multiplies.
//!
//! **Cost.** Factoring `O(n·kl·(kl + ku))`; a solve of `L` lanes
//! `O(n·(2kl + ku)·L)`, row operations on contiguous lanes (vectorised).

use crate::scalar::Real;

/// A band matrix `n × n` with `kl` sub- and `ku` superdiagonals, given
/// entry by entry, factored as `A = LU` (or `PA = LU`).
#[derive(Debug, Clone)]
pub struct BandedLu<T: Real> {
    n: usize,
    kl: usize,
    ku: usize,
    /// Row `i` holds columns `i − kl ..= i + kl + ku` (the room for the
    /// fill-in of partial pivoting): `width = 2kl + ku + 1` entries.
    a: Vec<T>,
    /// Row exchanged with row `j` at step `j` (`None`: no pivoting).
    pivots: Option<Vec<usize>>,
    growth: T,
}

impl<T: Real> BandedLu<T> {
    /// Factors the band matrix whose entry `(i, j)` (`|i − j|` within the
    /// band; zero outside it) is `entry(i, j)`: without pivoting where that
    /// is stable, else with partial pivoting. `Err(j)`: the matrix is
    /// singular in working precision at pivot `j`.
    pub fn factor(
        n: usize,
        kl: usize,
        ku: usize,
        entry: impl Fn(usize, usize) -> T,
    ) -> Result<Self, usize> {
        let plain = Self::load(n, kl, ku, &entry).eliminate(false);
        // A growth above this shows rounding broke total nonnegativity
        // (where it holds, |L||U| = LU ≈ A and the growth is ≈ ‖A‖∞).
        const STABLE_GROWTH: f64 = 16.0;
        match plain {
            Ok(lu) if lu.growth.to_f64() <= STABLE_GROWTH => Ok(lu),
            _ => Self::load(n, kl, ku, &entry).eliminate(true),
        }
    }

    fn load(n: usize, kl: usize, ku: usize, entry: &impl Fn(usize, usize) -> T) -> Self {
        let width = 2 * kl + ku + 1;
        let mut a = vec![T::zero(); n * width];
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                a[i * width + j + kl - i] = entry(i, j);
            }
        }
        Self {
            n,
            kl,
            ku,
            a,
            pivots: None,
            growth: T::zero(),
        }
    }

    fn width(&self) -> usize {
        2 * self.kl + self.ku + 1
    }

    /// Entry `(i, j)`, `i − kl ≤ j ≤ i + kl + ku`.
    fn at(&self, i: usize, j: usize) -> &T {
        &self.a[i * self.width() + j + self.kl - i]
    }

    fn at_mut(&mut self, i: usize, j: usize) -> &mut T {
        let w = self.width();
        &mut self.a[i * w + j + self.kl - i]
    }

    /// The superdiagonals of `U`: `ku`, or `kl + ku` after pivoting.
    fn u_band(&self) -> usize {
        if self.pivots.is_some() {
            self.kl + self.ku
        } else {
            self.ku
        }
    }

    fn eliminate(mut self, pivoting: bool) -> Result<Self, usize> {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        let mut pivots = Vec::with_capacity(if pivoting { n } else { 0 });
        // Row sums of |L| by the row's original index (pivoting's bound).
        let mut l_rows = vec![T::one(); n];
        let mut position: Vec<usize> = (0..n).collect();
        let last_col = |j: usize| (j + kl + ku).min(n - 1);
        for j in 0..n {
            let below = (j + kl).min(n - 1);
            if pivoting {
                let p = (j..=below)
                    .max_by(|&x, &y| {
                        let (ax, ay) = (self.at(x, j).clone().abs(), self.at(y, j).clone().abs());
                        ax.partial_cmp(&ay).unwrap_or(std::cmp::Ordering::Equal)
                    })
                    .unwrap_or(j);
                if p != j {
                    for c in j..=last_col(j) {
                        let t = self.at(j, c).clone();
                        *self.at_mut(j, c) = self.at(p, c).clone();
                        *self.at_mut(p, c) = t;
                    }
                    position.swap(j, p);
                }
                pivots.push(p);
            }
            let pivot = self.at(j, j).clone();
            if pivot.is_zero() || !pivot.clone().is_finite() {
                return Err(j);
            }
            for i in j + 1..=below {
                let l = self.at(i, j).clone() / &pivot;
                if l.is_zero() {
                    continue;
                }
                l_rows[position[i]] += l.clone().abs();
                for c in j + 1..=last_col(j) {
                    let u = self.at(j, c).clone() * &l;
                    *self.at_mut(i, c) -= &u;
                }
                *self.at_mut(i, j) = l;
            }
        }
        self.pivots = pivoting.then_some(pivots);
        self.growth = if pivoting {
            let l_norm = l_rows.into_iter().fold(T::zero(), |m, r| m.max(r));
            l_norm
                * self
                    .u_row_sums()
                    .into_iter()
                    .fold(T::zero(), |m, r| m.max(r))
        } else {
            self.abs_lu_norm()
        };
        if !self.growth.clone().is_finite() {
            return Err(n - 1);
        }
        Ok(self)
    }

    /// `|Û| 1`, row by row.
    fn u_row_sums(&self) -> Vec<T> {
        (0..self.n)
            .map(|i| {
                (i..=(i + self.u_band()).min(self.n - 1))
                    .fold(T::zero(), |s, c| s + self.at(i, c).clone().abs())
            })
            .collect()
    }

    /// `‖|L̂||Û|‖∞ = max_i (|L̂| (|Û| 1))_i` (no pivoting: `L̂` row `i` holds
    /// columns `i − kl .. i`).
    fn abs_lu_norm(&self) -> T {
        let u = self.u_row_sums();
        (0..self.n)
            .map(|i| {
                (i.saturating_sub(self.kl)..i)
                    .fold(u[i].clone(), |s, j| s + self.at(i, j).clone().abs() * &u[j])
            })
            .fold(T::zero(), |m, r| m.max(r))
    }

    /// The order `n`.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Whether the matrix is empty (never, for a factored one).
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Whether the factorization exchanged rows.
    pub fn pivoted(&self) -> bool {
        self.pivots.is_some()
    }

    /// `‖|L̂||Û|‖∞` (no pivoting) or the bound `‖L̂‖∞‖Û‖∞` (pivoting): the
    /// backward error of a solve is at most `γ_{3w}` times this, row-wise.
    pub fn growth(&self) -> T {
        self.growth.clone()
    }

    /// The longest inner product `w = kl + ku + 1` (with pivoting's
    /// fill-in, `2kl + ku + 1`): the `γ_{3w}` of the backward error.
    pub fn inner_length(&self) -> usize {
        self.kl + self.u_band() + 1
    }

    /// Solves `A X = B` in place for `lanes` right-hand sides: `x` is
    /// `n × lanes`, row-major (row `i` holds the `i`-th entry of every
    /// right-hand side, so each step is one operation on a contiguous row).
    pub fn solve_lanes(&self, x: &mut [T], lanes: usize) {
        let n = self.n;
        debug_assert_eq!(x.len(), n * lanes);
        for j in 0..n {
            if let Some(p) = self.pivots.as_ref().map(|p| p[j]).filter(|&p| p != j) {
                let (top, rest) = x.split_at_mut(p * lanes);
                top[j * lanes..(j + 1) * lanes].swap_with_slice(&mut rest[..lanes]);
            }
            let (top, rest) = x.split_at_mut((j + 1) * lanes);
            let row_j = &top[j * lanes..];
            for i in j + 1..=(j + self.kl).min(n - 1) {
                let l = self.at(i, j);
                if l.is_zero() {
                    continue;
                }
                let row_i = &mut rest[(i - j - 1) * lanes..(i - j) * lanes];
                axpy_neg(row_i, l, row_j);
            }
        }
        for j in (0..n).rev() {
            let (top, rest) = x.split_at_mut(j * lanes);
            let row_j = &mut rest[..lanes];
            let pivot = self.at(j, j);
            for v in row_j.iter_mut() {
                *v /= pivot;
            }
            for i in j.saturating_sub(self.u_band())..j {
                let u = self.at(i, j);
                if u.is_zero() {
                    continue;
                }
                axpy_neg(&mut top[i * lanes..(i + 1) * lanes], u, row_j);
            }
        }
    }

    /// Solves `Aᵀ x = b` in place (one right-hand side; the norm estimate's).
    pub fn solve_transpose(&self, x: &mut [T]) {
        let n = self.n;
        // Uᵀ y = b: forward, column j of U is row j of Uᵀ.
        for j in 0..n {
            let lo = j.saturating_sub(self.u_band());
            let s = (lo..j).fold(x[j].clone(), |s, i| s - self.at(i, j).clone() * &x[i]);
            x[j] = s / self.at(j, j);
        }
        // Lᵀ then the exchanges, last step first (LAPACK gbtrs, 'T').
        for j in (0..n).rev() {
            let hi = (j + self.kl).min(n - 1);
            x[j] = (j + 1..=hi).fold(x[j].clone(), |s, i| s - self.at(i, j).clone() * &x[i]);
            if let Some(p) = self.pivots.as_ref().map(|p| p[j]).filter(|&p| p != j) {
                x.swap(j, p);
            }
        }
    }
}

/// `y -= a · x`, element by element.
#[inline]
fn axpy_neg<T: Real>(y: &mut [T], a: &T, x: &[T]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi -= a.clone() * xi;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;

    /// A diagonally weak band matrix that needs pivoting, and a totally
    /// nonnegative one that does not: both solved against the dense
    /// solution in 256-bit MPFR.
    fn check(entry: impl Fn(usize, usize) -> f64, n: usize, kl: usize, ku: usize, pivot: bool) {
        let lu = BandedLu::<f64>::factor(n, kl, ku, &entry).unwrap();
        assert_eq!(lu.pivoted(), pivot);
        let lanes = 3;
        let b: Vec<f64> = (0..n * lanes)
            .map(|i| ((i * 7919) % 13) as f64 - 6.0)
            .collect();
        let mut x = b.clone();
        lu.solve_lanes(&mut x, lanes);
        type M = Mp<256>;
        let lum = BandedLu::<M>::factor(n, kl, ku, |i, j| M::from_f64_exact(entry(i, j))).unwrap();
        let mut xm: Vec<M> = b.iter().map(|&v| M::from_f64_exact(v)).collect();
        lum.solve_lanes(&mut xm, lanes);
        // Residual of the MPFR solution in MPFR, against the dense product.
        for l in 0..lanes {
            for i in 0..n {
                let mut r = M::from_f64_exact(b[i * lanes + l]);
                for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                    r -= M::from_f64_exact(entry(i, j)) * &xm[j * lanes + l];
                }
                assert!(r.to_f64().abs() < 1e-60, "MPFR residual {}", r.to_f64());
                let err = (x[i * lanes + l] - xm[i * lanes + l].to_f64()).abs();
                assert!(
                    err < 1e-12 * (1.0 + xm[i * lanes + l].to_f64().abs()),
                    "{err}"
                );
            }
        }
        // The transpose solve against the MPFR one.
        let mut y: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut ym: Vec<M> = y.iter().map(|&v| M::from_f64_exact(v)).collect();
        lu.solve_transpose(&mut y);
        lum.solve_transpose(&mut ym);
        for (a, b) in y.iter().zip(&ym) {
            assert!((a - b.to_f64()).abs() < 1e-12 * (1.0 + b.to_f64().abs()));
        }
    }

    #[test]
    fn needs_pivoting_when_the_diagonal_vanishes() {
        // Zero diagonal: elimination without exchanges breaks down at once.
        let e = |i: usize, j: usize| {
            if i == j {
                0.0
            } else {
                1.0 + ((i + 2 * j) % 5) as f64
            }
        };
        check(e, 40, 2, 1, true);
    }

    #[test]
    fn totally_nonnegative_needs_no_pivoting() {
        // Cubic B-spline collocation at the knots: (1, 4, 1)/6, TN.
        let e = |i: usize, j: usize| if i == j { 4.0 / 6.0 } else { 1.0 / 6.0 };
        check(e, 50, 1, 1, false);
    }

    #[test]
    fn singular_is_an_error() {
        assert_eq!(BandedLu::<f64>::factor(2, 1, 1, |_, _| 1.0).err(), Some(1));
    }
}
