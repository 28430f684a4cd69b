"""The scipy.ndimage drop-in: spline_filter1d, spline_filter, map_coordinates."""

from __future__ import annotations

import numpy as np

from . import _splinelab as _ext
from ._validate import _degree, _int, _mode, _opt_float, _real_array, _threads

_SCIPY_FILTER_RULE = {
    "mirror": "mirror",
    "constant": "mirror",
    "grid-constant": "mirror",
    "wrap": "mirror",
    "reflect": "reflect",
    "grid-mirror": "reflect",
    "nearest": "reflect",
    "grid-wrap": "grid-wrap",
}
_EXACT_EDGES = ("nearest", "grid-constant")
_MODES = "mirror, reflect, grid-mirror, grid-wrap, wrap, nearest, grid-constant, constant"


def _filter_mode(mode, exact_edges):
    """The engine's filter for scipy's `mode` (its rule), or with
    `exact_edges` the exact extension for nearest / grid-constant (cval 0)."""
    mode = _mode(mode)
    if mode not in _SCIPY_FILTER_RULE:
        raise ValueError(f"unknown mode {mode!r}: expected one of {_MODES}")
    if exact_edges and mode in _EXACT_EDGES:
        return mode
    return _SCIPY_FILTER_RULE[mode]


def _output_dtype(output, default):
    """The result dtype and the array to write into (scipy's `output`)."""
    target = None
    if isinstance(output, np.ndarray):
        target, dtype = output, output.dtype
    else:
        try:
            dtype = np.dtype(default if output is None else output)
        except TypeError as e:
            raise TypeError(f"output must be a dtype or an array: {e}") from None
    if dtype not in (np.dtype(np.float64), np.dtype(np.float32)):
        raise TypeError(f"output dtype must be float64 or float32, got {dtype}")
    return dtype, target


def _deliver(result, target, shape):
    if target is None:
        return result
    if target.shape != tuple(shape):
        raise ValueError(f"output has shape {target.shape}, expected {tuple(shape)}")
    target[...] = result
    return target


def _same_layout(a, b):
    """Whether `a` and `b` are the same elements in the same places."""
    ia, ib = a.__array_interface__, b.__array_interface__
    return ia["data"][0] == ib["data"][0] and a.strides == b.strides and a.shape == b.shape


def _filter(input, axes, order, output, mode, tol, threads, exact_edges=False):
    a = _real_array(input)
    dtype, target = _output_dtype(output, np.float64)
    if target is not None and target.shape != a.shape:
        raise ValueError(f"output has shape {target.shape}, expected {a.shape}")
    mode = _filter_mode(mode, bool(exact_edges))
    args = (axes, _degree(order), mode, 0.0, _opt_float(tol, "tol"), _threads(threads))
    # The result is written straight into `output` when it is C-ordered and
    # writeable, else into a new C-ordered array (numpy's allocator, which
    # asks for huge pages); the engine copies the input into it and filters
    # it in place. A conversion or an overlap with `output` goes through
    # numpy's copy into it instead (still one copy).
    direct = target is not None and target.flags.c_contiguous and target.flags.writeable
    out = target if direct else np.empty(a.shape, dtype)
    src = a
    if a.dtype != dtype or np.may_share_memory(a, out):
        if not _same_layout(a, out):
            np.copyto(out, a, casting="unsafe")
        src = None
    run = _ext.filter_f64 if dtype == np.float64 else _ext.filter_f32
    run(src, out, *args)
    if target is None or direct:
        return out
    target[...] = out
    return target


def _axis(axis, ndim):
    axis = _int(axis, "axis")
    if not -ndim <= axis < ndim:
        raise np.exceptions.AxisError(axis, ndim)
    return axis % ndim


