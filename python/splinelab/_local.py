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

import bisect
import itertools
import math
import numbers
import os
from concurrent.futures import ThreadPoolExecutor

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


def in_place_pays(shape, k, d):
    """Whether ``k`` points of degree ``d`` (0 or 1) on an in-memory array
    of ``shape`` are read in place by the engine (``map_samples_in_place``:
    nothing proportional to the array) rather than through its padded copy
    (the engine's ``route::in_place_pays``, the same formula from the same
    constants, :data:`_COST`). Then no window of the local route reads
    less."""
    taps = float(d + 1) ** len(shape)
    return d <= 1 and k * taps * _COST["in_place_tap"] < math.prod(shape) * _COST["copy"]


def half_width(d, tol):
    """The certified half-width of the local route's prefilter for degree
    ``d`` (2 or more) and ``tol`` (the same for every mode and
    ``nan_policy``), asked of the engine once per ``(d, tol)``."""
    n = _HALF_WIDTH.get((d, tol))
    return _HALF_WIDTH.setdefault((d, tol), _ext.local_half_width(d, tol)) if n is None else n


def floor_ns(ndim, k, d, filtered, tol):
    """The local route's floor for ``k`` points (:func:`may_be_local`; the
    engine's ``route::floor_ns``, in its order of operations)."""
    c = _COST
    floor = c["call"] + k * c["locate"]
    if not k:
        return floor
    if not filtered:
        return floor + c["point"] + c["read"] * float(d + 1) ** ndim
    n = half_width(d, tol)
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
        window = _window(src.shape, s)
        if math.prod(src.shape) > k * (_BOX + window):
            return None
    return np.asarray(src[tuple(slice(None) for _ in src.shape)])


def _window(shape, s):
    """The samples one isolated point's box reads under the settings ``s``:
    its ``d + 1`` samples a side, with the prefilter's half-width ``n``
    (:func:`half_width`) and scipy's pad each side where the samples are
    prefiltered."""
    _, _, pad = engine_args(s.mode, s.degree, s.prefilter, s.exact_edges)
    n = half_width(s.degree, s.tol) if s.prefilter and s.degree > 1 else 0
    return (s.degree + 1 + 2 * (n + pad)) ** len(shape)


def _is_dask(x):
    return type(x).__module__.split(".")[0] == "dask"


def fetch(src, boxes, work, threads=None):
    """The blocks ``[(first index, samples)]`` of the boxes ``(lo, hi)``, in
    ``work``'s dtype. Where ``src`` exposes its chunk grid
    (:func:`chunk_grid`), each stored chunk the boxes touch is read once
    (:func:`_fetch_by_chunk`); else one read per box (:func:`_read`).
    ``threads``: the call's (None: one per core), for the readers that
    take them."""
    grid = chunk_grid(src) if boxes else None
    if grid is not None:
        if _is_dask(src):
            src, grid = _dask_reader(src, boxes, grid)
        return _fetch_by_chunk(src, boxes, grid, work, threads)
    keys = [tuple(slice(lo, hi) for lo, hi in zip(l, h)) for l, h in boxes]
    parts = _read(src, keys, threads)
    return [(list(l), np.ascontiguousarray(np.asarray(p), dtype=work)) for (l, _), p in zip(boxes, parts)]


def chunk_grid(src):
    """The edges ``[0, ..., n]`` of the stored chunks of ``src`` on each
    axis, where it exposes them: ``chunks`` as one edge per axis (zarr,
    h5py: None when contiguous) or as the sizes on each axis (dask,
    xarray); else None."""
    try:
        chunks = src.chunks
    except (AttributeError, NotImplementedError):  # zarr 3 without a regular grid
        return None
    if not isinstance(chunks, (tuple, list)) or len(chunks) != len(src.shape):
        return None
    grid = [_edges(c, int(n)) for c, n in zip(chunks, src.shape)]
    return None if any(e is None for e in grid) else grid


def _edges(c, n):
    """One axis' chunk edges from its chunk edge ``c`` or its sizes ``c``
    (summing to ``n``); None for anything else (unknown dask sizes)."""
    if isinstance(c, numbers.Integral) and not isinstance(c, bool) and c > 0:
        return [*range(0, n, int(c)), n]
    if isinstance(c, (tuple, list)) and all(isinstance(k, numbers.Integral) and k >= 0 for k in c) and sum(c) == n:
        return [0, *itertools.accumulate(int(k) for k in c)]
    return None


#: The bytes of chunk parts read at a time (at least one part): the bound
#: on what a call holds beyond its boxes.
_GROUP_BYTES = 64 * 2**20


