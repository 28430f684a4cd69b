"""The scipy.ndimage drop-in: spline_filter1d, spline_filter, map_coordinates."""

from __future__ import annotations

import math

import numpy as np

from . import _splinelab as _ext
from . import _dtypes as _dt
from . import _local
from ._doc import fill
from ._engine import _direct, _interpolate, _map_real, _Points, _refuse_non_finite
from ._engine import _wrap_coordinates  # noqa: F401 (python/tests/test_scipy.py reads it here)
from ._modes import filter_rule
from ._settings import Settings, _defaults
from .errors import CoordinateShapeError
from ._validate import DEFAULT_TOL, _cval, _flag, _int, _real_array

def _same_layout(a, b):
    """Whether `a` and `b` are the same elements in the same places."""
    ia, ib = a.__array_interface__, b.__array_interface__
    return ia["data"][0] == ib["data"][0] and a.strides == b.strides and a.shape == b.shape


_FLOATS = frozenset((np.dtype(np.float64), np.dtype(np.float32)))  # hashed: a small call's lookup


def _filter(input, axes, order, output, mode, tol, threads, exact_edges=False, convolution=False,
            nan_policy="propagate", compute="float64"):
    """scipy's spline_filter(1d) for every dtype it takes: the arguments
    checked in the order the filters have always checked them (compute, the
    input, ``output``, then the settings, :meth:`Settings.for_filter`), then
    :func:`_filter_with`. ``output=None``: the input's dtype.
    ``convolution``: with ``tol``, the local truncated convolution (what
    chunked filtering needs, splinelab.dask) instead of the fast route."""
    compute = _dt.compute_name(compute)
    a = _dt.input_array(input)
    cplx = a.dtype.kind == "c"
    dtype, target = _dt.output_dtype(output, a.dtype, None, cplx)
    _dt.check_output_shape(target, a.shape)
    s = Settings.for_filter(order, mode, tol, threads, exact_edges, nan_policy, compute)
    return _filter_with(a, axes, s, dtype, target, convolution)


def _filter_with(a, axes, s, dtype, target, convolution=False):
    """The filter of ``a`` (checked: :func:`_filter`) along ``axes`` under
    the settings ``s`` into ``dtype`` (``target``: the array to write, or
    None), computed in float64 (``s.compute == "float32"``: in float32):
    float64/float32 results straight from the engine (float32 rounded
    after every axis, as scipy writes each axis into a float32 ``output``);
    integer and boolean results converted as scipy's filter converts them
    (truncated), after each axis as scipy does (it filters axis by axis
    into ``output``); float16 results rounded once after every axis is
    filtered in float64; complex input filtered part by part (same filter).
    ``s.nan_policy``: what non-finite samples do (:data:`NAN_POLICY_DOC`)."""
    if s.degree < 2 or a.size == 0:
        # Degrees 0 and 1, and no samples (scipy returns the empty array):
        if s.nan_policy == "raise":
            _refuse_non_finite(a)
        return _copied(a, dtype, target)
    compute = s.compute
    spec = (s.degree, s.filter_rule(), 0.0, s.tol, s.threads, bool(convolution), s.nan_policy)
    if a.dtype.kind == "c":
        part = _dt.real_dtype(dtype)
        out = np.empty(a.shape, dtype)
        out.real = _filter_float(a.real, part, None, (axes, *spec), compute)
        out.imag = _filter_float(a.imag, part, None, (axes, *spec), compute)
        return _dt.deliver(out, target, a.shape)
    if dtype in _FLOATS:
        return _filter_float(a, dtype, target, (axes, *spec), compute)
    work = np.dtype(np.float32 if compute == "float32" else np.float64)
    if dtype.kind == "f":
        # float16: every axis in the working dtype, then one rounding.
        return _dt.deliver(_filter_float(a, work, None, (axes, *spec), compute).astype(dtype), target, a.shape)
    # Integers and booleans: axis by axis, each stored as scipy stores it
    # and read back by the next (booleans as npy_bool's bytes, 0..255).
    carried = _dt.carried_dtype(dtype)
    for axis in axes:
        a = _dt.store_truncated(_dt.settled(_filter_float(a, work, None, ([axis], *spec), compute)), carried)
    return _dt.deliver(a.astype(dtype, copy=False), target, a.shape)


