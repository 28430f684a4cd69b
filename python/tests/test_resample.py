"""zoom, shift, rotate, affine_transform and geometric_transform against
scipy 1.17.1's own output, computed live: every mode, degrees 0..5, float64
and float32, 1-D to 3-D, points inside, at the edges and outside."""

import numpy as np
import pytest
from scipy import ndimage, special

import splinelab

EPS64 = np.finfo(np.float64).eps
EPS32 = np.finfo(np.float32).eps
MODES = ["constant", "grid-constant", "nearest", "mirror", "reflect", "grid-mirror", "grid-wrap", "wrap"]
# Lines of at least 24 samples: scipy 1.17.1's filters are wrong on shorter
# ones in reflect / grid-mirror / nearest (gh-24550) and, for quintics, in
# mirror (test_scipy.py judges those against check's MPFR reference).
SHAPES = [(40,), (26, 31), (24, 25, 27)]


def rng(seed=7):
    return np.random.default_rng(seed)


def ulps_of_max(ours, ref, eps=EPS64):
    ours, ref = np.asarray(ours, np.float64), np.asarray(ref, np.float64)
    assert ours.shape == ref.shape
    return np.abs(ours - ref).max() / (eps * max(np.abs(ref).max(), 1e-300))


def calls(x):
    """(name, ours, scipy's) for each function on ``x`` (1-D to 3-D)."""
    n = x.ndim
    m = np.eye(n) * 0.93 + 0.17 * np.ones((n, n)) - np.diag(np.arange(n) * 0.05)
    offset = [-2.5 + k for k in range(n)]
    out_shape = tuple(s + 3 for s in x.shape)
    cases = [
        ("zoom", lambda f, **k: f.zoom(x, 1.37, **k)),
        ("zoom-grid", lambda f, **k: f.zoom(x, [0.7, 1.9, 1.3][:n], grid_mode=True, **k)),
        ("zoom-down", lambda f, **k: f.zoom(x, 0.45, **k)),
        ("shift", lambda f, **k: f.shift(x, [2.3, -4.75, 0.5][:n], **k)),
        ("affine", lambda f, **k: f.affine_transform(x, m, offset, output_shape=out_shape, **k)),
        ("affine-diag", lambda f, **k: f.affine_transform(x, np.diag(m), offset, **k)),
        ("affine-homog", lambda f, **k: f.affine_transform(x, np.vstack([np.hstack([m, np.array(offset)[:, None]]),
                                                                         [0] * n + [1]]), **k)),
        ("geometric", lambda f, **k: f.geometric_transform(x, lambda o: tuple(0.8 * i - 1.25 for i in o), **k)),
    ]
    if n >= 2:
        cases.append(("rotate", lambda f, **k: f.rotate(x, 31.0, axes=(0, n - 1), **k)))
        cases.append(("rotate-same", lambda f, **k: f.rotate(x, -117.0, reshape=False, **k)))
    return cases


@pytest.mark.filterwarnings("ignore:It is recommended")
@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("d", [0, 1, 2, 3, 4, 5])
def test_float64_equals_scipy(d, mode):
    # Both round a sum of (d + 1)^ndim products of a filtered array: a few
    # ulps of max|value| per dimension times the filter's amplification.
    # Allowed: 16 ulps per dimension, 32 for quartics and quintics (their
    # filters amplify rounding more). Worst seen (all modes and functions):
    # degrees 1-3: 15.5 (1-D), 12.3 (3-D); quintics: 25.2 (1-D), 29.1 (2-D),
    # 52.2 (3-D).
    allowed = (16 if d <= 3 else 32)
    for shape in SHAPES:
        x = rng(len(shape)).uniform(-1, 1, shape)
        for name, call in calls(x):
            if name == "geometric" and len(shape) == 3:
                continue  # the per-point callable: 2-D is enough (slow in both)
            kw = dict(order=d, mode=mode, cval=0.375)
            ours, ref = call(splinelab, **kw), call(ndimage, **kw)
            assert ours.dtype == np.float64
            assert ulps_of_max(ours, ref) <= allowed * len(shape), (name, shape)


@pytest.mark.filterwarnings("ignore:It is recommended")
@pytest.mark.parametrize("mode", ["constant", "nearest", "mirror", "grid-wrap", "wrap"])
@pytest.mark.parametrize("d", [1, 3, 5])
def test_float32_computed_in_float32(d, mode):
    # float32 in, float32 out: computed in float32 (scipy: float64, then
    # rounded), so within float32 ulps times the amplification.
    x = rng(3).uniform(-1, 1, (26, 31)).astype(np.float32)
    for name, call in calls(x):
        kw = dict(order=d, mode=mode, cval=0.375)
        ours, ref = call(splinelab, **kw), call(ndimage, **kw)
        assert ours.dtype == np.float32 and ref.dtype == np.float32
        assert ulps_of_max(ours, ref, EPS32) <= 64, name


