"""``splinelab.RegularGridInterpolator`` and ``splinelab.interpn``: scipy
1.17's gridded interpolation on a rectilinear grid (issue 49), with the
exact not-a-knot tensor-product spline for "slinear", "cubic" and "quintic".

Python does scipy's argument handling (points, values, xi, bounds, fill
values, dtypes, descending axes, complex values); the extension computes:
``GridSpline`` (the spline's coefficients by one banded solve per grid line
along each axis in turn, and its evaluation), ``grid_linear`` (multilinear)
and ``grid_pchip`` (scipy's recursive PCHIP). "nearest" is numpy indexing,
scipy's rule (ties to the lower node).
"""

from __future__ import annotations

import inspect
import warnings
from types import GenericAlias

import numpy as np

from . import _splinelab as _ext
from ._validate import _threads

_SPLINE_DEGREE_MAP = {"slinear": 1, "cubic": 3, "quintic": 5, "pchip": 3,
                      "slinear_legacy": 1, "cubic_legacy": 3, "quintic_legacy": 5}
_SPLINE_METHODS_recursive = {"slinear_legacy", "cubic_legacy", "quintic_legacy", "pchip"}
_SPLINE_METHODS_ndbspl = {"slinear", "cubic", "quintic"}
_SPLINE_METHODS = list(_SPLINE_DEGREE_MAP)
_ALL_METHODS = ["linear", "nearest"] + _SPLINE_METHODS
_INTERPN_METHODS = ["linear", "nearest", "cubic", "quintic", "pchip", "splinef2d", "slinear",
                    "slinear_legacy", "cubic_legacy", "quintic_legacy"]


def _gcrotmk(A, b, x0=None, *, rtol=1e-5, atol=0.0, maxiter=1000, M=None, callback=None, m=20, k=None,
             CU=None, discard_C=False, truncate="oldest"):
    """The signature of scipy's default solver ``scipy.sparse.linalg.gcrotmk``
    (1.17), against which ``solver_args`` are checked; never called."""


# ---------------------------------------------------------------- arguments


def _check_points(points):
    """The axes as contiguous ascending float64 arrays, and the indices of
    the axes given descending (scipy's ``_check_points``)."""
    descending, grid = [], []
    for i, p in enumerate(points):
        p = np.asarray(p, dtype=float)
        if not np.all(p[1:] > p[:-1]):
            if np.all(p[1:] < p[:-1]):
                descending.append(i)
                p = np.flip(p)
            else:
                raise ValueError(f"The points in dimension {i} must be strictly ascending or descending")
        grid.append(np.ascontiguousarray(p))
    return tuple(grid), tuple(descending)


def _check_dimensionality(points, values):
    if len(points) > values.ndim:
        raise ValueError(f"There are {len(points)} point arrays, but values has {values.ndim} dimensions")
    for i, p in enumerate(points):
        if not np.asarray(p).ndim == 1:
            raise ValueError(f"The points in dimension {i} must be 1-dimensional")
        if not values.shape[i] == len(p):
            raise ValueError(f"There are {len(p)} points and {values.shape[i]} values in dimension {i}")


def _is_array_object(values):
    """numpy arrays (subclasses such as np.matrix included) and array-API
    arrays, which scipy converts with ``np.asarray``; a duck-typed object
    (``ndim``, ``shape``, ``__getitem__``) is kept as it is."""
    return (isinstance(values, (np.ndarray, np.generic)) or hasattr(values, "__array_namespace__")
            or type(values).__module__.partition(".")[0] == "pandas")  # array_like, as scipy's docs say


def _check_values(values):
    if _is_array_object(values) or not hasattr(values, "ndim"):
        values = np.asarray(values)
    if hasattr(values, "dtype") and hasattr(values, "astype"):
        if not np.issubdtype(values.dtype, np.inexact):
            values = values.astype(float)
    return values


def _check_fill_value(values, fill_value):
    if fill_value is not None:
        fill_dtype = np.asarray(fill_value).dtype
        if hasattr(values, "dtype") and not np.can_cast(fill_dtype, values.dtype, casting="same_kind"):
            raise ValueError("fill_value must be either 'None' or of a type compatible with values")
    return fill_value


