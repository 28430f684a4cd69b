"""The accessor's dask route (``splinelab.xarray``, issue 51, phase 1).

The data arrives with the interpolated (grid) axes first, any vectorised
axes next and the carried axes last; the result is a lazy dask array of the
points' shape followed by the carried axes. No interpolated axis is
rechunked into one chunk unless no window is certified (some ``mode=``
cases), and then only those axes, block by block of the carried axes:

- every grid axis in one chunk: each block of the carried axes is
  interpolated on its own (``blockwise``; each output block reads its input
  block only);
- "linear", "nearest", "slinear", "pchip" with a chunked grid axis: the
  points are grouped by the input chunks their windows touch (the cell, and
  for "pchip" two samples each side, which is all scipy's PCHIP reads), and
  each group reads only the union of its points' windows;
- "cubic", "quintic" with a chunked grid axis: along each chunked axis a
  point's value is ``sum_i w_i(q) y_i``, the cardinal weights computed from
  the coordinates alone (one banded solve, the extension's
  ``grid_cardinal_weights``); each point reads the window
  outside which its weights sum to at most the tolerance, so the result is
  within ``tol * max|data|`` of the whole-grid spline (certified by the
  weights themselves, up to the rounding of their solve), and the unchunked
  axes are interpolated exactly per window. (``_WINDOWS = False`` keeps the
  separable route testable: the unchunked axes first, block by block, each
  block read once, then each point's whole lines along the chunked axes;
  where every grid axis is chunked, whole lines per carried block.)
- ``mode=`` with a chunked grid axis: certified windows (:func:`_mode_windows`:
  each group of points reads its regions with the prefilter's certified
  overlap, filtered as splinelab.dask's output tasks filter theirs); whole
  lines along the grid axes per block of the carried axes for degree 0,
  'grid-wrap', and scipy's padded 'nearest' and 'grid-constant'.
"""

from __future__ import annotations

import itertools
import string

import numpy as np

from . import _splinelab as _ext


def is_dask(data) -> bool:
    """Whether ``data`` is a dask array."""
    return type(data).__module__.split(".")[0] == "dask" and hasattr(data, "chunks")


def array_module(data):
    """``dask.array`` for a dask array, else numpy (the functions
    elementwise conversions take from it)."""
    if is_dask(data):
        import dask.array as da
        return da
    return np


def interp(data, grid, new_f, rdims, vdims, pdims, nb, opts, dims):
    """The lazy result, shape ``vshape + pshape + carried shape``."""
    import dask.array as da

    from .xarray import _points

    ng, nv = len(grid), len(vdims)
    if nv:
        vshape = data.shape[ng:ng + nv]
        outs = []
        for vindex in np.ndindex(*vshape):
            block = data[(slice(None),) * ng + vindex]
            xi = _points(new_f, rdims, vdims, vindex)
            outs.append(_interp_points(block, grid, xi, opts, dims))
        pshape = tuple(new_f[0].shape[rdims.index(d)] for d in pdims)
        return da.stack(outs).reshape(vshape + pshape + data.shape[ng + nv:])
    xi = _points(new_f, rdims, vdims, ())
    pshape = new_f[0].shape if new_f else ()
    out = _interp_points(data, grid, xi, opts, dims)
    target = pshape + data.shape[ng:]
    return out if out.shape == target else out.reshape(target)


#: The not-a-knot splines on chunked axes read certified windows (below);
#: False: the separable route that reads every chunk once (kept testable).
_WINDOWS = True
#: The default of ``tol`` for the windows: the certified bound on the
#: distance from the whole-grid spline, relative to max|data|.
WINDOW_TOL = 1e-14


def _letters(n, start=0):
    return string.ascii_letters[start:start + n]


