"""Certified chunked prefiltering of dask arrays.

``spline_filter`` and ``spline_filter1d`` filter each chunk through
``dask.array.map_overlap`` with an overlap depth of ``n`` plus the degree's
support half-width ``(order + 1) // 2`` on each filtered axis, ``n`` the
half-width certified for ``tol``. The default route runs the exact
recursive filter over each padded block with **zeros beyond it** (the
engine's ``grid-constant`` rule with cval 0, exact to ``2^-106``), the
block's array edges first padded by the mode's own extension: a coefficient
at least ``n`` from the padded edge then reads every sample within ``n``
truly and only zeros in place of those beyond, so it differs from the exact
unchunked coefficient by at most ``b max|input|`` per axis, ``b = Σ_{|j|>n}
|c_j|`` — the bound of the truncated convolution of half-width ``n``, at the
recursion's cost (about 4 multiply-adds per sample and pole where the
convolution takes ``2n + 1``). The truncation error of ``n``, not the
chunking, sets the error: ``filter_bound(order, tol, ndim)['total'] *
max|input|`` at most. Any degree 0..199 (``order`` is the degree, as in
scipy). Integer outputs (filtered axis by axis and truncated, as scipy does)
take the truncated convolution of half-width ``n``, the same bound.

``route='recursive'`` filters each padded block with the exact recursive
filter under the block's own mirror extension instead: a coefficient at least ``n`` from
the padded edge then differs from the unchunked one only through samples
beyond the padding, each off by at most ``2 max|input|`` (the block's own
mirror extension against the true samples), so the per-axis error is at
most ``2 b max|input|``; the depth is taken for ``tol / 2`` to keep that
within ``tol``. :func:`bound` gives the total for either route.

Ends: blocks at an array edge extend their samples by ``mode`` themselves
(``boundary='none'``); ``grid-wrap`` takes its halo from the other end
(``boundary='periodic'``).

Missing data (``nan_policy``, as :func:`splinelab.spline_filter`):
'local' gives the unchunked NaN pattern whatever the chunking (the overlap
``depth`` covers the certified half-width the pattern is dilated by, and the
array edges are padded by the mode's extension, so each block sees every
missing sample within reach of its core) and values within the bound of
the unchunked ones; its ``tol`` is the one of the overlap (default 1e-12).
'propagate' (the default) matches scipy applied to the whole array: a
non-finite sample makes every line through it along a filtered axis
non-finite, which no block can see alone, so the result is masked by a
global reduction (``any non-finite`` over the filtered axes, one more read
of the input in the graph; degrees 0 and 1 need none). 'raise' refuses a
non-finite sample when the block holding it is computed (the index is the
one within that block). The resampling functions take their coefficients
from these filters; a non-finite coordinate is refused on dask.

dask-image's ``spline_filter`` (degrees 2..5) uses the exact filter per
block with a depth from the largest pole at a fixed 1e-8, ignoring the
tail's constant (the amplification ``A``), so its seam error is not bounded
by a stated tolerance.
"""

from __future__ import annotations

import bisect
import functools
import inspect
import itertools
import threading
from typing import NamedTuple

import dask
import dask.array as da
import numpy as np
from dask.highlevelgraph import HighLevelGraph, MaterializedLayer

import splinelab
from splinelab import _dtypes as _dt
from splinelab import _local
from splinelab._doc import fill
from splinelab._engine import _Points, _refuse_non_finite, _wrap_axis
from splinelab._modes import engine_args, filter_mode as _filter_mode, interp_mode as _interp_mode
from splinelab._ndimage import _axis, _filter_with
from splinelab._resample import _affine_parts, _per_axis, _rotation, _zoom_shift_coordinates
from splinelab._settings import Settings
from splinelab._validate import _cval, _degree, _nan_policy, _tol_for

__all__ = ["spline_filter", "spline_filter1d", "depth", "bound", "map_coordinates", "zoom", "shift", "affine_transform", "rotate"]

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


@fill
def depth(order, tol=DEFAULT_TOL, route="truncated"):
    """The overlap depth per filtered axis: certified half-width + support.

    Parameters
    ----------
    order : int
        The spline degree, 0..199.
    tol : float, optional
        The per-axis tolerance the half-width is certified for (default
        1e-12).
    route : {'truncated', 'recursive'}, optional
        'recursive' certifies the half-width for ``tol / 2``.

    Returns
    -------
    int
        ``n + (order + 1) // 2``, ``n`` from :func:`splinelab.filter_bound`.

    Raises
    ------
    ValueError
        ``tol=None`` or outside (0, 1), or an unknown ``route``.

    Examples
    --------
    >>> from splinelab.dask import depth
    >>> depth(3, 1e-10)  # n = 18 for cubics at 1e-10, support 2
    20
    >>> depth(3, 1e-10, route="recursive")  # n for 5e-11
    21
    """
    n = splinelab.filter_bound(order, _width_tol(tol, route))["half_width"] or 0
    return n + (order + 1) // 2


@fill
def bound(order, tol=DEFAULT_TOL, ndim=1, route="truncated"):
    """Certified ``max|chunked - exact unchunked| / max|input|`` over ``ndim`` filtered axes.

    Parameters
    ----------
    order : int
        The spline degree, 0..199.
    tol : float, optional
        The per-axis tolerance (default 1e-12).
    ndim : int, optional
        The number of filtered axes (default 1).
    route : {'truncated', 'recursive'}, optional
        The chunked filter's route (default 'truncated').

    Returns
    -------
    float
        ``(A + e)**ndim - A**ndim`` with ``A`` the amplification and ``e``
        the per-axis bound: ``b`` (truncated) or ``2 b`` (recursive), ``b``
        the tail of the half-width :func:`depth` uses; both stay below
        ``tol`` per axis.

    Raises
    ------
    ValueError
        ``tol=None`` or outside (0, 1), or an unknown ``route``.

    Examples
    --------
    >>> from splinelab.dask import bound
    >>> bound(3, 1e-10, ndim=2) < 7e-10, bound(3, 1e-10, ndim=2, route="recursive") < 7e-10
    (True, True)
    """
    f = splinelab.filter_bound(order, _width_tol(tol, route))
    e = f["bound"] * (2 if route == "recursive" else 1)
    a = f["amplification"]
    return (a + e) ** ndim - a**ndim


# numpy's name for the extension of each filter rule at an array edge.
_NUMPY_PAD = {"mirror": "reflect", "reflect": "symmetric"}


def _map(darr, axes, order, mode, tol, output, threads, route, nan_policy="propagate", compute="float64",
         overlap=None):
    darr = da.asarray(darr)
    dtype = np.dtype(output)
    compute = _dt.compute_name(compute)
    nan_policy = _nan_policy(nan_policy)
    d = depth(order, tol, route)
    if overlap is not None:
        # dask-image's `depth=`: never below the certified overlap (more only reads more).
        if isinstance(overlap, (bool, np.bool_)) or not isinstance(overlap, (int, np.integer)) or overlap < 0:
            raise ValueError(f"depth must be a non-negative integer (dask-image's overlap), got {overlap!r}")
        d = max(d, int(overlap))
    # An axis in one chunk has no seam: no overlap. An axis not longer than
    # two overlaps goes into one chunk: filtered whole, exactly.
    short = {ax: -1 for ax in axes if darr.numblocks[ax] > 1 and darr.shape[ax] <= 2 * d}
    if short:
        darr = darr.rechunk(short)
    seamed = [ax for ax in axes if darr.numblocks[ax] > 1]
    depths = {ax: (d if ax in seamed else 0) for ax in range(darr.ndim)}
    # Edge blocks extend by scipy's filter rule for `mode` (splinelab._ndimage._filter).
    rule = _filter_mode(mode, False)
    boundary = "periodic" if rule == "grid-wrap" else "none"
    zeros_beyond = route == "truncated" and dtype.kind in "fc"
    # 'local' dilates by the half-width of `tol` in every block (the filters
    # below run the same recursion under a truncated route).
    local_tol = tol if nan_policy == "local" else None
    block_tol = tol if route == "truncated" or local_tol else None
    # The settings checked once a call (here, not in every block's task).
    if zeros_beyond:
        settings = _BlockSettings.of(order, mode, local_tol, threads, nan_policy, compute)
    else:
        conv = Settings.for_filter(order, mode, block_tol, threads, False, nan_policy, compute)

    if zeros_beyond:
        block = functools.partial(_seamed_block, axes=axes, seamed=seamed, d=d, dtype=dtype, settings=settings)
    else:
        block = functools.partial(_convolved_block, axes=axes, conv=conv, dtype=dtype)
    out = darr.map_overlap(block, depth=depths, boundary=boundary, dtype=dtype, meta=np.array((), dtype=dtype))
    if nan_policy != "propagate" or order < 2 or darr.dtype.kind not in "fc":
        return out
    # scipy's whole-array pattern: every line through a non-finite sample
    # along a filtered axis (a reduction no block can make alone).
    spread = (~da.isfinite(darr)).any(axis=tuple(axes), keepdims=True)
    return da.where(spread, np.asarray(np.nan, dtype), out)