def test_zoom_shapes_and_factor_rule():
    # round(n * zoom) per axis (Python's round), and an axis of one output
    # sample, and zoom 1 (scipy returns the input, converted).
    x = rng(4).uniform(0, 255, (10, 7, 3))
    for z in [(0.25, 1.5, 1 / 3), (0.05, 2.5, 1.0), (1, 1, 1)]:
        ours, ref = splinelab.zoom(x, z), ndimage.zoom(x, z)
        assert ours.shape == ref.shape
        if ref.size:
            assert ulps_of_max(ours, ref) <= 16, z
    u8 = x.astype(np.uint8)
    np.testing.assert_array_equal(splinelab.zoom(u8, 1, output=np.int8), ndimage.zoom(u8, 1, output=np.int8))
    with pytest.warns(UserWarning, match="grid-constant"):
        splinelab.zoom(x, 2, grid_mode=True)


def test_rotate_shapes_axes_and_angles():
    x = rng(5).uniform(-1, 1, (9, 14, 11))
    for angle in [0, 30, 45, 90, 180, 270, -90, 1e-9, 359.5, 725.25]:
        for axes in [(1, 0), (0, 2), (-1, 1), (2, 0)]:
            for reshape in (True, False):
                ours = splinelab.rotate(x, angle, axes=axes, reshape=reshape, order=3)
                ref = ndimage.rotate(x, angle, axes=axes, reshape=reshape, order=3)
                assert ours.shape == ref.shape, (angle, axes, reshape)
                assert ulps_of_max(ours, ref) <= 32, (angle, axes, reshape)


def test_rotation_matrix_equals_scipys_degree_functions():
    from splinelab._resample import _sincos_degrees

    angles = np.concatenate([np.arange(-720, 721, 15.0), rng(6).uniform(-1000, 1000, 500)])
    got = np.array([_sincos_degrees(a) for a in angles])
    np.testing.assert_array_equal(got[np.abs(angles) % 90 == 0], np.stack([special.cosdg(angles), special.sindg(angles)], 1)[np.abs(angles) % 90 == 0])
    err = np.abs(got - np.stack([special.cosdg(angles), special.sindg(angles)], 1)).max()
    assert err <= EPS64


def test_geometric_transform_callable_forms():
    x = rng(8).uniform(-1, 1, (20, 22))

    def mapping(o, a, b=0.0):
        return (o[0] * a + b, o[1] - o[0] * 0.1)

    kw = dict(output_shape=(15, 25), order=3, mode="mirror", extra_arguments=(0.9,), extra_keywords={"b": 1.5})
    ref = ndimage.geometric_transform(x, mapping, **kw)
    np.testing.assert_allclose(splinelab.geometric_transform(x, mapping, **kw), ref, rtol=0, atol=32 * EPS64)
    seen = []

    def vectorized(o, a, b=0.0):
        seen.append(o.shape)
        return np.stack([o[0] * a + b, o[1] - o[0] * 0.1])

    ours = splinelab.geometric_transform(x, vectorized, vectorized=True, **kw)
    np.testing.assert_allclose(ours, ref, rtol=0, atol=32 * EPS64)
    assert seen == [(2, 15, 25)]


def test_affine_to_other_dimensions():
    # A (3, 2) matrix: a 2-D output read from a 3-D input (a slice plane).
    x = rng(9).uniform(-1, 1, (24, 25, 26))
    m = np.array([[0.5, 0.2], [0.1, 0.9], [0.3, -0.4]])
    kw = dict(offset=[2, 3, 12.5], output_shape=(20, 21), order=3, mode="nearest")
    assert ulps_of_max(splinelab.affine_transform(x, m, **kw), ndimage.affine_transform(x, m, **kw)) <= 32


@pytest.mark.parametrize("d", [7, 11])
def test_high_degrees_against_check_mpfr_reference(d):
    # Degrees above scipy's 5: zoom's values at its own points, judged by
    # check's MPFR reference (banded solve per axis, exact B-spline weights).
    x = rng(d).uniform(-1, 1, (30, 28))
    z = splinelab.zoom(x, 1.4, order=d, mode="mirror")
    rows = np.arange(z.shape[0]) * (29 / (z.shape[0] - 1))
    cols = np.arange(z.shape[1]) * (27 / (z.shape[1] - 1))
    at = np.stack([np.repeat(rows, len(cols)), np.tile(cols, len(rows))])
    r = splinelab.check("interp", samples=x, coordinates=at, values=z.ravel(), degree=d, mode="mirror")
    # Backward stable: the error is within a few u * sum_j |c_j| beta(x - j)
    # <= u * max|c| (the coefficients grow with the degree: max|c| = 95 for
    # degree 7, 2563 for degree 11, max|value| < 1.8). Measured: 0.61 (7),
    # 0.48 (11).
    c = splinelab.spline_filter(x, order=d, mode="mirror")
    in_u_max_c = r["max_ulps_scaled"] * np.abs(z).max() / np.abs(c).max()
    assert in_u_max_c <= 4, (in_u_max_c, r["worst"])


