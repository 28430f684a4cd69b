//! `splinelab interpolate` on the local route (issue 45): a `.npy` input is
//! memory-mapped (not read whole), its header checked
//! ([`crate::npy_layout::validate`]), viewed in place (`ndarray-npy`'s
//! [`ViewNpyExt`]), and the points evaluated from the samples their windows
//! need ([`splinelab::ndimage::local`]) where that costs less than the
//! global route's prefilter of the whole array ([`RouteCost`]) — or where
//! the file is above the input limit, which the global route cannot read.
//! Only the pages under the windows are read from the file.
//!
//! The same spline as the global route: the engine's modes (exact
//! `nearest` / `grid-constant`), `--tol` the truncation tolerance (without
//! it, the half-width certified below the global route's own rounding,
//! [`default_tol`](splinelab::ndimage::local::default_tol)), `--coeffs`
//! evaluates given coefficients (only each point's support is read). A
//! missing sample reaches only the points whose windows read it, under
//! every `--nan-policy`; under `raise` the global route names the first
//! missing sample of the file, so the local route runs there only for a
//! file above the input limit (and refuses a missing sample a window reads).

use super::engine_io::{LOCAL_TOL, OutputKind, Working, degree_from, output_kind, write_values};
use super::interpolate::{InterpolateArgs, read_points};
use super::prec::Prec;
use crate::error::CliError;
use crate::input::{input_error, max_input_bytes};
use crate::npy_layout::{NpyFloat, validate};
use crate::outln;
use crate::output::emit;
use crate::path_text::path_text;
use ndarray::ArrayViewD;
use ndarray_npy::ViewNpyExt;
use serde_json::json;
use splinelab::ndimage::interpolant::PointRule;
use splinelab::ndimage::local::{LocalOptions, LocalPlan, LocalSpec, LocalStats};
use splinelab::ndimage::samples::SampleSource;
use splinelab::prelude::{NanPolicy, NdimageError, RecursivePrefilter, Route, SplineFamily};
use splinelab::scalar::Real;
use splinelab_verify::check::UserFormat;
use std::fs::File;

/// Runs `interpolate` on the local route where it applies and pays;
/// `Ok(false)`: the global route's turn (not a `.npy`, an MPFR `--prec`, or
/// the global route is cheaper and the file within the input limit).
pub fn try_run(args: &InterpolateArgs) -> Result<bool, CliError> {
    let e = &args.engine;
    let is_npy = e.input.extension().and_then(|x| x.to_str()) == Some("npy");
    if !is_npy || !matches!(e.prec, None | Some(Prec::F64)) {
        return Ok(false);
    }
    let file = File::open(&e.input).map_err(|err| input_error(&e.input, err.to_string()))?;
    let over_limit = file
        .metadata()
        .map_err(|err| input_error(&e.input, err.to_string()))?
        .len()
        > max_input_bytes()?;
    // `raise` names the first missing sample of the whole file (the
    // global route's reader does, before the points are read): the local
    // route only where it must.
    if e.nan_policy == NanPolicy::Raise && !over_limit {
        return Ok(false);
    }
    // SAFETY: the map is read-only and lives only for this call. Another
    // process changing the file while it is mapped changes what is read
    // (any bytes are valid f64/f32 values); truncating it under the map
    // would fault the read, as it would for numpy's `mmap_mode="r"`.
    #[allow(unsafe_code)]
    let map = unsafe { memmap2::Mmap::map(&file) }
        .map_err(|err| input_error(&e.input, format!("cannot memory-map: {err}")))?;
    // The windows' rows are pages far apart: no readahead around them (a
    // hint; where it is refused the reads are the same).
    let _ = map.advise(memmap2::Advice::Random);
    let layout = validate(&map).map_err(|why| input_error(&e.input, why))?;
    let why = |err: ndarray_npy::ViewNpyError| {
        input_error(
            &e.input,
            format!("cannot be viewed in place ({err}); rewrite it little-endian"),
        )
    };
    match (layout.dtype, e.prec) {
        (NpyFloat::F32, None) => {
            let view = ArrayViewD::<f32>::view_npy(&map).map_err(why)?;
            run_on::<f32, _>(args, &view, Working::F32, UserFormat::F32, over_limit)
        }
        (NpyFloat::F32, Some(_)) => {
            let view = ArrayViewD::<f32>::view_npy(&map).map_err(why)?;
            run_on::<f64, _>(
                args,
                &view,
                Working::Prec(Prec::F64),
                UserFormat::F32,
                over_limit,
            )
        }
        (NpyFloat::F64, _) => {
            let view = ArrayViewD::<f64>::view_npy(&map).map_err(why)?;
            run_on::<f64, _>(
                args,
                &view,
                Working::Prec(Prec::F64),
                UserFormat::F64,
                over_limit,
            )
        }
    }
}

