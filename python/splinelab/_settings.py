"""One interpolation call, described once (issue 50): the settings every
layer takes (the drop-in's functions, the evaluation engine, the local
route, the dask wrappers), validated once into an immutable object, as the
engine's ``Options`` is in Rust. ``tol=None`` is decided here alone
(:func:`splinelab._validate._tol_for`: the default resolved for
``nan_policy``); what it means on each route is the engine's (the exact
filter on the global route, ``u·A/4`` on the local one). ``cval`` is kept
as given: whether it must be real or may be complex depends on the input,
which the dtype rules check (:func:`splinelab._engine._interpolate`)."""

from __future__ import annotations

from typing import NamedTuple

from . import _dtypes as _dt
from ._modes import SCIPY_FILTER_RULE, filter_rule, interp_mode
from ._validate import (DEFAULT_TOL, MAX_DEGREE, MAX_THREADS, _degree, _flag, _nan_policy, _opt_float, _threads,
                        _tol_for)


class Settings(NamedTuple):
    """The settings of one interpolation call (a named tuple: immutable,
    and made in a quarter of a frozen dataclass's time, which a small call
    notices).

    ``degree`` (scipy's ``order``), ``mode`` (scipy's name), ``cval`` (as
    given), ``prefilter``, ``tol`` (resolved: None is the exact filter),
    ``nan_policy``, ``threads`` (None: the default pool), ``exact_edges``,
    ``compute`` ('float64' or 'float32')."""

    degree: int
    mode: str
    cval: object
    prefilter: bool
    tol: float | None
    nan_policy: str
    threads: int | None
    exact_edges: bool
    compute: str

    @classmethod
    def of(cls, order, mode, cval, prefilter, tol, threads, exact_edges, nan_policy="propagate",
           compute="float64"):
        """The arguments checked in the order the functions have always
        checked them (degree, mode, prefilter, nan_policy, tol, threads,
        compute: the same exception at the same point of the call)."""
        if _defaults(order, mode, prefilter, tol, threads, nan_policy, compute):
            # The common call: nothing the checks below would change.
            return cls(order, mode, cval, prefilter, None, "propagate", threads, bool(exact_edges), "float64")
        d = _degree(order)
        mode = interp_mode(mode)
        prefilter = _flag(prefilter, "prefilter")
        nan_policy = _nan_policy(nan_policy)
        tol = _tol_for(tol, nan_policy, d if prefilter else 0)
        return cls(d, mode, cval, prefilter, tol, nan_policy, _threads(threads), bool(exact_edges),
                   _dt.compute_name(compute))

    @classmethod
    def interpolant(cls, order, mode, cval, tol, nan_policy, threads):
        """The settings of :class:`splinelab.Interpolant`, checked in its
        order (degree, mode, cval, nan_policy, tol, threads): always
        prefiltered, ``cval`` a float, ``tol`` as given (None: the local
        route's default, certified below the global route's rounding)."""
        d = _degree(order)
        mode = interp_mode(mode)
        cval = _opt_float(cval, "cval")
        nan_policy = _nan_policy(nan_policy)
        tol = _opt_float(tol, "tol")
        return cls(d, mode, cval, True, tol, nan_policy, _threads(threads), False, "float64")

    @classmethod
    def for_filter(cls, order, mode, tol, threads, exact_edges, nan_policy="propagate", compute="float64"):
        """The settings of spline_filter(1d): checked in the order the
        filters have always checked them (degree, mode, nan_policy, tol,
        threads; ``compute`` before the input, by the caller); the
        prefilter on, ``cval`` 0."""
        if _defaults(order, mode, True, tol, threads, nan_policy, compute):
            return cls(order, mode, 0.0, True, None, "propagate", threads, bool(exact_edges), "float64")
        d = _degree(order)
        mode = interp_mode(mode)
        nan_policy = _nan_policy(nan_policy)
        tol = _tol_for(tol, nan_policy, d)
        return cls(d, mode, 0.0, True, tol, nan_policy, _threads(threads), bool(exact_edges),
                   _dt.compute_name(compute))

    def filter_rule(self):
        """The engine's filter for this mode (:func:`splinelab._modes.filter_rule`)."""
        return filter_rule(self.mode, self.exact_edges)


def _defaults(order, mode, prefilter, tol, threads, nan_policy, compute):
    """Whether the arguments are the common call's, which need no check: an
    int degree in range, a known mode, a bool prefilter and every engine
    keyword at its default but ``threads`` (None or an int in range): what
    the checks would return unchanged (tol's default resolves to None
    under 'propagate'). Anything else takes the checks, so bad input is
    refused where it always was."""
    return (type(order) is int and 0 <= order <= MAX_DEGREE and type(mode) is str and mode in SCIPY_FILTER_RULE
            and (prefilter is True or prefilter is False) and tol is DEFAULT_TOL and _plain_threads(threads)
            and type(nan_policy) is str and nan_policy == "propagate" and type(compute) is str
            and compute == "float64")


def _plain_threads(threads):
    """Whether ``threads`` is one :func:`splinelab._validate._threads`
    returns as it is: None or an int in ``1..MAX_THREADS``."""
    return threads is None or (type(threads) is int and 1 <= threads <= MAX_THREADS)