def spline_filter1d(
    input, order=3, axis=-1, output=np.float64, mode="mirror", *, tol=None, threads=None, exact_edges=False
):
    """Interpolation coefficients along one axis (``scipy.ndimage.spline_filter1d``).

    ``order`` is the spline **degree**, 0..199 (scipy: 2..5; degrees 0 and 1
    return the input, as in scipy). The coefficients ``c`` satisfy
    ``sum_i c_i B(j - i) = input_j`` at every sample ``j``, the samples
    extended beyond the ends by ``mode``.

    Parameters
    ----------
    input : array_like, float64/float32/integer, any strides and shape.
        It is read once, strided (and converted when its dtype is not
        ``output``'s), into the C-ordered result, which is then filtered in
        place: one copy, no other.
    order : int, the degree.
    axis : int, the axis to filter (negative counts from the end).
    output : float64 (default) or float32 dtype, or an array to write into
        (written directly when C-contiguous, else through a temporary;
        ``output=input`` filters in place).
        float32 output is *computed* in float32 (scipy computes in float64
        and rounds); relative error about ``amplification * 6e-8``.
    mode : scipy's names and scipy's filters: 'mirror', 'constant',
        'grid-constant' and 'wrap' filter with the mirror rule; 'reflect',
        'grid-mirror' and 'nearest' with the half-sample (reflect) rule;
        'grid-wrap' is periodic (what scipy 1.17 computes, for every degree).
    exact_edges : bool, default False. True: 'nearest' and 'grid-constant'
        give the exact coefficients of the signal extended by its end
        samples / by zeros (scipy has no such filter; its map_coordinates
        approximates them by padding 12 samples).
    tol : None (exact recursive filter) or float in (0, 1): the truncated
        convolution of the certified width; ``|result - exact| <= bound *
        max|input|`` with ``bound = truncation_width(degree=order, tol=tol)['bound'] < tol``.
    threads : None (one per core) or the number of threads.

    Returns the coefficients (a new array, or ``output``).
    Formula: exact causal/anti-causal recursions per pole (Unser, Aldroubi
    and Eden 1993), poles rounded once from MPFR; cost O(poles) per sample.

    >>> import numpy as np, splinelab
    >>> c = splinelab.spline_filter1d(np.eye(3), order=3, axis=0)
    >>> bool(np.allclose((4 * c[0] + 2 * c[1]) / 6, [1, 0, 0]))
    True
    """
    a = np.asarray(input)
    return _filter(a, [_axis(axis, a.ndim)], order, output, mode, tol, threads, exact_edges)


def spline_filter(input, order=3, output=np.float64, mode="mirror", *, tol=None, threads=None, exact_edges=False):
    """Interpolation coefficients along every axis (``scipy.ndimage.spline_filter``).

    ``order`` is the spline **degree**, 0..199 (scipy: 2..5). Other
    arguments as :func:`spline_filter1d`. With ``tol`` the error compounds
    over the ``d`` axes to at most ``((A + b)**d - A**d) * max|input|``
    (``A`` the amplification, ``b`` the per-axis bound): :func:`filter_bound`.

    >>> import numpy as np, splinelab
    >>> x = np.full((4, 5), 2.5)  # the B-splines sum to 1: constants are kept
    >>> bool(np.allclose(splinelab.spline_filter(x, order=5), x))
    True
    """
    a = np.asarray(input)
    return _filter(a, list(range(a.ndim)), order, output, mode, tol, threads, exact_edges)


