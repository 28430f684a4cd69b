//! End conditions of S-spline curves (seed 000 eq 21–23): how the data
//! `P_0..P_{ν−1}` are extended to every index the truncated basis reaches.
//!
//! Each rule maps an index `i ∈ ℤ` to `P_i = P_r + a·T_0 + b·T_1` with a data
//! index `r` and integers `a, b` ([`EndRule::fold`]):
//!
//! - **free** (eq 21): `P_i = P_0` for `i < 0`, `P_i = P_{ν−1}` for `i ≥ ν`;
//! - **periodic** (eq 22): `P_i = P_{i mod ν}`;
//! - **end tangents** (replacing the garbled eq 23): with `j = ν − 1`,
//!   `P_{−i} = P_i − 2i·T_0` and `P_{j+i} = P_{j−i} + 2i·T_1` for all `i`.
//!
//! **Derivation of the tangent rule.** Write `P_i = P_0 + i·T_0 + R_i`. The
//! rule says exactly that `R_{−i} = R_i` (R is even about 0). The cardinal
//! spline reproduces linear data (`Σ_i (a + ib) S(u − i) = a + bu`) and `S`
//! is even, so `Σ_i R_i S(u − i)` is even in `u` and its derivative at 0
//! vanishes: `Q'(0) = T_0` exactly for the untruncated spline. The same
//! argument at `j` gives `Q'(j) = T_1`. The two reflections generate the
//! infinite dihedral group; both are involutions and each fixes its centre,
//! so the extension to all of `ℤ` is well defined (it grows quadratically
//! when `T_0 ≠ T_1`, which the geometric decay of `c_i` absorbs).
//!
//! For the truncated basis `S_n` (still even) the linear part gives
//! `Σ_i (a + ib) S_n(u − i) = C_n (a + bu)`, `C_n = Σ_{|i|≤n} c_i`, hence
//! `Q'(0) = C_n T_0` exactly, and `|C_n − 1| ≤` the tail bound of the width.

use crate::scalar::Real;
use nalgebra::SVector;

/// The end condition of an S-spline curve (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub enum EndCondition<T: Real, const D: usize> {
    /// Repeat the end points (eq 21).
    Free,
    /// Closed curve: indices modulo `ν` (eq 22).
    Periodic,
    /// Prescribed end tangents `Q'(0) = T_0`, `Q'(ν−1) = T_1` (derived rule).
    Tangents {
        /// `T_0`, the derivative at `u = 0`.
        start: SVector<T, D>,
        /// `T_1`, the derivative at `u = ν − 1`.
        end: SVector<T, D>,
    },
}

/// The index part of an end condition (what [`EndRule::fold`] needs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EndRule {
    /// See [`EndCondition::Free`].
    Free,
    /// See [`EndCondition::Periodic`].
    Periodic,
    /// See [`EndCondition::Tangents`].
    Reflect,
}

impl<T: Real, const D: usize> EndCondition<T, D> {
    /// The index rule of this condition.
    pub fn rule(&self) -> EndRule {
        match self {
            EndCondition::Free => EndRule::Free,
            EndCondition::Periodic => EndRule::Periodic,
            EndCondition::Tangents { .. } => EndRule::Reflect,
        }
    }

    /// `P_i` for any `i ∈ ℤ` under this condition (`data` non-empty).
    /// Cost `O(1 + |i|/ν)`; interior indices return the data point unchanged.
    pub fn extended(&self, data: &[SVector<T, D>], i: i64) -> SVector<T, D> {
        let (r, a, b) = self.rule().fold(i, data.len());
        match self {
            EndCondition::Tangents { start, end } if a != 0 || b != 0 => {
                &data[r] + start * T::from_int(a) + end * T::from_int(b)
            }
            _ => data[r].clone(),
        }
    }
}

impl EndRule {
    /// Maps `i` to `(r, a, b)` with `P_i = P_r + a T_0 + b T_1` for `len = ν ≥ 1`
    /// data points (`a = b = 0` except for [`EndRule::Reflect`]).
    pub fn fold(self, i: i64, len: usize) -> (usize, i64, i64) {
        let n = len as i64;
        match self {
            EndRule::Free => (i.clamp(0, n - 1) as usize, 0, 0),
            EndRule::Periodic => (i.rem_euclid(n) as usize, 0, 0),
            EndRule::Reflect if n == 1 => (0, 2 * i.min(0), 2 * i.max(0)),
            EndRule::Reflect => reflect(i, n - 1),
        }
    }

    /// Every `i ∈ [lo, hi]` with `fold(i).0 == k`, ascending. Cost
    /// `O(1 + (hi − lo)/ν)` except for the free ends (`k = 0` or `ν − 1`),
    /// which own every index beyond them.
    /// **Method**: inverse of [`EndRule::fold`] by index arithmetic; exact
    /// (integers only; `end_conditions.rs::tests::folds_and_preimages_agree`).
    /// **Source**: seed 000 eqs 21–23 (end conditions).
    pub fn preimages(self, k: usize, len: usize, lo: i64, hi: i64) -> Vec<i64> {
        let (n, k) = (len as i64, k as i64);
        let mut out: Vec<i64> = match self {
            EndRule::Free => {
                let from = if k == 0 { lo.min(0) } else { k };
                let to = if k == n - 1 { hi.max(k) } else { k };
                (from.max(lo)..=to.min(hi)).collect()
            }
            EndRule::Periodic => {
                let first = lo + (k - lo).rem_euclid(n);
                (first..=hi).step_by(len).collect()
            }
            EndRule::Reflect if n == 1 => (lo..=hi).collect(),
            EndRule::Reflect => {
                let p = 2 * (n - 1);
                let mut v: Vec<i64> = [k, p - k]
                    .iter()
                    .flat_map(|&r| {
                        let first = lo + (r - lo).rem_euclid(p);
                        (first..=hi).step_by(p as usize)
                    })
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            }
        };
        out.retain(|i| (lo..=hi).contains(i));
        out
    }
}

/// Reflection fold for `j = ν − 1 ≥ 1`: iterate the two reflections
/// `i → −i` (adds `2i T_0` … see module doc) and `i → 2j − i` until `i ∈ [0, j]`.
fn reflect(mut i: i64, j: i64) -> (usize, i64, i64) {
    let (mut a, mut b) = (0i64, 0i64);
    loop {
        if i < 0 {
            // P_i = P_{−i} + 2i T_0.
            a += 2 * i;
            i = -i;
        } else if i > j {
            // P_i = P_{2j−i} + 2(i − j) T_1.
            b += 2 * (i - j);
            i = 2 * j - i;
        } else {
            return (i as usize, a, b);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folds_and_preimages_agree() {
        for rule in [EndRule::Free, EndRule::Periodic, EndRule::Reflect] {
            for len in [1usize, 2, 3, 7] {
                for k in 0..len {
                    let pre = rule.preimages(k, len, -20, 25);
                    let want: Vec<i64> = (-20..=25).filter(|&i| rule.fold(i, len).0 == k).collect();
                    assert_eq!(pre, want, "{rule:?} len={len} k={k}");
                }
            }
        }
        // P_{-2} = P_2 − 4 T_0 ; P_{j+1} = P_{j−1} + 2 T_1 (j = 4).
        assert_eq!(EndRule::Reflect.fold(-2, 5), (2, -4, 0));
        assert_eq!(EndRule::Reflect.fold(5, 5), (3, 0, 2));
    }
}