def _interp_points(data, grid, xi, opts, dims):
    """The values at points ``xi`` (P, ngrid): (P, carried...)."""
    ng = len(grid)
    chunked = [a for a in range(ng) if data.numblocks[a] > 1]
    if not chunked:
        return _whole_grid(data, grid, xi, opts, dims)
    if opts.mode is None and opts.method in ("linear", "nearest", "slinear", "pchip"):
        return _windows(data, grid, xi, opts, dims)
    unchunked = [a for a in range(ng) if a not in chunked]
    if opts.mode is not None and _mode_windows_apply(grid, xi, opts):
        return _mode_windows(data, grid, xi, opts, chunked)
    if opts.mode is None and _WINDOWS:
        return _spline_windows(data, grid, xi, opts, dims, chunked, unchunked)
    if opts.mode is None and unchunked:
        return _separable(data, grid, xi, opts, dims, chunked, unchunked)
    # whole lines along the grid axes, block by block of the carried axes
    chunks = {a: -1 for a in range(ng)}
    chunks.update({a: "auto" for a in range(ng, data.ndim)})
    return _whole_grid(data.rechunk(chunks), grid, xi, opts, dims)


def _whole_grid(data, grid, xi, opts, dims):
    """Every grid axis in one chunk: one task per block of the carried axes."""
    import dask.array as da

    from .xarray import _evaluate, _result_dtype

    ng, nb = len(grid), data.ndim - len(grid)
    gi, bi = _letters(ng), _letters(nb, ng)
    p = "Z"

    def block(values):
        return _evaluate(grid, np.asarray(values), xi, opts, dims)

    return da.blockwise(block, p + bi, data, gi + bi, new_axes={p: len(xi)}, concatenate=True,
                        dtype=_result_dtype(data.dtype, opts), meta=np.empty((0,) * (1 + nb)))


def _cells(g, x, halo, minimum):
    """The window [lo, hi) of samples a point's value reads along one axis."""
    n = len(g)
    x = np.where(np.isnan(x), g[0], x)
    i = np.clip(np.searchsorted(g, x, side="right") - 1, 0, max(n - 2, 0))
    lo = np.maximum(i - halo, 0)
    hi = np.minimum(i + 2 + halo, n)
    short = hi - lo < minimum
    lo = np.where(short, np.maximum(np.minimum(lo, n - minimum), 0), lo)
    hi = np.where(short, np.minimum(lo + minimum, n), hi)
    return lo, hi


def _windows(data, grid, xi, opts, dims):
    """The local methods on chunked grid axes: points grouped by the input
    chunks their windows touch; each group reads the union of its windows."""
    import dask.array as da

    from .xarray import _HALO, METHODS, _evaluate

    ng = len(grid)
    P = len(xi)
    lo = np.empty((P, ng), dtype=np.intp)
    hi = np.empty((P, ng), dtype=np.intp)
    for a, g in enumerate(grid):
        lo[:, a], hi[:, a] = _cells(g, xi[:, a], _HALO[opts.method], min(METHODS[opts.method], len(g)))
    order, starts, ends = _chunk_groups(data, [(a, lo[:, a], hi[:, a]) for a in range(ng)])
    nb = data.ndim - ng
    gi, bi = _letters(ng), _letters(nb, ng)
    parts = []
    for s, e in zip(starts, ends):
        members = order[s:e]
        wlo, whi = lo[members].min(axis=0), hi[members].max(axis=0)
        window = data[tuple(slice(a, b) for a, b in zip(wlo, whi))]
        sub = [g[a:b] for g, a, b in zip(grid, wlo, whi)]
        pts = xi[members]

        def block(values, sub=sub, pts=pts):
            out = _evaluate(sub, np.asarray(values), pts, opts, dims)
            return out

        part = da.blockwise(block, "Z" + bi, window, gi + bi, new_axes={"Z": len(members)}, concatenate=True,
                            dtype=_dtype(data, opts), meta=np.empty((0,) * (1 + nb)),
                            name=_name("splinelab-window", window, pts, opts))
        parts.append(part)
    out = da.concatenate(parts, axis=0)
    inverse = np.empty(P, dtype=np.intp)
    inverse[order] = np.arange(P)
    if not np.array_equal(order, np.arange(P)):
        out = out[inverse]
    return _refill(out, grid, xi, opts, dims)


