//! The cubic Beta2-spline with tension `β2 ≥ 0` (Barsky–DeRose 1985, with
//! `β1 = 1`) and the closed forms of its S-spline (seed 000 §4, appendix d).

use super::basis_window::BasisWindow;
use crate::scalar::Real;
use rug::Rational;

/// The four basis segments `[b_{−2}, b_{−1}, b_0, b_1](t)`, `t ∈ [0, 1]`
/// (eq 36), with `δ = β2 + 12`:
/// `b_1 = 2t³/δ`, `b_0 = (2 + 6t + (3β2+6)t² − (2β2+6)t³)/δ`,
/// `b_{−1} = ((β2+8) − (3β2+12)t² + (2β2+6)t³)/δ`, `b_{−2} = 2(1 − t)³/δ`.
///
/// Cost: about 20 operations. Each segment is evaluated by Horner; `b_{−2}`
/// as `2(1−t)³`, which is exact in `1 − t` for `t ∈ [½, 1]` (Sterbenz).
///
/// ```
/// use splinelab::sspline::beta2::segments;
/// let b = segments(&0.0_f64, &0.5); // β2 = 0: the uniform cubic B-spline
/// assert!((b[1] - 23.0 / 48.0).abs() < 1e-16);
/// ```
pub fn segments<T: Real>(beta2: &T, t: &T) -> [T; 4] {
    let n = |k: i64| T::from_int(k);
    let delta = beta2.clone() + n(12);
    let t2 = t.clone() * t;
    let t3 = t2.clone() * t;
    let s = T::one() - t.clone();
    let b1 = n(2) * t3.clone();
    let b0 = n(2) + n(6) * t.clone() + (n(3) * beta2.clone() + n(6)) * t2.clone()
        - (n(2) * beta2.clone() + n(6)) * t3.clone();
    let bm1 = (beta2.clone() + n(8)) - (n(3) * beta2.clone() + n(12)) * t2
        + (n(2) * beta2.clone() + n(6)) * t3;
    let bm2 = n(2) * s.clone() * &s * s;
    [bm2, bm1, b0, b1].map(|b| b / delta.clone())
}

/// The translates `B(x − i, β2)` of the centred Beta2 basis that are
/// non-zero at `x`: with `x = ⌊x⌋ + t`, the translates `i = ⌊x⌋ − 1 … ⌊x⌋ + 2`
/// take the segments `b_{−2}, b_{−1}, b_0, b_1` at `t` (eq 28, 36).
pub fn centred_window<T: Real>(beta2: &T, x: &T) -> BasisWindow<T> {
    let fl = x.clone().floor();
    let t = x.clone() - &fl;
    BasisWindow {
        first: fl.to_f64() as i64 - 1,
        values: segments(beta2, &t).to_vec(),
    }
}

/// Exact node values `[V_1, V_2, V_3] = [2, β2 + 8, 2] / (β2 + 12)` (eq 37).
pub fn node_values_exact(beta2: &Rational) -> Vec<Rational> {
    let delta = Rational::from(beta2 + 12u32);
    let two = Rational::from(2) / &delta;
    vec![two.clone(), Rational::from(beta2 + 8u32) / &delta, two]
}

/// The pole `ξ_0 = −(β2+8)/4 + √((β2+4)(β2+12))/4` (eq 38), evaluated in the
/// algebraically identical cancellation-free form
/// `ξ_0 = −4 / ((β2+8) + √((β2+4)(β2+12)))` (the two terms of eq 38 nearly
/// cancel for large β2: their squares differ by exactly 1). Relative error a
/// few `u` for every β2 ≥ 0.
///
/// ```
/// use splinelab::sspline::beta2::pole_closed_form;
/// // √3 − 2 = −0.26794919243112270647…
/// assert!((pole_closed_form(&0.0_f64) + 0.2679491924311227).abs() < 6e-17);
/// ```
///
/// ```
/// use splinelab::sspline::beta2::pole_closed_form;
/// // In MPFR at β2 = 0: the cubic's pole √3 − 2, to 256-bit rounding.
/// use splinelab::nalgebra::ComplexField;
/// use splinelab::scalar::{Mp, Real};
/// type M = Mp<256>;
/// let xi = pole_closed_form(&M::from_int(0));
/// assert!((xi - (M::from_int(3).sqrt() - M::from_int(2))).to_f64().abs() < 1e-75);
/// ```
pub fn pole_closed_form<T: Real>(beta2: &T) -> T {
    let n = |k: i64| T::from_int(k);
    let root = ((beta2.clone() + n(4)) * (beta2.clone() + n(12))).sqrt();
    -n(4) / (beta2.clone() + n(8) + root)
}

/// `κ_0 = √(1 + 8/(β2 + 4))` (eq 40). A few `u` relative error.
pub fn kappa_closed_form<T: Real>(beta2: &T) -> T {
    (T::one() + T::from_int(8) / (beta2.clone() + T::from_int(4))).sqrt()
}

/// `c_i = κ_0 ξ_0^i`, `i = 0..count−1` (eq 29), with the stable pole of
/// [`pole_closed_form`] and one correctly rounded power in MPFR (`powi`).
/// Relative error about `(i + 3) u`, dominated by the rounding of `ξ_0`.
pub fn coefficients_closed_form<T: Real>(beta2: &T, count: usize) -> Vec<T> {
    let xi = pole_closed_form(beta2);
    let kappa = kappa_closed_form(beta2);
    (0..count)
        .map(|i| kappa.clone() * xi.clone().powi(i as i32))
        .collect()
}

/// The cubic B-spline case (eq 18): `c_i = √3 (√3 − 2)^i`, with the pole
/// computed as `−1/(2 + √3)` (no cancellation). Relative error about `(i+3) u`.
///
/// ```
/// use splinelab::sspline::beta2::cubic_coefficients_closed_form;
/// let c: Vec<f64> = cubic_coefficients_closed_form(2);
/// assert!((c[0] - 3f64.sqrt()).abs() < 1e-15);
/// ```
pub fn cubic_coefficients_closed_form<T: Real>(count: usize) -> Vec<T> {
    let s3 = T::from_int(3).sqrt();
    let xi = -T::one() / (T::from_int(2) + s3.clone());
    (0..count)
        .map(|i| s3.clone() * xi.clone().powi(i as i32))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sspline::bspline_uniform::uniform_bspline_exact;

    #[test]
    fn zero_tension_is_the_cubic_bspline() {
        // Exact rationals: segments at t = k/8 against eq 31 at x = t + 3 − l.
        for k in 0..=8 {
            let t = Rational::from((k, 8));
            let t_f = t.to_f64();
            let b = segments(&0.0_f64, &t_f);
            for (l, bl) in b.iter().enumerate() {
                let x = Rational::from(&t + (3 - l as i64));
                let exact = uniform_bspline_exact(4, &x).to_f64();
                assert!((bl - exact).abs() < 1e-16, "t={t} l={l}");
            }
        }
    }
}
