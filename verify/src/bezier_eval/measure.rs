//! One evaluation measured exactly against [`super::ExactPoly`], and the
//! tallies of how often each running / a-priori bound holds.

use super::cases::random_case;
use super::exact::{ExactPoly, gamma, unit_roundoff};
use super::method::{EvalError, Method, Prepared};
use crate::rng::SplitMix64;
use rayon::prelude::*;
use rug::Rational;
use serde::{Deserialize, Serialize};
use splinelab::bernstein::bezier::{BezierError, Evaluation};
use splinelab::scalar::Real;
use splinelab::validation::InputError;

/// One evaluation measured exactly.
#[derive(Debug, Clone)]
pub struct Measured {
    /// The computed value and running bound.
    pub eval: Evaluation<f64>,
    /// `|value − p(t)|`, exact.
    pub abs_error: Rational,
    /// `|p(t)|`, exact.
    pub abs_value: Rational,
    /// `Σ|b_i||B_i^n(t)|`, exact.
    pub abs_sum: Rational,
}

impl Measured {
    /// The running bound holds: `|value − p(t)| ≤ bound`, decided exactly.
    pub fn running_holds(&self) -> bool {
        Rational::from_f64(self.eval.bound).is_some_and(|b| self.abs_error <= b)
    }

    /// The relative error `|value − p|/|p|` rounded to f64 (`∞` when
    /// `p(t) = 0` and the value is not).
    pub fn rel_error(&self) -> f64 {
        if self.abs_value == 0 {
            return if self.abs_error == 0 {
                0.0
            } else {
                f64::INFINITY
            };
        }
        f64::from_rational(&Rational::from(&self.abs_error / &self.abs_value))
    }

    /// `cond_B(p, t)` rounded to f64 (`∞` at a root).
    pub fn cond(&self) -> f64 {
        if self.abs_value == 0 {
            return f64::INFINITY;
        }
        f64::from_rational(&Rational::from(&self.abs_sum / &self.abs_value))
    }

    /// The a-priori bound of `method` where one is proven (t ∈ [0, 1] only):
    /// de Casteljau `γ_{3n} S`, direct Bernstein sum `γ_{3n+2} S`, compensated
    /// `u|p| + 2γ_{3n}² S` (`S = Σ|b_i|B_i^n(t)`).
    pub fn a_priori(&self, method: Method, n: usize) -> Option<Rational> {
        if self.eval.extrapolated {
            return None;
        }
        match method {
            Method::DeCasteljau => Some(gamma(3 * n) * &self.abs_sum),
            Method::Bernstein => Some(gamma(3 * n + 2) * &self.abs_sum),
            Method::Compensated => {
                let g = gamma(3 * n);
                Some(
                    unit_roundoff() * &self.abs_value + Rational::from(2) * &g * &g * &self.abs_sum,
                )
            }
            _ => None,
        }
    }
}

/// The polynomial prepared for every method, and its exact twin.
pub(super) fn prepared(coeffs: &[f64]) -> Result<(Prepared<f64>, ExactPoly), EvalError> {
    Ok((Prepared::new(coeffs.to_vec())?, ExactPoly::from_f64(coeffs)))
}

/// Evaluates `prepared` at `t` by `method` and measures it against `exact`.
pub fn measure(
    prepared: &Prepared<f64>,
    exact: &ExactPoly,
    method: Method,
    t: f64,
) -> Result<Measured, EvalError> {
    let eval = prepared.evaluate(method, &t)?;
    let tq = Rational::from_f64(t)
        .ok_or(InputError::NonFinite {
            name: "the parameter t",
        })
        .map_err(BezierError::from)?;
    let p = exact.value(&tq);
    let v = Rational::from_f64(eval.value).ok_or(BezierError::Overflow {
        method: "exact",
        degree: 0,
    })?;
    Ok(Measured {
        abs_error: (v - &p).abs(),
        abs_value: p.abs(),
        abs_sum: exact.abs_sum(&tq),
        eval,
    })
}

