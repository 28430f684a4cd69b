//! S-spline studies (seed 000): accuracy of the coefficient methods in f64
//! and MPFR, decay of `|c_n|`, truncation error measures, basis shapes, the
//! recommended-width table and the f64 saturation widths.
//!
//! References: the partial-fraction coefficients in `REF_BITS`-bit MPFR,
//! themselves checked against closed forms (eq 18, 29), published poles and
//! the two other methods in the tests (`verify/tests/sspline_*.rs`).

use crate::metrics::{relative_error, ulps_f64};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use splinelab::scalar::{Mp, Real};
use splinelab::sspline::{
    CoefficientMethod, Criterion, SplineFamily, SsplineError, TruncatedBasis, TruncationAnalysis,
    WidthChooser, coefficients, f64_saturation_width,
};

/// Bits of the MPFR reference.
pub const REF_BITS: u32 = 512;
/// Reference scalar.
pub type Reference = Mp<REF_BITS>;
/// Bits of the MPFR working precision whose method agreement is measured.
pub const MP_BITS: u32 = 192;
/// Working MPFR scalar of the agreement study.
pub type Working = Mp<MP_BITS>;
/// Precision of the truncation error measures.
pub type Measure = Mp<128>;

/// What the study sweeps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SsplineParams {
    /// Orders of the accuracy, decay and width studies.
    pub orders: Vec<u32>,
    /// Coefficients measured, `c_0..c_{count−1}`.
    pub count: usize,
    /// Tensions β2 (decimal text, exact) of the error, shape and width studies.
    pub tensions: Vec<String>,
    /// Tolerances of the width table.
    pub tolerances: Vec<f64>,
    /// Largest half-width in the error-measure curves.
    pub max_n: usize,
    /// Orders of the width table (with every tension).
    pub width_orders: Vec<u32>,
}

impl SsplineParams {
    /// The full sweep: orders 2..24, `c_0..c_60`, five tensions, 1e-3..1e-15.
    pub fn full() -> Self {
        SsplineParams {
            orders: (2..=24).collect(),
            count: 61,
            tensions: ["0", "1", "5", "10", "50"].map(String::from).to_vec(),
            tolerances: vec![1e-3, 1e-6, 1e-9, 1e-12, 1e-15],
            max_n: 24,
            width_orders: (2..=24).collect(),
        }
    }

    /// A short sweep for the quick report.
    pub fn quick() -> Self {
        SsplineParams {
            orders: vec![2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 24],
            max_n: 16,
            width_orders: vec![2, 3, 4, 5, 6, 8, 12],
            ..Self::full()
        }
    }
}

/// Accuracy of one coefficient method for one order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MethodAccuracy {
    /// B-spline order.
    pub order: u32,
    /// Method name.
    pub method: String,
    /// Worst f64 error over `c_0..c_{count−1}` (normal values only), in ulps;
    /// `None` when the method fails in f64 (message in `f64_failure`).
    pub f64_max_ulps: Option<f64>,
    /// Decimal digits lost in f64: `log10(max(ulps, 1))`.
    pub f64_digits_lost: Option<f64>,
    /// Why f64 failed, if it did.
    pub f64_failure: Option<String>,
    /// Correct bits in `Working` (192-bit) MPFR: `−log2(max_i rel_i)`.
    pub mp_bits: f64,
    /// Largest componentwise condition number `cond_i` over the range.
    pub cond_max: f64,
    /// Correct bits relative to the conditioning: `−log2(max_i rel_i / cond_i)`
    /// (≈ `MP_BITS` for a backward-stable method).
    pub mp_bits_conditioned: f64,
}

/// `|c_n|` against `n` for one order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DecaySeries {
    /// B-spline order.
    pub order: u32,
    /// `(n, |c_n|)` for the non-zero coefficients.
    pub points: Vec<(usize, f64)>,
}

/// The four error measures at one half-width.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ErrorRow {
    /// Half-width.
    pub n: usize,
    /// `|c_n|`.
    pub coeff: f64,
    /// Knot interpolation error.
    pub knot: f64,
    /// Uniform (worst curve) error.
    pub uniform: f64,
    /// Analytic tail bound.
    pub bound: f64,
}

/// Error measures against `n` for one family.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ErrorCurve {
    /// The family, as text.
    pub family: String,
    /// One row per `n = 1..=max_n`.
    pub rows: Vec<ErrorRow>,
}

/// Samples of a truncated basis `S_{0,4}(x, β2)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BasisShape {
    /// Tension β2 (decimal text).
    pub tension: String,
    /// Half-width (smallest with `|c_n| < 1e-3`).
    pub n: usize,
    /// `(x, S_n(x))`.
    pub points: Vec<(f64, f64)>,
}

/// One entry of the recommended-width table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WidthRow {
    /// The family, as text.
    pub family: String,
    /// Tolerance.
    pub tol: f64,
    /// Criterion name.
    pub criterion: String,
    /// Chosen half-width.
    pub n: usize,
    /// Error at `n`.
    pub achieved: f64,
    /// Tail bound at `n` (rounded up).
    pub bound: f64,
}