def _convolved_block(x, *, axes, conv, dtype):
    """:func:`_map`'s block under a route without zeros beyond: the local
    convolution (a coefficient reads only samples within ``n``). Module
    level, bound with ``functools.partial``: the graph pickles with plain
    ``pickle`` (a closure needs cloudpickle)."""
    return _filter_array(x, axes, conv, dtype, convolution=True)


def _seamed_block(x, block_info=None, *, axes, seamed, d, dtype, settings):
    """:func:`_map`'s block with zeros beyond its read edges
    (:func:`_filter_block`), its ends at the array's edges read from dask's
    ``block_info``."""
    info = block_info[0]
    ends = [(i == 0, i == k - 1) for i, k in zip(info["chunk-location"], info["num-chunks"])]
    whole = [ax for ax in axes if ax not in seamed]
    return _filter_block(x, seamed, whole, d, ends, dtype, settings)


class _BlockSettings(NamedTuple):
    """The two filters of :func:`_filter_block`, checked once a call
    (:meth:`Settings.for_filter`, the checks the filters make) and pickled
    into its tasks: ``seamed`` ('grid-constant' with exact edges: zeros
    beyond the read edges), ``whole`` (the mode itself); ``rule``: the
    mode's filter rule, which extends the array's own edges."""

    seamed: Settings
    whole: Settings
    rule: str

    @classmethod
    def of(cls, order, mode, tol, threads, nan_policy="propagate", compute="float64"):
        return cls(Settings.for_filter(order, "grid-constant", tol, threads, True, nan_policy, compute),
                   Settings.for_filter(order, mode, tol, threads, False, nan_policy, compute),
                   _filter_mode(mode, False))


def _filter_array(x, axes, s, dtype, convolution=False):
    """``splinelab._ndimage._filter`` of a block under the settings ``s``
    made once a call: the block's own checks (a numeric dtype; ``dtype``
    against the block's, complex blocks promoted as scipy promotes them),
    then :func:`splinelab._ndimage._filter_with`."""
    a = _dt.input_array(x)
    dtype, _ = _dt.output_dtype(dtype, a.dtype, None, a.dtype.kind == "c")
    return _filter_with(a, axes, s, dtype, None, convolution)


def _filter_block(x, seamed, whole, d, ends, dtype, settings):
    """A block's filter with zeros beyond its read edges: the ``seamed``
    axes, the block's ends that are the array's first extended by ``d``
    samples of the mode's rule (:func:`_pad_ends`), filtered exactly with
    zeros beyond and cropped; then the ``whole`` axes (in one block) under
    the mode itself (``settings``: :class:`_BlockSettings`). The chunked
    prefilter's blocks and the fused route's regions (:class:`_Fused`) both."""
    x, crop = _pad_ends(x, seamed, settings.rule, d, ends)
    # Run with no seamed axis too: it converts the block to ``dtype`` (and
    # applies ``nan_policy``) before the whole axes, as it always has.
    x = _filter_array(x, seamed, settings.seamed, dtype)[crop]
    if whole:
        x = _filter_array(x, whole, settings.whole, dtype)
    return x


def _pad_ends(x, seamed, rule, d, ends):
    """``x`` padded by ``d`` samples of the mode's extension (``rule``) on
    each side of a seamed axis where the block meets the array's edge
    (``ends[axis]``: at the start, at the end; there map_overlap adds no
    halo; ``grid-wrap`` has its periodic halo already), and the slices that
    take the padding off again."""
    pads = _end_pads(x.ndim, seamed, rule, d, ends)
    if not any(lo or hi for lo, hi in pads):
        return x, ()
    crop = tuple(slice(lo, lo + n) for (lo, _), n in zip(pads, x.shape))
    return np.pad(x, pads, mode=_NUMPY_PAD[rule]), crop


def _end_pads(ndim, seamed, rule, d, ends):
    """:func:`_pad_ends`'s padding, ``(before, after)`` per axis of
    ``ndim``: ``d`` on each side of a seamed axis where the block meets the
    array's edge, under a ``rule`` numpy pads."""
    pads = [(0, 0)] * ndim
    if rule in _NUMPY_PAD:
        for ax in seamed:
            pads[ax] = (d if ends[ax][0] else 0, d if ends[ax][1] else 0)
    return pads


def _dask_image_names(**aliases):
    """Accept dask-image's name for a parameter (``alias=name``) as well as
    splinelab's: the call goes on under splinelab's name; both given is a
    TypeError naming both."""
    def wrap(func):
        sig = inspect.signature(func)

        @functools.wraps(func)
        def call(*args, **kwargs):
            for alias, name in aliases.items():
                if alias in kwargs:
                    rest = {k: v for k, v in kwargs.items() if k not in aliases}
                    try:
                        given = name in sig.bind_partial(*args, **rest).arguments
                    except TypeError:
                        given = name in rest
                    if given:
                        raise TypeError(f"{func.__name__}() got both {name}= and {alias}= (dask-image's name for "
                                        f"{name}): pass one")
                    kwargs[name] = kwargs.pop(alias)
            return func(*args, **kwargs)
        return call
    return wrap


def _either(chunks, output_chunks):
    """``chunks=`` or dask-image's ``output_chunks=``, not both."""
    if chunks is not None and output_chunks is not None:
        raise TypeError("got both chunks= and output_chunks= (dask-image's name for chunks): pass one")
    return output_chunks if chunks is None else chunks


def _rechunked(out, output_chunks):
    return out if output_chunks is None else out.rechunk(output_chunks)


@_dask_image_names(image="darr")
@fill
def spline_filter(darr, order=3, mode="mirror", tol=DEFAULT_TOL, output=np.float64, threads=1, route="truncated",
                  nan_policy="propagate", compute="float64", *, output_chunks=None, depth=None):
    """:func:`splinelab.spline_filter` of a dask array, chunk by chunk.

    Parameters
    ----------
    darr : dask.array.Array or array_like
        The samples.
    %(dask_order)s
    %(dask_mode)s
    %(dask_tol)s
    %(dask_output)s
    %(dask_tail)s
    %(dask_filter_chunks)s
    %(dask_depth)s

    Returns
    -------
    dask.array.Array
        The coefficients, chunked as the input (lazy).

    Raises
    ------
    %(dask_raises)s

    Notes
    -----
    Method: ``dask.array.map_overlap`` with the overlap :func:`depth` on
    each filtered axis (module documentation). Error: at most
    :func:`bound` ``* max|input|`` from the unchunked exact coefficients,
    whatever the chunking. Cost: the recursion's per block (about 4
    multiply-adds per sample and pole), on the block and its overlap.

    Examples
    --------
    >>> import dask.array as da, numpy as np, splinelab, splinelab.dask
    >>> x = np.random.default_rng(0).uniform(-1, 1, (64, 64))
    >>> c = splinelab.dask.spline_filter(da.from_array(x, chunks=32), order=3).compute()
    >>> bound = splinelab.filter_bound(3, 1e-12, ndim=2)["total"]
    >>> bool(np.abs(c - splinelab.spline_filter(x, order=3)).max() <= bound + 1e-14)
    True
    """
    darr = da.asarray(darr)
    return _rechunked(_map(darr, list(range(darr.ndim)), order, mode, tol, output, threads, route, nan_policy,
                           compute, depth), output_chunks)