def _copied(a, dtype, target):
    """scipy's filter of degree 0 or 1: ``output[...] = input`` (numpy's
    conversion), no filter, no call into the engine."""
    if target is None and a.dtype == dtype:
        return a.copy()  # no conversion, so no warning to silence
    out = target if target is not None else np.empty(a.shape, dtype)
    with np.errstate(invalid="ignore", over="ignore"):
        np.copyto(out, a, casting="unsafe")
    return out


def _filter_float(a, dtype, target, args, compute="float64"):
    """The engine's filter into a float64/float32 result (`target` or new),
    computed in float64 (``compute="float32"``: in float32, then converted
    into ``dtype``)."""
    if compute == "float32" and dtype != np.float32:
        out = _filter_float(a, np.dtype(np.float32), None, args, compute).astype(dtype)
        return out if target is None else _dt.deliver(out, target, a.shape)
    # The result is written straight into `output` when it is C-ordered and
    # writeable, else into a new C-ordered array (numpy's allocator, which
    # asks for huge pages); the engine reads the input where it lies
    # (float64 or float32, any strides: widened as its first pass reads
    # it) and writes the result. Other input dtypes are read from a copy
    # (`_dt.engine_samples`), and an overlap with `output` goes through
    # numpy's copy into it instead (still one copy).
    direct = (target is not None and target.flags.c_contiguous and target.flags.writeable
              and target.dtype == dtype)
    out = target if direct else np.empty(a.shape, dtype)
    src = _dt.engine_samples(a, compute == "float32")
    if direct and np.may_share_memory(a, out):  # a new array shares nothing
        if not _same_layout(a, out):
            np.copyto(out, a, casting="unsafe")
        src = None
    _ext.filter(src, out, *args, f32=compute == "float32")
    if target is None or direct:
        return out
    target[...] = out
    return target


def _axis(axis, ndim):
    axis = _int(axis, "axis")
    if not -ndim <= axis < ndim:
        raise np.exceptions.AxisError(axis, ndim)
    return axis % ndim


@fill
def spline_filter1d(
    input, order=3, axis=-1, output=np.float64, mode="mirror", *, tol=DEFAULT_TOL, threads=None, exact_edges=False,
    nan_policy="propagate", compute="float64",
):
    """Interpolation coefficients along one axis (``scipy.ndimage.spline_filter1d``).

    The coefficients ``c`` of the spline of degree ``order`` through the
    samples: ``sum_i c_i B(j - i) = input_j`` at every sample ``j``, the
    samples extended beyond the ends by ``mode``.

    Parameters
    ----------
    %(filter_input)s
    %(filter_order)s
    axis : int, optional
        The axis to filter (negative counts from the end). Default -1.
    %(filter_output)s
    %(filter_mode)s
    %(filter_keywords)s

    Returns
    -------
    ndarray
        The coefficients: a new array, or ``output``.

    Raises
    ------
    numpy.exceptions.AxisError
        ``axis`` out of range (also for a 0-d input).
    %(raises)s

    Notes
    -----
    Method: the exact causal/anti-causal recursions, one pair per pole
    (Unser, Aldroubi and Eden 1993), the poles rounded once from MPFR; with
    ``tol``, the truncated convolution of half-width
    :func:`splinelab.truncation_width`. Error: ``tol=None``, the rounding of
    the recursions (the report's accuracy section measures it against
    MPFR); with ``tol``, at most ``bound * max|input|`` more. Cost:
    O(poles) operations per sample; memory: the output.

    Examples
    --------
    The cubic coefficients of the identity's columns reproduce it:

    >>> import numpy as np, splinelab
    >>> c = splinelab.spline_filter1d(np.eye(3), order=3, axis=0)
    >>> bool(np.allclose((4 * c[0] + 2 * c[1]) / 6, [1, 0, 0]))
    True
    """
    if tol is DEFAULT_TOL:
        # The common call in one step (map_coordinates'; degrees 0 and 1
        # scipy's copy).
        values = _ext.filter_common(input, order, axis, False, output, mode, threads, nan_policy, compute, exact_edges)
        if values is not None:
            return values
    common = _common(input, order, axis, output, mode, tol, threads, exact_edges, nan_policy, compute)
    if common is not None:
        return _common_filter(order, *common)
    a = np.asarray(input)
    return _filter(a, [_axis(axis, a.ndim)], order, output, mode, tol, threads, exact_edges, nan_policy=nan_policy,
                   compute=compute)


_SCALARS = frozenset((np.float64, np.float32, float))
_EVERY = object()  # spline_filter's axes (None is an axis spline_filter1d refuses)


