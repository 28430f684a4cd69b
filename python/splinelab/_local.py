"""The local route (issue 45): values at a few points of a large array from
the samples their windows need, chosen by cost in :func:`map_coordinates`
with no keyword, and the readers of arrays that are not in memory.

The engine (``splinelab::ndimage::local``) groups the points into tiles,
reads each tile's samples with a margin of the certified half-width ``n``
(folded at the edges exactly as each mode extends the samples on the
global route: scipy's 12-sample padding of 'nearest' / 'grid-constant' at
degrees 2-5, 'wrap' as the mirror spline at the folded point, 'constant'
as the mirror spline with ``cval`` outside), prefilters the tile by the
truncated convolution and evaluates its points. With ``tol=None`` the
half-width is certified for ``u * A / 4`` (``A`` the filter's
amplification, ``u`` the unit roundoff): below the global route's own
rounding error. Each coefficient is computed by the same operations
whichever tile holds it, so an ndarray, a memory map, a zarr array, an
HDF5 dataset and a dask array of any chunking give the same bits.

On this route a missing (NaN) sample reaches only the points whose windows
read it, also under ``nan_policy='propagate'`` (the global route makes every
coefficient of every line through it NaN, as scipy); ``'raise'`` refuses
only a missing sample that some window reads.
"""

from __future__ import annotations

import math

import numpy as np

from . import _splinelab as _ext
from ._modes import engine_args

#: "auto" (the default): the route by cost; "local" / "global": forced
#: (tests and benchmarks compare the two routes on the same call).
ROUTE = "auto"

_FLOATS = (np.dtype(np.float64), np.dtype(np.float32))


#: The engine's pricing constants in nanoseconds (``splinelab::ndimage::
#: local::route``): the local route's set-up per call, per point located and
#: per point evaluated, per sample read and per convolution tap; the global
#: route's prefilter per sample and axis and its copy per sample.
_COST = _ext.LOCAL_ROUTE_COST

#: The local route's certified half-width per ``(degree, tol)``, asked of
#: the engine once (:func:`may_be_local`).
_HALF_WIDTH = {}


def may_be_local(shape, k, d, prefilter, tol):
    """Whether the local route can cost less than the global one for ``k``
    points on an array of ``shape`` (degree ``d``, ``tol`` as the call's):
    its floor below the global route's prefilter (or copy) of the whole
    array. The floor (the engine's ``floor_ns``): the set-up, every point
    located and, where there is one, the cheapest box evaluated (a tile of
    edge 1, whose samples reach the certified half-width ``n`` beyond it,
    or without a prefilter one point's support). False decides the global
    route with no call into the engine (the engine's first test in
    ``LocalPlan::new_if_local``, the same formula from the same constants,
    :data:`_COST`; its price of the local route never falls below it).
    Arithmetic on the shape and the count, and ``n`` asked of the engine
    once per ``(d, tol)``."""
    filtered = prefilter and d >= 2
    global_ns = math.prod(shape) * ((_COST["global"] * len(shape) if filtered else 0.0) + _COST["copy"])
    # The set-up and locating alone first: no half-width needed where they decide.
    return _COST["call"] + k * _COST["locate"] < global_ns and floor_ns(len(shape), k, d, filtered, tol) < global_ns


def floor_ns(ndim, k, d, filtered, tol):
    """The local route's floor for ``k`` points (:func:`may_be_local`; the
    engine's ``route::floor_ns``, in its order of operations)."""
    c = _COST
    floor = c["call"] + k * c["locate"]
    if not k:
        return floor
    if not filtered:
        return floor + c["point"] + c["read"] * float(d + 1) ** ndim
    key = (d, tol)
    n = _HALF_WIDTH.get(key)
    if n is None:
        n = _HALF_WIDTH.setdefault(key, _ext.local_half_width(d, tol))
    # route::tile_ns(ndim, d, n, 1).
    b = float(1 + d)
    e = b + 2.0 * n
    outputs = sum(e ** (ndim - j) * b ** j for j in range(1, ndim + 1))
    tile = c["tap"] * float(2 * n + 1) * outputs + c["read"] * e ** ndim
    return floor + c["point"] + tile


