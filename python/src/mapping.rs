//! `mapped_points`: the coordinates a `geometric_transform` mapping
//! returned, one row per output index, as the `(ndim, k)` float64 array
//! the engine evaluates at. Python calls the mapping (`list(map(...))`, a
//! loop in C, as scipy's is); reading the rows here replaces
//! `np.fromiter` over a chained iterator, its reshape and its transposed
//! copy, a fifth of a small `geometric_transform` (issue 50).

use crate::common::{exact, real};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

/// The rows of `rows` (a list of the mapping's returns) as an `(ndim, k)`
/// float64 array: row `k` is column `k`. `None` unless every row is an
/// exact tuple or list of `ndim` exact Python floats or ints (an int as
/// Python's `float()` rounds it): the Python layer then reads the rows
/// itself, naming a bad one as it always has.
#[pyfunction]
pub fn mapped_points<'py>(
    py: Python<'py>,
    rows: &Bound<'py, PyAny>,
    ndim: usize,
) -> Option<Bound<'py, PyAny>> {
    let rows = exact::<PyList>(rows)?;
    let k = rows.len();
    let mut out = crate::alloc::zeros::<f64>(py, &[ndim, k]).ok()?;
    let points = out.slice_mut();
    for (j, row) in rows.iter().enumerate() {
        match exact::<PyTuple>(&row) {
            Some(t) => read_row(points, k, j, ndim, t.len(), t.iter()),
            None => {
                let l = exact::<PyList>(&row)?;
                read_row(points, k, j, ndim, l.len(), l.iter())
            }
        }?;
    }
    Some(out.into_any())
}

/// Column `j` of the `(ndim, k)` points from one row of `len` items:
/// `None` unless it has `ndim` of them, each a [`real`].
fn read_row<'py>(
    points: &mut [f64],
    k: usize,
    j: usize,
    ndim: usize,
    len: usize,
    items: impl Iterator<Item = Bound<'py, PyAny>>,
) -> Option<()> {
    (len == ndim).then_some(())?;
    for (d, x) in items.enumerate() {
        *points.get_mut(d * k + j)? = real(&x)?;
    }
    Some(())
}
