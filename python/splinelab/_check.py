"""`check`: your own numbers against certified references."""

from __future__ import annotations

import json
import os

import numpy as np

from . import _splinelab as _ext
from ._sspline import _family
from ._validate import _count, _degree_or_order, _mode, _opt_float, _real_array

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


def _out(out):
    return None if out is None else os.fspath(out)


def _check_prefilter(samples, coeffs, degree=None, order=None, mode="mirror", max_ulps=None, format=None, out=None):
    d = _degree_or_order(degree, order)
    user, fmt = _values(coeffs, format)
    return _ext.check_prefilter(
        _list(samples, "samples"), user, fmt, d, _mode(mode), _opt_float(max_ulps, "max_ulps"), _out(out)
    )


def _check_interp(
    samples, coordinates, values, degree=None, order=None, mode="mirror", cval=0.0, max_ulps=None, format=None,
    out=None,
):
    s = _real_array(samples, "samples")
    if s.ndim < 1:
        raise ValueError("samples must have at least one axis, got a 0-D array")
    c = np.asarray(_real_array(coordinates, "coordinates"), dtype=np.float64)
    if c.ndim == 1 and s.ndim == 1:
        c = c[None, :]
    if c.ndim != 2 or c.shape[0] != s.ndim:
        raise ValueError(f"coordinates must have shape ({s.ndim}, count) as in map_coordinates, got {c.shape}")
    user, fmt = _values(values, format)
    return _ext.check_interp(
        np.ascontiguousarray(s, dtype=np.float64).ravel().tolist(), list(s.shape),
        c.T.ravel().tolist(), user, fmt, _degree_or_order(degree, order), _mode(mode), _opt_float(cval, "cval"),
        _opt_float(max_ulps, "max_ulps"), _out(out),
    )


def _check_grid_spline(grid, samples, points, values, degree=3, max_ulps=None, format=None, out=None):
    axes = [_vector(g, f"grid[{a}]").astype(np.float64) for a, g in enumerate(grid)]
    s = np.asarray(_real_array(samples, "samples"), dtype=np.float64)
    if s.shape != tuple(len(g) for g in axes):
        raise ValueError(f"samples of shape {s.shape} do not match the grid {tuple(len(g) for g in axes)}")
    # Descending axes as scipy takes them: flipped with their samples.
    for a, g in enumerate(axes):
        if len(g) > 1 and g[0] > g[-1]:
            axes[a] = g[::-1].copy()
            s = np.flip(s, axis=a)
    p = np.asarray(_real_array(points, "points"), dtype=np.float64)
    if p.ndim == 1 and len(axes) == 1:
        p = p[:, None]
    if p.ndim != 2 or p.shape[1] != len(axes):
        raise ValueError(f"points must have shape (count, {len(axes)}) as RegularGridInterpolator's xi, got {p.shape}")
    user, fmt = _values(values, format)
    return _ext.check_grid_spline(
        [g.tolist() for g in axes], np.ascontiguousarray(s).ravel().tolist(), _count(degree, "degree"),
        np.ascontiguousarray(p).ravel().tolist(), user, fmt, _opt_float(max_ulps, "max_ulps"), _out(out),
    )


def _check_cond(nodes, values, basis="bernstein", norm="2", max_ulps=None, format=None, out=None):
    if isinstance(nodes, np.ndarray) and nodes.ndim == 1 or (len(nodes) > 0 and np.ndim(nodes[0]) == 0):
        sets = [_list(nodes, "nodes")]
    else:
        sets = [_list(n, "nodes") for n in nodes]
    user, fmt = _values(values, format)
    return _ext.check_cond(sets, str(basis), str(norm), user, fmt, _opt_float(max_ulps, "max_ulps"), _out(out))


def _check_coeffs(values, order=None, degree=None, tension=None, max_ulps=None, format=None, out=None):
    m = _family(degree, order) if tension is None else 4
    user, fmt = _values(values, format)
    t = None if tension is None else str(tension)
    return _ext.check_coeffs(user, fmt, m, t, _opt_float(max_ulps, "max_ulps"), _out(out))


def _check_bspline_eval(knots, coeffs, degree, x, values, extrapolate=True, max_ulps=None, format=None, out=None):
    user, fmt = _values(values, format)
    return _ext.check_bspline_eval(
        _list(knots, "knots"), _list(coeffs, "coeffs"), _count(degree, "degree"), _list(x, "x"),
        user, fmt, bool(extrapolate), _opt_float(max_ulps, "max_ulps"), _out(out),
    )


def _check_bezier_eval(coeffs, t, values, max_ulps=None, format=None, out=None):
    user, fmt = _values(values, format)
    return _ext.check_bezier_eval(
        _list(coeffs, "coeffs"), _list(t, "t"), user, fmt, _opt_float(max_ulps, "max_ulps"), _out(out)
    )


def _spline(s, what):
    try:
        t, c, k = s
    except (TypeError, ValueError):
        raise TypeError(f"{what} must be a (t, c, k) triple") from None
    return (_list(t, f"{what} t"), _list(c, f"{what} c"), _count(k, f"{what} k"))


