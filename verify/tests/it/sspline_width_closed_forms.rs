//! The width chooser and the truncation-error measures judged against an
//! independent computation, not against the `TruncationAnalysis` the
//! chooser itself uses.
//!
//! For the cubic B-spline and the Beta2-spline the coefficients have closed
//! forms, `c_i = κ₀ ξ₀^{|i|}` (seed 000 eq 18, 29, 38, 40), and the basis is
//! written out below from eq 36 segment by segment. From these alone, in
//! 128-bit MPFR:
//!
//! - the knot error has a closed form. `E(j) = Σ_{|i|>n} c_i β(j − i)` needs
//!   `|j − i| ≤ 1`; for `|j| < n` no tail index is in reach, `E(n) = V₁ c_{n+1}`
//!   and `E(n + 1) = δ − S_n(n + 1) = −V₁ c_n`, and `E(j) = 0` beyond. So
//!   `max_j |E(j)| = V₁ |c_n| = (2/δ) κ₀ |ξ₀|^n`, `δ = β2 + 12`;
//! - the uniform error `sup_x Σ_k |E(x − k)|` is found by dense sampling of
//!   `[0, ½]` and a golden-section refinement of the best sample.

use rug::Rational;
use splinelab::scalar::prelude::*;
use splinelab::sspline::{Criterion, SplineFamily, TruncationAnalysis, truncation_width};

type M = Mp<128>;

fn m(x: f64) -> M {
    M::from_f64_exact(x)
}

/// A Beta2-spline (β2 = 0 is the uniform cubic) in closed form.
struct ClosedForm {
    beta2: M,
    kappa: M,
    xi: M,
}

impl ClosedForm {
    fn new(beta2: &Rational) -> Self {
        let b = M::from_rational(beta2);
        let four = m(4.0);
        // eq 38 and eq 40.
        let xi = -(b.clone() + m(8.0)) / four.clone()
            + ((b.clone() + four.clone()) * (b.clone() + m(12.0))).sqrt() / four.clone();
        let kappa = (m(1.0) + m(8.0) / (b.clone() + four)).sqrt();
        ClosedForm {
            beta2: b,
            kappa,
            xi,
        }
    }

    fn delta(&self) -> M {
        self.beta2.clone() + m(12.0)
    }

    /// `c_i = κ₀ ξ₀^{|i|}` (eq 29).
    fn c(&self, i: i64) -> M {
        self.kappa.clone() * self.xi.clone().powi(i.unsigned_abs() as i32)
    }

    /// The centred basis from the segments of eq 36: on `[k, k + 1)`,
    /// `β(y) = b_{−1−k}(y − k)`, `k ∈ {−2, −1, 0, 1}`.
    fn beta(&self, y: &M) -> M {
        let k = y.clone().floor().to_f64() as i64;
        if !(-2..=1).contains(&k) {
            return m(0.0);
        }
        let t = y.clone() - m(k as f64);
        let (t2, t3) = (t.clone() * t.clone(), t.clone() * t.clone() * t.clone());
        let b = self.beta2.clone();
        let num = match -1 - k {
            1 => m(2.0) * t3,
            0 => {
                m(2.0) + m(6.0) * t + (m(3.0) * b.clone() + m(6.0)) * t2
                    - (m(2.0) * b + m(6.0)) * t3
            }
            -1 => {
                (b.clone() + m(8.0)) - (m(3.0) * b.clone() + m(12.0)) * t2
                    + (m(2.0) * b + m(6.0)) * t3
            }
            _ => m(2.0) - m(6.0) * t + m(6.0) * t2 - m(2.0) * t3,
        };
        num / self.delta()
    }

    /// `V₁ |c_n|`, the knot error of half-width `n` (module doc).
    fn knot_error(&self, n: usize) -> M {
        m(2.0) / self.delta() * self.c(n as i64).abs()
    }

    /// Tail terms beyond `|i| = n + L` are below `|ξ₀|^L` relatively: L is
    /// chosen so that this is `< 2^{−80}`, far below the `10⁻⁹` compared.
    fn reach(&self, n: usize) -> i64 {
        let l = (80.0 / -self.xi.to_f64().abs().log2()).ceil() as i64;
        n as i64 + l
    }

    /// `E(y) = Σ_{|i|>n} c_i β(y − i)`, only the (at most four) `i` with
    /// `|y − i| < 2`.
    fn tail(&self, n: usize, y: &M) -> M {
        let base = y.clone().floor().to_f64() as i64;
        let mut e = m(0.0);
        for i in base - 1..=base + 2 {
            if i.unsigned_abs() as usize > n {
                e += self.c(i) * self.beta(&(y.clone() - m(i as f64)));
            }
        }
        e
    }

    /// `Σ_k |E(x − k)|` for `x ∈ [0, ½]`; `E(x − k)` vanishes for
    /// `|k| < n − 2` (no tail index within reach of the basis).
    fn curve_error(&self, n: usize, x: &M) -> M {
        let (lo, hi) = (n as i64 - 3, self.reach(n) + 2);
        (-hi..=hi).filter(|k| k.abs() >= lo).fold(m(0.0), |acc, k| {
            acc + self.tail(n, &(x.clone() - m(k as f64))).abs()
        })
    }