def test_zoom_factor_as_0d_array_is_its_number():
    # scipy's _normalize_sequence: np.iterable(np.array(2)) is False, so a
    # 0-d array is one factor for every axis (scipy's test_zoom_0d_array).
    x = rng(10).uniform(-1, 1, (10, 7))
    for z in (np.array(2), np.array(1.5), np.float64(0.75)):
        ours, ref = splinelab.zoom(x, z), ndimage.zoom(x, z)
        assert ours.shape == ref.shape
        assert ulps_of_max(ours, ref) <= 16, z
    assert ulps_of_max(splinelab.shift(x, np.array(1.25)), ndimage.shift(x, np.array(1.25))) <= 16
    with pytest.raises(TypeError, match="zoom must be real"):
        splinelab.zoom(x, np.array(True))


@pytest.mark.parametrize(
    "call",
    [
        lambda f, out: f.affine_transform(np.arange(8.0), [[1]], output=out, output_shape=(12,)),
        lambda f, out: f.zoom(np.arange(8.0), 3, output=out),
        lambda f, out: f.shift(np.arange(8.0), 1.5, output=out),
        lambda f, out: f.map_coordinates(np.arange(8.0), [[1.5, 2.5]], output=out),
        lambda f, out: f.spline_filter(np.arange(8.0), output=out),
        lambda f, out: f.rotate(np.ones((3, 4, 5)), 30, output=out),
    ],
)
def test_output_of_another_shape_is_scipys_runtime_error(call):
    # scipy raises RuntimeError("output shape not correct"); ours is a
    # ValueError that is also a RuntimeError, so code written for scipy
    # catches it (scipy's test_affine_transform_output_shape).
    out = np.ones(16)
    with pytest.raises(RuntimeError, match="output shape not correct"):
        call(ndimage, out)
    with pytest.raises(RuntimeError, match=r"output has shape \(16,\), expected") as info:
        call(splinelab, out)
    assert isinstance(info.value, ValueError)
    np.testing.assert_array_equal(out, 1.0)


def test_affine_output_array_sets_the_shape():
    # Without output_shape, the output array's shape is the output's, as
    # scipy (the first half of scipy's test_affine_transform_output_shape).
    x = rng(12).uniform(-1, 1, 8)
    ours, ref = np.ones(16), np.ones(16)
    splinelab.affine_transform(x, [[1]], output=ours)
    ndimage.affine_transform(x, [[1]], output=ref)
    assert ulps_of_max(ours, ref) <= 16
    np.testing.assert_allclose(ours[:8], x, rtol=0, atol=4 * EPS64)


@pytest.mark.parametrize("mode", ["constant", "grid-constant"])
def test_empty_input_gives_cval_as_scipy(mode):
    # An empty axis puts every point outside the grid: scipy gives cval in
    # its constant modes (reproject interpolates empty chunks this way);
    # ours too, in the output's dtype, for every function.
    pts = np.array([[0.0, -1.0, 2.5], [1.0, 1.0, 7.0]])
    for dtype, cval in [(np.float64, 7.6), (np.float32, 7.6), (np.int32, 7.0), (np.complex128, 7.6 - 2j)]:
        for d in (0, 1, 3, 5):
            a = np.zeros((0, 5), dtype)
            ours = splinelab.map_coordinates(a, pts, order=d, mode=mode, cval=cval)
            ref = ndimage.map_coordinates(a, pts, order=d, mode=mode, cval=cval)
            assert ours.dtype == ref.dtype
            # scipy's grid-constant pads with cval and filters: cval within
            # a few ulps; ours is cval itself.
            np.testing.assert_allclose(ours, ref, rtol=8 * EPS64)
            np.testing.assert_array_equal(ours, np.full(3, cval, dtype))
    a = np.zeros((0, 5))
    for name, args in [("rotate", (30,)), ("affine_transform", ([[1, 0.2], [0, 1]], 0.0, (2, 3))),
                       ("affine_transform", ([1.0, 0.5], 0.0, (2, 3))), ("zoom", (2,)),
                       ("geometric_transform", (lambda o: (o[0] - 1.0, o[1]), (2, 3)))]:
        ours = getattr(splinelab, name)(a, *args, mode=mode, cval=7.5)
        ref = getattr(ndimage, name)(a, *args, mode=mode, cval=7.5)
        assert ours.shape == ref.shape, name
        np.testing.assert_allclose(ours, ref, rtol=8 * EPS64, err_msg=name)
    assert np.all(splinelab.map_coordinates(a, pts, order=3, mode=mode, derivative=(1, 0)) == 0)
    # Other modes read outside the array in scipy (undefined values): refused.
    with pytest.raises(ValueError):
        splinelab.map_coordinates(a, pts, order=3, mode="mirror")
