//! The uniform B-spline `N_{0,m}` on the knots `0, 1, …, m` and its centred
//! form `β_m(x) = N_{0,m}(x + m/2)` (seed 000 eq 7, 31).

use super::basis_window::BasisWindow;
use crate::scalar::Real;
use rug::ops::Pow;
use rug::{Integer, Rational};

/// Exact value of `N_{0,m}(x)` at a rational point by the truncated-power
/// form (eq 31): `N_{0,m}(x) = 1/(m−1)! Σ_{p=0}^{m} (−1)^p C(m,p) (x−p)_+^{m−1}`.
///
/// Cost: `O(m)` big-rational terms of size `O(m log m)` bits. Exact — the
/// alternating sum cancels heavily, which is why the floating-point routines
/// use the de Boor–Cox recursion instead.
///
/// ```
/// use splinelab::sspline::bspline_uniform::uniform_bspline_exact;
/// use rug::Rational;
/// assert_eq!(uniform_bspline_exact(4, &Rational::from(2)), Rational::from((2, 3)));
/// ```
pub fn uniform_bspline_exact(m: u32, x: &Rational) -> Rational {
    if *x <= 0 || *x >= m {
        return Rational::new();
    }
    let mut sum = Rational::new();
    let mut binom = Integer::from(1);
    for p in 0..=m {
        let t = Rational::from(x - p);
        if t > 0 {
            let term = t.pow(m - 1) * &binom;
            if p % 2 == 0 {
                sum += term;
            } else {
                sum -= term;
            }
        }
        binom = binom * (m - p) / (p + 1);
    }
    let mut fact = Integer::from(1);
    for k in 2..m {
        fact *= k;
    }
    sum / fact
}

/// The `m` values `A[s] = N_{0,m}(u + s)`, `s = 0..m−1`, for `u ∈ [0, 1]`: all
/// B-splines of order `m` that are non-zero on one knot interval.
///
/// De Boor–Cox recursion on uniform knots,
/// `N_{0,k}(t) = (t N_{0,k−1}(t) + (k − t) N_{0,k−1}(t − 1)) / (k − 1)`
/// (de Boor, *A Practical Guide to Splines*, ch. IX). Cost `O(m²)`; every
/// term is non-negative, so the relative error of each value is `O(m² u)`.
pub fn cell_values<T: Real>(m: u32, u: &T) -> Vec<T> {
    let mut a = vec![T::zero(); m as usize];
    cell_values_into(m, u, &mut a);
    a
}

/// [`cell_values`] into `a[0..m]`, without allocating (the recursion runs
/// in place, `s` descending, so each step reads the previous order's
/// `a[s]` and `a[s − 1]`). Same arithmetic, bit for bit.
/// **Accuracy**: exact at rationals
/// (`bspline_uniform.rs::tests::recursion_matches_truncated_powers_exactly_at_rationals`).
/// **Source**: seed 000 eq 7; de Boor, *A Practical Guide to Splines*.
pub fn cell_values_into<T: Real>(m: u32, u: &T, a: &mut [T]) {
    a[0] = T::one();
    for k in 2..=m as usize {
        let kk = T::from_int(k as i64);
        let inv = T::one() / T::from_int(k as i64 - 1);
        for s in (0..k).rev() {
            let t = u.clone() + T::from_int(s as i64);
            let mut v = T::zero();
            if s + 1 < k {
                v += t.clone() * &a[s];
            }
            if s >= 1 {
                v += (kk.clone() - t) * a[s - 1].clone();
            }
            a[s] = v * inv.clone();
        }
    }
}

/// `a[s] = N_{0,m}^{(d)}(u + s)`, `s = 0..m−1`, `d ≤ m − 1`: the order
/// `m − d` values differenced `d` times,
/// `N_{0,k}'(t) = N_{0,k−1}(t) − N_{0,k−1}(t − 1)` (de Boor, ch. X).
/// Cost `O(m²)`; the differences cancel, so the absolute error is about
/// `2^d (m − d)² u` (values of size up to `2^d`).
pub fn cell_derivatives_into<T: Real>(m: u32, d: u32, u: &T, a: &mut [T]) {
    let k = (m - d) as usize;
    cell_values_into(m - d, u, a);
    for len in k..m as usize {
        // Difference of a[0..len] into a[0..=len].
        a[len] = T::zero();
        for s in (0..=len).rev() {
            let prev = if s >= 1 { a[s - 1].clone() } else { T::zero() };
            a[s] = a[s].clone() - prev;
        }
    }
}

/// The window of the centred B-spline of order `m` at an `f64` point `x`:
/// returns `first` with `β_m(x − first − l) = N_{0,m}(u + m − 1 − l)`, and
/// the exact (or once-rounded) cell position `u ∈ [0, 1)` (see
/// [`centred_window`] for why `x + m/2` is never formed). `O(1)`.
/// **Accuracy**: `u` exact or rounded once
/// (`bspline_uniform.rs::tests::window_is_exact_to_rounding_near_powers_of_two`).
/// **Source**: the centred B-spline of seed 000 eqs 7 and 31.
pub fn centred_cell(m: u32, x: f64) -> (i64, f64) {
    let fl = x.floor();
    let t = x - fl;
    let fl = fl as i64 + m as i64 / 2;
    let (fl, u) = if m.is_multiple_of(2) {
        (fl, t)
    } else if t >= 0.5 {
        (fl + 1, t - 0.5)
    } else {
        (fl, t + 0.5)
    };
    (fl - m as i64 + 1, u)
}

