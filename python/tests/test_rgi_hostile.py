"""Hostile and odd calls to RegularGridInterpolator and interpn, judged
against scipy 1.17.1.

Reference: scipy itself, called the same way at run time. The rule
(:func:`assert_like_scipy`): splinelab gives scipy's values (NaN where
scipy's is NaN, the fill value where scipy fills), or raises scipy's
exception class. Where scipy fails by accident rather than by a check it
makes (a pandas object or a duck-typed array read as a numpy array would
be, a generator of axes that scipy consumes twice, an allocation of a
broadcast grid's full size), the answer scipy gives on the same data as
plain numpy arrays (or, for the broadcast grid, the closed form) is
accepted too: it is what scipy's documentation promises.
"""

import fractions
import resource
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest
import scipy.interpolate as si

import splinelab

METHODS = ["linear", "nearest", "slinear", "cubic", "quintic", "pchip", "slinear_legacy", "cubic_legacy",
           "quintic_legacy"]
SPLINES = {"slinear": 1, "cubic": 3, "quintic": 5, "slinear_legacy": 1, "cubic_legacy": 3, "quintic_legacy": 5}
# scipy solves "slinear", "cubic", "quintic" iteratively (gcrotmk, atol 1e-6):
# its values there are within 1e-5 of the exact spline, splinelab's are the exact
# spline's (test_rgi.py); everywhere else both compute the same formulas.
SCIPY_ITERATIVE = {"cubic": 2e-5, "quintic": 2e-5, "slinear": 1e-13}
LEGACY_ULPS = 1e-13  # scipy's legacy route: make_interp_spline axis by axis, the same exact spline
PCHIP_ULPS = 1e-14  # the same formulas in the same order, evaluated locally (a few ulps)

X = np.linspace(0.0, 1.0, 6)
V = np.sin(np.add.outer(X, 2 * X))
INSIDE = np.array([[0.3, 0.5], [0.5, 0.9]])
OUTSIDE3 = np.array([[2.0, 0.5], [0.5, 0.5], [-1.0, 0.2], [0.3, 3.0]])  # 3 points outside, 1 inside


def _outcome(call):
    """``("values", array)`` or ``("raises", exception class, message)``,
    warnings silenced (numpy's overflow warnings are scipy's, not a result)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return ("values", np.asarray(call()))
    except Exception as e:  # noqa: BLE001 - the class is what is compared
        return ("raises", type(e), str(e))


def _rtol(method):
    """0 (bit for bit) for "linear" and "nearest", scipy's numbers."""
    if method in SCIPY_ITERATIVE:
        return SCIPY_ITERATIVE[method]
    return LEGACY_ULPS if method in SPLINES else PCHIP_ULPS if method == "pchip" else 0.0


def _same_values(got, want, rtol):
    if got.shape != want.shape or got.dtype != want.dtype:
        return False
    if rtol == 0.0:
        return np.array_equal(got, want, equal_nan=True)
    return bool(np.allclose(got, want, rtol=rtol, atol=rtol * np.nanmax(np.abs(want), initial=0.0), equal_nan=True)
                and np.array_equal(np.isnan(got), np.isnan(want)))


def assert_like_scipy(call_of, method="linear", accept=None):
    """``call_of(module)`` with splinelab gives what it gives with scipy:
    the same values (``_rtol(method)``), or the same exception class. Where
    scipy raises, or answers NaN where ``accept()`` is finite (its own
    overflow), ``accept()`` (when given) is an answer accepted instead:
    scipy's answer for the same data as numpy arrays, or for the same
    problem rescaled exactly."""
    want = _outcome(lambda: call_of(si))
    got = _outcome(lambda: call_of(splinelab))
    if want[0] == "values" and got[0] == "values" and _same_values(got[1], want[1], _rtol(method)):
        return
    if want[0] == "raises" and got[0] == "raises" and got[1] is want[1]:
        return
    if accept is not None and got[0] == "values":
        answer = _outcome(accept)
        scipy_failed = want[0] == "raises" or (
            answer[0] == "values" and np.any(np.isnan(want[1]) & np.isfinite(answer[1])))
        if scipy_failed and answer[0] == "values" and _same_values(got[1], answer[1], _rtol(method)):
            return
    raise AssertionError(f"{method}: scipy {want[:2]}{want[2:]!r}\n    splinelab {got[:2]}{got[2:]!r}")