def _common(input, order, axis, output, mode, tol, threads, exact_edges, nan_policy, compute):
    """The common filter call, or None where it is not one: a float64 or
    float32 array in native byte order, a degree in range, an axis it has
    (:data:`_EVERY`: every axis), ``output`` None or a float64 / float32 dtype, a
    known mode and every engine keyword at its default but ``threads`` (None
    or an int in range). Every check of
    :func:`_filter` passes there and changes nothing, so its result is
    :func:`_common_filter`'s, a microsecond or two sooner."""
    if not (type(input) is np.ndarray and input.dtype in _FLOATS and (exact_edges is False or exact_edges is True)
            and _defaults(order, mode, True, tol, threads, nan_policy, compute)):
        return None
    if axis is _EVERY:
        axes = list(range(input.ndim))
    elif type(axis) is int and -input.ndim <= axis < input.ndim:
        axes = [axis % input.ndim]
    else:
        return None
    if output is None:
        dtype = input.dtype
    elif isinstance(output, np.dtype) or (type(output) is type and output in _SCALARS):
        dtype = np.dtype(output)
        if dtype not in _FLOATS:
            return None
    else:
        return None
    return input, axes, dtype, filter_rule(mode, exact_edges), threads


def _common_filter(order, a, axes, dtype, rule, threads):
    """:func:`_filter_with` of the common call (:func:`_common`): degrees 0
    and 1 scipy's copy (converted), above them the engine's filter into a
    new array, straight."""
    if order < 2 or a.size == 0:
        return a.copy() if a.dtype is dtype else _copied(a, dtype, None)
    out = np.empty(a.shape, dtype)
    _ext.filter(a, out, axes, order, rule, 0.0, None, threads, False, "propagate", f32=False)
    return out


@fill
def spline_filter(input, order=3, output=np.float64, mode="mirror", *, tol=DEFAULT_TOL, threads=None, exact_edges=False,
                  nan_policy="propagate", compute="float64"):
    """Interpolation coefficients along every axis (``scipy.ndimage.spline_filter``).

    :func:`spline_filter1d` along each axis in turn: the coefficients of the
    tensor-product spline of degree ``order`` through the samples.

    Parameters
    ----------
    %(filter_input)s
    %(filter_order)s
    %(filter_output)s
    %(filter_mode)s
    %(filter_keywords)s

    Returns
    -------
    ndarray
        The coefficients: a new array, or ``output``.

    Raises
    ------
    %(raises)s

    Notes
    -----
    Method: :func:`spline_filter1d`'s recursions (Unser, Aldroubi and Eden
    1993) along every axis. Error: with ``tol`` it compounds over the ``d``
    axes to at most ``((A + b)**d - A**d) * max|input|`` (``A`` the
    amplification, ``b`` the per-axis bound): :func:`filter_bound`. Cost:
    O(poles) operations per sample and axis. Memory: the output (the input
    is read where it lies; a float32 output holds the float32 coefficients
    only, as scipy's) and work buffers of at most about 1 MiB a thread
    whatever the array's size (long lines are filtered in blocks of rows;
    scipy: one line buffer).

    Examples
    --------
    The B-splines sum to 1, so a constant is its own coefficients:

    >>> import numpy as np, splinelab
    >>> x = np.full((4, 5), 2.5)
    >>> bool(np.allclose(splinelab.spline_filter(x, order=5), x))
    True
    """
    if tol is DEFAULT_TOL:
        # The common call in one step (spline_filter1d's).
        values = _ext.filter_common(input, order, None, True, output, mode, threads, nan_policy, compute, exact_edges)
        if values is not None:
            return values
    common = _common(input, order, _EVERY, output, mode, tol, threads, exact_edges, nan_policy, compute)
    if common is not None:
        return _common_filter(order, *common)
    a = np.asarray(input)
    return _filter(a, list(range(a.ndim)), order, output, mode, tol, threads, exact_edges, nan_policy=nan_policy,
                   compute=compute)


