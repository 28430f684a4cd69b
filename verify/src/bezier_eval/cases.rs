//! The test polynomials: the study's families (exact products of roots,
//! rounded once to f64), the random cases of the bound check and scatter,
//! and Jiang et al.'s example.

use crate::rng::SplitMix64;
use rug::Rational;
use serde::{Deserialize, Serialize};
use splinelab::scalar::Real;

/// The Bernstein coefficients of `∏_k (t − r_k)`, exactly: multiplying a
/// degree-`m` polynomial by `t − r = −r·B_0^1 + (1 − r)·B_1^1` gives
/// `c_k = ((m + 1 − k) a_k (−r) + k a_{k−1} (1 − r)) / (m + 1)`.
pub fn product_of_roots(roots: &[Rational]) -> Vec<Rational> {
    let mut a = vec![Rational::from(1)];
    for r in roots {
        let m = a.len() - 1;
        let (l0, l1) = (Rational::from(-r), Rational::from(1) - r);
        let c = (0..=m + 1)
            .map(|k| {
                let mut v = Rational::new();
                if k <= m {
                    v += Rational::from((m + 1 - k) as u64) * &a[k] * &l0;
                }
                if k >= 1 {
                    v += Rational::from(k as u64) * &a[k - 1] * &l1;
                }
                v / Rational::from((m + 1) as u64)
            })
            .collect();
        a = c;
    }
    a
}

/// The test families of the study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Family {
    /// `(t − ½)ⁿ`: coefficients `(−1)ⁿ⁻ⁱ 2⁻ⁿ`, exact in f64; an n-fold root.
    HalfPower,
    /// `(t − r)^k (t − s)^j` with `r = 3/8`, `s = 3/8 + 2⁻¹²`, `k = ⌈n/2⌉`:
    /// two close multiple roots (coefficients rounded to f64).
    NearMultipleRoot,
    /// Wilkinson-like `∏_{i=1}^n (t − i/n)` in Bernstein form (rounded).
    Wilkinson,
    /// Coefficients uniform in `[−1, 1]`.
    Random,
}

impl Family {
    /// All families.
    pub const ALL: [Family; 4] = [
        Family::HalfPower,
        Family::NearMultipleRoot,
        Family::Wilkinson,
        Family::Random,
    ];

    /// Display name.
    pub fn name(self) -> &'static str {
        match self {
            Family::HalfPower => "(t-1/2)^n",
            Family::NearMultipleRoot => "(t-r)^k (t-s)^j",
            Family::Wilkinson => "prod (t-i/n)",
            Family::Random => "random",
        }
    }

    /// The root the family clusters around (for grids "near the root").
    pub fn root(self) -> Option<f64> {
        match self {
            Family::HalfPower => Some(0.5),
            Family::NearMultipleRoot => Some(0.375),
            Family::Wilkinson | Family::Random => None,
        }
    }

    /// The f64 coefficients at degree `n ≥ 1` (`seed` only for `Random`).
    pub fn coeffs(self, n: usize, seed: u64) -> Vec<f64> {
        let round = |q: Vec<Rational>| q.iter().map(f64::from_rational).collect();
        match self {
            Family::HalfPower => {
                let mag = 0.5f64.powi(n as i32);
                (0..=n)
                    .map(|i| if (n - i).is_multiple_of(2) { mag } else { -mag })
                    .collect()
            }
            Family::NearMultipleRoot => {
                let r = Rational::from((3, 8));
                let s = &r + (Rational::from(1) >> 12u32);
                let k = n.div_ceil(2);
                let roots: Vec<Rational> = (0..n)
                    .map(|i| if i < k { r.clone() } else { s.clone() })
                    .collect();
                round(product_of_roots(&roots))
            }
            Family::Wilkinson => {
                let roots: Vec<Rational> = (1..=n)
                    .map(|i| Rational::from((i as u64, n as u64)))
                    .collect();
                round(product_of_roots(&roots))
            }
            Family::Random => {
                let mut g = SplitMix64::new(seed ^ (n as u64).wrapping_mul(0x9E37));
                (0..=n).map(|_| g.range(-1.0, 1.0)).collect()
            }
        }
    }
}

/// A random case of the bound check / scatter: family, degree, `t`.
pub(super) fn random_case(
    g: &mut SplitMix64,
    max_degree: usize,
    allow_extrapolation: bool,
) -> (Vec<f64>, f64) {
    let n = 1 + (g.next_u64() % max_degree as u64) as usize;
    let coeffs = match g.next_u64() % 4 {
        0 => Family::Random.coeffs(n, g.next_u64()),
        1 => Family::HalfPower.coeffs(n, 0),
        2 => Family::NearMultipleRoot.coeffs(n, 0),
        _ => {
            // Random real roots in [0, 1], some repeated.
            let mut roots: Vec<Rational> = Vec::new();
            while roots.len() < n {
                let r =
                    Rational::from_f64((g.range(0.0, 1.0) * 64.0).round() / 64.0).expect("finite");
                let mult = 1 + (g.next_u64() % 3) as usize;
                roots.extend(std::iter::repeat_n(r, mult.min(n - roots.len())));
            }
            product_of_roots(&roots)
                .iter()
                .map(f64::from_rational)
                .collect()
        }
    };
    let t = match g.next_u64() % 8 {
        0 if allow_extrapolation => g.range(-0.5, 1.5),
        1 | 2 => {
            // Near a dyadic point (possible root) at a random scale.
            let c = (g.range(0.0, 1.0) * 64.0).round() / 64.0;
            (c + g.range(-1.0, 1.0) * 2f64.powi(-((g.next_u64() % 40) as i32))).clamp(0.0, 1.0)
        }
        _ => g.unit(),
    };
    (coeffs, t)
}

/// The coefficients of Jiang et al.'s test polynomial `(t − ¾)⁷ (t − 1)`
/// (exact in f64: a true 7-fold root at `t = ¾`).
pub fn jiang_example() -> Vec<f64> {
    let mut roots = vec![Rational::from((3, 4)); 7];
    roots.push(Rational::from(1));
    product_of_roots(&roots)
        .iter()
        .map(f64::from_rational)
        .collect()
}
