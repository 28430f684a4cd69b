//! Study "gridded" (issue 49): the exact not-a-knot tensor-product spline
//! on a rectilinear grid ([`GridSpline`]), its cost and its accuracy.
//!
//! 1. **Cost against the grid size**: cubic splines on 2-D and 3-D grids
//!    and quintic ones on 3-D grids of `N` points (`N` from `10³` to the
//!    profile's largest), every axis jittered (gaps uniform in `[0.5, 1.5)`,
//!    so no axis is uniform), random values in `[−1, 1)`: the construction's
//!    wall time ([`crate::timing::try_median_ns`]), the work memory it
//!    allocates by its module doc (the coefficients, one scalar per value,
//!    and one block of `n_a × LANES` scalars per thread) against the
//!    values' bytes, and its peak anonymous memory above the start
//!    ([`crate::peak_memory::measure`], one build on its own: a lower
//!    bound, blind to pages the allocator reuses, see
//!    [`CostRow::peak_bytes`]).
//! 2. **Accuracy against the exact spline**: on a small 3-D grid whose
//!    every axis has its closest pair of nodes exactly `min_gap` apart (the
//!    other gaps uniform in `[0.5, 1.5)`), random values in `[−1, 1)`: the
//!    `f64` spline against its 256-bit MPFR twin
//!    (`GridSpline::<Mp<256>>` on the same `f64` nodes and values, so the
//!    reference is the exact spline of the same data to ~`2^−256`), as
//!    the largest `|ŝ − s|` over random points (half uniform in the grid,
//!    half around the closest pairs) and the largest coefficient error,
//!    next to the stated [`GridSpline::error_bound`] and
//!    [`GridSpline::coefficient_error`] and each axis' `κ`.
//!
//! Timings are reported, never asserted (see [`crate::timing`]); the
//! bounds are asserted by the tests (`tests/it/gridded.rs`).

use crate::peak_memory::measure;
use crate::rng::SplitMix64;
use crate::timing::try_median_ns;
use serde::Serialize;
use splinelab::gridded::grid_spline::LANES;
use splinelab::gridded::{GridSpline, GriddedError};
use splinelab::ndarray::{ArrayD, IxDyn};
use splinelab::scalar::{Mp, Real};

/// The reference's precision.
type Reference = Mp<256>;

/// One kind of grid in the cost sweep.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct CostCase {
    /// Dimensions.
    pub dims: usize,
    /// Spline degree.
    pub degree: usize,
}

/// What to measure.
#[derive(Debug, Clone, Serialize)]
pub struct GriddedParams {
    /// The grids of the cost sweep.
    pub cost_cases: Vec<CostCase>,
    /// Grid sizes `N` (points) of the cost sweep, ascending.
    pub sizes: Vec<usize>,
    /// Timing samples per build (the median is reported).
    pub repeats: usize,
    /// Shape of the accuracy grid.
    pub accuracy_shape: Vec<usize>,
    /// Degrees of the accuracy study.
    pub accuracy_degrees: Vec<usize>,
    /// Closest pair of nodes on every axis, one accuracy grid each.
    pub min_gaps: Vec<f64>,
    /// Random points per accuracy grid.
    pub accuracy_points: usize,
}

impl GriddedParams {
    /// CI profile: grids of `10³` to `10⁶` points.
    pub fn quick() -> Self {
        GriddedParams {
            sizes: vec![1_000, 10_000, 100_000, 1_000_000],
            repeats: 3,
            ..Self::full()
        }
    }

    /// Report profile: `10³` to `10⁷` points, every half decade.
    pub fn full() -> Self {
        GriddedParams {
            cost_cases: vec![
                CostCase { dims: 3, degree: 3 },
                CostCase { dims: 3, degree: 5 },
                CostCase { dims: 2, degree: 3 },
            ],
            sizes: vec![
                1_000, 3_000, 10_000, 30_000, 100_000, 300_000, 1_000_000, 3_000_000, 10_000_000,
            ],
            repeats: 5,
            // The accuracy cases are the same in both profiles (its figures
            // compare across them).
            accuracy_shape: vec![12, 10, 8],
            accuracy_degrees: vec![3, 5],
            min_gaps: vec![0.5, 1e-2, 1e-4],
            accuracy_points: 400,
        }
    }
}