# ---------------------------------------------------------------- axes scaled by 1e-300 .. 4e307


# scipy's PCHIP of these axes: slopes dy/dx that overflow or weights that
# underflow (1e-300, 1e-310: "`dydx` must contain only finite values."), or a
# first pass whose cubic overflows (4e307, 1e+-160: "`y` must contain only
# finite values." for the next axis): ValueError; on one axis at 4e307 its
# slopes are finite (0) and its cubic overflows to NaN, with no check after.
# PCHIP is scale invariant: the answer accepted instead is scipy's on the same
# nodes and points multiplied by a power of two (exact) to order 1. NaN is
# neither.
SCALES = [1e-300, 1e-160, 1e160, 4e307, 1e-310]


def _rescaled(a, scale):
    """``a`` times the power of two that takes ``scale`` to order 1: exact,
    so the stored (rounded, or subnormal) nodes keep every bit."""
    return np.ldexp(np.asarray(a, dtype=float), -int(np.frexp(scale)[1]))


@pytest.mark.parametrize("scale", SCALES)
def test_pchip_on_scaled_axes_as_scipy_or_scale_invariant(scale):
    ax, pts = X * scale, INSIDE * scale
    assert_like_scipy(lambda m: m.RegularGridInterpolator((ax, ax), V, method="pchip")(pts), "pchip",
                      accept=lambda: si.RegularGridInterpolator((_rescaled(ax, scale),) * 2, V, method="pchip")(
                          _rescaled(pts, scale)))
    mixed = np.stack([pts[:, 0], INSIDE[:, 1]], axis=-1)
    assert_like_scipy(lambda m: m.interpn((ax, X), V, mixed, method="pchip"), "pchip",
                      accept=lambda: si.interpn((_rescaled(ax, scale), X), V,
                                                np.stack([_rescaled(pts[:, 0], scale), INSIDE[:, 1]], -1),
                                                method="pchip"))


@pytest.mark.parametrize("scale", SCALES)
def test_pchip_on_one_scaled_axis_as_scipy_or_scale_invariant(scale):
    ax, q = X * scale, np.array([[0.3], [0.55]]) * scale
    assert_like_scipy(lambda m: m.RegularGridInterpolator((ax,), np.sin(X), method="pchip")(q), "pchip",
                      accept=lambda: si.RegularGridInterpolator((_rescaled(ax, scale),), np.sin(X), method="pchip")(
                          _rescaled(q, scale)))


@pytest.mark.parametrize("method", [m for m in METHODS if m != "pchip"])
@pytest.mark.parametrize("scale", [1e-300, 1e-160, 1e160, 4e307])
def test_other_methods_on_scaled_axes_give_scipys_values(method, scale):
    """Every other method answers on these axes, as scipy (a spline is
    scale invariant; linear and nearest use ratios of differences)."""
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X * scale, X * scale), V, method=method)(INSIDE * scale),
                      method)


@pytest.mark.parametrize("method", ["slinear", "cubic", "quintic", "cubic_legacy"])
def test_subnormal_spacing_is_refused_as_scipy(method):
    """Axes scaled by 1e-310 (subnormal node spacing): scipy's solvers and
    checks refuse them with ValueError (splinelab: a singular collocation
    matrix). "pchip": test_pchip_on_scaled_axes_as_scipy_or_scale_invariant."""
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X * 1e-310, X), V, method=method)([[0.3e-310, 0.5]]),
                      method)


# ---------------------------------------------------------------- far outside, fill_value=None


FAR = [[1e300, 0.5], [-1e300, 0.5], [0.5, 1e300], [1e200, 0.5], [1e10, 0.5], [0.5, -1e10]]
FAR_BOTH = [[1e300, -1e300], [1e300, 1e300]]  # "linear": two overflowing weights meet, NaN


@pytest.mark.parametrize("method", ["linear", "nearest"])
def test_extrapolation_far_outside_gives_scipys_values(method):
    """scipy's "linear" extrapolates the end cells to finite values at
    +-1e300 (NaN where two overflowing weights meet); "nearest" takes the
    end node."""
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X, X), V, method=method, bounds_error=False,
                                                          fill_value=None)(FAR + FAR_BOTH), method)