@fill
def map_coordinates(
    input,
    coordinates,
    output=None,
    order=3,
    mode="constant",
    cval=0.0,
    prefilter=True,
    *,
    tol=DEFAULT_TOL,
    threads=None,
    exact_edges=False,
    derivative=None,
    nan_policy="propagate",
    compute="float64",
):
    """Values of the spline interpolant at coordinates (``scipy.ndimage.map_coordinates``).

    The spline of degree ``order`` through the samples of ``input``
    (extended beyond the grid by ``mode``), evaluated at each point, or with
    ``derivative`` one of its partial derivatives.

    Parameters
    ----------
    input : array_like
        The samples: bool, integer, float or complex (scipy's dtypes), any
        strides. Every input is computed in float64, as scipy computes it
        (complex: complex128, part by part). An array-like that is not in
        memory (anything with ``shape``, ``dtype``, ``ndim`` and basic-slice
        ``__getitem__``: zarr, h5py, dask) is read only where the points'
        windows need it (the local route: :doc:`/large_arrays`): each
        stored chunk they touch once where it exposes its chunk grid
        (``chunks``), else one box at a time; or whole, once, where the
        points cover it (reading it costs less than their boxes one by one).
    coordinates : array_like
        Shape ``(input.ndim, ...)``: one row per axis, as in scipy.
    %(interp_output)s
    %(interp_order)s
    mode : str, optional
        As scipy 1.17 computes them: 'constant' (the default, as in scipy)
        is the 'mirror' spline inside ``[0, n - 1]`` on every axis and
        ``cval`` at any point outside; 'mirror', 'reflect' ('grid-mirror')
        and 'grid-wrap' fold the point; 'nearest' and 'grid-constant'
        (degrees 2..5) pad the input with 12 edge samples / ``cval`` on
        every side, filter it with scipy's rule (:func:`spline_filter1d`)
        and evaluate at ``x + 12``, as scipy does — an approximation of the
        spline of the extended signal (off by about ``rho**(24 - k)`` of the
        data ``k <= 12`` samples outside, ``rho`` the largest pole: 2e-14
        for cubics, 2e-9 for quintics at the ends). ``exact_edges=True``,
        and every degree above 5, evaluate that spline exactly instead.
        'wrap' is scipy's: the 'mirror' spline at the point moved by whole
        periods ``n - 1`` into ``[0, n - 1]`` (the first and last samples
        overlap; 'grid-wrap' is the periodic spline, period ``n``).
    %(cval)s
    %(prefilter)s
    %(interp_engine)s
    derivative : sequence of int, optional
        ``(k_0, k_1, ...)``, one order per axis, each ``k_a <= order``: the
        partial derivative ``d^(k_0 + k_1 + ...) f / dx_0^k_0 dx_1^k_1 ...``
        of the same spline at the points instead of its values, from the
        B-spline derivative weights (exact rational recurrences, the
        engine's ``Interpolant::eval_derivative``); outside the grid the
        derivative of the extended spline (the folding's reflections change
        the sign of odd orders; 0 where 'constant' gives ``cval``). Tested
        against 5-point central differences of scipy's values
        (python/tests/test_gradient.py). splinelab's own keyword; see also
        :func:`spline_gradient`.
    %(interp_tail)s

    Returns
    -------
    ndarray
        The values, shape ``coordinates.shape[1:]``: a new array of
        ``output``'s dtype, or ``output``.

    Raises
    ------
    splinelab.errors.CoordinateShapeError
        ``coordinates`` without one row per input axis.
    %(raises)s

    Notes
    -----
    Method: the prefilter (:func:`spline_filter`, scipy's rule for the
    mode), then the B-spline weights of each point. With few points the
    local route is taken by itself (:doc:`/large_arrays`): only the
    samples within the certified half-width of the points' windows are
    read and prefiltered. Degree 0 picks the nearest sample (scipy's rule
    at half-integers). An input with an empty axis gives ``cval`` at every
    point in 'constant' / 'grid-constant' (all points lie outside), as
    scipy; other modes refuse it (scipy reads outside the array).

    Error: that of one rounding of the result in float64 beyond the
    prefilter's (``tol``: at most ``bound * max|input|`` more).

    Cost: the prefilter (O(poles) per sample and axis) once, then
    ``(order + 1)**ndim`` multiply-adds per point. Memory beside the input
    and the result, as scipy's or less: with the prefilter (``order >= 2``)
    one float64 array of coefficients, the input's shape grown by
    ``order // 2 + 2`` per side (scipy: a float64 copy of the
    coefficients); float64 and float32 input is read where it lies (other
    dtypes: a float32 or float64 copy first). Degrees 0 and 1 read the
    samples where they lie, as scipy does, where the points are few for
    the array (their samples cost less to read one by one than a copy;
    ``splinelab._local.in_place_pays``), else, as ``prefilter=False``
    above them, through a padded float64 copy of the input, which scipy
    does not hold. 'nearest' and 'grid-constant'
    (scipy's route): the input padded by 12 (a copy in its dtype, as
    scipy's) and one float64 coefficient array of that.
    ``compute="float32"``: float32 arrays instead. The prefilter's work
    buffers stay within about 1 MiB a thread (:func:`spline_filter`).

    Examples
    --------
    The cubic spline through ``k**3`` at a sample, and the same with the
    coefficients computed first:

    >>> import numpy as np, splinelab
    >>> v = splinelab.map_coordinates(np.array([0.0, 1, 8, 27, 64]), [[1.0, 2.5]], order=3)
    >>> bool(abs(v[0] - 1.0) < 1e-14)
    True
    >>> c = splinelab.spline_filter(np.array([0.0, 1, 8, 27, 64]), order=3)
    >>> w = splinelab.map_coordinates(c, [[1.0, 2.5]], order=3, prefilter=False)
    >>> bool(np.allclose(v, w, rtol=0, atol=1e-13))
    True

    A first derivative (``derivative``, splinelab's own) of ``i + 2 j``, far from the
    ends:

    >>> x = np.add.outer(np.arange(40.0), 2 * np.arange(40.0))
    >>> d = splinelab.map_coordinates(x, [[19.5], [20.25]], order=3, mode="mirror", derivative=(0, 1))
    >>> bool(abs(d[0] - 2.0) < 1e-8)
    True
    """
    if output is None and derivative is None and tol is DEFAULT_TOL and exact_edges is False and _local.ROUTE == "auto":
        # The common call in one step: the engine recognises it from the
        # arguments as given (exact types) and evaluates it, or says None.
        values = _ext.map_coordinates_common(
            input, coordinates, (order, mode, cval, prefilter, threads, nan_policy, compute))
        if values is not None:
            return values
    prefilter = _flag(prefilter, "prefilter")
    at = _coordinates(coordinates, np.ndim(input))
    shape = at.shape[1:]
    flat = np.ascontiguousarray(at.reshape(at.shape[0], -1))
    s = Settings.of(order, mode, cval, prefilter, tol, threads, exact_edges, nan_policy, compute)
    deriv = _derivative(derivative, at.shape[0])
    sign = _reflection_sign(flat, np.shape(input), s.mode, deriv) if deriv else None
    if deriv is None and type(input) is np.ndarray:
        values = _direct(input, _Points(flat), s, output)  # the common call, in one step
        if values is not None:
            return values.reshape(shape)
    if _local.is_array_like(input) and math.prod(input.shape) == 0:
        # Nothing to read: the in-memory rules, as scipy reads it (cval
        # under the constant modes; reproject passes empty dask blocks).
        input = np.empty(input.shape, np.dtype(input.dtype))
    if _local.is_array_like(input):
        # Not in memory (zarr, h5py, dask): read whole where that costs no
        # more than the windows' boxes (then the in-memory call's bits),
        # else only the windows' boxes.
        whole = _local.read_whole(_local.source(input), flat, s)
        if whole is None:
            return _map_array_like(input, flat, shape, output, s, deriv, sign)
        input = whole

    def evaluate(a, cv, work):
        values = _map_real(a, flat, s, cv, deriv, work)
        return values if sign is None else values * sign.astype(values.dtype)

    return _interpolate(input, output, shape, cval, evaluate, coordinates, compute=s.compute)


