"""The accessor's windowed splines and its dask routes (``splinelab.xarray``).

**Windowed sums, one computation for every route.** Along an axis with
nodes x₀ … xₙ₋₁ the degree-k spline's value at q is ``sum_i w_i(q) y_i``:
for "slinear" the two B-spline values of q's interval (scipy's ``BSpline``
interval rule, ``x_l <= q < x_{l+1}``), for "cubic" and "quintic" the
not-a-knot spline's cardinal weights ``w(q) = A^{-T} b(q)`` (one banded
solve with the collocation matrix' transpose, the extension's
``grid_cardinal_weights``), which decay geometrically away from q and are
cut to the window outside which they sum to at most ``tol_a``
(:func:`axis_windows`). On several axes the sums nest, the first axis
innermost. :func:`weighted_sum` adds each window's terms one by one, first
to last, starting from zero, the same expression for every element, so an
element's bits depend on its point, the data and ``tol`` only: not on which
other points share the call's batch, whether the points form an orthogonal
grid (:func:`weighted_sum` without ``inv``) or not, or which samples a
block holds around the window. The in-memory route and every dask route
call it, so a result does not depend on the chunking.

The truncated sum is within ``tol * max|data|`` of the whole-grid spline
(:func:`axis_windows`: the weights left outside a point's windows have
1-norm at most ``tol`` divided by the product of the weights' 1-norms), up
to the rounding of the weights' solve. NaN stays in the windows that hold
it; along one axis a non-finite sample makes its whole line NaN, as
scipy's ``interp1d`` (``xarray.DataArray.interp``'s routine) does
(:func:`line_flags`).

**Dask.** The data arrives with the interpolated (grid) axes first, any
vectorised axes next and the carried axes last; the result is a lazy dask
array of the points' shape followed by the carried axes. No interpolated
axis is rechunked into one chunk unless the new coordinates are themselves
lazy (then every interpolated axis is, as xarray does), or no window is
certified (some ``mode=`` cases):

- every grid axis in one chunk: each block of the carried axes is
  interpolated on its own (``blockwise``; each output block reads its input
  block only);
- "linear", "nearest", "pchip" with a chunked grid axis: the points are
  grouped by the input chunks their windows touch (the cell, and for
  "pchip" two samples each side, which is all scipy's PCHIP reads), and
  each group reads only the union of its points' windows;
- "slinear", "cubic", "quintic" with a chunked grid axis: the same
  grouping by the windows of :func:`axis_windows`; each group's task
  computes :func:`weighted_sum` on the union of its windows;
- dask-backed new coordinates: every grid axis rechunked into one chunk,
  and each block of the vectorised and carried axes interpolated with its
  block of the new coordinates (nothing computed at the call);
- ``mode=`` with a chunked grid axis: certified windows (:func:`_mode_windows`:
  each group of points reads its regions with the prefilter's certified
  overlap, filtered as splinelab.dask's output tasks filter theirs); whole
  lines along the grid axes per block of the carried axes for degree 0,
  'grid-wrap', and scipy's padded 'nearest' and 'grid-constant'. (``mode=``
  on windows is within ``splinelab.dask.bound`` of the whole-line result,
  not bit for bit.)
"""

from __future__ import annotations

import functools
import math
import string
from typing import NamedTuple

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


#: The spline degree of each method computed by windowed sums.
DEGREE = {"slinear": 1, "cubic": 3, "quintic": 5}
#: The default of ``tol`` for the cubic and quintic windows: the certified
#: bound on the distance from the whole-grid spline, relative to max|data|.
WINDOW_TOL = 1e-14


# ---------------------------------------------------------------- windows


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


class Windows(NamedTuple):
    """One axis' windows for a set of coordinates: coordinate ``j`` reads
    samples ``lo[j] … lo[j] + length[j] - 1`` with weights
    ``weights[j, :length[j]]`` (zero beyond)."""

    lo: np.ndarray
    length: np.ndarray
    weights: np.ndarray


def _packed(lo, hi, weights):
    length = (hi - lo).astype(np.intp)
    packed = np.zeros((len(lo), int(length.max(initial=1))))
    for j, w in enumerate(weights):
        packed[j, :len(w)] = w
    return Windows(np.asarray(lo, dtype=np.intp), length, packed)