@pytest.mark.parametrize("method", ["slinear", "slinear_legacy"])
def test_linear_spline_extrapolation_far_outside_gives_scipys_values(method):
    """The degree-1 spline continued far outside: scipy's NdBSpline (de
    Boor with knot differences) gives the end cells' planes, finite to
    1e307. The basis divides by knot differences ``t_hi - t_lo``, not by
    ``(t_hi - x) + (x - t_lo)``, which cancels far outside the grid."""
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X, X), V, method=method, bounds_error=False,
                                                          fill_value=None)(FAR), method)


def _end_piece_exact(x, y, k, q):
    """The not-a-knot spline of degree ``k`` through ``(x, y)`` continued to
    ``q`` beyond ``x[-1]``: scipy's ``make_interp_spline`` (a banded direct
    solve, independent of splinelab) for the last piece's polynomial, which
    is evaluated in exact rational arithmetic."""
    pp = si.PPoly.from_spline(si.make_interp_spline(x, y, k=k))
    s = fractions.Fraction(q) - fractions.Fraction(pp.x[-2])
    c = [fractions.Fraction(v) for v in pp.c[:, -1]]
    return float(sum(ci * s ** (len(c) - 1 - j) for j, ci in enumerate(c)))


@pytest.mark.parametrize("distance", [1e2, 1e8, 1e12, 1e30])
@pytest.mark.parametrize("method", ["slinear", "cubic", "quintic"])
def test_spline_extrapolation_keeps_relative_accuracy(method, distance):
    """Far outside, the end piece's polynomial ``sum c_j s^j`` is dominated
    by its leading term: its relative condition is about 1, and the exact
    spline's coefficients differ from make_interp_spline's by a few hundred
    ulps of the data (the grid's conditioning). Bound: 1e-11 relative."""
    y = np.sin(X)
    q = 1.0 + distance
    r = splinelab.RegularGridInterpolator((X,), y, method=method, bounds_error=False, fill_value=None)
    got = r([[q]])[0]
    exact = _end_piece_exact(X, y, SPLINES[method], q)
    assert np.isfinite(got) and abs(got - exact) <= 1e-11 * abs(exact), (got, exact, abs(got - exact) / abs(exact))


# ---------------------------------------------------------------- fill_value arrays


# scipy writes ``result[out_of_bounds] = fill_value`` into its (points,) result
# (plus any trailing axes of the values): numpy's boolean-mask assignment, so a
# 1-D array with one value per point outside is taken in order, and a 2-D array
# is a TypeError. splinelab writes the fill into a result of the same shape.
FILLS = {
    "one per outside point (3,)": np.array([10.0, 20.0, 30.0]),
    "one per outside point, list": [10.0, 20.0, 30.0],
    "one per outside point, int": np.array([1, 2, 3]),
    "(4,) for 3 outside": np.array([1.0, 2.0, 3.0, 4.0]),  # both ValueError; the messages differ
    "(3, 1)": np.array([[1.0], [2.0], [3.0]]),  # scipy: TypeError
    "(1, 1)": np.array([[7.0]]),
    "(1,)": np.array([7.0]),
    "0-d": np.array(7.0),
    "tuple (1,)": (5.0,),
}


@pytest.mark.parametrize("method", ["linear", "nearest", "cubic", "pchip", "cubic_legacy"])
@pytest.mark.parametrize("name", list(FILLS))
def test_fill_value_arrays_as_scipy(name, method):
    fill = FILLS[name]
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X, X), V, method=method, bounds_error=False,
                                                          fill_value=fill)(OUTSIDE3), method)
    assert_like_scipy(lambda m: m.interpn((X, X), V, OUTSIDE3, method=method, bounds_error=False, fill_value=fill),
                      method)


@pytest.mark.parametrize("fill", [np.array([10.0, 20.0, 30.0]), np.array([[7.0]])], ids=["(3,)", "(1, 1)"])
def test_fill_value_array_with_no_point_outside_as_scipy(fill):
    """No point outside: scipy's assignment selects nothing, and refuses a
    (3,) array (ValueError) and a 2-D one (TypeError) all the same;
    splinelab makes the same empty assignment, with the same refusals."""
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X, X), V, bounds_error=False, fill_value=fill)(INSIDE))


@pytest.mark.parametrize("fill", [np.array([1.0, 2.0]), np.array([[1.0, 2.0]] * 3), np.array([[1.0], [2.0], [3.0]])],
                         ids=["trailing (2,)", "(3, 2)", "(3, 1)"])
