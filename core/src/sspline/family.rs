//! The family of centred basis functions an S-spline is built on.

use super::basis_window::BasisWindow;
use super::{MAX_ORDER, SsplineError, beta2, bspline_uniform};
use crate::scalar::Real;
use rug::ops::Pow;
use rug::{Integer, Rational};
use std::fmt;

/// The basis family of an S-spline: the centred uniform B-spline of order
/// `m` (degree `m − 1`, seed 000 §2.2) or the cubic Beta2-spline with
/// tension `β2 ≥ 0` (seed 000 §4, eq 36; `β2 = 0` is the cubic B-spline).
///
/// β2 is held as an exact rational so that every precision sees the same
/// number the user gave.
///
/// ```
/// use splinelab::sspline::SplineFamily;
/// let f = SplineFamily::parse_tension("0.1").unwrap();
/// assert_eq!(f, SplineFamily::Beta2(rug::Rational::from((1, 10))));
/// assert!(SplineFamily::order(1).is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SplineFamily {
    /// Uniform B-spline of order `m` (`2 ≤ m ≤ 200`).
    Order(u32),
    /// Cubic Beta2-spline with tension `β2 ≥ 0`.
    Beta2(Rational),
}

impl SplineFamily {
    /// The B-spline family of order `m`, validated (`2 ≤ m ≤ 200`).
    pub fn order(m: u32) -> Result<Self, SsplineError> {
        let f = SplineFamily::Order(m);
        f.validate()?;
        Ok(f)
    }

    /// The Beta2 family with an exact rational tension, validated (`β2 ≥ 0`).
    pub fn beta2(b: Rational) -> Result<Self, SsplineError> {
        let f = SplineFamily::Beta2(b);
        f.validate()?;
        Ok(f)
    }

    /// The Beta2 family with the exact binary value of `b` (NaN, infinities
    /// and negative values are refused).
    pub fn beta2_from_f64(b: f64) -> Result<Self, SsplineError> {
        let q = Rational::from_f64(b).ok_or_else(|| SsplineError::InvalidTension(b.to_string()))?;
        Self::beta2(q)
    }

    /// The Beta2 family with tension given as decimal text (`"0.1"`,
    /// `"2.5e1"`) or a fraction (`"1/3"`), converted exactly.
    pub fn parse_tension(s: &str) -> Result<Self, SsplineError> {
        let q = parse_exact_decimal(s.trim())
            .ok_or_else(|| SsplineError::InvalidTension(s.to_string()))?;
        Self::beta2(q)
    }

    /// Checks the parameters; every public entry point calls this.
    pub fn validate(&self) -> Result<(), SsplineError> {
        match self {
            SplineFamily::Order(m) if (2..=MAX_ORDER).contains(m) => Ok(()),
            SplineFamily::Order(m) => Err(SsplineError::OrderOutOfRange(*m)),
            SplineFamily::Beta2(b) if *b >= 0 => Ok(()),
            SplineFamily::Beta2(b) => Err(SsplineError::InvalidTension(b.to_string())),
        }
    }

    /// Spline order `m` of the basis (4 for Beta2).
    pub fn spline_order(&self) -> u32 {
        match self {
            SplineFamily::Order(m) => *m,
            SplineFamily::Beta2(_) => 4,
        }
    }

    /// Number of poles `p = ⌊(m − 1)/2⌋` in (−1, 0), i.e. half the degree of
    /// the Euler–Frobenius polynomial.
    pub fn pole_count(&self) -> usize {
        ((self.spline_order() - 1) / 2) as usize
    }

    /// Support radius of the centred basis: `β(x) = 0` for `|x| ≥ m/2`.
    pub fn half_support(&self) -> f64 {
        self.spline_order() as f64 / 2.0
    }

    /// The tension β2 (0 for a B-spline family of order 4 is *not* implied:
    /// `None` for every B-spline family).
    pub fn tension(&self) -> Option<&Rational> {
        match self {
            SplineFamily::Beta2(b) => Some(b),
            SplineFamily::Order(_) => None,
        }
    }

    /// The non-zero translates `β(x − i)` of the centred basis at `x`
    /// (de Boor–Cox recursion for B-splines, eq 36 for Beta2). `O(m²)`
    /// operations, all on non-negative terms: relative error `O(m² u)`.
    ///
    /// ```
    /// use splinelab::sspline::SplineFamily;
    /// let w = SplineFamily::Order(4).basis_window(&0.0_f64);
    /// // Cubic B-spline at the nodes −1, 0, 1: 1/6, 2/3, 1/6 (and 0).
    /// let v: Vec<f64> = w.values.iter().map(|v| v * 6.0).collect();
    /// assert_eq!((w.first, v), (-1, vec![1.0, 4.0, 1.0, 0.0]));
    /// ```
    pub fn basis_window<T: Real>(&self, x: &T) -> BasisWindow<T> {
        match self {
            SplineFamily::Order(m) => bspline_uniform::centred_window(*m, x),
            SplineFamily::Beta2(b) => beta2::centred_window(&T::from_rational(b), x),
        }
    }

    /// Value of the centred basis `β(x)` itself.
    pub fn basis<T: Real>(&self, x: &T) -> T {
        let w = self.basis_window(x);
        let l = -w.first;
        if l >= 0 && (l as usize) < w.values.len() {
            w.values[l as usize].clone()
        } else {
            T::zero()
        }
    }
}