def _name(prefix, window, points, opts, *more):
    """A task name from what the task computes (dask would otherwise
    tokenize the closure by pickling it, milliseconds a group)."""
    from dask.base import tokenize
    return f"{prefix}-{tokenize(window.name, points, opts.method, opts.below, opts.above, opts.tol, *more)}"


def _dtype(data, opts):
    from .xarray import _result_dtype
    return _result_dtype(data.dtype, opts)


def _refill(out, grid, xi, opts, dims):
    """Windows end inside the grid: a point beyond a window's end is beyond
    the grid's (the windows hold the cells of their points), so the fill a
    window applied is the grid's; bounds_error was checked there too. Here
    only the check that happens before any reading."""
    from .xarray import _apply_fill
    if opts.bounds_error:
        _apply_fill(np.empty((len(xi), 0)), grid, xi, opts, dims)
    return out


def _separable(data, grid, xi, opts, dims, chunked, unchunked):
    """The not-a-knot splines with chunked grid axes: the tensor-product
    spline is separable, so the unchunked axes are interpolated first (per
    input block, to one value per point and sample of the chunked axes),
    then each point's lines along the chunked axes (whole, in one task per
    block of the carried axes)."""
    import dask.array as da

    from .xarray import _apply_fill, _raw, _result_dtype

    ng, nb = len(grid), data.ndim - len(grid)
    P = len(xi)
    gu = [grid[a] for a in unchunked]
    gc = [grid[a] for a in chunked]
    xu, xc = xi[:, unchunked], xi[:, chunked]
    perm = unchunked + chunked + list(range(ng, data.ndim))
    moved = data.transpose(perm)
    nu, nc = len(unchunked), len(chunked)
    ui, ci, bi = _letters(nu), _letters(nc, nu), _letters(nb, nu + nc)
    dtype = _result_dtype(data.dtype, opts)

    def stage1(values):
        return _raw(gu, np.asarray(values), xu, opts)   # (P, chunked block..., carried block...)

    reduced = da.blockwise(stage1, "Z" + ci + bi, moved, ui + ci + bi, new_axes={"Z": P}, concatenate=True,
                           dtype=dtype, meta=np.empty((0,) * (1 + nc + nb)))
    chunks = {0: "auto"}
    chunks.update({1 + a: -1 for a in range(nc)})
    chunks.update({1 + nc + a: "auto" for a in range(nb)})
    reduced = reduced.rechunk(chunks)

    def stage2(values, block_info=None):
        start = block_info[0]["array-location"][0][0] if block_info else 0
        values = np.asarray(values)
        out = np.empty((values.shape[0],) + values.shape[1 + nc:], dtype=dtype)
        for j in range(values.shape[0]):
            out[j] = _raw(gc, values[j], xc[start + j:start + j + 1], opts)[0]
        return out

    out = da.map_blocks(stage2, reduced, drop_axis=list(range(1, 1 + nc)), dtype=dtype,
                        meta=np.empty((0,) * (1 + nb)))
    _apply_fill(np.empty((P, 0)), grid, xi, opts, dims)   # bounds_error before any reading
    return out.map_blocks(_fill_block, grid=grid, xi=xi, opts=opts, dims=dims, dtype=dtype)


def _fill_block(values, grid, xi, opts, dims, nan=None, block_info=None):
    from .xarray import _apply_fill
    start, stop = block_info[0]["array-location"][0] if block_info else (0, len(values))
    out = _apply_fill(np.array(values), grid, xi[start:stop], opts, dims)
    if nan is not None:
        out[nan[start:stop]] = np.nan
    return out


