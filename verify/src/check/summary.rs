//! Per-element errors of a user's results and their summary: ulps in the
//! user's format, relative and absolute error, correct digits, the worst
//! element and, where a boundary is defined, the boundary/interior split.

use super::format::UserFormat;
use super::stable_bound::BOUND_FACTOR;
use crate::metrics::{correct_digits, relative_error};
use rayon::prelude::*;
use rug::Float;
use serde::Serialize;
use std::collections::BTreeMap;

/// Where an element sits, for checks whose error depends on the boundary
/// (the first and last `h` samples of a prefilter) or not.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Region {
    /// Within the horizon `h` of either end.
    Boundary,
    /// Everything else.
    Interior,
}

impl Region {
    /// `"boundary"` or `"interior"`.
    pub fn name(self) -> &'static str {
        match self {
            Region::Boundary => "boundary",
            Region::Interior => "interior",
        }
    }

    /// The region of index `i` among `n`, boundary zone of `h` at each end.
    pub fn of(i: usize, n: usize, h: usize) -> Region {
        if i < h || i + h >= n {
            Region::Boundary
        } else {
            Region::Interior
        }
    }
}

/// The error of one user value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ElementError {
    /// Position in the user's array (flattened, C order).
    pub index: usize,
    /// The user's value.
    pub value: f64,
    /// The reference rounded to f64 (for display; the errors use it unrounded).
    pub reference: f64,
    /// `|x − r|` in ulps of the user's format at `r` (infinite for NaN/inf).
    pub ulps: f64,
    /// `|x − r| / |r|` (`|x − r|` when `r = 0`).
    pub rel: f64,
    /// `|x − r|`.
    pub abs: f64,
    /// `−log10(rel)`, capped at the digits of the format.
    pub digits: f64,
    /// Boundary or interior, where defined.
    pub region: Option<Region>,
    /// The error a backward-stable computation would make here
    /// ([`stable_bound`](super::stable_bound)), where the kind has one.
    pub bound: Option<f64>,
    /// `abs / bound` (0 when both are 0, infinite for a non-finite value).
    pub excess: Option<f64>,
}

impl ElementError {
    /// The element with its stable bound and excess set.
    pub fn with_bound(mut self, bound: f64) -> Self {
        self.excess = Some(excess(self.abs, bound));
        self.bound = Some(bound);
        self
    }
}

/// `error / bound`: 0 for an exact value, infinite for an error where the
/// bound is 0 or for a non-finite value.
pub fn excess(error: f64, bound: f64) -> f64 {
    if error == 0.0 {
        0.0
    } else if error.is_finite() && bound > 0.0 {
        error / bound
    } else {
        f64::INFINITY
    }
}

/// How the default verdict is reached.
#[derive(Debug, Clone, PartialEq)]
pub enum BoundBasis {
    /// Every element carries a stable bound; the text states the bound and
    /// its source.
    PerElement(String),
    /// The kind has no stable bound; the text says why.
    Unavailable(String),
}

/// The element furthest over its stable bound.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorstExcess {
    /// Its index.
    pub index: usize,
    /// `error / bound`.
    pub excess: f64,
    /// Its absolute error.
    pub error: f64,
    /// Its stable bound.
    pub bound: f64,
    /// Its region, where defined.
    pub region: Option<Region>,
}

/// The worst element (largest ulps; the first one on ties).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Worst {
    /// Its index.
    pub index: usize,
    /// Its error in ulps.
    pub ulps: f64,
    /// Its relative error.
    pub rel: f64,
    /// Its absolute error.
    pub abs: f64,
    /// Its region, where defined.
    pub region: Option<Region>,
}

/// The errors of one region.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegionSummary {
    /// Largest error in ulps.
    pub max_ulps: f64,
    /// Median error in ulps.
    pub median_ulps: f64,
    /// Elements in the region.
    pub count: usize,
}

