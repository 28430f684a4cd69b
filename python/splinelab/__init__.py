"""splinelab for Python: spline prefiltering and interpolation of any degree.

Drop-in for ``scipy.ndimage``'s spline functions, with the same argument
names and defaults where they overlap: ``spline_filter1d``,
``spline_filter`` and ``map_coordinates``. As in scipy, ``order`` is the
spline **degree** (scipy's ``order``; the papers' B-spline order is
``degree + 1``), here any of 0..199 where scipy stops at 5.

Extra keywords:

- ``tol=``: use the truncated prefilter whose half-width is *certified* for
  ``tol`` (each coefficient within ``tol * max|input|`` of the exact one per
  filtered axis; :func:`truncation_width` gives the width and bound);
- ``threads=``: threads for the parallel path (``None``: one per core).

Modes: scipy's names, computed as scipy 1.17 computes them (the filters
have scipy's three rules: mirror, half-sample reflect, periodic; see
:func:`spline_filter1d`); ``map_coordinates`` defaults to ``constant`` as
scipy and refuses scipy's ``wrap`` (use ``grid-wrap``). ``exact_edges=True``
gives the exact spline of the edge- or constant-extended signal for
``nearest`` / ``grid-constant``, which scipy approximates.

Data: float64 and float32 arrays (integer arrays are converted), any
strides. Functions release the GIL while computing. Bad arguments raise
``ValueError`` (bad values, with the Rust engine's message) or ``TypeError``
(wrong types).

>>> import numpy as np, splinelab
>>> c = splinelab.spline_filter1d(np.array([0.0, 1.0, 8.0, 27.0]), order=3)
>>> s = (c[:-2] + 4 * c[1:-1] + c[2:]) / 6  # the cubic B-spline at the knots
>>> bool(np.allclose(s, [1.0, 8.0]))
True
"""

from __future__ import annotations

import json
import numbers

import numpy as np

from . import _splinelab as _ext

__version__ = _ext.__version__

__all__ = [
    "spline_filter1d",
    "spline_filter",
    "map_coordinates",
    "truncation_width",
    "coefficients",
    "check",
    "filter_bound",
]

MAX_DEGREE = 199


def _int(value, what):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{what} must be an integer, got {type(value).__name__}")
    return int(value)


def _degree(order):
    d = _int(order, "order (the spline degree)")
    if not 0 <= d <= MAX_DEGREE:
        raise ValueError(f"order (the spline degree) {d} is outside 0..{MAX_DEGREE}")
    return d


def _opt_float(value, what):
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{what} must be a real number or None, got {type(value).__name__}")
    return float(value)


def _threads(threads):
    return None if threads is None else _int(threads, "threads")


def _mode(mode):
    if not isinstance(mode, str):
        raise TypeError(f"mode must be a string, got {type(mode).__name__}")
    return mode


# scipy.ndimage's spline_filter1d has three filters only (ni_splines.c): the
# mirror rule, the reflect (half-sample) rule and the periodic one; every
# mode name maps onto one of them. nearest and grid-constant are *not* the
# spline of the edge- or constant-extended signal there (map_coordinates
# approximates that by padding 12 samples first).
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


def _real_array(input, what="input"):
    a = np.asarray(input)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"{what} must be a real (float or integer) array, got dtype {a.dtype}")
    return a


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


def _family(degree, order):
    """The paper's B-spline order m from degree= or order= (m = degree + 1)."""
    if degree is not None and order is not None:
        raise ValueError("give degree= or order= (= degree + 1), not both")
    if order is not None:
        return _int(order, "order")
    return _int(3 if degree is None else degree, "degree") + 1


def truncation_width(degree=None, order=None, tension=None, *, tol, criterion="uniform"):
    """The smallest truncation half-width ``n`` meeting ``tol`` (``splinelab width --json``).

    Here ``order`` is the papers' B-spline order ``m = degree + 1`` (give
    one of ``degree`` and ``order``; default cubic, degree 3 — as
    everywhere in splinelab, degree 0..199 means scipy's ``order``).
    ``tension`` (a decimal or ``'p/q'`` string, exact) selects the cubic Beta2
    family. ``criterion``: 'uniform' (worst curve error for ``|P| <= 1``),
    'coeff' (``|c_n| < tol``, the paper's rule) or 'knot'.

    Returns a dict: ``n``, ``bound`` (guaranteed tail bound, rounded up),
    ``achieved``, ``criterion``, ``tol``, ``order``, ``tension``, ``family``,
    ``support_radius``, ``f64_saturation_n``.

    >>> import splinelab
    >>> w = splinelab.truncation_width(degree=3, tol=1e-10)
    >>> w['n'], w['bound'] < 1e-10
    (18, True)
    """
    m = _family(degree, order)
    t = None if tension is None else str(tension)
    tol = _opt_float(tol, "tol")
    n, achieved, bound, crit, saturation, half_support, m, tension, family = _ext.truncation_width(
        m, t, tol, str(criterion)
    )
    return {
        "order": m, "tension": tension, "family": family, "tol": tol, "criterion": crit, "n": n,
        "achieved": achieved, "bound": bound, "support_radius": n + half_support, "f64_saturation_n": saturation,
    }