@pytest.mark.parametrize("method", ["linear", "cubic", "pchip"])
def test_fill_value_arrays_with_trailing_values_as_scipy(method, fill):
    v = np.stack([V, 2 * V], axis=-1)
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X, X), v, method=method, bounds_error=False,
                                                          fill_value=fill)(OUTSIDE3), method)


@pytest.mark.parametrize("values", ["complex", "float32"])
def test_fill_value_per_point_for_complex_and_float32_values_as_scipy(values):
    v = V + 1j * V if values == "complex" else V.astype(np.float32)
    fill = np.array([1 + 1j, 2, 3]) if values == "complex" else np.array([1.0, 2.0, 3.0])
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X, X), v, bounds_error=False, fill_value=fill)(OUTSIDE3))


# ---------------------------------------------------------------- pandas


def _pandas_cases():
    """Per case: the call, and scipy's call on the same data as numpy
    arrays (None where scipy takes the pandas object itself)."""
    pd = pytest.importorskip("pandas")
    s, s_index = pd.Series(np.sin(X)), pd.Series(np.sin(X), index=np.arange(6) * 10)
    df = pd.DataFrame(V)
    return {
        "DataFrame values": (lambda m, meth: m.RegularGridInterpolator((X, X), df, method=meth)(INSIDE),
                             lambda meth: si.RegularGridInterpolator((X, X), V, method=meth)(INSIDE)),
        "DataFrame values, interpn": (lambda m, meth: m.interpn((X, X), df, INSIDE, method=meth),
                                      lambda meth: si.interpn((X, X), V, INSIDE, method=meth)),
        "Series values": (lambda m, meth: m.RegularGridInterpolator((X,), s, method=meth)([[0.3], [0.55]]),
                          lambda meth: si.RegularGridInterpolator((X,), np.sin(X), method=meth)([[0.3], [0.55]])),
        "Series values, index 0, 10, ..": (
            lambda m, meth: m.RegularGridInterpolator((X,), s_index, method=meth)([[0.3], [0.55]]),
            lambda meth: si.RegularGridInterpolator((X,), np.sin(X), method=meth)([[0.3], [0.55]])),
        "Series axes": (lambda m, meth: m.RegularGridInterpolator((pd.Series(X), pd.Index(X)), V, method=meth)(INSIDE),
                        None),
        "DataFrame points": (lambda m, meth: m.RegularGridInterpolator((X, X), V, method=meth)(pd.DataFrame(INSIDE)),
                             None),
    }


PANDAS = ["DataFrame values", "DataFrame values, interpn", "Series values", "Series values, index 0, 10, ..",
          "Series axes", "DataFrame points"]


@pytest.mark.parametrize("method", ["linear", "nearest", "slinear", "cubic", "quintic", "pchip", "cubic_legacy"])
@pytest.mark.parametrize("case", PANDAS)
def test_pandas_objects_as_scipy(case, method):
    """pandas objects are read with ``np.asarray``, as the array_like they
    are (a Series' index is not its axis): every method, the recursive
    routes included, answers as scipy does on the same numpy arrays."""
    call, on_arrays = _pandas_cases()[case]
    assert_like_scipy(lambda m: call(m, method), method, accept=on_arrays and (lambda: on_arrays(method)))


# ---------------------------------------------------------------- duck-typed values


class Duck:
    """scipy's own duck-typed values (its test_duck_typed_values): ``ndim``,
    ``shape``, ``__getitem__``; ``__array__`` refuses."""

    def __init__(self, a):
        self.ndim, self.shape, self._v = a.ndim, a.shape, a

    def __getitem__(self, i):
        return self._v[i]

    def __array__(self, dtype=None, copy=None):
        raise RuntimeError("No array representation")


class DuckWithDtype(Duck):
    @property
    def dtype(self):
        return self._v.dtype

    def astype(self, dtype):
        return type(self)(self._v.astype(dtype))


class DuckWithoutUfuncs(DuckWithDtype):
    """Converts with ``np.asarray``, but refuses numpy's ufuncs (no
    ``np.isfinite`` on it)."""

    __array_ufunc__ = None

    def __array__(self, dtype=None, copy=None):
        return np.asarray(self._v, dtype=dtype)


