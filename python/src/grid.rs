//! scipy.interpolate's gridded splines: `GridSpline` (the exact not-a-knot
//! tensor-product spline of odd degree, for `RegularGridInterpolator` and
//! `interpn`'s `slinear`, `cubic` and `quintic`), `grid_linear` and
//! `grid_nearest` (scipy's `linear` and `nearest`, in its operations) and
//! `grid_pchip`.
//! The Python layer (`splinelab._rgi`) has done scipy's argument handling:
//! ascending float64 nodes, values of shape grid × m (float64 or float32;
//! complex values as pairs), points `(n, d)` float64 C-contiguous.

use crate::error::{engine_error, value_error};
use crate::pool::run_with;
use numpy::ndarray::{ArrayViewD, Axis, CowArray, IxDyn};
use numpy::{
    PyArray1, PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArrayDyn, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use splinelab::gridded::multilinear::{self, CornerProduct};
use splinelab::gridded::{self, GridAxis, GriddedError, Layout};
use splinelab::ndimage::alloc::try_standard_layout;
use splinelab::ndimage::samples::Sample;

fn grid_error(e: GriddedError) -> PyErr {
    match e {
        GriddedError::Alloc(e) => engine_error(e),
        e => value_error(e),
    }
}

fn nodes(grid: &[PyReadonlyArray1<'_, f64>]) -> Vec<Vec<f64>> {
    grid.iter().map(|g| g.as_array().to_vec()).collect()
}

/// `xi` as a row-major slice of `n × d` points, and `n`.
fn points<'a>(xi: &'a PyReadonlyArray2<'_, f64>, d: usize) -> PyResult<(&'a [f64], usize)> {
    match *xi.shape() {
        [n, dims] if dims == d => Ok((
            xi.as_slice()
                .map_err(|_| value_error("points must be C-contiguous"))?,
            n,
        )),
        _ => Err(value_error(format!(
            "points of shape {:?} do not have {d} coordinates each",
            xi.shape()
        ))),
    }
}

/// Estimated nanoseconds of one thread's work (`pool::run_with` runs a
/// call at most [`crate::pool::SMALL_NS`] on the calling thread): about a
/// nanosecond per multiply-add, as the engine's other estimates.
fn work_ns(multiply_adds: usize) -> f64 {
    multiply_adds as f64
}

/// A new array `n × m` (float64, or the samples' type) filled by `fill`
/// without the GIL (`work` estimated nanoseconds).
fn results<'py, T: numpy::Element + Send>(
    py: Python<'py>,
    n: usize,
    m: usize,
    threads: Option<usize>,
    work: f64,
    fill: impl FnOnce(&mut [T]) -> Result<(), GriddedError> + Send,
) -> PyResult<Bound<'py, PyAny>> {
    let mut out = crate::alloc::zeros::<T>(py, &[n, m])?;
    let slice = out.slice_mut();
    crate::pool::run_detached(py, threads, work, || fill(slice))?.map_err(grid_error)?;
    Ok(out.into_any())
}

/// Float64 or float32 values, read as they lie.
enum Values<'py> {
    F64(PyReadonlyArrayDyn<'py, f64>),
    F32(PyReadonlyArrayDyn<'py, f32>),
}

impl<'py> Values<'py> {
    fn extract(values: &Bound<'py, PyAny>) -> PyResult<Self> {
        if let Ok(v) = values.extract::<PyReadonlyArrayDyn<'py, f64>>() {
            Ok(Values::F64(v))
        } else if let Ok(v) = values.extract::<PyReadonlyArrayDyn<'py, f32>>() {
            Ok(Values::F32(v))
        } else {
            Err(PyTypeError::new_err(
                "values must be a float64 or float32 array",
            ))
        }
    }
}

/// The axes of a grid whose values are evaluated as given (degree 1's
/// knots: only nodes and cells are read for PCHIP).
fn linear_axes(grid: Vec<Vec<f64>>) -> Result<Vec<GridAxis<f64>>, GriddedError> {
    grid.into_iter()
        .enumerate()
        .map(|(a, x)| GridAxis::not_a_knot(x, 1, a))
        .collect()
}