/// The non-zero translates `β_m(x − i)` of the centred B-spline at `x`
/// (`m` of them), from [`cell_values`]: with `y = x + m/2 = ⌊y⌋ + u`,
/// `β_m(x − i) = N_{0,m}(u + ⌊y⌋ − i)`. Same cost and accuracy.
///
/// `y` is never formed: `x + m/2` rounds to `ulp(x + m/2)`, which near a
/// power of two costs `ulp(x)` in `u` (6e-10 at `x ≈ 2^23`). Instead the
/// fractional part `t = x − ⌊x⌋` is taken exactly (Sterbenz) and shifted by
/// the half for odd `m` in `[0, 1)` (`t − ½` exact, `t + ½` rounded once
/// to `ulp(1)`), so the error in `u` is at most `u_T`, relative to the
/// cell, whatever the size of `x`.
/// Tested in `bspline_uniform.rs::tests::window_is_exact_to_rounding_near_powers_of_two`.
/// **Source**: seed 000 eqs 7 and 31; de Boor, *A Practical Guide to Splines*.
pub fn centred_window<T: Real>(m: u32, x: &T) -> BasisWindow<T> {
    let fl_x = x.clone().floor();
    let t = x.clone() - &fl_x;
    let fl_x = fl_x.to_f64() as i64;
    let half = T::one().scale_by_pow2(-1);
    // ⌊x + m/2⌋ and its fractional part u, without forming x + m/2.
    let (fl, u) = if m.is_multiple_of(2) {
        (fl_x + m as i64 / 2, t)
    } else if t >= half {
        (fl_x + m as i64 / 2 + 1, t - half)
    } else {
        (fl_x + m as i64 / 2, t + half)
    };
    let mut values = cell_values(m, &u);
    values.reverse();
    BasisWindow {
        first: fl - m as i64 + 1,
        values,
    }
}

/// `N_{0,m}(x)` in floating point (de Boor–Cox, see [`cell_values`]).
///
/// ```
/// use splinelab::sspline::bspline_uniform::uniform_bspline;
/// assert!((uniform_bspline(3, &1.5_f64) - 0.75).abs() < 1e-16);
/// ```
///
/// ```
/// // In MPFR against the exact rational truncated-power form: N_4(1/3) = 1/162.
/// use rug::Rational;
/// use splinelab::scalar::{Mp, Real};
/// use splinelab::sspline::bspline_uniform::{uniform_bspline, uniform_bspline_exact};
/// type M = Mp<128>;
/// let x = Rational::from((1, 3));
/// let exact = M::from_rational(&uniform_bspline_exact(4, &x));
/// assert!((exact.clone() - M::from_int(1) / M::from_int(162)).to_f64().abs() < 1e-40);
/// assert!((uniform_bspline(4, &M::from_rational(&x)) - exact).to_f64().abs() < 1e-40);
/// ```
pub fn uniform_bspline<T: Real>(m: u32, x: &T) -> T {
    if *x <= T::zero() || *x >= T::from_int(m as i64) {
        return T::zero();
    }
    let fl = x.clone().floor();
    let u = x.clone() - &fl;
    let s = fl.to_f64() as usize;
    cell_values(m, &u)[s].clone()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    use nalgebra::ComplexField;

    /// At `x = 2^k − 0.7` and `2^k + 0.3` (`k ≤ 40`) every window value is
    /// within `m² u` of the exact rational `N_{0,m}` at the exact binary `x`:
    /// the error is relative to the cell, not to `ulp(x)`.
    #[test]
    fn window_is_exact_to_rounding_near_powers_of_two() {
        for k in 1..=40 {
            let p = 2f64.powi(k);
            for x in [p - 0.7, p + 0.3, -p + 0.3, p - 0.5, p + 0.5] {
                let xq = Rational::from_f64(x).unwrap();
                for m in 2..=9u32 {
                    let w = centred_window(m, &x);
                    for (l, v) in w.values.iter().enumerate() {
                        let i = w.first + l as i64;
                        // β_m(x − i) = N_{0,m}(x − i + m/2), exactly.
                        let arg = Rational::from(&xq - i) + Rational::from((m, 2));
                        let exact = uniform_bspline_exact(m, &arg);
                        let err = (Rational::from_f64(*v).unwrap() - exact).abs();
                        let tol = Rational::from_f64((m * m) as f64 * f64::EPSILON).unwrap();
                        assert!(err <= tol, "k={k} x={x} m={m} i={i}: {}", err.to_f64());
                    }
                    // The window covers every non-zero translate.
                    let below = Rational::from(&xq - (w.first - 1)) + Rational::from((m, 2));
                    assert_eq!(uniform_bspline_exact(m, &below), 0, "x={x} m={m}");
                }
            }
        }
    }

    #[test]
    fn recursion_matches_truncated_powers_exactly_at_rationals() {
        for m in 2..=12u32 {
            for num in 0..=(4 * m) {
                let x = Rational::from((num, 4));
                let exact = uniform_bspline_exact(m, &x);
                let rec: Mp<256> = uniform_bspline(m, &Mp::from_rational(&x));
                let diff = (rec - Mp::<256>::from_rational(&exact)).abs();
                assert!(diff.to_f64() < 1e-70, "m={m} x={x}");
            }
        }
    }
}