impl fmt::Display for SplineFamily {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SplineFamily::Order(m) => write!(f, "order {m}"),
            SplineFamily::Beta2(b) => write!(f, "Beta2 β2={}", rational_text(b)),
        }
    }
}

/// Longest exact text [`rational_text`] writes; beyond it, an approximation.
const MAX_EXACT_TEXT: usize = 60;

/// A rational as short text: integer, terminating decimal, or `p/q`; one
/// whose exact text would exceed [`MAX_EXACT_TEXT`] characters (a tension
/// like `1/10⁶⁵⁵³⁵`) as `≈` and 16 significant digits.
fn rational_text(q: &Rational) -> String {
    let bits = q.numer().significant_bits() as usize + q.denom().significant_bits() as usize;
    // ≥ log10(2) ≈ 0.3 digits per bit: a cheap test before any formatting.
    if bits * 3 / 10 > MAX_EXACT_TEXT {
        return format!("≈{:.16e}", rug::Float::with_val(64, q));
    }
    let exact = exact_text(q);
    if exact.chars().count() > MAX_EXACT_TEXT {
        return format!("≈{:.16e}", rug::Float::with_val(64, q));
    }
    exact
}

fn exact_text(q: &Rational) -> String {
    if *q.denom() == 1 {
        return q.numer().to_string();
    }
    let d = q.denom().clone();
    let twos = d.find_one(0).unwrap_or(0);
    let fives = {
        let mut k = 0;
        let mut r = d.clone() >> twos;
        while r.is_divisible_u(5) {
            r /= 5;
            k += 1;
        }
        (r == 1).then_some(k)
    };
    match fives {
        Some(f) => {
            let digits = twos.max(f);
            let scaled = Rational::from(q * Integer::from(10).pow(digits));
            let s = scaled.numer().clone().abs().to_string();
            let s = format!("{s:0>width$}", width = digits as usize + 1);
            let (int, frac) = s.split_at(s.len() - digits as usize);
            let sign = if *q < 0 { "-" } else { "" };
            format!("{sign}{int}.{frac}")
        }
        None => q.to_string(),
    }
}

/// Parses `[+-]digits[.digits][e[+-]digits]` or `p/q` into an exact rational.
fn parse_exact_decimal(s: &str) -> Option<Rational> {
    if let Some((p, q)) = s.split_once('/') {
        let p: Integer = p.trim().parse().ok()?;
        let q: Integer = q.trim().parse().ok()?;
        return (q != 0).then(|| Rational::from((p, q)));
    }
    let (mantissa, exp) = match s.find(['e', 'E']) {
        Some(k) => (&s[..k], s[k + 1..].parse::<i32>().ok()?),
        None => (s, 0),
    };
    let (neg, body) = match mantissa.strip_prefix('-') {
        Some(b) => (true, b),
        None => (false, mantissa.strip_prefix('+').unwrap_or(mantissa)),
    };
    let (int, frac) = body.split_once('.').unwrap_or((body, ""));
    let all_digits = |t: &str| t.chars().all(|c| c.is_ascii_digit());
    if int.len() + frac.len() == 0 || !all_digits(int) || !all_digits(frac) || exp.abs() > 4000 {
        return None;
    }
    let digits: Integer = format!("{int}{frac}").parse().ok()?;
    let scale = exp - frac.len() as i32;
    let ten = Integer::from(10).pow(scale.unsigned_abs());
    let q = if scale >= 0 {
        Rational::from(digits * ten)
    } else {
        Rational::from((digits, ten))
    };
    Some(if neg { -q } else { q })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_decimals_exactly() {
        let p = |s| parse_exact_decimal(s);
        assert_eq!(p("0.1"), Some(Rational::from((1, 10))));
        assert_eq!(p("-2.5e1"), Some(Rational::from(-25)));
        assert_eq!(p("1/3"), Some(Rational::from((1, 3))));
        assert_eq!(p("5"), Some(Rational::from(5)));
        assert_eq!(p("nan"), None);
        assert_eq!(p("1/0"), None);
        assert_eq!(p(""), None);
        assert_eq!(p("."), None);
    }

    #[test]
    fn validates() {
        assert!(SplineFamily::order(2).is_ok());
        assert_eq!(
            SplineFamily::order(201),
            Err(SsplineError::OrderOutOfRange(201))
        );
        assert!(SplineFamily::parse_tension("-1").is_err());
        assert!(SplineFamily::beta2_from_f64(f64::NAN).is_err());
        assert!(SplineFamily::beta2_from_f64(f64::INFINITY).is_err());
        assert_eq!(
            SplineFamily::parse_tension("0.25").unwrap().to_string(),
            "Beta2 β2=0.25"
        );
        assert_eq!(
            SplineFamily::parse_tension("1/3").unwrap().to_string(),
            "Beta2 β2=1/3"
        );
        assert_eq!(
            SplineFamily::parse_tension("50").unwrap().to_string(),
            "Beta2 β2=50"
        );
        // 1/10^65535 once panicked formatting its 65,535 decimals.
        let tiny = format!("1/1{}", "0".repeat(65_535));
        assert_eq!(
            SplineFamily::parse_tension(&tiny).unwrap().to_string(),
            "Beta2 β2=≈1.000000000000000e-65535"
        );
        assert_eq!(
            SplineFamily::parse_tension("1e-70").unwrap().to_string(),
            "Beta2 β2=≈1.000000000000000e-70"
        );
    }
}
