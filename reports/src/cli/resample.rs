//! `splinelab resample`: scipy.ndimage's `zoom`, `shift`, `rotate` (2-D)
//! and `affine_transform` on the engine, `.npy` in and out like
//! `prefilter`: the prefilter once, then `zoom` / `shift` evaluated
//! separably ([`Interpolant::resample_grid`]) and `rotate` / `--matrix`
//! with the points generated where they are evaluated
//! ([`Interpolant::resample_affine`]). The points are scipy's, formed with
//! its operations (`NI_ZoomShift`, `NI_GeometricTransform`); the modes are
//! the engine's, as in `interpolate` (`nearest` and `grid-constant` the
//! exact spline of the extended signal, which scipy approximates by
//! padding 12 samples; scipy's `constant` and `wrap` are the Python
//! package's). Works in f64 (a float32 input's result rounded once to
//! float32), or f32 with `--compute float32`. NaN/±inf
//! samples by `--nan-policy` ([`super::nan_io`]).

use super::engine_io::{
    EngineArgs, Plan, Working, check_conditioning, engine_error, estimate, options, plan,
    to_working, write_result,
};
use super::nan_io::{NanSummary, eval_reach, with_summary};
use super::prec::Prec;
use crate::array_io::read_array;
use crate::error::CliError;
use crate::input::input_error;
use crate::outln;
use crate::output::emit;
use crate::path_text::path_text;
use clap::{ArgGroup, Args};
use serde_json::json;
use splinelab::ndimage::alloc::{checked_len, try_filled, try_with_capacity};
use splinelab::ndimage::interpolant::PointRule;
use splinelab::prelude::{Interpolant, Real};
use std::path::{Path, PathBuf};

/// Arguments of `splinelab resample`.
#[derive(Debug, Args)]
#[command(group(ArgGroup::new("transform").required(true).args(["zoom", "shift", "rotate", "matrix"])))]
pub struct ResampleArgs {
    /// The engine options.
    #[command(flatten)]
    pub engine: EngineArgs,
    /// Zoom factors (one, or one per axis, comma-separated): scipy's zoom.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub zoom: Option<Vec<f64>>,
    /// With --zoom: scipy's grid_mode (pixel edges aligned).
    #[arg(long)]
    pub grid_mode: bool,
    /// Shift in samples (one, or one per axis): scipy's shift.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub shift: Option<Vec<f64>>,
    /// Rotation in degrees of a 2-D input (scipy's rotate, reshape=True).
    #[arg(long, allow_negative_numbers = true)]
    pub rotate: Option<f64>,
    /// An affine matrix (.npy): (ndim,), (ndim, out_ndim), (ndim, ndim + 1)
    /// or (ndim + 1, ndim + 1), as scipy's affine_transform.
    #[arg(long)]
    pub matrix: Option<PathBuf>,
    /// With --matrix: the offset (one, or one per input axis).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub offset: Option<Vec<f64>>,
    /// With --matrix: the output shape (default: the input's).
    #[arg(long, value_delimiter = ',')]
    pub output_shape: Option<Vec<usize>>,
}

/// What to evaluate: per-axis coordinate vectors (formed only after the
/// budget has accepted their size), or an affine map.
enum Points {
    Grid(Vec<Axis>),
    Affine {
        matrix: Vec<f64>,
        offset: Vec<f64>,
        shape: Vec<usize>,
    },
}

impl Points {
    fn shape(&self) -> Vec<usize> {
        match self {
            Points::Grid(axes) => axes.iter().map(|a| a.count).collect(),
            Points::Affine { shape, .. } => shape.clone(),
        }
    }
}

/// Runs `splinelab resample`.
pub fn run(args: &ResampleArgs) -> Result<(), CliError> {
    let plan = plan(&args.engine, 0)?;
    if !matches!(plan.working, Working::F32 | Working::Prec(Prec::F64)) {
        return Err(CliError::invalid(
            "--prec",
            "resample computes in f64 (or f32 with --compute float32)",
        ));
    }
    let points = points(args, plan.data.shape())?;
    let shape = points.shape();
    let m = f64::from(plan.degree) + 1.0;
    // As a float: an output too large to count is refused by the budget
    // (or by the allocation), not by an overflow.
    let count: f64 = shape.iter().map(|&n| n as f64).product();
    let what = format!("resampling to {shape:?}");
    let _spinner = args.engine.budget.check(&estimate(
        &plan,
        shape.len(),
        count * m.powi(i32::try_from(shape.len()).unwrap_or(i32::MAX)),
        &what,
    ))?;
    let nan = match plan.working {
        Working::F32 => compute::<f32>(&plan, args, &points, &shape)?,
        _ => compute::<f64>(&plan, args, &points, &shape)?,
    };
    let e = &args.engine;
    let mut text = String::new();
    outln!(
        text,
        "resample: shape {:?} -> {shape:?}, degree {}, mode {} in {}",
        plan.data.shape(),
        plan.degree,
        e.mode,
        plan.working.name()
    );
    nan.lines(&mut text, "values");
    outln!(text, "wrote            {}", path_text(&e.output));
    emit(&text)
}

