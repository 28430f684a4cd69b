"""splinelab.RegularGridInterpolator and splinelab.interpn (issue 49)
against scipy 1.17.1 and against the exact not-a-knot spline.

References: scipy itself at run time (a peer: linear, nearest, slinear,
pchip, every refusal); for the spline methods the exact spline computed
independently, ``make_interp_spline(x, y, k, axis=a)`` along each axis in
turn (a banded solve per line, scipy's own code) for the coefficients and
``NdBSpline`` to evaluate them; on small grids a dense solve of the whole
Kronecker collocation system. Never scipy's RegularGridInterpolator for
cubic/quintic: its iterative solve stops at ``atol=1e-6``.

``python python/tests/test_rgi.py`` prints the figures the issue asks for.
"""

import numpy as np
import pytest
import scipy.interpolate as si
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.interpolate import BSpline, NdBSpline, make_interp_spline

import splinelab

EPS = np.finfo(float).eps
SPLINE_DEGREE = {"slinear": 1, "cubic": 3, "quintic": 5}


# ---------------------------------------------------------------- references


def exact_spline(grid, values, k):
    """The exact not-a-knot tensor-product spline: make_interp_spline along
    each axis in turn (its coefficients), as an NdBSpline."""
    c = np.asarray(values, dtype=float)
    knots = []
    for a, g in enumerate(grid):
        s = make_interp_spline(g, c, k=k, axis=a)
        c = np.moveaxis(s.c, 0, a)
        knots.append(s.t)
    return NdBSpline(tuple(knots), c, k)


def not_a_knot(x, k):
    """scipy's not-a-knot knots for odd k: x[(k+1)/2 : -(k+1)/2] inside,
    the ends k + 1 times."""
    h = (k + 1) // 2
    return np.r_[(x[0],) * (k + 1), x[h:-h], (x[-1],) * (k + 1)]


def random_grid(rng, shape, lo=-1.0, hi=2.0):
    """Random nodes on each axis (uniform draws, sorted): spacing as
    irregular as it comes, pairs close together included."""
    axes = []
    for n in shape:
        while True:
            x = np.sort(rng.uniform(lo, hi, n))
            if np.all(np.diff(x) > 0):
                axes.append(x)
                break
    return tuple(axes)


def points_in(rng, grid, n, margin=0.0):
    """n random points in the grid's box widened by ``margin`` of each
    axis' length on either side."""
    cols = []
    for g in grid:
        w = g[-1] - g[0]
        cols.append(rng.uniform(g[0] - margin * w, g[-1] + margin * w, n))
    return np.stack(cols, axis=-1)


def nodes(grid):
    return np.stack([m.ravel() for m in np.meshgrid(*grid, indexing="ij")], axis=-1)


def midpoints(grid):
    """The cell midpoints (scipy's nearest ties: yi = 0.5 exactly where the
    arithmetic gives it)."""
    return nodes([(g[1:] + g[:-1]) / 2 for g in grid])


def rel_err(a, b, scale):
    a, b = np.asarray(a), np.asarray(b)
    return float(np.max(np.abs(a - b)) / scale) if a.size else 0.0


# ---------------------------------------------------------------- exact splines


def jittered_grid(rng, shape, jitter=0.4):
    """Non-uniform nodes: each interior node of a uniform grid on [0, 1]
    moved by up to ``jitter`` of the spacing (neighbouring spacings up to
    (1 + 2 jitter) / (1 - 2 jitter) apart, 7:1 at 0.4)."""
    axes = []
    for n in shape:
        h = 1.0 / (n - 1)
        x = np.linspace(0.0, 1.0, n)
        x[1:-1] += rng.uniform(-jitter * h, jitter * h, n - 2)
        axes.append(x)
    return tuple(axes)


def _jittered_case():
    """A random non-uniform 3-D grid, 23 x 31 x 17, random values."""
    rng = np.random.default_rng(49)
    grid = jittered_grid(rng, (23, 31, 17))
    return rng, grid, rng.uniform(-1, 1, (23, 31, 17))