class DuckWithoutArray:
    """No ``__array__`` at all: ``np.asarray`` makes a 0-d object array,
    on which ``np.isfinite`` fails."""

    def __init__(self, a):
        self.ndim, self.shape, self._v = a.ndim, a.shape, a

    def __getitem__(self, i):
        return self._v[i]


DUCKS = [Duck, DuckWithDtype, DuckWithoutUfuncs, DuckWithoutArray]


@pytest.mark.parametrize("method", ["linear", "nearest", "slinear", "cubic", "quintic", "pchip", "cubic_legacy"])
@pytest.mark.parametrize("duck", DUCKS, ids=lambda d: d.__name__)
def test_duck_typed_values_as_scipy(duck, method):
    """Every route reads duck-typed values as scipy's linear route does,
    through ``__getitem__`` (not by converting the duck with ``np.asarray``,
    which a duck may refuse or turn into an object array): scipy's answer,
    or scipy's answer for the same numpy array where scipy fails on the
    duck."""
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X, X), duck(V), method=method)(INSIDE), method,
                      accept=lambda: si.RegularGridInterpolator((X, X), V, method=method)(INSIDE))


# ---------------------------------------------------------------- non-finite points


NONFINITE = [[np.inf, 0.5], [-np.inf, 0.5], [0.5, np.inf], [0.5, -np.inf], [np.nan, 0.5], [0.5, np.nan],
             [np.inf, np.nan], [np.nan, np.inf], [np.inf, np.inf]]
NONFINITE_PARAMS = [pytest.param(method, p, id=f"{method}-{p}")
                    for method in ["linear", "nearest", "slinear", "cubic", "quintic", "pchip", "cubic_legacy"]
                    for p in NONFINITE]


@pytest.mark.parametrize("fill_value", [np.nan, None, 3.0], ids=["nan", "None", "3.0"])
@pytest.mark.parametrize("method, point", NONFINITE_PARAMS)
def test_infinite_and_nan_points_as_scipy(method, point, fill_value):
    """scipy's recursive routes (pchip, *_legacy) evaluate the last axis
    first and refuse a non-finite result before the next axis (ValueError)
    whatever bounds_error and fill_value: a point with a non-finite
    coordinate after the first axis is refused there, as scipy refuses it;
    the other routes give NaN or the fill, as scipy's do."""
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X, X), V, method=method, bounds_error=False,
                                                          fill_value=fill_value)([point, [0.3, 0.4]]), method)


@pytest.mark.parametrize("method", ["linear", "nearest", "cubic", "pchip", "cubic_legacy"])
def test_infinite_point_with_bounds_error_as_scipy(method):
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X, X), V, method=method)([[0.5, np.inf]]), method)


@pytest.mark.parametrize("method", ["linear", "nearest", "slinear", "cubic", "pchip", "cubic_legacy"])
@pytest.mark.parametrize("point", [np.inf, -np.inf, np.nan])
def test_one_axis_infinite_points_as_scipy(method, point):
    """One axis: the only pass is the last, with no check after it."""
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X,), np.sin(X), method=method, bounds_error=False,
                                                          fill_value=None)([[point], [0.5]]), method)


# ---------------------------------------------------------------- unaligned points


def _unaligned(a):
    """``a`` copied to an address one byte past an aligned one (C order):
    what a dask.distributed worker hands a task (test_pickle.py)."""
    a = np.ascontiguousarray(a)
    u = np.frombuffer(bytearray(a.nbytes + 1), dtype=a.dtype, offset=1, count=a.size).reshape(a.shape)
    u[...] = a
    assert not u.flags.aligned and u.flags.c_contiguous
    return u


@pytest.mark.parametrize("method", METHODS)
def test_unaligned_points_give_scipys_values(method):
    """Points at an unaligned address are copied to an aligned array before
    the engine reads them: every method gives scipy's values."""
    assert_like_scipy(lambda m: m.RegularGridInterpolator((X, X), V, method=method)(
        _unaligned(INSIDE) if m is splinelab else INSIDE), method)
    assert_like_scipy(lambda m: m.interpn((X, X), V, _unaligned(INSIDE) if m is splinelab else INSIDE,
                                          method=method), method)


@pytest.mark.parametrize("method", ["linear", "cubic", "pchip"])
def test_unaligned_values_and_axes_give_scipys_values(method):
    assert_like_scipy(lambda m: m.RegularGridInterpolator(
        (_unaligned(X), X) if m is splinelab else (X, X), _unaligned(V) if m is splinelab else V,
        method=method)(INSIDE), method)


