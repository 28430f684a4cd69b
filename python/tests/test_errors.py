"""Bad input raises the right Python exception with the Rust message."""

import warnings

import numpy as np
import pytest

import splinelab


@pytest.mark.parametrize(
    "call, exc, words",
    [
        (lambda: splinelab.spline_filter1d(np.ones(5), order=200), ValueError, "0..199"),
        (lambda: splinelab.spline_filter1d(np.ones(5), order=-1), ValueError, "0..199"),
        (lambda: splinelab.spline_filter1d(np.ones(5), order=3.0), TypeError, "integer"),
        (lambda: splinelab.spline_filter1d(np.ones(5), mode="periodic"), ValueError, "unknown mode"),
        (lambda: splinelab.spline_filter1d(np.ones(5), mode=3), TypeError, "string"),
        # Data the filter could overflow: an error, not inf / NaN (one line, N-D, float32, map_coordinates).
        (lambda: splinelab.spline_filter1d(np.array([1e308, -1e308, 1e308, 0.0]), 3), ValueError, "overflow"),
        (lambda: splinelab.spline_filter(np.full((3, 3), 1e308), 3), ValueError, "overflow"),
        (lambda: splinelab.spline_filter1d(np.array([3e38, -3e38] * 4, np.float32), 3, output=np.float32), ValueError, "overflow"),
        (lambda: splinelab.map_coordinates(np.full((3, 3), 1e308), [[1.0], [1.0]], mode="mirror"), ValueError, "overflow"),
        (lambda: splinelab.spline_filter1d(np.ones(5), tol=2.0), ValueError, "toleran"),
        (lambda: splinelab.spline_filter1d(np.ones(5), tol=float("nan")), ValueError, "toleran"),
        (lambda: splinelab.spline_filter1d(np.ones(5), tol="1e-3"), TypeError, "tol"),
        (lambda: splinelab.spline_filter1d(np.ones((3, 4)), axis=2), np.exceptions.AxisError, "axis"),
        (lambda: splinelab.spline_filter1d(np.array([1.0, np.nan, 2.0]), nan_policy="raise"), ValueError,
         "sample 1 is not finite (nan)"),
        (lambda: splinelab.spline_filter1d(np.array([1.0, np.inf]), nan_policy="raise"), ValueError,
         "sample 1 is not finite (inf)"),
        (lambda: splinelab.spline_filter1d(np.ones(3, complex), output="float64"), TypeError, "complex"),
        (lambda: splinelab.spline_filter1d(np.array(["a", "b"])), TypeError, "numeric"),
        (lambda: splinelab.spline_filter(np.ones(5), output="U3"), TypeError, "numeric"),
        (lambda: splinelab.map_coordinates(np.ones(5), [[1.0]], output=np.empty(1, complex) + 0j * 0, cval=1j), TypeError,
         "complex"),
        (lambda: splinelab.map_coordinates(np.ones(5), [[1.0]], output=np.empty(2)), ValueError, "shape"),
        (lambda: splinelab.zoom(np.ones((4, 4)), 2, output=np.empty((4, 4))), ValueError, "shape"),
        (lambda: splinelab.zoom(np.ones((4, 4)), (2, 2, 2)), ValueError, "one value per axis"),
        (lambda: splinelab.affine_transform(np.ones((4, 4)), np.ones((3, 3))), ValueError, "bottom row"),
        (lambda: splinelab.affine_transform(np.ones((4, 4)), np.ones((3, 2))), ValueError, "rows"),
        (lambda: splinelab.affine_transform(np.ones((4, 4)), np.ones((2, 3, 1))), ValueError, "1-D or 2-D"),
        (lambda: splinelab.rotate(np.ones(4), 30), ValueError, "2D"),
        (lambda: splinelab.rotate(np.ones((4, 4)), 30, axes=(0, 2)), ValueError, "rotation plane"),
        (lambda: splinelab.geometric_transform(np.ones(4), lambda o: (o[0], o[0])), ValueError, "expected 1"),
        (lambda: splinelab.geometric_transform(np.ones(4), 3), TypeError, "callable"),
        (lambda: splinelab.spline_filter(np.ones(5), output=np.empty(4)), ValueError, "shape"),
        (lambda: splinelab.spline_filter(np.ones(5), threads=0), ValueError, "threads"),
        (lambda: splinelab.map_coordinates(np.ones((3, 3)), np.ones((3, 2))), ValueError, "shape"),
        (lambda: splinelab.map_coordinates(np.ones(3), [[np.nan]], nan_policy="raise"), ValueError, "finite"),
        (lambda: splinelab.map_coordinates(np.ones(3), [[1.0]], order=200), ValueError, "egree"),
        (lambda: splinelab.map_coordinates(np.ones(3), [[1.0]], prefilter="no"), TypeError, "prefilter"),
        (lambda: splinelab.truncation_width(degree=3, tol=0.0), ValueError, "toleran"),
        (lambda: splinelab.truncation_width(degree=3, order=4, tol=1e-3), ValueError, "not both"),
        (lambda: splinelab.truncation_width(degree=3, tol=1e-3, criterion="max"), ValueError, "criterion"),
        (lambda: splinelab.truncation_width(order=300, tol=1e-3), ValueError, "order"),
        (lambda: splinelab.coefficients(degree=3, bits=5), ValueError, "bit"),
        (lambda: splinelab.coefficients(degree=3, count=0), ValueError, "count"),
        # Integers beyond what the extension takes are refused naming the
        # argument (PyO3 alone raises an OverflowError naming none).
        (lambda: splinelab.coefficients(degree=3, count=-1), ValueError, "count -1 is outside 0.."),
        (lambda: splinelab.coefficients(degree=3, count=10**20), ValueError, "count"),
        (lambda: splinelab.coefficients(degree=3, count=3, bits=-1), ValueError, "bits"),
        (lambda: splinelab.coefficients(degree=10**20, count=3), ValueError, "degree"),
        (lambda: splinelab.filter_bound(3, 1e-10, ndim=10**20), ValueError, "ndim"),
        (lambda: splinelab.check("prefilter", samples=[1.0], coeffs=[1.0], degree=-1), ValueError, "degree -1"),
        # The width search is estimated before it starts (degree 199 at 1e-10
        # takes minutes): refused up front, naming the budget.
        (lambda: splinelab.truncation_width(degree=199, tol=1e-10), ValueError, "pass budget="),
        (lambda: splinelab.truncation_width(degree=3, tol=1e-10, budget=0), ValueError, "budget=0"),
        (lambda: splinelab.check("nope"), ValueError, "kind"),
        (lambda: splinelab.check("prefilter", samples=[1.0, 2.0], coeffs=[1.0]), ValueError, "expected 2"),
        (lambda: splinelab.check("prefilter", samples=[1.0], coeffs=[1.0], degree=16), ValueError, "degree"),
        (lambda: splinelab.check("prefilter", samples=[1.0], coeffs=[1.0], mode="periodic"), ValueError, "mode"),
        (lambda: splinelab.check("prefilter", samples=[1.0], coeffs=[1.0], max_ulps=-1), ValueError, "max_ulps"),
        (lambda: splinelab.check("bezier-eval", coeffs=[1.0], t=[0.5]), TypeError, "values"),
        (lambda: splinelab.check("cond", nodes=[0.0, 1.0], values=[1.0], basis="chebyshev"), ValueError,
         "unknown basis 'chebyshev' (expected one of bernstein, monomial)"),
        (lambda: splinelab.check("cond", nodes=[0.0, 1.0], values=[1.0], norm="1"), ValueError,
         "unknown norm '1' (expected one of 2, inf)"),
        (lambda: splinelab.check("interp", samples=[1.0, 2.0], coordinates=[0.5], values=[1.5], format="f16"),
         ValueError, "unknown format 'f16' (f64, f32)"),
        (lambda: splinelab.check("interp", samples=[1.0, 2.0], coordinates=[0.5], values=[1.5], mode="periodic"),
         ValueError, "mode"),
        (lambda: splinelab.check("knot-insertion", before=1, after=2), TypeError, "triple"),
    ],
)
def test_bad_input_raises(call, exc, words):
    with pytest.raises(exc) as e:
        call()
    assert words.lower() in str(e.value).lower()


