//! Study "update cost" (seeds 000, 003): what one data-point edit costs with
//! the truncated S-spline (local, `2n + 1` control points) against the
//! global cubic spline (a tridiagonal re-solve) and Boehm knot insertion,
//! and what a full build of the coefficients costs and how accurate it is:
//! the truncated convolution against the exact recursive prefilter, both
//! against a 256-bit MPFR build.
//!
//! Timings here are in-process medians over repeats (a quick look for the
//! report); the rigorous figures are the criterion benches
//! `cargo bench -p splinelab-benches --bench update_cost` and `--bench full_build`.

use crate::rng::SplitMix64;
use crate::timing::{median_ns, try_median_ns_fresh};
use nalgebra::{Vector2, Vector3};
use rug::Rational;
use serde::Serialize;
use splinelab::bspline::de_boor::BSpline;
use splinelab::bspline::knot_insertion::InsertionError;
use splinelab::curves::global_cubic::{CubicEnds, control_points};
use splinelab::curves::sspline_surface::{Direction, SsplineSurface};
use splinelab::curves::{CurveError, sspline_curve::SsplineCurve};
use splinelab::scalar::prelude::*;
use splinelab::sspline::end_conditions::{EndCondition, EndRule};
use splinelab::sspline::node_values::node_values_exact;
use splinelab::sspline::prefilter::{
    ConvolutionPrefilter, Prefilter1d, PrefilterError, RecursivePrefilter,
};
use splinelab::sspline::{
    Criterion, SplineFamily, SsplineError, f64_saturation_width, truncation_width,
};
use std::hint::black_box;