# ---------------------------------------------------------------- a generator of axes


ITERABLES = {"generator": lambda: (p for p in (X, X)), "map": lambda: map(np.asarray, (X, X)),
             "iterator": lambda: iter([X, X])}


@pytest.mark.parametrize("method", ["linear", "nearest", "slinear", "cubic", "pchip", "cubic_legacy"])
@pytest.mark.parametrize("kind", list(ITERABLES))
def test_axes_given_as_an_iterator_as_scipy(kind, method):
    """scipy reads ``points`` more than once (array_namespace, then its
    checks): an iterator is empty by the second read, and scipy refuses
    (ValueError from the constructor or the call; interpn: TypeError, no
    len()). Answering as scipy answers for a tuple of the same axes is
    accepted."""
    make = ITERABLES[kind]
    on_tuple = lambda: si.RegularGridInterpolator((X, X), V, method=method)(INSIDE)  # noqa: E731
    assert_like_scipy(lambda m: m.RegularGridInterpolator(make(), V, method=method)(INSIDE), method, accept=on_tuple)
    assert_like_scipy(lambda m: m.interpn(make(), V, INSIDE, method=method), method,
                      accept=lambda: si.interpn((X, X), V, INSIDE, method=method))


# ---------------------------------------------------------------- a 10^6 x 10^6 broadcast grid


_HUGE = textwrap.dedent("""
    import json, sys, time, numpy as np, scipy.interpolate as si, splinelab
    n = 10**6
    ax = np.arange(n, dtype=float)
    v = np.broadcast_to(np.float64(1.0), (n, n))
    out = {}
    for module, methods in (("splinelab", sys.argv[1].split(",")), ("scipy", sys.argv[2].split(","))):
        m = splinelab if module == "splinelab" else si
        for method in methods:
            t = time.perf_counter()
            try:
                r = m.RegularGridInterpolator((ax, ax), v, method=method)([[1.5, 2.5], [999998.5, 3.25]])
                res = ["values", r.tolist()]
            except Exception as e:
                res = ["raises", type(e).__name__]
            out[f"{module} {method}"] = res + [round(time.perf_counter() - t, 3)]
    print(json.dumps(out))
""")
# scipy's "slinear", "cubic", "quintic" build the sparse Kronecker system of
# 10^12 rows: MemoryError after ~40 s and 15 GB (under a 16 GB address-space
# limit, 2 cores); not run here. Its "linear" and "nearest" answer at once,
# its "pchip" and "cubic_legacy" refuse at once (MemoryError: a 931 GiB
# mask, a 7.3 TiB copy).
HUGE_SCIPY = ["linear", "nearest", "pchip", "cubic_legacy"]
HUGE_SPLINELAB = ["linear", "nearest", "pchip", "cubic_legacy", "cubic", "slinear", "quintic"]


def _limit_address_space():
    resource.setrlimit(resource.RLIMIT_AS, (8 << 30, 8 << 30))


@pytest.fixture(scope="module")
def huge():
    """Both libraries on the broadcast grid in one child process (60 s
    limit, 8 GiB of address space: a hang or a full-size allocation cannot
    take the machine)."""
    import json

    run = subprocess.run([sys.executable, "-c", _HUGE, ",".join(HUGE_SPLINELAB), ",".join(HUGE_SCIPY)],
                         capture_output=True, text=True, timeout=60, preexec_fn=_limit_address_space)
    assert run.returncode == 0, run.stderr[-3000:]
    return json.loads(run.stdout.splitlines()[-1])


@pytest.mark.parametrize("method", HUGE_SPLINELAB)
def test_huge_broadcast_grid_as_scipy(huge, method):
    """The data is the constant 1: every method's interpolant is 1 (the
    closed form), which is accepted where scipy runs out of memory; a
    MemoryError is scipy's own outcome for the spline methods."""
    got = huge[f"splinelab {method}"]
    want = huge.get(f"scipy {method}", ["raises", "MemoryError", None])
    if want[0] == "values":
        assert got[:2] == want[:2], (got, want)
    else:
        assert want[1] == "MemoryError"
        assert got[:2] in (["raises", "MemoryError"], ["values", [1.0, 1.0]]), got
    assert got[2] < 10.0, f"{method} took {got[2]} s"
