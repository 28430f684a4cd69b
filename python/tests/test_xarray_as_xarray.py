"""What xarray's own interpolation tests showed the accessor must do as
xarray does (issue 51; python/tests/downstream runs those tests with the
accessor swapped in): results that never share memory with the input,
xarray's NaN patterns along one dimension, lazy new coordinates left lazy,
"linear" reading only its window, an indexer's own coordinate labelling the
result.

References: xarray 2026.9.0's ``interp`` at run time (scipy's ``interp1d``
along one dimension, exact for these methods), applied line by line where
xarray's rule is per call; the input itself for the copies.
"""

import contextlib
import threading

import numpy as np
import pandas as pd
import pytest

xr = pytest.importorskip("xarray", reason="pip install splinelab[xarray]")
da_mod = pytest.importorskip("dask.array")
dask = pytest.importorskip("dask")

import splinelab.xarray  # noqa: E402,F401  (registers the accessor)
from splinelab.xarray import METHODS  # noqa: E402

ONE_DIM = ["linear", "nearest", "slinear", "cubic", "quintic"]


@contextlib.contextmanager
def no_compute():
    """dask computations in the block raise (xarray's raise_if_dask_computes)."""
    def scheduler(dsk, keys, **kwargs):
        raise RuntimeError("a dask array was computed")

    with dask.config.set(scheduler=scheduler):
        yield


# ---------------------------------------------------------------- copies


@pytest.mark.parametrize("method", list(METHODS))
@pytest.mark.parametrize("chunked", [False, True])
def test_writing_to_a_result_never_changes_the_input(method, chunked):
    """A variable not interpolated, a coordinate along another dimension
    and the data: writing to each in the result leaves the input as it was
    (xarray returns copies; checked here too). (An index's values are
    read-only in both.)"""
    ds = xr.Dataset({"a": (("x", "y"), np.arange(24.0).reshape(8, 3)), "b": ("y", np.zeros(3))},
                    coords={"x": np.arange(8.0), "y": [10, 20, 30], "y2": ("y", [1.0, 2.0, 3.0])})
    before = ds.copy(deep=True)
    src = ds.chunk(x=3) if chunked else ds
    for out in (ds.interp(x=[0.5, 2.5], method=method), src.splinelab.interp(x=[0.5, 2.5], method=method)):
        out = out.compute()
        for name in ("a", "b", "y2"):
            out[name].values[...] = -1
        xr.testing.assert_identical(ds, before)
    da = ds["a"]
    out = da.splinelab.interp(x=[1.5], method=method)
    out.values[...] = -1
    out["y2"].values[...] = -1
    xr.testing.assert_identical(ds, before)


# ---------------------------------------------------------------- NaN


def reference(data, method, q, kwargs):
    """xarray's interp along x: of the whole array for the local methods
    (scipy's rule is per element); for "cubic" and "quintic", whose rule is
    per call (interp1d makes every point NaN where its array holds one), of
    each line on its own."""
    if method not in ("cubic", "quintic"):
        return data.interp(x=q, method=method, kwargs=kwargs).values
    cols = [data.isel(y=j).interp(x=q, method=method, kwargs=kwargs).values for j in range(data.sizes["y"])]
    return np.stack(cols, axis=-1)


