//! The study: relative error near multiple roots, vs degree and vs
//! `cond_B`, the bound statistics and the closing figure, as report data.

use super::cases::{Family, jiang_example, random_case};
use super::measure::{BoundStats, Measured, check_bounds, measure, prepared};
use super::method::{EvalError, Method};
use crate::rng::SplitMix64;
use rayon::prelude::*;
use rug::Rational;
use serde::{Deserialize, Serialize};

/// Sizes of the study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct BezierEvalParams {
    /// Grid points per near-root curve.
    pub near_root_points: usize,
    /// Largest degree of the degree sweep (from 1).
    pub max_degree: usize,
    /// `t` samples per degree in the sweep.
    pub degree_samples: usize,
    /// Cases in the error-vs-condition scatter.
    pub scatter_cases: usize,
    /// Random cases of the bound check.
    pub bound_cases: usize,
    /// Grid intervals on `[0, 1]` for the closing figure.
    pub closing_grid: usize,
}

impl BezierEvalParams {
    /// A short sweep (seconds).
    pub fn quick() -> Self {
        BezierEvalParams {
            near_root_points: 121,
            max_degree: 30,
            degree_samples: 24,
            scatter_cases: 400,
            bound_cases: 3_000,
            closing_grid: 1_000,
        }
    }
    /// The full sweep of the issue (degrees 1..60, 10⁵ bound cases).
    pub fn full() -> Self {
        BezierEvalParams {
            near_root_points: 401,
            max_degree: 60,
            degree_samples: 64,
            scatter_cases: 3_000,
            bound_cases: 100_000,
            closing_grid: 10_000,
        }
    }
}

/// Relative error of one method at one point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ErrorPoint {
    /// Abscissa (t, degree or condition number).
    pub x: f64,
    /// Relative error (may be 0 for an exact result).
    pub rel_error: f64,
}

/// A curve of one method.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MethodSeries {
    /// The method.
    pub method: Method,
    /// Its points.
    pub points: Vec<ErrorPoint>,
}

/// Relative error vs `t` near the root of one family at one degree.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NearRoot {
    /// The family.
    pub family: Family,
    /// Its degree.
    pub degree: usize,
    /// One curve per method.
    pub series: Vec<MethodSeries>,
}

/// Max relative error vs degree for one family.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ByDegree {
    /// The family.
    pub family: Family,
    /// One curve per method (x = degree).
    pub series: Vec<MethodSeries>,
}

/// The closing figure for one method.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClosingRow {
    /// The method.
    pub method: Method,
    /// Max relative error over the grid (`t ≠ ½`).
    pub max_rel_error: f64,
    /// Where it occurred.
    pub at_t: f64,
    /// Max relative error over the grid points with `|t − ½| ≥ 0.1`.
    pub max_rel_error_away: f64,
}

/// The documented limitation: compensated result exactly 0 near a multiple
/// root while `p(t) ≠ 0`, with the bound still holding (on `(t − ¾)⁷(t − 1)`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ZeroResultCase {
    /// Degree of the polynomial.
    pub degree: usize,
    /// The point.
    pub t: f64,
    /// The exact value, 17 digits.
    pub exact: String,
    /// The compensated value.
    pub compensated: f64,
    /// Its running bound.
    pub bound: f64,
    /// The bound holds (exactly decided).
    pub holds: bool,
}

/// Everything the report shows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BezierEvalData {
    /// The sizes used.
    pub params: BezierEvalParams,
    /// Relative error vs t near a root.
    pub near_root: Vec<NearRoot>,
    /// Max relative error vs degree.
    pub by_degree: Vec<ByDegree>,
    /// Error vs condition number (x = cond_B).
    pub scatter: Vec<MethodSeries>,
    /// Bound statistics.
    pub bounds: Vec<BoundStats>,
    /// Max relative error on `(t − ½)^20` over `[0, 1]`.
    pub closing: Vec<ClosingRow>,
    /// The zero-result limitation, if found on the near-root grid.
    pub zero_result: Option<ZeroResultCase>,
}

/// Errors of the study.
pub type StudyError = EvalError;

/// Relative errors of every method at every `t` (`p(t) = 0` points skipped).
fn series_over(
    coeffs: &[f64],
    ts: &[f64],
    x_of: impl Fn(f64, &Measured) -> f64 + Sync,
) -> Result<Vec<MethodSeries>, EvalError> {
    let (prep, exact) = prepared(coeffs)?;
    Method::all()
        .map(|method| {
            let points = ts
                .par_iter()
                .map(|&t| measure(&prep, &exact, method, t).map(|m| (t, m)))
                .collect::<Result<Vec<_>, _>>()?
                .into_iter()
                .filter(|(_, m)| m.abs_value != 0)
                .map(|(t, m)| ErrorPoint {
                    x: x_of(t, &m),
                    rel_error: m.rel_error(),
                })
                .collect();
            Ok(MethodSeries { method, points })
        })
        .collect()
}

fn near_root(params: &BezierEvalParams) -> Result<Vec<NearRoot>, EvalError> {
    let cases = [(Family::HalfPower, 7usize), (Family::NearMultipleRoot, 8)];
    cases
        .iter()
        .map(|&(family, degree)| {
            let root = family.root().unwrap_or(0.5);
            let m = params.near_root_points;
            let ts: Vec<f64> = (0..m)
                .map(|k| root - 0.05 + 0.1 * k as f64 / (m - 1) as f64)
                .collect();
            let series = series_over(&family.coeffs(degree, 0), &ts, |t, _| t)?;
            Ok(NearRoot {
                family,
                degree,
                series,
            })
        })
        .collect()
}