fn compute<T: Real + Copy + Send + Sync>(
    plan: &Plan,
    args: &ResampleArgs,
    points: &Points,
    shape: &[usize],
) -> Result<NanSummary, CliError> {
    let e = &args.engine;
    if plan.degree >= 1 {
        check_conditioning::<T>(plan)?;
    }
    let f = Interpolant::new(&to_working::<T>(&plan.data), options(plan, e))
        .map_err(|err| engine_error(&e.input, err))?;
    let mut out = checked_len(shape, OUT)
        .and_then(|n| try_filled(n, T::zero(), OUT))
        .map_err(|err| engine_error(&e.input, err))?;
    let done = match points {
        Points::Grid(axes) => {
            let axes = axes
                .iter()
                .map(Axis::coordinates)
                .collect::<Result<Vec<_>, _>>()?;
            let axes: Vec<&[f64]> = axes.iter().map(Vec::as_slice).collect();
            f.resample_grid(&axes, &vec![0; axes.len()], &mut out)
        }
        Points::Affine {
            matrix,
            offset,
            shape,
        } => f.resample_affine(matrix, offset, shape, 0.0, PointRule::Fold, &mut out),
    };
    done.map_err(|err| CliError::invalid("--matrix", err.to_string()))?;
    let (reach, bound) = eval_reach::<T>(plan, e, true)?;
    let nan = NanSummary::of(plan, &out, reach, bound);
    let header = json!({"degree": plan.degree, "mode": e.mode.name(), "shape": shape});
    write_result(plan, &e.output, shape, &out, with_summary(header, &nan))?;
    Ok(nan)
}

/// One value per axis: a single value repeated, or exactly `ndim`.
fn per_axis(values: &[f64], ndim: usize, arg: &'static str) -> Result<Vec<f64>, CliError> {
    match values {
        [v] => Ok(vec![*v; ndim]),
        v if v.len() == ndim => Ok(v.to_vec()),
        v => Err(CliError::invalid(
            arg,
            format!(
                "{} values for a {ndim}-D input: give one, or one per axis",
                v.len()
            ),
        )),
    }
    .and_then(|v| match v.iter().all(|x| x.is_finite()) {
        true => Ok(v),
        false => Err(CliError::invalid(arg, "values must be finite")),
    })
}

/// What the output array holds (named where it cannot be allocated).
const OUT: &str = "the resampled values";

/// One output axis of a zoom or shift: `count` indices `k`, whose
/// coordinates are scipy's `NI_ZoomShift` ones, `k + shift`, then `· zoom`
/// (`grid`: `+ ½`, `· zoom`, `− ½`).
struct Axis {
    count: usize,
    zoom: Option<f64>,
    shift: Option<f64>,
    grid: bool,
}

impl Axis {
    /// The coordinates, in a vector allocated fallibly (an axis too long
    /// to hold is an error, not an abort).
    fn coordinates(&self) -> Result<Vec<f64>, CliError> {
        let mut axis = try_with_capacity(self.count, "the output's coordinates")
            .map_err(CliError::numerical)?;
        axis.extend((0..self.count).map(|k| {
            let mut c = k as f64;
            if let Some(s) = self.shift {
                c += s;
            }
            match self.zoom {
                Some(z) if self.grid => (c + 0.5) * z - 0.5,
                Some(z) => c * z,
                None => c,
            }
        }));
        Ok(axis)
    }
}

/// The [`Axis`] of `count` indices, `zoom`, `shift` and `grid` mode.
fn zoom_shift_axis(count: usize, zoom: Option<f64>, shift: Option<f64>, grid: bool) -> Axis {
    Axis {
        count,
        zoom,
        shift,
        grid,
    }
}

fn points(args: &ResampleArgs, shape: &[usize]) -> Result<Points, CliError> {
    let ndim = shape.len();
    if let Some(z) = &args.zoom {
        let z = per_axis(z, ndim, "--zoom")?;
        let out: Vec<usize> = shape
            .iter()
            .zip(&z)
            .map(|(&n, &z)| (n as f64 * z).round_ties_even().max(0.0) as usize)
            .collect();
        let axes = shape
            .iter()
            .zip(&out)
            .map(|(&n, &m)| {
                let (num, div) = if args.grid_mode {
                    (n as f64, m as f64)
                } else {
                    (n as f64 - 1.0, m as f64 - 1.0)
                };
                let factor = if div != 0.0 { num / div } else { 1.0 };
                zoom_shift_axis(m, Some(factor), None, args.grid_mode)
            })
            .collect();
        return Ok(Points::Grid(axes));
    }
    if let Some(s) = &args.shift {
        let s = per_axis(s, ndim, "--shift")?;
        let axes = shape
            .iter()
            .zip(&s)
            .map(|(&n, &s)| zoom_shift_axis(n, None, Some(-s), false))
            .collect();
        return Ok(Points::Grid(axes));
    }
    if let Some(angle) = args.rotate {
        return rotation(angle, shape);
    }
    // clap's group requires one of the four; the error keeps it a message.
    let Some(path) = args.matrix.as_ref() else {
        return Err(CliError::invalid(
            "--matrix",
            "give one of --zoom, --shift, --rotate or --matrix",
        ));
    };
    let a = read_array(path)?;
    let out_shape = args.output_shape.clone().unwrap_or_else(|| shape.to_vec());
    let offset = per_axis(args.offset.as_deref().unwrap_or(&[0.0]), ndim, "--offset")?;
    affine_points(path, &a.shape, &a.data, offset, out_shape, ndim)
}

