"""The accessor's results do not depend on the chunking, bit for bit.

Property: for every method, any data (NaN included where the method takes
it), any new coordinates (orthogonal or pointwise, inside, on the nodes and
beyond the ends, each fill), and any chunking of the data (regular or not,
along interpolated, vectorised and carried dimensions) and of dask-backed
new coordinates, the dask result's bytes equal those of the same call on
the in-memory data: the in-memory route and every dask route compute each
element by the same operations (``splinelab._xarray_dask``'s windowed sums
for "slinear", and for "cubic"/"quintic" where few new coordinates make
windows cheaper; else every route solves whole lines). Where the in-memory
call raises, the dask computation raises the same class.

The values themselves are checked against xarray's ``interp`` and the
exact spline in test_xarray.py; here only their independence from chunking.
"""

from unittest import mock

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

xr = pytest.importorskip("xarray", reason="pip install splinelab[xarray]")
da_mod = pytest.importorskip("dask.array")

import splinelab.xarray  # noqa: E402,F401  (registers the accessor)
from splinelab import _xarray_dask  # noqa: E402
from splinelab.xarray import METHODS  # noqa: E402

#: xarray's fills: its default (NaN), a number, and extrapolation (None
#: along several dimensions, "extrapolate" along one).
FILLS = ("default", "number", "extrapolate")


def bits(a):
    """The bytes of an array, NaN payloads and signed zeros included."""
    a = np.ascontiguousarray(a)
    return a.dtype, a.shape, a.tobytes()