/// The local route on `source` computed in `T`.
fn run_on<T, S>(
    args: &InterpolateArgs,
    source: &S,
    working: Working,
    format: UserFormat,
    over_limit: bool,
) -> Result<bool, CliError>
where
    T: Real + Send + Sync,
    S: SampleSource<T> + ?Sized,
{
    let e = &args.engine;
    let degree = degree_from(e.degree, e.order, 0)?;
    let shape = source.shape().to_vec();
    if shape.is_empty() || shape.contains(&0) {
        return Err(input_error(
            &e.input,
            format!("no samples (shape {shape:?})"),
        ));
    }
    let tol = match (e.tol, e.nan_policy) {
        (None, NanPolicy::Local) => Some(LOCAL_TOL),
        (tol, _) => tol,
    };
    if args.coeffs && e.tol.is_some() {
        return Err(CliError::invalid(
            "--tol",
            "does not apply with --coeffs (no prefilter runs)",
        ));
    }
    if degree >= 2 && !args.coeffs {
        let max_error = e
            .max_error
            .unwrap_or(if working == Working::F32 { 1e-4 } else { 1e-8 });
        let family = SplineFamily::order(degree + 1)
            .map_err(|err| CliError::invalid("--degree", err.to_string()))?;
        RecursivePrefilter::<T>::new_within(&family, max_error)
            .map_err(|err| CliError::Numerical(format!("{err} (or accept it with --max-error)")))?;
    }
    let mut opts = LocalOptions {
        prefilter: !args.coeffs,
        ..LocalOptions::new(degree, e.mode)
    };
    opts.options.cval = e.cval;
    opts.options.nan_policy = e.nan_policy;
    if let Some(tol) = tol {
        opts.options.route = Route::Convolution { tol };
    }
    let engine = |err| super::engine_io::engine_error(&e.input, err);
    let spec = LocalSpec::<T>::new(&shape, opts).map_err(engine)?;
    let points = read_points(&args.at, shape.len())?;
    let at_error = |err: NdimageError| input_error(&args.at, err.to_string());
    // Above the input limit the local route runs at any cost (the global
    // route cannot read the file); within it, `new_if_local` decides as
    // the priced plan would without grouping and pricing every point where
    // the local route cannot win (10^6 points: seconds before the global
    // route was taken).
    let plan = if over_limit {
        LocalPlan::new(&spec, points.view(), PointRule::Fold, None).map_err(at_error)?
    } else {
        match LocalPlan::new_if_local(&spec, points.view(), PointRule::Fold).map_err(at_error)? {
            Some(plan) => plan,
            None => return Ok(false),
        }
    };
    let mut out = vec![T::zero(); points.nrows()];
    let stats = plan
        .evaluate(&spec, source, None, &mut out)
        .map_err(engine)?;
    let output = match output_kind(&e.output)? {
        OutputKind::Npy(_) => OutputKind::Npy(format),
        json => json,
    };
    let header = json!({
        "degree": degree,
        "mode": e.mode.name(),
        "route": "local",
        "half_width": spec.half_width(),
        "bound_per_axis": spec.bound(),
        "samples_read": stats.samples_read,
    });
    write_values(output, working, &e.output, &[out.len()], &out, header)?;
    summary(args, &shape, degree, working, &spec, stats, points.nrows())?;
    Ok(true)
}

fn summary<T: Real>(
    args: &InterpolateArgs,
    shape: &[usize],
    degree: u32,
    working: Working,
    spec: &LocalSpec<T>,
    stats: LocalStats,
    points: usize,
) -> Result<(), CliError> {
    let e = &args.engine;
    let mut text = String::new();
    outln!(
        text,
        "interpolate: shape {shape:?}, degree {degree}, mode {}, {points} points in {}",
        e.mode,
        working.name()
    );
    let total: usize = shape.iter().product();
    outln!(
        text,
        "route            local (memory-mapped): {} tiles, {} samples read of {total}",
        stats.tiles,
        stats.samples_read
    );
    if degree >= 2 && !args.coeffs {
        outln!(
            text,
            "coefficients     truncated at half-width {}, bound per axis {:e} (·max|s|)",
            spec.half_width(),
            spec.bound()
        );
    }
    outln!(text, "wrote            {}", path_text(&e.output));
    emit(&text)
}
