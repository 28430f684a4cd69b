//! The B-spline weights of one cell in closed form, orders 2 to 6
//! (degrees 1 to 5, scipy's range), in `f64`: the pieces of the uniform
//! B-spline `N_{0,m}` as polynomials in the cell position `u ∈ [0, 1)`
//! ([`centred_cell`](crate::sspline::bspline_uniform::centred_cell)) and
//! `v = 1 − u`, each evaluated by Horner's rule, instead of de Boor–Cox's
//! `O(m²)` recursion (`cell_values_into`) per point and axis.
//!
//! **Method.** `w[l] = N_{0,m}(u + m − 1 − l)`. The B-spline is symmetric,
//! `N(t) = N(m − t)`, so `w[m − 1 − l](u) = w[l](v)`: only the pieces on
//! `[0, 1]`, `[1, 2]` and (quintic) `[2, 3]` are needed, from the
//! truncated-power form `N_{0,m}(t) = 1/(m−1)! Σ_p (−1)^p C(m, p) (t −
//! p)_+^{m−1}` (seed 000 eq 31) expanded about the piece's left knot:
//!
//! | order | `[0, 1]` at `s` | `[1, 2]` at `1 + s` | middle |
//! |---|---|---|---|
//! | 2 | `s` | | |
//! | 3 | `s²/2` | | `3/4 − (u − 1/2)²` |
//! | 4 | `s³/6` | `2/3 − (1−s)²(1+s)/2` | |
//! | 5 | `s⁴/24` | `(1 + 4s + 6s² + 4s³(1 − s))/24` | `115/192 − d²(5/8 − d²/4)`, `d = u − 1/2` |
//! | 6 | `s⁵/120` | `(1 + 5s + 10s² + 10s³ + 5s⁴(1 − s))/120` | `(26 + 50s + 20s² − 20s³ − 20s⁴ + 10s⁵)/120` on `[2, 3]` |
//!
//! **Accuracy.** Every form is a sum of non-negative terms or a difference
//! whose terms are at most about twice the result, so each weight is within
//! a few ulps of the exact weight at the same `u`: measured at most
//! `1.8 · 2^−53` absolute (weights lie in `[0, 1]`) over random and edge
//! fractions against de Boor–Cox in 256-bit MPFR
//! (`tests::closed_forms_match_the_recursion_in_mpfr`). **Source**: de
//! Boor, *A Practical Guide to Splines*, ch. IX; seed 000 eqs 7, 31; the
//! same pieces as scipy's `get_spline_interpolation_weights`
//! (`ni_splines.c`), arranged here to avoid its `1 − Σ` last weight.

/// `s` multiplied out once for the forms below.
#[inline(always)]
fn quartic_side(s: f64, t: f64) -> f64 {
    // (1 + 4s + 6s² + 4s³ t) / 24 with t = 1 − s: N_{0,5}(1 + s).
    (1.0 + s * (4.0 + s * (6.0 + 4.0 * s * t))) / 24.0
}

/// `N_{0,6}(1 + s) = (1 + 5s + 10s² + 10s³ + 5s⁴ t) / 120`, `t = 1 − s`.
#[inline(always)]
fn quintic_side(s: f64, t: f64) -> f64 {
    (1.0 + s * (5.0 + s * (10.0 + s * (10.0 + 5.0 * s * t)))) / 120.0
}

/// `N_{0,6}(2 + s) = (26 + 50s + 20s² − 20s³ − 20s⁴ + 10s⁵) / 120`.
#[inline(always)]
fn quintic_middle(s: f64) -> f64 {
    (26.0 + s * (50.0 + s * (20.0 - s * (20.0 + s * (20.0 - 10.0 * s))))) / 120.0
}

/// The `M` weights `w[l] = N_{0,M}(u + M − 1 − l)` of cell position `u`,
/// `M = 1..=6`, in closed form (module documentation; order 1 is the
/// single weight 1). `None` for other orders. Cubics: `v³/6`, `2/3 − u²(2 − u)/2`, `2/3 − v²(2 − v)/2`, `u³/6`.
#[inline(always)]
pub(super) fn closed_form<const M: usize>(u: f64) -> Option<[f64; M]> {
    let v = 1.0 - u;
    let mut w = [0.0; M];
    match M {
        // Degree 0: the nearest sample, weight one (its cell is the
        // rounding of `centred_cell`, scipy's order-0 rule inside the grid).
        1 => w[0] = 1.0,
        2 => {
            w[0] = v;
            w[1] = u;
        }
        3 => {
            let d = u - 0.5;
            w[0] = 0.5 * (v * v);
            w[1] = 0.75 - d * d;
            w[2] = 0.5 * (u * u);
        }
        4 => {
            let (u2, v2) = (u * u, v * v);
            w[0] = v2 * v / 6.0;
            w[1] = 2.0 / 3.0 - 0.5 * u2 * (2.0 - u);
            w[2] = 2.0 / 3.0 - 0.5 * v2 * (2.0 - v);
            w[3] = u2 * u / 6.0;
        }
        5 => {
            let (u2, v2) = (u * u, v * v);
            let d = u - 0.5;
            let d2 = d * d;
            w[0] = v2 * v2 / 24.0;
            w[1] = quartic_side(v, u);
            w[2] = 115.0 / 192.0 - d2 * (0.625 - 0.25 * d2);
            w[3] = quartic_side(u, v);
            w[4] = u2 * u2 / 24.0;
        }
        6 => {
            let (u2, v2) = (u * u, v * v);
            w[0] = v2 * v2 * v / 120.0;
            w[1] = quintic_side(v, u);
            w[2] = quintic_middle(v);
            w[3] = quintic_middle(u);
            w[4] = quintic_side(u, v);
            w[5] = u2 * u2 * u / 120.0;
        }
        _ => return None,
    }
    Some(w)
}