/// The f64 saturation width of one family.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SaturationRow {
    /// The family, as text.
    pub family: String,
    /// Smallest `n` whose tail bound is ≤ 2^−54.
    pub n: usize,
}

/// Everything the report section shows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SsplineStudy {
    /// The sweep.
    pub params: SsplineParams,
    /// Method accuracy per order.
    pub accuracy: Vec<MethodAccuracy>,
    /// `|c_n|` decay per order.
    pub decay: Vec<DecaySeries>,
    /// Error measures for the cubic and each tension.
    pub errors: Vec<ErrorCurve>,
    /// Basis shapes `S_{0,4}(x, β2)`.
    pub shapes: Vec<BasisShape>,
    /// The width table.
    pub widths: Vec<WidthRow>,
    /// f64 saturation widths.
    pub saturation: Vec<SaturationRow>,
}

/// Runs the whole study (rayon-parallel over orders and families).
pub fn run_sspline(params: &SsplineParams) -> Result<SsplineStudy, SsplineError> {
    let tension_families = params
        .tensions
        .iter()
        .map(|t| SplineFamily::parse_tension(t))
        .collect::<Result<Vec<_>, _>>()?;
    let accuracy = params
        .orders
        .par_iter()
        .map(|m| order_accuracy(&SplineFamily::order(*m)?, params.count))
        .collect::<Result<Vec<_>, _>>()?
        .concat();
    let decay = params
        .orders
        .iter()
        .map(|m| decay_series(*m, params.count))
        .collect::<Result<Vec<_>, _>>()?;
    let mut curve_families = vec![SplineFamily::Order(4)];
    curve_families.extend(
        tension_families
            .iter()
            .filter(|f| f.tension().is_some_and(|t| *t != 0))
            .cloned(),
    );
    let errors = curve_families
        .par_iter()
        .map(|f| error_curve(f, params.max_n))
        .collect::<Result<Vec<_>, _>>()?;
    let shapes = tension_families
        .iter()
        .zip(&params.tensions)
        .map(|(f, t)| basis_shape(f, t))
        .collect::<Result<Vec<_>, _>>()?;
    let mut width_families: Vec<SplineFamily> = params
        .width_orders
        .iter()
        .map(|m| SplineFamily::Order(*m))
        .collect();
    width_families.extend(tension_families);
    let widths = width_families
        .par_iter()
        .map(|f| width_rows(f, &params.tolerances))
        .collect::<Result<Vec<_>, _>>()?
        .concat();
    let saturation = width_families
        .iter()
        .map(|f| {
            Ok(SaturationRow {
                family: f.to_string(),
                n: f64_saturation_width(f)?,
            })
        })
        .collect::<Result<Vec<_>, SsplineError>>()?;
    Ok(SsplineStudy {
        params: params.clone(),
        accuracy,
        decay,
        errors,
        shapes,
        widths,
        saturation,
    })
}

/// The reference coefficients `c_0..c_{count−1}` (partial fractions in
/// `REF_BITS`-bit MPFR).
pub fn reference_coefficients(
    family: &SplineFamily,
    count: usize,
) -> Result<Vec<Reference>, SsplineError> {
    coefficients(family, count, CoefficientMethod::PartialFractions)
}

/// Componentwise condition numbers of `c_i` under relative perturbations of
/// the node values: `cond_i = (|A⁻¹| |A| |c|)_i / |c_i|` with `A` the
/// bi-infinite Toeplitz matrix `β(j − k)` (Skeel; Higham, *Accuracy and
/// Stability*, §7.2), `|A⁻¹|_{ij} = |c_{i−j}|`. Evaluated in f64 from the
/// reference coefficients (an estimate needs no more), the infinite sums
/// cut where `c` is below `2^{−64}` of `c_0`.
pub fn componentwise_condition(
    family: &SplineFamily,
    count: usize,
) -> Result<Vec<f64>, SsplineError> {
    let e = splinelab::sspline::euler_frobenius::PoleExpansion::<Measure>::new(family)?;
    let rho = e.decay_rate().to_f64();
    let extra = if rho > 0.0 {
        (64.0 / -rho.log2()).ceil() as usize
    } else {
        0
    };
    let k = count + extra + family.spline_order() as usize;
    let c: Vec<f64> = coefficients::<Measure>(family, 2 * k + 1, CoefficientMethod::Production)?
        .iter()
        .map(|x| x.to_f64())
        .collect();
    let v: Vec<f64> = splinelab::sspline::node_values::node_values::<f64>(family)?;
    let p = (v.len() / 2) as i64;
    let cat = |i: i64| c.get(i.unsigned_abs() as usize).map_or(0.0, |x| x.abs());
    let kk = k as i64;
    let ac: Vec<f64> = (-2 * kk..=2 * kk)
        .map(|j| (-p..=p).map(|d| v[(p + d) as usize] * cat(j - d)).sum())
        .collect();
    Ok((0..count as i64)
        .map(|i| {
            let s: f64 = (-kk..=kk)
                .map(|j| cat(i - j) * ac[(j + 2 * kk) as usize])
                .sum();
            if c[i as usize] == 0.0 {
                1.0
            } else {
                s / c[i as usize].abs()
            }
        })
        .collect())
}