def try_map(a, flat, s, cv, deriv):
    """map_coordinates of the real float64/float32 array ``a`` at ``flat``
    (``(ndim, k)``) under the settings ``s`` (``cv`` its ``cval``, a float)
    on the local route, or None where the global route is cheaper (or
    forced by :data:`ROUTE`)."""
    d, mode, prefilter, tol = s.degree, s.mode, s.prefilter, s.tol
    if ROUTE == "global" or a.dtype not in _FLOATS or a.ndim == 0:
        return None
    if ROUTE == "auto" and not may_be_local(a.shape, np.shape(flat)[1], d, prefilter, tol):
        return None
    engine_mode, rule, pad = engine_args(mode, d, prefilter, s.exact_edges)
    run = _ext.local_map_f64 if a.dtype == np.float64 else _ext.local_map_f32
    points = np.ascontiguousarray(np.asarray(flat, dtype=np.float64))
    return run(a, points, d, engine_mode, cv, tol, prefilter, s.threads, deriv, rule, s.nan_policy, pad,
               ROUTE == "local")


_NEEDS = "an array-like needs shape, dtype, ndim and basic-slice __getitem__ (numpy, zarr, h5py and dask arrays have them)"


def is_array_like(x):
    """Whether ``x`` is an array that is not a numpy array but can be read a
    box at a time: it has ``shape``, ``dtype``, ``ndim`` and ``__getitem__``."""
    return not isinstance(x, np.ndarray) and all(hasattr(x, k) for k in ("shape", "dtype", "ndim", "__getitem__"))


def source(input):
    """``input`` as what the local route reads: a numpy array (memory maps
    included, read from their buffer), an array-like read a box at a time,
    or a sequence converted by numpy. Anything else: TypeError naming what
    is needed."""
    if isinstance(input, np.ndarray):
        return input
    if is_array_like(input):
        if np.dtype(input.dtype).kind not in "biuf":
            raise TypeError(f"input must have a real (float, integer or bool) dtype, got {input.dtype}")
        return input
    if isinstance(input, (list, tuple)) or np.isscalar(input):
        return np.asarray(input)
    raise TypeError(f"input of type {type(input).__name__} cannot be read: {_NEEDS}")


#: A box's own cost on the local route of an array-like, in samples read
#: whole and evaluated in memory in the same time: the plan, the Python
#: slice and copy and the reader's call per box. Measured (loaded 2-core
#: machine, boxcost.py of the issue-42 notes, local2-dask.md: linear points on
#: 2000^2): 18 us a box (numpy-backed reader), 27 us (dask), against 5 ns a
#: sample read whole: 3.6e3 and 4.7e3 samples; 10^4 leaves room for the
#: slower calls of h5py and zarr readers.
_BOX = 10**4


def read_whole(src, flat, s):
    """The array-like ``src`` read whole (one basic-slice read, as a numpy
    array) where that costs no more than its windows read a box each on
    the local route, else None: by :data:`ROUTE` ("local": never, "global":
    always), by cost under "auto". The cost of the windows is bounded above
    by ``k (B + W)`` for ``k`` points (:data:`_BOX` per box, one box a
    point, ``W`` the samples of one point's box, :func:`_window`), so an
    array of at most that size is read whole: at most ``B + W`` samples a
    point, never more than the boxes' own bound (a dask block of
    reproject, whose points cover it, costs one ``np.asarray`` as on scipy;
    a few points of a large array still read only their windows). ``s``:
    the call's settings (:class:`splinelab._settings.Settings`)."""
    if ROUTE == "local":
        return None
    if ROUTE == "auto":
        k = flat.shape[1]
        window = _window(src.shape, s.degree, s.mode, s.prefilter, s.tol, s.exact_edges, s.nan_policy)
        if math.prod(src.shape) > k * (_BOX + window):
            return None
    return np.asarray(src[tuple(slice(None) for _ in src.shape)])


def _window(shape, d, mode, prefilter, tol, exact_edges, nan_policy):
    """The samples one isolated point's box reads: its ``d + 1`` samples a
    side, with the prefilter's half-width ``n`` and scipy's pad each side
    where the samples are prefiltered."""
    engine_mode, _, pad = engine_args(mode, d, prefilter, exact_edges)
    n = 0
    if prefilter and d > 1:
        spline = _ext.LocalSplineF64(list(shape), d, engine_mode, 0.0, tol, nan_policy, True, pad, 2**62, True)
        n = spline.truncation()[0]
    return (d + 1 + 2 * (n + pad)) ** len(shape)