@pytest.mark.parametrize("method", ONE_DIM)
@pytest.mark.parametrize("kwargs", [None, {"fill_value": "extrapolate"}, {"fill_value": -3.0}])
@pytest.mark.parametrize("chunks", [None, 3, 5])
def test_nan_along_one_dimension_is_xarrays(method, kwargs, chunks):
    """NaN samples along the interpolated dimension give xarray's NaN
    pattern and, elsewhere, its numbers: a point reads NaN where scipy's
    interp1d reads one ("linear": the interval left of a node; "slinear":
    the interval right of it; "nearest": the nearest node; "cubic",
    "quintic": a line holding a NaN is NaN), in memory and chunked."""
    rng = np.random.default_rng(11)
    x = np.cumsum(rng.uniform(0.5, 1.5, 14))
    values = rng.normal(size=(14, 4))
    values[5, 1] = np.nan
    values[[0, 13], 2] = np.nan
    data = xr.DataArray(values, dims=("x", "y"), coords={"x": x, "y": np.arange(4.0)})
    q = np.r_[x[0] - 0.5, x[[0, 4, 5, 6, 13]], (x[4] + x[5]) / 2, (x[5] + x[6]) / 2, rng.uniform(x[0], x[-1], 6),
              x[-1] + 0.5]
    ref = reference(data, method, q, kwargs)
    src = data if chunks is None else data.chunk(x=chunks)
    got = src.splinelab.interp(x=q, method=method, kwargs=kwargs).values
    assert np.array_equal(np.isnan(got), np.isnan(ref)), (np.isnan(got), np.isnan(ref))
    ok = ~np.isnan(ref)
    assert np.abs(got[ok] - ref[ok]).max() <= 1e-12 * np.abs(ref[ok]).max()
    # the NaN-free line is the same with or without the others' NaN
    assert np.isnan(got[:, 3]).sum() == np.isnan(ref[:, 3]).sum()


@pytest.mark.parametrize("chunked", [False, True])
def test_slinear_after_an_out_of_range_step_is_xarrays(chunked):
    """xarray interpolates "slinear" one dimension after the other: the
    first step's fill (NaN beyond the end) is data for the second, which
    scipy's degree-1 spline carries locally."""
    data = xr.DataArray(np.arange(6.0).reshape(3, 2), dims=["x", "y"], coords={"x": [0, 1, 2], "y": [0, 1]})
    ref = data.interp(x=[0.5, 2.5], y=[0.5], method="slinear")
    src = data.chunk(x=1) if chunked else data
    got = src.splinelab.interp(x=[0.5, 2.5], y=[0.5], method="slinear")
    np.testing.assert_array_equal(got.values, ref.values)   # [[1.5], [nan]]
    assert np.isnan(ref.values[1, 0]) and ref.values[0, 0] == 1.5


# ---------------------------------------------------------------- lazy new coordinates


@pytest.mark.parametrize("method", list(METHODS))
@pytest.mark.parametrize("data_chunks", [None, {"lat": 4, "lon": 5}, {"q": 7}])
def test_lazy_new_coordinates_stay_lazy(method, data_chunks):
    """New coordinates held by dask (xarray's test_interp_vectorized_dask:
    one q per (lat, lon)) are not computed at the call, whatever the data's
    chunks; the computed result is the in-memory call's, bit for bit, and
    xarray's numbers (cubic and quintic along one dimension are exact in
    scipy)."""
    rng = np.random.default_rng(12)
    nq = 21
    data = xr.DataArray(rng.normal(size=(8, 10, 3, nq)), dims=("lat", "lon", "day", "q"),
                        coords={"lat": np.linspace(-80, 80, 8), "lon": np.linspace(0, 300, 10), "day": [0, 1, 2],
                                "q": np.linspace(0.0, 1.0, nq)})
    bar = xr.DataArray(rng.uniform(-0.05, 1.05, (8, 10)), dims=("lat", "lon"))
    src = data if data_chunks is None else data.chunk(data_chunks)
    with no_compute():
        lazy = src.splinelab.interp(q=bar.chunk(lat=3, lon=4), method=method, kwargs={"fill_value": None}
                                    if method != "pchip" else {"extrapolate": True})
    whole = data.splinelab.interp(q=bar, method=method, kwargs={"fill_value": None}
                                  if method != "pchip" else {"extrapolate": True})
    assert isinstance(lazy.data, da_mod.Array) and lazy.dims == whole.dims
    assert lazy.values.tobytes() == whole.values.tobytes()
    theirs = data.interp(q=bar, method=method, kwargs={"fill_value": None} if method != "pchip" else
                         {"extrapolate": True}).values
    assert np.array_equal(np.isnan(whole.values), np.isnan(theirs))
    assert np.nanmax(np.abs(whole.values - theirs)) <= 1e-12 * np.nanmax(np.abs(theirs))