def coefficients(degree=None, order=None, tension=None, *, count=10, bits=None):
    """The S-spline coefficients ``c_0 .. c_{count-1}`` (``splinelab coeffs``).

    ``order`` is the papers' ``m = degree + 1`` (default cubic). With
    ``bits=None``: a float64 array, each correctly rounded (partial
    fractions with >= 128 guard bits, rounded once). With ``bits=B``
    (16..2048): a list of decimal strings carrying ``B`` bits, computed at
    the next compiled MPFR precision >= ``B``.

    >>> import splinelab
    >>> c = splinelab.coefficients(degree=3, count=2)
    >>> float(c[0]) == 3 ** 0.5
    True
    >>> splinelab.coefficients(degree=3, count=1, bits=100)[0][:20]
    '1.732050807568877293'
    """
    m = _family(degree, order)
    t = None if tension is None else str(tension)
    count = _int(count, "count")
    if bits is None:
        return _ext.coefficients_f64(m, t, count)
    return json.loads(_ext.coefficients_decimal(m, t, count, _int(bits, "bits")))["c"]


def filter_bound(order, tol=None, ndim=1):
    """Certified bound of the prefilter for ``order`` (the degree) and ``tol``.

    Returns a dict: ``half_width`` (``None`` for the exact filter),
    ``bound`` (per-axis tail ``b``), ``amplification`` (``A = 1/|V(-1)|``:
    ``max|c| <= A max|s|``) and ``total``: ``(A + b)**ndim - A**ndim``, so
    that ``|truncated - exact| <= total * max|input|`` over ``ndim`` axes.

    >>> import splinelab
    >>> b = splinelab.filter_bound(3, 1e-10, ndim=2)
    >>> b['half_width'], round(b['amplification'], 12)
    (18, 3.0)
    """
    n, b, amp = _ext.filter_bound(_degree(order), _opt_float(tol, "tol"))
    d = _int(ndim, "ndim")
    return {"half_width": n, "bound": b, "amplification": amp, "total": (amp + b) ** d - amp**d}


def _vector(x, what):
    a = _real_array(x, what)
    if a.ndim != 1:
        raise ValueError(f"{what} must be 1-D, got shape {a.shape}")
    return a


def _values(values, format):
    v = _vector(values, "values")
    fmt = format or ("f32" if v.dtype == np.float32 else "f64")
    return v.astype(np.float64).tolist(), fmt


def _list(x, what):
    return _vector(x, what).astype(np.float64).tolist()


def _check_prefilter(samples, coeffs, degree=None, order=None, mode="mirror", max_ulps=None, format=None):
    d = _check_degree(degree, order)
    user, fmt = _values(coeffs, format)
    return _ext.check_prefilter(_list(samples, "samples"), user, fmt, d, _mode(mode), _opt_float(max_ulps, "max_ulps"))


def _check_degree(degree, order):
    if degree is not None and order is not None:
        raise ValueError("give degree= or order= (= degree + 1), not both")
    return _int(order, "order") - 1 if order is not None else _int(3 if degree is None else degree, "degree")


def _check_interp(
    samples, coordinates, values, degree=None, order=None, mode="mirror", cval=0.0, max_ulps=None, format=None
):
    s = _real_array(samples, "samples")
    if s.ndim not in (1, 2):
        raise ValueError(f"samples must be 1-D or 2-D, got {s.ndim}-D")
    c = np.asarray(_real_array(coordinates, "coordinates"), dtype=np.float64)
    if c.ndim == 1 and s.ndim == 1:
        c = c[None, :]
    if c.ndim != 2 or c.shape[0] != s.ndim:
        raise ValueError(f"coordinates must have shape ({s.ndim}, count) as in map_coordinates, got {c.shape}")
    user, fmt = _values(values, format)
    return _ext.check_interp(
        np.ascontiguousarray(s, dtype=np.float64).ravel().tolist(), list(s.shape),
        c.T.ravel().tolist(), user, fmt, _check_degree(degree, order), _mode(mode), _opt_float(cval, "cval"),
        _opt_float(max_ulps, "max_ulps"),
    )