/// The accuracy of every method for one family (see [`MethodAccuracy`]).
pub fn order_accuracy(
    family: &SplineFamily,
    count: usize,
) -> Result<Vec<MethodAccuracy>, SsplineError> {
    let reference = reference_coefficients(family, count)?;
    let cond = componentwise_condition(family, count)?;
    let order = family.spline_order();
    let methods = CoefficientMethod::INDEPENDENT
        .into_iter()
        .chain([CoefficientMethod::Production]);
    methods
        .map(|method| {
            let (f64_max_ulps, f64_failure) = match coefficients::<f64>(family, count, method) {
                Ok(c) => (Some(max_ulps(&c, &reference)), None),
                Err(e) => (None, Some(e.to_string())),
            };
            let mp: Vec<Working> = coefficients(family, count, method)?;
            let rel: Vec<f64> = mp
                .iter()
                .zip(&reference)
                .map(|(x, r)| {
                    if r.as_float().is_zero() && x.as_float().is_zero() {
                        0.0
                    } else {
                        relative_error(x, &r.to_float())
                    }
                })
                .collect();
            let worst = rel.iter().cloned().fold(0.0, f64::max);
            let worst_cond = rel
                .iter()
                .zip(&cond)
                .map(|(r, c)| r / c)
                .fold(0.0, f64::max);
            Ok(MethodAccuracy {
                order,
                method: method.name().into(),
                f64_max_ulps,
                f64_digits_lost: f64_max_ulps.map(|u| u.max(1.0).log10()),
                f64_failure,
                mp_bits: bits(worst),
                cond_max: cond.iter().cloned().fold(0.0, f64::max),
                mp_bits_conditioned: bits(worst_cond),
            })
        })
        .collect()
}

/// `−log2(rel)`, capped at the working precision for an exact result.
fn bits(rel: f64) -> f64 {
    if rel == 0.0 {
        MP_BITS as f64
    } else {
        -rel.log2()
    }
}

/// Worst distance in ulps over the coefficients that are normal f64 values.
pub fn max_ulps(c: &[f64], reference: &[Reference]) -> f64 {
    c.iter()
        .zip(reference)
        .filter(|(_, r)| r.to_f64().abs() >= f64::MIN_POSITIVE || r.as_float().is_zero())
        .map(|(x, r)| ulps_f64(*x, &r.to_float()))
        .fold(0.0, f64::max)
}

fn decay_series(order: u32, count: usize) -> Result<DecaySeries, SsplineError> {
    let c = reference_coefficients(&SplineFamily::order(order)?, count)?;
    Ok(DecaySeries {
        order,
        points: c
            .iter()
            .enumerate()
            .map(|(n, x)| (n, x.to_f64().abs()))
            .filter(|(_, a)| *a >= f64::MIN_POSITIVE)
            .collect(),
    })
}

/// The four measures for `n = 1..=max_n` (128-bit MPFR, rounded to f64).
pub fn error_curve(family: &SplineFamily, max_n: usize) -> Result<ErrorCurve, SsplineError> {
    let a = TruncationAnalysis::<Measure>::new(family, max_n)?;
    let rows = (1..=max_n)
        .map(|n| {
            let e = a.errors(n);
            ErrorRow {
                n,
                coeff: e.coeff.to_f64(),
                knot: e.knot.to_f64(),
                uniform: e.uniform.to_f64(),
                bound: e.bound.to_f64(),
            }
        })
        .collect();
    Ok(ErrorCurve {
        family: family.to_string(),
        rows,
    })
}

/// `S_{0,4}(x, β2)` truncated at the paper's rule `|c_n| < 1e-3`, sampled
/// at 401 points over its support.
pub fn basis_shape(family: &SplineFamily, tension: &str) -> Result<BasisShape, SsplineError> {
    let n = WidthChooser::new(family, 1e-3)?
        .choose(1e-3, Criterion::Coeff)?
        .n;
    let s = TruncatedBasis::<f64>::new(family, n)?;
    let r = s.support_radius();
    let points = (0..=400)
        .map(|k| {
            let x = -r + 2.0 * r * k as f64 / 400.0;
            (x, s.eval(&x))
        })
        .collect();
    Ok(BasisShape {
        tension: tension.into(),
        n,
        points,
    })
}

fn width_rows(family: &SplineFamily, tolerances: &[f64]) -> Result<Vec<WidthRow>, SsplineError> {
    let min_tol = tolerances.iter().cloned().fold(1.0, f64::min);
    let chooser = WidthChooser::new(family, min_tol)?;
    let mut rows = Vec::new();
    for &tol in tolerances {
        for criterion in Criterion::all() {
            let w = chooser.choose(tol, criterion)?;
            rows.push(WidthRow {
                family: family.to_string(),
                tol,
                criterion: criterion.name().into(),
                n: w.n,
                achieved: w.achieved,
                bound: w.bound,
            });
        }
    }
    Ok(rows)
}
