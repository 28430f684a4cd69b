//! `splinelab prefilter`: the interpolation coefficients of an N-D array of
//! samples (scipy.ndimage's `spline_filter`, or `spline_filter1d` with
//! `--axis`), any degree 1..=199, exact or truncated to a certified width,
//! in f32, f64 or MPFR; NaN/±inf samples by `--nan-policy`
//! ([`super::nan_io`]). See [`super::engine_io`] for the options.

use super::engine_io::{
    EngineArgs, Plan, Working, check_conditioning, engine_error, estimate, plan, to_working,
    write_result,
};
use super::nan_io::{NanSummary, Reach, max_finite, with_summary};
use crate::error::CliError;
use crate::outln;
use crate::output::emit;
use crate::path_text::path_text;
use crate::with_real;
use clap::Args;
use serde_json::json;
use splinelab::ndimage::alloc::try_standard_layout;
use splinelab::ndimage::missing::local_bound;
use splinelab::prelude::{LineFilter, NanPolicy, Real, spline_filter, spline_filter1d};

/// Arguments of `splinelab prefilter`.
#[derive(Debug, Args)]
pub struct PrefilterArgs {
    /// The engine options.
    #[command(flatten)]
    pub engine: EngineArgs,
    /// Filter along this axis only (scipy's `spline_filter1d`); default every axis.
    #[arg(long, value_parser = super::whole::<usize>)]
    pub axis: Option<usize>,
}

/// What a run reports besides the file.
struct Outcome {
    half_width: Option<usize>,
    bound: f64,
    amplification: f64,
    nan: NanSummary,
}

/// Runs `splinelab prefilter`.
pub fn run(args: &PrefilterArgs) -> Result<(), CliError> {
    let plan = plan(&args.engine, 1)?;
    let ndim = plan.data.ndim();
    if let Some(a) = args.axis
        && a >= ndim
    {
        return Err(CliError::invalid(
            "--axis",
            format!("{a} is out of range for an array of {ndim} dimensions"),
        ));
    }
    let axes = if args.axis.is_some() { 1 } else { ndim };
    let _spinner = args
        .engine
        .budget
        .check(&estimate(&plan, axes, 0.0, "prefilter"))?;
    let out = match plan.working {
        Working::F32 => compute::<f32>(&plan, args, axes)?,
        Working::Prec(p) => with_real!(p, T => compute::<T>(&plan, args, axes)?),
    };
    report(&plan, args, axes, &out)
}

fn compute<T: Real + Send + Sync>(
    plan: &Plan,
    args: &PrefilterArgs,
    axes: usize,
) -> Result<Outcome, CliError> {
    let amplification = check_conditioning::<T>(plan)?;
    let e = &args.engine;
    let filter = LineFilter::<T>::new(&plan.family, e.mode, e.cval, plan.route)
        .and_then(|f| f.with_nan_policy(plan.nan_policy))
        .map_err(|err| engine_error(&e.input, err))?;
    let mut a = to_working::<T>(&plan.data);
    // Degree 1 has no prefilter: scipy copies the samples. The engine's
    // order-2 filter is the identity on finite samples, but its NaN masks
    // are those of a filter (a whole line under propagate, a certified
    // width of 1 under local), so it is not run.
    if plan.degree >= 2 {
        match args.axis {
            Some(axis) => spline_filter1d(&mut a, axis, &filter),
            None => spline_filter(&mut a, &filter),
        }
        .map_err(|err| engine_error(&e.input, err))?;
    }
    let values =
        try_standard_layout(&a, "the coefficients").map_err(|err| engine_error(&e.input, err))?;
    let values = values.as_slice().ok_or_else(|| {
        CliError::numerical("the coefficients are not in C order after the copy into C order")
    })?;
    let nan = NanSummary::of(
        plan,
        values,
        reach(plan, &filter),
        Some(local_bound(&filter, axes) * max_finite(plan)),
    );
    let header = json!({
        "degree": plan.degree,
        "mode": e.mode.name(),
        "half_width": filter.half_width(),
        "bound_per_axis": filter.bound(),
    });
    write_result(
        plan,
        &e.output,
        a.shape(),
        values,
        with_summary(header, &nan),
    )?;
    Ok(Outcome {
        half_width: filter.half_width(),
        bound: filter.bound(),
        amplification,
        nan,
    })
}

/// How far a missing sample reaches into the coefficients: the certified
/// half-width under `local`, every filtered line under `propagate` (degree
/// 1 has no prefilter: the coefficients are the samples).
fn reach<T: Real>(plan: &Plan, filter: &LineFilter<T>) -> Reach {
    match (plan.nan_policy, filter.half_width()) {
        _ if plan.degree < 2 => Reach::Within(0),
        (NanPolicy::Local, Some(n)) => Reach::Within(n),
        _ => Reach::Lines,
    }
}

/// The summary on stdout: route, width and bound, where the file went.
fn report(plan: &Plan, args: &PrefilterArgs, axes: usize, out: &Outcome) -> Result<(), CliError> {
    let e = &args.engine;
    let mut text = String::new();
    outln!(
        text,
        "prefilter: shape {:?}, degree {} (order m = {}), mode {}, {} in {}",
        plan.data.shape(),
        plan.degree,
        plan.degree + 1,
        e.mode,
        match args.axis {
            Some(a) => format!("axis {a}"),
            None => "every axis".into(),
        },
        plan.working.name()
    );
    match out.half_width {
        None => outln!(text, "route            exact (recursive filter)"),
        Some(n) => {
            let a = out.amplification;
            let total = (a + out.bound).powi(axes as i32) - a.powi(axes as i32);
            outln!(
                text,
                "route            truncated to half-width n = {n} (certified for --tol: a long line in blocks overlapping by n, else the exact recursion)"
            );
            outln!(
                text,
                "bound per axis   {:e}  (|c_truncated − c_exact| ≤ bound·max|s| along one axis)",
                out.bound
            );
            if axes > 1 {
                outln!(
                    text,
                    "bound, {axes} axes   {total:e}  ((A + b)^D − A^D, A = 1/|V(−1)| = {a:.3e})"
                );
            }
        }
    }
    outln!(
        text,
        "conditioning     u·1/|V(−1)| = {:.1e} (estimated relative error of the coefficients)",
        out.amplification * (-(plan.working.bits() as f64)).exp2()
    );
    out.nan.lines(&mut text, "coefficients");
    outln!(text, "wrote            {}", path_text(&e.output));
    emit(&text)
}