# ---------------------------------------------------------------- certified windows


def cardinal_weights(x, k, q):
    """The not-a-knot spline's cardinal weights: ``W[j] @ y`` is the value at
    ``q[j]`` of the degree-``k`` not-a-knot spline through ``(x, y)`` (the end
    pieces extended outside), for every ``y``.

    ``W = B(q) A^{-1}`` with ``A`` the collocation matrix (banded, bandwidth
    ``k``) and ``B(q)`` the B-spline values at ``q``: row ``j`` is one banded
    solve with ``A^T`` (the extension's ``grid_cardinal_weights``, the LU of
    the grid spline's own solves). Returns ``(len(q), len(x))``.
    """
    return _ext.grid_cardinal_weights(np.ascontiguousarray(x, dtype=np.float64), int(k),
                                      np.ascontiguousarray(q, dtype=np.float64))


def _tails(w):
    """For each row of weights, the tails outside ``[lo, hi)`` as the
    windows grow: left[i] = sum |w[:i]|, right[i] = sum |w[i:]|, each summed
    from its own end (the small terms first)."""
    a = np.abs(w)
    left = np.concatenate([np.zeros((len(w), 1)), np.cumsum(a, axis=1)], axis=1)
    right = np.concatenate([np.cumsum(a[:, ::-1], axis=1)[:, ::-1], np.zeros((len(w), 1))], axis=1)
    return left, right


def _chunk_groups(data, spans):
    """The points grouped by the input chunks their windows touch: ``spans``
    holds ``(axis, lo, hi)`` per grouped axis (per point, the window
    ``[lo, hi)``). Returns ``(order, starts, ends)``: group ``i`` is
    ``order[starts[i]:ends[i]]``."""
    P = len(spans[0][1])
    keys = np.empty((P, 2 * len(spans)), dtype=np.intp)
    for c, (a, lo, hi) in enumerate(spans):
        bounds = np.cumsum((0,) + data.chunks[a])
        keys[:, 2 * c] = np.searchsorted(bounds, lo, side="right") - 1
        keys[:, 2 * c + 1] = np.searchsorted(bounds, hi - 1, side="right") - 1
    _, group = np.unique(keys, axis=0, return_inverse=True)
    group = group.ravel()
    order = np.argsort(group, kind="stable")
    starts = np.flatnonzero(np.r_[True, np.diff(group[order]) != 0])
    return order, starts, np.r_[starts[1:], P]


def _weight_norms(x, k, q, batch=256):
    """``‖w(q_j)‖₁`` of the cardinal weights at each point, a batch of
    points at a time (``len(q) × len(x)`` weights at once would not fit
    for many points on a long axis)."""
    return np.concatenate([np.abs(cardinal_weights(x, k, q[s:s + batch])).sum(axis=1)
                           for s in range(0, len(q), batch)] or [np.zeros(0)])


def _windows_of(x, k, q, tol, batch=256):
    """Per point, the smallest window ``[lo, hi)`` of samples whose
    cardinal weights outside sum to at most ``tol / 2`` on each side (in
    absolute value), the weights inside, the tails left outside on the left
    and on the right, and the whole sum (the Lebesgue function at the
    point)."""
    P = len(q)
    lo = np.empty(P, dtype=np.intp)
    hi = np.empty(P, dtype=np.intp)
    ltail, rtail, norm = np.empty(P), np.empty(P), np.empty(P)
    weights = []
    for s in range(0, P, batch):
        w = cardinal_weights(x, k, q[s:s + batch])
        left, right = _tails(w)
        for r in range(len(w)):
            a, b = _cut(left[r], right[r], tol)
            lo[s + r], hi[s + r] = a, b
            ltail[s + r], rtail[s + r], norm[s + r] = left[r][a], right[r][b], left[r][-1]
            weights.append(w[r, a:b].copy())
    return lo, hi, weights, ltail, rtail, norm