def _check_cond(nodes, values, basis="bernstein", norm="2", max_ulps=None, format=None):
    if isinstance(nodes, np.ndarray) and nodes.ndim == 1 or (len(nodes) > 0 and np.ndim(nodes[0]) == 0):
        sets = [_list(nodes, "nodes")]
    else:
        sets = [_list(n, "nodes") for n in nodes]
    user, fmt = _values(values, format)
    return _ext.check_cond(sets, str(basis), str(norm), user, fmt, _opt_float(max_ulps, "max_ulps"))


def _check_coeffs(values, order=None, degree=None, tension=None, max_ulps=None, format=None):
    m = _family(degree, order) if tension is None else 4
    user, fmt = _values(values, format)
    t = None if tension is None else str(tension)
    return _ext.check_coeffs(user, fmt, m, t, _opt_float(max_ulps, "max_ulps"))


def _check_bspline_eval(knots, coeffs, degree, x, values, extrapolate=True, max_ulps=None, format=None):
    user, fmt = _values(values, format)
    return _ext.check_bspline_eval(
        _list(knots, "knots"), _list(coeffs, "coeffs"), _int(degree, "degree"), _list(x, "x"),
        user, fmt, bool(extrapolate), _opt_float(max_ulps, "max_ulps"),
    )


def _check_bezier_eval(coeffs, t, values, max_ulps=None, format=None):
    user, fmt = _values(values, format)
    return _ext.check_bezier_eval(_list(coeffs, "coeffs"), _list(t, "t"), user, fmt, _opt_float(max_ulps, "max_ulps"))


def _spline(s, what):
    try:
        t, c, k = s
    except (TypeError, ValueError):
        raise TypeError(f"{what} must be a (t, c, k) triple") from None
    return (_list(t, f"{what} t"), _list(c, f"{what} c"), _int(k, f"{what} k"))


def _check_knot_insertion(before, after, max_ulps=None, format=None):
    return _ext.check_knot_insertion(
        _spline(before, "before"), _spline(after, "after"), format or "f64", _opt_float(max_ulps, "max_ulps")
    )


_KINDS = {
    "prefilter": _check_prefilter,
    "coeffs": _check_coeffs,
    "bspline-eval": _check_bspline_eval,
    "bezier-eval": _check_bezier_eval,
    "knot-insertion": _check_knot_insertion,
    "interp": _check_interp,
    "cond": _check_cond,
}


def check(kind, **kwargs):
    """Checks your own numbers against certified references (``splinelab check KIND --json``).

    Returns the same dict as the command line's ``--json`` (``kind``, ``n``,
    ``reference_bits``, ``worst``, ``regions``, ``digits_min``, ``failed``,
    ``verdict``, ...). Keywords per kind (as the command's options):

    - 'prefilter': ``samples, coeffs, degree=3`` (or ``order=degree+1``),
      ``mode='mirror'`` ('mirror', 'reflect', 'grid-wrap'); degree 1..15;
    - 'coeffs': ``values, order=/degree=/tension=``;
    - 'bspline-eval': ``knots, coeffs, degree, x, values, extrapolate=True``;
    - 'bezier-eval': ``coeffs, t, values``;
    - 'knot-insertion': ``before=(t, c, k), after=(t, c, k)``;
    - 'interp': ``samples`` (1-D or 2-D), ``coordinates`` (shape (ndim, count),
      as map_coordinates), ``values``, ``degree=3``, ``mode='mirror'``,
      ``cval=0.0`` (for 'grid-constant'; scipy's 'constant' and 'wrap' are
      not checked);
    - 'cond': ``nodes`` (one node set, or a list of sets), ``values`` (one
      condition number per set), ``basis='bernstein'`` or 'monomial',
      ``norm='2'`` or 'inf'.

    Every kind takes ``max_ulps=`` (verdict 'fail' when an element exceeds
    it) and ``format=`` ('f64'/'f32'; default: the values' dtype).

    >>> import numpy as np, splinelab
    >>> s = np.array([1.0, 2.0, 0.5, 3.0, 1.0, 0.0, 2.0, 1.0])
    >>> r = splinelab.check("prefilter", samples=s, coeffs=splinelab.spline_filter1d(s), max_ulps=16)
    >>> r["kind"], r["verdict"], r["degree"]
    ('prefilter', 'pass', 3)
    """
    if kind not in _KINDS:
        raise ValueError(f"unknown check kind {kind!r} (expected one of {', '.join(_KINDS)})")
    return json.loads(_KINDS[kind](**kwargs))