/// Checks `values` against the grid and evaluates `f` on its samples, read
/// in place where they fill one block of memory (any order: a flipped
/// descending axis included) once broadcast axes are read as one sample,
/// else copied once (fallibly: a view too large is MemoryError, not an
/// abort).
fn on_samples<S: Sample<f64> + numpy::Element>(
    values: ArrayViewD<'_, S>,
    axes: &[GridAxis<f64>],
    f: impl FnOnce(&[S], &Layout, usize) -> Result<(), GriddedError>,
) -> Result<(), GriddedError> {
    let grid: Vec<usize> = axes.iter().map(GridAxis::len).collect();
    let m = match values.shape().split_last() {
        Some((&m, lead)) if lead == grid.as_slice() => m,
        _ => {
            return Err(GriddedError::Shape {
                grid,
                got: values.shape().to_vec(),
            });
        }
    };
    // A broadcast axis (stride 0) holds one distinct sample along it: that
    // one is read, and the layout steps 0 along the axis (a broadcast grid
    // is never copied or scanned whole).
    let broadcast: Vec<usize> = values
        .strides()
        .iter()
        .zip(values.shape())
        .enumerate()
        .filter(|(_, (stride, len))| **stride == 0 && **len > 1)
        .map(|(a, _)| a)
        .collect();
    let mut distinct = values.clone();
    for &a in &broadcast {
        distinct.collapse_axis(Axis(a), 0);
    }
    let steps_zero = |mut layout: Layout| {
        for &a in &broadcast {
            if let Some(stride) = layout.strides.get_mut(a) {
                *stride = 0;
            }
        }
        layout
    };
    if let Some((data, layout)) = Layout::of_view(&distinct) {
        return f(data, &steps_zero(layout), m);
    }
    let c: CowArray<'_, S, IxDyn> = try_standard_layout(&distinct, "gridded samples")?;
    let slice = c.as_slice().ok_or(GriddedError::Shape {
        grid,
        got: values.shape().to_vec(),
    })?;
    f(slice, &steps_zero(Layout::c_order(distinct.shape())), m)
}

/// The exact not-a-knot tensor-product spline of odd `degree` through
/// `values` (grid × m) on `grid` (ascending float64 nodes per axis).
#[pyclass(module = "splinelab._splinelab", frozen)]
pub struct GridSpline {
    inner: gridded::GridSpline<f64>,
}

#[pymethods]
impl GridSpline {
    #[new]
    #[pyo3(signature = (grid, values, degree, threads=None))]
    fn new(
        py: Python<'_>,
        grid: Vec<PyReadonlyArray1<'_, f64>>,
        values: &Bound<'_, PyAny>,
        degree: usize,
        threads: Option<usize>,
    ) -> PyResult<Self> {
        let nodes = nodes(&grid);
        // Per sample and axis: a copy in, then about 3k + 2 multiply-adds.
        let work =
            work_ns(nodes.iter().map(Vec::len).product::<usize>() * nodes.len() * (3 * degree + 2));
        let built = match Values::extract(values)? {
            Values::F64(v) => {
                let v = v.as_array();
                crate::pool::run_detached(py, threads, work, || {
                    gridded::GridSpline::interpolate(nodes, v, degree)
                })?
            }
            Values::F32(v) => {
                let v = v.as_array();
                crate::pool::run_detached(py, threads, work, || {
                    gridded::GridSpline::interpolate(nodes, v, degree)
                })?
            }
        };
        Ok(Self {
            inner: built.map_err(grid_error)?,
        })
    }

    /// The spline (or its derivative `nu`) at the points `xi` (`n × d`): `n × m` float64.
    #[pyo3(signature = (xi, nu=None, threads=None))]
    fn eval<'py>(
        &self,
        py: Python<'py>,
        xi: PyReadonlyArray2<'py, f64>,
        nu: Option<Vec<usize>>,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let s = &self.inner;
        let (x, n) = points(&xi, s.axes().len())?;
        let nu = nu.unwrap_or_default();
        let (d, k) = (s.axes().len(), s.degree());
        let per_point = d * k * k + (k + 1).saturating_pow(d as u32) * s.batch();
        let work = work_ns(n.saturating_mul(per_point));
        results(py, n, s.batch(), threads, work, |out| {
            s.eval_into(x, &nu, out)
        })
    }

    /// The B-spline coefficients (a float64 copy, grid × m).
    #[getter]
    fn coefficients<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let mut shape: Vec<usize> = self.inner.axes().iter().map(GridAxis::len).collect();
        shape.push(self.inner.batch());
        let mut out = crate::alloc::zeros::<f64>(py, &shape)?;
        out.slice_mut().copy_from_slice(self.inner.coefficients());
        Ok(out.into_any())
    }

    /// The knot vector of each axis.
    #[getter]
    fn knots<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray1<f64>>> {
        self.inner
            .axes()
            .iter()
            .map(|a| PyArray1::from_slice(py, a.knots()))
            .collect()
    }

    /// The degree.
    #[getter]
    fn degree(&self) -> usize {
        self.inner.degree()
    }

    /// `‖A_a^{−1}‖∞` per axis: the ∞-norm condition number of each axis'
    /// collocation matrix (`‖A_a‖∞ = 1`).
    #[getter]
    fn condition(&self) -> Vec<f64> {
        self.inner.conditioning().iter().map(|c| c.kappa).collect()
    }

    /// Whether each axis' factorization exchanged rows.
    #[getter]
    fn pivoted(&self) -> Vec<bool> {
        self.inner
            .conditioning()
            .iter()
            .map(|c| c.pivoted)
            .collect()
    }

    /// A bound on the computed spline's distance from the exact one inside the grid.
    #[getter]
    fn error_bound(&self) -> f64 {
        self.inner.error_bound()
    }
}

