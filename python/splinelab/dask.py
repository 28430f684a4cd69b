"""Certified chunked prefiltering of dask arrays.

``spline_filter`` and ``spline_filter1d`` filter each chunk with the
truncated prefilter of half-width ``n`` certified for ``tol``, through
``dask.array.map_overlap`` with an overlap depth of ``n`` plus the degree's
support half-width ``(order + 1) // 2`` on each filtered axis. A
coefficient at least ``n`` samples from its block's padded edge reads only
true samples, so the chunked result equals the unchunked truncated one up
to rounding, and differs from the exact (recursive, unchunked) filter by at
most ``filter_bound(order, tol, ndim)['total'] * max|input|``: the
truncation error of ``n``, not the chunking, sets the error. Any degree
0..199 (``order`` is the degree, as in scipy).

``route='recursive'`` filters each padded block with the exact recursive
filter instead (about 4 multiply-adds per sample and pole where the
truncated convolution takes ``2n + 1``): a coefficient at least ``n`` from
the padded edge then differs from the unchunked one only through samples
beyond the padding, each off by at most ``2 max|input|`` (the block's own
mirror extension against the true samples), so the per-axis error is at
most ``2 b max|input|``; the depth is taken for ``tol / 2`` to keep that
within ``tol``. :func:`bound` gives the total for either route.

Ends: blocks at an array edge extend their samples by ``mode`` themselves
(``boundary='none'``); ``grid-wrap`` takes its halo from the other end
(``boundary='periodic'``).

dask-image's ``spline_filter`` (degrees 2..5) uses the exact filter per
block with a depth from the largest pole at a fixed 1e-8, ignoring the
tail's constant (the amplification ``A``), so its seam error is not bounded
by a stated tolerance.
"""

from __future__ import annotations

import dask.array as da
import numpy as np

import splinelab
from splinelab._ndimage import _axis, _filter, _filter_mode

__all__ = ["spline_filter", "spline_filter1d", "depth", "bound"]

DEFAULT_TOL = 1e-12
ROUTES = ("truncated", "recursive")


def _route(route):
    if route not in ROUTES:
        raise ValueError(f"route must be one of {ROUTES}, got {route!r}")
    return route


def _width_tol(tol, route):
    """The tolerance the half-width is certified for (see the module doc).
    ``tol=None`` is refused: the overlap is certified for a tolerance, and
    without one it would be the spline's support only (a silent error of
    order 1 at every chunk edge)."""
    if tol is None:
        raise ValueError(f"tol=None: the chunked filter needs a tolerance to certify its overlap (default {DEFAULT_TOL})")
    return tol / 2 if _route(route) == "recursive" else tol


def depth(order, tol=DEFAULT_TOL, route="truncated"):
    """The overlap depth per filtered axis: certified half-width + support.

    >>> from splinelab.dask import depth
    >>> depth(3, 1e-10)  # n = 18 for cubics at 1e-10, support 2
    20
    >>> depth(3, 1e-10, route="recursive")  # n for 5e-11
    21
    """
    n = splinelab.filter_bound(order, _width_tol(tol, route))["half_width"] or 0
    return n + (order + 1) // 2


def bound(order, tol=DEFAULT_TOL, ndim=1, route="truncated"):
    """Certified ``max|chunked - exact unchunked| / max|input|`` over ``ndim`` filtered axes.

    ``(A + e)**ndim - A**ndim`` with ``A`` the amplification and ``e`` the
    per-axis bound: ``b`` (truncated) or ``2 b`` (recursive), ``b`` the tail
    of the half-width :func:`depth` uses; both stay below ``tol`` per axis.

    >>> from splinelab.dask import bound
    >>> bound(3, 1e-10, ndim=2) < 7e-10, bound(3, 1e-10, ndim=2, route="recursive") < 7e-10
    (True, True)
    """
    f = splinelab.filter_bound(order, _width_tol(tol, route))
    e = f["bound"] * (2 if route == "recursive" else 1)
    a = f["amplification"]
    return (a + e) ** ndim - a**ndim


def _map(darr, axes, order, mode, tol, output, threads, route):
    darr = da.asarray(darr)
    dtype = np.dtype(output)
    d = depth(order, tol, route)
    depths = {ax: (d if ax in axes else 0) for ax in range(darr.ndim)}
    # Edge blocks extend by scipy's filter rule for `mode` (splinelab._ndimage._filter).
    boundary = "periodic" if _filter_mode(mode, False) == "grid-wrap" else "none"
    block_tol = tol if route == "truncated" else None

    def block(x):
        return _filter(x, axes, order, dtype, mode, block_tol, threads)

    return darr.map_overlap(block, depth=depths, boundary=boundary, dtype=dtype, meta=np.array((), dtype=dtype))


def spline_filter(darr, order=3, mode="mirror", tol=DEFAULT_TOL, output=np.float64, threads=1, route="truncated"):
    """``splinelab.spline_filter`` of a dask array, chunk by chunk.

    ``order`` is the spline **degree** 0..199. ``tol`` in (0, 1) is the
    certified per-axis truncation tolerance (see the module documentation);
    ``threads`` per block (default 1: dask already runs blocks in parallel).
    ``route``: 'truncated' (default) or 'recursive' (faster; see the module
    documentation); :func:`bound` gives the certified error of either.

    >>> import dask.array as da, numpy as np, splinelab, splinelab.dask
    >>> x = np.random.default_rng(0).uniform(-1, 1, (64, 64))
    >>> c = splinelab.dask.spline_filter(da.from_array(x, chunks=32), order=3).compute()
    >>> bound = splinelab.filter_bound(3, 1e-12, ndim=2)["total"]
    >>> bool(np.abs(c - splinelab.spline_filter(x, order=3)).max() <= bound + 1e-14)
    True
    """
    darr = da.asarray(darr)
    return _map(darr, list(range(darr.ndim)), order, mode, tol, output, threads, route)


def spline_filter1d(
    darr, order=3, axis=-1, mode="mirror", tol=DEFAULT_TOL, output=np.float64, threads=1, route="truncated"
):
    """``splinelab.spline_filter1d`` of a dask array along ``axis``, chunk by chunk.

    ``order`` is the spline **degree** 0..199; other arguments as
    :func:`spline_filter`.
    """
    darr = da.asarray(darr)
    return _map(darr, [_axis(axis, darr.ndim)], order, mode, tol, output, threads, route)