def _map_array_like(src, flat, shape, output, s, deriv, sign):
    """map_coordinates of an array-like that is not in memory, on the local
    route: the boxes the windows need fetched (:func:`splinelab._local.fetch`)
    and evaluated; the dtype rules of :func:`_interpolate` (real input)."""
    src = _local.source(src)
    dtype, target = _dt.output_dtype(output, src.dtype, _dt.default_output(src.dtype, False), False)
    _dt.check_output_shape(target, shape)
    work = np.dtype(np.float32 if _dt.real_dtype(dtype) == np.float32 else np.float64)
    values = _local.evaluate_array_like(src, flat, s, _cval(s.cval, False), deriv, work)
    if sign is not None:
        values = values * sign.astype(values.dtype)
    result = values.reshape(shape)
    result = result if result.dtype == dtype else _dt.store_rounded(result, dtype)
    return _dt.deliver(result, target, shape)


def _derivative(derivative, ndim):
    """``derivative``: None or one non-negative order per axis."""
    if derivative is None:
        return None
    orders = [_int(k, "derivative order") for k in np.atleast_1d(np.asarray(derivative, dtype=object))]
    if len(orders) != ndim or any(k < 0 for k in orders):
        raise ValueError(f"derivative must give one non-negative order per axis ({ndim}), got {derivative!r}")
    return orders if any(orders) else None


