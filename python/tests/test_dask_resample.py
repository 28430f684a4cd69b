"""Resampling on dask (splinelab.dask.map_coordinates, zoom, shift,
affine_transform, rotate) with chunks of a few samples: the coefficients
come once from the certified chunked prefilter and each output chunk reads
only its region, so the result is within bound(order, tol, ndim) *
max|input| (+ rounding) of the unchunked splinelab result, every mode."""

import warnings

import dask.array as da
import numpy as np
import pytest

import splinelab
import splinelab.dask as sld

EPS = np.finfo(np.float64).eps
MODES = ["constant", "mirror", "reflect", "grid-wrap", "wrap", "nearest", "grid-constant"]


@pytest.fixture(scope="module")
def data():
    return np.random.default_rng(30).uniform(-1, 1, (40, 37))


def within(ours, ref, x, order, tol=sld.DEFAULT_TOL):
    b = sld.bound(max(order, 2), tol, ndim=2) if order > 1 else 0.0
    err = np.abs(ours - ref).max()
    assert err <= b * np.abs(x).max() + 64 * EPS * np.abs(ref).max(), err
    return err


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("order", [0, 3])
def test_chunked_equals_unchunked_within_bound(data, order, mode):
    d = da.from_array(data, chunks=7)
    m = [[0.9, 0.2], [-0.3, 1.1]]
    at = np.random.default_rng(31).uniform(-50, 90, (2, 300))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cases = [
            (sld.zoom(d, 1.6, order=order, mode=mode, chunks=9), splinelab.zoom(data, 1.6, order=order, mode=mode)),
            (sld.shift(d, (2.5, -7.25), order=order, mode=mode, cval=0.5, chunks=11),
             splinelab.shift(data, (2.5, -7.25), order=order, mode=mode, cval=0.5)),
            (sld.rotate(d, 33, order=order, mode=mode, chunks=12), splinelab.rotate(data, 33, order=order, mode=mode)),
            (sld.affine_transform(d, m, [3, -40], order=order, mode=mode, chunks=(5, 13)),
             splinelab.affine_transform(data, m, [3, -40], order=order, mode=mode)),
            (sld.map_coordinates(d, da.from_array(at, chunks=(2, 17)), order=order, mode=mode),
             splinelab.map_coordinates(data, at, order=order, mode=mode)),
        ]
    for ours, ref in cases:
        within(ours.compute(), ref, data, order)


@pytest.mark.parametrize("axes", [(1, 0), (0, 2), (2, 1)])
@pytest.mark.parametrize("mode", ["constant", "mirror", "grid-wrap", "nearest"])
def test_rotate_3d_equals_scipys_plane_by_plane(axes, mode):
    # One N-D affine map on dask (identity off the plane) against
    # splinelab.rotate, which rotates plane by plane as scipy does (checked
    # against scipy in test_resample.py): equal within the 3-D bound.
    x = np.random.default_rng(32).uniform(-1, 1, (9, 11, 10))
    ours = sld.rotate(da.from_array(x, chunks=5), 27, axes=axes, order=3, mode=mode, chunks=6).compute()
    ref = splinelab.rotate(x, 27, axes=axes, order=3, mode=mode)
    assert ours.shape == ref.shape
    b = sld.bound(3, sld.DEFAULT_TOL, ndim=3)
    err = np.abs(ours - ref).max()
    assert err <= b * np.abs(x).max() + 64 * EPS * np.abs(ref).max(), err


def test_each_chunk_reads_only_its_region(data):
    # An interior zoom chunk's region is its points' box plus the support,
    # not the whole array.
    plan = sld._Plan(da.from_array(data, chunks=8), 3, "mirror", 0.0, sld.DEFAULT_TOL, "truncated", 1)
    x, _ = plan.prepared(np.array([[10.0, 12.5], [20.0, 22.0]]))
    assert plan.region(x) == [(6, 18), (16, 27)]  # floor(min) - 4 .. ceil(max) + 5


FUSED_MODES = ["constant", "mirror", "reflect", "grid-mirror", "wrap", "nearest", "grid-constant"]


@pytest.mark.parametrize("mode", FUSED_MODES)
def test_fused_blocks_equal_unchunked_within_bound(mode):
    """On an array several overlaps wide, each output block prefilters its
    own region (seams inside the array, padding at its edges): within the
    chunked filter's bound of the in-memory result, every mode that fuses."""
    x = np.random.default_rng(33).uniform(-1, 1, (150, 140))
    d = da.from_array(x, chunks=50)
    plan = sld._Plan(d, 3, mode, 0.0, sld.DEFAULT_TOL, "truncated", 1, fuse=True)
    assert plan.fused is not None and sld.depth(3) < 50
    m = [[0.9, 0.2], [-0.3, 1.1]]
    for ours, ref in [(sld.rotate(d, 33, order=3, mode=mode, chunks=45), splinelab.rotate(x, 33, order=3, mode=mode)),
                      (sld.affine_transform(d, m, [30, -40], order=3, mode=mode, chunks=(40, 60)),
                       splinelab.affine_transform(x, m, [30, -40], order=3, mode=mode)),
                      (sld.zoom(d, 1.3, order=5, mode=mode, chunks=70), splinelab.zoom(x, 1.3, order=5, mode=mode))]:
        b = sld.bound(5, sld.DEFAULT_TOL, ndim=2)
        err = np.abs(ours.compute() - ref).max()
        assert err <= b * np.abs(x).max() + 64 * EPS * np.abs(ref).max(), err


def test_fused_blocks_propagate_a_missing_sample_as_scipy():
    """One NaN sample: scipy's pattern (every coefficient NaN, so every
    value but the 'constant' ones outside), as splinelab in memory."""
    x = np.random.default_rng(34).uniform(-1, 1, (120, 110))
    x[100, 7] = np.nan
    ours = sld.rotate(da.from_array(x, chunks=40), 20, order=3, chunks=50).compute()
    ref = splinelab.rotate(x, 20, order=3)
    assert np.array_equal(np.isnan(ours), np.isnan(ref)) and np.isnan(ref).mean() > 0.5
    assert np.array_equal(ours[~np.isnan(ref)], ref[~np.isnan(ref)])


def test_graph_holds_no_coordinates():
    """The output blocks make their own points: the pickled graph of a
    2400² rotation in 600² blocks is a few kilobytes a block (its 5.8 M
    points would be 92 MB), and a few tasks a block."""
    cloudpickle = pytest.importorskip("cloudpickle")
    lazy = sld.rotate(da.zeros((2400, 2400), chunks=600, dtype=np.float32), 5, reshape=False, chunks=600)
    graph = dict(lazy.__dask_graph__())
    assert len(cloudpickle.dumps(graph)) < 16 * 1024 * 16 and len(graph) < 30 * 16


def test_local_cluster(data):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as c:
        with distributed.Client(c):
            ours = sld.zoom(da.from_array(data, chunks=10), 1.3, order=5, mode="reflect").compute()
    within(ours, splinelab.zoom(data, 1.3, order=5, mode="reflect"), data, 5)


def test_refusals(data):
    with pytest.raises(TypeError, match="float64 or float32"):
        sld.zoom(da.from_array(data), 2, output=np.uint8)
    with pytest.raises(ValueError, match="at least 2D"):
        sld.rotate(da.ones(4), 10)
    with pytest.raises(ValueError, match="rotation plane"):
        sld.rotate(da.ones((4, 4, 4)), 10, axes=(1, 1))
    with pytest.raises(ValueError, match="coordinates must have shape"):
        sld.map_coordinates(da.from_array(data), da.ones((3, 5)))