def test_extension_refuses_a_bad_axis_without_panicking():
    # The compiled half reached directly (bypassing the Python checks).
    x = np.ones(5)
    with pytest.raises(ValueError, match="axis 3 is out of range"):
        splinelab._ext.filter(x, np.empty(5), [3], 3, "mirror", 0.0, None, 1)


def test_non_finite_user_values_are_failures_not_errors():
    s = np.array([1.0, 2.0, 0.5, 3.0])
    c = splinelab.spline_filter1d(s)
    c[2] = np.nan
    r = splinelab.check("prefilter", samples=s, coeffs=c, max_ulps=4)
    assert r["verdict"] == "fail" and r["failed"] >= 1



@pytest.mark.parametrize("mode", ["constant", "nearest", "reflect", "mirror", "wrap", "grid-wrap",
                                  "grid-constant", "grid-mirror"])
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_coordinates_are_refused_in_every_mode_without_warnings(mode, bad):
    # The engine checks the points (on the pool); the folds and shifts made
    # in Python before it must carry the NaN or infinity there, quietly.
    a = np.arange(42.0).reshape(6, 7)
    c = np.array([[1.0, 2.5, 3.0], [0.5, 4.0, bad]])
    calls = [dict(input=a), dict(input=a, derivative=(1, 0)), dict(input=a, output=np.uint8),
             dict(input=a, order=0), dict(input=a + 1j * a), dict(input=a + 1j * a, derivative=(0, 1))]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for kw in calls:
            with pytest.raises(ValueError, match="coordinate [0-9]+ is not finite"):
                splinelab.map_coordinates(coordinates=c, mode=mode, nan_policy="raise", **kw)
