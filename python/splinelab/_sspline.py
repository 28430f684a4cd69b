"""The S-spline functions of seed 000: truncation widths, coefficients, the filter bound."""

from __future__ import annotations

import json

from . import _splinelab as _ext
from ._validate import _count, _degree, _degree_or_order, _int, _opt_float

# numpy's largest number of dimensions (NPY_MAXDIMS in numpy 2).
MAX_NDIM = 64


def _family(degree, order):
    """The paper's B-spline order m from degree= or order= (m = degree + 1)."""
    return _degree_or_order(degree, order) + 1


def truncation_width(degree=None, order=None, tension=None, *, tol, criterion="uniform", budget=60.0):
    """The smallest truncation half-width ``n`` meeting ``tol`` (``splinelab width --json``).

    Parameters
    ----------
    degree : int, optional
        The spline degree (0..199, scipy's ``order``). Give one of ``degree``
        and ``order``; default cubic, degree 3.
    order : int, optional
        Here the papers' B-spline order ``m = degree + 1``.
    tension : str, optional
        A decimal or ``'p/q'`` string (exact): selects the cubic Beta2
        family.
    tol : float
        The tolerance, in (0, 1). Keyword only.
    criterion : {'uniform', 'coeff', 'knot'}, optional
        'uniform' (default: worst curve error for ``|P| <= 1``), 'coeff'
        (``|c_n| < tol``, the paper's rule) or 'knot'.
    budget : float, optional
        Seconds, as the command line's ``--budget`` (default 60).

    Returns
    -------
    dict
        ``n``, ``bound`` (guaranteed tail bound, rounded up), ``achieved``,
        ``criterion``, ``tol``, ``order``, ``tension``, ``family``,
        ``support_radius``, ``f64_saturation_n``.

    Raises
    ------
    ValueError
        Both ``degree`` and ``order``; ``tol`` outside (0, 1); an unknown
        ``criterion``; a search estimated longer than ``budget`` (the message
        gives the estimate).

    Notes
    -----
    Method: a search over ``n`` of the certified tail bound of the S-spline
    (sampling spline) coefficients of Kuriyama, Kawai and Omura (the
    project's seed 000), in MPFR. Cost: the search's cost is estimated first
    (``splinelab_verify::cost::width_search``) and a request estimated
    longer than ``budget`` is refused before any work (degree 199 at
    ``tol=1e-10`` takes minutes).

    Examples
    --------
    >>> import splinelab
    >>> w = splinelab.truncation_width(degree=3, tol=1e-10)
    >>> w['n'], w['bound'] < 1e-10
    (18, True)
    """
    m = _family(degree, order)
    t = None if tension is None else str(tension)
    tol = _opt_float(tol, "tol")
    budget = _opt_float(budget, "budget")
    n, achieved, bound, crit, saturation, half_support, m, tension, family = _ext.truncation_width(
        m, t, tol, str(criterion), budget
    )
    return {
        "order": m, "tension": tension, "family": family, "tol": tol, "criterion": crit, "n": n,
        "achieved": achieved, "bound": bound, "support_radius": n + half_support, "f64_saturation_n": saturation,
    }


def coefficients(degree=None, order=None, tension=None, *, count=10, bits=None):
    """The S-spline coefficients ``c_0, ..., c_{count-1}`` (``splinelab coeffs``).

    Parameters
    ----------
    degree : int, optional
        The spline degree (default cubic).
    order : int, optional
        The papers' ``m = degree + 1`` (give one of ``degree`` and ``order``).
    tension : str, optional
        A decimal or ``'p/q'`` string: the cubic Beta2 family.
    count : int, optional
        How many coefficients (default 10). Keyword only.
    bits : int, optional
        None (default): float64. ``B`` (16..2048): decimal strings carrying
        ``B`` bits. Keyword only.

    Returns
    -------
    ndarray or list of str
        With ``bits=None`` a float64 array, each correctly rounded (partial
        fractions with >= 128 guard bits, rounded once). With ``bits=B`` a
        list of decimal strings carrying ``B`` bits, computed at the next
        compiled MPFR precision >= ``B``.

    Raises
    ------
    ValueError
        Both ``degree`` and ``order``, or ``bits`` outside 16..2048.

    Examples
    --------
    >>> import splinelab
    >>> c = splinelab.coefficients(degree=3, count=2)
    >>> float(c[0]) == 3 ** 0.5
    True
    >>> splinelab.coefficients(degree=3, count=1, bits=100)[0][:20]
    '1.732050807568877293'
    """
    m = _family(degree, order)
    t = None if tension is None else str(tension)
    count = _count(count, "count")
    if bits is None:
        return _ext.coefficients_f64(m, t, count)
    return json.loads(_ext.coefficients_decimal(m, t, count, _count(bits, "bits")))["c"]