/// Why the study could not run.
#[derive(Debug, thiserror::Error)]
pub enum UpdateCostError {
    /// Building or editing a curve or surface failed.
    #[error(transparent)]
    Curve(#[from] CurveError),
    /// A prefilter failed.
    #[error(transparent)]
    Prefilter(#[from] PrefilterError),
    /// Coefficients or widths failed.
    #[error(transparent)]
    Sspline(#[from] SsplineError),
    /// Knot insertion failed.
    #[error("knot insertion: {0}")]
    Insertion(String),
}

/// What to measure.
#[derive(Debug, Clone, Serialize)]
pub struct UpdateCostParams {
    /// Data counts `N` of the curve-edit timings.
    pub edit_sizes: Vec<usize>,
    /// Sample counts of the full-build timings.
    pub build_sizes: Vec<usize>,
    /// Samples of the accuracy comparison against MPFR.
    pub accuracy_len: usize,
    /// Timing repeats (the median is reported).
    pub repeats: usize,
    /// Tolerance the edit width is chosen for (uniform criterion).
    pub tol: f64,
}

impl UpdateCostParams {
    /// CI profile: `N ≤ 1e5`.
    pub fn quick() -> Self {
        UpdateCostParams {
            edit_sizes: vec![100, 1_000, 10_000, 100_000],
            build_sizes: vec![1_000, 10_000, 100_000],
            accuracy_len: 20_000,
            repeats: 5,
            tol: 1e-6,
        }
    }

    /// Report profile: `N ≤ 1e6` for edits, `≤ 1e7` for full builds.
    pub fn full() -> Self {
        UpdateCostParams {
            edit_sizes: vec![100, 1_000, 10_000, 100_000, 1_000_000],
            build_sizes: vec![1_000, 10_000, 100_000, 1_000_000, 10_000_000],
            repeats: 7,
            ..Self::quick()
        }
    }
}

/// One curve size: median time of one point edit by each route.
#[derive(Debug, Clone, Serialize)]
pub struct EditRow {
    /// Data points `N`.
    pub n: usize,
    /// S-spline `shift_point` (the paper's `2n + 1` update), ns.
    pub local_ns: f64,
    /// S-spline `move_point` (recomputes `2n + 1` sums, bitwise = rebuild), ns.
    pub local_recompute_ns: f64,
    /// Global natural cubic spline: edit and re-solve, ns.
    pub global_ns: f64,
    /// Boehm insertion of one knot mid-curve into the S-spline's B-spline,
    /// returning a new curve (copies the net), ns.
    pub insertion_ns: f64,
    /// The same insertion in place (`insert_knot_in_place`: `O(k)` plus one
    /// move of the tail, room reserved), ns.
    pub insertion_in_place_ns: f64,
}

/// One full-build timing.
#[derive(Debug, Clone, Serialize)]
pub struct BuildRow {
    /// `cubic` or `quintic`.
    pub family: String,
    /// `recursive`, `convolution ε=1e-6` or `convolution f64-saturating`.
    pub method: String,
    /// Half-width of a convolution (0 for the recursive filter).
    pub half_width: usize,
    /// Samples.
    pub n: usize,
    /// Throughput, samples per second (median).
    pub samples_per_s: f64,
}

/// Accuracy of one full-build route in `f64` against the 256-bit build.
#[derive(Debug, Clone, Serialize)]
pub struct BuildAccuracy {
    /// `cubic` or `quintic`.
    pub family: String,
    /// As in [`BuildRow`].
    pub method: String,
    /// Half-width (0: recursive).
    pub half_width: usize,
    /// `max_k |D_k − D_k^ref| / (‖1/V‖₁ max|s|)` in units of `u = 2^{−53}`.
    pub error_u: f64,
    /// The a-priori truncation bound `Σ_{|j|>n}|c_j| / ‖1/V‖₁` in units of `u` (0: recursive).
    pub tail_u: f64,
}

/// A sampled planar curve.
#[derive(Debug, Clone, Serialize)]
pub struct Polyline {
    /// Label.
    pub name: String,
    /// Points `[x, y]`.
    pub points: Vec<[f64; 2]>,
}

/// A sampled space curve, in world coordinates (the report projects it).
#[derive(Debug, Clone, Serialize)]
pub struct Wireframe {
    /// Label.
    pub name: String,
    /// Points `[x, y, z]`.
    pub points: Vec<[f64; 3]>,
}

/// The locally edited surface, as wireframes.
#[derive(Debug, Clone, Serialize)]
pub struct SurfaceEdit {
    /// Grid side.
    pub side: usize,
    /// Half-width in each direction.
    pub half_width: usize,
    /// Control points changed by the edit (expected `(2n + 1)²`).
    pub changed_control_points: usize,
    /// Wireframe of the surface before and after the edit.
    pub wireframes: Vec<Wireframe>,
}

/// Everything the report shows.
#[derive(Debug, Clone, Serialize)]
pub struct UpdateCostData {
    /// The parameters.
    pub params: UpdateCostParams,
    /// Edit half-width `n` (cubic, uniform criterion at `tol`).
    pub half_width: usize,
    /// Curve-edit timings per `N`.
    pub edits: Vec<EditRow>,
    /// Full-build throughputs.
    pub builds: Vec<BuildRow>,
    /// Full-build accuracy in `f64`.
    pub accuracy: Vec<BuildAccuracy>,
    /// `max |D_move − D_rebuild|` after a sequence of `move_point` edits
    /// (0 means bitwise equal).
    pub move_vs_rebuild: f64,
    /// `max |D_shift − D_rebuild| / (‖c‖₁ max|P| u)` after the same edits by `shift_point`.
    pub shift_vs_rebuild_u: f64,
    /// The three end conditions on one data set.
    pub end_conditions: Vec<Polyline>,
    /// The data points of `end_conditions`.
    pub end_condition_data: Vec<[f64; 2]>,
    /// The locally edited surface.
    pub surface: SurfaceEdit,
}

/// `Σ_j |c_j| = 1/|V(−1)|` (the `c_j` alternate in sign): the ∞-norm of the
/// inverse filter, the scale of `D` for samples bounded by 1.
pub fn inverse_norm(family: &SplineFamily) -> Result<f64, SsplineError> {
    let v = node_values_exact(family)?;
    let alt = v.iter().enumerate().fold(
        Rational::new(),
        |a, (i, x)| {
            if i % 2 == 0 { a + x } else { a - x }
        },
    );
    Ok(1.0 / alt.abs().to_f64())
}

fn cubic() -> SplineFamily {
    SplineFamily::Order(4)
}

fn curve_data(len: usize, seed: u64) -> Vec<Vector2<f64>> {
    let mut r = SplitMix64::new(seed);
    (0..len)
        .map(|i| Vector2::new(i as f64, r.range(-1.0, 1.0)))
        .collect()
}

fn edit_row(len: usize, n: usize, repeats: usize) -> Result<EditRow, UpdateCostError> {
    let data = curve_data(len, 7 + len as u64);
    let mut s = SsplineCurve::new(&cubic(), n, &data, EndCondition::Free)?;
    let k = len / 2;
    let mut flip = 0.0;
    let mut edit = |s: &mut SsplineCurve<f64, 2>, recompute: bool| {
        flip = 1.0 - flip;
        let p = Vector2::new(k as f64, flip);
        let r = if recompute {
            s.move_point(k, p)
        } else {
            s.shift_point(k, p)
        };
        black_box(r.is_ok());
    };
    let local_ns = median_ns(repeats, || edit(&mut s, false));
    let local_recompute_ns = median_ns(repeats, || edit(&mut s, true));
    let mut p = data.clone();
    let global_ns = median_ns(repeats, || {
        p[k].y = 1.0 - p[k].y;
        black_box(control_points(&p, &CubicEnds::Natural).is_ok());
    });
    let b = s.to_bspline()?;
    let u = k as f64 + 0.5;
    let mut failed = None;
    let insertion_ns = median_ns(repeats, || {
        if let Err(e) = b.insert_knot(black_box(&u)) {
            failed = Some(e.to_string());
        }
    });
    if let Some(e) = failed {
        return Err(UpdateCostError::Insertion(e));
    }
    let insertion_in_place_ns = in_place_insertion_ns(&b, k as f64, repeats)
        .map_err(|e| UpdateCostError::Insertion(e.to_string()))?;
    Ok(EditRow {
        n: len,
        local_ns,
        local_recompute_ns,
        global_ns,
        insertion_ns,
        insertion_in_place_ns,
    })
}

/// Insertions per timed sample of [`in_place_insertion_ns`].
const IN_PLACE_BATCH: usize = 256;

/// Median wall time of one in-place insertion, in ns: each of `repeats`
/// samples inserts [`IN_PLACE_BATCH`] distinct knots into `(x, x + 1)` (a
/// single knot span of the S-spline's integer knots, mid-curve) of a fresh
/// copy of `b` with room reserved; the copy is not timed.
fn in_place_insertion_ns(
    b: &BSpline<f64, 2>,
    x: f64,
    repeats: usize,
) -> Result<f64, InsertionError> {
    try_median_ns_fresh(
        repeats,
        IN_PLACE_BATCH,
        || {
            let mut c = b.clone();
            c.reserve(IN_PLACE_BATCH);
            c
        },
        |c, m| {
            let u = x + 0.25 + m as f64 / (2 * IN_PLACE_BATCH) as f64;
            c.insert_knot_in_place(black_box(&u))
        },
    )
}

/// The two families of the full-build study.
fn build_families() -> [(&'static str, SplineFamily); 2] {
    [
        ("cubic", SplineFamily::Order(4)),
        ("quintic", SplineFamily::Order(6)),
    ]
}

/// The routes: recursive (`None`) and convolutions of the two widths.
fn build_methods(
    family: &SplineFamily,
    tol: f64,
) -> Result<Vec<(String, Option<usize>)>, SsplineError> {
    let eps = truncation_width(family, tol, Criterion::Uniform)?.n;
    let sat = f64_saturation_width(family)?;
    Ok(vec![
        ("recursive".into(), None),
        (format!("convolution ε={tol:e}"), Some(eps)),
        ("convolution f64-saturating".into(), Some(sat)),
    ])
}

fn signal(len: usize, seed: u64) -> Vec<f64> {
    let mut r = SplitMix64::new(seed);
    (0..len).map(|_| r.range(-1.0, 1.0)).collect()
}

/// One full-build route: the recursive filter (no width) or a convolution
/// of a width, behind the routes' one trait.
fn prefilter(
    family: &SplineFamily,
    width: Option<usize>,
) -> Result<Box<dyn Prefilter1d<f64>>, PrefilterError> {
    Ok(match width {
        None => Box::new(RecursivePrefilter::new(family)?),
        Some(n) => Box::new(ConvolutionPrefilter::new(family, n)?),
    })
}

fn build_rows(p: &UpdateCostParams) -> Result<Vec<BuildRow>, UpdateCostError> {
    let mut rows = Vec::new();
    for (name, family) in build_families() {
        for (method, width) in build_methods(&family, p.tol)? {
            let filter = prefilter(&family, width)?;
            for &len in &p.build_sizes {
                let s = signal(len, 11);
                let ns = median_ns(p.repeats.min(5), || {
                    black_box(
                        filter
                            .apply(&s, EndRule::Reflect)
                            .map(|d| d.len())
                            .unwrap_or(0),
                    );
                });
                rows.push(BuildRow {
                    family: name.into(),
                    method: method.clone(),
                    half_width: width.unwrap_or(0),
                    n: len,
                    samples_per_s: len as f64 / (ns * 1e-9),
                });
            }
        }
    }
    Ok(rows)
}

fn accuracy_rows(p: &UpdateCostParams) -> Result<Vec<BuildAccuracy>, UpdateCostError> {
    type Ref = Mp<256>;
    let s = signal(p.accuracy_len, 13);
    let exact: Vec<Ref> = s.iter().map(|&x| Ref::from_f64_exact(x)).collect();
    let mut rows = Vec::new();
    for (name, family) in build_families() {
        let reference = RecursivePrefilter::<Ref>::new(&family)?.apply(&exact, EndRule::Reflect)?;
        let norm = inverse_norm(&family)?;
        let scale = norm * s.iter().fold(0f64, |m, x| m.max(x.abs()));
        let expansion =
            splinelab::sspline::euler_frobenius::PoleExpansion::<Mp<128>>::new(&family)?;
        for (method, width) in build_methods(&family, p.tol)? {
            let d = prefilter(&family, width)?.apply(&s, EndRule::Reflect)?;
            let err = d
                .iter()
                .zip(&reference)
                .map(|(x, r)| (Ref::from_f64_exact(*x) - r.clone()).abs().to_f64())
                .fold(0f64, f64::max);
            let tail = width.map_or(0.0, |n| expansion.tail_bound(n).to_f64());
            let u = f64::EPSILON / 2.0;
            rows.push(BuildAccuracy {
                family: name.into(),
                method,
                half_width: width.unwrap_or(0),
                error_u: err / scale / u,
                tail_u: tail / norm / u,
            });
        }
    }
    Ok(rows)
}

/// Applies the same edits by `move_point`, by `shift_point` and by a
/// rebuild; returns `(max |move − rebuild|, max |shift − rebuild| / (‖c‖₁ max|P| u))`.
fn edits_vs_rebuild(n: usize) -> Result<(f64, f64), UpdateCostError> {
    let mut data = curve_data(200, 17);
    let mut moved = SsplineCurve::new(&cubic(), n, &data, EndCondition::Free)?;
    let mut shifted = moved.clone();
    let mut r = SplitMix64::new(19);
    for _ in 0..50 {
        let k = (r.next_u64() % data.len() as u64) as usize;
        let p = Vector2::new(k as f64, r.range(-1.0, 1.0));
        moved.move_point(k, p)?;
        shifted.shift_point(k, p)?;
        data[k] = p;
    }
    let rebuilt = SsplineCurve::new(&cubic(), n, &data, EndCondition::Free)?;
    let diff = |a: &SsplineCurve<f64, 2>| {
        a.control_points()
            .iter()
            .zip(rebuilt.control_points())
            .map(|(x, y)| (x - y).amax())
            .fold(0f64, f64::max)
    };
    let scale = inverse_norm(&cubic())? * data.iter().map(|p| p.amax()).fold(0f64, f64::max);
    Ok((diff(&moved), diff(&shifted) / scale / (f64::EPSILON / 2.0)))
}

/// A closed-looking wavy shape, so the three end conditions differ visibly.
fn picture_data() -> Vec<Vector2<f64>> {
    [
        [0.0, 0.0],
        [1.0, 1.5],
        [2.5, 2.0],
        [4.0, 1.0],
        [4.5, -0.5],
        [3.5, -2.0],
        [2.0, -2.2],
        [0.8, -1.2],
    ]
    .iter()
    .map(|p| Vector2::new(p[0], p[1]))
    .collect()
}

fn sample_curve(c: &SsplineCurve<f64, 2>, name: &str) -> Result<Polyline, CurveError> {
    let (lo, hi) = c.domain();
    let steps = 40 * (hi - lo).ceil() as usize;
    let points = (0..=steps)
        .map(|i| {
            let u = lo + (hi - lo) * i as f64 / steps as f64;
            c.eval(&u).map(|q| [q.x, q.y])
        })
        .collect::<Result<_, _>>()?;
    Ok(Polyline {
        name: name.into(),
        points,
    })
}

fn end_condition_curves(n: usize) -> Result<Vec<Polyline>, CurveError> {
    let data = picture_data();
    let ends = [
        ("free (eq 21)", EndCondition::Free),
        ("periodic (eq 22)", EndCondition::Periodic),
        (
            "end tangents T₀ = (0, 4), T₁ = (−4, 0)",
            EndCondition::Tangents {
                start: Vector2::new(0.0, 4.0),
                end: Vector2::new(-4.0, 0.0),
            },
        ),
    ];
    ends.into_iter()
        .map(|(name, end)| sample_curve(&SsplineCurve::new(&cubic(), n, &data, end)?, name))
        .collect()
}

/// The wireframe of `s` sampled at half-integer steps, as one polyline that
/// snakes along the rows, then back along the columns: every drawn segment
/// is a grid edge, so one series draws the whole net.
fn wireframe(s: &SsplineSurface<f64, 3>, side: usize, name: &str) -> Result<Wireframe, CurveError> {
    let m = 2 * (side - 1);
    let at = |i: usize, j: usize| {
        s.eval(&(i as f64 / 2.0), &(j as f64 / 2.0))
            .map(|p| [p.x, p.y, p.z])
    };
    let mut points = Vec::with_capacity(2 * (m + 1) * (m + 1));
    for i in 0..=m {
        for jj in 0..=m {
            let j = if i % 2 == 0 { jj } else { m - jj };
            points.push(at(i, j)?);
        }
    }
    // m is even, so the row snake ends at (m, m): walk the columns from there.
    for jj in 0..=m {
        for ii in 0..=m {
            let i = if jj % 2 == 0 { m - ii } else { ii };
            points.push(at(i, m - jj)?);
        }
    }
    Ok(Wireframe {
        name: name.into(),
        points,
    })
}

fn surface_edit(n: usize) -> Result<SurfaceEdit, CurveError> {
    let side = 30;
    let data: Vec<Vector3<f64>> = (0..side * side)
        .map(|x| {
            let (i, j) = ((x / side) as f64, (x % side) as f64);
            Vector3::new(i, j, 0.6 * (0.5 * i).sin() * (0.4 * j).cos())
        })
        .collect();
    let d = Direction {
        family: cubic(),
        n,
        rule: EndRule::Free,
    };
    let before = SsplineSurface::new(&d, &d, side, side, &data)?;
    let mut after = before.clone();
    let k = side / 2;
    after.move_point(k, k, Vector3::new(k as f64, k as f64, 3.0))?;
    let changed = before
        .control_points()
        .iter()
        .zip(after.control_points())
        .filter(|(a, b)| a != b)
        .count();
    Ok(SurfaceEdit {
        side,
        half_width: n,
        changed_control_points: changed,
        // "before" drawn last: "after" shows only where the edit reached.
        wireframes: vec![
            wireframe(&after, side, &format!("after moving P({k},{k}) up by 3"))?,
            wireframe(&before, side, "before")?,
        ],
    })
}

/// Runs the study.
pub fn run_update_cost(params: &UpdateCostParams) -> Result<UpdateCostData, UpdateCostError> {
    let n = truncation_width(&cubic(), params.tol, Criterion::Uniform)?.n;
    let edits = params
        .edit_sizes
        .iter()
        .map(|&len| edit_row(len, n, params.repeats))
        .collect::<Result<_, _>>()?;
    let (move_vs_rebuild, shift_vs_rebuild_u) = edits_vs_rebuild(n)?;
    Ok(UpdateCostData {
        params: params.clone(),
        half_width: n,
        edits,
        builds: build_rows(params)?,
        accuracy: accuracy_rows(params)?,
        move_vs_rebuild,
        shift_vs_rebuild_u,
        end_conditions: end_condition_curves(n)?,
        end_condition_data: picture_data().iter().map(|p| [p.x, p.y]).collect(),
        surface: surface_edit(n)?,
    })
}