/// [`closed_form`] for a run-time order `m` into `w[..m]`; `false` (and
/// `w` untouched) outside `2..=6`.
pub(super) fn closed_form_into(m: u32, u: f64, w: &mut [f64]) -> bool {
    fn put<const M: usize>(u: f64, w: &mut [f64]) -> bool {
        closed_form::<M>(u)
            .map(|c| w[..M].copy_from_slice(&c))
            .is_some()
    }
    match m {
        2 => put::<2>(u, w),
        3 => put::<3>(u, w),
        4 => put::<4>(u, w),
        5 => put::<5>(u, w),
        6 => put::<6>(u, w),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Mp, Real};
    use crate::sspline::bspline_uniform::cell_values_into;

    /// The largest `|closed form − exact|` in units of `2^−53` over the
    /// fractions `us`, the exact weights by de Boor–Cox in 256-bit MPFR
    /// (the generic recursion, reversed to the window's order).
    fn worst_error<const M: usize>(us: &[f64]) -> f64 {
        let mut worst = 0.0f64;
        for &u in us {
            let got = closed_form::<M>(u).expect("order 2..=6");
            let mut exact = vec![Mp::<256>::from_f64_exact(0.0); M];
            cell_values_into(M as u32, &Mp::<256>::from_f64_exact(u), &mut exact);
            exact.reverse();
            for (g, e) in got.iter().zip(&exact) {
                let err = (Mp::<256>::from_f64_exact(*g) - e).to_f64().abs();
                worst = worst.max(err / f64::EPSILON * 2.0);
            }
        }
        worst
    }

    /// Random fractions, the ends of the cell, its middle, and the
    /// neighbours of each in floating point.
    fn fractions() -> Vec<f64> {
        let mut us: Vec<f64> = vec![0.0, 0.5, 0.25, 0.75, 1.0 / 3.0, 2.0 / 3.0];
        for e in [0.0f64, 0.5] {
            let mut x = e;
            for _ in 0..4 {
                x = f64::from_bits(x.to_bits() + 1);
                us.push(x);
            }
        }
        let mut x = 1.0f64;
        for _ in 0..4 {
            x = f64::from_bits(x.to_bits() - 1);
            us.push(x);
        }
        us.extend([1e-300, 1e-17, 1e-9, 0.5 - 1e-9, 0.5 + 1e-9, 1.0 - 1e-9]);
        // A fixed xorshift stream of 4 000 uniform fractions.
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..4_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            us.push((s >> 11) as f64 / (1u64 << 53) as f64);
        }
        us
    }

    #[test]
    fn closed_forms_match_the_recursion_in_mpfr() {
        let us = fractions();
        let worst = [
            worst_error::<2>(&us),
            worst_error::<3>(&us),
            worst_error::<4>(&us),
            worst_error::<5>(&us),
            worst_error::<6>(&us),
        ];
        // Half an ulp of 1 is 1 in these units: a few roundings each
        // (measured 0.5, 0.75, 1.29, 1.09, 1.71 for orders 2 to 6).
        for (k, w) in worst.iter().enumerate() {
            assert!(*w <= 2.0, "order {}: {w} × 2^-53", k + 2);
        }
    }

    #[test]
    fn closed_forms_are_symmetric_and_partition_unity() {
        for u in [0.0, 0.125, 0.375, 0.5, 0.625, 0.875] {
            let w = closed_form::<6>(u).unwrap();
            let r = closed_form::<6>(1.0 - u).unwrap();
            for l in 0..6 {
                assert_eq!(w[l], r[5 - l], "u = {u}");
            }
            assert!((w.iter().sum::<f64>() - 1.0).abs() <= 4.0 * f64::EPSILON);
        }
        // At the knots: the B-spline's values at the integers.
        let knots6 = [1.0, 26.0, 66.0, 26.0, 1.0, 0.0].map(|k| k / 120.0);
        let knots5 = [1.0, 11.0, 11.0, 1.0, 0.0].map(|k| k / 24.0);
        let near =
            |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= f64::EPSILON);
        assert!(near(&closed_form::<6>(0.0).unwrap(), &knots6));
        assert!(near(&closed_form::<5>(0.0).unwrap(), &knots5));
        assert!(closed_form::<7>(0.5).is_none());
        let mut w = [0.0; 7];
        assert!(!closed_form_into(7, 0.5, &mut w));
    }
}