def filter_bound(order, tol=None, ndim=1):
    """Certified bound of the prefilter for ``order`` (the degree) and ``tol``.

    Parameters
    ----------
    order : int
        The spline degree, 0..199.
    tol : float, optional
        The truncated prefilter's tolerance; None (default) for the exact
        filter.
    ndim : int, optional
        The number of filtered axes, 1..64 (default 1).

    Returns
    -------
    dict
        ``half_width`` (None for the exact filter), ``bound`` (per-axis tail
        ``b``), ``amplification`` (``A = 1/|V(-1)|``: ``max|c| <= A
        max|s|``) and ``total``: ``(A + b)**ndim - A**ndim``, so that
        ``|truncated - exact| <= total * max|input|`` over ``ndim`` axes.

    Raises
    ------
    splinelab.errors.OrderError
        ``order`` outside 0..199.
    ValueError
        ``tol`` outside (0, 1), or ``ndim`` outside 1..64.

    Examples
    --------
    >>> import splinelab
    >>> b = splinelab.filter_bound(3, 1e-10, ndim=2)
    >>> b['half_width'], round(b['amplification'], 12)
    (18, 3.0)
    """
    n, b, amp = _ext.filter_bound(_degree(order), _opt_float(tol, "tol"))
    d = _int(ndim, "ndim", 1, MAX_NDIM)
    return {"half_width": n, "bound": b, "amplification": amp, "total": (amp + b) ** d - amp**d}


def nan_reach(order, tol=1e-12):
    """How many samples along each axis a missing sample reaches under ``nan_policy='local'``.

    For the spline of degree ``order`` and the prefilter's tolerance
    ``tol``: ``n + order // 2 + 1``, with ``n`` the half-width certified for
    ``tol`` (:func:`filter_bound`'s ``half_width``, ``Σ_{|j|>n}|c_j| <
    tol``; 0 for degrees 0 and 1, which have no prefilter) and
    ``order // 2 + 1`` the spline's own window (an output at ``x`` reads the
    ``order + 1`` coefficients within ``(order + 1) / 2``).

    Parameters
    ----------
    order : int
        The spline degree, 0..199.
    tol : float, optional
        The prefilter's tolerance, in (0, 1). Default 1e-12.

    Returns
    -------
    int
        The reach, in samples.

    Raises
    ------
    splinelab.errors.OrderError
        ``order`` outside 0..199.
    ValueError
        ``tol`` outside (0, 1).
    TypeError
        ``tol`` not a real number (None included).

    Notes
    -----
    A coefficient is NaN when a missing (NaN, ±inf) sample lies within
    ``n`` of it on every axis (folded by the mode), so an output at ``x``
    can be NaN only where ``|x_a - j_a| <= nan_reach`` on every axis ``a``
    for a missing sample ``j``; the dask functions overlap their chunks by
    at least this. Elsewhere the output is within ``((A + b)**d - (A -
    b)**d) * max|finite input|`` (``A``, ``b``: :func:`filter_bound`'s
    ``amplification`` and ``bound``; ``d`` axes) of the exact spline of the
    input with its missing samples filled by any values of magnitude at
    most ``max|finite input|``. Cost: one certified width search (MPFR,
    cached by the filters).

    Examples
    --------
    >>> import splinelab
    >>> splinelab.nan_reach(3, 1e-12), splinelab.nan_reach(1)
    (24, 1)
    """
    t = _opt_float(tol, "tol")
    if t is None:  # no tolerance, no certified width: name the argument
        raise TypeError("tol must be a real number in (0, 1), got None")
    return _ext.nan_reach(_degree(order), t)