/// Which evaluation a gridded call of samples wants.
#[derive(Clone, Copy)]
enum OnSamples {
    Linear(CornerProduct),
    Pchip,
}

fn eval_samples<'py>(
    py: Python<'py>,
    grid: Vec<PyReadonlyArray1<'py, f64>>,
    values: &Bound<'py, PyAny>,
    xi: PyReadonlyArray2<'py, f64>,
    threads: Option<usize>,
    how: OnSamples,
) -> PyResult<Bound<'py, PyAny>> {
    let axes = linear_axes(nodes(&grid)).map_err(grid_error)?;
    let (x, n) = points(&xi, axes.len())?;
    fn run<S: Sample<f64> + numpy::Element>(
        axes: &[GridAxis<f64>],
        v: ArrayViewD<'_, S>,
        x: &[f64],
        out: &mut [f64],
        how: OnSamples,
    ) -> Result<(), GriddedError> {
        on_samples(v, axes, |s, layout, m| {
            match how {
                OnSamples::Linear(order) => {
                    multilinear::multilinear_eval(axes, s, layout, m, x, order, out)
                }
                OnSamples::Pchip => gridded::pchip_eval(axes, s, layout, m, x, out),
            }
            Ok(())
        })
    }
    let m = |shape: &[usize]| shape.last().copied().unwrap_or(0);
    // Multiply-adds a point: 2^d (linear), about 8 · 4^d (PCHIP).
    let (taps, ops): (usize, usize) = match how {
        OnSamples::Linear(_) => (2, 1),
        OnSamples::Pchip => (4, 8),
    };
    let per_point = |m: usize| taps.saturating_pow(axes.len() as u32) * ops * m.max(1);
    let work = |m: usize| work_ns(n.saturating_mul(per_point(m)));
    match Values::extract(values)? {
        Values::F64(v) => {
            let v = v.as_array();
            results(py, n, m(v.shape()), threads, work(m(v.shape())), |out| {
                run(&axes, v, x, out, how)
            })
        }
        Values::F32(v) => {
            let v = v.as_array();
            results(py, n, m(v.shape()), threads, work(m(v.shape())), |out| {
                run(&axes, v, x, out, how)
            })
        }
    }
}

/// The multilinear interpolant of `values` (grid × m, float64 or float32)
/// at `xi` (`n × d`), extrapolating linearly: scipy's `linear`, in scipy's
/// operations (`gridded::multilinear`). `value_first`: each corner's term
/// as scipy's 2-D kernel forms it, `(v · w_0) · w_1` (scipy takes it for
/// 2-D float64 and complex128 values without trailing axes), else
/// `v · (w_0 · w_1 ⋯)` (its general route).
#[pyfunction]
#[pyo3(signature = (grid, values, xi, threads=None, value_first=false))]
pub fn grid_linear<'py>(
    py: Python<'py>,
    grid: Vec<PyReadonlyArray1<'py, f64>>,
    values: &Bound<'py, PyAny>,
    xi: PyReadonlyArray2<'py, f64>,
    threads: Option<usize>,
    value_first: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let order = if value_first {
        CornerProduct::ValueFirst
    } else {
        CornerProduct::WeightsFirst
    };
    eval_samples(py, grid, values, xi, threads, OnSamples::Linear(order))
}

