"""spline_filter1d/spline_filter equal scipy 1.17.1's own output in every scipy mode name."""

import numpy as np
import pytest
import scipy.ndimage as ndi

import splinelab

MODES = ["mirror", "constant", "grid-constant", "wrap", "reflect", "grid-mirror", "nearest", "grid-wrap"]


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("order", [0, 1, 2, 3, 4, 5])
def test_spline_filter1d_equals_scipy(mode, order):
    x = np.random.default_rng(18).uniform(-1, 1, 40)
    ours = splinelab.spline_filter1d(x, order=order, mode=mode)
    ref = ndi.spline_filter1d(x, order=order, mode=mode)
    assert np.abs(ours - ref).max() <= 16 * np.spacing(np.abs(ref).max())


@pytest.mark.parametrize("mode", MODES)
def test_spline_filter_equals_scipy(mode):
    x = np.random.default_rng(7).uniform(-1, 1, (12, 17))
    ours = splinelab.spline_filter(x, order=3, mode=mode)
    ref = ndi.spline_filter(x, order=3, mode=mode)
    assert np.abs(ours - ref).max() <= 32 * np.spacing(np.abs(ref).max())


def test_exact_edges_differs_from_scipy_rule():
    x = np.random.default_rng(1).uniform(-1, 1, 40)
    exact = splinelab.spline_filter1d(x, order=3, mode="nearest", exact_edges=True)
    assert np.abs(exact - ndi.spline_filter1d(x, order=3, mode="nearest")).max() > 1e-3
    # Modes without edge values keep scipy's rule under exact_edges.
    np.testing.assert_array_equal(splinelab.spline_filter1d(x, order=3, mode="wrap", exact_edges=True),
                                  splinelab.spline_filter1d(x, order=3, mode="mirror"))


@pytest.mark.parametrize("mode", MODES)
def test_dask_follows_scipy_rule(mode):
    da = pytest.importorskip("dask.array")
    import splinelab.dask

    x = np.random.default_rng(3).uniform(-1, 1, 300)
    c = splinelab.dask.spline_filter(da.from_array(x, chunks=64), order=3, mode=mode, tol=1e-13).compute()
    ref = ndi.spline_filter(x, order=3, mode=mode)
    assert np.abs(c - ref).max() <= 1e-12
