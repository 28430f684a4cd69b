//! `bezier-eval`: a user's values of a Bernstein polynomial
//! `Σ b_i C(n,i) tⁱ(1−t)^{n−i}` against exact rational de Casteljau on the
//! f64 inputs.

use super::bspline_eval::EXACT_FLOAT_BITS;
use super::format::UserFormat;
use super::stable_bound::{gamma, unit_roundoff};
use super::summary::{BoundBasis, CheckSummary, Context, element_error, from_elements};
use super::{CheckError, require_finite, require_len};
use rayon::prelude::*;
use rug::{Float, Rational};

/// Largest `len(t) · n²` accepted (rational operations).
pub const MAX_WORK: usize = 50_000_000;

/// The value at `t` by de Casteljau's algorithm in exact arithmetic:
/// `n(n+1)/2` convex combinations, no rounding at all.
pub fn de_casteljau_exact(b: &[Rational], t: &Rational) -> Rational {
    let s: Rational = 1 - t.clone();
    let mut d = b.to_vec();
    for r in 1..d.len() {
        for i in 0..d.len() - r {
            d[i] = Rational::from(&s * &d[i]) + Rational::from(t * &d[i + 1]);
        }
    }
    d.swap_remove(0)
}

/// `Σ_i |b_i| |C(n,i) tⁱ (1−t)^{n−i}|` exactly: the scale of de
/// Casteljau's rounding errors (de Casteljau on `|b|` inside `[0, 1]`).
pub fn abs_bernstein_sum(b: &[Rational], t: &Rational) -> Rational {
    let n = b.len() - 1;
    let (t, s) = (t.clone().abs(), Rational::from(1 - t).abs());
    let mut binom = rug::Integer::from(1);
    let mut sum = Rational::new();
    for (i, bi) in b.iter().enumerate() {
        let term = Rational::from(bi.abs_ref())
            * Rational::from(&binom)
            * rug::ops::Pow::pow(t.clone(), i as u32)
            * rug::ops::Pow::pow(s.clone(), (n - i) as u32);
        sum += term;
        binom = binom * (n - i) as u64 / (i as u64 + 1);
    }
    sum
}

/// Checks `user[j] ≈ B(t_j)` for the Bernstein coefficients `b` (parallel over t).
pub fn check_bezier_eval(
    b: &[f64],
    t: &[f64],
    user: &[f64],
    format: UserFormat,
    max_ulps: Option<f64>,
) -> Result<CheckSummary, CheckError> {
    if b.is_empty() {
        return Err(CheckError::Empty("Bernstein coefficients".into()));
    }
    if t.is_empty() {
        return Err(CheckError::Empty("t".into()));
    }
    require_finite("Bernstein coefficients", b)?;
    require_finite("t", t)?;
    require_len("values (one per t)", t.len(), user.len())?;
    let work = t.len().saturating_mul(b.len() * b.len());
    if work > MAX_WORK {
        return Err(CheckError::TooLarge(format!(
            "len(t)·n² = {work} exceeds {MAX_WORK}"
        )));
    }
    let q = |x: &f64| Rational::from_f64(*x).expect("finite");
    let bq: Vec<Rational> = b.iter().map(q).collect();
    let g = gamma(2 * (b.len() - 1), format);
    let u0 = unit_roundoff(format);
    let elements = t
        .par_iter()
        .zip(user.par_iter())
        .enumerate()
        .map(|(i, (t, u))| {
            let t = q(t);
            let r = Float::with_val(EXACT_FLOAT_BITS, &de_casteljau_exact(&bq, &t));
            let scale = abs_bernstein_sum(&bq, &t).to_f64();
            element_error(i, *u, &r, format, None).with_bound(g * scale + u0 * r.to_f64().abs())
        })
        .collect();
    let ctx = Context {
        kind: "bezier-eval",
        format,
        reference_bits: None,
        reference: "exact rational de Casteljau".into(),
        horizon: None,
        max_ulps,
        bound: BoundBasis::PerElement(format!(
            "γ_{}·Σ_i |b_i||B_i^n(t)| + u|p(t)|: the forward error of de Casteljau's algorithm (Farouki–Rajan 1987; Mainar–Peña 1999; Higham, Accuracy and Stability, 2nd ed., §5.1 for the analogous Horner bound)",
            2 * (b.len() - 1)
        )),
    };
    Ok(from_elements(&ctx, elements))
}