def _validate_grid_dimensions(points, method):
    k = _SPLINE_DEGREE_MAP[method]
    for i, point in enumerate(points):
        n = len(np.atleast_1d(point))
        if n <= k:
            raise ValueError(f"There are {n} points in dimension {i}, but method {method} requires at least "
                             f" {k + 1} points per dimension.")


def _check_solver(solver, solver_args):
    """scipy calls ``solver(A, b, atol=1e-6, **solver_args)`` (``atol`` only
    where ``solver_args`` has none, and not for ``spsolve``, called as
    ``spsolve(A, b, **solver_args)``); the direct banded solve calls nothing,
    but a solver or arguments scipy's call would refuse are refused here with
    scipy's ``TypeError``."""
    args = dict(solver_args or {})
    target = _gcrotmk if solver is None else solver
    if not callable(target):
        raise TypeError(f"solver {target!r} is not callable")
    if getattr(target, "__name__", "") != "spsolve" and "atol" not in args:
        args["atol"] = 1e-6
    try:
        signature = inspect.signature(target)
    except (TypeError, ValueError):
        return  # a builtin without a signature: nothing to check
    try:
        signature.bind(None, None, **args)
    except TypeError as e:
        raise TypeError(f"solver {getattr(target, '__name__', target)!r} cannot be called as scipy calls it, "
                        f"solver(A, b, **{args}): {e}") from None


def _ndim_coords_from_arrays(points, ndim):
    """``points`` as an array of shape ``(..., ndim)``: a tuple of coordinate
    arrays is broadcast and stacked, a 1-D array is one or more points."""
    if isinstance(points, tuple) and len(points) == 1:
        points = points[0]
    if isinstance(points, tuple):
        p = np.broadcast_arrays(*points)
        for j in range(1, len(p)):
            if p[j].shape != p[0].shape:
                raise ValueError("coordinate arrays do not have the same shape")
        out = np.empty(p[0].shape + (len(points),), dtype=float)
        for j, item in enumerate(p):
            out[..., j] = item
        return out
    points = np.asanyarray(points)
    if points.ndim == 1:
        points = points.reshape(-1, ndim)
    return points


def _scan_points(grid, xi, bounds_error):
    """The points' NaN and out-of-bounds masks (None where no point is
    flagged), in one pass by the engine; with ``bounds_error``, scipy's
    ``ValueError`` for the first axis with a coordinate outside
    ``[grid[0], grid[-1]]`` (NaN included: it compares false). ``xi`` is
    ``(n, ndim)`` C-contiguous float64."""
    if any(len(g) == 0 for g in grid):
        raise IndexError("index 0 is out of bounds for axis 0 with size 0")  # scipy's, reading grid[i][0]
    nans, outside, first_out = _ext.grid_points_scan(list(grid), xi)
    if bounds_error and first_out is not None:
        raise ValueError(f"One of the requested xi is out of bounds in dimension {first_out}")
    return nans, None if bounds_error else outside


def _bounds_check(grid, xi):
    """scipy's ValueError for a coordinate outside ``[grid[0], grid[-1]]``."""
    _scan_points(grid, np.require(xi, dtype=float, requirements="CA"), True)


# ---------------------------------------------------------------- data for the engine


def _native_real(values):
    """``values`` (n-D, real or complex) as float64 or float32 in native byte
    order for the extension, and the complex dtype to view the results as
    (None for real values). Complex values are viewed as (real, imag) pairs
    along a last axis of length 2 (a copy only when the array has to be made
    contiguous for the view)."""
    v = np.asarray(values)
    kind = v.dtype.kind
    if kind == "c":
        cdtype = np.complex64 if v.dtype.itemsize == 8 else np.complex128
        v = np.ascontiguousarray(v, dtype=cdtype)
        return v.view(np.float32 if cdtype == np.complex64 else np.float64).reshape(v.shape + (2,)), cdtype
    if v.dtype == np.float32 or v.dtype == np.float64:
        if not v.dtype.isnative:
            v = v.astype(v.dtype.newbyteorder("="))
        return v, None
    return v.astype(np.float64), None


def _stacked(grid_shape, values):
    """``values`` reshaped to ``grid_shape + (m,)`` for the extension (m the
    product of the trailing dimensions, doubled for complex values), and the
    complex dtype (or None). A view where the layout allows one."""
    v, cdtype = _native_real(values)
    return v.reshape(tuple(grid_shape) + (-1,)), cdtype