/// One pass over the points `xi` (`n × d`) against the grid's ends
/// `[grid[a][0], grid[a][-1]]`: `(nans, outside, first_axis_out)` where
/// `nans[p]` says point `p` has a NaN coordinate, `outside[p]` that a
/// coordinate lies beyond an end, and `first_axis_out` is the first axis
/// with a coordinate not inside its closed range (NaN included: scipy's
/// `_bounds_check` reports that axis). The masks are None when no point is
/// flagged (the common call allocates nothing).
#[pyfunction]
#[allow(clippy::type_complexity)]
pub fn grid_points_scan<'py>(
    py: Python<'py>,
    grid: Vec<PyReadonlyArray1<'py, f64>>,
    xi: PyReadonlyArray2<'py, f64>,
) -> PyResult<(
    Option<Bound<'py, PyAny>>,
    Option<Bound<'py, PyAny>>,
    Option<usize>,
)> {
    let ends: Vec<(f64, f64)> = grid
        .iter()
        .map(|g| {
            let g = g.as_array();
            (g.first().copied(), g.last().copied())
        })
        .map(|(lo, hi)| (lo.unwrap_or(f64::NAN), hi.unwrap_or(f64::NAN)))
        .collect();
    let d = ends.len();
    let (x, n) = points(&xi, d)?;
    let (mut any_nan, mut any_out, mut first) = (false, false, d);
    for p in x.chunks_exact(d.max(1)) {
        for (a, (v, (lo, hi))) in p.iter().zip(&ends).enumerate() {
            if !(lo <= v && v <= hi) {
                first = first.min(a);
                any_nan |= v.is_nan();
                any_out |= v < lo || v > hi;
            }
        }
    }
    let mask = |flag: &dyn Fn(&[f64]) -> bool| -> PyResult<Bound<'py, PyAny>> {
        let mut out = crate::alloc::zeros::<bool>(py, &[n])?;
        for (o, p) in out.slice_mut().iter_mut().zip(x.chunks_exact(d.max(1))) {
            *o = flag(p);
        }
        Ok(out.into_any())
    };
    let nans = if any_nan {
        Some(mask(&|p| p.iter().any(|v| v.is_nan()))?)
    } else {
        None
    };
    let outside = if any_out {
        Some(mask(&|p| {
            p.iter().zip(&ends).any(|(v, (lo, hi))| v < lo || v > hi)
        })?)
    } else {
        None
    };
    Ok((nans, outside, (first < d).then_some(first)))
}

/// The samples of `values` (grid × m, float64 or float32) at scipy's
/// nearest node of each point of `xi` (`n × d`): `n × m` in the values'
/// dtype, ties to the lower node (`gridded::multilinear::nearest_node`).
#[pyfunction]
#[pyo3(signature = (grid, values, xi, threads=None))]
pub fn grid_nearest<'py>(
    py: Python<'py>,
    grid: Vec<PyReadonlyArray1<'py, f64>>,
    values: &Bound<'py, PyAny>,
    xi: PyReadonlyArray2<'py, f64>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    let axes = linear_axes(nodes(&grid)).map_err(grid_error)?;
    let (x, n) = points(&xi, axes.len())?;
    fn gather<'py, S: Sample<f64> + numpy::Element + Copy>(
        py: Python<'py>,
        axes: &[GridAxis<f64>],
        v: ArrayViewD<'_, S>,
        x: &[f64],
        n: usize,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let m = v.shape().last().copied().unwrap_or(0);
        // A binary search per axis and m copies a point.
        let work = work_ns(n.saturating_mul(8 * axes.len() + m));
        results(py, n, m, threads, work, |out: &mut [S]| {
            on_samples(v, axes, |s, layout, m| {
                multilinear::nearest_gather(axes, s, layout, m, x, out);
                Ok(())
            })
        })
    }
    match Values::extract(values)? {
        Values::F64(v) => gather(py, &axes, v.as_array(), x, n, threads),
        Values::F32(v) => gather(py, &axes, v.as_array(), x, n, threads),
    }
}

/// scipy's recursive PCHIP of `values` (grid × m) at `xi` (`n × d`),
/// read locally (four samples per axis a point).
#[pyfunction]
#[pyo3(signature = (grid, values, xi, threads=None))]
pub fn grid_pchip<'py>(
    py: Python<'py>,
    grid: Vec<PyReadonlyArray1<'py, f64>>,
    values: &Bound<'py, PyAny>,
    xi: PyReadonlyArray2<'py, f64>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    eval_samples(py, grid, values, xi, threads, OnSamples::Pchip)
}

/// The cardinal weights of the not-a-knot spline of odd `degree` on the
/// ascending nodes `x` at the points `q`: row `p` is `w(q_p) = A^{−T} b(q_p)`
/// (`gridded::cardinal`), so `W @ y` is the spline through `(x, y)` at `q`
/// (the end pieces continued outside). `len(q) × len(x)` float64.
#[pyfunction]
#[pyo3(signature = (x, degree, q, threads=None))]
pub fn grid_cardinal_weights<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    degree: usize,
    q: PyReadonlyArray1<'py, f64>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    use rayon::prelude::*;
    let axis = gridded::CardinalAxis::new(x.as_array().to_vec(), degree, 0).map_err(grid_error)?;
    let q = q.as_array();
    let n = axis.axis().len();
    let mut out = crate::alloc::zeros::<f64>(py, &[q.len(), n])?;
    {
        let rows = out.slice_mut();
        let q: Vec<f64> = q.to_vec();
        py.detach(|| {
            run_with(threads, work_ns(q.len() * n * 8), || {
                rows.par_chunks_mut(n.max(1))
                    .zip(q.par_iter())
                    .for_each(|(row, at)| row.copy_from_slice(&axis.full_weights(at)));
            })
        })?;
    }
    Ok(out.into_any())
}
