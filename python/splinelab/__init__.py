"""splinelab for Python: spline prefiltering and interpolation of any degree.

Drop-in for ``scipy.ndimage``'s spline functions, with the same argument
names and defaults where they overlap: ``spline_filter1d``,
``spline_filter``, ``map_coordinates``, ``zoom``, ``shift``, ``rotate``,
``affine_transform`` and ``geometric_transform`` (plus ``spline_gradient``
and ``map_coordinates(derivative=...)``), and for ``scipy.interpolate``'s
``RegularGridInterpolator`` and ``interpn``, whose "slinear", "cubic" and
"quintic" splines are computed exactly (a direct banded solve per grid line). As in scipy, ``order`` is the
spline **degree** (scipy's ``order``; the papers' B-spline order is
``degree + 1``), here any of 0..199 where scipy stops at 5.

Extra keywords:

- ``tol=``: use the truncated prefilter whose half-width is *certified* for
  ``tol`` (each coefficient within ``tol * max|input|`` of the exact one per
  filtered axis; :func:`truncation_width` gives the width and bound);
- ``threads=``: threads for the parallel path (``None``: one per core);
- ``nan_policy=``: what NaN/±inf samples (missing data) do: 'propagate'
  (default, scipy's pattern), 'raise', or 'local' (NaN only within
  :func:`nan_reach` samples of a missing one, a certified bound elsewhere).

Modes: scipy's names, computed as scipy 1.17 computes them (the filters
have scipy's three rules: mirror, half-sample reflect, periodic; see
:func:`spline_filter1d`); ``map_coordinates`` defaults to ``constant`` as
scipy and computes scipy's ``wrap`` (period ``n - 1``) as scipy does. ``exact_edges=True``
gives the exact spline of the edge- or constant-extended signal for
``nearest`` / ``grid-constant``, which scipy approximates.

Data: every dtype scipy takes (bool, integer, float, complex), any
strides; ``output`` as in scipy (integer results rounded as scipy rounds
them). Functions release the GIL while computing. Bad arguments raise
``ValueError`` (bad values, with the Rust engine's message) or ``TypeError``
(wrong types), and where scipy raises ``RuntimeError`` a class of
:mod:`splinelab.errors` that is both; an output or a work array that cannot
be allocated raises ``MemoryError``, as scipy.

>>> import numpy as np, splinelab
>>> c = splinelab.spline_filter1d(np.array([0.0, 1.0, 8.0, 27.0]), order=3)
>>> s = (c[:-2] + 4 * c[1:-1] + c[2:]) / 6  # the cubic B-spline at the knots
>>> bool(np.allclose(s, [1.0, 8.0]))
True
"""

from __future__ import annotations

from . import _splinelab as _ext
from . import errors
from ._check import check
from ._interpolant import Interpolant
from ._ndimage import map_coordinates, spline_filter, spline_filter1d, spline_gradient
from ._resample import affine_transform, geometric_transform, rotate, shift, zoom
from ._rgi import RegularGridInterpolator, interpn
from ._sspline import coefficients, filter_bound, nan_reach, truncation_width
from ._validate import MAX_DEGREE

__version__ = _ext.__version__

__all__ = [
    "spline_filter1d",
    "spline_filter",
    "map_coordinates",
    "spline_gradient",
    "zoom",
    "shift",
    "rotate",
    "affine_transform",
    "geometric_transform",
    "RegularGridInterpolator",
    "interpn",
    "Interpolant",
    "truncation_width",
    "coefficients",
    "check",
    "filter_bound",
    "nan_reach",
    "MAX_DEGREE",
]


def __getattr__(name):
    # `import splinelab` then `splinelab.dask` works without `import splinelab.dask`
    # (dask stays an optional, lazily imported dependency).
    if name == "dask":
        import importlib

        return importlib.import_module(".dask", __name__)
    raise AttributeError(f"module 'splinelab' has no attribute {name!r}")
