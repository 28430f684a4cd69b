"""The accessor's dask route (``splinelab.xarray``, issue 51, phase 1).

The data arrives with the interpolated (grid) axes first, any vectorised
axes next and the carried axes last; the result is a lazy dask array of the
points' shape followed by the carried axes. No interpolated axis is
rechunked into one chunk unless the method's value at a point depends on
the whole axis and no window is certified yet (the not-a-knot splines and
``mode=``), and then only that axis, block by block of the carried axes:

- every grid axis in one chunk: each block of the carried axes is
  interpolated on its own (``blockwise``; each output block reads its input
  block only);
- "linear", "nearest", "slinear", "pchip" with a chunked grid axis: the
  points are grouped by the input chunks their windows touch (the cell, and
  for "pchip" two samples each side, which is all scipy's PCHIP reads), and
  each group reads only the union of its points' windows;
- "cubic", "quintic" with a chunked grid axis: the spline is separable, so
  the unchunked grid axes are interpolated first block by block (each input
  block read once, reduced to one value per point per sample of the
  chunked axes), then the chunked axes' whole lines of those reduced values
  are interpolated point by point; where every grid axis is chunked, the
  data's whole lines along them are read per block of the carried axes.
"""

from __future__ import annotations

import string

import numpy as np


def is_dask(data) -> bool:
    """Whether ``data`` is a dask array."""
    return type(data).__module__.split(".")[0] == "dask" and hasattr(data, "chunks")


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
    keys = np.empty((P, 2 * ng), dtype=np.intp)
    for a, g in enumerate(grid):
        lo[:, a], hi[:, a] = _cells(g, xi[:, a], _HALO[opts.method], min(METHODS[opts.method], len(g)))
        bounds = np.cumsum((0,) + data.chunks[a])
        keys[:, 2 * a] = np.searchsorted(bounds, lo[:, a], side="right") - 1
        keys[:, 2 * a + 1] = np.searchsorted(bounds, hi[:, a] - 1, side="right") - 1
    _, group = np.unique(keys, axis=0, return_inverse=True)
    group = group.ravel()
    order = np.argsort(group, kind="stable")
    starts = np.flatnonzero(np.r_[True, np.diff(group[order]) != 0])
    ends = np.r_[starts[1:], P]
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
                            dtype=_dtype(data, opts), meta=np.empty((0,) * (1 + nb)))
        parts.append(part)
    out = da.concatenate(parts, axis=0)
    inverse = np.empty(P, dtype=np.intp)
    inverse[order] = np.arange(P)
    if not np.array_equal(order, np.arange(P)):
        out = out[inverse]
    return _refill(out, grid, xi, opts, dims)


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


def _fill_block(values, grid, xi, opts, dims, block_info=None):
    from .xarray import _apply_fill
    start, stop = block_info[0]["array-location"][0] if block_info else (0, len(values))
    return _apply_fill(np.array(values), grid, xi[start:stop], opts, dims)