@_dask_image_names(image="darr")
@fill
def spline_filter1d(
    darr, order=3, axis=-1, mode="mirror", tol=DEFAULT_TOL, output=np.float64, threads=1, route="truncated",
    nan_policy="propagate", compute="float64", *, output_chunks=None, depth=None,
):
    """:func:`splinelab.spline_filter1d` of a dask array along ``axis``, chunk by chunk.

    Parameters
    ----------
    darr : dask.array.Array or array_like
        The samples.
    %(dask_order)s
    axis : int, optional
        The axis to filter (default -1).
    %(dask_mode)s
    %(dask_tol)s
    %(dask_output)s
    %(dask_tail)s
    %(dask_filter_chunks)s
    %(dask_depth)s

    Returns
    -------
    dask.array.Array
        The coefficients, chunked as the input (lazy).

    Raises
    ------
    %(dask_raises)s

    Notes
    -----
    As :func:`spline_filter`, along one axis.
    """
    darr = da.asarray(darr)
    return _rechunked(_map(darr, [_axis(axis, darr.ndim)], order, mode, tol, output, threads, route, nan_policy,
                           compute, depth), output_chunks)


# ---------------------------------------------------------------------------
# Resampling on dask: each output chunk reads only the coefficient region
# its points need (their bounding box after the mode's folding, plus the
# spline's support) and evaluates it as given coefficients. The windows of
# every point lie inside its region, and a region reaches an array edge only
# where the true edge is, so the engine's extension there is the true one:
# chunked = unchunked evaluation of the chunked coefficients, which are
# within ``bound(order, tol, ndim) * max|input|`` of the exact ones; the
# B-spline weights are non-negative and sum to 1, so the values are within
# the same bound (plus rounding) of splinelab's unchunked result, whatever
# the chunking.
#
# The coefficients come from the certified chunked prefilter above, or, on
# output grids (zoom, shift, affine_transform, rotate) where the route
# allows (_fusable), from each output task itself: it reads its region's
# samples with the certified overlap and filters them as the chunked filter
# filters a block (_Fused), the same bound. Output tasks make their points
# and find their regions from the block's box (no coordinate array is built
# on the client or pickled into the graph), and the input chunks and the
# missing-sample flag are shared keys of one graph (_one). Issue 51's
# 8000² rotation on two workers: python/bench/cluster.py.

_FOLDING = ("mirror", "reflect", "grid-mirror", "grid-wrap")


def _fold(x, n, mode):
    """The engine's ``Mode::fold_coordinate`` (the same operations, so the
    same bits) for the symmetric and periodic modes."""
    x = np.asarray(x, dtype=np.float64)
    if mode == "mirror":
        if n == 1:
            return np.zeros_like(x)
        p = 2.0 * (n - 1.0)
        r = np.abs(np.where(np.abs(x) <= p, x, np.mod(x, p)))
        return np.where(r <= n - 1.0, r, p - r)
    if mode in ("reflect", "grid-mirror"):
        p = 2.0 * n
        inside = (x >= -p - 0.5) & (x <= p - 0.5)
        r = np.where(inside, x, np.mod(x + 0.5, p) - 0.5)
        r = np.where(r < -0.5, -1.0 - r, r)
        return np.where(r <= n - 0.5, r, p - 1.0 - r)
    # grid-wrap
    return np.where((x >= -0.5) & (x <= n - 0.5), x,
                    np.where((x < -0.5) & (x >= -0.5 - n), x + n,
                             np.where((x > n - 0.5) & (x <= 2.0 * n - 0.5), x - n, np.mod(x + 0.5, n) - 0.5)))