def test_lazy_new_coordinates_on_several_dimensions_stay_lazy():
    """Pointwise dask coordinates over two chunked dimensions, and dates on a
    datetime axis: nothing computed at the call; then the in-memory bits."""
    rng = np.random.default_rng(13)
    t = pd.date_range("2000-01-01", periods=30, freq="D")
    data = xr.DataArray(rng.normal(size=(30, 12, 2)), dims=("time", "y", "z"),
                        coords={"time": t, "y": np.arange(12.0), "z": [0, 1]})
    when = xr.DataArray(t[3] + pd.to_timedelta(rng.uniform(0, 20, 9), "D"), dims="p")
    where = xr.DataArray(rng.uniform(0, 11, 9), dims="p")
    for method in ("linear", "cubic", "slinear"):
        with no_compute():
            lazy = data.chunk(time=7, y=5).splinelab.interp(time=when.chunk(p=4), y=where.chunk(p=2), method=method)
        whole = data.splinelab.interp(time=when, y=where, method=method)
        assert lazy.values.tobytes() == whole.values.tobytes()
        xr.testing.assert_identical(lazy.coords.to_dataset().compute(), whole.coords.to_dataset())


# ---------------------------------------------------------------- reads


class CountingArray:
    """An array-like that records the boxes its ``__getitem__`` reads (not
    the empty one dask reads for its meta)."""

    def __init__(self, values):
        self.values = values
        self.shape, self.dtype, self.ndim = values.shape, values.dtype, values.ndim
        self.boxes = []
        self.lock = threading.Lock()

    def __getitem__(self, key):
        out = self.values[key]
        if out.size:
            with self.lock:
                self.boxes.append(key)
        return out


@pytest.mark.parametrize("method", ["linear", "nearest"])
def test_linear_reads_only_its_window(method):
    """xarray's test_indexing_localize, on dask: one point of a 36811-sample
    axis in chunks of 1000 reads xarray's window only, samples 18404 to
    18407 (xarray restricts "linear" and "nearest" to the samples from two
    before the node nearest the smallest new coordinate to two after the
    node nearest the largest; dask reads that slice of its chunk), and
    gives xarray's numbers."""
    values = np.random.default_rng(14).normal(size=(4, 36811))
    w = np.linspace(0, 30000, 36811)
    arr = CountingArray(values)
    lazy = xr.DataArray(da_mod.from_array(arr, chunks=(4, 1000), lock=False, asarray=True), dims=("p", "w"),
                        coords={"w": w})
    out = lazy.splinelab.interp(w=15000.5, method=method)
    assert not arr.boxes
    got = out.values
    reads = {(k[1].start, k[1].stop) for k in arr.boxes}
    assert reads == {(18404, 18408)}, reads
    ref = xr.DataArray(values, dims=("p", "w"), coords={"w": w}).interp(w=15000.5, method=method)
    np.testing.assert_array_equal(got, ref.values)


# ---------------------------------------------------------------- labels


@pytest.mark.parametrize("method", ["linear", "cubic"])
def test_an_indexers_own_coordinate_labels_the_result(method):
    """A DataArray indexer along the new dimension with a coordinate of its
    own there (dates labelling positions given as numbers, as xarray's
    interp_calendar passes them) keeps that coordinate, as xarray keeps it;
    its other coordinates are attached."""
    data = xr.DataArray(np.sin(np.arange(10.0)), dims="x", coords={"x": np.arange(10.0)})
    dates = pd.date_range("2000-01-01", periods=3)
    new = xr.DataArray([1.5, 2.25, 7.0], dims="x", coords={"x": dates, "label": ("x", ["a", "b", "c"])})
    ours, theirs = data.splinelab.interp(x=new, method=method), data.interp(x=new, method=method)
    xr.testing.assert_identical(ours.coords.to_dataset(), theirs.coords.to_dataset())
    assert np.abs(ours.values - theirs.values).max() <= 1e-12