/// The result of a check: the JSON contract of `splinelab check --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckSummary {
    /// The KIND checked (`prefilter`, `coeffs`, …).
    pub kind: String,
    /// The user's format (`f32`/`f64`).
    pub format: UserFormat,
    /// Elements checked.
    pub n: usize,
    /// MPFR bits of the certified reference (`None` for exact rational references).
    pub reference_bits: Option<u32>,
    /// How the reference was made.
    pub reference: String,
    /// The worst element (`None` when `n = 0`).
    pub worst: Option<Worst>,
    /// Boundary/interior summaries, where defined.
    pub regions: Option<BTreeMap<String, RegionSummary>>,
    /// Boundary horizon `h` (samples at each end), where defined.
    pub horizon: Option<usize>,
    /// Fewest correct digits over the elements.
    pub digits_min: f64,
    /// Median error in ulps over all elements.
    pub median_ulps: f64,
    /// The largest absolute error in ulps of the references' scale
    /// `max |r_i|`: the norm-wise view, for results (a recursive filter's)
    /// whose errors are absolute, not relative to each element.
    pub max_ulps_scaled: f64,
    /// Elements whose user value is NaN or infinite.
    pub non_finite: usize,
    /// The `--max-ulps` threshold, if given.
    pub max_ulps: Option<f64>,
    /// Elements over the threshold (0 without one); non-finite values count.
    pub failed: usize,
    /// `"pass"` or `"fail"`.
    pub verdict: String,
    /// What the verdict rests on: `"stable-bound"` (every error within
    /// `bound_factor` × its stable bound, and `--max-ulps` if given),
    /// `"max-ulps"` (the kind has no bound; the explicit threshold only) or
    /// `"finite-only"` (neither: only NaN/inf values fail).
    pub verdict_basis: String,
    /// Why there is no stable-bound verdict (`None` when there is one).
    pub no_verdict_reason: Option<String>,
    /// The stable bound used and its source (`None` without one).
    pub stable_bound: Option<String>,
    /// `K`: the error allowed is `K` × the stable bound.
    pub bound_factor: Option<f64>,
    /// Elements whose error exceeds `K` × their bound (non-finite values count).
    pub over_bound: usize,
    /// The element with the largest `error / bound`.
    pub worst_excess: Option<WorstExcess>,
    /// `log10` of the worst excess, at least 0: the digits lost beyond what
    /// the problem's conditioning explains.
    pub digits_lost: Option<f64>,
    /// Every element's error (not part of the JSON summary: it can be 10⁶ long).
    #[serde(skip)]
    pub elements: Vec<ElementError>,
}

/// How the elements are summarised besides the errors themselves.
#[derive(Debug, Clone)]
pub struct Context<'a> {
    /// The KIND.
    pub kind: &'a str,
    /// The user's format.
    pub format: UserFormat,
    /// Bits of the reference, `None` if exact.
    pub reference_bits: Option<u32>,
    /// Description of the reference.
    pub reference: String,
    /// Boundary horizon, for kinds that have one.
    pub horizon: Option<usize>,
    /// Threshold in ulps.
    pub max_ulps: Option<f64>,
    /// The stable bound the elements carry, or why there is none.
    pub bound: BoundBasis,
}

/// The error of `x` against `r`, in the user's format.
pub fn element_error(
    index: usize,
    x: f64,
    r: &Float,
    format: UserFormat,
    region: Option<Region>,
) -> ElementError {
    let ulps = format.ulps(x, r);
    let rel = relative_error(&x, r);
    let abs = if x.is_finite() {
        Float::with_val(r.prec().max(64), x - r).abs().to_f64()
    } else {
        f64::INFINITY
    };
    ElementError {
        index,
        value: x,
        reference: r.to_f64(),
        ulps,
        rel,
        abs,
        digits: correct_digits(rel, format.digits()),
        region,
        bound: None,
        excess: None,
    }
}

