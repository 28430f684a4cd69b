"""nan_policy: missing data (NaN, ±inf samples, NaN coordinates, cval=nan).

'propagate' against scipy 1.17.1 (the peer): the same outputs non-finite,
the finite ones as close as test_scipy.py asks; 'local' against an
independent brute-force reach written here and against the exact spline
(tol=None) of the data with its missing samples filled by random values
in the data's range (hypothesis); 'raise' and the refusals by message."""

import itertools
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import ndimage

import splinelab

MODES = ["mirror", "reflect", "grid-mirror", "grid-wrap", "wrap", "nearest", "grid-constant", "constant"]
SHAPES = [(9,), (7, 6), (5, 4, 4)]
BAD = [np.nan, np.inf, -np.inf]


def places(shape):
    """A corner, an edge (middle of the first axis' last face) and the interior."""
    last = tuple(n - 1 for n in shape)
    edge = (shape[0] // 2,) + last[1:] if len(shape) > 1 else (0,)
    inner = tuple(n // 2 for n in shape)
    return [last, edge, inner]


def samples(shape, dtype, seed=1):
    return np.random.default_rng(seed).uniform(-1, 1, shape).astype(dtype)


# scipy filters these with its half-sample rule, wrong on lines shorter than
# 24 samples (relative error ~ rho^(2 n), test_scipy.py): their values on
# the sweep's short axes are compared where no filter runs.
REFLECT_RULE = ("reflect", "grid-mirror", "nearest")


def same_pattern_and_values(ours, ref, dtype, what, values=True):
    """Equal non-finite patterns; finite values (with ``values``) within
    1e-11 of max|value| (f64) or 2e-4 (f32: computed in float32 here, in
    float64 by scipy)."""
    ours, ref = np.asarray(ours), np.asarray(ref)
    bad_o, bad_r = ~np.isfinite(ours), ~np.isfinite(ref)
    assert np.array_equal(bad_o, bad_r), f"{what}: ours {bad_o.sum()} non-finite, scipy {bad_r.sum()}, " \
                                         f"differ at {np.argwhere(bad_o != bad_r)[:5].tolist()}"
    ok = ~bad_r
    if values and ok.any():
        scale = max(1.0, np.abs(ref[ok]).max())
        tol = 1e-11 if dtype == np.float64 else 2e-4
        assert np.abs(ours[ok] - ref[ok]).max() <= tol * scale, what


def sweep_cases():
    for shape, dtype in itertools.product(SHAPES, [np.float64, np.float32]):
        for where, bad in itertools.product(places(shape), BAD):
            a = samples(shape, dtype)
            a[where] = bad
            yield shape, dtype, a, f"{shape} {np.dtype(dtype).name} {bad} at {where}"


@pytest.mark.parametrize("order", range(6))
def test_propagate_resampling_pattern_is_scipys(order):
    for shape, dtype, a, what in sweep_cases():
        for mode in MODES:
            w = f"{what} {mode} order {order}"
            v = order < 2 or mode not in REFLECT_RULE
            zooms = [1.7] * a.ndim
            same_pattern_and_values(splinelab.zoom(a, zooms, order=order, mode=mode),
                                    ndimage.zoom(a, zooms, order=order, mode=mode), dtype, "zoom " + w, v)
            shifts = [0.5 + 0.7 * k for k in range(a.ndim)]
            same_pattern_and_values(splinelab.shift(a, shifts, order=order, mode=mode),
                                    ndimage.shift(a, shifts, order=order, mode=mode), dtype, "shift " + w, v)
            m = np.eye(a.ndim) + 0.15 * np.ones((a.ndim, a.ndim))
            off = [-0.6] * a.ndim
            same_pattern_and_values(splinelab.affine_transform(a, m, off, order=order, mode=mode),
                                    ndimage.affine_transform(a, m, off, order=order, mode=mode), dtype,
                                    "affine " + w, v)
            if a.ndim == 2:
                same_pattern_and_values(splinelab.rotate(a, 33, order=order, mode=mode),
                                        ndimage.rotate(a, 33, order=order, mode=mode), dtype, "rotate " + w, v)


@pytest.mark.parametrize("order", range(6))
def test_propagate_map_coordinates_pattern_is_scipys(order):
    rng = np.random.default_rng(5)
    for shape, dtype, a, what in sweep_cases():
        at = rng.uniform(-2.5, np.array(shape)[:, None] + 1.5, (a.ndim, 40))
        at[:, :len(shape)] = np.round(at[:, :len(shape)])  # integer points: zero weights count
        for mode, prefilter in itertools.product(MODES, [True, False]):
            w = f"{what} {mode} order {order} prefilter {prefilter}"
            v = order < 2 or not prefilter or mode not in REFLECT_RULE
            same_pattern_and_values(
                splinelab.map_coordinates(a, at, order=order, mode=mode, prefilter=prefilter),
                ndimage.map_coordinates(a, at, order=order, mode=mode, prefilter=prefilter), dtype, w, v)
        if order == 3:
            mapping = (lambda o: tuple(0.8 * x + 0.3 for x in o))
            same_pattern_and_values(splinelab.geometric_transform(a, mapping, order=order),
                                    ndimage.geometric_transform(a, mapping, order=order), dtype, "geometric " + what)


@pytest.mark.parametrize("order", range(2, 6))  # scipy's filters refuse 0 and 1
def test_propagate_filters_pattern_is_scipys(order):
    for shape, dtype, a, what in sweep_cases():
        for mode in MODES:
            w = f"{what} {mode} order {order}"
            v = mode not in REFLECT_RULE
            same_pattern_and_values(splinelab.spline_filter(a, order, mode=mode),
                                    ndimage.spline_filter(a, order, mode=mode), dtype, "filter " + w, v)
            for axis in range(a.ndim):
                same_pattern_and_values(splinelab.spline_filter1d(a, order, axis=axis, mode=mode),
                                        ndimage.spline_filter1d(a, order, axis=axis, mode=mode), dtype,
                                        f"filter1d axis {axis} " + w, v)


@pytest.mark.parametrize("order", range(6))
def test_non_finite_coordinates_and_cval_nan_are_scipys(order):
    rng = np.random.default_rng(8)
    for shape in SHAPES:
        a = samples(shape, np.float64)
        c = rng.uniform(-1.5, min(shape) + 0.5, (len(shape), 24))
        c[:, :2] = np.round(c[:, :2])
        for k in range(2, 24):  # one or two non-finite coordinates per point, every kind
            c[k % len(shape), k] = BAD[k % 3]
            if k % 4 == 0:
                c[(k + 1) % len(shape), k] = BAD[(k // 4) % 3]
        for mode, cval in itertools.product(MODES, [0.25, np.nan]):
            w = f"{shape} {mode} order {order} cval {cval}"
            v = order < 2 or mode not in REFLECT_RULE
            ours = splinelab.map_coordinates(a, c, order=order, mode=mode, cval=cval)
            same_pattern_and_values(ours, ndimage.map_coordinates(a, c, order=order, mode=mode, cval=cval),
                                    np.float64, w, v)
            # cval=nan on a grid (zoom by a non-integer factor reads outside under grid-constant).
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", UserWarning)  # both recommend grid-constant / grid-wrap
                same_pattern_and_values(splinelab.zoom(a, 1.3, order=order, mode=mode, cval=cval, grid_mode=True),
                                        ndimage.zoom(a, 1.3, order=order, mode=mode, cval=cval, grid_mode=True),
                                        np.float64, "zoom " + w, v)
    a = samples((6, 7), np.float64)
    # shift by NaN: every coordinate NaN on that axis.
    same_pattern_and_values(splinelab.shift(a, [np.nan, 0.5], order=order, mode="nearest"),
                            ndimage.shift(a, [np.nan, 0.5], order=order, mode="nearest"), np.float64, "shift nan")


def test_complex_nan_in_either_part_and_integers():
    a = samples((8, 7), np.float64) + 1j * samples((8, 7), np.float64, seed=2)
    a[3, 2] = complex(np.nan, 0.5)
    a[6, 6] = complex(0.1, np.inf)
    for order in (1, 3):
        ours = splinelab.zoom(a, 1.5, order=order)
        ref = ndimage.zoom(a, 1.5, order=order)
        same_pattern_and_values(ours.real, ref.real, np.float64, f"real {order}")
        same_pattern_and_values(ours.imag, ref.imag, np.float64, f"imag {order}")
    i = np.arange(30).reshape(5, 6)
    np.testing.assert_array_equal(splinelab.zoom(i, 2, order=3, nan_policy="raise"), ndimage.zoom(i, 2, order=3))


def test_raise_names_the_first_sample_and_its_value():
    a = samples((5, 9), np.float64)
    a[3, 4], a[4, 0] = -np.inf, np.nan
    for call in [lambda **k: splinelab.spline_filter(a, **k), lambda **k: splinelab.zoom(a, 2, **k),
                 lambda **k: splinelab.map_coordinates(a, [[1.0], [2.0]], **k),
                 lambda **k: splinelab.zoom(a, 2, order=1, **k), lambda **k: splinelab.spline_filter(a, 1, **k),
                 lambda **k: splinelab.shift(a, 0.5, mode="nearest", **k)]:
        with pytest.raises(ValueError, match=r"^sample 31 is not finite \(-inf\)$"):
            call(nan_policy="raise")
    with pytest.raises(ValueError, match=r"sample 2 is not finite \(nan\)"):
        splinelab.spline_filter1d(np.array([1.0, 2.0, np.nan]), nan_policy="raise", tol=1e-9)


def test_unknown_policy_and_local_without_tol_are_refused():
    a = samples((6,), np.float64)
    for f in [lambda **k: splinelab.spline_filter(a, **k), lambda **k: splinelab.zoom(a, 2, **k),
              lambda **k: splinelab.map_coordinates(a, [[1.0]], **k), lambda **k: splinelab.spline_gradient(a, [[1.0]], **k),
              lambda **k: splinelab.rotate(a[None].repeat(3, 0), 10, **k)]:
        with pytest.raises(ValueError, match="'propagate', 'raise' or 'local'"):
            f(nan_policy="omit")
        with pytest.raises(ValueError, match="tol=None the exact recursive prefilter carries a missing sample"):
            f(nan_policy="local", tol=None)
    with pytest.raises(TypeError, match="nan_policy must be a string"):
        splinelab.zoom(a, 2, nan_policy=None)
    # Degrees 0 and 1 have no prefilter: a finite reach without tol.
    x = np.arange(8.0)
    x[3] = np.nan  # outputs at k * 7 / 15 in [2, 4): k = 5..8
    np.testing.assert_array_equal(np.flatnonzero(np.isnan(splinelab.zoom(x, 2, order=1, nan_policy="local", tol=None))),
                                  [5, 6, 7, 8])
    assert splinelab.nan_reach(3, 1e-12) == splinelab.filter_bound(3, 1e-12)["half_width"] + 2
    # No tolerance, no certified width: a TypeError naming the argument.
    with pytest.raises(TypeError, match="tol"):
        splinelab.nan_reach(3, None)


# --- 'local': hypothesis ----------------------------------------------------

LOCAL_MODES = ["mirror", "reflect", "grid-wrap"]


def fold(i, n, mode):
    """Sample index ``i`` extended by ``mode`` (written here, independently)."""
    if mode == "mirror":
        if n == 1:
            return 0
        p = 2 * n - 2
        r = i % p
        return r if r < n else p - r
    if mode == "reflect":
        r = i % (2 * n)
        return r if r < n else 2 * n - 1 - r
    return i % n


def window(x, d):
    """The d + 1 coefficient indices a point reads (scipy's window)."""
    first = int(np.floor(x)) - (d - 1) // 2 if d % 2 else int(np.floor(x + 0.5)) - d // 2
    return range(first, first + d + 1)


def brute_force_nan(missing, points, d, n, mode):
    """Which points' values the missing samples reach: some coefficient of
    the window, folded, lies within n (folded) of a missing sample on every
    axis."""
    shape = missing.shape
    miss = [tuple(j) for j in np.argwhere(missing)]

    def coeff_nan(c):
        return any(all(any(fold(c[a] + k, shape[a], mode) == j[a] for k in range(-n, n + 1))
                       for a in range(len(shape))) for j in miss)

    out = []
    for p in points.T:
        wins = [[fold(i, shape[a], mode) for i in window(p[a], d)] for a in range(len(shape))]
        out.append(any(coeff_nan(c) for c in itertools.product(*wins)))
    return np.array(out)


def local_bound(d, tol, ndim):
    f = splinelab.filter_bound(d, tol)
    a, b = f["amplification"], f["bound"]
    return (a + b) ** ndim - (a - b) ** ndim


@st.composite
def local_case(draw):
    d = draw(st.sampled_from(list(range(10)) + [15]))
    ndim = draw(st.integers(1, 2))
    shape = tuple(draw(st.integers(1, 14 if ndim == 2 else 40)) for _ in range(ndim))
    tol = draw(st.sampled_from([1e-3, 1e-6, 1e-12]))
    mode = draw(st.sampled_from(LOCAL_MODES))
    seed = draw(st.integers(0, 2**32 - 1))
    dtype = draw(st.sampled_from([np.float64, np.float32]))
    count = draw(st.integers(0, 3))
    return d, shape, tol, mode, seed, dtype, count


@settings(max_examples=60, deadline=None)
@given(local_case())
def test_local_nan_set_is_the_certified_reach_and_values_are_any_fillings_spline(case):
    d, shape, tol, mode, seed, dtype, count = case
    rng = np.random.default_rng(seed)
    a = rng.uniform(-1, 1, shape).astype(dtype)
    missing = np.zeros(shape, bool)
    for _ in range(count):
        missing[tuple(rng.integers(0, n) for n in shape)] = True
    a[missing] = rng.choice([np.nan, np.inf, -np.inf])
    pts = np.stack([rng.uniform(0, n - 1, 30) for n in shape])
    pts[:, :5] = np.round(pts[:, :5])  # integer points: the window's zero weight counts
    got = splinelab.map_coordinates(a, pts, order=d, mode=mode, nan_policy="local", tol=tol)
    n = splinelab.nan_reach(d, tol) - (d // 2 + 1)
    # (a) the NaN set is exactly the certified reach.
    np.testing.assert_array_equal(np.isnan(got), brute_force_nan(missing, pts, d, n, mode))
    # (b) elsewhere within the bound of the exact spline of two fillings in the data's range.
    finite = a[~missing].astype(np.float64)
    big = np.abs(finite).max(initial=0.0)
    lo, hi = (finite.min(), finite.max()) if finite.size else (0.0, 0.0)
    ok = ~np.isnan(got)
    for _ in range(2):
        filled = a.astype(np.float64)
        filled[missing] = rng.uniform(lo, hi, missing.sum())
        exact = splinelab.map_coordinates(filled, pts, order=d, mode=mode, tol=None)
        err = np.abs(got[ok] - exact[ok]).max(initial=0.0)
        assert err <= allowed(d, tol, len(shape), big, dtype), (err, case)
    # (c) with nothing missing, the exact spline (tol=None) within the bound.
    clean = a.copy()
    clean[missing] = 0.5
    ref = splinelab.map_coordinates(clean.astype(np.float64), pts, order=d, mode=mode, tol=None)
    got = splinelab.map_coordinates(clean, pts, order=d, mode=mode, nan_policy="local", tol=tol)
    assert np.isfinite(got).all()
    assert np.abs(got - ref).max() <= allowed(d, tol, len(shape), max(big, 0.5), dtype)


def allowed(d, tol, ndim, big, dtype):
    """The stated bound times max|finite data|, plus the rounding of the
    dtype (64 units of it per unit of the amplification A^ndim)."""
    if d < 2:
        bound, amp = 0.0, 1.0
    else:
        bound, amp = local_bound(d, tol, ndim), splinelab.filter_bound(d, None)["amplification"]
    return (bound + 64 * np.finfo(dtype).eps * amp**ndim) * big


@settings(max_examples=25, deadline=None)
@given(local_case())
def test_local_filter_nan_set_is_the_folded_dilation(case):
    d, shape, tol, mode, seed, _, count = case
    if d < 2:
        d += 2
    rng = np.random.default_rng(seed)
    a = rng.uniform(-1, 1, shape)
    missing = np.zeros(shape, bool)
    for _ in range(count):
        missing[tuple(rng.integers(0, n) for n in shape)] = True
    a[missing] = np.nan
    c = splinelab.spline_filter(a, d, mode=mode, nan_policy="local", tol=tol)
    n = splinelab.nan_reach(d, tol) - (d // 2 + 1)
    want = np.zeros(shape, bool)
    for j in np.argwhere(missing):
        for idx in itertools.product(*[range(s) for s in shape]):
            if all(any(fold(idx[ax] + k, shape[ax], mode) == j[ax] for k in range(-n, n + 1))
                   for ax in range(len(shape))):
                want[idx] = True
    np.testing.assert_array_equal(np.isnan(c), want)


def test_local_one_masked_pixel_keeps_the_image():
    """The issue's picture in numbers: scipy's zoom of a 40x40 image with one
    NaN is all NaN at order 3; 'local' leaves NaN only within the reach."""
    a = samples((40, 40), np.float64)
    a[20, 20] = np.nan
    assert np.isnan(ndimage.zoom(a, 2, order=3)).all()
    assert np.isnan(splinelab.zoom(a, 2, order=3)).all()
    z = splinelab.zoom(a, 2, order=3, nan_policy="local", tol=1e-3)
    r = splinelab.nan_reach(3, 1e-3)
    rows = np.flatnonzero(np.isnan(z).any(axis=1)) * 39 / 79  # input coordinates of the NaN rows
    assert np.isnan(z).any() and np.abs(rows - 20).max() <= r
    assert np.isfinite(z).mean() > 0.5


@pytest.mark.parametrize("policy", ["propagate", "local"])
def test_gradient_reads_the_windows_the_values_read(policy):
    """spline_gradient has no scipy peer: its derivative weights read the
    same windows as the values, so its non-finite pattern is theirs."""
    a = samples((12, 11), np.float64)
    a[5, 0], a[0, 7] = np.nan, np.inf
    at = np.random.default_rng(3).uniform(-1, 12, (2, 60))
    at[:, :8] = np.round(at[:, :8])
    for order in range(1, 6):
        kw = dict(order=order, mode="mirror", nan_policy=policy, tol=1e-4)
        values = splinelab.map_coordinates(a, at, **kw)
        grad = splinelab.spline_gradient(a, at, **kw)
        for row in grad:
            np.testing.assert_array_equal(np.isfinite(row), np.isfinite(values), err_msg=f"{policy} {order}")
