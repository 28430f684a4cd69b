"""Every dtype scipy 1.17.1 takes, against scipy's own output computed live:
integer and boolean inputs and outputs (rounded / converted as scipy does),
output as a dtype, a dtype name or an array of any byte order and strides,
complex input, and aliasing refused."""

import warnings

import numpy as np
import pytest
from scipy import ndimage

import splinelab

EPS = np.finfo(np.float64).eps
INTS = [np.uint8, np.int8, np.uint16, np.int16, np.uint32, np.int32, np.uint64, np.int64]


def rng(seed=7):
    return np.random.default_rng(seed)


def image(dtype, shape=(30, 33), seed=1):
    if np.dtype(dtype) == bool:
        return rng(seed).uniform(-1, 1, shape) > 0
    info = np.iinfo(dtype) if np.dtype(dtype).kind in "iu" else None
    lo, hi = (max(info.min, -30000), min(info.max, 30000)) if info else (-1, 1)
    return rng(seed).uniform(lo, hi, shape).astype(dtype)


@pytest.mark.parametrize("dtype", INTS + [bool])
def test_integer_outputs_are_scipys_rounding_and_saturation(dtype):
    # Exact values (order 1 at the samples) at every edge of the conversion:
    # halves, out of range, NaN, 2**63, 2**64; scipy stores them by its C rule.
    special = np.array([-300.7, -2.5, -1.5, -0.5, -0.4, 0.49999999999999994, 0.5, 1.5, 2.5, 254.5, 255.5, 256.0,
                        300.2, 32767.5, 65535.5, 70000.6, 2.0**31 - 0.5, 2.0**31, 3e9, -3e9, 2.0**32, 5e9, 2.0**63,
                        2.0**64, 1e20, -1e20])
    x = np.zeros(3 * len(special))
    x[1::3] = special
    # The last point is outside: cval = NaN (the engine refuses NaN samples).
    at = np.append(np.arange(1, len(x), 3, dtype=float), -5.0)[None]
    ours = splinelab.map_coordinates(x, at, order=1, output=dtype, cval=np.nan)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        ref = ndimage.map_coordinates(x, at, order=1, output=dtype, cval=np.nan)
    assert ours.dtype == ref.dtype
    np.testing.assert_array_equal(ours, ref)


class _Float64Ndimage:
    """scipy.ndimage with output=float64: the values before conversion."""

    def __getattr__(self, name):
        f = getattr(ndimage, name)
        return lambda *a, **k: f(*a, **{**k, "output": np.float64})


ndimage_float64 = _Float64Ndimage()


def assert_equal_but_ties(ours, ref, values):
    differ = ours != ref
    if not differ.any():
        return
    v = values[differ]
    tie = np.abs(v - np.floor(v) - (0.0 if ours.dtype == bool else 0.5)) < 1e-9 * np.maximum(1, np.abs(v))
    tie |= np.abs(v - np.round(v)) < 1e-9 * np.maximum(1, np.abs(v)) if ours.dtype == bool else False
    assert tie.all(), (ours[differ][~tie], ref[differ][~tie], v[~tie])
    if ours.dtype != bool:
        assert (np.abs(ours[differ].astype(float) - ref[differ].astype(float)) <= 1).all()


@pytest.mark.parametrize("dtype", [np.uint8, np.int16, np.int32, np.float32, bool])
@pytest.mark.parametrize("d", [0, 1, 3, 5])
def test_output_none_is_the_input_dtype(dtype, d):
    # Integer images come back in their dtype, rounded as scipy rounds.
    x = image(dtype)
    pts = np.stack([rng(2).uniform(-2, 31, 500), rng(3).uniform(-2, 34, 500)])
    for call in (lambda f: f.map_coordinates(x, pts, order=d, mode="nearest"),
                 lambda f: f.zoom(x, 1.3, order=d, mode="mirror"),
                 lambda f: f.rotate(x, 20, order=d)):
        ours, ref = call(splinelab), call(ndimage)
        assert ours.dtype == ref.dtype == np.dtype(dtype)
        if np.dtype(dtype) == np.float32:
            # computed in float32 (scipy: float64, rounded): float32 ulps
            assert np.abs(ours - ref.astype(float)).max() <= 64 * np.finfo(np.float32).eps * np.abs(ref).max()
        else:
            # Rounding to integers: equal except at ties (a value within
            # rounding of a half-integer, or of an integer for bool, rounds
            # either way), where they are neighbours.
            assert_equal_but_ties(ours, ref, call(ndimage_float64))