    /// `sup_{x ∈ [0, ½]} Σ_k |E(x − k)|`: 101 samples, then 70 golden-section
    /// steps in the bracket of the best one (the function is unimodal there:
    /// a smooth maximum or a kink).
    fn uniform_error(&self, n: usize) -> M {
        const GRID: i64 = 100;
        let at = |j: i64| m(j as f64) / m((2 * GRID) as f64);
        let best = (0..=GRID)
            .map(|j| (j, self.curve_error(n, &at(j))))
            .fold((0, m(-1.0)), |b, v| if v.1 > b.1 { v } else { b });
        let (mut a, mut b) = (at((best.0 - 1).max(0)), at((best.0 + 1).min(GRID)));
        let g = (m(5.0).sqrt() - m(1.0)) / m(2.0);
        let mut top = best.1;
        for _ in 0..70 {
            let x1 = b.clone() - g.clone() * (b.clone() - a.clone());
            let x2 = a.clone() + g.clone() * (b.clone() - a.clone());
            let (f1, f2) = (self.curve_error(n, &x1), self.curve_error(n, &x2));
            if f1 < f2 {
                a = x1;
            } else {
                b = x2;
            }
            for f in [f1, f2] {
                if f > top {
                    top = f;
                }
            }
        }
        top
    }
}

fn cases() -> Vec<(SplineFamily, ClosedForm)> {
    [Rational::from(0), Rational::from(5), Rational::from((1, 3))]
        .into_iter()
        .map(|b| {
            let family = if b == 0 {
                SplineFamily::Order(4)
            } else {
                SplineFamily::Beta2(b.clone())
            };
            (family, ClosedForm::new(&b))
        })
        .collect()
}

fn rel(a: &M, b: &M) -> f64 {
    ((a.clone() - b.clone()) / b.clone()).abs().to_f64()
}

#[test]
fn knot_error_is_v1_times_c_n() {
    for (f, cf) in cases() {
        let a = TruncationAnalysis::<Mp<128>>::new(&f, 20).unwrap();
        for n in [1, 2, 5, 12, 20] {
            let got = M::from_f64_exact(a.knot_error(n).to_f64());
            let want = cf.knot_error(n);
            assert!(rel(&got, &want) < 1e-15, "{f} n={n}: {got:?} vs {want:?}");
        }
    }
}

/// Two-sided: the analysis' sup is neither below nor above the independent
/// one by more than its documented `10⁻⁹` (located in f64, then evaluated).
#[test]
fn uniform_error_equals_the_independent_sup() {
    for (f, cf) in cases() {
        let a = TruncationAnalysis::<Mp<128>>::new(&f, 8).unwrap();
        for n in [1, 3, 8] {
            let got = M::from_f64_exact(a.uniform_error(n).to_f64());
            let want = cf.uniform_error(n);
            assert!(rel(&got, &want) < 1e-9, "{f} n={n}: {got:?} vs {want:?}");
        }
    }
}

/// The smallest `n` with `measure(n) < tol`, from the closed forms; `None`
/// when a measure lies within `10⁻⁶` of `tol` (too close to call for a test
/// whose reference sup is itself located numerically).
fn independent_width(measure: impl Fn(usize) -> M, tol: f64, from: usize) -> Option<usize> {
    let eps = m(tol);
    for n in from..200 {
        let e = measure(n);
        if rel(&e, &eps) < 1e-6 {
            return None;
        }
        if e < eps {
            return Some(n);
        }
    }
    None
}

#[test]
fn chooser_width_matches_the_closed_forms() {
    for (f, cf) in cases() {
        for tol in [0.3, 1e-2, 3e-4, 1e-6, 1e-9, 1e-13] {
            for (criterion, measure) in [
                (
                    Criterion::Knot,
                    Box::new(|n| cf.knot_error(n)) as Box<dyn Fn(usize) -> M>,
                ),
                (Criterion::Uniform, Box::new(|n| cf.uniform_error(n))),
            ] {
                // uniform ≥ knot: the uniform width is at least the knot width.
                let from = independent_width(|n| cf.knot_error(n), tol, 1).unwrap_or(1);
                let Some(want) = independent_width(&measure, tol, from) else {
                    continue;
                };
                let w = truncation_width(&f, tol, criterion).unwrap();
                assert_eq!(w.n, want, "{f} {criterion} tol {tol}");
                let achieved = measure(want);
                assert!(
                    rel(&m(w.achieved), &achieved) < 1e-9,
                    "{f} {criterion} tol {tol}: achieved {} vs {achieved:?}",
                    w.achieved
                );
                // The certified bound must cover the independent worst curve error.
                assert!(
                    m(w.bound) >= cf.uniform_error(want),
                    "{f} {criterion} tol {tol}: bound {} below the sup",
                    w.bound
                );
            }
        }
    }
}