def _reflection_sign(flat, shape, mode, deriv):
    """+1 or -1 per point: the engine differentiates the spline at the
    folded point; where the fold reflects ('mirror', 'reflect' /
    'grid-mirror'), an odd derivative order changes sign."""
    sign = np.ones(flat.shape[1])
    for axis, (x, n, k) in enumerate(zip(flat, shape, deriv)):
        if k % 2 == 0 or n < 2:
            continue
        with np.errstate(invalid="ignore"):  # ±inf: the engine refuses the point
            if mode == "mirror":
                reflected = np.mod(x, 2.0 * (n - 1)) > n - 1
            elif mode in ("reflect", "grid-mirror"):
                reflected = np.mod(x + 0.5, 2.0 * n) > n
            else:
                continue
        sign[reflected] = -sign[reflected]
    return sign


@fill
def spline_gradient(
    input, coordinates, order=3, mode="constant", cval=0.0, prefilter=True, *, tol=DEFAULT_TOL, threads=None,
    exact_edges=False, nan_policy="propagate", compute="float64",
):
    """All first partial derivatives of :func:`map_coordinates`' interpolant at the points.

    Row ``a`` is the derivative along axis ``a``:
    ``map_coordinates(..., derivative=e_a)``. splinelab's own function
    (scipy has none).

    Parameters
    ----------
    %(interp_input)s
    coordinates : array_like
        Shape ``(input.ndim, ...)``: one row per axis, as in scipy.
    %(interp_order)s
    %(interp_mode)s
    %(cval)s
    %(prefilter)s
    %(interp_keywords)s

    Returns
    -------
    ndarray
        Shape ``(ndim, *coordinates.shape[1:])``; float64, or float32 for
        float32 input (computed in float64 and rounded once, or in float32
        with ``compute="float32"``); complex for complex input.

    Raises
    ------
    splinelab.errors.CoordinateShapeError
        ``coordinates`` without one row per input axis.
    %(raises)s

    Notes
    -----
    Method: the B-spline derivative weights of
    :func:`map_coordinates`' ``derivative``. Error and memory as
    :func:`map_coordinates`. Cost: ``ndim`` evaluations (and prefilters).

    Examples
    --------
    The gradient of ``i / 2 + 3 j``, far from the ends:

    >>> import numpy as np, splinelab
    >>> x = np.add.outer(0.5 * np.arange(40.0), 3 * np.arange(40.0))
    >>> g = splinelab.spline_gradient(x, [[19.5], [20.25]], order=3, mode="mirror")
    >>> bool(np.allclose(g[:, 0], [0.5, 3.0], rtol=0, atol=1e-8))
    True
    """
    a = np.asarray(input)
    out = np.float32 if a.dtype in (np.float32, np.complex64) else np.float64
    if a.dtype.kind == "c":
        out = np.complex64 if out == np.float32 else np.complex128
    rows = []
    for axis in range(a.ndim):
        unit = [0] * a.ndim
        unit[axis] = 1
        rows.append(map_coordinates(a, coordinates, output=out, order=order, mode=mode, cval=cval,
                                    prefilter=prefilter, tol=tol, threads=threads, exact_edges=exact_edges,
                                    derivative=unit, nan_policy=nan_policy, compute=compute))
    return np.stack(rows)


def _coordinates(coordinates, ndim):
    """scipy's coordinate array, ``(ndim, ...)``, as float64. Finiteness is
    the engine's check (on the pool, while it reads the points: a NaN or an
    infinity stays one through the folds and shifts made here first), so a
    non-finite coordinate is refused with ``ValueError("coordinate k is not
    finite")`` without a serial pass over the array here."""
    if type(coordinates) is np.ndarray and coordinates.dtype == np.float64:
        at = coordinates  # the common call: nothing to convert
    else:
        at = _real_array(coordinates, "coordinates").astype(np.float64, copy=False)
    if at.ndim < 1 or at.shape[0] != ndim:
        raise CoordinateShapeError(f"coordinates must have shape ({ndim}, ...), got {at.shape}")
    return at