@pytest.mark.parametrize("out", ["uint8", np.int16, np.dtype(">i4"), np.dtype(">f8"), np.float32, "<u2", bool])
def test_output_as_dtype_or_name(out):
    x = image(np.float64) * 200
    pts = np.stack([rng(4).uniform(0, 29, 300), rng(5).uniform(0, 32, 300)])
    ours = splinelab.map_coordinates(x, pts, output=out, order=3)
    ref = ndimage.map_coordinates(x, pts, output=out, order=3)
    assert ours.dtype == ref.dtype
    if ours.dtype.kind == "f":
        tol = 64 * np.finfo(ours.dtype).eps * np.abs(ref).max()
        assert np.abs(ours.astype(float) - ref.astype(float)).max() <= tol
    else:
        np.testing.assert_array_equal(ours, ref)


def test_output_arrays_of_any_byte_order_and_strides():
    x = image(np.float64) * 100
    big = np.zeros((44, 48), dtype=">f8")
    strided = np.zeros((88, 48), dtype=np.int16)[::2]
    fortran = np.zeros((44, 48), dtype=np.float32, order="F")
    for out in (big, strided, fortran):
        ours = splinelab.zoom(x, 1.45, output=out)
        assert ours is out
        ref = ndimage.zoom(x, 1.45, output=np.zeros(out.shape, out.dtype))
        if out.dtype.kind == "i":
            np.testing.assert_array_equal(ours, ref)
        else:
            assert np.abs(ours.astype(float) - ref.astype(float)).max() <= 64 * np.finfo(out.dtype).eps * 100
    # Big-endian input too.
    xb = x.astype(">f8")
    np.testing.assert_allclose(splinelab.shift(xb, 1.5), ndimage.shift(xb, 1.5), rtol=0, atol=32 * EPS * 100)


@pytest.mark.parametrize("dtype", [np.uint8, np.int16, np.int32, np.float32, bool, np.dtype(">f8")])
def test_integer_and_bool_inputs_in_the_filters(dtype):
    # Computed in float64; integer outputs truncated as scipy's filter stores them.
    x = image(dtype)
    for out in (np.float64, np.float32, None, np.int32, np.int16):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            ours = splinelab.spline_filter(x, order=3, output=out)
            ref = ndimage.spline_filter(x, order=3, output=out)
        assert ours.dtype == ref.dtype, out
        scale = np.abs(ref.astype(float)).max()
        if ours.dtype.kind == "f":
            assert np.abs(ours.astype(float) - ref.astype(float)).max() <= 32 * np.finfo(ours.dtype).eps * scale
        else:
            np.testing.assert_array_equal(ours, ref)
    ours = splinelab.spline_filter1d(x, order=1, axis=0, output=np.uint8)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        np.testing.assert_array_equal(ours, ndimage.spline_filter1d(x, order=1, axis=0, output=np.uint8))


@pytest.mark.parametrize("dtype", [np.complex128, np.complex64])
def test_complex_input_part_by_part(dtype):
    x = (rng(8).uniform(-1, 1, (26, 28)) + 1j * rng(9).uniform(-1, 1, (26, 28))).astype(dtype)
    eps = np.finfo(x.real.dtype).eps
    pts = np.stack([rng(10).uniform(-2, 27, 300), rng(11).uniform(-2, 29, 300)])
    calls = [
        lambda f: f.spline_filter(x, order=3, output=dtype),
        lambda f: f.spline_filter1d(x, order=5, axis=0, output=dtype),
        lambda f: f.map_coordinates(x, pts, order=3, mode="mirror"),
        lambda f: f.map_coordinates(x, pts, order=3, cval=0.5 - 0.25j),
        lambda f: f.zoom(x, 1.5, order=3, mode="grid-wrap"),
        lambda f: f.shift(x, (1.5, -2.25), order=5, mode="nearest", cval=1j),
        lambda f: f.rotate(x, 33, order=3, cval=1 + 1j),
        lambda f: f.affine_transform(x, [[1.0, 0.1], [0.2, 0.9]], order=2, mode="wrap"),
    ]
    for k, call in enumerate(calls):
        ours, ref = call(splinelab), call(ndimage)
        assert ours.dtype == ref.dtype, k
        assert np.abs(ours - ref).max() <= 64 * eps * np.abs(ref).max(), k
    with pytest.warns(UserWarning, match="complex"):
        assert splinelab.spline_filter(x, output=np.float64).dtype == np.complex128


def test_an_aliased_output_gets_the_separate_outputs_result():
    # Computed into new arrays, then written into `output`: as scipy does
    # where it reads a prefiltered copy (degree 3 here).
    x = rng(12).uniform(-1, 1, (20, 20))
    for call in [lambda m, a, out: m.shift(a, 1.5, output=out),
                 lambda m, a, out: m.rotate(a, 90, reshape=False, output=out),
                 lambda m, a, out: m.map_coordinates(a, a[:2, :2] * 10 + 5, output=out[0, :2])]:
        y, z = x.copy(), x.copy()
        call(splinelab, y, y)
        call(ndimage, z, z)
        np.testing.assert_allclose(y, z, rtol=0, atol=1e-12)
    # The filters read the input first: in place stays allowed (documented).
    y = x.copy()
    assert splinelab.spline_filter(y, output=y) is y