def _fetch_by_chunk(src, boxes, grid, work, threads):
    """:func:`fetch` reading each touched chunk once: the part of it the
    boxes cover, in groups of :data:`_GROUP_BYTES` ordered by chunk, each
    part copied into the boxes it serves and released. Held at once: the
    boxes (as one read per box holds them) and one group. The same samples
    as one read per box, so the same bits."""
    out = [np.empty([h - l for l, h in zip(lo, hi)], work) for lo, hi in boxes]
    itemsize = np.dtype(src.dtype).itemsize
    for group in _groups(_chunk_parts(boxes, grid), itemsize):
        parts = _read(src, [key for key, _ in group], threads)
        for (_, uses), part in zip(group, parts):
            part = np.asarray(part)
            for i, into, sub in uses:
                out[i][into] = part[sub]
    return [(list(lo), o) for (lo, _), o in zip(boxes, out)]


def _dask_reader(darr, boxes, grid):
    """What to read for the boxes of the dask array ``darr`` (chunk edges
    ``grid``) and its chunk grid: where every block the boxes touch is
    ``getter(leaf, the block's slices)`` of one array-like ``leaf`` (what
    ``dask.array.from_zarr`` and ``from_array`` build) and dask would run
    them in this process, ``leaf`` itself with its own stored chunks (dask's
    where it exposes none): the same samples without a dask graph per call,
    about 1 ms of this process' time per chunk part (issue 51's 100 points of
    the 12000^2 zarr array: 82 parts). Else ``darr`` and ``grid`` (any other
    graph, a lock to honour, or a distributed scheduler: its workers read).
    The leaf comes as a :class:`_Leaf`, read as dask's scheduler read it."""
    found = _from_array_leaf(darr, {c for box in boxes for c in _touched_by(box, grid)}, grid)
    if found is None:
        return darr, grid
    leaf = _Leaf(*found)
    own = chunk_grid(found[0])
    return leaf, grid if own is None else own


class _Leaf:
    """The array-like under a plain dask graph (:func:`_dask_reader`), read
    as dask's scheduler read it (:func:`_read`): on threads under the
    threaded one (``threaded``: dask calls its lock-free getters from
    several threads at once, so xarray's lazily indexed zarr variables, for
    one, decode in parallel as they did), one read after another under the
    synchronous one."""

    def __init__(self, a, threaded):
        self.a, self.threaded = a, threaded
        self.shape, self.dtype, self.ndim = tuple(a.shape), a.dtype, len(a.shape)

    def __getitem__(self, key):
        return self.a[key]


def _from_array_leaf(darr, blocks, grid):
    """The array-like every one of ``blocks`` (chunk indices of ``darr``)
    is a plain read of and whether dask's scheduler is the threaded one, or
    None (see :func:`_dask_reader`). dask's task objects are read, so a dask
    that changes them takes its graph (None)."""
    import dask.base
    import dask.local
    import dask.threaded

    try:
        from dask._task_spec import DataNode, Task, TaskRef
        from dask.array.core import getter, getter_inline, getter_nofancy
    except ImportError:
        return None
    # The local schedulers run the getters here; distributed's workers may
    # see a store this process does not (and its reads belong to them).
    scheduler = dask.base.get_scheduler(collections=[darr])
    if scheduler not in (dask.threaded.get, dask.local.get_sync):
        return None
    graph = darr.__dask_graph__()
    if not hasattr(graph, "cull"):
        return None
    keys = [(darr.name, *c) for c in blocks]
    tasks = dict(graph.cull(set(keys)))
    leaf = None
    for key in keys:
        task = tasks.get(key)
        if (type(task) is not Task or task.func not in (getter, getter_inline, getter_nofancy)
                or len(task.args) != 2 or task.kwargs.get("lock") or type(task.args[1]) is not DataNode):
            return None
        ref, index = task.args
        if type(ref) is TaskRef:
            ref = tasks.get(ref.key)
        if type(ref) is DataNode:
            ref = ref.value
        want = tuple(slice(e[i], e[i + 1]) for e, i in zip(grid, key[1:]))
        if (leaf is not None and ref is not leaf) or not _same_slices(index.value, want):
            return None
        leaf = ref
    ok = (leaf is not None and (isinstance(leaf, np.ndarray) or is_array_like(leaf))
          and tuple(leaf.shape) == darr.shape and np.dtype(leaf.dtype) == darr.dtype)
    return (leaf, scheduler is dask.threaded.get) if ok else None


def _same_slices(got, want):
    """Whether the key ``got`` is the slices ``want`` (steps None or 1)."""
    return (isinstance(got, tuple) and len(got) == len(want)
            and all(isinstance(g, slice) and g.step in (None, 1) and (g.start or 0, g.stop) == (w.start, w.stop)
                    for g, w in zip(got, want)))


def _touched_by(box, grid):
    """The chunk indices the box ``(lo, hi)`` touches."""
    lo, hi = box
    return itertools.product(*[range(bisect.bisect_right(e, l) - 1, bisect.bisect_left(e, h))
                               for e, l, h in zip(grid, lo, hi)])