/// How often a bound held and how tight it was.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BoundStats {
    /// The method.
    pub method: Method,
    /// `"running"` or `"a priori"`.
    pub kind: String,
    /// Cases where the bound applies.
    pub cases: usize,
    /// Cases where it held (must equal `cases`).
    pub holds: usize,
    /// Cases with a nonzero error (where tightness is defined).
    pub nonzero: usize,
    /// Median of `log10(bound / error)` over nonzero errors.
    pub median_log10_ratio: f64,
    /// 90th percentile of the same.
    pub p90_log10_ratio: f64,
}

/// Tally of one bound over many cases.
#[derive(Debug, Clone, Default)]
pub struct Tally {
    cases: usize,
    holds: usize,
    log_ratios: Vec<f64>,
}

impl Tally {
    /// Records one case: the bound and the exact error.
    pub fn record(&mut self, bound: &Rational, error: &Rational) {
        self.cases += 1;
        if error <= bound {
            self.holds += 1;
        }
        if *error != 0 && *bound != 0 {
            self.log_ratios
                .push(f64::from_rational(&Rational::from(bound / error)).log10());
        }
    }

    /// Cases recorded and cases where the bound held.
    pub fn counts(&self) -> (usize, usize) {
        (self.cases, self.holds)
    }

    pub(super) fn stats(mut self, method: Method, kind: &str) -> BoundStats {
        self.log_ratios.sort_by(f64::total_cmp);
        let q = |p: f64| {
            if self.log_ratios.is_empty() {
                0.0
            } else {
                self.log_ratios[((self.log_ratios.len() - 1) as f64 * p) as usize]
            }
        };
        BoundStats {
            method,
            kind: kind.into(),
            cases: self.cases,
            holds: self.holds,
            nonzero: self.log_ratios.len(),
            median_log10_ratio: q(0.5),
            p90_log10_ratio: q(0.9),
        }
    }
}

/// Checks every running and a-priori bound on `cases` random cases (degrees
/// `1..=max_degree`, t mostly in `[0, 1]`, 1/8 of them extrapolated), exactly.
/// Returns `(method, running tally, a-priori tally)`.
pub fn check_bounds(
    cases: usize,
    max_degree: usize,
    seed: u64,
) -> Result<Vec<(Method, Tally, Tally)>, EvalError> {
    let chunks = 64.min(cases.max(1));
    let per = cases.div_ceil(chunks);
    let partial: Vec<Vec<(Tally, Tally)>> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut g = SplitMix64::new(seed.wrapping_add(c as u64 * 0x1234_5678_9ABC));
            let mut tallies = vec![(Tally::default(), Tally::default()); Method::all().len()];
            for _ in 0..per.min(cases - (c * per).min(cases)) {
                let (coeffs, t) = random_case(&mut g, max_degree, true);
                let (prep, exact) = prepared(&coeffs)?;
                let n = coeffs.len() - 1;
                for (k, method) in Method::all().enumerate() {
                    let m = measure(&prep, &exact, method, t)?;
                    tallies[k].0.record(
                        &Rational::from_f64(m.eval.bound).expect("finite"),
                        &m.abs_error,
                    );
                    if let Some(b) = m.a_priori(method, n) {
                        tallies[k].1.record(&b, &m.abs_error);
                    }
                }
            }
            Ok(tallies)
        })
        .collect::<Result<_, EvalError>>()?;
    Ok(Method::all()
        .enumerate()
        .map(|(k, method)| {
            let mut run = Tally::default();
            let mut pri = Tally::default();
            for p in &partial {
                merge(&mut run, &p[k].0);
                merge(&mut pri, &p[k].1);
            }
            (method, run, pri)
        })
        .collect())
}

fn merge(into: &mut Tally, from: &Tally) {
    into.cases += from.cases;
    into.holds += from.holds;
    into.log_ratios.extend_from_slice(&from.log_ratios);
}
