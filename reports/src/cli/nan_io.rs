//! `--nan-policy` of `prefilter`, `interpolate` and `resample` (issue 37):
//! the option (the engine's [`NanPolicy`] names), the tolerance `local`
//! runs with when `--tol` is not given, and the summary of what the
//! non-finite samples did (how many outputs are NaN, how far a missing
//! sample reaches), on stdout and in the `.json` output.

use super::engine_io::{EngineArgs, LOCAL_TOL, Plan, engine_error};
use crate::error::CliError;
use crate::outln;
use serde_json::{Value, json};
use splinelab::ndimage::missing::local_bound;
use splinelab::prelude::{LineFilter, NanPolicy, Real, Route, nan_reach};

/// How far one missing sample reaches into the results.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reach {
    /// Every line through it along each filtered axis (`propagate` with a
    /// prefilter, scipy's pattern: after filtering every axis, all of it).
    Lines,
    /// At most this many samples away along every axis (`local`'s certified
    /// reach, or the spline's own window where no prefilter runs).
    Within(usize),
}

impl Reach {
    fn json(self) -> Value {
        match self {
            Reach::Lines => json!("lines"),
            Reach::Within(r) => json!(r),
        }
    }

    fn text(self) -> String {
        match self {
            Reach::Lines => {
                "every line through it along each filtered axis (scipy's pattern)".into()
            }
            Reach::Within(0) => "only its own position (no prefilter)".into(),
            Reach::Within(1) => "at most 1 sample along each axis".into(),
            Reach::Within(r) => format!("at most {r} samples along each axis"),
        }
    }
}

/// What the non-finite samples did in one run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NanSummary {
    /// The policy.
    pub policy: NanPolicy,
    /// The prefilter's tolerance (none: the exact route).
    pub tol: Option<f64>,
    /// Non-finite samples (or given coefficients) in the input.
    pub missing: usize,
    /// Non-finite results (NaN, or ±inf where an infinite sample is read
    /// with weight one by degrees 0 and 1).
    pub non_finite: usize,
    /// Results written.
    pub total: usize,
    /// How far a missing sample reaches.
    pub reach: Reach,
    /// Under `local`: `local_bound · max|finite sample|`, how far a result
    /// outside the reach may be from the exact spline of the data with the
    /// missing samples filled by any values of at most that magnitude.
    pub bound: Option<f64>,
}

impl NanSummary {
    /// The summary of `results` of the run `plan`.
    pub fn of<T: Real>(plan: &Plan, results: &[T], reach: Reach, bound: Option<f64>) -> Self {
        let policy = plan.nan_policy;
        NanSummary {
            policy,
            tol: tol_of(plan.route),
            missing: plan.missing,
            non_finite: results.iter().filter(|x| !x.is_finite()).count(),
            total: results.len(),
            reach,
            bound: bound.filter(|_| policy == NanPolicy::Local),
        }
    }

    /// The fields added to the `.json` output.
    pub fn json(&self) -> Value {
        json!({
            "nan_policy": self.policy.name(),
            "tol": self.tol,
            "missing_samples": self.missing,
            "non_finite_outputs": self.non_finite,
            "nan_reach": self.reach.json(),
            "local_bound": self.bound,
        })
    }

    /// The summary lines on stdout; `what` names the results.
    pub fn lines(&self, text: &mut String, what: &str) {
        if self.missing == 0 {
            outln!(
                text,
                "nan policy       {}: every sample finite",
                self.policy
            );
            return;
        }
        outln!(
            text,
            "nan policy       {}: {} sample{} not finite; {} of {} {what} NaN or ±inf",
            self.policy,
            self.missing,
            if self.missing == 1 { "" } else { "s" },
            self.non_finite,
            self.total
        );
        // A positive bound: a truncated prefilter certified the reach.
        let certified = self.bound.filter(|b| *b > 0.0).and(self.tol);
        let tol = certified.map_or(String::new(), |t| format!(" (certified for tol {t:e})"));
        outln!(
            text,
            "nan reach        a missing sample reaches {}{tol}",
            self.reach.text()
        );
        if certified.is_none() {
            return;
        }
        if let Some(b) = self.bound {
            outln!(
                text,
                "outside reach    within {b:e} of the exact spline with the missing samples filled by any \
                 values of at most max|finite sample|"
            );
        }
    }
}

/// Combines a command's JSON header with the summary's fields.
pub fn with_summary(mut header: Value, nan: &NanSummary) -> Value {
    if let (Some(h), Value::Object(n)) = (header.as_object_mut(), nan.json()) {
        h.extend(n);
    }
    header
}

/// The largest finite `|s|` of the samples: the scale of `local`'s bound.
pub fn max_finite(plan: &Plan) -> f64 {
    plan.data
        .iter()
        .filter(|x| x.is_finite())
        .fold(0.0, |m, x| m.max(x.abs()))
}

/// How far a missing sample reaches into interpolated values, and under
/// `local` the bound outside the reach (`local_bound` over every axis,
/// times [`max_finite`]). Without a prefilter (degrees 0 and 1, or
/// `--coeffs`) an output reads only its window of `⌊d/2⌋ + 1` samples per
/// axis ([`nan_reach`]'s window) and nothing beyond it: bound 0.
pub fn eval_reach<T: Real>(
    plan: &Plan,
    args: &EngineArgs,
    prefilter: bool,
) -> Result<(Reach, Option<f64>), CliError> {
    let d = plan.degree;
    let tol = tol_of(plan.route).unwrap_or(LOCAL_TOL);
    if !prefilter || d < 2 {
        return Ok((Reach::Within(d as usize / 2 + 1), Some(0.0)));
    }
    if plan.nan_policy != NanPolicy::Local {
        return Ok((Reach::Lines, None));
    }
    let engine = |e| engine_error(&args.input, e);
    let filter =
        LineFilter::<T>::new(&plan.family, args.mode, args.cval, plan.route).map_err(engine)?;
    let bound = local_bound(&filter, plan.data.ndim()) * max_finite(plan);
    Ok((
        Reach::Within(nan_reach(d, tol).map_err(engine)?),
        Some(bound),
    ))
}

/// The tolerance of a route (none for the exact one).
fn tol_of(route: Route) -> Option<f64> {
    match route {
        Route::Truncated { tol } | Route::Convolution { tol } => Some(tol),
        Route::Exact => None,
    }
}