/// One build of the cost sweep.
#[derive(Debug, Clone, Serialize)]
pub struct CostRow {
    /// Dimensions.
    pub dims: usize,
    /// Degree.
    pub degree: usize,
    /// The grid's shape.
    pub shape: Vec<usize>,
    /// Grid points `N`.
    pub points: usize,
    /// Construction, seconds (median).
    pub build_s: f64,
    /// Construction per grid point, ns.
    pub ns_per_point: f64,
    /// Peak anonymous bytes above the start, one build measured alone (the
    /// values were allocated before it). The resident set sees only pages
    /// new to the process: an allocation the allocator serves from memory
    /// freed earlier (glibc's heap, for blocks under its `mmap` threshold,
    /// at most 32 MiB) is not seen, so this is a lower bound, exact for
    /// builds whose coefficients exceed 32 MiB.
    pub peak_bytes: usize,
    /// Bytes of the values (f64).
    pub values_bytes: usize,
    /// Bytes of the coefficients the spline keeps.
    pub coefficient_bytes: usize,
    /// The work memory the module doc states beyond the coefficients: one
    /// block of `max_a n_a × LANES` scalars per thread.
    pub block_bytes: usize,
    /// The work memory the build allocates by the module doc: the
    /// coefficients plus the blocks.
    pub stated_bytes: usize,
}

/// One grid of the accuracy study.
#[derive(Debug, Clone, Serialize)]
pub struct AccuracyRow {
    /// Degree.
    pub degree: usize,
    /// The closest pair of nodes on every axis.
    pub min_gap: f64,
    /// The grid's shape.
    pub shape: Vec<usize>,
    /// `κ_a = ‖A_a^{−1}‖∞` per axis (f64 build).
    pub kappas: Vec<f64>,
    /// Largest LU growth over the axes.
    pub growth: f64,
    /// Whether any axis' factorization exchanged rows.
    pub pivoted: bool,
    /// Largest |coefficient| (the MPFR twin's).
    pub max_coefficient: f64,
    /// `max_j |ĉ_j − c_j|`.
    pub coefficient_error: f64,
    /// [`GridSpline::coefficient_error`] of the f64 build.
    pub coefficient_bound: f64,
    /// Largest `|s|` over the points (the MPFR twin's).
    pub max_value: f64,
    /// `max |ŝ(x) − s(x)|` over the points.
    pub error: f64,
    /// [`GridSpline::error_bound`] of the f64 build.
    pub bound: f64,
    /// Points compared.
    pub points: usize,
}

impl AccuracyRow {
    /// `error / bound` (≤ 1: the bound holds; its inverse is how loose it is).
    pub fn error_over_bound(&self) -> f64 {
        self.error / self.bound
    }

    /// Correct decimal digits relative to the spline's size,
    /// `−log10(error / max|s|)` (17 where the error is 0).
    pub fn digits(&self) -> f64 {
        if self.error == 0.0 {
            17.0
        } else {
            -(self.error / self.max_value).log10()
        }
    }
}

/// Everything the report shows.
#[derive(Debug, Clone, Serialize)]
pub struct GriddedData {
    /// The parameters.
    pub params: GriddedParams,
    /// rayon's threads during the builds.
    pub threads: usize,
    /// Per case and size.
    pub cost: Vec<CostRow>,
    /// Per degree and closest gap.
    pub accuracy: Vec<AccuracyRow>,
}