/// Compares the user's values with the references element by element (in
/// parallel) and summarises. `user` and `refs` have equal lengths (the
/// callers check that on the inputs first).
pub fn summarize(ctx: &Context<'_>, user: &[f64], refs: &[Float]) -> CheckSummary {
    let n = user.len();
    let elements: Vec<ElementError> = user
        .par_iter()
        .zip(refs.par_iter())
        .enumerate()
        .map(|(i, (x, r))| {
            let region = ctx.horizon.map(|h| Region::of(i, n, h));
            element_error(i, *x, r, ctx.format, region)
        })
        .collect();
    from_elements(ctx, elements)
}

/// [`summarize`] with every element's stable bound (`bounds[i]` for
/// element `i`).
pub fn summarize_bounded(
    ctx: &Context<'_>,
    user: &[f64],
    refs: &[Float],
    bounds: &[f64],
) -> CheckSummary {
    let n = user.len();
    let elements: Vec<ElementError> = user
        .par_iter()
        .zip(refs.par_iter())
        .zip(bounds.par_iter())
        .enumerate()
        .map(|(i, ((x, r), b))| {
            let region = ctx.horizon.map(|h| Region::of(i, n, h));
            element_error(i, *x, r, ctx.format, region).with_bound(*b)
        })
        .collect();
    from_elements(ctx, elements)
}

/// The summary of already computed element errors.
pub fn from_elements(ctx: &Context<'_>, elements: Vec<ElementError>) -> CheckSummary {
    let worst = elements
        .iter()
        .fold(None::<&ElementError>, |w, e| match w {
            Some(w) if e.ulps <= w.ulps => Some(w),
            _ => Some(e),
        })
        .map(|e| Worst {
            index: e.index,
            ulps: e.ulps,
            rel: e.rel,
            abs: e.abs,
            region: e.region,
        });
    let regions = ctx.horizon.map(|_| {
        [Region::Boundary, Region::Interior]
            .into_iter()
            .map(|reg| {
                let u: Vec<f64> = elements
                    .iter()
                    .filter(|e| e.region == Some(reg))
                    .map(|e| e.ulps)
                    .collect();
                (reg.name().to_string(), region_summary(u))
            })
            .collect()
    });
    // A NaN where the reference is undefined too (outside a B-spline's base
    // interval without extrapolation) is the right answer.
    let non_finite = elements
        .iter()
        .filter(|e| !(e.value.is_finite() || e.value.is_nan() && e.reference.is_nan()))
        .count();
    let failed = match ctx.max_ulps {
        Some(k) => elements
            .iter()
            .filter(|e| e.ulps > k || e.ulps.is_nan())
            .count(),
        None => 0,
    };
    let judged = judge_bounds(ctx, &elements);
    let all = region_summary(elements.iter().map(|e| e.ulps).collect());
    let max_ulps_scaled = scaled_ulps(&elements, ctx.format);
    CheckSummary {
        kind: ctx.kind.into(),
        format: ctx.format,
        n: elements.len(),
        reference_bits: ctx.reference_bits,
        reference: ctx.reference.clone(),
        worst,
        regions,
        horizon: ctx.horizon,
        digits_min: elements
            .iter()
            .map(|e| e.digits)
            .fold(ctx.format.digits(), f64::min),
        median_ulps: all.median_ulps,
        max_ulps_scaled,
        non_finite,
        max_ulps: ctx.max_ulps,
        failed,
        verdict: verdict(failed + non_finite + judged.over_bound),
        verdict_basis: judged.basis.into(),
        no_verdict_reason: judged.reason,
        stable_bound: judged.stable_bound,
        bound_factor: judged.factor,
        over_bound: judged.over_bound,
        digits_lost: judged.worst.as_ref().map(|w| w.excess.log10().max(0.0)),
        worst_excess: judged.worst,
        elements,
    }
}

/// The stable-bound part of a summary.
struct Judged {
    basis: &'static str,
    reason: Option<String>,
    stable_bound: Option<String>,
    factor: Option<f64>,
    over_bound: usize,
    worst: Option<WorstExcess>,
}