/// scipy's matrix forms (the homogeneous ones carry the offset); a
/// diagonal (ndim,) matrix is evaluated as scipy does, `(o + offset/m)·m`.
/// A matrix of another shape, or not finite, is refused naming `path`.
fn affine_points(
    path: &Path,
    dims: &[usize],
    m: &[f64],
    offset: Vec<f64>,
    out: Vec<usize>,
    ndim: usize,
) -> Result<Points, CliError> {
    if m.iter().any(|v| !v.is_finite()) {
        return Err(input_error(path, "the matrix must be finite"));
    }
    // The shape's rows of `m` (C order), each `c` long.
    let rows = |c: usize| m.chunks_exact(c.max(1));
    match *dims {
        [n] if n == ndim && out.len() == ndim && m.len() == ndim && offset.len() == ndim => {
            let axes = out
                .iter()
                .zip(m)
                .zip(&offset)
                .map(|((&k, &mk), &o)| zoom_shift_axis(k, Some(mk), Some(o / mk), false))
                .collect();
            Ok(Points::Grid(axes))
        }
        [r, c] if c == ndim + 1 && (r == ndim || r == ndim + 1) && m.len() == r * c => {
            let bottom: Vec<f64> = (0..=ndim).map(|j| f64::from(u8::from(j == ndim))).collect();
            if r == ndim + 1
                && rows(c)
                    .nth(ndim)
                    .is_some_and(|row| row != bottom.as_slice())
            {
                return Err(input_error(
                    path,
                    "homogeneous matrix: the bottom row must be [0, …, 0, 1]",
                ));
            }
            let matrix = rows(c)
                .take(ndim)
                .flat_map(|row| row.iter().take(ndim).copied())
                .collect();
            let offset = rows(c)
                .take(ndim)
                .filter_map(|row| row.get(ndim).copied())
                .collect();
            Ok(Points::Affine {
                matrix,
                offset,
                shape: out,
            })
        }
        [r, c] if r == ndim && c == out.len() => Ok(Points::Affine {
            matrix: m.to_vec(),
            offset,
            shape: out,
        }),
        _ => Err(input_error(
            path,
            format!(
                "matrix of shape {dims:?} for a {ndim}-D input and a {}-D output: expected \
                 ({ndim},), ({ndim}, {}), ({ndim}, {}) or ({}, {})",
                out.len(),
                out.len(),
                ndim + 1,
                ndim + 1,
                ndim + 1
            ),
        )),
    }
}

/// scipy's rotate (axes (1, 0), reshape=True) of a 2-D input: the matrix
/// `[[c, s], [−s, c]]` (the angle reduced exactly about a multiple of 90°,
/// as the Python package), the output shape holding the rotated input and
/// the centres `(n − 1)/2` matched.
fn rotation(angle: f64, shape: &[usize]) -> Result<Points, CliError> {
    let [iy, ix] = *shape else {
        return Err(CliError::invalid("--rotate", "takes a 2-D input"));
    };
    if !angle.is_finite() {
        return Err(CliError::invalid("--rotate", "must be finite"));
    }
    let x = angle % 360.0;
    let q = (x / 90.0).round_ties_even();
    let r = (x - 90.0 * q).to_radians();
    let (s0, c0) = (r.sin(), r.cos());
    let (c, s) = match (q as i64).rem_euclid(4) {
        0 => (c0, s0),
        1 => (-s0, c0),
        2 => (-c0, -s0),
        _ => (s0, -c0),
    };
    let (fy, fx) = (iy as f64, ix as f64);
    let ys = [0.0, s * fx, c * fy, c * fy + s * fx];
    let xs = [0.0, c * fx, -s * fy, -s * fy + c * fx];
    let extent = |v: [f64; 4]| {
        let (lo, hi) = v
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &t| (a.min(t), b.max(t)));
        (hi - lo + 0.5) as usize
    };
    let (oy, ox) = (extent(ys), extent(xs));
    let (hy, hx) = ((oy as f64 - 1.0) / 2.0, (ox as f64 - 1.0) / 2.0);
    let offset = vec![
        (fy - 1.0) / 2.0 - (c * hy + s * hx),
        (fx - 1.0) / 2.0 - (-s * hy + c * hx),
    ];
    Ok(Points::Affine {
        matrix: vec![c, s, -s, c],
        offset,
        shape: vec![oy, ox],
    })
}