@st.composite
def chunking(draw, n):
    """A chunking of ``n`` samples: one chunk, a regular size, or irregular cuts."""
    kind = draw(st.sampled_from(["one", "regular", "irregular"]))
    if kind == "one" or n < 2:
        return (n,)
    if kind == "regular":
        size = draw(st.integers(1, n))
        return (size,) * (n // size) + ((n % size,) if n % size else ())
    cuts = sorted(draw(st.sets(st.integers(1, n - 1), min_size=1, max_size=min(6, n - 1))))
    return tuple(np.diff([0, *cuts, n]).tolist())


@st.composite
def calls(draw):
    method = draw(st.sampled_from(list(METHODS)))
    nint = draw(st.integers(1, 2))
    # a long axis with few points takes the windows for cubic/quintic, many the whole-line solve
    sizes = [draw(st.integers(max(METHODS[method], 2), draw(st.sampled_from([12, 80])))) for _ in range(nint)]
    ncarried = draw(st.integers(1, 3))
    seed = draw(st.integers(0, 2 ** 16))
    pointwise = nint > 1 and draw(st.booleans())
    vectorised = nint == 1 and draw(st.booleans())
    npoints = draw(st.integers(1, draw(st.sampled_from([3, 40]))))
    nan = draw(st.booleans()) and method != "pchip"
    fill = draw(st.sampled_from(FILLS))
    lazy = draw(st.booleans())
    shape = sizes + [ncarried]
    chunks = [draw(chunking(n)) for n in shape]
    point_chunks = draw(chunking(npoints)) if lazy else None
    # "cubic"/"quintic": the cost rule's choice, or either route forced
    # (the rule reads sizes only; here each route's own independence)
    windows = draw(st.sampled_from([None, True, False]))
    dates = draw(st.booleans())   # the first axis datetime64: dates as new coordinates
    return dict(method=method, sizes=sizes, ncarried=ncarried, seed=seed, pointwise=pointwise,
                vectorised=vectorised, npoints=npoints, nan=nan, fill=fill, lazy=lazy, chunks=chunks,
                point_chunks=point_chunks, windows=windows, dates=dates)


def build(c):
    rng = np.random.default_rng(c["seed"])
    dims = [f"x{a}" for a in range(len(c["sizes"]))] + ["t"]
    coords = {}
    for d, n in zip(dims, c["sizes"]):
        x = np.linspace(0.0, 10.0, n)
        x[1:-1] += rng.uniform(-0.3, 0.3, n - 2) * 10.0 / max(n - 1, 1)
        coords[d] = x
    coords["t"] = np.arange(c["ncarried"], dtype=float)
    values = rng.normal(size=c["sizes"] + [c["ncarried"]])
    if c["nan"]:
        values.flat[rng.integers(0, values.size, max(1, values.size // 40))] = np.nan
    start = np.datetime64("2001-03-04T05:06:07", "ns")

    def as_dates(days):   # days after `start`, to the nanosecond
        return start + np.round(np.asarray(days) * 86400e9).astype("timedelta64[ns]")

    floats = dict(coords)
    if c["dates"]:
        coords["x0"] = as_dates(coords["x0"])
    data = xr.DataArray(values, dims=dims, coords=coords)

    def new_coordinate(d, n, pdim):
        x = floats[d]
        q = rng.uniform(x[0] - 1.5, x[-1] + 1.5, n)
        on_node = rng.random(n) < 0.2                       # some exactly on the nodes
        q[on_node] = x[rng.integers(0, len(x), on_node.sum())]
        if c["vectorised"]:   # one new coordinate per carried position: vectorised over t
            q = rng.uniform(x[0] - 1.0, x[-1] + 1.0, (c["ncarried"], n))
        if c["dates"] and d == "x0":
            q = as_dates(q)
        if c["vectorised"]:
            arr = xr.DataArray(q, dims=("t", pdim))
        elif c["pointwise"] or c["lazy"]:
            arr = xr.DataArray(q, dims=(pdim,))
        else:
            return q
        return arr.chunk({pdim: c["point_chunks"]}) if c["lazy"] else arr

    indexers = {}
    for d in dims[:-1]:
        pdim = "p" if c["pointwise"] else f"q{d}"
        indexers[d] = new_coordinate(d, c["npoints"], pdim)
    kwargs = None
    if c["fill"] == "number":
        kwargs = {"fill_value": -7.25}
    elif c["fill"] == "extrapolate":
        kwargs = {"fill_value": "extrapolate" if len(dims) == 2 and c["method"] != "pchip" else None}
        if c["method"] == "pchip" and len(dims) == 2:
            kwargs = {"extrapolate": True}
    return data, indexers, kwargs


def outcome(f):
    try:
        return "value", f()
    except Exception as err:   # noqa: BLE001 - the class is the outcome compared
        return "raises", type(err)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(c=calls())
def test_results_do_not_depend_on_the_chunking(c):
    if c["windows"] is None:
        check(c)
    else:
        with mock.patch.object(_xarray_dask, "use_windows", lambda *args: c["windows"]):
            check(c)


def check(c):
    data, indexers, kwargs = build(c)
    # the reference: in memory, with the new coordinates in memory too
    computed = {k: v.compute() if isinstance(v, xr.DataArray) else v for k, v in indexers.items()}
    whole = outcome(lambda: data.splinelab.interp(method=c["method"], kwargs=kwargs, **computed).values)
    chunked = data.chunk(dict(zip(data.dims, c["chunks"])))
    lazy = outcome(lambda: chunked.splinelab.interp(method=c["method"], kwargs=kwargs, **indexers))
    if whole[0] == "raises":
        # the same class where it is raised: at the call, or at compute
        got = lazy[1] if lazy[0] == "raises" else outcome(lambda: lazy[1].values)[1]
        assert got is whole[1], (c, whole, lazy)
        return
    assert lazy[0] == "value", (c, lazy)
    assert isinstance(lazy[1].data, da_mod.Array)
    assert bits(lazy[1].values) == bits(whole[1]), (c, lazy[1].values, whole[1])


@pytest.mark.parametrize("method", list(METHODS))
def test_a_point_does_not_depend_on_the_chunk_boundaries_beside_it(method):
    """Every chunking of a 60-sample axis (chunks of 1 to 60, and cut at
    each sample) gives the in-memory bits at points on and between the
    nodes, with NaN samples where the method takes them."""
    rng = np.random.default_rng(4)
    x = np.cumsum(rng.uniform(0.5, 1.5, 60))
    values = rng.normal(size=(60, 2))
    if method != "pchip":
        values[7, 1] = np.nan
    data = xr.DataArray(values, dims=("x", "t"), coords={"x": x, "t": [0.0, 1.0]})
    q = np.r_[x[[0, 5, 29, 30, 59]], rng.uniform(x[0], x[-1], 4)]
    whole = data.splinelab.interp(x=q, method=method).values
    for chunks in [(size,) * (60 // size) + ((60 % size,) if 60 % size else ()) for size in (1, 2, 7, 29, 60)] + [
            (cut, 60 - cut) for cut in range(1, 60, 3)]:
        got = data.chunk(x=chunks).splinelab.interp(x=q, method=method).values
        assert bits(got) == bits(whole), chunks