def map_coordinates(
    input,
    coordinates,
    output=None,
    order=3,
    mode="constant",
    cval=0.0,
    prefilter=True,
    *,
    tol=None,
    threads=None,
    exact_edges=False,
):
    """Values of the spline interpolant at coordinates (``scipy.ndimage.map_coordinates``).

    ``order`` is the spline **degree**, 0..199 (scipy: 0..5). Degree 0 picks
    the nearest sample (scipy's rule at half-integers) and degree 1 is
    multilinear, both without a prefilter, as in scipy. ``coordinates`` has
    shape ``(input.ndim, ...)``: one row per axis, as in scipy; the result
    has shape ``coordinates.shape[1:]``. ``prefilter=False``: ``input``
    already holds the coefficients (e.g. from ``spline_filter`` with the
    same mode); they are extended beyond the grid by ``mode`` (``cval`` for
    'grid-constant') and evaluated as given, as scipy does (``tol`` does not
    apply).

    Modes, as scipy 1.17 computes them: 'constant' (the default, as in
    scipy) is the 'mirror' spline inside ``[0, n - 1]`` on every axis and
    ``cval`` at any point outside; 'mirror', 'reflect' ('grid-mirror') and
    'grid-wrap' fold the point; 'nearest' and 'grid-constant' (degrees 2..5)
    pad the input with 12 edge samples / ``cval`` on every side, filter it
    with scipy's rule (:func:`spline_filter1d`) and evaluate at ``x + 12``,
    as scipy does — an approximation of the spline of the extended signal
    (off by about ``rho**(24 - k)`` of the data ``k <= 12`` samples outside,
    ``rho`` the largest pole: 2e-14 for cubics, 2e-9 for quintics at the
    ends). ``exact_edges=True``, and every degree above 5, evaluate that
    spline exactly instead. scipy's 'wrap' (period ``n - 1``, the first and
    last samples overlap) is not offered: use 'grid-wrap' (period ``n``).
    float32 input is computed in float32 unless ``output`` says float64.
    Cost: the prefilter (O(poles) per sample and axis) once, then
    ``(order + 1)**ndim`` multiply-adds per point.

    >>> import numpy as np, splinelab
    >>> v = splinelab.map_coordinates(np.array([0.0, 1, 8, 27, 64]), [[1.0, 2.5]], order=3)
    >>> bool(abs(v[0] - 1.0) < 1e-14)
    True
    >>> c = splinelab.spline_filter(np.array([0.0, 1, 8, 27, 64]), order=3)
    >>> w = splinelab.map_coordinates(c, [[1.0, 2.5]], order=3, prefilter=False)
    >>> bool(np.allclose(v, w, rtol=0, atol=1e-13))
    True
    """
    if not isinstance(prefilter, (bool, np.bool_)):
        raise TypeError(f"prefilter must be True or False, got {type(prefilter).__name__}")
    a = _real_array(input)
    default = a.dtype if a.dtype in (np.float32, np.float64) else np.float64
    dtype, target = _output_dtype(output, default)
    a = a.astype(dtype, copy=False)
    at = _real_array(coordinates, "coordinates").astype(np.float64, copy=False)
    if at.ndim < 1 or at.shape[0] != a.ndim:
        raise ValueError(f"coordinates must have shape ({a.ndim}, ...), got {at.shape}")
    flat = np.ascontiguousarray(at.reshape(a.ndim, -1))
    if not np.isfinite(flat).all():
        raise ValueError("coordinates must be finite")
    run = _ext.map_coordinates_f64 if dtype == np.float64 else _ext.map_coordinates_f32
    cv = _opt_float(cval, "cval")
    d, mode, tol, threads = _degree(order), _mode(mode), _opt_float(tol, "tol"), _threads(threads)
    if mode == "wrap":
        raise ValueError(
            "mode 'wrap' (scipy's: period n - 1, the first and last samples overlap) is not offered: "
            "use 'grid-wrap' (period n)"
        )
    if mode not in _SCIPY_FILTER_RULE:
        raise ValueError(f"unknown mode {mode!r}: expected one of {_MODES}")
    if prefilter and 1 < d <= 5 and mode in _EXACT_EDGES and not exact_edges:
        # scipy's route (_prepad_for_spline_filter): pad 12, filter with
        # its rule, evaluate the coefficients at x + 12 (rounded as scipy).
        pad = 12
        kind = {"mode": "edge"} if mode == "nearest" else {"mode": "constant", "constant_values": cv}
        coeffs = _filter(np.pad(a, pad, **kind), list(range(a.ndim)), d, dtype, mode, tol, threads)
        values = run(coeffs, flat + pad, d, mode, cv, None, False, threads)
    else:
        engine_mode = "mirror" if mode == "constant" else mode
        values = run(a, flat, d, engine_mode, cv, tol, bool(prefilter), threads)
    if mode == "constant":
        # scipy: no interpolation beyond the edges.
        limit = np.array(a.shape, dtype=np.float64)[:, None] - 1.0
        values = np.where(((flat < 0) | (flat > limit)).any(axis=0), np.asarray(cv, values.dtype), values)
    return _deliver(values.reshape(at.shape[1:]), target, at.shape[1:])
