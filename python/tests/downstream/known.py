"""The downstream tests that fail with splinelab swapped in, each with its
reason (README.md in this folder). splinelab_swap marks them
xfail(strict=True) when swapped, and run.py requires each to pass on the
original (scipy, or xarray's own ``interp``): a fixed one shows as a strict
XPASS failure, and its entry goes.

Only differences where splinelab is more accurate than scipy belong here,
each with the figure that shows it. scipy's clients have none at present:
reproject's 37 float32 tests (two routes compared at ``rtol=1e-7`` on
float32 data) pass since float32 input is computed in float64 and rounded
once, as scipy computes it (issue 42), and its NaN-coordinate test passes
under ``nan_policy="propagate"`` (issue 37, scipy's values at NaN
coordinates).

xarray's: ``test_interpolate_nd`` compares ``interp(..., method="quintic")``
on three dimensions with scipy's ``interpn``, whose quintic spline is
``gcrotmk``'s iterative solve (``atol=1e-6``), at xarray's default
``assert_allclose`` tolerance (``rtol=1e-5, atol=1e-8``). scipy's values are
2.5e-6 of max|data| from the exact not-a-knot spline (make_interp_spline
along each axis, NdBSpline), the accessor's 1.2e-15; they differ by up to
2.2 times that tolerance. (Cubic: scipy 1.4e-6 from the exact spline, within
the tolerance; the test passes.) ``python/tests/test_xarray.py::
test_xarrays_quintic_nd_case_is_scipys_iterative_error`` measures both.
"""

_QUINTIC_ND = ("the exact quintic spline (1.2e-15 of max|data| from make_interp_spline + NdBSpline) where "
               "scipy's interpn is gcrotmk's (2.5e-6 from it), compared at rtol=1e-5: they differ by 2.2x that")

KNOWN: dict[str, str] = {
    "xarray/tests/test_interp.py::test_interpolate_nd[no_chunk-quintic]": _QUINTIC_ND,
    "xarray/tests/test_interp.py::test_interpolate_nd[chunked-quintic]": _QUINTIC_ND,
}