def _random_nodes_case():
    """The issue's harder case: 23 x 31 x 17 nodes drawn uniformly at random
    (closest pair 3.5e-4 apart here), random values: the quintic's
    collocation matrices are ill-conditioned (make_interp_spline itself
    misses the data at the nodes by 5.5e-9)."""
    rng = np.random.default_rng(44)
    grid = random_grid(rng, (23, 31, 17), 0.0, 1.0)
    return rng, grid, rng.uniform(-1, 1, (23, 31, 17))


@pytest.mark.parametrize("method", ["cubic", "quintic"])
def test_spline_on_a_random_nonuniform_3d_grid_is_the_exact_spline(method):
    rng, grid, values = _jittered_case()
    k = SPLINE_DEGREE[method]
    ip = splinelab.RegularGridInterpolator(grid, values, method=method, bounds_error=False, fill_value=None)
    ref = exact_spline(grid, values, k)
    scale = np.abs(values).max()
    inside = points_in(rng, grid, 3000)
    at_nodes = nodes(grid)
    outside = points_in(rng, grid, 500, margin=0.05)
    err_inside = rel_err(ip(inside), ref(inside), scale)
    err_nodes = rel_err(ip(at_nodes), values.ravel(), scale)
    assert err_inside <= 1e-12, err_inside
    assert err_nodes <= 1e-12, err_nodes
    # extrapolation by the end pieces (as NdBSpline), up to 5 % of each
    # axis out: the same 1e-12 times what the end pieces amplify there
    err_outside = np.abs(ip(outside) - ref(outside)) / scale
    assert np.all(err_outside <= 1e-12 * extrapolation_gain(grid, outside, k)), err_outside.max()
    # the stated bound holds against the exact data at the nodes
    assert np.max(np.abs(ip(at_nodes) - values.ravel())) <= ip.error_bound
    assert len(ip.condition) == 3 and all(np.isfinite(c) and c >= 1 for c in ip.condition)


@pytest.mark.parametrize("method", ["cubic", "quintic"])
def test_spline_on_random_nodes_meets_the_data_to_its_bound(method):
    rng, grid, values = _random_nodes_case()
    ip = splinelab.RegularGridInterpolator(grid, values, method=method)
    assert np.max(np.abs(ip(nodes(grid)) - values.ravel())) <= ip.error_bound
    # against the independent route, whose own error grows with the same
    # conditioning: both within a few units of prod(cond) u max|f|
    xi = points_in(rng, grid, 1000)
    ref = exact_spline(grid, values, SPLINE_DEGREE[method])(xi)
    tol = 16 * EPS * np.prod(ip.condition) * np.abs(values).max()
    assert np.max(np.abs(ip(xi) - ref)) <= tol


@pytest.mark.parametrize("method", ["slinear", "cubic", "quintic"])
def test_spline_derivatives_are_the_exact_spline_derivatives(method):
    rng = np.random.default_rng(7)
    k = SPLINE_DEGREE[method]
    grid = random_grid(rng, (9, 11))
    values = rng.uniform(-1, 1, (9, 11))
    ip = splinelab.RegularGridInterpolator(grid, values, method=method)
    ref = exact_spline(grid, values, k)
    xi = points_in(rng, grid, 400)
    hmin = min(np.diff(g).min() for g in grid)
    for nu in [(1, 0), (0, 1), (1, 1), (2, 0), (k + 1, 0)]:
        want = ref(xi, nu=nu)
        # a coefficient error e moves the |nu|-th derivative by at most
        # e (2k / hmin)^|nu| (Markov's inequality on each piece)
        tol = 1e-12 * np.abs(values).max() * (2 * k / hmin) ** sum(nu)
        assert np.max(np.abs(ip(xi, nu=nu) - want)) <= tol, nu


@pytest.mark.parametrize("method", ["slinear_legacy", "cubic_legacy", "quintic_legacy"])
def test_legacy_methods_are_the_same_exact_spline_in_the_values_dtype(method):
    rng = np.random.default_rng(3)
    grid = random_grid(rng, (8, 9))
    values = rng.uniform(-1, 1, (8, 9)).astype(np.float32)
    xi = points_in(rng, grid, 50)
    ours = splinelab.RegularGridInterpolator(grid, values, method=method)(xi)
    theirs = si.RegularGridInterpolator(grid, values, method=method)(xi)
    exact = exact_spline(grid, values, SPLINE_DEGREE[method.split("_")[0]])(xi)
    assert ours.dtype == theirs.dtype == np.float32
    np.testing.assert_array_equal(ours, exact.astype(np.float32))


