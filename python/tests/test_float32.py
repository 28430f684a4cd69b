"""float32, complex64 and float16 data computed as scipy computes them
(issue 42): in float64 (complex128), rounded once into the narrow result.

The sweep (``float32_sweep.py``: the eight functions, orders 0-5, every
mode, 1-D to 3-D) compares each narrow call with the same call on the data
widened exactly, rounded once: at least 99.9 % equal and none more than one
ulp of the narrow dtype away (``python/bench/float32_accuracy.py`` runs the
same sweep on scipy side by side). ``compute="float32"`` keeps the float32
arithmetic: it differs from that, within its stated bound.
"""

import numpy as np
import pytest
import scipy.ndimage as ndi

import splinelab
from float32_sweep import MODES, WIDE, data, sweep, ulps


@pytest.mark.parametrize("dtype", [np.float32, np.complex64, np.float16])
def test_narrow_data_is_the_float64_result_rounded_once(dtype):
    count, equal, worst, where, refused = sweep(splinelab, dtype)
    assert refused == 0
    assert count > 10**5
    assert equal / count >= 0.999, (equal, count)
    assert worst <= 1.0, (worst, where)


def per_axis(x, order, mode, out_dtype):
    """scipy's ``spline_filter(x, output=float32)``: each axis filtered in
    float64 from the previous axis' float32 values, rounded once."""
    cur = x
    for axis in range(x.ndim):
        cur = splinelab.spline_filter1d(cur.astype(np.float64), order=order, axis=axis, mode=mode).astype(out_dtype)
    return cur


@pytest.mark.parametrize("shape", [(40,), (13, 17), (9, 8, 11)])
@pytest.mark.parametrize("order", [2, 3, 5])
def test_float32_filter_output_is_rounded_after_every_axis_as_scipy(shape, order):
    x = data(shape, np.float32, seed=order)
    for mode in ("mirror", "reflect", "grid-wrap", "nearest"):
        got = splinelab.spline_filter(x, order=order, mode=mode, output=np.float32)
        assert got.dtype == np.float32
        want = per_axis(x, order, mode, np.float32)
        np.testing.assert_array_equal(got, want)
        # As accurate as scipy's: against float64 rounded once, no farther
        # than scipy's own result is (plus one rounding of slack).
        ref = splinelab.spline_filter(x.astype(np.float64), order=order, mode=mode).astype(np.float32)
        ours = ulps(got, ref).max()
        theirs = ulps(ndi.spline_filter(x, order=order, mode=mode, output=np.float32), ref).max()
        assert ours <= theirs + 1.0, (mode, ours, theirs)
        # In place (output=x): the same values.
        y = x.copy()
        splinelab.spline_filter(y, order=order, mode=mode, output=y)
        np.testing.assert_array_equal(y, got)


def test_float32_input_reads_where_it_lies():
    """Strided, transposed and big-endian float32 input gives the values of
    its contiguous native copy."""
    x = data((24, 30), np.float32, seed=3)
    at = np.stack([np.linspace(-1, 23, 50), np.linspace(0.3, 31, 50)])
    for view in (x[::2, ::3], x.T, x.astype(">f4")):
        want = splinelab.map_coordinates(np.ascontiguousarray(view).astype(np.float32), at[:, :20] % 10,
                                         order=3, mode="mirror")
        got = splinelab.map_coordinates(view, at[:, :20] % 10, order=3, mode="mirror")
        assert got.dtype == np.float32
        np.testing.assert_array_equal(got, want)


@pytest.mark.parametrize("mode", MODES)
def test_compute_float32_is_the_float32_arithmetic_within_its_bound(mode):
    """The opt-in: float32 samples and arithmetic. It is not the float64
    result rounded once (it differs at some points), and it stays within
    ``4 (A + 1) 2**-24 max|x|`` of it (``A`` the amplification)."""
    x = data((64, 48), np.float32, seed=9)
    at = np.stack([np.random.default_rng(1).uniform(-3, n + 2, 3000) for n in x.shape])
    a = splinelab.filter_bound(3)["amplification"]
    ref = splinelab.map_coordinates(x.astype(np.float64), at, order=3, mode=mode)
    opt = splinelab.map_coordinates(x, at, order=3, mode=mode, compute="float32")
    default = splinelab.map_coordinates(x, at, order=3, mode=mode)
    assert opt.dtype == default.dtype == np.float32
    np.testing.assert_array_equal(default, ref.astype(np.float32))
    assert not np.array_equal(opt, default)
    err = np.abs(opt.astype(np.float64) - ref).max() / np.abs(x).max()
    assert err <= 4 * (a + 1) * 2.0**-24, err


def test_compute_is_taken_everywhere_and_checked():
    x = data((12, 10), np.float32)
    for f in (lambda **k: splinelab.zoom(x, 1.5, **k), lambda **k: splinelab.shift(x, 0.3, **k),
              lambda **k: splinelab.rotate(x, 10, **k), lambda **k: splinelab.affine_transform(x, [1.0, 0.9], **k),
              lambda **k: splinelab.spline_filter(x, output=np.float32, **k),
              lambda **k: splinelab.spline_filter1d(x, output=np.float32, **k),
              lambda **k: splinelab.geometric_transform(x, lambda o: o, **k),
              lambda **k: splinelab.spline_gradient(x, [[1.5], [2.5]], **k)):
        assert f(compute="float32").dtype == f().dtype == np.float32
        with pytest.raises(ValueError, match="compute"):
            f(compute="float16")


@pytest.mark.parametrize("dtype", [np.uint8, np.int16, np.int32, np.uint64])
def test_integers_are_computed_in_float64(dtype):
    """Integer input (read through an exact float32 or float64 copy) gives
    the float64 values of its samples, and float32 results rounded once."""
    x = (np.random.default_rng(2).uniform(0, 100, (14, 15))).astype(dtype)
    want = splinelab.zoom(x.astype(np.float64), 1.7, order=3, mode="mirror")
    got = splinelab.zoom(x, 1.7, order=3, mode="mirror", output=np.float32)
    np.testing.assert_array_equal(got, want.astype(np.float32))
    got = splinelab.zoom(x, 1.7, order=3, mode="mirror", output=np.float64)
    np.testing.assert_array_equal(got, want)


def test_prefilter_false_float32_coefficients_are_read_in_float64():
    x = data((20, 21), np.float32, seed=4)
    c = splinelab.spline_filter(x, order=3, output=np.float32)
    at = np.stack([np.linspace(0, 19, 40), np.linspace(20, 0, 40)])
    want = splinelab.map_coordinates(c.astype(np.float64), at, order=3, prefilter=False).astype(np.float32)
    got = splinelab.map_coordinates(c, at, order=3, prefilter=False)
    np.testing.assert_array_equal(got, want)
    assert got.dtype == np.float32 and WIDE[np.dtype(np.float32)] is np.float64
