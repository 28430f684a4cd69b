"""The ``tol=`` route of spline_filter1d / spline_filter against scipy 1.17.1's
exact filter: within the certified bound, and on long lines really the
blocks (a loose tolerance shows a difference of the bound's order)."""

import numpy as np
import pytest
import scipy.ndimage as ndi

import splinelab

MODES = ["mirror", "constant", "grid-constant", "wrap", "reflect", "grid-mirror", "nearest", "grid-wrap"]
EPS = np.finfo(np.float64).eps


def allowed(order, tol, x):
    """bound * max|x| plus the rounding of both exact filters (64 u A max|x|)."""
    f = splinelab.filter_bound(order, tol)
    return (f["bound"] + 64 * EPS * f["amplification"]) * np.abs(x).max()


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("order", [3, 5])
@pytest.mark.parametrize("tol", [1e-4, 1e-12])
def test_long_line_within_the_bound_of_scipy(mode, order, tol):
    x = np.random.default_rng(order).uniform(-1, 1, 100_000)
    ours = splinelab.spline_filter1d(x, order=order, mode=mode, tol=tol)
    ref = ndi.spline_filter1d(x, order=order, mode=mode)
    err = np.abs(ours - ref).max()
    assert err <= allowed(order, tol, x)
    if tol == 1e-4:
        # The blocks ran: their truncation is visible, far above rounding.
        assert err > 1e-3 * splinelab.filter_bound(order, tol)["bound"]


def test_long_line_same_bits_whatever_the_threads():
    x = np.random.default_rng(3).uniform(-1, 1, 300_000)
    one = splinelab.spline_filter1d(x, order=3, tol=1e-12, threads=1)
    two = splinelab.spline_filter1d(x, order=3, tol=1e-12, threads=2)
    np.testing.assert_array_equal(one, two)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_long_line_errors_are_reported(dtype):
    x = np.ones(100_000, dtype)
    x[77_777] = np.nan
    with pytest.raises(ValueError, match=r"sample 77777 is not finite \(nan\)"):
        splinelab.spline_filter1d(x, order=3, tol=1e-9, output=dtype, nan_policy="raise")
    big = np.full(100_000, np.finfo(dtype).max / 2, dtype)
    with pytest.raises(ValueError, match="could overflow"):
        splinelab.spline_filter1d(big, order=3, tol=1e-9, output=dtype)


@pytest.mark.parametrize("order", [3, 5])
def test_nd_within_the_bound_of_scipy(order):
    x = np.random.default_rng(9).uniform(-1, 1, (64, 300))
    tol = 1e-6
    ours = splinelab.spline_filter(x, order=order, tol=tol)
    ref = ndi.spline_filter(x, order=order)
    f = splinelab.filter_bound(order, tol)
    a, b = f["amplification"], f["bound"]
    total = ((a + b) ** 2 - a**2 + 64 * EPS * a**2) * np.abs(x).max()
    assert np.abs(ours - ref).max() <= total


def test_float32_long_line_within_the_bound_of_scipy():
    x = np.random.default_rng(5).uniform(-1, 1, 100_000).astype(np.float32)
    ours = splinelab.spline_filter1d(x, order=3, tol=1e-6, output=np.float32)
    ref = ndi.spline_filter1d(x.astype(np.float64), order=3)
    f = splinelab.filter_bound(3, 1e-6)
    eps32 = float(np.finfo(np.float32).eps)
    assert np.abs(ours - ref).max() <= f["bound"] + 64 * eps32 * f["amplification"]