fn by_degree(params: &BezierEvalParams) -> Result<Vec<ByDegree>, EvalError> {
    [Family::Random, Family::Wilkinson, Family::HalfPower]
        .iter()
        .map(|&family| {
            let per_degree = (1..=params.max_degree)
                .into_par_iter()
                .map(|n| {
                    let mut g = SplitMix64::new(0xB0B + n as u64);
                    let ts: Vec<f64> = (0..params.degree_samples).map(|_| g.unit()).collect();
                    let s = series_over(&family.coeffs(n, 17), &ts, |_, _| n as f64)?;
                    Ok(s.into_iter()
                        .map(|ms| ms.points.iter().map(|p| p.rel_error).fold(0.0, f64::max))
                        .collect::<Vec<f64>>())
                })
                .collect::<Result<Vec<_>, EvalError>>()?;
            let series = Method::all()
                .enumerate()
                .map(|(k, method)| MethodSeries {
                    method,
                    points: per_degree
                        .iter()
                        .enumerate()
                        .map(|(i, row)| ErrorPoint {
                            x: (i + 1) as f64,
                            rel_error: row[k],
                        })
                        .collect(),
                })
                .collect();
            Ok(ByDegree { family, series })
        })
        .collect()
}

fn scatter(params: &BezierEvalParams) -> Result<Vec<MethodSeries>, EvalError> {
    let mut g = SplitMix64::new(0x5CA7);
    let cases: Vec<(Vec<f64>, f64)> = (0..params.scatter_cases)
        .map(|_| random_case(&mut g, 25, false))
        .collect();
    let measured: Vec<Vec<(f64, f64)>> = cases
        .par_iter()
        .map(|(coeffs, t)| {
            let (prep, exact) = prepared(coeffs)?;
            Method::all()
                .map(|m| measure(&prep, &exact, m, *t).map(|x| (x.cond(), x.rel_error())))
                .collect::<Result<Vec<_>, _>>()
        })
        .collect::<Result<_, EvalError>>()?;
    Ok(Method::all()
        .enumerate()
        .map(|(k, method)| MethodSeries {
            method,
            points: measured
                .iter()
                .map(|row| row[k])
                .filter(|(c, _)| c.is_finite())
                .map(|(x, rel_error)| ErrorPoint { x, rel_error })
                .collect(),
        })
        .collect())
}

/// The closing figure: every method on `(t − ½)^20` at `t = k/N`, `t ≠ ½`.
pub fn closing(grid: usize) -> Result<Vec<ClosingRow>, EvalError> {
    let coeffs = Family::HalfPower.coeffs(20, 0);
    let ts: Vec<f64> = (0..=grid).map(|k| k as f64 / grid as f64).collect();
    let series = series_over(&coeffs, &ts, |t, _| t)?;
    Ok(series
        .into_iter()
        .map(|s| {
            let worst = s.points.iter().fold((0.0f64, 0.0), |w, p| {
                if p.rel_error > w.0 {
                    (p.rel_error, p.x)
                } else {
                    w
                }
            });
            let away = s
                .points
                .iter()
                .filter(|p| (p.x - 0.5).abs() >= 0.1)
                .fold(0.0f64, |w, p| w.max(p.rel_error));
            ClosingRow {
                method: s.method,
                max_rel_error: worst.0,
                at_t: worst.1,
                max_rel_error_away: away,
            }
        })
        .collect())
}

/// Searches `(t − ¾)⁷ (t − 1)` at `t = ¾ + k·2⁻³⁰` for a point where the
/// compensated result is exactly 0 but `p(t) ≠ 0` (the documented
/// limitation).
pub fn find_zero_result() -> Result<Option<ZeroResultCase>, EvalError> {
    let coeffs = jiang_example();
    let (prep, exact) = prepared(&coeffs)?;
    for k in 1..20_000 {
        let t = 0.75 + k as f64 * 2f64.powi(-30);
        let m = measure(&prep, &exact, Method::Compensated, t)?;
        if m.eval.value == 0.0 && m.abs_value != 0 {
            let ex = exact.value(&Rational::from_f64(t).expect("finite"));
            return Ok(Some(ZeroResultCase {
                degree: coeffs.len() - 1,
                t,
                exact: splinelab::scalar::decimal_string(&rug::Float::with_val(200, &ex), 17),
                compensated: m.eval.value,
                bound: m.eval.bound,
                holds: m.running_holds(),
            }));
        }
    }
    Ok(None)
}

/// Runs the whole study.
pub fn run_bezier_eval(params: &BezierEvalParams) -> Result<BezierEvalData, EvalError> {
    let bounds = check_bounds(params.bound_cases, 20, 0xC0FFEE)?
        .into_iter()
        .flat_map(|(m, run, pri)| {
            let mut v = vec![run.stats(m, "running")];
            if pri.counts().0 > 0 {
                v.push(pri.stats(m, "a priori"));
            }
            v
        })
        .collect();
    Ok(BezierEvalData {
        params: *params,
        near_root: near_root(params)?,
        by_degree: by_degree(params)?,
        scatter: scatter(params)?,
        bounds,
        closing: closing(params.closing_grid)?,
        zero_result: find_zero_result()?,
    })
}