def test_vector_and_complex_values_are_interpolated_column_by_column():
    rng = np.random.default_rng(11)
    grid = random_grid(rng, (7, 8, 6))
    values = rng.uniform(-1, 1, (7, 8, 6, 2, 3)) + 1j * rng.uniform(-1, 1, (7, 8, 6, 2, 3))
    xi = points_in(rng, grid, 40).reshape(5, 8, 3)
    for method in ["linear", "nearest", "slinear", "cubic", "quintic"]:
        out = splinelab.RegularGridInterpolator(grid, values, method=method)(xi)
        assert out.shape == (5, 8, 2, 3) and out.dtype == np.complex128
        for i in range(2):
            for j in range(3):
                for part in (np.real, np.imag):
                    one = splinelab.RegularGridInterpolator(grid, part(values[..., i, j]), method=method)(xi)
                    np.testing.assert_allclose(part(out[..., i, j]), one, rtol=0, atol=1e-14, err_msg=method)


# ---------------------------------------------------------------- scipy's numbers


SCIPY_EXACT = ["linear", "nearest", "slinear"]


def extrapolation_gain(grid, xi, degree):
    """How much an end piece amplifies its data at points outside the grid:
    prod over axes of (1 + 2 d / h)^degree, d the distance beyond the end
    and h the end cell's width (the magnitudes of the end piece's weights
    sum to at most that)."""
    gain = np.ones(len(xi))
    for x, g in zip(xi.T, grid):
        below = np.maximum(g[0] - x, 0) / (g[1] - g[0])
        above = np.maximum(x - g[-1], 0) / (g[-1] - g[-2])
        gain *= (1 + 2 * (below + above)) ** degree
    return gain


@pytest.mark.parametrize("ndim", [1, 2, 3, 4])
@pytest.mark.parametrize("method", SCIPY_EXACT + ["pchip"])
def test_linear_nearest_slinear_pchip_give_scipys_numbers(method, ndim):
    rng = np.random.default_rng(100 + ndim)
    shape = (9, 7, 6, 5)[:ndim]
    grid = random_grid(rng, shape)
    values = rng.uniform(-1, 1, shape)
    xi = np.concatenate([points_in(rng, grid, 400), nodes(grid), midpoints(grid),
                         points_in(rng, grid, 100, margin=0.2)])
    scale = np.abs(values).max()
    # 1e-14 of max|f| inside the grid (pchip: 1e-13, its slopes computed in
    # another order than scipy's), times the end pieces' gain outside
    tol = (1e-13 if method == "pchip" else 1e-14) * scale * extrapolation_gain(grid, xi, 3 if method == "pchip" else 1)
    for fill_value in [None, np.nan, -7.0]:
        kw = dict(method=method, bounds_error=False, fill_value=fill_value)
        ours = splinelab.RegularGridInterpolator(grid, values, **kw)(xi)
        theirs = si.RegularGridInterpolator(grid, values, **kw)(xi)
        assert ours.dtype == theirs.dtype and ours.shape == theirs.shape
        np.testing.assert_array_equal(np.isnan(ours), np.isnan(theirs))
        if method == "nearest":
            np.testing.assert_array_equal(ours, theirs)
        else:
            err = np.abs(np.nan_to_num(ours) - np.nan_to_num(theirs))
            assert np.all(err <= tol), (method, fill_value, float(np.max(err / tol)))