def _cut(left, right, tol):
    """The window ``[a, b)`` from one row's tails (:func:`_tails`): ``a``
    the last index with ``left[a] <= tol/2``, ``b`` the first with
    ``right[b] <= tol/2``."""
    a = max(int(np.searchsorted(left, tol / 2, side="right")) - 1, 0)
    b = int(np.searchsorted(-right, -tol / 2, side="left"))
    return a, min(max(b, a + 1), len(left) - 1)


def _narrowed(lo, weights, ltail, rtail, tol):
    """The windows of a larger ``tol`` from those of a smaller one, without
    a second solve: inside a window the tails continue the same running
    sums (the same additions in the same order as :func:`_tails`, so the
    same windows as solving again)."""
    lo2, hi2, kept = np.empty_like(lo), np.empty_like(lo), []
    for j, w in enumerate(weights):
        a = np.abs(w)
        left = np.cumsum(np.r_[ltail[j], a])
        right = np.cumsum(np.r_[rtail[j], a[::-1]])[::-1]
        s, e = _cut(left, right, tol)
        lo2[j], hi2[j] = lo[j] + s, lo[j] + e
        kept.append(w[s:e])
    return lo2, hi2, kept


#: The 1-norm of a chunked axis' cardinal weights assumed when its windows
#: are first cut (not-a-knot cubic and quintic stay well below it on the
#: grids seen in practice); a larger one cuts them again from a new solve.
_NORM_GUESS = 8.0


def _chunked_windows(grid, k, distinct, chunked, unchunked, tol, P):
    """Per chunked axis, each point's window and weights for ``tol_a = tol
    / (len(chunked) * max prod N)`` (:func:`_spline_windows`). One solve per
    chunked axis gives both its norms and its windows: they are cut for the
    smallest ``tol_a`` the norms allow (:data:`_NORM_GUESS`), then narrowed
    to ``tol_a`` once the norms are known."""
    norms = np.ones(P)
    for a in unchunked:
        uq, inv = distinct[a]
        norms *= _weight_norms(grid[a], k, uq)[inv.ravel()]
    floor = float(tol / (len(chunked) * norms.max() * _NORM_GUESS ** len(chunked)))
    cut = {}
    for a in chunked:
        uq, inv = distinct[a]
        cut[a] = _windows_of(grid[a], k, uq, floor)
        norms *= cut[a][5][inv.ravel()]
    tol_a = float(tol / (len(chunked) * norms.max()))
    wins = {}
    for a in chunked:
        uq, inv = distinct[a]
        lo, _, w, ltail, rtail, _ = cut[a]
        if tol_a >= floor:
            lo, hi, w = _narrowed(lo, w, ltail, rtail, tol_a)
        else:  # norms beyond the guess: cut again, at tol_a
            lo, hi, w, _, _, _ = _windows_of(grid[a], k, uq, tol_a)
        inv = inv.ravel()
        wins[a] = (lo[inv], hi[inv], [w[i] for i in inv])
    return wins


