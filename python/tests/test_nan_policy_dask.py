"""nan_policy on dask: 'local' gives the unchunked NaN pattern whatever the
chunking, and values within the bound of the unchunked ones; 'propagate'
gives scipy's whole-array pattern (the global reduction)."""

import numpy as np
import pytest
from scipy import ndimage

da = pytest.importorskip("dask.array")

import splinelab  # noqa: E402
import splinelab.dask  # noqa: E402

TOL = 1e-9


def image(shape=(96, 90), seed=4):
    a = np.random.default_rng(seed).uniform(-1, 1, shape)
    a[0, 3] = np.nan
    a[50, 45] = np.inf
    a[95, 89] = -np.inf
    a[70, 0] = np.nan
    return a


@pytest.mark.parametrize("chunks", [(32, 90), (24, 29), (96, 17)])
@pytest.mark.parametrize("mode", ["mirror", "reflect", "grid-wrap"])
@pytest.mark.parametrize("order", [3, 5])
def test_local_filter_has_the_unchunked_pattern_whatever_the_chunking(chunks, mode, order):
    a = image()
    whole = splinelab.spline_filter(a, order, mode=mode, nan_policy="local", tol=TOL)
    part = splinelab.dask.spline_filter(da.from_array(a, chunks=chunks), order, mode=mode, tol=TOL,
                                        nan_policy="local").compute()
    np.testing.assert_array_equal(np.isnan(part), np.isnan(whole))
    assert np.isnan(whole).any() and np.isfinite(whole).any()
    ok = np.isfinite(whole)
    big = np.abs(a[np.isfinite(a)]).max()
    f = splinelab.filter_bound(order, TOL)
    amp, b = f["amplification"], f["bound"]
    # Both within the local bound of the exact spline of one filling, and the
    # chunked route within dask's own bound of it.
    allowed = (2 * ((amp + b) ** 2 - (amp - b) ** 2) + splinelab.dask.bound(order, TOL, 2)) * big + 1e-13
    assert np.abs(part[ok] - whole[ok]).max() <= allowed


@pytest.mark.parametrize("chunks", [(32, 90), (24, 29)])
def test_local_zoom_has_the_unchunked_pattern(chunks):
    a = image()
    whole = splinelab.zoom(a, 1.5, order=3, mode="mirror", nan_policy="local", tol=TOL)
    part = splinelab.dask.zoom(da.from_array(a, chunks=chunks), 1.5, order=3, mode="mirror", tol=TOL,
                               nan_policy="local").compute()
    np.testing.assert_array_equal(np.isnan(part), np.isnan(whole))
    ok = np.isfinite(whole)
    assert np.abs(part[ok] - whole[ok]).max() <= 1e-6


@pytest.mark.parametrize("order", [1, 3])
def test_propagate_is_scipys_whole_array_pattern(order):
    a = np.random.default_rng(2).uniform(-1, 1, (30, 26))
    a[7, 25] = np.nan
    d = da.from_array(a, chunks=(10, 13))
    np.testing.assert_array_equal(~np.isfinite(splinelab.dask.spline_filter1d(d, 3, axis=0).compute()),
                                  ~np.isfinite(ndimage.spline_filter1d(a, 3, axis=0)))
    np.testing.assert_array_equal(~np.isfinite(splinelab.dask.spline_filter(d, 3).compute()),
                                  ~np.isfinite(ndimage.spline_filter(a, 3)))
    np.testing.assert_array_equal(~np.isfinite(splinelab.dask.zoom(d, 1.4, order=order, mode="mirror").compute()),
                                  ~np.isfinite(ndimage.zoom(a, 1.4, order=order, mode="mirror")))


def test_raise_and_unknown_policy_on_dask():
    a = image()
    with pytest.raises(ValueError, match="is not finite"):
        splinelab.dask.spline_filter(da.from_array(a, chunks=16), 3, nan_policy="raise").compute()
    with pytest.raises(ValueError, match="'propagate', 'raise' or 'local'"):
        splinelab.dask.spline_filter(da.from_array(a, chunks=16), 3, nan_policy="drop")
