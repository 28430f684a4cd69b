//! `splinelab interpolate`: the spline interpolant of an N-D array evaluated
//! at given points (scipy.ndimage's `map_coordinates` with `prefilter=True`),
//! any degree 0..=199 (0: the nearest sample, 1: multilinear, no prefilter,
//! as scipy), exact or truncated coefficients, f32, f64 or MPFR; with
//! `--coeffs` the input already holds the coefficients (scipy's
//! `prefilter=False`). NaN/±inf samples by `--nan-policy`
//! ([`super::nan_io`]).
//!
//! Points are sample indices, one row per point: shape `(k, ndim)`, or
//! `(k,)` for a 1-D array (scipy's own layout is the transpose, `(ndim, k)`).
//! Points outside the grid are allowed; the mode defines the value there
//! (folded for mirror/reflect/grid-wrap; for nearest and grid-constant the
//! exact spline of the edge- or constant-extended signal, which scipy
//! approximates by padding 12 samples).

use super::engine_io::{
    EngineArgs, Plan, Working, check_conditioning, engine_error, estimate, options, plan,
    to_working, write_result,
};
use super::nan_io::{NanSummary, eval_reach, with_summary};
use crate::array_io::read_array;
use crate::error::CliError;
use crate::input::input_error;
use crate::outln;
use crate::output::emit;
use crate::path_text::path_text;
use crate::with_real;
use clap::Args;
use ndarray::Array2;
use serde_json::json;
use splinelab::prelude::{Interpolant, Real};
use std::path::{Path, PathBuf};

/// Arguments of `splinelab interpolate`.
#[derive(Debug, Args)]
pub struct InterpolateArgs {
    /// The engine options.
    #[command(flatten)]
    pub engine: EngineArgs,
    /// The points: shape (k, ndim) in sample-index coordinates, or (k,) for 1-D data.
    #[arg(long)]
    pub at: PathBuf,
    /// The input holds spline coefficients already (scipy's prefilter=False):
    /// they are extended by the mode and evaluated as given.
    #[arg(long)]
    pub coeffs: bool,
}

/// Runs `splinelab interpolate` on the global route (the caller offers the
/// local route first, issue 45).
pub fn run(args: &InterpolateArgs) -> Result<(), CliError> {
    let plan = plan(&args.engine, 0)?;
    // The user's --tol (plan.route also carries local's default tolerance).
    if args.coeffs && args.engine.tol.is_some() {
        return Err(CliError::invalid(
            "--tol",
            "does not apply with --coeffs (no prefilter runs)",
        ));
    }
    // Far grid-constant points need no clamp here: Mode::fold_coordinate
    // brings them to ±2^40 (same value, no cell-index overflow).
    let points = read_points(&args.at, plan.data.ndim())?;
    let m = (plan.degree + 1) as f64;
    let ndim = plan.data.ndim() as i32;
    let per_point = m.powi(ndim) + ndim as f64 * m * m;
    let what = format!("interpolation at {} points", points.nrows());
    let _spinner = args.engine.budget.check(&estimate(
        &plan,
        ndim as usize,
        points.nrows() as f64 * per_point,
        &what,
    ))?;
    let (bound, nan) = match plan.working {
        Working::F32 => compute::<f32>(&plan, args, &points)?,
        Working::Prec(p) => with_real!(p, T => compute::<T>(&plan, args, &points)?),
    };
    let e = &args.engine;
    let mut text = String::new();
    outln!(
        text,
        "interpolate: shape {:?}, degree {}, mode {}, {} points in {}",
        plan.data.shape(),
        plan.degree,
        e.mode,
        points.nrows(),
        plan.working.name()
    );
    if plan.route != splinelab::prelude::Route::Exact && !args.coeffs {
        outln!(
            text,
            "coefficients     truncated, bound per axis {bound:e} (·max|s|)"
        );
    }
    nan.lines(&mut text, "values");
    outln!(text, "wrote            {}", path_text(&e.output));
    emit(&text)
}

fn compute<T: Real + Send + Sync>(
    plan: &Plan,
    args: &InterpolateArgs,
    points: &Array2<f64>,
) -> Result<(f64, NanSummary), CliError> {
    let e = &args.engine;
    let data = to_working::<T>(&plan.data);
    let f = if args.coeffs {
        Interpolant::from_coefficients_with(&data, options(plan, e))
    } else {
        if plan.degree >= 1 {
            check_conditioning::<T>(plan)?;
        }
        Interpolant::new(&data, options(plan, e))
    }
    .map_err(|err| engine_error(&e.input, err))?;
    let mut out = vec![T::zero(); points.nrows()];
    f.eval_many(points.view(), &mut out)
        .map_err(|err| input_error(&args.at, err.to_string()))?;
    let (reach, bound) = eval_reach::<T>(plan, e, !args.coeffs)?;
    let nan = NanSummary::of(plan, &out, reach, bound);
    let header = json!({
        "degree": plan.degree,
        "mode": e.mode.name(),
        "bound_per_axis": f.truncation_bound(),
    });
    write_result(
        plan,
        &e.output,
        &[out.len()],
        &out,
        with_summary(header, &nan),
    )?;
    Ok((f.truncation_bound(), nan))
}

/// Reads the points: `(k, ndim)`, or `(k,)` when `ndim = 1`; every
/// coordinate finite.
pub fn read_points(path: &Path, ndim: usize) -> Result<Array2<f64>, CliError> {
    super::engine_io::check_input_file(path)?;
    let a = read_array(path)?;
    let rows = match a.shape.as_slice() {
        [k] if ndim == 1 => *k,
        [k, n] if *n == ndim => *k,
        s => {
            return Err(input_error(
                path,
                format!(
                    "points of shape {s:?} for a {ndim}-D array: expected (k, {ndim}){}",
                    if ndim == 1 { " or (k,)" } else { "" }
                ),
            ));
        }
    };
    if let Some((i, x)) = a.data.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(input_error(
            path,
            format!(
                "point {} coordinate {} is {x} (coordinates must be finite)",
                i / ndim.max(1),
                i % ndim.max(1),
            ),
        ));
    }
    Array2::from_shape_vec((rows, ndim), a.data).map_err(|e| input_error(path, e.to_string()))
}