def _is_dask(x):
    return type(x).__module__.split(".")[0] == "dask"


def fetch(src, boxes, work):
    """The blocks ``[(first index, samples)]`` of the boxes ``(lo, hi)``, in
    ``work``'s dtype: one ``__getitem__`` per box; for a dask array one
    graph (``dask.compute``) computing only the chunks under the boxes, or,
    where the bounding box holds fewer samples than the boxes and their
    slices' graph work (:data:`_DASK_SLICE` each), that box computed once
    and the boxes cut from it."""
    keys = [tuple(slice(lo, hi) for lo, hi in zip(l, h)) for l, h in boxes]
    if _is_dask(src) and len(keys) > 1 and _size(_bounds(boxes)) <= sum(_size(b) + _DASK_SLICE for b in boxes):
        # Many boxes: one slice, its graph culled once, the boxes cut from
        # it (a slice per box culls the graph per box: 45 s for 10^4 cubic
        # points of a 35x250x150 dask-image spline_filter, scipy 66 ms).
        lo, hi = _bounds(boxes)
        whole = np.asarray(src[tuple(slice(a, b) for a, b in zip(lo, hi))].compute())
        parts = [whole[tuple(slice(k.start - o, k.stop - o) for k, o in zip(key, lo))] for key in keys]
    elif _is_dask(src):
        import dask

        parts = dask.compute(*[src[k] for k in keys]) if keys else []
    else:
        parts = [src[k] for k in keys]
    return [(list(l), np.ascontiguousarray(np.asarray(p), dtype=work)) for (l, _), p in zip(boxes, parts)]


#: A dask slice's own graph work, in samples computed in the same time
#: (measured: 1.6 ms a box in the case above, ~10 ns a sample).
_DASK_SLICE = 10**5


def _bounds(boxes):
    """The bounding box ``(lo, hi)`` of boxes ``[(lo, hi)]``."""
    return [min(b[0][a] for b in boxes) for a in range(len(boxes[0][0]))], \
        [max(b[1][a] for b in boxes) for a in range(len(boxes[0][0]))]


def _size(box):
    """The number of samples in the box ``(lo, hi)``."""
    return math.prod(h - l for l, h in zip(*box))


def evaluate_array_like(src, flat, s, cval, deriv, work):
    """map_coordinates of an array-like on the local route under the
    settings ``s`` (``cval`` checked, a float), computed in float64 and
    returned as ``work`` (float64, or float32 rounded once, as the global
    route): the boxes the windows need fetched (:func:`fetch`: float32
    samples as they are, others as float64) and evaluated; flat values (no
    reflection sign)."""
    d, tol, prefilter = s.degree, s.tol, s.prefilter
    engine_mode, rule, pad = engine_args(s.mode, d, prefilter, s.exact_edges)
    f32 = np.dtype(src.dtype) == np.float32 and np.dtype(work) == np.float32
    cls, read = (_ext.LocalSplineF32, np.float32) if f32 else (_ext.LocalSplineF64, np.float64)
    engine = cls(list(src.shape), d, engine_mode, cval, tol, s.nan_policy, prefilter, pad, 2**62, True)
    points = np.ascontiguousarray(flat, dtype=np.float64)
    fetched = fetch(src, engine.boxes_for_eval(points, rule), read)
    return engine.eval_blocks(list(src.shape), fetched, points, rule, deriv, s.threads).astype(work, copy=False)


def cheaper(shape, flat, d, mode, prefilter, tol, exact_edges=False):
    """Whether the local route costs less than the global one for the
    points ``flat`` (``(ndim, k)``) on an array of ``shape`` (the engine's
    estimate: samples read and convolved against the whole array's prefilter)."""
    engine_mode, rule, pad = engine_args(mode, d, prefilter, exact_edges)
    points = np.ascontiguousarray(flat, dtype=np.float64)
    local_ns, global_ns, _, _ = _ext.local_route_cost(list(shape), points, d, engine_mode, tol, prefilter, rule, pad)
    return local_ns < global_ns