def _linear_windows(g, q):
    """"slinear": the degree-1 B-spline values of each coordinate's
    interval (scipy's ``BSpline``: ``g[l] <= q < g[l+1]``, the last interval
    at the last node and beyond, the first below), as scipy's de Boor step
    computes them: ``(g[l+1] - q) / h`` and ``(q - g[l]) / h``."""
    lo = np.clip(np.searchsorted(g, q, side="right") - 1, 0, len(g) - 2)
    h = g[lo + 1] - g[lo]
    return Windows(lo.astype(np.intp), np.full(len(q), 2, dtype=np.intp),
                   np.stack([(g[lo + 1] - q) / h, (q - g[lo]) / h], axis=1))


#: The product of the axes' weight 1-norms assumed, per axis, when the
#: windows are first cut (not-a-knot cubic and quintic stay well below it
#: on the grids seen in practice); a larger one cuts them again from a new
#: solve.
_NORM_GUESS = 8.0


def axis_windows(grid, k, distinct, tol):
    """Per axis, the :class:`Windows` of its distinct coordinates
    ``distinct[a]`` for the degree-``k`` spline.

    "slinear" (k = 1): the interval's two B-spline values. Cubic and
    quintic: the cardinal weights cut so that each side left outside sums
    to at most ``tol_a / 2``, ``tol_a = tol / (ngrid * prod_a N_a)``,
    ``N_a`` the largest 1-norm of axis a's weights over its coordinates
    (the Lebesgue function). A point's nested sum then differs from the
    whole-grid spline's by at most

        (prod_a N_a - prod_a (N_a - tau_a)) * max|data|
        <= sum_a tau_a prod_(b != a) N_b * max|data| <= tol * max|data|,

    ``tau_a <= tol_a`` the weight left outside along axis a (up to the
    rounding of the banded solve that gives the weights). One solve per
    axis gives both the norms and the windows: they are cut for
    ``tol / (ngrid * _NORM_GUESS**ngrid)``, then narrowed to ``tol_a`` once
    the norms are known (or cut again where the norms exceed the guess).
    The windows depend on the axes, the coordinates' set and ``tol`` only.
    """
    if k == 1:
        return [_linear_windows(g, q) for g, q in zip(grid, distinct)]
    ng = len(grid)
    floor = tol / (ng * _NORM_GUESS ** ng)
    cut = [_windows_of(g, k, q, floor) for g, q in zip(grid, distinct)]
    norms = math.prod(float(c[5].max(initial=1.0)) for c in cut)
    tol_a = tol / (ng * norms)
    out = []
    for g, q, (lo, _, w, ltail, rtail, _) in zip(grid, distinct, cut):
        if tol_a >= floor:
            lo, hi, w = _narrowed(lo, w, ltail, rtail, tol_a)
        else:  # norms beyond the guess: cut again, at tol_a
            lo, hi, w, _, _, _ = _windows_of(g, k, q, tol_a)
        out.append(_packed(lo, hi, w))
    return out


def safe_points(grid, xi, opts):
    """The points whose windows are computed: per axis a coordinate that is
    NaN, or out of range on a side whose fill is a value (the point is
    filled whatever it reads), becomes the axis' first node, so that it
    neither widens the other points' windows nor reads far. An axis'
    replacement depends on that axis' coordinate only, so the coordinates
    of an orthogonal grid stay an orthogonal grid."""
    safe = np.array(xi, dtype=np.float64, copy=True)
    for a, g in enumerate(grid):
        x = safe[:, a]
        bad = np.isnan(x)
        if not isinstance(opts.below, str):
            bad |= x < g[0]
        if not isinstance(opts.above, str):
            bad |= x > g[-1]
        x[bad] = g[0]
    return safe


def point_windows(grid, xi, opts):
    """The windows of points ``xi`` (P, ngrid): per axis the
    :class:`Windows` of its distinct (safe) coordinates, and per axis each
    point's index into them."""
    safe = safe_points(grid, xi, opts)
    distinct, inv = [], []
    for a in range(len(grid)):
        u, i = np.unique(safe[:, a], return_inverse=True)
        distinct.append(u)
        inv.append(i.ravel())
    return axis_windows(grid, DEGREE[opts.method], distinct, _tol(opts)), inv


def _tol(opts):
    return WINDOW_TOL if opts.tol is None else float(opts.tol)