/// Strictly ascending jittered nodes: gaps uniform in `[0.5, 1.5)`, one of
/// them (at a random place) `min_gap` when given, so that the closest pair
/// is exactly `min_gap` apart (for `min_gap ≤ 0.5`).
pub fn jittered_nodes(n: usize, rng: &mut SplitMix64, min_gap: Option<f64>) -> Vec<f64> {
    let mut gaps: Vec<f64> = (1..n).map(|_| rng.range(0.5, 1.5)).collect();
    if let Some(g) = min_gap.filter(|_| !gaps.is_empty()) {
        let at = (rng.next_u64() % gaps.len() as u64) as usize;
        gaps[at] = g;
    }
    let mut x = Vec::with_capacity(n);
    x.push(0.0);
    for g in gaps {
        x.push(x[x.len() - 1] + g);
    }
    x
}

/// A shape of about `points` grid points in `dims` dimensions, the axes of
/// unequal lengths (aspect 1.25 : 1 : 0.8), each at least `min_len`.
pub fn grid_shape(points: usize, dims: usize, min_len: usize) -> Vec<usize> {
    let side = (points as f64).powf(1.0 / dims as f64);
    let aspect: &[f64] = match dims {
        1 => &[1.0],
        2 => &[1.25, 0.8],
        _ => &[1.25, 1.0, 0.8],
    };
    (0..dims)
        .map(|a| ((side * aspect[a.min(aspect.len() - 1)]).round() as usize).max(min_len))
        .collect()
}

/// Random values in `[−1, 1)` of shape `shape × 1`.
fn random_values(shape: &[usize], rng: &mut SplitMix64) -> ArrayD<f64> {
    let mut full = shape.to_vec();
    full.push(1);
    let len = full.iter().product();
    ArrayD::from_shape_vec(IxDyn(&full), rng.signal(len))
        .unwrap_or_else(|_| unreachable!("the vector has the shape's length"))
}

fn cost_row(
    case: CostCase,
    points: usize,
    repeats: usize,
    rng: &mut SplitMix64,
) -> Result<CostRow, GriddedError> {
    let shape = grid_shape(points, case.dims, case.degree + 1);
    let nodes: Vec<Vec<f64>> = shape
        .iter()
        .map(|&n| jittered_nodes(n, rng, None))
        .collect();
    let values = random_values(&shape, rng);
    let n: usize = shape.iter().product();
    let build = || GridSpline::interpolate(nodes.clone(), values.view(), case.degree);
    // Memory first, on its own, before the timing loop reuses freed pages.
    let (spline, _, peak_bytes) = measure(build);
    let coefficient_bytes = std::mem::size_of_val(spline?.coefficients());
    let ns = try_median_ns(repeats, || build().map(drop))?;
    let threads = rayon::current_num_threads();
    let longest = shape.iter().copied().max().unwrap_or(0);
    let block_bytes = threads * longest * LANES * std::mem::size_of::<f64>();
    Ok(CostRow {
        dims: case.dims,
        degree: case.degree,
        shape,
        points: n,
        build_s: ns * 1e-9,
        ns_per_point: ns / n as f64,
        peak_bytes,
        values_bytes: values.len() * std::mem::size_of::<f64>(),
        coefficient_bytes,
        block_bytes,
        stated_bytes: coefficient_bytes + block_bytes,
    })
}

/// The cost sweep: every case at every size.
pub fn run_cost(p: &GriddedParams) -> Result<Vec<CostRow>, GriddedError> {
    let mut rng = SplitMix64::new(49);
    let mut rows = Vec::new();
    for &case in &p.cost_cases {
        for &points in &p.sizes {
            rows.push(cost_row(case, points, p.repeats, &mut rng)?);
        }
    }
    Ok(rows)
}