@pytest.mark.parametrize("dtype", [np.float32, np.float64, np.complex64, np.complex128, np.int32, np.float16, bool])
@pytest.mark.parametrize("method", ["linear", "nearest", "slinear", "cubic", "pchip", "cubic_legacy"])
def test_result_dtype_is_scipys(method, dtype):
    if method == "pchip" and np.dtype(dtype).kind == "c":
        pytest.skip("pchip refuses complex values (tested with the refusals)")
    x, y = np.linspace(0, 1, 6), np.array([0.0, 0.3, 0.4, 1.0, 1.7])
    values = (np.arange(30).reshape(6, 5) % 4).astype(dtype)
    xi = np.array([[0.31, 0.77], [0.5, 0.35], [np.nan, 0.2]], dtype=np.float32)
    kw = dict(method=method, bounds_error=False)
    ours = splinelab.RegularGridInterpolator((x, y), values, **kw)(xi)
    theirs = si.RegularGridInterpolator((x, y), values, **kw)(xi)
    assert ours.dtype == theirs.dtype
    # the values: scipy's cubic stops its iterative solve at atol=1e-6
    tol = 1e-5 if method == "cubic" else 8 * np.finfo(ours.dtype).eps * 3
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=tol)


def test_descending_axes_flip_points_and_values_as_scipy():
    rng = np.random.default_rng(5)
    grid = random_grid(rng, (8, 7, 6))
    values = rng.uniform(-1, 1, (8, 7, 6))
    xi = points_in(rng, grid, 100)
    desc = (grid[0][::-1], grid[1], grid[2][::-1])
    vdesc = values[::-1, :, ::-1]
    for method in splinelab.RegularGridInterpolator._ALL_METHODS:
        ip = splinelab.RegularGridInterpolator(desc, vdesc, method=method)
        np.testing.assert_array_equal(ip(xi), splinelab.RegularGridInterpolator(grid, values, method=method)(xi))
        assert all(np.all(np.diff(g) > 0) for g in ip.grid)
    np.testing.assert_array_equal(splinelab.interpn(desc, vdesc, xi, method="cubic"),
                                  splinelab.interpn(grid, values, xi, method="cubic"))


def test_interpn_matches_scipy_including_xi_shapes_and_splinef2d():
    rng = np.random.default_rng(8)
    grid = random_grid(rng, (7, 9))
    values = rng.uniform(-1, 1, (7, 9))
    xi_tuple = (np.linspace(grid[0][0], grid[0][-1], 4)[:, None], np.linspace(grid[1][0], grid[1][-1], 5)[None, :])
    for method in ["linear", "nearest", "slinear", "pchip"]:
        ours = splinelab.interpn(grid, values, xi_tuple, method=method)
        theirs = si.interpn(grid, values, xi_tuple, method=method)
        assert ours.shape == theirs.shape == (4, 5)
        np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-13)
    # 1-D xi: one point, a leading axis of 1
    assert splinelab.interpn(grid, values, [0.1, 0.2], bounds_error=False).shape == (1,)
    # splinef2d is FITPACK's interpolating cubic (knots x[2:-2]): the
    # not-a-knot cubic, up to FITPACK's own rounding; fill_value outside
    xi = np.concatenate([points_in(rng, grid, 200), points_in(rng, grid, 50, margin=0.3)])
    ours = splinelab.interpn(grid, values, xi, method="splinef2d", bounds_error=False, fill_value=99.0)
    theirs = si.interpn(grid, values, xi, method="splinef2d", bounds_error=False, fill_value=99.0)
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-11)
    np.testing.assert_array_equal(ours == 99.0, theirs == 99.0)


def test_length_one_axes_are_constant_along_them_as_scipy():
    x, y = np.array([1.0]), np.linspace(1, 10, 10)
    values = (x[:, None] + y[None, :]) ** 2
    xi = np.array([[1, 1.4], [1, 5.3], [1, 10], [1.5, 0.3], [0.2, 11.5], [np.nan, 2.0]])
    for method in ["linear", "nearest"]:
        for fill_value in [None, 101.0]:
            kw = dict(method=method, bounds_error=False, fill_value=fill_value)
            ours = splinelab.RegularGridInterpolator((x, y), values, **kw)(xi)
            theirs = si.RegularGridInterpolator((x, y), values, **kw)(xi)
            np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-13)
    # every axis of length one
    ours = splinelab.RegularGridInterpolator(([2.0], [3.0]), [[5.0]], bounds_error=False)([[2.0, 3.0], [2.0, 4.0]])
    np.testing.assert_array_equal(ours, [5.0, np.nan])


# ---------------------------------------------------------------- NaN and bad input