def _chunk_parts(boxes, grid):
    """Per touched chunk, in C order of chunk index: the key of the part of
    it the boxes cover (their bounding box within it) and its uses
    ``(box index, slices into the box, slices into the part)``."""
    touched = {}
    for i, box in enumerate(boxes):
        for c in _touched_by(box, grid):
            touched.setdefault(c, []).append(i)
    parts = []
    for c in sorted(touched):
        cuts = {i: _cut(boxes[i], [(e[j], e[j + 1]) for e, j in zip(grid, c)]) for i in touched[c]}
        first = [min(cut[0][a] for cut in cuts.values()) for a in range(len(c))]
        last = [max(cut[1][a] for cut in cuts.values()) for a in range(len(c))]
        uses = [(i, _slices(l, h, boxes[i][0]), _slices(l, h, first)) for i, (l, h) in cuts.items()]
        parts.append((_slices(first, last, [0] * len(c)), uses))
    return parts


def _cut(box, chunk):
    """The part ``(lo, hi)`` of ``box`` within the chunk ``[(start, stop)]``."""
    return [max(l, s) for l, (s, _) in zip(box[0], chunk)], [min(h, t) for h, (_, t) in zip(box[1], chunk)]


def _slices(lo, hi, origin):
    """The box ``lo..hi`` as slices of an array whose first index is ``origin``."""
    return tuple(slice(l - o, h - o) for l, h, o in zip(lo, hi, origin))


def _groups(parts, itemsize):
    """``parts`` in consecutive groups of at most :data:`_GROUP_BYTES`
    (a larger part alone)."""
    group, size = [], 0
    for part in parts:
        n = itemsize * math.prod(s.stop - s.start for s in part[0])
        if group and size + n > _GROUP_BYTES:
            yield group
            group, size = [], 0
        group.append(part)
        size += n
    if group:
        yield group


#: The readers that may be called from several threads at once (zarr's
#: decompression releases the GIL: the chunks of a group decode in parallel).
#: Not h5py: its calls hold its one library lock through the decompression,
#: so a pool only adds its own cost (60 parts of 500^2 gzip chunks, 2-core
#: machine at load 3.9, fastest of 11: 0.40 s serial, 0.43 s on 2 threads).
_THREAD_SAFE = ("zarr",)


def _read(src, keys, threads):
    """``src[key]`` for each of ``keys``: a dask array's in one graph
    (``dask.compute``: each chunk under them computed once), a zarr
    array's (and a :class:`_Leaf` that dask read on threads) on ``threads``
    threads (None: one per core), others' one call after another."""
    if _is_dask(src):
        import dask

        return list(dask.compute(*[src[k] for k in keys])) if keys else []
    workers = min(len(keys), threads or os.cpu_count() or 1)
    pooled = src.threaded if isinstance(src, _Leaf) else type(src).__module__.split(".")[0] in _THREAD_SAFE
    if workers > 1 and pooled:
        with ThreadPoolExecutor(workers) as pool:
            return list(pool.map(src.__getitem__, keys))
    return [src[k] for k in keys]


def engine(shape, s, cval, samples, cache_bytes=2**62, one_call=True):
    """The local spline of the settings ``s`` (``cval`` checked, a float)
    on an array of ``shape`` whose samples are read as ``samples``
    (float32: its float32 class; else float64), and its point rule."""
    engine_mode, rule, pad = engine_args(s.mode, s.degree, s.prefilter, s.exact_edges)
    cls = _ext.LocalSplineF32 if np.dtype(samples) == np.float32 else _ext.LocalSplineF64
    return cls(list(shape), s.degree, engine_mode, cval, s.tol, s.nan_policy, s.prefilter, pad, cache_bytes,
               one_call), rule


def evaluate_array_like(src, flat, s, cval, deriv, work):
    """map_coordinates of an array-like on the local route under the
    settings ``s`` (``cval`` checked, a float), computed in float64 and
    returned as ``work`` (float64, or float32 rounded once, as the global
    route): the boxes the windows need fetched (:func:`fetch`: float32
    samples as they are, others as float64) and evaluated; flat values (no
    reflection sign)."""
    f32 = np.dtype(src.dtype) == np.float32 and np.dtype(work) == np.float32
    read = np.float32 if f32 else np.float64
    spline, rule = engine(src.shape, s, cval, read)
    points = np.ascontiguousarray(flat, dtype=np.float64)
    fetched = fetch(src, spline.boxes_for_eval(points, rule), read, s.threads)
    return spline.eval_blocks(list(src.shape), fetched, points, rule, deriv, s.threads).astype(work, copy=False)


def cheaper(shape, flat, d, mode, prefilter, tol, exact_edges=False):
    """Whether the local route costs less than the global one for the
    points ``flat`` (``(ndim, k)``) on an array of ``shape`` (the engine's
    estimate: samples read and convolved against the whole array's prefilter)."""
    engine_mode, rule, pad = engine_args(mode, d, prefilter, exact_edges)
    points = np.ascontiguousarray(flat, dtype=np.float64)
    local_ns, global_ns, _, _ = _ext.local_route_cost(list(shape), points, d, engine_mode, tol, prefilter, rule, pad)
    return local_ns < global_ns