def _spline_windows(data, grid, xi, opts, dims, chunked, unchunked):
    """The not-a-knot splines with chunked grid axes, reading certified windows.

    Along each chunked axis a point's value is ``sum_i w_i(q) y_i`` (the
    cardinal weights, from the coordinates alone); the window keeps the
    samples whose weights outside it sum to at most ``tol_a``, and the
    truncated sum differs from the whole-grid spline by at most

        (prod_c N_c - prod_c (N_c - tail_c)) * prod_u N_u * max|data|,

    N the weights' 1-norms (the Lebesgue function at the point) over the
    chunked (c) and unchunked (u) axes; ``tol_a = tol / (len(c) * prod N)``
    makes that at most ``tol * max|data|`` (up to the rounding of the banded
    solve that gives the weights). The unchunked axes are interpolated
    exactly (the whole spline, per window). Points are grouped by the input
    chunks their windows touch; each group reads the union of its windows.
    """
    import dask.array as da

    from .xarray import _apply_fill, _raw, _result_dtype

    k = {"cubic": 3, "quintic": 5}[opts.method]
    tol = WINDOW_TOL if opts.tol is None else float(opts.tol)
    ng, P = len(grid), len(xi)
    safe = np.where(np.isnan(xi), np.array([g[0] for g in grid]), xi)
    # per axis, the distinct coordinates only (an outer grid has few)
    distinct = {a: np.unique(safe[:, a], return_inverse=True) for a in range(ng)}
    wins = _chunked_windows(grid, k, distinct, chunked, unchunked, tol, P)
    order, starts, ends = _chunk_groups(data, [(a, wins[a][0], wins[a][1]) for a in chunked])
    nb = data.ndim - ng
    gi, bi = _letters(ng), _letters(nb, ng)
    dtype = _result_dtype(data.dtype, opts)
    gu = [grid[a] for a in unchunked]
    parts = []
    for s, e in zip(starts, ends):
        members = order[s:e]
        ulo = {a: int(wins[a][0][members].min()) for a in chunked}
        uhi = {a: int(wins[a][1][members].max()) for a in chunked}
        window = data[tuple(slice(ulo[a], uhi[a]) if a in chunked else slice(None) for a in range(ng))]
        # each point's weights along each chunked axis, on the union window
        wts = []
        for j in members:
            per_axis = []
            for a in chunked:
                w = np.zeros(uhi[a] - ulo[a])
                off = wins[a][0][j] - ulo[a]
                w[off:off + len(wins[a][2][j])] = wins[a][2][j]
                per_axis.append(w)
            wts.append(per_axis)
        pts_u = safe[members][:, unchunked]

        def block(values, wts=wts, pts_u=pts_u):
            v = np.asarray(values)
            if unchunked:   # the exact spline along the unchunked axes: (Pg, window_c..., carried...)
                v = np.moveaxis(v, unchunked, list(range(len(unchunked))))
                u = _raw(gu, v, pts_u, opts)
            else:
                u = None
            out = np.empty((len(wts),) + v.shape[ng:], dtype=dtype)
            for j, per_axis in enumerate(wts):
                r = u[j] if u is not None else v
                for w in per_axis:   # contract the chunked axes one by one (each now first)
                    r = np.tensordot(w, r, axes=(0, 0))
                out[j] = r
            return out

        parts.append(da.blockwise(block, "Z" + bi, window, gi + bi, new_axes={"Z": len(members)}, concatenate=True,
                                  dtype=dtype, meta=np.empty((0,) * (1 + nb)),
                                  name=_name("splinelab-spline-window", window, pts_u, opts, *itertools.chain(*wts))))
    out = da.concatenate(parts, axis=0)
    inverse = np.empty(P, dtype=np.intp)
    inverse[order] = np.arange(P)
    if not np.array_equal(order, np.arange(P)):
        out = out[inverse]
    _apply_fill(np.empty((P, 0)), grid, xi, opts, dims)   # bounds_error before any reading
    nan = np.isnan(xi).any(axis=1)
    return out.map_blocks(_fill_block, grid=grid, xi=np.where(nan[:, None], np.nan, xi), opts=opts, dims=dims,
                          nan=nan, dtype=dtype)


# ---------------------------------------------------------------- mode= windows


def _mode_rules(grid, opts):
    """splinelab.dask's reading rules for ``mode=`` on the index grid (cval
    NaN, as :func:`splinelab.xarray._evaluate_mode`)."""
    from . import dask as sld
    from .xarray import _MODE_ORDER
    shape = [len(g) for g in grid]
    return sld._Rules(_MODE_ORDER[opts.method], opts.mode, np.nan, "float64", shape, shape, True)