/// Random points: half uniform in the grid's box, half with each
/// coordinate in the three cells around that axis' closest pair.
fn accuracy_points(nodes: &[Vec<f64>], count: usize, rng: &mut SplitMix64) -> Vec<f64> {
    let closest: Vec<(f64, f64)> = nodes
        .iter()
        .map(|x| {
            let j = (1..x.len())
                .min_by(|&a, &b| (x[a] - x[a - 1]).total_cmp(&(x[b] - x[b - 1])))
                .unwrap_or(1);
            (x[j.saturating_sub(2)], x[(j + 1).min(x.len() - 1)])
        })
        .collect();
    let mut out = Vec::with_capacity(count * nodes.len());
    for i in 0..count {
        for (a, x) in nodes.iter().enumerate() {
            let (lo, hi) = if i % 2 == 0 {
                (x[0], x[x.len() - 1])
            } else {
                closest[a]
            };
            out.push(rng.range(lo, hi));
        }
    }
    out
}

/// The f64 spline of one grid against its MPFR twin.
pub fn accuracy_row(
    degree: usize,
    min_gap: f64,
    shape: &[usize],
    count: usize,
    seed: u64,
) -> Result<AccuracyRow, GriddedError> {
    let mut rng = SplitMix64::new(seed);
    let nodes: Vec<Vec<f64>> = shape
        .iter()
        .map(|&n| jittered_nodes(n, &mut rng, Some(min_gap)))
        .collect();
    let values = random_values(shape, &mut rng);
    let s = GridSpline::interpolate(nodes.clone(), values.view(), degree)?;
    let wide = |v: &[f64]| v.iter().map(|&x| Reference::from_f64_exact(x)).collect();
    let nodes_mp: Vec<Vec<Reference>> = nodes.iter().map(|x| wide(x)).collect();
    let twin = GridSpline::<Reference>::interpolate(
        nodes_mp,
        values.mapv(Reference::from_f64_exact).view(),
        degree,
    )?;
    let (mut coefficient_error, mut max_coefficient) = (0.0f64, 0.0f64);
    for (c, m) in s.coefficients().iter().zip(twin.coefficients()) {
        let m = m.to_f64();
        coefficient_error = coefficient_error.max((c - m).abs());
        max_coefficient = max_coefficient.max(m.abs());
    }
    let x = accuracy_points(&nodes, count, &mut rng);
    let got = s.eval(&x, &[])?;
    let want = twin.eval(&wide(&x), &[])?;
    let (mut error, mut max_value) = (0.0f64, 0.0f64);
    for (g, w) in got.iter().zip(&want) {
        // The difference in MPFR, rounded once.
        let d = (Reference::from_f64_exact(*g) - w.clone()).to_f64().abs();
        error = error.max(d);
        max_value = max_value.max(w.to_f64().abs());
    }
    let c = s.conditioning();
    Ok(AccuracyRow {
        degree,
        min_gap,
        shape: shape.to_vec(),
        kappas: c.iter().map(|a| a.kappa).collect(),
        growth: c.iter().map(|a| a.growth).fold(0.0, f64::max),
        pivoted: c.iter().any(|a| a.pivoted),
        max_coefficient,
        coefficient_error,
        coefficient_bound: s.coefficient_error(),
        max_value,
        error,
        bound: s.error_bound(),
        points: count,
    })
}

/// The accuracy study: every degree at every closest gap (one seed per gap,
/// so both degrees see the same grid and values).
pub fn run_accuracy(p: &GriddedParams) -> Result<Vec<AccuracyRow>, GriddedError> {
    let mut rows = Vec::new();
    for &k in &p.accuracy_degrees {
        for (i, &gap) in p.min_gaps.iter().enumerate() {
            rows.push(accuracy_row(
                k,
                gap,
                &p.accuracy_shape,
                p.accuracy_points,
                490 + i as u64,
            )?);
        }
    }
    Ok(rows)
}

/// Runs the study.
pub fn run_gridded(p: &GriddedParams) -> Result<GriddedData, GriddedError> {
    Ok(GriddedData {
        params: p.clone(),
        threads: rayon::current_num_threads(),
        accuracy: run_accuracy(p)?,
        cost: run_cost(p)?,
    })
}
