//! The exact reference: a Bernstein polynomial with dyadic coefficients run
//! through de Casteljau's recurrence in big integers, and the f64 unit
//! roundoff and `γ_k` as exact rationals.

use rug::ops::Pow;
use rug::{Integer, Rational};

/// A Bernstein polynomial with rational coefficients, stored as integers
/// over one common denominator so that de Casteljau's recurrence runs in
/// `rug::Integer` (no gcd per operation): at `t = T/S`,
/// `p(t) = (Σ_i C(n,i) N_i Tⁱ (S − T)ⁿ⁻ⁱ) / (D Sⁿ)`.
#[derive(Debug, Clone)]
pub struct ExactPoly {
    nums: Vec<Integer>,
    den: Integer,
}

impl ExactPoly {
    /// From exact rational coefficients (non-empty).
    pub fn new(coeffs: &[Rational]) -> Self {
        let den = coeffs
            .iter()
            .fold(Integer::from(1), |d, c| d.lcm(c.denom()));
        let nums = coeffs
            .iter()
            .map(|c| c.numer() * (&den / Integer::from(c.denom())))
            .collect();
        ExactPoly { nums, den }
    }

    /// From f64 coefficients, exactly (they must be finite).
    pub fn from_f64(coeffs: &[f64]) -> Self {
        let q: Vec<Rational> = coeffs
            .iter()
            .map(|&c| Rational::from_f64(c).expect("finite coefficient"))
            .collect();
        Self::new(&q)
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.nums.len() - 1
    }

    fn run(&self, t: &Rational, abs: bool) -> Rational {
        let (tn, s) = (t.numer().clone(), t.denom().clone());
        let mut rn = Integer::from(&s - &tn);
        let mut tn = tn;
        let mut b = self.nums.clone();
        if abs {
            rn.abs_mut();
            tn.abs_mut();
            b.iter_mut().for_each(Integer::abs_mut);
        }
        let n = self.degree();
        for j in 1..=n {
            for i in 0..=n - j {
                let right = Integer::from(&tn * &b[i + 1]);
                b[i] *= &rn;
                b[i] += right;
            }
        }
        let den = &self.den * s.pow(n as u32);
        Rational::from((b.swap_remove(0), den))
    }

    /// The exact `p(t)`.
    pub fn value(&self, t: &Rational) -> Rational {
        self.run(t, false)
    }

    /// The exact `Σ |b_i| |B_i^n(t)|` (numerator of `cond_B`).
    pub fn abs_sum(&self, t: &Rational) -> Rational {
        self.run(t, true)
    }
}

/// The unit roundoff of f64, `2⁻⁵³`, exactly.
pub fn unit_roundoff() -> Rational {
    Rational::from(1) >> 53u32
}

/// `γ_k = k u / (1 − k u)` for f64, exactly.
pub fn gamma(k: usize) -> Rational {
    let ku = Rational::from(k as u64) * unit_roundoff();
    &ku / (Rational::from(1) - &ku)
}