def _mode_windows_apply(grid, xi, opts):
    """Whether ``mode=`` reads windows on chunked axes: a spline of degree 1
    or more, finite points, and a mode whose windows splinelab.dask reads
    as given (not the periodic filter of 'grid-wrap', not scipy's padding of
    'nearest' and 'grid-constant' at degrees 2 to 5); else whole lines."""
    from . import dask as sld
    rules = _mode_rules(grid, opts)
    return (rules.d >= 1 and not rules.pad and np.isfinite(xi).all()
            and sld._filter_mode(opts.mode, False) in sld._NUMPY_PAD)


def _mode_windows(data, grid, xi, opts, chunked):
    """``mode=`` with chunked grid axes, reading certified windows: each
    group of points (by the input chunks their windows touch) reads the
    samples of its points' regions with the certified overlap along the
    chunked axes (the whole of the others) and prefilters them as
    splinelab.dask's output tasks do (zeros beyond, the array's edges padded
    by the mode's extension): within ``splinelab.dask.bound(degree, tol,
    ngrid) * max|data|`` of the whole-line result (``tol`` default 1e-12).
    A non-finite sample makes its whole column NaN, as on whole lines."""
    import dask.array as da

    from . import dask as sld
    from .xarray import _index_points
    ng, nb = len(grid), data.ndim - len(grid)
    rules = _mode_rules(grid, opts)
    x, mask = rules.prepared(_index_points(grid, xi))
    tol = sld.DEFAULT_TOL if opts.tol is None else float(opts.tol)
    fused = sld._Fused(rules.d, opts.mode, sld.depth(rules.d, tol), 1, rules.extent) if rules.d > 1 else None
    spans = []
    for a in chunked:  # each point's region, with the overlap it is filtered with (as an output task's)
        lo, hi = rules.spans(a, x[a], x[a])
        spans.append((a, *(fused.widened(a, lo, hi) if fused is not None else (lo, hi))))
    order, starts, ends = _chunk_groups(data, spans)
    # scipy's pattern where a prefilter runs: a non-finite sample, its column NaN
    flag = (~da.isfinite(data)).any(axis=tuple(range(ng))) if fused and data.dtype.kind in "fc" else None
    gi, bi = _letters(ng), _letters(nb, ng)
    dtype = np.dtype(np.float64)
    parts = []
    for s, e in zip(starts, ends):
        members = order[s:e]
        reach = [(0, n) for n in rules.extent]
        for a, lo, hi in spans:
            reach[a] = (int(lo[members].min()), int(hi[members].max()))
        window = data[tuple(slice(a, b) for a, b in reach)]
        pts = x[:, members]
        pmask = None if mask is None else mask[members]

        def block(values, missing=None, pts=pts, pmask=pmask, reach=reach):
            v = np.asarray(values, dtype=np.float64) if fused is None else fused.coefficients(values, reach, False)
            if missing is not None:
                v = np.where(np.asarray(missing), np.nan, v)
            cols = v.reshape(v.shape[:ng] + (-1,))
            out = np.empty((pts.shape[1], cols.shape[-1]), dtype=dtype)
            lo = [a for a, _ in reach]
            for c in range(cols.shape[-1]):
                out[:, c] = sld._evaluate_region(cols[..., c], lo, pts.copy(), pmask, rules, dtype)
            return out.reshape((pts.shape[1],) + v.shape[ng:])

        args = (window, gi + bi) + ((flag, bi) if flag is not None else ())
        parts.append(da.blockwise(block, "Z" + bi, *args, new_axes={"Z": len(members)}, concatenate=True,
                                  dtype=dtype, meta=np.empty((0,) * (1 + nb)),
                                  name=_name("splinelab-mode-window", window, pts, opts, reach)))
    out = da.concatenate(parts, axis=0)
    inverse = np.empty(len(xi), dtype=np.intp)
    inverse[order] = np.arange(len(xi))
    return out if np.array_equal(order, np.arange(len(xi))) else out[inverse]
