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

from dataclasses import dataclass

from . import _dtypes as _dt
from ._modes import interp_mode
from ._validate import _degree, _flag, _nan_policy, _opt_float, _threads, _tol_for


@dataclass(frozen=True, slots=True)
class Settings:
    """The settings of one interpolation call.

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