def _samples(grid_shape, values):
    """:func:`_stacked` for ``grid_linear``, ``grid_nearest`` and
    ``grid_pchip``, which read samples in place wherever they fill one block
    of memory (any strides: a descending axis flipped by numpy included) and
    a broadcast axis as its one sample; a sliced view is copied once by the
    extension (``MemoryError`` where it cannot be)."""
    return _stacked(grid_shape, values)


def _from_columns(out, cdtype):
    """The extension's ``(n, m)`` float64 result back in the values' type:
    complex pairs viewed as complex128 (scipy's result for complex input)."""
    if cdtype is None:
        return out
    return np.ascontiguousarray(out).view(np.complex128)


class _Spline:
    """The exact spline of one degree over the (ascending) grid: the
    extension's ``GridSpline`` and how to read its results back."""

    def __init__(self, grid, values, degree, threads):
        stacked, self.cdtype = _stacked([len(g) for g in grid], values)
        self.spline = _ext.GridSpline(list(grid), stacked, degree, threads)

    def __call__(self, xi, nu=None, threads=None):
        out = self.spline.eval(np.ascontiguousarray(xi, dtype=np.float64), nu, threads)
        return _from_columns(out, self.cdtype)


def _power_of_two_scaled(grid, xi):
    """The axes and the points' coordinates, each axis scaled by the power of
    two that brings its largest node magnitude into ``[0.5, 1)`` where that
    magnitude is beyond ``2^±64`` (else as they are).

    PCHIP is invariant under a scaling of ``x``, and a power of two scales
    without rounding, so the values are those of the unscaled computation
    wherever it neither overflows nor underflows; on axes scaled by 1e-300
    or 4e307 its slopes and Hermite terms would (scipy then returns NaN or
    raises ``ValueError``)."""
    exps = [int(np.frexp(max(abs(g[0]), abs(g[-1])))[1]) for g in grid]
    exps = [e if abs(e) > 64 else 0 for e in exps]
    if not any(exps):
        return list(grid), np.ascontiguousarray(xi)
    return [np.ldexp(g, -e) for g, e in zip(grid, exps)], np.ascontiguousarray(np.ldexp(xi, -np.array(exps)))


def _nu(nu, ndim):
    """scipy's (NdBSpline's) checks of the derivative orders."""
    if nu is None:
        return None
    nu = np.asarray(nu, dtype=np.int64)
    if nu.ndim != 1 or nu.shape[0] != ndim:
        raise ValueError(f"invalid number of derivative orders nu = {nu!r} for ndim = {ndim}.")
    if any(nu < 0):
        raise ValueError(f"derivatives must be positive, got nu = {nu!r}")
    return [int(v) for v in nu]


def _distinct(v):
    """``v`` with each broadcast axis (stride 0) cut to its one sample: the
    values a scan must read (a broadcast grid of 10^12 points has as many
    distinct values as its base)."""
    if not isinstance(v, np.ndarray) or 0 not in v.strides:
        return v
    return v[tuple(slice(0, 1) if s == 0 else slice(None) for s in v.strides)]