class _Rules:
    """How a mode reads coefficients, and nothing lazy: what an output task
    needs (it is pickled into each task, so it holds no dask array). The
    engine mode for given coefficients, scipy's 12-sample pad, the points'
    transformation, and the region of coefficients a set of points reads."""

    def __init__(self, order, mode, cval, compute, shape, extent, prefilter):
        self.d, self.mode, self.cval, self.compute = order, mode, float(cval), compute
        self.shape, self.extent = tuple(shape), tuple(extent)  # the input's, the coefficients' (padded)
        self.engine_mode, _, self.pad = engine_args(mode, order, bool(prefilter), False)

    def prepared(self, flat, box=None, own=False):
        """Global points (``(ndim, k)``) the way the engine reads them: the
        scipy rules applied, then folded into the grid (folding modes) or
        clamped where the spline is constant (padded ones); and the mask of
        'constant' points that take ``cval``. ``box``: bounds known to hold
        the points (the output block's), or None: found here. ``own``: a
        task's own points, used at once, whose region is its box's (the
        mask is then made in the thread's scratch arrays, valid until its
        next task, and 'constant' leaves the points outside unfolded)."""
        if box is not None and self.within(*box):
            return flat, None
        low, high = flat.min(axis=1, initial=np.inf), flat.max(axis=1, initial=-np.inf)
        if not (np.isfinite(low).all() and np.isfinite(high).all()) and flat.size:
            raise ValueError(_NOT_FINITE)
        # Points inside the grid on an axis are left as they are by every
        # rule below (the fold is the identity there): no pass over them.
        inside = (low >= 0) & (high <= np.array(self.shape, dtype=np.float64) - 1.0)
        mask = None
        if self.mode == "constant" and not inside.all():
            mask = self._outside(flat, ~inside, own)
            if own and not self.pad:
                # A task's 'constant': the points outside take cval whatever
                # the spline gives there, and the others lie in the grid,
                # where the fold leaves them as they are: none is moved (the
                # engine reads any coordinate within the coefficients given;
                # the region is the box's, not found from these points).
                return flat, mask
        if inside.all() and not self.pad:
            return flat, mask
        rows = []
        reach = self.d // 2 + 1 + 1
        for axis, x in enumerate(flat):
            n = self.extent[axis]
            if inside[axis] and not self.pad:
                rows.append(x)
                continue
            if self.mode == "wrap":
                x = _wrap_axis(x, n)
            if self.engine_mode in _FOLDING and self.d > 0:
                x = _fold(x, n, self.engine_mode)
            elif self.pad or self.mode in ("nearest", "grid-constant"):
                x = np.clip(x + self.pad, -reach, n - 1 + reach)
            rows.append(x)
        return np.stack(rows), mask

    def _outside(self, flat, axes, own):
        """Whether each point lies outside ``[0, n - 1]`` on one of the
        ``axes`` (flags; the others hold every point)."""
        k = flat.shape[1]
        mask = _scratch.get("mask", (k,), bool) if own else np.empty(k, bool)
        cmp = _scratch.get("compared", (k,), bool) if own else np.empty(k, bool)
        mask[...] = False
        for axis in np.flatnonzero(axes):
            mask |= np.less(flat[axis], 0, out=cmp)
            mask |= np.greater(flat[axis], self.shape[axis] - 1.0, out=cmp)
        return mask

    def within(self, low, high):
        """Whether a box lies inside the grid on every axis with room for
        the rounding of the points in it (then every rule leaves them as
        they are) and no padding moves them."""
        room = 1e-9 * (1.0 + np.maximum(np.abs(low), np.abs(high)))
        return bool(not self.pad and (low - room >= 0).all()
                    and (high + room <= np.array(self.shape, dtype=np.float64) - 1.0).all())

    def region(self, x):
        """Per axis ``(lo, hi)``: the coefficients the windows at ``x`` read."""
        return [self._span(axis, row.min(), row.max()) if row.size else self._whole(axis)
                for axis, row in enumerate(x)]

    def box_region(self, low, high):
        """:meth:`region` of every point whose raw coordinates lie in the box
        ``[low, high]`` (per axis, before :meth:`prepared`), from the box
        alone: a superset of the region of the points themselves, so no
        coordinate array is made to find it."""
        if not (np.isfinite(low).all() and np.isfinite(high).all()):
            raise ValueError(_NOT_FINITE)
        out = []
        for axis, (a, b) in enumerate(zip(low, high)):
            a, b = float(a) - 1.0, float(b) + 1.0  # the rounding of the points themselves
            n = self.extent[axis]
            if self.mode == "wrap" and not 0 <= a <= b <= n - 1:
                out.append(self._whole(axis))
            elif self.engine_mode in _FOLDING and self.d > 0:
                out.append(self._folded_span(axis, a, b))
            else:
                reach = self.d // 2 + 1 + 1
                if self.pad or self.mode in ("nearest", "grid-constant"):
                    a, b = (float(np.clip(v + self.pad, -reach, n - 1 + reach)) for v in (a, b))
                out.append(self._span(axis, a, b))
        return out

    def _folded_span(self, axis, a, b):
        """The span of the fold of ``[a, b]``: the fold is continuous and
        linear between its turns (mirror: multiples of ``n - 1``; reflect:
        ``k n - 1/2``), so the image's ends are among the folded ends and
        turns; grid-wrap jumps, so a box across an end reads the whole axis."""
        n, mode = self.extent[axis], self.engine_mode
        if mode == "grid-wrap":
            inside = -0.5 <= a and b <= n - 0.5
            return self._span(axis, a, b) if inside else self._whole(axis)
        step, first = (n - 1.0, 0.0) if mode == "mirror" else (float(n), -0.5)
        if step <= 0 or b - a >= 2 * step:
            return self._whole(axis)
        turns = first + step * np.arange(np.ceil((a - first) / step), np.floor((b - first) / step) + 1)
        folded = _fold(np.concatenate([[a, b], turns]), n, mode)
        return self._span(axis, folded.min(), folded.max())

    def _whole(self, axis):
        return 0, self.extent[axis]

    def _span(self, axis, low, high):
        """The coefficients the windows of points in ``[low, high]`` read."""
        lo, hi = self.spans(axis, low, high)
        return int(lo), int(hi)

    def spans(self, axis, low, high):
        """:meth:`_span` of each pair of ``low`` and ``high`` (arrays or
        numbers, prepared coordinates): the arrays of ``lo`` and ``hi``."""
        n = self.extent[axis]
        low, high = np.asarray(low, dtype=np.float64), np.asarray(high, dtype=np.float64)
        if self.d == 0 and self.engine_mode in _FOLDING:
            # Degree 0 folds by its own rule at half-integers (scipy's):
            # the whole axis (one sample per point, cheap).
            return np.zeros(low.shape, np.intp), np.full(high.shape, n, np.intp)
        m = self.d + 1
        # Clipped first so that far points convert to integers without
        # overflow: a window at 2^52 or beyond lies off the array either way.
        far = 2.0**52
        lo = np.floor(np.clip(low, -far, far)).astype(np.intp) - (m // 2 + 2)
        hi = np.ceil(np.clip(high, -far, far)).astype(np.intp) + (m // 2 + 3)
        if self.engine_mode == "grid-wrap":
            # A window over an end reads the other end: the whole axis.
            over = (lo < 0) | (hi > n)
            lo, hi = np.where(over, 0, lo), np.where(over, n, hi)
        return np.maximum(lo, 0), np.minimum(hi, n)


_NOT_FINITE = ("a coordinate is not finite: non-finite coordinates are not taken on dask "
               "(splinelab.map_coordinates gives scipy's values there)")


class _Scratch(threading.local):
    """Per worker thread, the scratch arrays an output task works in (the
    region's samples filtered in place, its points), kept from one task to
    the next. A worker of dask.distributed runs with glibc's
    ``MALLOC_TRIM_THRESHOLD_`` at 64 KiB (its nanny's default), under which
    every large array is a fresh ``mmap`` whose pages are faulted in and
    zeroed by the kernel, and returned on ``free``: tens of megabytes per
    task, as much time as the interpolation itself on a 2-core machine
    (issue 51). Nothing kept here is returned from a task (a task's result
    is always a new array), and none larger than :data:`_SCRATCH_MAX` bytes
    is kept (such a task pays one allocation among much more work)."""

    def __init__(self):
        self.arrays = {}

    def get(self, name, shape, dtype):
        """An uninitialised C-ordered array of ``shape`` and ``dtype``: a view
        of the thread's buffer ``name`` (grown as needed), or a new array
        where it would exceed :data:`_SCRATCH_MAX`."""
        dtype = np.dtype(dtype)
        nbytes = int(np.prod(shape, dtype=np.int64)) * dtype.itemsize
        if nbytes > _SCRATCH_MAX:
            return np.empty(shape, dtype)
        buf = self.arrays.get(name)
        if buf is None or buf.size < nbytes:
            buf = self.arrays[name] = np.empty(max(nbytes, 1), np.uint8)
        return buf[:nbytes].view(dtype).reshape(shape)


_SCRATCH_MAX = 256 << 20
_scratch = _Scratch()


class _Plan:
    """The lazy side of a resampling: the coefficient array (or, fused, the
    samples each task prefilters itself) and the :class:`_Rules`."""

    def __init__(self, darr, order, mode, cval, tol, route, threads, nan_policy="propagate", compute="float64",
                 prefilter=True, fuse=False):
        mode, compute = _interp_mode(mode), _dt.compute_name(compute)
        if compute == "float32":
            darr = darr.astype(np.float32)
        shape = darr.shape
        engine_mode, _, pad = engine_args(mode, order, bool(prefilter), False)
        if order > 5 and mode in ("nearest", "grid-constant"):
            raise ValueError(f"mode {mode!r} above degree 5 (the exact extension) is not offered on dask")
        if pad:
            kind = {"mode": "edge"} if mode == "nearest" else {"mode": "constant", "constant_values": float(cval)}
            darr = da.pad(darr, pad, **kind)
        self.rules = _Rules(order, mode, cval, compute, shape, darr.shape, prefilter)
        self.fused, self.missing_flag = None, None
        if order > 1 and prefilter and fuse and _fusable(darr, mode, route, nan_policy, compute):
            # Each output task prefilters its own region (see _Fused).
            self.fused = _Fused(order, mode, depth(order, tol, route), threads, darr.shape)
            # The flag: a 0-d dask array (output grids, :func:`_blocks_layer`)
            # and one Delayed (scattered points, :func:`_lazy_block`).
            self.missing_flag = _any_missing(darr) if darr.dtype.kind == "f" else None
            self.missing = _one(self.missing_flag) if self.missing_flag is not None else False
        elif order > 1 and prefilter:
            smallest = min(darr.chunksize)
            need = depth(order, tol, route)
            if smallest < need:  # the overlap needs chunks of at least the depth
                darr = darr.rechunk(tuple(min(max(c, need), n) for c, n in zip(darr.chunksize, darr.shape)))
            # Coefficients in the arithmetic's dtype (float64: from float32
            # blocks read as they lie, as the unchunked filter).
            coeff_dtype = np.float32 if compute == "float32" else np.float64
            darr = spline_filter(darr, order=order, mode=mode, tol=tol, output=coeff_dtype, threads=threads,
                                 route=route, nan_policy=nan_policy, compute=compute)
        elif _nan_policy(nan_policy) == "raise":
            darr = darr.map_blocks(_refused_if_missing, dtype=darr.dtype)
        self.coeffs = darr  # the coefficients, or (fused) the samples

    def prepared(self, flat):
        return self.rules.prepared(flat)

    def region(self, x):
        return self.rules.region(x)

    def read(self, bounds):
        """What a task reads for the coefficient region ``bounds``: the lazy
        array, the span it covers where it holds samples to prefilter
        (fused: the region and its certified overlap; None: coefficients),
        and the flag of a non-finite sample anywhere (fused)."""
        if self.fused is None:
            return self.coeffs[tuple(slice(a, b) for a, b in bounds)], None, False
        reach = self.fused.reach(bounds)
        return self.coeffs[tuple(slice(a, b) for a, b in reach)], reach, self.missing


def _fusable(darr, mode, route, nan_policy, compute):
    """Whether the fused route gives what the chunked prefilter gives:
    real samples, the truncated route's rule, scipy's NaN pattern (the whole
    array NaN after a non-finite sample: one flag), float64 arithmetic, and
    an edge rule numpy pads by (not the periodic one)."""
    return (darr.dtype.kind in "biuf" and route == "truncated" and _nan_policy(nan_policy) == "propagate"
            and compute == "float64" and _filter_mode(mode, False) in _NUMPY_PAD)


class _Fused:
    """The prefilter done by each output task on its own region: the region
    read with the certified overlap ``depth`` on each side (no more than the
    array), filtered exactly with zeros beyond (the array edges first
    padded by ``depth`` samples of the mode's extension), and cropped. A
    coefficient at least the half-width from the read edge then differs from
    the unchunked one by at most ``b max|input|`` per axis, as in the
    chunked filter (module documentation): the same bound. No coefficient
    array is stored or sent between workers; each task reads float32
    samples where the input is float32, and the overlap is filtered twice
    where regions meet (a few percent for chunks of hundreds of samples)."""

    def __init__(self, order, mode, depth, threads, extent):
        self.order, self.mode, self.depth, self.threads = order, mode, depth, threads
        self.extent = tuple(extent)
        # Checked once, pickled into every task (not made per region).
        self.settings = _BlockSettings.of(order, mode, None, threads)

    def reach(self, bounds):
        """The region ``bounds`` (per axis ``(lo, hi)``) with its overlap."""
        return [tuple(int(v) for v in self.widened(axis, a, b)) for axis, (a, b) in enumerate(bounds)]

    def widened(self, axis, lo, hi):
        """:meth:`reach` along ``axis`` of each of the spans ``[lo, hi)``
        (arrays or numbers)."""
        return np.maximum(np.subtract(lo, self.depth), 0), np.minimum(np.add(hi, self.depth), self.extent[axis])

    def axes_of(self, reach):
        """The axes of a region ``reach`` filtered in one block (it spans
        the array: ``whole``), those filtered with seams, and per axis
        whether the region starts and ends at the array's edges."""
        whole = [ax for ax, ((a, b), n) in enumerate(zip(reach, self.extent)) if a == 0 and b == n]
        seamed = [ax for ax in range(len(reach)) if ax not in whole]
        ends = [(a == 0, b == n) for (a, b), n in zip(reach, self.extent)]
        return whole, seamed, ends

    def coefficients(self, samples, reach, missing):
        """The coefficients over ``reach`` from its samples: true within the
        bound on the region inside it (those at least the half-width from
        an edge that is not the array's), which is all the windows read:
        not cropped (no copy), the region's windows never reach the rest."""
        x = np.asarray(samples)  # the filtered axes first (``reach``'s), any others carried
        whole, seamed, ends = self.axes_of(reach)
        x = _filter_block(x, seamed, whole, self.depth, ends, np.dtype(np.float64), self.settings)
        if missing:  # scipy's pattern: every coefficient NaN (the chunked filter's global mask)
            x = np.full(x.shape, np.nan)
        return x

    def in_scratch(self, pieces, reach):
        """:meth:`coefficients` of the samples given as ``pieces`` (the
        region's dask chunks, nested lists, one level per axis), computed in
        the thread's scratch arrays (:class:`_Scratch`): the pieces written
        once into a float64 array with the array edges' padding (numpy's
        pad, as :func:`_pad_ends`), filtered there in place (the same filter,
        the same bits: it widens float32 samples exactly either way), then
        the axes in one block under the mode itself. Valid until the
        thread's next task; C-ordered."""
        ndim = len(reach)
        grid = _piece_grid(pieces, ndim)
        carried = grid[(0,) * grid.ndim].shape[ndim:]
        whole, seamed, ends = self.axes_of(reach)
        pads = _end_pads(ndim + len(carried), seamed, self.settings.rule, self.depth, ends)
        inner = [b - a for a, b in reach] + list(carried)
        x = _scratch.get("samples", [n + lo + hi for n, (lo, hi) in zip(inner, pads)], np.float64)
        core = x[tuple(slice(lo, lo + n) for n, (lo, _) in zip(inner, pads))]
        _place(grid, core)
        _pad_in_place(x, pads, _NUMPY_PAD.get(self.settings.rule))
        f64 = np.dtype(np.float64)
        if seamed:
            x = _filter_with(x, seamed, self.settings.seamed, f64, x)
        if any(lo or hi for lo, hi in pads):
            cropped = x[tuple(slice(lo, lo + n) for n, (lo, _) in zip(inner, pads))]
            x = _scratch.get("coefficients", cropped.shape, f64)
            np.copyto(x, cropped)
        if whole:
            x = _filter_with(x, whole, self.settings.whole, f64, x)
        return x


def _piece_grid(pieces, ndim):
    """The nested lists of a region's chunks as an object array of the
    block grid (an array: one block)."""
    if isinstance(pieces, np.ndarray):
        grid = np.empty((1,) * ndim, dtype=object)
        grid[(0,) * ndim] = pieces
        return grid
    shape, level = [], pieces
    for _ in range(ndim):  # walked, not np.shape (which would stack the chunks)
        shape.append(len(level))
        level = level[0]
    grid = np.empty(shape, dtype=object)
    for idx in np.ndindex(grid.shape):
        p = pieces
        for i in idx:
            p = p[i]
        grid[idx] = np.asarray(p)
    return grid


def _assembled(pieces, ndim):
    """The pieces (nested lists, one level per axis) as one C-ordered array
    in the thread's scratch array 'region' (valid until its next task), of
    their common dtype."""
    grid = _piece_grid(pieces, ndim)
    blocks = list(grid.flat)
    dtype = np.result_type(*blocks)
    shape = [sum(grid[(0,) * ax + (i,) + (0,) * (grid.ndim - ax - 1)].shape[ax] for i in range(grid.shape[ax]))
             for ax in range(ndim)] + list(blocks[0].shape[ndim:])
    if len(blocks) == 1 and blocks[0].flags.c_contiguous:
        return blocks[0]
    out = _scratch.get("region", shape, dtype)
    _place(grid, out)
    return out


def _place(grid, out):
    """The blocks of ``grid`` written side by side into ``out`` (converted
    as numpy converts: float32 and integers of up to 53 bits exactly)."""
    starts = [np.cumsum([0] + [grid[(0,) * ax + (i,) + (0,) * (grid.ndim - ax - 1)].shape[ax]
                               for i in range(grid.shape[ax])]) for ax in range(grid.ndim)]
    for idx in np.ndindex(grid.shape):
        block = grid[idx]
        where = tuple(slice(int(starts[ax][i]), int(starts[ax][i]) + block.shape[ax]) for ax, i in enumerate(idx))
        np.copyto(out[where], block, casting="unsafe")


def _pad_in_place(x, pads, rule):
    """``np.pad(core, pads, mode=rule)`` where ``x`` holds ``core`` in its
    middle: the padding written around it, axis by axis as numpy pads (each
    axis over the whole extent of the axes padded before it). The source of
    each padded index is numpy's own pad of the index vector."""
    for ax, (lo, hi) in enumerate(pads):
        if not (lo or hi):
            continue
        n = x.shape[ax] - lo - hi
        src = np.pad(np.arange(n), (lo, hi), mode=rule) + lo
        for part in (np.arange(lo), np.arange(lo + n, lo + n + hi)):
            if part.size:
                np.copyto(_along(x, ax, part), np.take(x, src[part], axis=ax))


def _along(x, ax, idx):
    """The view of ``x`` at the contiguous indices ``idx`` along ``ax``."""
    return x[(slice(None),) * ax + (slice(int(idx[0]), int(idx[-1]) + 1),)]


def _any_missing(darr):
    """Whether ``darr`` holds a non-finite sample (a lazy 0-d bool): one
    task a chunk (:func:`_chunk_missing`), then ``any``."""
    return da.reduction(darr, _chunk_missing, _aggregate_any, dtype=bool, name="any-non-finite")


def _chunk_missing(x, axis, keepdims):
    """Whether the chunk ``x`` holds a non-finite sample, shaped as a
    reduction's chunk result. Decided by the sum where it is finite (a NaN
    or infinity makes it NaN or infinite): one pass in the chunk's own
    dtype, no mask the size of the chunk (a fresh mapping of pages in a
    worker); a sum that is not finite (a missing sample, or an overflow of
    finite ones) is decided by ``isfinite``."""
    with np.errstate(over="ignore", invalid="ignore"):
        total = np.add.reduce(x, axis=None) if x.size else 0.0
    flag = not np.isfinite(total) and not np.isfinite(x).all()
    return np.full((1,) * x.ndim if keepdims else (), flag)


def _aggregate_any(x, axis, keepdims):
    return np.any(x, axis=axis, keepdims=keepdims)


def _refused_if_missing(x):
    """nan_policy='raise' where no prefilter runs (degrees 0 and 1)."""
    _refuse_non_finite(x)
    return x


def _evaluate_region(region_coeffs, lo, x, mask, rules, dtype):
    """The values at global points ``x`` (prepared; made local in place:
    the caller's own) from the coefficient region starting at ``lo``; every
    window inside the region. Computed in
    the plan's arithmetic (float64: float32 results rounded once)."""
    work = _dt.Work(rules.compute, dtype)
    local = np.subtract(x, np.array(lo, dtype=np.float64)[:, None], out=x)
    coeffs = work.samples(np.ascontiguousarray(region_coeffs))
    values = _Points(local).evaluate(coeffs, rules.d, rules.engine_mode, rules.cval, None, False, 1, None, work=work)
    if mask is not None:  # the engine's new array: written in place
        np.copyto(values, np.asarray(rules.cval, values.dtype), where=mask)
    return values.astype(dtype, copy=False)


def _task(read, bounds, rules, points, dtype, shape, fused=None, reach=None, box=None):
    """One output block, computed in a worker: its points made here (not
    sent, in the thread's scratch array), the coefficients of its region
    (read, or prefiltered here)."""
    flat = points(out=_scratch.get("points", (len(bounds), int(np.prod(shape))), np.float64))
    x, mask = rules.prepared(flat, box, own=True)
    if reach is not None:  # fused: `read` holds the chunks of `reach` (the region and its overlap)
        read, bounds = fused.in_scratch(read, reach), reach
    elif isinstance(read, list):  # the chunks of the coefficients' region, written side by side
        read = _assembled(read, len(bounds))
    return _evaluate_region(read, [a for a, _ in bounds], x, mask, rules, dtype).reshape(shape)


def _with_missing(values, missing, rules, points, box):
    """The block after the flag of a non-finite sample anywhere: scipy's
    pattern (every coefficient NaN: every value NaN but 'constant''s cval
    outside the grid, what the evaluation of NaN coefficients gives), else
    the values as they are. A task of its own, after the block's, so that
    the blocks do not wait for the flag (every chunk read) to start."""
    if not missing:
        return values
    _, mask = rules.prepared(points(), box)
    out = np.full(values.shape, np.nan, dtype=values.dtype)
    if mask is not None:
        out.reshape(-1)[mask] = rules.cval
    return out


def _lazy_block(plan, bounds, points, dtype, shape, box=None):
    read, reach, missing = plan.read(bounds)
    value = dask.delayed(_task, pure=True)(_one(read), bounds, plan.rules, points, dtype, shape, plan.fused, reach,
                                           box)
    if missing is not False:
        value = dask.delayed(_with_missing, pure=True)(value, missing, plan.rules, points, box)
    return da.from_delayed(value, shape=shape, dtype=dtype)


def _one(lazy):
    """``lazy`` (a dask array) as one Delayed that shares the keys of its
    graph: a dask array passed to ``delayed`` is optimised call by call,
    under new keys, so tasks many blocks read (the input's chunks, a
    reduction) would be copied into each block's graph and run once per
    block."""
    if lazy.npartitions > 1:
        lazy = lazy.rechunk(lazy.shape)
    return lazy.to_delayed(optimize_graph=False).ravel()[0]


def _chunk(plan, flat, dtype):
    """One chunk of scattered points (``(ndim, k)``, given) as a lazy array."""
    bounds = plan.region(plan.prepared(flat)[0])
    return _lazy_block(plan, bounds, functools.partial(_given, flat), dtype, (flat.shape[1],))


def _given(flat, out=None):
    """Scattered points as float64 (a new array: the task makes them local
    in place; ``out`` is not used)."""
    return np.array(flat, dtype=np.float64)


def _work_dtype(darr, output):
    dtype = np.dtype(output) if output is not None else darr.dtype
    if dtype.kind not in "f":
        raise TypeError(f"dask resampling computes float64 or float32 results, got output={dtype}")
    return dtype


def _on_output_grid(darr, out_shape, chunks, grid, order, mode, cval, tol, route, output, threads,
                    nan_policy="propagate", compute="float64", prefilter=True):
    """The output of ``out_shape`` in ``chunks``; ``grid`` gives the points
    of a block (``grid.points(slices)``, ``(ndim, k)``, scipy's arithmetic)
    and their box (``grid.box(slices)``). Each block is one task that makes
    its points and reads its region; the graph holds no coordinate array.

    The graph is written directly (:func:`_blocks_layer`): one layer of the
    blocks and of the pieces of the input's chunks they read, on top of the
    input's own layers and the missing-sample flag's."""
    darr = da.asarray(darr)
    dtype = _work_dtype(darr, output)
    plan = _Plan(darr, order, mode, cval, tol, route, threads, nan_policy, compute, prefilter, fuse=True)
    chunks = da.core.normalize_chunks(chunks if chunks is not None else darr.chunksize[: len(out_shape)] if
                                      len(out_shape) == darr.ndim else "auto", out_shape, dtype=dtype)
    starts = [np.concatenate([[0], np.cumsum(c)[:-1]]).astype(int) for c in chunks]
    jobs = {}
    for idx in itertools.product(*[range(len(c)) for c in chunks]):
        slices = tuple(slice(int(starts[a][i]), int(starts[a][i] + chunks[a][i])) for a, i in enumerate(idx))
        shape = tuple(s.stop - s.start for s in slices)
        box = grid.box(slices) if all(shape) else None
        bounds = plan.rules.box_region(*box) if box else [(0, 0)] * darr.ndim
        reach = plan.fused.reach(bounds) if plan.fused is not None else None
        jobs[idx] = _Job(bounds, plan.rules, functools.partial(grid.points, slices), dtype, shape, plan.fused, reach,
                         box)
    missing = plan.missing_flag
    name = "splinelab-resample-" + dask.base.tokenize(plan.coeffs.name, plan.rules, plan.fused, grid, chunks, dtype,
                                                      None if missing is None else missing.name)
    graph = _blocks_layer(name, jobs, plan.coeffs, missing)
    return da.Array(graph, name, chunks, dtype=dtype, meta=np.empty((0,) * len(out_shape), dtype))


class _Job:
    """What one output block's task needs besides the chunks it reads
    (pickled into the task): :func:`_task`'s arguments."""

    __slots__ = ("bounds", "rules", "points", "dtype", "shape", "fused", "reach", "box")

    def __init__(self, bounds, rules, points, dtype, shape, fused, reach, box):
        self.bounds, self.rules, self.points, self.dtype = bounds, rules, points, dtype
        self.shape, self.fused, self.reach, self.box = shape, fused, reach, box

    def __getstate__(self):
        return tuple(getattr(self, k) for k in self.__slots__)

    def __setstate__(self, state):
        for k, v in zip(self.__slots__, state):
            setattr(self, k, v)


def _run_job(job, pieces):
    """A block's task: :func:`_task` on the pieces of the chunks it reads."""
    return _task(pieces, job.bounds, job.rules, job.points, job.dtype, job.shape, job.fused, job.reach, job.box)


def _finish_job(values, missing, job):
    """:func:`_with_missing` of a block's values."""
    return _with_missing(values, missing, job.rules, job.points, job.box)


def _cut(chunk, lo, hi):
    """The piece ``[lo, hi)`` (per axis) of a chunk (a view)."""
    return chunk[tuple(slice(a, b) for a, b in zip(lo, hi))]


def _blocks_layer(name, jobs, source, missing):
    """The graph of the blocks ``jobs`` (index -> :class:`_Job`) reading the
    chunks of the dask array ``source`` (the coefficients, or fused the
    samples), with the 0-d flag ``missing`` (or None): ``source``'s and
    ``missing``'s layers, and one layer ``name`` holding per block its
    task, the pieces of the chunks it reads (a chunk it reads whole: the
    chunk's own key) and, with a flag, the task that applies it, under the
    key ``(name, *index)``. Written directly, not through dask.delayed
    (which makes one layer per block and per piece, each with a copy of the
    tasks it reads and no dependency named, so that the optimizer fuses the
    input's reads into the flag's reduction and every chunk is read twice)."""
    edges = [np.cumsum((0,) + tuple(c)) for c in source.chunks]
    tasks = {}
    for idx, job in jobs.items():
        span = job.reach if job.reach is not None else job.bounds
        per_axis = []  # per axis, the chunks read: (index, start, stop within the chunk)
        for ax, (a, b) in enumerate(span):
            e = [int(v) for v in edges[ax]]
            if b <= a:  # nothing read: an empty piece of one chunk (the task's array keeps its axes)
                i = min(max(bisect.bisect_right(e, a) - 1, 0), len(e) - 2)
                per_axis.append([(i, 0, 0)])
                continue
            first, last = bisect.bisect_right(e, a) - 1, bisect.bisect_left(e, b)
            per_axis.append([(i, max(a, e[i]) - e[i], min(b, e[i + 1]) - e[i]) for i in range(first, last)])
        grid = np.empty([len(p) for p in per_axis], dtype=object)
        for pos in np.ndindex(grid.shape):
            parts = [per_axis[ax][k] for ax, k in enumerate(pos)]
            chunk = (source.name,) + tuple(i for i, _, _ in parts)
            lo, hi = tuple(a for _, a, _ in parts), tuple(b for _, _, b in parts)
            full = tuple(int(edges[ax][i + 1] - edges[ax][i]) for ax, (i, _, _) in enumerate(parts))
            if lo == (0,) * len(lo) and hi == full:
                grid[pos] = chunk
            else:
                key = ("splinelab-piece-" + name[len("splinelab-resample-"):],) + idx + pos
                tasks[key] = (_cut, chunk, lo, hi)
                grid[pos] = key
        if missing is None:
            tasks[(name,) + idx] = (_run_job, job, grid.tolist())
        else:
            values = ("splinelab-block-" + name[len("splinelab-resample-"):],) + idx
            tasks[values] = (_run_job, job, grid.tolist())
            tasks[(name,) + idx] = (_finish_job, values, (missing.name,), job)
    inputs = [source] + ([missing] if missing is not None else [])
    layers, deps = {}, {}
    for x in inputs:
        layers.update(x.__dask_graph__().layers)
        deps.update(x.__dask_graph__().dependencies)
    layers[name] = MaterializedLayer(tasks)
    deps[name] = {n for x in inputs for n in x.__dask_layers__()}
    return HighLevelGraph(layers, deps)


class _GridPoints:
    """The tensor grid of one coordinate vector per axis (zoom, shift)."""

    def __init__(self, axes):
        self.axes = axes

    def points(self, slices, out=None):
        mesh = np.meshgrid(*[x[s] for x, s in zip(self.axes, slices)], indexing="ij")
        return np.stack([m.reshape(-1) for m in mesh], out=out)

    def box(self, slices):
        parts = [x[s] for x, s in zip(self.axes, slices)]
        return np.array([p.min() for p in parts]), np.array([p.max() for p in parts])


class _AffinePoints:
    """The points ``m @ o + offset`` of the output indices ``o``."""

    def __init__(self, m, offsets):
        self.m, self.offsets = m, offsets

    def points(self, slices, out=None):
        """Per output axis ``h``: ``offset[h]``, then ``+= o_l m[h, l]`` for
        each index axis ``l`` in turn (the same operations, so the same bits,
        as adding whole index grids), the partial sums broadcast: one pass
        over the block per added axis, no index grids; the last sum written
        into ``out`` (``(ndim, k)``) where given."""
        idx = [np.arange(s.start, s.stop, dtype=np.float64) for s in slices]
        k = len(slices)
        grid = (self.m.shape[0],) + tuple(len(i) for i in idx)
        points = np.empty(grid) if out is None else out.reshape(grid)
        for h in range(self.m.shape[0]):
            t = np.full((1,) * k, self.offsets[h])
            for ll in range(k):
                step = (idx[ll] * self.m[h, ll]).reshape((1,) * ll + (-1,) + (1,) * (k - ll - 1))
                t = np.add(t, step, out=points[h] if ll == k - 1 else None)
            if k == 0:
                points[h] = t
        return points.reshape(self.m.shape[0], -1)

    def box(self, slices):
        """The box of the block's points: an affine map takes its extremes
        at the corners of the block of indices."""
        corners = np.array(list(itertools.product(*[(s.start, s.stop - 1) for s in slices])), dtype=np.float64).T
        with np.errstate(invalid="ignore", over="ignore"):
            p = self.m @ corners + self.offsets[:, None]
        return p.min(axis=1), p.max(axis=1)


@fill
def map_coordinates(input, coordinates, order=3, mode="constant", cval=0.0, tol=DEFAULT_TOL, output=None,
                    threads=1, route="truncated", nan_policy="propagate", compute="float64", prefilter=True):
    """:func:`splinelab.map_coordinates` with dask.

    ``input`` (dask or numpy) is prefiltered once by the certified chunked
    filter; ``coordinates`` is a dask array ``(ndim, ...)`` chunked along
    the points (axis 0 whole), and the result is chunked like them.

    Parameters
    ----------
    input : dask.array.Array or array_like
        The samples.
    coordinates : dask.array.Array or array_like
        Shape ``(input.ndim, ...)``, chunked along the points.
    %(dask_resample)s
    %(dask_tol)s
    %(dask_output)s
    %(dask_tail)s
    %(dask_prefilter)s

    Returns
    -------
    dask.array.Array
        The values, chunked like the points (lazy).

    Raises
    ------
    %(dask_raises)s

    Notes
    -----
    Each chunk reads only the coefficient region its points need (its
    bounding box, computed when the graph is built). Error: within
    ``bound(order, tol, ndim) * max|input|`` (plus rounding) of
    :func:`splinelab.map_coordinates` (module documentation). A coefficient
    that is NaN reaches the outputs whose window holds it, as unchunked.
    ``compute='float64'``: float64 coefficients, float32 results rounded
    once, as :func:`splinelab.map_coordinates`.

    Examples
    --------
    >>> import dask.array as da, numpy as np, splinelab, splinelab.dask
    >>> x = np.random.default_rng(0).uniform(-1, 1, (40, 40))
    >>> at = da.from_array(np.random.default_rng(1).uniform(0, 39, (2, 500)), chunks=(2, 64))
    >>> v = splinelab.dask.map_coordinates(da.from_array(x, chunks=20), at, order=3, mode="mirror").compute()
    >>> bool(np.abs(v - splinelab.map_coordinates(x, at.compute(), order=3, mode="mirror")).max() < 1e-11)
    True
    """
    darr = da.asarray(input)
    at = da.asarray(coordinates)
    if at.ndim < 1 or at.shape[0] != darr.ndim:
        raise ValueError(f"coordinates must have shape ({darr.ndim}, ...), got {at.shape}")
    dtype = _work_dtype(darr, output)
    flat = at.reshape(at.shape[0], -1).rechunk({0: -1}).astype(np.float64)
    parts = dask.compute(*flat.to_delayed().ravel())  # each chunk's points, to find its region
    local = None if compute == "float32" or not prefilter else _local_points(darr, parts, at, order, mode, cval, tol, threads,
                                                             nan_policy, dtype)
    if local is not None:
        return local
    plan = _Plan(darr, order, mode, cval, tol, route, threads, nan_policy, compute, prefilter)
    pieces = [_chunk(plan, np.asarray(p), dtype) for p in parts]
    return da.concatenate(pieces).reshape(at.shape[1:])


def _local_points(darr, parts, at, order, mode, cval, tol, threads, nan_policy, dtype):
    """:func:`map_coordinates` on the local route where it reads less than
    the chunked prefilter (issue 45): one graph computing only the chunks
    under the points' windows; the same bits as ``splinelab.map_coordinates``
    of the same data in memory. None where the chunked route is cheaper."""
    d, mode = _degree(order), _interp_mode(mode)
    pts = np.concatenate([np.asarray(p, dtype=np.float64) for p in parts], axis=1)
    nan_policy = _nan_policy(nan_policy)
    tol = _tol_for(tol, nan_policy, d)
    s = Settings(d, mode, cval, True, tol, nan_policy, threads, False, "float64")
    if darr.dtype.kind not in "biuf" or not np.isfinite(pts).all() or not _local.cheaper(darr.shape, pts, d, mode,
                                                                                          True, tol):
        return None
    values = _local.evaluate_array_like(darr, pts, s, _cval(cval, False), None, dtype)
    return da.from_array(values.reshape(at.shape[1:]), chunks=at.chunks[1:])


@fill
def zoom(input, zoom, order=3, mode="constant", cval=0.0, *, grid_mode=False, tol=DEFAULT_TOL, output=None,
         chunks=None, threads=1, route="truncated", nan_policy="propagate", compute="float64", prefilter=True,
         output_chunks=None):
    """:func:`splinelab.zoom` of a dask array (scipy's output shape and coordinates).

    Parameters
    ----------
    input : dask.array.Array or array_like
        The samples.
    zoom : float or sequence of float
        The factor along every axis, or one per axis.
    %(dask_resample)s
    grid_mode : bool, optional
        As :func:`splinelab.zoom` (default False).
    %(dask_resample_keywords)s

    Returns
    -------
    dask.array.Array
        The resampled array in ``chunks`` (lazy).

    Raises
    ------
    %(dask_raises)s

    Notes
    -----
    Error bound as :func:`map_coordinates`.
    """
    darr = da.asarray(input)
    zooms = _per_axis(zoom, darr.ndim, "zoom")
    out_shape = tuple(int(round(n * z)) for n, z in zip(darr.shape, zooms))
    num, div = np.array(darr.shape), np.array(out_shape)
    if not grid_mode:
        num, div = num - 1, div - 1
    factors = np.divide(num, div, out=np.ones(darr.ndim, dtype=np.float64), where=div != 0)
    axes = _zoom_shift_coordinates(out_shape, zooms=factors, grid_mode=grid_mode)
    return _on_output_grid(darr, out_shape, _either(chunks, output_chunks), _GridPoints(axes), order,
                           mode, cval, tol, route, output, threads, nan_policy, compute, prefilter)


@fill
def shift(input, shift, order=3, mode="constant", cval=0.0, *, tol=DEFAULT_TOL, output=None, chunks=None,
          threads=1, route="truncated", nan_policy="propagate", compute="float64", prefilter=True, output_chunks=None):
    """:func:`splinelab.shift` of a dask array.

    Parameters
    ----------
    input : dask.array.Array or array_like
        The samples.
    shift : float or sequence of float
        The shift along every axis, or one per axis.
    %(dask_resample)s
    %(dask_resample_keywords)s

    Returns
    -------
    dask.array.Array
        The shifted array in ``chunks`` (lazy).

    Raises
    ------
    %(dask_raises)s

    Notes
    -----
    Error bound as :func:`map_coordinates`.
    """
    darr = da.asarray(input)
    shifts = [-s for s in _per_axis(shift, darr.ndim, "shift")]
    axes = _zoom_shift_coordinates(darr.shape, shifts=shifts)
    return _on_output_grid(darr, darr.shape, _either(chunks, output_chunks), _GridPoints(axes), order,
                           mode, cval, tol, route, output, threads, nan_policy, compute, prefilter)


@_dask_image_names(image="input")
@fill
def affine_transform(input, matrix, offset=0.0, output_shape=None, order=3, mode="constant", cval=0.0, *,
                     tol=DEFAULT_TOL, output=None, chunks=None, threads=1, route="truncated", nan_policy="propagate",
                     compute="float64", prefilter=True, output_chunks=None):
    """:func:`splinelab.affine_transform` of a dask array (every matrix form scipy takes).

    Parameters
    ----------
    input : dask.array.Array or array_like
        The samples.
    matrix : ndarray
        As :func:`splinelab.affine_transform`.
    offset : float or sequence of float, optional
        As :func:`splinelab.affine_transform` (default 0.0).
    output_shape : tuple of int, optional
        Defaults to the input's shape.
    %(dask_resample)s
    %(dask_resample_keywords)s

    Returns
    -------
    dask.array.Array
        The transformed array in ``chunks`` (lazy).

    Raises
    ------
    %(dask_raises)s

    Notes
    -----
    Error bound as :func:`map_coordinates`.
    """
    darr = da.asarray(input)
    out_shape = tuple(output_shape) if output_shape is not None else darr.shape
    m, offsets = _affine_parts(matrix, offset, darr.ndim, len(out_shape))
    if m.ndim == 1:
        with np.errstate(divide="ignore", invalid="ignore"):
            grid = _GridPoints(_zoom_shift_coordinates(out_shape, zooms=m, shifts=offsets / m))
    else:
        grid = _AffinePoints(m, offsets)
    return _on_output_grid(darr, out_shape, _either(chunks, output_chunks), grid, order, mode, cval, tol, route,
                           output, threads, nan_policy, compute, prefilter)


@_dask_image_names(input_arr="input")
@fill
def rotate(input, angle, axes=(1, 0), reshape=True, order=3, mode="constant", cval=0.0, *, tol=DEFAULT_TOL,
           output=None, chunks=None, threads=1, route="truncated", nan_policy="propagate", compute="float64",
           prefilter=True, output_chunks=None):
    """:func:`splinelab.rotate` of a dask array (scipy's matrix, centre and output shape).

    Parameters
    ----------
    input : dask.array.Array or array_like
        The samples.
    angle : float
        In degrees.
    axes : tuple of 2 ints, optional
        The plane of the rotation (default ``(1, 0)``).
    reshape : bool, optional
        As :func:`splinelab.rotate` (default True).
    %(dask_resample)s
    %(dask_resample_keywords)s

    Returns
    -------
    dask.array.Array
        The rotated array in ``chunks`` (lazy).

    Raises
    ------
    %(dask_raises)s

    Notes
    -----
    Error bound as :func:`map_coordinates`. Above two dimensions the
    rotation is one N-D affine map, the identity off the plane: at the
    integer coordinates there the N-D spline interpolates, so it equals
    scipy's plane-by-plane rotation within ``bound(order, tol, ndim) *
    max|input|`` (plus rounding).
    """
    darr = da.asarray(input)
    axes, rot, plane_offset, _, out_shape = _rotation(angle, axes, darr.shape, reshape)
    matrix = np.eye(darr.ndim)
    matrix[np.ix_(axes, axes)] = rot
    offset = np.zeros(darr.ndim)
    offset[axes] = plane_offset
    return affine_transform(darr, matrix, offset, out_shape, order, mode, cval, tol=tol,
                            output=output, chunks=_either(chunks, output_chunks), threads=threads, route=route,
                            nan_policy=nan_policy, compute=compute, prefilter=prefilter)