@pytest.mark.parametrize("method", ["linear", "nearest"])
def test_nan_in_values_propagates_as_scipys(method):
    rng = np.random.default_rng(2)
    grid = random_grid(rng, (7, 8))
    values = rng.uniform(-1, 1, (7, 8))
    values[3, 4] = np.nan
    values[0, 7] = np.inf
    xi = np.concatenate([points_in(rng, grid, 300), nodes(grid)])
    with np.errstate(invalid="ignore"):
        ours = splinelab.RegularGridInterpolator(grid, values, method=method)(xi)
        theirs = si.RegularGridInterpolator(grid, values, method=method)(xi)
    np.testing.assert_array_equal(np.isnan(ours), np.isnan(theirs))
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-14, equal_nan=True)


def _grid2(n=6, m=7):
    return (np.linspace(0, 1, n), np.linspace(0, 2, m)), np.arange(n * m, dtype=float).reshape(n, m)


def _bad_calls():
    """(label, call(RGI, interpn), words both messages contain)."""
    (x, y), v = _grid2()
    v_nan = v.copy()
    v_nan[2, 3] = np.nan
    small = (np.array([0.0, 1.0, 2.0]), y), v[:3]
    return [
        ("non-monotonic points", lambda R, I: R((np.array([0, 0.5, 0.2, 0.7, 0.8, 1]), y), v),
         ["strictly ascending or descending"]),
        ("repeated points", lambda R, I: R((np.array([0, 0.5, 0.5, 0.7, 0.8, 1]), y), v),
         ["strictly ascending or descending"]),
        ("NaN in points", lambda R, I: R((np.array([0, 0.5, np.nan, 0.7, 0.8, 1]), y), v),
         ["strictly ascending or descending"]),
        ("2-D points", lambda R, I: R((x, np.stack([y, y])), v), []),
        ("points and values of other lengths", lambda R, I: R((x[:-1], y), v), ["points", "values in dimension"]),
        ("more point arrays than dimensions", lambda R, I: R((x, y, y), v), ["point arrays"]),
        ("unknown method", lambda R, I: R((x, y), v, method="spline"), ["not defined"]),
        ("unknown method at call", lambda R, I: R((x, y), v)([[0.5, 0.5]], method="spline"), ["not defined"]),
        ("unknown method in interpn", lambda R, I: I((x, y), v, [[0.5, 0.5]], method="spline"), ["interpn", "spline"]),
        ("cubic on three points", lambda R, I: R(*small, method="cubic"), ["points in dimension"]),
        ("quintic on five points", lambda R, I: R((x[:5], y), v[:5], method="quintic"), ["points in dimension"]),
        ("pchip on three points", lambda R, I: R(*small, method="pchip"), ["points in dimension"]),
        ("cubic at call on three points", lambda R, I: R(*small)([[0.5, 0.5]], method="cubic"),
         ["points in dimension"]),
        ("xi of another dimension", lambda R, I: R((x, y), v)([[0.5, 0.5, 0.5]]), ["dimension 3"]),
        ("xi of another dimension in interpn", lambda R, I: I((x, y), v, np.ones((1, 1, 3))), ["dimension 3"]),
        ("xi out of bounds", lambda R, I: R((x, y), v)([[0.5, 2.5]]), ["out of bounds in dimension 1"]),
        ("NaN xi with bounds_error", lambda R, I: R((x, y), v)([[np.nan, 1.0]]), ["out of bounds in dimension 0"]),
        ("xi out of bounds in interpn", lambda R, I: I((x, y), v, [[1.5, 1.0]], method="cubic"),
         ["out of bounds in dimension 0"]),
        ("tuple xi of incompatible shapes", lambda R, I: R((x, y), v)((np.ones(3), np.ones(4))), []),
        ("complex fill_value for real values", lambda R, I: R((x, y), v, fill_value=1 + 2j), ["fill_value"]),
        ("solver with linear", lambda R, I: R((x, y), v, solver=lambda a, b: b), ["solver"]),
        ("solver_args with nearest", lambda R, I: R((x, y), v, method="nearest", solver_args={"atol": 1}),
         ["solver"]),
        ("a solver with the wrong interface", lambda R, I: R((x, y), v, method="slinear", solver=lambda a: a), []),
        ("solver_args gcrotmk refuses", lambda R, I: R((x, y), v, method="cubic", solver_args={"woof": 1}), []),
        ("nu with linear", lambda R, I: R((x, y), v)([[0.5, 0.5]], nu=(1, 0)), ["derivatives"]),
        ("nu of the wrong length", lambda R, I: R((x, y), v, method="cubic")([[0.5, 0.5]], nu=(1,)),
         ["derivative orders"]),
        ("a scalar nu", lambda R, I: R((x, y), v, method="cubic")([[0.5, 0.5]], nu=1), ["derivative orders"]),
        ("negative nu", lambda R, I: R((x, y), v, method="cubic")([[0.5, 0.5]], nu=(-1, 0)), ["positive"]),
        ("complex values with pchip", lambda R, I: R((x, y), v + 1j, method="pchip"), ["real"]),
        ("NaN values with cubic", lambda R, I: R((x, y), v_nan, method="cubic"), ["finite"]),
        ("NaN values with slinear", lambda R, I: R((x, y), v_nan, method="slinear"), ["finite"]),
        ("NaN values with pchip", lambda R, I: R((x, y), v_nan, method="pchip")([[0.5, 0.5]]), ["finite"]),
        ("NaN values, cubic at call", lambda R, I: R((x, y), v_nan)([[0.5, 0.5]], method="cubic"), ["finite"]),
        ("splinef2d in 3-D", lambda R, I: I((x, y, y), np.ones((6, 7, 7)), [[0.5, 0.5, 0.5]], method="splinef2d"),
         ["2-dimensional"]),
        ("splinef2d extrapolating", lambda R, I: I((x, y), v, [[0.5, 0.5]], method="splinef2d", bounds_error=False,
                                                   fill_value=None), ["extrapolation"]),
        ("splinef2d on vector values", lambda R, I: I((x,), v, [[0.5]], method="splinef2d"), ["scalar data"]),
        ("splinef2d on descending points", lambda R, I: I((x[::-1], y), v, [[0.5, 0.5]], method="splinef2d"),
         ["strictly increasing"]),
    ]