def _require_finite(values, message):
    """scipy's refusal of NaN or infinity in the values of a spline method
    (each distinct value read once, about 4 Mi elements at a time: no array
    of the values' size)."""
    v = _distinct(np.asarray(values))
    if v.ndim == 0 or v.size == 0:
        finite = bool(np.all(np.isfinite(v)))
    else:
        step = max(1, (1 << 22) // max(1, v.size // v.shape[0]))
        finite = all(np.all(np.isfinite(v[i:i + step])) for i in range(0, v.shape[0], step))
    if not finite:
        raise ValueError(message)


# ---------------------------------------------------------------- the interpolator


class RegularGridInterpolator:
    """Interpolator on a rectilinear grid in N >= 1 dimensions: scipy's ``RegularGridInterpolator``, exact splines.

    Drop-in for :class:`scipy.interpolate.RegularGridInterpolator` (scipy
    1.17): the same arguments, defaults, attributes, results and exceptions,
    except that "slinear", "cubic" and "quintic" give the **exact**
    not-a-knot tensor-product spline (scipy's knots, ``_not_a_knot`` per
    axis) where scipy solves for its coefficients iteratively (``gcrotmk``,
    stopping at a residual norm of ``max(1e-5 |b|, 1e-6)`` over the whole
    grid): here one banded LU solve per grid line along each axis
    in turn (with partial pivoting, which the not-a-knot rows need), in
    O(N k) time and one coefficient array of memory. The spline meets the
    data at every node to :attr:`error_bound`.

    Parameters
    ----------
    points : tuple of array_like
        The grid's axes, n 1-D arrays of float of lengths m1, ..., mn, each
        strictly ascending or strictly descending (a descending axis is
        reversed, points and values together), any spacing.
    values : array_like
        The data on the grid, of shape ``(m1, ..., mn, ...)``; trailing
        dimensions beyond the n axes are interpolated together. Real
        (integers and booleans are converted to float64, as scipy) or
        complex. float64 and float32 are read as they are (in place,
        descending axes too; a broadcast view is copied once for "linear"
        and "pchip"); other dtypes are converted to float64.
    method : str, optional
        "linear" (default), "nearest", "slinear", "cubic", "quintic",
        "pchip", or scipy's "slinear_legacy", "cubic_legacy",
        "quintic_legacy" (the same exact splines; scipy's legacy route is
        exact too, and slow). The default of :meth:`__call__`.
    bounds_error : bool, optional
        True (default): a point outside the grid is a ``ValueError``.
    fill_value : float or None, optional
        The value at points outside the grid when ``bounds_error`` is
        False (default NaN); None extrapolates (each method's end pieces).
        Must cast to the values' dtype ("same_kind").
    solver, solver_args : optional
        Accepted as scipy accepts them, for "slinear", "cubic" and
        "quintic" only (another method with either is scipy's
        ``ValueError``): the direct solve needs no solver and calls none,
        but a solver, or ``solver_args``, that scipy's call
        ``solver(A, b, atol=1e-6, **solver_args)`` would refuse is refused
        with scipy's ``TypeError``.
    threads : int or None, optional
        splinelab's own: threads for construction and evaluation (None:
        one per core).

    Attributes
    ----------
    grid : tuple of ndarray
        The axes, ascending.
    values : ndarray
        The data (reversed along the axes given descending).
    method : str
    fill_value : float or None
    bounds_error : bool
    condition : list of float or None
        The spline methods: per axis, an estimate of the infinity-norm
        condition number of the 1-D collocation matrix (None for the other
        methods).
    error_bound : float or None
        The spline methods: a bound on ``|computed - exact|`` of the
        spline's values inside the grid (for the construction method; None
        for the other methods).

    Raises
    ------
    ValueError
        As scipy: an unknown method; points not strictly monotonic, not
        1-D, or of another length than the values' axis; more point arrays
        than values has dimensions; fewer than ``k + 1`` points on an axis
        for a spline method (``k`` the degree, 3 for "pchip"); a
        ``fill_value`` that does not cast to the values' dtype; complex
        values with "pchip"; a solver for a method without one; NaN or
        infinity in the values of a spline method (scipy's ``gcrotmk``
        refuses them).
    TypeError
        A ``solver`` or ``solver_args`` that scipy's call would refuse.
    MemoryError
        Coefficients that cannot be allocated.

    Notes
    -----
    "linear" and "nearest" give scipy's numbers (nearest rounds ties down,
    as scipy); "pchip" scipy's recursive PCHIP (last axis first). Results
    are float64 (complex128) for "linear" and the spline methods, the
    values' dtype for "nearest", "pchip" and the legacy methods, as scipy.
    See :doc:`/coming_from_scipy_interpolate`.

    Examples
    --------
    >>> import numpy as np, splinelab
    >>> x = np.array([0.0, 0.4, 1.1, 1.5, 2.6, 3.0])
    >>> y = np.linspace(-1.0, 1.0, 7)
    >>> f = lambda x, y: x**3 - 2 * x * y**2 + y
    >>> v = f(*np.meshgrid(x, y, indexing="ij"))
    >>> ip = splinelab.RegularGridInterpolator((x, y), v, method="cubic")
    >>> bool(abs(ip([1.3, 0.25])[0] - f(1.3, 0.25)) < 1e-12)   # a cubic is reproduced exactly
    True
    >>> at_nodes = np.stack(np.meshgrid(x, y, indexing="ij"), axis=-1)
    >>> bool(np.abs(ip(at_nodes) - v).max() <= ip.error_bound)   # meets the data to its bound
    True
    """

    _SPLINE_DEGREE_MAP = _SPLINE_DEGREE_MAP
    _SPLINE_METHODS_recursive = _SPLINE_METHODS_recursive
    _SPLINE_METHODS_ndbspl = _SPLINE_METHODS_ndbspl
    _SPLINE_METHODS = _SPLINE_METHODS
    _ALL_METHODS = _ALL_METHODS

    __class_getitem__ = classmethod(GenericAlias)

    def __init__(self, points, values, method="linear", bounds_error=True, fill_value=np.nan, *, solver=None,
                 solver_args=None, threads=None):
        if method not in _ALL_METHODS:
            raise ValueError(f"Method '{method}' is not defined")
        elif method in _SPLINE_METHODS:
            _validate_grid_dimensions(points, method)
        self._threads = _threads(threads)
        self.method = method
        self._spline = None
        self.bounds_error = bounds_error
        self._grid, self._descending_dimensions = _check_points(points)
        self._values = _check_values(values)
        _check_dimensionality(self._grid, self._values)
        self.fill_value = _check_fill_value(self._values, fill_value)
        if self._descending_dimensions:
            # scipy flips the values as given (an integer array stays integer)
            self._values = np.flip(values, axis=self._descending_dimensions)
        if method == "pchip" and np.iscomplexobj(self._values):
            raise ValueError("`PchipInterpolator` only works with real values. If you are trying to use the real "
                             "components of the passed array, use `np.real` on the array before passing to "
                             "`RegularGridInterpolator`.")
        if method in _SPLINE_METHODS_ndbspl:
            _check_solver(solver, solver_args)
            self._spline = self._construct_spline(method)
        elif solver is not None or solver_args:
            raise ValueError(f"method = {method!r} does not accept the 'solver' argument. Got  "
                             f"solver = {solver!r} and with arguments {solver_args}.")

    def __getstate__(self):
        # The spline is rebuilt from the values on unpickling (the same
        # bits: a deterministic solve), so the values travel once.
        return {**self.__dict__, "_spline": None}

    def __setstate__(self, state):
        self.__dict__.update(state)
        if self.method in _SPLINE_METHODS_ndbspl:
            self._spline = self._construct_spline(self.method)

    def _construct_spline(self, method):
        _validate_grid_dimensions(self._grid, method)
        values = self._array_values()
        _require_finite(values, "RHS must contain only finite numbers")
        return _Spline(self._grid, values, _SPLINE_DEGREE_MAP[method], self._threads)

    @property
    def grid(self):
        """The grid's axes, each ascending (a tuple of float64 arrays)."""
        return tuple(self._grid)

    @property
    def values(self):
        """The data on the grid, reversed along the axes given descending."""
        return self._values

    @property
    def condition(self):
        """Per axis, an estimate of the infinity-norm condition number of the 1-D collocation matrix.

        A list of floats for the spline methods ("slinear", "cubic",
        "quintic": the construction's method), None for the others.
        """
        return None if self._spline is None else list(self._spline.spline.condition)

    @property
    def error_bound(self):
        """A bound on ``|computed - exact|`` of the spline's values inside the grid.

        The exact spline meets the data at every node, so the interpolant
        meets it to within this bound there. A float for the spline methods
        (the construction's method), None for the others.
        """
        return None if self._spline is None else float(self._spline.spline.error_bound)

    def __call__(self, xi, method=None, *, nu=None):
        """Interpolation at coordinates.

        Parameters
        ----------
        xi : array_like or tuple of array_like
            The points, of shape ``(..., ndim)``, or a tuple of ``ndim``
            coordinate arrays broadcast together; a 1-D array is one point,
            or several laid end to end.
        method : str, optional
            Another method for this call (default: the construction's); a
            spline method other than the construction's builds its spline
            for this call.
        nu : sequence of int, optional
            Derivative orders, one per axis, for "slinear", "cubic" and
            "quintic" only (a ``ValueError`` otherwise, as scipy).

        Returns
        -------
        ndarray
            Of shape ``xi.shape[:-1] + values.shape[ndim:]``
            (``(1,) + values.shape[ndim:]`` for a 1-D ``xi``). NaN where a
            coordinate is NaN; ``fill_value`` outside the grid unless None.
        """
        spline = self._spline
        method = self.method if method is None else method
        changed = self.method != method
        if method not in _ALL_METHODS:
            raise ValueError(f"Method '{method}' is not defined")
        if changed and method in _SPLINE_METHODS_ndbspl:
            spline = self._construct_spline(method)
        if nu is not None and method not in _SPLINE_METHODS_ndbspl:
            raise ValueError(f"Can only compute derivatives for methods {_SPLINE_METHODS_ndbspl}, got "
                             f"method = {method!r}.")
        xi, xi_shape, ndim, nans, out_of_bounds = self._prepare_xi(xi)

        if method == "linear":
            result = self._linear(xi)
        elif method == "nearest":
            result = self._nearest(xi)
        else:
            if changed:
                _validate_grid_dimensions(self._grid, method)
            if method in _SPLINE_METHODS_ndbspl:
                result = spline(xi, _nu(nu, ndim), self._threads)
            elif method == "pchip":
                values = self._array_values()
                _require_finite(values, "`y` must contain only finite values.")
                # scipy's recursive route interpolates the last axis first and
                # refuses a non-finite result before the next axis
                _require_finite(xi[:, 1:], "`y` must contain only finite values.")
                stacked, _ = _samples([len(g) for g in self._grid], values)
                grid, at = _power_of_two_scaled(self._grid, xi)
                result = _ext.grid_pchip(grid, stacked, at, self._threads)
                result = result.astype(values.dtype, copy=False)
            else:  # the legacy methods: scipy's recursive route to the same exact spline
                values = self._array_values()
                _require_finite(values, "Array must not contain infs or nans.")
                _require_finite(xi[:, 1:], "Array must not contain infs or nans.")
                result = self._construct_spline(method)(xi, None, self._threads)
                result = result.astype(values.dtype, copy=False)

        # scipy writes fill_value and NaN into its (points,) + trailing result,
        # with numpy's boolean-mask assignment: an array of one value per point
        # outside is taken in order, a 2-D one or one of another size refused
        # (even where no point is outside)
        result = result.reshape((xi.shape[0],) + self._values.shape[ndim:])
        if not self.bounds_error and self.fill_value is not None:
            if out_of_bounds is not None:
                result[out_of_bounds] = self.fill_value
            elif np.ndim(self.fill_value) > 0:
                result[np.zeros(len(result), dtype=bool)] = self.fill_value
        if nans is not None:
            result[nans] = np.nan
        return result.reshape(xi_shape[:-1] + self._values.shape[ndim:])

    def _prepare_xi(self, xi):
        ndim = len(self._grid)
        xi = _ndim_coords_from_arrays(xi, ndim=ndim)
        if xi.shape[-1] != ndim:
            raise ValueError(f"The requested sample points xi have dimension {xi.shape[-1]} but this "
                             f"RegularGridInterpolator has dimension {ndim}")
        xi_shape = xi.shape
        # C order and aligned: the engine reads xi as one slice (a numpy array
        # unpickled by dask.distributed can sit at any byte offset)
        xi = np.require(xi.reshape(-1, xi_shape[-1]), dtype=float, requirements="CA")
        nans, out_of_bounds = _scan_points(self._grid, xi, self.bounds_error)
        return xi, xi_shape, ndim, nans, out_of_bounds

    def _array_values(self):
        """The values as an array (a duck-typed object read whole with
        ``__getitem__``, as scipy's linear route reads it piece by piece)."""
        v = self._values
        if not hasattr(v, "dtype") or not hasattr(v, "reshape"):
            v = np.asarray(v[tuple(slice(None) for _ in range(v.ndim))])
            if not np.issubdtype(v.dtype, np.inexact):
                v = v.astype(float)
        return v

    def _linear(self, xi):
        """scipy's multilinear interpolation (linear extrapolation), in
        scipy's floating-point operations (the node values are the samples,
        bit for bit); an axis of one point is constant along it."""
        values = self._array_values()
        keep, values = self._long_axes(values)
        grid = [self._grid[i] for i in keep]
        stacked, cdtype = _samples([len(g) for g in grid], values)
        if not grid:
            out = np.broadcast_to(stacked.astype(np.float64), (xi.shape[0],) + stacked.shape).copy()
        else:
            out = _ext.grid_linear(grid, stacked, _columns(xi, keep), self._threads, self._value_first())
        return _from_columns(out, cdtype)

    def _value_first(self):
        """Whether scipy evaluates this grid with its 2-D kernel (float64 or
        complex128 values of exactly two axes, native and writeable), which
        forms each corner's term as ``(v * w0) * w1``; its general route
        forms ``v * (w0 * w1)``."""
        v = self._values
        return (len(self._grid) == 2 and isinstance(v, np.ndarray) and v.ndim == 2 and v.flags.writeable
                and v.dtype in (np.float64, np.complex128) and v.dtype.byteorder == "=")

    def _long_axes(self, values):
        """The axes of more than one point, and the values with the others
        (of one point: constant along them) taken away."""
        keep = [i for i, g in enumerate(self._grid) if len(g) > 1]
        if len(keep) < len(self._grid):
            values = values[tuple(slice(None) if len(g) > 1 else 0 for g in self._grid)]
        return keep, values

    def _nearest(self, xi):
        """The nearest node, ties to the lower one (scipy's ``yi <= .5`` on
        scipy's normalised distance, the same floating-point operations):
        float32, float64 and complex values gathered by the engine in their
        dtype, any other through numpy's indexing."""
        values = self._values
        keep, values = self._long_axes(values) if isinstance(values, np.ndarray) else ([], None)
        if values is not None and keep and values.dtype.isnative and values.dtype in _GATHERED:
            grid = [self._grid[i] for i in keep]
            stacked, cdtype = _samples([len(g) for g in grid], values)
            out = _ext.grid_nearest(grid, stacked, _columns(xi, keep), self._threads)
            return out if cdtype is None else np.ascontiguousarray(out).view(values.dtype)
        index = []
        for x, g in zip(xi.T, self._grid):
            if len(g) == 1:
                index.append(np.zeros(x.shape, dtype=np.intp))
                continue
            i = np.clip(np.searchsorted(g, x, side="right") - 1, 0, len(g) - 2)
            with np.errstate(invalid="ignore"):
                y = (x - g[i]) / (g[i + 1] - g[i])
                index.append(np.where(y <= 0.5, i, i + 1))
        return np.asarray(self._values[tuple(index)])


def _columns(xi, keep):
    """The coordinates of the axes ``keep`` (``xi`` itself when they are all)."""
    return xi if len(keep) == xi.shape[1] else np.ascontiguousarray(xi[:, keep])


#: The dtypes whose "nearest" values the engine gathers (complex ones as
#: pairs of reals).
_GATHERED = (np.float32, np.float64, np.complex64, np.complex128)


# ---------------------------------------------------------------- interpn


def interpn(points, values, xi, method="linear", bounds_error=True, fill_value=np.nan, *, threads=None):
    """Multidimensional interpolation on a rectilinear grid: scipy's ``interpn``, exact splines.

    Drop-in for :func:`scipy.interpolate.interpn` (scipy 1.17): builds a
    :class:`RegularGridInterpolator` and evaluates it at ``xi``, with
    scipy's checks and messages.

    Parameters
    ----------
    points : tuple of array_like
        The grid's axes, n 1-D arrays of lengths m1, ..., mn, strictly
        ascending or descending.
    values : array_like
        The data on the grid, of shape ``(m1, ..., mn, ...)`` (real or
        complex).
    xi : array_like or tuple of array_like
        The points, of shape ``(..., n)``, or a tuple of ``n`` arrays
        broadcast together.
    method : str, optional
        "linear" (default), "nearest", "slinear", "cubic", "quintic",
        "pchip", "splinef2d" or the ``*_legacy`` spline names.
        "splinef2d" (2-D scalar data, ascending axes only, as scipy's
        ``RectBivariateSpline``) is FITPACK's interpolating cubic with
        knots at ``x[2:-2]``, which is the not-a-knot cubic: here the same
        exact spline as "cubic", its result in ``xi``'s dtype and
        ``fill_value`` at every point outside the grid (NaN points
        included), as scipy.
    bounds_error : bool, optional
        True (default): a point outside the grid is a ``ValueError``.
    fill_value : float or None, optional
        The value outside the grid when ``bounds_error`` is False (default
        NaN); None extrapolates (not with "splinef2d").
    threads : int or None, optional
        splinelab's own: threads (None: one per core).

    Returns
    -------
    ndarray
        The interpolated values, of shape ``xi.shape[:-1] + values.shape[n:]`` (``(1,) + values.shape[ndim:]`` for a 1-D
        ``xi``), in the dtype of :class:`RegularGridInterpolator`'s result
        for the method ("splinef2d": ``xi``'s dtype, as scipy).

    Raises
    ------
    ValueError
        scipy's: an unknown method, "splinef2d" on other than 2-D scalar
        data or with ``fill_value=None`` and ``bounds_error=False``, a point
        outside the grid with ``bounds_error``, and the checks of
        :class:`RegularGridInterpolator`.

    Examples
    --------
    >>> import numpy as np, splinelab
    >>> x, y = np.linspace(0, 4, 5), np.linspace(0, 5, 6)
    >>> v = 2 * x[:, None] + 3 * y[None, :]
    >>> splinelab.interpn((x, y), v, [2.21, 3.12])
    array([13.78])
    """
    if method not in _INTERPN_METHODS:
        raise ValueError("interpn only understands the methods 'linear', 'nearest', 'slinear', 'cubic', 'quintic', "
                         f"'pchip', and 'splinef2d'. You provided {method}.")
    if not hasattr(values, "ndim"):
        values = np.asarray(values)
    ndim = values.ndim
    if ndim > 2 and method == "splinef2d":
        raise ValueError("The method splinef2d can only be used for 2-dimensional input data")
    if not bounds_error and fill_value is None and method == "splinef2d":
        raise ValueError("The method splinef2d does not support extrapolation.")
    if len(points) > ndim:
        raise ValueError(f"There are {len(points)} point arrays, but values has {ndim} dimensions")
    if len(points) != ndim and method == "splinef2d":
        raise ValueError("The method splinef2d can only be used for scalar data with one point per coordinate")

    grid, _ = _check_points(points)
    _check_dimensionality(grid, values)
    xi = _ndim_coords_from_arrays(xi, ndim=len(grid))
    if xi.shape[-1] != len(grid):
        raise ValueError(f"The requested sample points xi have dimension {xi.shape[-1]}, but this "
                         f"RegularGridInterpolator has dimension {len(grid)}")
    if bounds_error:
        _bounds_check(grid, xi.reshape(-1, xi.shape[-1]))

    if method in _ALL_METHODS:
        interp = RegularGridInterpolator(points, values, method=method, bounds_error=bounds_error,
                                         fill_value=fill_value, threads=threads)
        return interp(xi)
    return _splinef2d(points, values, xi, fill_value, threads)


def _splinef2d(points, values, xi, fill_value, threads):
    """scipy's "splinef2d": ``RectBivariateSpline(x, y, z)`` (FITPACK's
    interpolating cubic, ``s=0``: knots ``x[2:-2]`` per axis, the not-a-knot
    spline) at the points inside the grid, ``fill_value`` elsewhere."""
    xi_shape = xi.shape
    xi = xi.reshape(-1, xi.shape[-1])
    x, y = (np.ravel(np.asarray(p)) for p in (points[0], points[1]))
    z = np.asarray(values)
    if np.iscomplexobj(z):
        warnings.warn("Casting complex values to real discards the imaginary part", np.exceptions.ComplexWarning,
                      stacklevel=3)
        z = z.real
    if not np.all(np.diff(x) > 0.0):
        raise ValueError("x must be strictly increasing")
    if not np.all(np.diff(y) > 0.0):
        raise ValueError("y must be strictly increasing")
    for name, n in (("x", len(x)), ("y", len(y))):
        if n <= 3:
            raise ValueError(f"splinef2d (FITPACK's regrid) needs at least 4 points along {name}, got {n}")
    grid = (np.asarray(x, dtype=float), np.asarray(y, dtype=float))
    valid = np.all((grid[0][0] <= xi[:, 0], xi[:, 0] <= grid[0][-1],
                    grid[1][0] <= xi[:, 1], xi[:, 1] <= grid[1][-1]), axis=0)
    result = np.empty_like(xi[:, 0])
    spline = _Spline(grid, np.asarray(z, dtype=np.float64), 3, _threads(threads))
    if np.any(valid):
        result[valid] = spline(np.asarray(xi[valid], dtype=np.float64))[:, 0]
    result[np.logical_not(valid)] = fill_value
    return result.reshape(xi_shape[:-1])
