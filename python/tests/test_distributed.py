"""A dask.distributed round trip (issue 51): the graphs of ``splinelab.dask``
and of the xarray accessor pickle, run on process workers that share no
memory with the client, and give the in-memory numbers within the stated
bound.

One ``LocalCluster`` per module: 2 process workers (``processes=True``),
1 thread each, a 1 GiB memory limit each, no dashboard, loopback only.
Small sizes: the module runs in a few seconds, most of it the cluster's
start. The results are gathered with ``client.compute(...).result()`` (not
the default scheduler), so every task runs in a worker process.
"""

import numpy as np
import pytest

distributed = pytest.importorskip("distributed")
da = pytest.importorskip("dask.array")
xr = pytest.importorskip("xarray", reason="pip install splinelab[xarray]")

import splinelab  # noqa: E402
import splinelab.dask as sld  # noqa: E402
import splinelab.xarray  # noqa: E402,F401  (registers the accessor)

EPS = np.finfo(np.float64).eps


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, memory_limit="1GiB",
                                  host="127.0.0.1", dashboard_address=None) as cluster, \
            distributed.Client(cluster) as c:
        yield c


def _run_in_workers(client, lazy):
    """``lazy`` computed by the cluster: every task in a worker process."""
    return client.compute(lazy).result()


def test_workers_are_separate_processes(client):
    import os
    pids = set(client.run(os.getpid).values())
    assert len(pids) == 2 and os.getpid() not in pids


def test_affine_transform_round_trip(client):
    """A cubic rotation of a 96 x 80 array in 24 x 20 chunks (16 blocks):
    within ``bound(3, tol, 2) * max|input|`` (plus rounding) of
    ``splinelab.affine_transform`` in memory."""
    x = np.random.default_rng(51).uniform(-1, 1, (96, 80))
    c, s = np.cos(0.1), np.sin(0.1)
    matrix, offset = np.array([[c, -s], [s, c]]), np.array([4.0, -3.0])
    tol = 1e-12
    lazy = sld.affine_transform(da.from_array(x, chunks=(24, 20)), matrix, offset, order=3, mode="mirror", tol=tol,
                                chunks=(32, 40))
    got = _run_in_workers(client, lazy)
    exact = splinelab.affine_transform(x, matrix, offset, order=3, mode="mirror")
    assert got.shape == exact.shape and lazy.numblocks == (3, 2)
    assert np.abs(got - exact).max() <= sld.bound(3, tol, 2) * np.abs(x).max() + 64 * EPS * np.abs(exact).max()


def test_map_coordinates_round_trip(client):
    """Cubic ``map_coordinates`` of 400 points in 4 chunks from a 64 x 64
    array in 16 x 16 chunks: within the same bound of the in-memory call."""
    x = np.random.default_rng(52).uniform(-1, 1, (64, 64))
    pts = np.random.default_rng(53).uniform(-2, 65, (2, 400))
    tol = 1e-12
    lazy = sld.map_coordinates(da.from_array(x, chunks=16), da.from_array(pts, chunks=(2, 100)), order=3,
                               mode="reflect", tol=tol)
    got = _run_in_workers(client, lazy)
    exact = splinelab.map_coordinates(x, pts, order=3, mode="reflect")
    assert np.abs(got - exact).max() <= sld.bound(3, tol, 2) * np.abs(x).max() + 64 * EPS * np.abs(exact).max()


def test_xarray_cubic_interp_round_trip(client):
    """The accessor's cubic interpolation of a DataArray (time 120 in chunks
    of 10, lat 16 in chunks of 8, lon 12; non-uniform time) onto new time
    and lat coordinates, computed on the cluster: within ``tol * max|data|``
    (plus rounding) of the same call on the in-memory DataArray, the bound
    the accessor states for windows on chunked axes."""
    rng = np.random.default_rng(54)
    t = np.cumsum(rng.uniform(0.5, 1.5, 120))
    lat, lon = np.linspace(-40.0, 40.0, 16), np.linspace(0.0, 330.0, 12)
    data = xr.DataArray(rng.normal(size=(120, 16, 12)), dims=("time", "lat", "lon"),
                        coords={"time": t, "lat": lat, "lon": lon}, attrs={"units": "K"}, name="temp")
    new = dict(time=np.linspace(t[3], t[-4], 37), lat=np.linspace(-35.0, 35.0, 9))
    tol = 1e-12
    whole = data.splinelab.interp(method="cubic", **new)
    lazy = data.chunk(time=10, lat=8).splinelab.interp(method="cubic", tol=tol, **new)
    assert isinstance(lazy.data, da.Array)
    got = _run_in_workers(client, lazy.data)
    assert got.shape == whole.shape and lazy.dims == whole.dims and lazy.attrs == whole.attrs
    scale = np.abs(data.values).max()
    assert (np.abs(got - whole.values) <= tol * scale + 1e-14 * np.maximum(scale, np.abs(whole.values))).all()