#: The cardinal weights' decay per sample on uniform nodes: the root of
#: modulus below 1 nearest 1 of the B-spline's Euler-Frobenius polynomial
#: (cubic 2 - sqrt(3); quintic the larger of its two).
_DECAY = {3: 2.0 - 3.0 ** 0.5, 5: 0.4305753470999738}


def _taps(k, n, tol, ng):
    """A window's length estimated before any solve: both sides down to
    ``tol / (16 ngrid)`` at the uniform grid's decay, plus the support."""
    return min(n, 2 * math.ceil(math.log(tol / (16 * ng)) / math.log(_DECAY[k])) + k + 1)


def use_windows(sizes, k, counts, points, columns, outer, tol):
    """Whether "cubic" and "quintic" are windowed sums (else the exact
    whole-grid spline, :class:`splinelab.RegularGridInterpolator`'s): where
    the windows cost less than the exact solve, by a count of operations
    from the grid's ``sizes``, the new coordinates' ``counts`` per axis,
    ``points``, the carried ``columns`` and whether the points are an
    orthogonal grid. Windows: 10 per cardinal weight (one O(n) solve per
    coordinate) and 3 per term of the sums; exact: a banded solve of
    ``k + 1`` per sample and axis, and ``(k + 1)^ngrid`` per point. Few new
    coordinates on a large grid take windows (and on dask read only them);
    many (a resampling) the exact solve (and on dask whole lines along the
    interpolated axes). Sizes and counts only: the same answer for every
    chunking, and before any coordinate is read."""
    ng = len(sizes)
    taps = [_taps(k, n, tol, ng) for n in sizes]
    if outer:
        sums, before = 0, 1
        for a in range(ng):
            before *= counts[a]
            sums += before * math.prod(sizes[a + 1:]) * taps[a]
    else:
        sums = points * math.prod(taps)
    windows = 10 * sum(c * n for c, n in zip(counts, sizes)) + 3 * sums * columns
    exact = (math.prod(sizes) * ng * (k + 1) + points * (k + 1) ** ng) * columns
    return windows <= exact


# ---------------------------------------------------------------- sums


def _accumulate(acc, w, taps, keep):
    """One term of every window's sum: ``acc + w * taps`` where the window
    has that term (``keep``), ``acc`` unchanged beyond its end. The one
    expression every route evaluates, element by element."""
    return np.where(keep, acc + w * taps, acc)


def _on_axis(v, axis, ndim):
    """A per-coordinate vector shaped to broadcast along ``axis``."""
    shape = [1] * ndim
    shape[axis] = -1
    return v.reshape(shape)