@pytest.mark.parametrize("label,call,words", _bad_calls(), ids=[c[0] for c in _bad_calls()])
def test_bad_input_is_refused_with_scipys_exception(label, call, words):
    with pytest.raises(Exception) as theirs:
        call(si.RegularGridInterpolator, si.interpn)
    with pytest.raises(Exception) as ours:
        call(splinelab.RegularGridInterpolator, splinelab.interpn)
    assert isinstance(ours.value, type(theirs.value)), (label, repr(ours.value), repr(theirs.value))
    for word in words:
        assert word.lower() in str(theirs.value).lower(), (label, word, str(theirs.value))
        assert word.lower() in str(ours.value).lower(), (label, word, str(ours.value))


_HUGE = """
import resource, sys
import numpy as np
import splinelab
resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
x = np.linspace(0, 1, 10**6)
v = np.broadcast_to(np.float64(1.0), (10**6, 10**6))  # 8 TB as an array, 8 bytes as a view
for method in sys.argv[1:]:
    try:
        out = splinelab.RegularGridInterpolator((x, x), v, method=method)([[0.5, 0.5], [0.3, 0.9]])
        print(method, *out)
    except MemoryError:
        print(method, "MemoryError")
"""


def test_a_broadcast_grid_is_read_as_its_distinct_values_and_too_large_a_spline_is_a_memory_error():
    # A 10^6 x 10^6 broadcast grid: "linear", "nearest" and "pchip" read
    # its one value (scipy's "linear" answers too; its "pchip" copies and
    # raises MemoryError); the splines' coefficients cannot be allocated
    # under a 3 GiB address space: MemoryError after a finiteness scan of
    # the one distinct value (it scanned 10^12 values for minutes).
    import subprocess
    import sys

    methods = ["cubic", "quintic", "slinear", "linear", "nearest", "pchip"]
    run = subprocess.run([sys.executable, "-c", _HUGE, *methods], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr[-2000:]
    expect = [f"{m} MemoryError" for m in methods[:3]] + [f"{m} 1.0 1.0" for m in methods[3:]]
    assert run.stdout.splitlines() == expect, run.stdout


def test_attributes_scipys_tests_read():
    (x, y), v = _grid2()
    ip = splinelab.RegularGridInterpolator((x[::-1], y), v, method="cubic", bounds_error=False, fill_value=3.0)
    assert isinstance(ip.grid, tuple) and np.array_equal(ip.grid[0], x) and np.array_equal(ip.grid[1], y)
    np.testing.assert_array_equal(ip.values, v[::-1])
    assert (ip.method, ip.fill_value, ip.bounds_error) == ("cubic", 3.0, False)
    ip.fill_value = None  # read at call time, as scipy
    assert np.isfinite(ip([[2.0, 1.0]])).all()
    assert splinelab.RegularGridInterpolator((x, y), v).error_bound is None


# ---------------------------------------------------------------- properties


def _small_case(data, kinds=("slinear", "cubic", "quintic")):
    """A method, its degree, a small non-uniform grid (jittered nodes,
    spacings up to 19:1 apart, on a random interval) and random values of a
    random magnitude."""
    method = data.draw(st.sampled_from(kinds), label="method")
    k = {"slinear": 1, "cubic": 3, "quintic": 5, "pchip": 3, "linear": 1, "nearest": 0}[method]
    d = data.draw(st.integers(1, 3), label="ndim")
    shape = tuple(data.draw(st.lists(st.integers(max(k + 1, 2), 7), min_size=d, max_size=d), label="shape"))
    jitter = data.draw(st.sampled_from([0.0, 0.2, 0.45]), label="jitter")
    seed = data.draw(st.integers(0, 2**32 - 1), label="seed")
    rng = np.random.default_rng(seed)
    offset, length = rng.uniform(-10, 10), 10.0 ** rng.uniform(-2, 2)
    grid = tuple(offset + length * g for g in jittered_grid(rng, shape, jitter))
    values = rng.uniform(-1, 1, shape) * data.draw(st.sampled_from([1.0, 1e-3, 1e5]), label="scale")
    return method, k, grid, values, rng


@settings(max_examples=40, deadline=None)
@given(data=st.data())
def test_interpolant_meets_the_data_at_every_node_to_its_error_bound(data):
    method, _, grid, values, _ = _small_case(data)
    ip = splinelab.RegularGridInterpolator(grid, values, method=method)
    err = np.max(np.abs(ip(nodes(grid)) - values.ravel()))
    assert err <= ip.error_bound, (err, ip.error_bound)


@settings(max_examples=30, deadline=None)
@given(data=st.data())
def test_coefficients_agree_with_a_dense_kronecker_solve(data):
    method, k, grid, values, rng = _small_case(data)
    ip = splinelab.RegularGridInterpolator(grid, values, method=method)
    knots = [not_a_knot(g, k) for g in grid]
    # the whole collocation matrix: the Kronecker product of the axes' own
    mats = [BSpline.design_matrix(g, t, k).toarray() for g, t in zip(grid, knots)]
    full = mats[0]
    for m in mats[1:]:
        full = np.kron(full, m)
    dense = np.linalg.solve(full, values.ravel()).reshape(values.shape)
    xi = points_in(rng, grid, 50)
    want = NdBSpline(tuple(knots), dense, k)(xi)
    # the dense LU's error: a few units of cond_inf(full) u max|coefficients|
    tol = ip.error_bound + 8 * EPS * np.linalg.cond(full, np.inf) * np.abs(dense).max()
    assert np.max(np.abs(ip(xi) - want)) <= tol


@settings(max_examples=30, deadline=None)
@given(data=st.data())
def test_reversing_an_axis_reverses_the_interpolant(data):
    method, _, grid, values, rng = _small_case(data, ("linear", "nearest", "slinear", "cubic", "quintic", "pchip"))
    axis = data.draw(st.integers(0, len(grid) - 1), label="axis")
    xi = points_in(rng, grid, 40)
    ip = splinelab.RegularGridInterpolator(grid, values, method=method)
    base = ip(xi)
    # the same grid given descending: the same numbers, bit for bit
    desc = tuple(g[::-1] if a == axis else g for a, g in enumerate(grid))
    np.testing.assert_array_equal(splinelab.RegularGridInterpolator(desc, np.flip(values, axis), method=method)(xi),
                                  base)
    # the mirrored grid x -> -x: the mirrored interpolant (not-a-knot ends,
    # PCHIP's and the multilinear rules are symmetric), to rounding
    mirrored = tuple(-g[::-1] if a == axis else g for a, g in enumerate(grid))
    xm = xi.copy()
    xm[:, axis] = -xm[:, axis]
    got = splinelab.RegularGridInterpolator(mirrored, np.flip(values, axis), method=method)(xm)
    if method == "nearest":
        # ties go to the lower node on both sides: only where yi != 0.5
        return
    bound = ip.error_bound if ip.error_bound is not None else 0.0
    assert np.max(np.abs(got - base)) <= 2 * bound + 1e-13 * np.abs(base).max()


@settings(max_examples=30, deadline=None)
@given(data=st.data())
def test_float32_and_float64_input_agree_where_float32_holds_the_values(data):
    method, _, grid, values, rng = _small_case(data, ("linear", "nearest", "slinear", "cubic", "quintic", "pchip"))
    v32 = values.astype(np.float32)
    v64 = v32.astype(np.float64)  # the same numbers
    xi = points_in(rng, grid, 40, margin=0.1)
    kw = dict(method=method, bounds_error=False, fill_value=None)
    r32 = splinelab.RegularGridInterpolator(grid, v32, **kw)(xi)
    r64 = splinelab.RegularGridInterpolator(grid, v64, **kw)(xi)
    if method in ("nearest", "pchip"):
        assert r32.dtype == np.float32  # the values' dtype, as scipy
        np.testing.assert_array_equal(r32, r64.astype(np.float32))
    elif method == "linear":
        # scipy's own float32 and float64 results differ in the last bit in
        # 2-D (its 2-D kernel takes float64 only, and forms the products in
        # another order): each is scipy's, bit for bit.
        assert r32.dtype == np.float64
        np.testing.assert_array_equal(r32, si.RegularGridInterpolator(grid, v32, **kw)(xi))
        np.testing.assert_array_equal(r64, si.RegularGridInterpolator(grid, v64, **kw)(xi))
    else:
        assert r32.dtype == np.float64
        np.testing.assert_array_equal(r32, r64)


# ---------------------------------------------------------------- figures


def figures():
    """The issue's accuracy figures (printed by ``python test_rgi.py``)."""
    for case in (_jittered_case, _random_nodes_case):
        _figures(*case())


def _figures(rng, grid, values):
    scale = np.abs(values).max()
    xi = points_in(rng, grid, 3000)
    print(f"grid {tuple(len(g) for g in grid)}, closest nodes "
          f"{min(np.diff(g).min() for g in grid):.2e} apart; errors / max|f|")
    for method in ["cubic", "quintic"]:
        ref = exact_spline(grid, values, SPLINE_DEGREE[method])(xi)
        ip = splinelab.RegularGridInterpolator(grid, values, method=method)
        at_nodes = rel_err(ip(nodes(grid)), values.ravel(), scale)
        line = (f"  {method:8s} splinelab vs exact {rel_err(ip(xi), ref, scale):.1e}, at nodes {at_nodes:.1e}, "
                f"error_bound {ip.error_bound:.1e}, condition {[f'{c:.1e}' for c in ip.condition]}")
        if method == "quintic" and min(np.diff(g).min() for g in grid) < 1e-3:
            # scipy's gcrotmk runs its 1000 iterations per column here (185 s)
            line += "; scipy: ValueError: solver = gcrotmk returns info = 1000 (not run: 3 minutes)"
        else:
            sp = si.RegularGridInterpolator(grid, values, method=method)
            line += (f"; scipy vs exact {rel_err(sp(xi), ref, scale):.1e}, "
                     f"at nodes {rel_err(sp(nodes(grid)), values.ravel(), scale):.1e}")
        print(line)
    for method in ["linear", "nearest", "slinear"]:
        ours = splinelab.RegularGridInterpolator(grid, values, method=method)(xi)
        theirs = si.RegularGridInterpolator(grid, values, method=method)(xi)
        print(f"  {method:8s} splinelab vs scipy {rel_err(ours, theirs, scale):.1e}")


if __name__ == "__main__":
    figures()