/// Counts the elements over `K` × bound and finds the worst excess.
fn judge_bounds(ctx: &Context<'_>, elements: &[ElementError]) -> Judged {
    match &ctx.bound {
        BoundBasis::Unavailable(why) => Judged {
            basis: if ctx.max_ulps.is_some() {
                "max-ulps"
            } else {
                "finite-only"
            },
            reason: Some(why.clone()),
            stable_bound: None,
            factor: None,
            over_bound: 0,
            worst: None,
        },
        BoundBasis::PerElement(text) => {
            // NaN-for-NaN (undefined reference) elements carry no excess.
            let judged = elements
                .iter()
                .filter_map(|e| Some((e, e.excess?, e.bound?)));
            let over_bound = judged
                .clone()
                .filter(|(_, x, _)| x.is_nan() || *x > BOUND_FACTOR)
                .count();
            let worst = judged
                .fold(None::<(&ElementError, f64, f64)>, |w, c| match w {
                    Some(w) if c.1 <= w.1 || c.1.is_nan() => Some(w),
                    _ => Some(c),
                })
                .map(|(e, x, b)| WorstExcess {
                    index: e.index,
                    excess: x,
                    error: e.abs,
                    bound: b,
                    region: e.region,
                });
            Judged {
                basis: "stable-bound",
                reason: None,
                stable_bound: Some(text.clone()),
                factor: Some(BOUND_FACTOR),
                over_bound,
                worst,
            }
        }
    }
}

/// `"pass"` when nothing failed.
pub fn verdict(failures: usize) -> String {
    if failures == 0 { "pass" } else { "fail" }.into()
}

/// `max |x_i − r_i|` in ulps of the format at `max |r_i|` (infinite if a
/// value is not finite; NaN-for-NaN elements are skipped).
fn scaled_ulps(elements: &[ElementError], format: UserFormat) -> f64 {
    let scale = elements
        .iter()
        .filter(|e| e.reference.is_finite())
        .map(|e| e.reference.abs())
        .fold(0.0, f64::max);
    let exp = format.ulp_exp(&Float::with_val(53, scale));
    elements
        .iter()
        .filter(|e| !e.reference.is_nan())
        .map(|e| e.abs)
        .fold(0.0, f64::max)
        / 2f64.powi(exp)
}

fn region_summary(mut u: Vec<f64>) -> RegionSummary {
    u.sort_by(f64::total_cmp);
    let count = u.len();
    let median_ulps = match count {
        0 => 0.0,
        _ if count % 2 == 1 => u[count / 2],
        _ => 0.5 * (u[count / 2 - 1] + u[count / 2]),
    };
    RegionSummary {
        max_ulps: u.last().copied().unwrap_or(0.0),
        median_ulps,
        count,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn worst_median_and_failures() {
        let refs: Vec<Float> = (0..5)
            .map(|i| Float::with_val(128, 1.0 + i as f64))
            .collect();
        let mut user: Vec<f64> = (0..5).map(|i| 1.0 + i as f64).collect();
        user[3] += 2.0 * 4.0 * f64::EPSILON; // 2 ulps at 4
        user[4] = f64::NAN;
        let ctx = Context {
            kind: "t",
            format: UserFormat::F64,
            reference_bits: Some(128),
            reference: "test".into(),
            horizon: Some(1),
            max_ulps: Some(1.0),
            bound: BoundBasis::Unavailable("test".into()),
        };
        let s = summarize(&ctx, &user, &refs);
        let w = s.worst.clone().unwrap();
        assert_eq!((w.index, w.region), (4, Some(Region::Boundary)));
        assert_eq!(s.failed, 2);
        assert_eq!(s.non_finite, 1);
        assert_eq!(s.verdict, "fail");
        let interior = &s.regions.as_ref().unwrap()["interior"];
        assert_eq!((interior.count, interior.max_ulps), (3, 2.0));
    }
}