def weighted_sum(values, wins, inv=None, offsets=None, batch_elements=1 << 20):
    """The nested windowed sums of ``values`` (the grid axes first, then any
    trailing axes), the first axis innermost, each window's terms added
    first to last from zero (:func:`_accumulate`).

    Without ``inv``: on the orthogonal grid of the windows' coordinates, an
    array ``(len(wins[0].lo), ..., trailing...)``, one axis contracted after
    the other. With ``inv`` (per axis each point's index into ``wins[a]``):
    at the points, ``(P, trailing...)``, each point's windows gathered (in
    batches of about ``batch_elements`` elements) and contracted in the same
    order. ``offsets``: where ``values`` starts along each grid axis (a
    block read around the windows). Every element is the same expression of
    the same numbers either way.
    """
    ng = len(wins)
    offsets = [0] * ng if offsets is None else offsets
    dtype = np.result_type(values.dtype, np.float64)
    if inv is None:
        r = values
        for a, win in enumerate(wins):
            lo = win.lo - offsets[a]
            if len(lo) <= win.weights.shape[1]:
                # few coordinates: each one's window summed on its own, by
                # slices (the same terms in the same order: _accumulate keeps
                # acc beyond a window's end)
                parts = []
                for j in range(len(lo)):
                    acc = np.zeros(r.shape[:a] + r.shape[a + 1:], dtype=dtype)
                    for t in range(int(win.length[j])):
                        acc = acc + win.weights[j, t] * r[(slice(None),) * a + (lo[j] + t,)]
                    parts.append(acc)
                r = np.stack(parts, axis=a) if parts else np.zeros(r.shape[:a] + (0,) + r.shape[a + 1:], dtype)
                continue
            acc = np.zeros(r.shape[:a] + (len(lo),) + r.shape[a + 1:], dtype=dtype)
            for t in range(win.weights.shape[1]):
                taps = np.take(r, lo + np.minimum(t, win.length - 1), axis=a)
                acc = _accumulate(acc, _on_axis(win.weights[:, t], a, r.ndim), taps,
                                  _on_axis(t < win.length, a, r.ndim))
            r = acc
        return r
    P = len(inv[0]) if ng else 1
    trailing = values.shape[ng:]
    out = np.empty((P,) + trailing, dtype=dtype)
    spans = [int(w.length.max(initial=1)) for w in wins]
    per_point = math.prod(spans) * max(math.prod(trailing), 1)
    step = max(1, batch_elements // per_point)
    for s in range(0, P, step):
        members = slice(s, min(s + step, P))
        B = members.stop - members.start
        idx, wts, keep = [], [], []
        for a, win in enumerate(wins):
            j = inv[a][members]
            T = int(win.length[j].max(initial=1))
            t = np.arange(T)
            length = win.length[j][:, None]
            shape = [B] + [1] * ng
            shape[1 + a] = T
            idx.append((win.lo[j][:, None] - offsets[a] + np.minimum(t, length - 1)).reshape(shape))
            wts.append(win.weights[j, :T])
            keep.append(t < length)
        r = values[tuple(idx)] if ng else values[None]
        for a in range(ng):
            acc = np.zeros(r.shape[:1] + r.shape[2:], dtype=dtype)
            extra = (1,) * (r.ndim - 2)
            for t in range(r.shape[1]):
                acc = _accumulate(acc, wts[a][:, t].reshape((B,) + extra), r[:, t], keep[a][:, t].reshape((B,) + extra))
            r = acc
        out[members] = r
    return out


def line_flags(values, ng):
    """Along one axis: per line (trailing position), whether it holds a
    non-finite sample (scipy's ``interp1d`` then gives NaN everywhere)."""
    if values.dtype.kind not in "fc":
        return np.zeros(values.shape[ng:], dtype=bool)
    return ~np.isfinite(values).all(axis=tuple(range(ng)))


def spline_values(grid, values, xi, opts, outer=None, flags=None):
    """"slinear", "cubic", "quintic" at points ``xi`` (P, ngrid), extrapolated
    (fills are applied after): ``(P, trailing...)``. ``outer``: the points
    are the orthogonal grid of these per-axis coordinates (C order), summed
    axis by axis; else point by point: the same bits. Points with a NaN
    coordinate are NaN; along one axis the lines ``flags`` marks (by default
    :func:`line_flags` of ``values``) are NaN (cubic and quintic)."""
    values = np.asarray(values)
    values = values.astype(np.result_type(values.dtype, np.float64), copy=False)
    ng = len(grid)
    if outer is not None:
        safe = [safe_points([g], np.asarray(q, dtype=np.float64)[:, None], opts)[:, 0] for g, q in zip(grid, outer)]
        distinct, inv = zip(*(np.unique(q, return_inverse=True) for q in safe))
        wins = axis_windows(grid, DEGREE[opts.method], list(distinct), _tol(opts))
        out = weighted_sum(values, wins)
        for a, i in enumerate(inv):   # back from the distinct coordinates to the given ones (copies)
            out = np.take(out, i.ravel(), axis=a)
        out = out.reshape((-1,) + values.shape[ng:])
    else:
        wins, inv = point_windows(grid, xi, opts)
        out = weighted_sum(values, wins, inv)
    return _spline_nan(out, xi, opts, values, ng, flags)


def _spline_nan(out, xi, opts, values, ng, flags):
    nan = np.isnan(xi).any(axis=1)
    if nan.any():
        out[nan] = np.nan
    if opts.one_dim and DEGREE[opts.method] > 1:
        flags = line_flags(values, ng) if flags is None else np.asarray(flags)
        if flags.any():
            out[:, flags] = np.nan
    return out


# ---------------------------------------------------------------- dask


def interp(data, grid, new_f, rdims, vdims, pdims, nb, opts, dims, outer=None):
    """The lazy result, shape ``vshape + pshape + carried shape``; the new
    coordinates ``new_f`` are numpy arrays (broadcast to ``rdims``)."""
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
    out = _interp_points(data, grid, xi, opts, dims, outer)
    target = pshape + data.shape[ng:]
    return out if out.shape == target else out.reshape(target)


def interp_lazy(data, grid, new_lazy, rdims, vdims, pdims, opts, dims):
    """Dask-backed new coordinates: nothing is computed at the call. Every
    grid axis in one chunk and the points' axes in one chunk; each block of
    the vectorised and carried axes is the in-memory computation of its
    data block at its block of the new coordinates (``new_lazy``: dask or
    numpy arrays, float64, broadcast to ``rdims``). Shape ``vshape + pshape
    + carried shape``."""
    import dask.array as da

    from .xarray import _result_dtype

    ng, nv = len(grid), len(vdims)
    nb = data.ndim - ng - nv
    if not is_dask(data):
        data = da.from_array(data, chunks=data.shape) if data.size else da.asarray(data)
    chunks = {a: -1 for a in range(ng)}
    chunks.update({a: "auto" for a in range(ng, data.ndim)})
    data = data.rechunk(chunks, method=_RECHUNK)
    order = vdims + pdims
    perm = [rdims.index(d) for d in order]
    coords = []
    for n in new_lazy:
        n = da.asarray(n).transpose(perm)
        coords.append(n.rechunk({nv + i: -1 for i in range(len(pdims))}, method=_RECHUNK))
    gi, vi = _letters(ng), _letters(nv, ng)
    pi, bi = _letters(len(pdims), ng + nv), _letters(nb, ng + nv + len(pdims))
    dtype = _result_dtype(data.dtype, opts)

    block = functools.partial(_lazy_block, grid=grid, order=order, vdims=vdims, pdims=pdims, opts=opts, dims=dims)
    args = [data, gi + vi + bi]
    for c in coords:
        args += [c, vi + pi]
    return da.blockwise(block, vi + pi + bi, *args, concatenate=True, dtype=dtype,
                        meta=np.empty((0,) * (nv + len(pdims) + nb), dtype=dtype))


def _lazy_block(values, *cs, grid, order, vdims, pdims, opts, dims):
    """:func:`interp_lazy`'s task: a data block at its block of the new
    coordinates (module-level, so a graph pickles without cloudpickle)."""
    from .xarray import _interp_numpy

    values, cs = np.asarray(values), [np.asarray(c) for c in cs]
    out = _interp_numpy(values, grid, cs, order, vdims, pdims, opts, dims)
    return out.reshape(cs[0].shape + values.shape[len(grid) + len(vdims):])


#: dask's rechunking by tasks: its peer-to-peer method (distributed's default
#: for large rechunks) cancelled the whole-line graphs written to zarr on a
#: LocalCluster ("lost dependencies", python/bench/cluster.py timeaxis).
_RECHUNK = "tasks"


def _letters(n, start=0):
    return string.ascii_letters[start:start + n]


def _interp_points(data, grid, xi, opts, dims, outer=None):
    """The values at points ``xi`` (P, ngrid): (P, carried...)."""
    ng = len(grid)
    chunked = [a for a in range(ng) if data.numblocks[a] > 1]
    if not chunked:
        return _whole_grid(data, grid, xi, opts, dims, outer)
    if opts.mode is None and opts.method in DEGREE and opts.windows:
        return _weighted_windows(data, grid, xi, opts, dims, chunked)
    if opts.mode is None and opts.method not in DEGREE:
        return _windows(data, grid, xi, opts, dims)
    if opts.mode is not None and _mode_windows_apply(grid, xi, opts):
        return _mode_windows(data, grid, xi, opts, chunked)
    # whole lines along the grid axes, block by block of the carried axes
    # (the exact spline, or mode= without certified windows)
    chunks = {a: -1 for a in range(ng)}
    chunks.update({a: "auto" for a in range(ng, data.ndim)})
    return _whole_grid(data.rechunk(chunks, method=_RECHUNK), grid, xi, opts, dims)


def _whole_grid(data, grid, xi, opts, dims, outer=None):
    """Every grid axis in one chunk: one task per block of the carried axes."""
    import dask.array as da

    from .xarray import _result_dtype

    ng, nb = len(grid), data.ndim - len(grid)
    gi, bi = _letters(ng), _letters(nb, ng)
    p = "Z"
    block = functools.partial(_whole_grid_block, grid=grid, xi=xi, opts=opts, dims=dims, outer=outer)
    return da.blockwise(block, p + bi, data, gi + bi, new_axes={p: len(xi)}, concatenate=True,
                        dtype=_result_dtype(data.dtype, opts), meta=np.empty((0,) * (1 + nb)))


def _whole_grid_block(values, grid, xi, opts, dims, outer):
    """:func:`_whole_grid`'s task: every point of ``xi`` on one block of the
    carried axes."""
    from .xarray import _evaluate

    ng = len(grid)
    values = np.asarray(values)
    cols = values.reshape(values.shape[:ng] + (-1,))
    step = max(1, _COLUMN_BYTES // (8 * max(math.prod(values.shape[:ng]), 1)))
    if cols.shape[-1] <= step:
        return _evaluate(grid, values, xi, opts, dims, outer)
    # a few columns at a time (the same bits: every route's numbers are
    # column by column), so a large block's working memory stays small
    parts = [_evaluate(grid, cols[..., s:s + step], xi, opts, dims, outer) for s in range(0, cols.shape[-1], step)]
    return np.concatenate(parts, axis=-1).reshape((len(xi),) + values.shape[ng:])


#: The grid values (as float64) a whole-grid task interpolates at once.
_COLUMN_BYTES = 16 << 20


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
    """"linear", "nearest", "pchip" on chunked grid axes: points grouped by
    the input chunks their windows touch; each group reads the union of its
    windows (the cells, which hold every sample these methods read)."""
    from .xarray import _HALO, METHODS

    ng = len(grid)
    P = len(xi)
    lo = np.empty((P, ng), dtype=np.intp)
    hi = np.empty((P, ng), dtype=np.intp)
    for a, g in enumerate(grid):
        lo[:, a], hi[:, a] = _cells(g, xi[:, a], _HALO[opts.method], min(METHODS[opts.method], len(g)))

    task = functools.partial(_window_task, grid=grid, xi=xi, opts=opts, dims=dims)
    out = _grouped(data, ng, [(a, lo[:, a], hi[:, a]) for a in range(ng)], task, opts, "splinelab-window", xi)
    return _refill(out, grid, xi, opts, dims)


def _window_task(values, members, box, grid, xi, opts, dims):
    """:func:`_windows`' task: the points ``members`` on the samples ``box``."""
    from .xarray import _evaluate

    sub = [g[a:b] for g, (a, b) in zip(grid, box)]
    return _evaluate(sub, values, xi[members], opts, dims)


def _weighted_windows(data, grid, xi, opts, dims, chunked):
    """"slinear", "cubic", "quintic" on chunked grid axes: each point's
    windows (:func:`point_windows`, computed from the coordinates before any
    reading), the points grouped by the input chunks their windows touch
    along the chunked axes; each group's task reads the union of its
    windows (along every grid axis) and computes :func:`weighted_sum` on it,
    the in-memory route's numbers to the bit. Along one axis the lines'
    non-finite flags (one streaming pass over the data, in the same graph)
    make whole lines NaN, as in memory."""
    from .xarray import _apply_fill

    ng = len(grid)
    wins, inv = point_windows(grid, xi, opts)
    lo = [w.lo[i] for w, i in zip(wins, inv)]
    hi = [w.lo[i] + w.length[i] for w, i in zip(wins, inv)]
    flags = None
    if opts.one_dim and DEGREE[opts.method] > 1 and data.dtype.kind in "fc":
        import dask.array as da
        flags = (~da.isfinite(data)).any(axis=tuple(range(ng)))

    task = functools.partial(_spline_window_task, wins=wins, inv=inv, xi=xi, opts=opts, ng=ng)
    out = _grouped(data, ng, [(a, lo[a], hi[a]) for a in chunked], task, opts, "splinelab-spline-window", xi,
                   reach=[(a, lo[a], hi[a]) for a in range(ng)], flags=flags)
    _apply_fill(np.empty((len(xi), 0)), grid, xi, opts, dims)   # bounds_error before any reading
    return out.map_blocks(_fill_block, grid=grid, xi=xi, opts=opts, dims=dims, dtype=out.dtype)


def _spline_window_task(values, members, box, flag=None, *, wins, inv, xi, opts, ng):
    """:func:`_weighted_windows`' task: the weighted sums of the points
    ``members`` on the samples ``box``."""
    v = values.astype(np.result_type(values.dtype, np.float64), copy=False)
    out = weighted_sum(v, wins, [i[members] for i in inv], [a for a, _ in box])
    return _spline_nan(out, xi[members], opts, v, ng, flag)


def _grouped(data, ng, spans, task, opts, prefix, xi, reach=None, flags=None):
    """Points grouped by the input chunks their windows touch (``spans``:
    per grouped axis, each point's window ``[lo, hi)``); each group is one
    task ``task(values, members, box)`` on the union of its points' windows
    along the axes of ``reach`` (default ``spans``; the whole of the other
    grid axes), ``box`` its ``(start, stop)`` per grid axis, and ``flags``
    (a dask array over the carried axes) passed as ``flag``. The parts in
    the points' order, shape ``(P, carried...)``."""
    import dask.array as da

    P = len(xi)
    nb = data.ndim - ng
    reach = spans if reach is None else reach
    order, starts, ends = _chunk_groups(data, spans)
    gi, bi = _letters(ng), _letters(nb, ng)
    dtype = _dtype(data, opts)
    parts = []
    for s, e in zip(starts, ends):
        members = order[s:e]
        box = [(0, n) for n in data.shape[:ng]]
        for a, lo, hi in reach:
            box[a] = (int(lo[members].min()), int(hi[members].max()))
        window = data[tuple(slice(a, b) for a, b in box)]

        block = functools.partial(_group_block, task=task, members=members, box=box)

        args = (window, gi + bi) + ((flags, bi) if flags is not None else ())
        parts.append(da.blockwise(block, "Z" + bi, *args, new_axes={"Z": len(members)}, concatenate=True,
                                  dtype=dtype, meta=np.empty((0,) * (1 + nb), dtype=dtype),
                                  name=_name(prefix, window, xi[members], opts, box)))
    out = da.concatenate(parts, axis=0)
    inverse = np.empty(P, dtype=np.intp)
    inverse[order] = np.arange(P)
    return out if np.array_equal(order, np.arange(P)) else out[inverse]


def _group_block(values, flag=None, *, task, members, box):
    """:func:`_grouped`'s task: ``task`` on one group's window."""
    kw = {} if flag is None else {"flag": np.asarray(flag)}
    return task(np.asarray(values), members, box, **kw)


def _name(prefix, window, points, opts, *more):
    """A task name from what the task computes (dask would otherwise
    tokenize the closure by pickling it, milliseconds a group)."""
    from dask.base import tokenize
    token = tokenize(window.name, points, opts.method, opts.below, opts.above, opts.tol, opts.one_dim, *more)
    return f"{prefix}-{token}"


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


def _fill_block(values, grid, xi, opts, dims, block_info=None):
    from .xarray import _apply_fill
    start, stop = block_info[0]["array-location"][0] if block_info else (0, len(values))
    return _apply_fill(np.array(values), grid, xi[start:stop], opts, dims)


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

        block = functools.partial(_mode_window_block, pts=pts, pmask=pmask, reach=reach, fused=fused, rules=rules,
                                  ng=ng)

        args = (window, gi + bi) + ((flag, bi) if flag is not None else ())
        parts.append(da.blockwise(block, "Z" + bi, *args, new_axes={"Z": len(members)}, concatenate=True,
                                  dtype=dtype, meta=np.empty((0,) * (1 + nb)),
                                  name=_name("splinelab-mode-window", window, pts, opts, reach)))
    out = da.concatenate(parts, axis=0)
    inverse = np.empty(len(xi), dtype=np.intp)
    inverse[order] = np.arange(len(xi))
    return out if np.array_equal(order, np.arange(len(xi))) else out[inverse]


def _mode_window_block(values, missing=None, *, pts, pmask, reach, fused, rules, ng):
    """:func:`_mode_windows`' task: one group's points on its prefiltered region."""
    from . import dask as sld

    v = np.asarray(values, dtype=np.float64) if fused is None else fused.coefficients(values, reach, False)
    if missing is not None:
        v = np.where(np.asarray(missing), np.nan, v)
    cols = v.reshape(v.shape[:ng] + (-1,))
    out = np.empty((pts.shape[1], cols.shape[-1]), dtype=np.float64)
    lo = [a for a, _ in reach]
    for c in range(cols.shape[-1]):
        out[:, c] = sld._evaluate_region(cols[..., c], lo, pts.copy(), pmask, rules, np.float64)
    return out.reshape((pts.shape[1],) + v.shape[ng:])