def _check_knot_insertion(before, after, max_ulps=None, format=None, out=None):
    return _ext.check_knot_insertion(
        _spline(before, "before"), _spline(after, "after"), format or "f64", _opt_float(max_ulps, "max_ulps"),
        _out(out),
    )


_KINDS = {
    "prefilter": _check_prefilter,
    "coeffs": _check_coeffs,
    "bspline-eval": _check_bspline_eval,
    "bezier-eval": _check_bezier_eval,
    "knot-insertion": _check_knot_insertion,
    "interp": _check_interp,
    "cond": _check_cond,
    "grid-spline": _check_grid_spline,
}


def check(kind, **kwargs):
    """Checks your own numbers against certified references (``splinelab check KIND --json``).

    Parameters
    ----------
    kind : {'prefilter', 'coeffs', 'bspline-eval', 'bezier-eval', 'knot-insertion', 'interp', 'cond', 'grid-spline'}
        What the numbers are.
    **kwargs
        The keywords of ``kind`` (as the command's options):

        - 'prefilter': ``samples, coeffs, degree=3`` (or
          ``order=degree+1``), ``mode='mirror'`` (scipy's names; 'constant'
          and 'wrap' filter with the mirror rule, as spline_filter1d does);
          degree 1..15;
        - 'coeffs': ``values, order=/degree=/tension=``;
        - 'bspline-eval': ``knots, coeffs, degree, x, values,
          extrapolate=True``;
        - 'bezier-eval': ``coeffs, t, values``;
        - 'knot-insertion': ``before=(t, c, k), after=(t, c, k)``;
        - 'interp': ``samples`` (any number of dimensions), ``coordinates``
          (shape (ndim, count), as map_coordinates), ``values``,
          ``degree=3``, ``mode='mirror'`` (every map_coordinates mode:
          'constant' — the mirror spline inside [0, n - 1], ``cval``
          outside —, 'nearest', 'reflect', 'mirror', 'grid-wrap', 'wrap' —
          period n - 1 —, 'grid-constant'), ``cval=0.0``;
        - 'cond': ``nodes`` (one node set, or a list of sets), ``values``
          (one condition number per set), ``basis='bernstein'`` or
          'monomial', ``norm='2'`` or 'inf';
        - 'grid-spline': ``grid`` (one 1-D array of nodes per axis,
          ascending or descending), ``samples`` (their shape), ``points``
          (shape (count, ndim), as RegularGridInterpolator's ``xi``),
          ``values``, ``degree=3`` (odd: scipy's 'slinear' 1, 'cubic' 3,
          'quintic' 5): the exact not-a-knot tensor-product spline, solved
          and evaluated in MPFR; the verdict's bound is what a stable
          banded solve per axis would make from the grid's conditioning.

        Every kind takes ``max_ulps=`` (verdict 'fail' when an element
        exceeds it), ``format=`` ('f64'/'f32'; default: the values' dtype)
        and ``out=`` (a folder: the command line's ``--out`` page, SVG
        charts, ``reference.npy``/``error.npy``/``bound.npy`` and a
        ``summary.json`` whose ``figures`` ``splinelab compare`` reads; the
        folder is replaced).

    Returns
    -------
    dict
        The command line's ``--json``: ``kind``, ``n``, ``reference_bits``,
        ``worst``, ``regions``, ``digits_min``, ``failed``, ``verdict``,
        ``verdict_basis`` ('stable-bound', or 'max-ulps'/'finite-only' for
        a kind without a bound, with ``no_verdict_reason``),
        ``stable_bound`` (the bound and its source), ``over_bound``,
        ``worst_excess`` (``index``, ``excess`` = error / bound, ``error``,
        ``bound``) and ``digits_lost`` (log10 of the worst excess: the
        digits lost beyond what the conditioning explains), ...

    Raises
    ------
    ValueError
        An unknown ``kind``, arrays of mismatched lengths, a degree outside
        the kind's range.
    TypeError
        A keyword ``kind`` does not take, or a required one missing.

    See Also
    --------
    splinelab.testing.assert_check : For pytest: raises with the summary
        instead of returning it.

    Notes
    -----
    The references are computed in MPFR or exact rational arithmetic
    (``reference_bits``). The default verdict is 'fail' when any
    element's error exceeds ``bound_factor`` (8) times the error a
    backward-stable computation would make there from the problem's own
    conditioning.

    Examples
    --------
    >>> import numpy as np, splinelab
    >>> s = np.array([1.0, 2.0, 0.5, 3.0, 1.0, 0.0, 2.0, 1.0])
    >>> r = splinelab.check("prefilter", samples=s, coeffs=splinelab.spline_filter1d(s), max_ulps=16)
    >>> r["kind"], r["verdict"], r["degree"], r["verdict_basis"]
    ('prefilter', 'pass', 3, 'stable-bound')
    """
    return _run(kind, kwargs)[0]


def _run(kind, kwargs):
    """``check``'s dict and the command line's text summary of it."""
    if kind not in _KINDS:
        raise ValueError(f"unknown check kind {kind!r} (expected one of {', '.join(_KINDS)})")
    result, text = _KINDS[kind](**kwargs)
    return json.loads(result), text
