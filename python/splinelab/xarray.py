"""``import splinelab.xarray``: the ``splinelab`` accessor on xarray's DataArray and Dataset (issue 51).

``da.splinelab.interp(...)`` and ``ds.splinelab.interp(...)`` are
xarray's ``DataArray.interp`` and ``Dataset.interp`` with
splinelab's interpolators underneath: the same indexing forms (orthogonal
1-D coordinates, scalars, pointwise DataArray indexers sharing a dimension,
a subset of the dimensions), the same coordinates, dimensions and attributes
in the result, the same ``kwargs`` (``fill_value``, ``bounds_error``) and
out-of-range points, datetime coordinates (numpy datetime64, and cftime dates
in any calendar) converted as xarray converts them.
The numbers: along one dimension "linear", "nearest" and "slinear" are
scipy's ``interp1d`` (xarray's routine there) to the bit, NaN samples
included; "pchip" :class:`splinelab.RegularGridInterpolator`'s, scipy's.
"cubic" and "quintic" are the not-a-knot spline: exact (one banded solve
per grid line), or where the new coordinates are few for the grid, sums of
its cardinal weights over certified windows, within ``tol * max|data|`` of
it (``splinelab._xarray_dask``); along two or more dimensions, where
xarray calls scipy's ``interpn`` and its iterative ``gcrotmk`` solve, that
spline instead of scipy's approximation of it. ``mode=`` interpolates in
ndimage's boundary modes through :func:`splinelab.map_coordinates` on
uniform axes. Results are copies (writing to one never changes the input).

On dask-backed data the result is lazy, the same bits as in memory
whatever the chunking, and no interpolated axis is rechunked into one
chunk where windows are read: see :doc:`/coming_from_xarray` for which input
blocks each output block reads. Dask-backed new coordinates are not
computed at the call.

xarray is an optional dependency: ``pip install splinelab[xarray]``.
"""

from __future__ import annotations

try:
    import xarray as xr
except ImportError as _err:  # pragma: no cover - exercised in a subprocess by the tests
    raise ImportError("splinelab.xarray needs xarray, an optional dependency: "
                      "pip install splinelab[xarray]") from _err

import itertools
import math
import warnings
from collections.abc import Mapping, Sequence

import numpy as np

from . import RegularGridInterpolator, map_coordinates

__all__ = ["SplinelabDataArrayAccessor", "SplinelabDatasetAccessor", "METHODS"]

#: The methods of the accessor, and the fewest samples each needs on an
#: interpolated axis (the spline's degree + 1; "pchip": scipy's four).
METHODS = {"linear": 2, "nearest": 1, "slinear": 2, "cubic": 4, "quintic": 6, "pchip": 4}
#: The methods whose value at a point reads only nearby samples, and how
#: many samples beyond the point's cell on each side (the window a chunked
#: axis reads for them; "linear" one: along one dimension scipy's
#: ``interp1d`` takes a node's left interval).
_HALO = {"linear": 1, "nearest": 0, "slinear": 0, "pchip": 2}
#: The ndimage spline degree of each method under ``mode=``.
_MODE_ORDER = {"nearest": 0, "linear": 1, "slinear": 1, "cubic": 3, "quintic": 5}
#: The methods xarray interpolates along one dimension at a time where the
#: new coordinates are orthogonal (xarray's ``decompose_interp``).
_DECOMPOSED = ("linear", "nearest", "slinear")
_KWARGS = {"fill_value", "bounds_error", "extrapolate"}


# ---------------------------------------------------------------- indexers


def _coords_dict(coords, coords_kwargs):
    if coords is not None and coords_kwargs:
        raise ValueError("cannot specify both keyword and positional arguments to .interp")
    if coords is None:
        return dict(coords_kwargs)
    if not isinstance(coords, Mapping):
        raise ValueError("the first argument to .interp must be a dictionary")
    return dict(coords)


def _axis_variable(obj, dim):
    """The coordinate along ``dim`` (0, 1, ... where the dimension has none, as xarray)."""
    if dim in obj.variables:
        return obj.variables[dim]
    return xr.Variable((dim,), np.arange(obj.sizes[dim]))


def _is_cftime(values):
    """Whether ``values`` hold cftime dates (xarray's test: an object array
    whose first element is a ``cftime.datetime``; never without cftime)."""
    a = np.asarray(values)
    if a.dtype.kind != "O" or a.size == 0:
        return False
    try:
        import cftime
    except ImportError:
        return False
    return isinstance(a.flat[0], cftime.datetime)


def _is_datetime_like(values):
    """numpy datetimes and timedeltas, or cftime dates (xarray's
    ``_contains_datetime_like_objects``). A dask array is judged by its
    dtype, and an object one by its first element (the only one computed)."""
    from ._xarray_dask import is_dask
    kind = values.dtype.kind
    if kind in "Mm":
        return True
    if is_dask(values):
        return kind == "O" and values.size > 0 and _is_cftime(values.ravel()[:1].compute())
    return _is_cftime(values)


def _parsed_dates(obj, k, a):
    """Date strings as the axis' dates, as xarray's ``_validate_indexers``:
    datetime64[ns] on a datetime64 axis, the index's cftime type (partial
    dates such as "2001-03" allowed) on a cftime axis; others unchanged."""
    x = _axis_variable(obj, k).values
    if x.dtype.kind in "Mm":
        return a.astype("datetime64[ns]")
    if _is_cftime(x):
        from xarray.coding.cftimeindex import _parse_array_of_cftime_strings
        return _parse_array_of_cftime_strings(a, obj.indexes[k].date_type)
    return a


def _validated(obj, coords):
    """xarray's checks of ``interp``'s indexers, in its order; each as a Variable."""
    missing = [k for k in coords if k not in obj.dims]
    if missing:
        raise ValueError(f"Dimensions {set(missing)} do not exist. Expected one or more of {dict(obj.sizes)}")
    out = {}
    for k, v in coords.items():
        attrs = dict(_axis_variable(obj, k).attrs)
        if isinstance(v, xr.Dataset):
            raise TypeError("cannot use a Dataset as an indexer")
        if isinstance(v, xr.DataArray):
            v = v.variable
        elif isinstance(v, tuple):
            v = xr.Variable(*v)
        elif isinstance(v, xr.Variable):
            pass
        elif isinstance(v, Sequence) and not isinstance(v, str) and len(v) == 0:
            v = xr.Variable((k,), np.empty((0,), dtype="int64"), attrs=attrs)
        else:
            a = np.asarray(v)
            if a.dtype.kind in "US":
                a = _parsed_dates(obj, k, a)
            if a.ndim > 1:
                raise IndexError(f"Unlabeled multi-dimensional array cannot be used for indexing: {k}")
            v = xr.Variable((k,) if a.ndim else (), a, attrs=attrs)
        x = _axis_variable(obj, k)
        if _is_datetime_like(x.values) and not _is_datetime_like(v.data):
            raise TypeError("When interpolating over a datetime-like coordinate, the coordinates to interpolate "
                            f"to must be either datetime strings or datetimes. Instead got\n{v}")
        out[k] = v
    return out


def _result_sizes(dim_sizes_of):
    """The sizes of the broadcast of the new coordinates, xarray's error where they disagree."""
    sizes = {}
    for v in dim_sizes_of:
        for d, n in v.sizes.items():
            if d in sizes and sizes[d] != n:
                raise ValueError(f"operands cannot be broadcast together with mismatched lengths for dimension "
                                 f"{d}: {sizes[d]} vs {n}")
            sizes[d] = n
    return sizes


def _groups(indexers, method):
    """xarray's order of work: for "linear", "nearest" and "slinear" the
    indexers split into runs whose new coordinates share no dimension (each
    interpolated on its own, in the given order); otherwise all together."""
    if method not in _DECOMPOSED:
        return [dict(indexers)]
    items = list(indexers.items())
    out, run, run_dims = [], {}, set()
    for i, (k, axis) in enumerate(items):
        run[k] = axis
        new = axis[1]
        run_dims |= set(new.dims if new.ndim else (k,))
        later = set().union(*(set(a[1].dims if a[1].ndim else (kk,)) for kk, a in items[i + 1:]))
        if i == len(items) - 1 or not run_dims & later:
            out.append(run)
            run, run_dims = {}, set()
    return out


# ---------------------------------------------------------------- numbers


class _Options:
    """What the interpolation of one group needs besides the data."""

    def __init__(self, method, kwargs, mode, tol, one_dim):
        self.method = method
        self.mode = mode
        self.tol = tol
        self.one_dim = one_dim
        # "slinear", "cubic", "quintic": windowed sums (the others, and
        # "cubic"/"quintic" where _xarray_dask.use_windows says no, the
        # whole-grid interpolator); set per group by _interp_group
        self.windows = method == "slinear"
        kwargs = dict(kwargs or {})
        unknown = set(kwargs) - _KWARGS
        if unknown:
            raise TypeError(f"splinelab's interp takes the kwargs {sorted(_KWARGS)}; got {sorted(unknown)}")
        self.bounds_error = bool(kwargs.get("bounds_error", False))
        # xarray's defaults: interp1d (one dimension) fills NaN, and None
        # means NaN there; interpn (several) fills NaN, and None extrapolates;
        # PchipInterpolator along one dimension takes ``extrapolate``, not
        # ``fill_value``.
        if one_dim and method == "pchip":
            if "fill_value" in kwargs:
                raise TypeError("PchipInterpolator.__init__() got an unexpected keyword argument 'fill_value'")
            fill = "extrapolate" if kwargs.get("extrapolate", False) else np.nan
        else:
            if "extrapolate" in kwargs:
                raise TypeError("'extrapolate' is a keyword of the one-dimensional 'pchip' only")
            fill = kwargs.get("fill_value", np.nan)
            if fill is None:
                fill = np.nan if one_dim else "extrapolate"
            elif isinstance(fill, str) and fill != "extrapolate":
                raise ValueError(f"{fill!r} is not a valid fill_value")
            elif isinstance(fill, str) and not one_dim:
                raise ValueError("fill_value must be either 'None' or of a type compatible with values "
                                 "(xarray passes it to scipy's interpn, which takes no 'extrapolate')")
            elif not one_dim and np.ndim(fill) != 0:
                raise ValueError("fill_value must be a number or None when interpolating over several dimensions")
        if mode is not None:
            if method not in _MODE_ORDER:
                raise ValueError(f"mode= takes the methods {sorted(_MODE_ORDER)}; got {method!r}")
        self.below, self.above = (fill, fill) if np.ndim(fill) == 0 or isinstance(fill, str) else tuple(fill)


def _float_axes(xs, news, origins=None):
    """The grid's axes and the new coordinates as float64, datetimes as
    xarray converts them (offset by the axis' minimum ``origins``, in the
    axis' unit; cftime dates in nanoseconds). The minimum is the whole
    axis' (before the restriction of "linear" and "nearest" to a window,
    where xarray takes the window's), so a point's numbers do not depend on
    which samples it is read with (default: each axis' own). New
    coordinates that are dask arrays stay lazy."""
    from ._xarray_dask import is_dask
    out_x, out_new = [], []
    origins = [None] * len(xs) if origins is None else origins
    for x, new, x0 in zip(xs, news, origins):
        x = np.asarray(x)
        x0 = _origin(x) if x0 is None else x0
        new = new if is_dask(new) else np.asarray(new)
        if _is_cftime(x):
            out_x.append(_cftime_ns(x, x0))
            out_new.append(new.map_blocks(_cftime_ns, x0, dtype=np.float64) if is_dask(new) else _cftime_ns(new, x0))
        elif x.dtype.kind in "Mm":
            unit = np.timedelta64(1, np.datetime_data(x.dtype)[0])
            out_x.append((x - x0) / unit)
            out_new.append((new - x0) / unit)
        else:
            out_x.append(np.asarray(x, dtype=np.float64))
            out_new.append(new.astype(np.float64))
    return out_x, out_new


def _cftime_ns(dates, x0):
    """cftime dates as float nanoseconds after ``x0``, xarray's arithmetic
    step by step (``py_timedelta_to_float``: the differences' float
    seconds, times 1e6, times 1000), so the axes are xarray's to the bit.
    Dates of another calendar or type raise what their subtraction raises."""
    delta = np.asarray(dates - x0)
    us = np.reshape([d.total_seconds() for d in delta.ravel()], delta.shape) * 1e6
    return us * (np.timedelta64(1, "us") / np.timedelta64(1, "ns"))


def _check_axis(dim, x, method, mode):
    """The checks of one interpolated axis, each naming the dimension."""
    if x.size < METHODS[method]:
        raise ValueError(f"dimension {dim!r} has {x.size} points, but method {method!r} needs at least "
                         f"{METHODS[method]}")
    if np.any(np.isnan(x)):
        raise ValueError(f"the coordinate of dimension {dim!r} contains NaN")
    d = np.diff(x)
    if np.any(d == 0):
        raise ValueError(f"the coordinate of dimension {dim!r} has repeated values")
    if np.any(d < 0):
        raise ValueError(f"the coordinate of dimension {dim!r} is not monotonically increasing "
                         "(assume_sorted=True with unsorted values)")
    if mode is not None and x.size > 1 and not np.allclose(d, d[0], rtol=1e-9, atol=0):
        raise ValueError(f"mode= needs uniformly spaced coordinates; dimension {dim!r} is not")


def _result_dtype(dtype, opts):
    """xarray's in-memory dtypes: float64 (complex128) for "linear" and the
    splines (scipy's ``interp1d`` and ``interpn``), the values' float dtype
    for "nearest", and for "pchip" along several dimensions (``interpn``;
    along one, ``PchipInterpolator`` gives float64)."""
    keeps = opts.method == "nearest" or (opts.method == "pchip" and not opts.one_dim)
    if keeps and dtype.kind in "fc":
        return dtype
    return np.dtype(np.complex128) if dtype.kind == "c" else np.dtype(np.float64)


def _raw(grid, values, xi, opts, outer=None):
    """Values on a grid (the grid's axes first, any trailing axes) at points
    ``xi`` (P, ngrid), extrapolated: (P, trailing...). "slinear", "cubic"
    and "quintic" are windowed sums (:func:`splinelab._xarray_dask.spline_values`;
    ``outer``: the points are the orthogonal grid of these coordinates);
    "linear" along one dimension of a 1-D float64 or integer array is
    ``numpy.interp``, as scipy's ``interp1d`` computes it there; the others
    :class:`splinelab.RegularGridInterpolator`'s."""
    from ._xarray_dask import DEGREE, spline_values
    dtype = _result_dtype(values.dtype, opts)
    if opts.mode is not None:
        out = _evaluate_mode(grid, values, xi, opts)
    elif opts.method in DEGREE and opts.windows:
        out = spline_values(grid, values, xi, opts, outer)
    elif _numpy_interp(values, opts):
        out = np.interp(xi[:, 0], grid[0], np.asarray(values, dtype=np.float64))
    elif opts.method == "linear" and opts.one_dim:
        out = _interp1d_linear(grid[0], np.asarray(values), xi[:, 0])
    elif opts.method in DEGREE and opts.one_dim:
        out = _exact_lines(grid, values, xi, opts)
    else:
        ip = RegularGridInterpolator(tuple(grid), values, method=opts.method, bounds_error=False, fill_value=None)
        out = np.asarray(ip(xi))
    return out.astype(dtype, copy=False)


def _interp1d_linear(x, y, q):
    """"linear" along one dimension as scipy's ``interp1d`` computes it
    (xarray's routine there; its ``_call_linear``): the interval
    ``x[i-1] < q <= x[i]`` (the first at and below the first node), and
    ``slope * (q - x[i-1]) + y[i-1]``, so a NaN sample spreads to the points
    of the intervals beside it, a node's own interval the one on its left."""
    i = np.clip(np.searchsorted(x, q), 1, len(x) - 1)
    lo, hi = i - 1, i
    shape = (-1,) + (1,) * (y.ndim - 1)
    slope = (y[hi] - y[lo]) / (x[hi] - x[lo]).reshape(shape)
    return slope * (q - x[lo]).reshape(shape) + y[lo]


def _exact_lines(grid, values, xi, opts):
    """The exact spline along one axis, a line holding a non-finite sample
    NaN (scipy's ``interp1d``, xarray's routine there, gives NaN for every
    point of an array holding a NaN; a line is what it solves)."""
    from ._xarray_dask import line_flags
    values = np.asarray(values)
    flags = line_flags(values, 1)
    if flags.any():
        values = np.where(flags, 0, values)
    out = np.asarray(RegularGridInterpolator(tuple(grid), values, method=opts.method, bounds_error=False,
                                             fill_value=None)(xi))
    if flags.any():
        out[:, flags] = np.nan
    return out


def _numpy_interp(values, opts):
    """Where scipy's ``interp1d`` (xarray's one-dimensional "linear")
    delegates to ``numpy.interp``: a 1-D float64 or integer array and a fill
    that does not extrapolate (it is exact at the nodes, and a NaN sample
    spreads only to the intervals beside it)."""
    return (opts.method == "linear" and opts.one_dim and values.ndim == 1
            and (values.dtype == np.float64 or values.dtype.kind in "iub")
            and not isinstance(opts.below, str) and not isinstance(opts.above, str))


def _apply_fill(out, grid, xi, opts, dims):
    """Out-of-range points as xarray gives them: NaN, ``fill_value``, a pair
    (below, above), extrapolated, or ``bounds_error``'s ``ValueError``."""
    if opts.mode is not None or not len(xi):
        return out
    below = np.zeros(len(xi), dtype=bool)
    above = np.zeros(len(xi), dtype=bool)
    for a, (g, x) in enumerate(zip(grid, xi.T)):
        lo, hi = x < g[0], x > g[-1]
        if opts.bounds_error and (lo.any() or hi.any()):
            side = "below the minimum" if lo.any() else "above the maximum"
            raise ValueError(f"a new coordinate of dimension {dims[a]!r} is {side} of its coordinate "
                             f"[{g[0]}, {g[-1]}] (bounds_error=True)")
        below |= lo
        above |= hi
    for mask, fill in ((below, opts.below), (above & ~below, opts.above)):
        if isinstance(fill, str) or not mask.any():
            continue
        if not out.flags.writeable:
            out = out.copy()
        out[mask] = fill
    return out


def _evaluate(grid, values, xi, opts, dims, outer=None):
    """``_raw`` with ``_apply_fill``."""
    return _apply_fill(_raw(grid, values, xi, opts, outer), grid, xi, opts, dims)


def _index_points(grid, xi):
    """The points ``xi`` (``(P, ngrid)``) in the uniform axes' index
    coordinates, ``(ngrid, P)``: ndimage's, for ``mode=``."""
    idx = np.empty((len(grid), len(xi)))
    for a, g in enumerate(grid):
        step = (g[-1] - g[0]) / (len(g) - 1) if len(g) > 1 else 1.0
        idx[a] = (xi[:, a] - g[0]) / step
    return idx


def _evaluate_mode(grid, values, xi, opts):
    """``mode=``: splinelab.map_coordinates on the uniform axes' index
    coordinates (ndimage's boundary modes, the certified prefilter at
    ``tol``), one call per trailing column."""
    values = np.asarray(values)
    ng = len(grid)
    idx = _index_points(grid, xi)
    trailing = values.shape[ng:]
    cols = values.reshape(values.shape[:ng] + (-1,))
    out = np.empty((len(xi), cols.shape[-1]), dtype=np.result_type(values.dtype, np.float64))
    order = _MODE_ORDER[opts.method]
    for c in range(cols.shape[-1]):
        out[:, c] = map_coordinates(np.ascontiguousarray(cols[..., c]), idx, order=order, mode=opts.mode,
                                    cval=np.nan, tol=opts.tol)
    return out.reshape((len(xi),) + trailing)


# ---------------------------------------------------------------- one variable


def _interp_variable(var, indexers, method, kwargs, mode, tol):
    """One variable interpolated as ``xarray.core.missing.interp`` does:
    group by group, each group's result dims xarray's."""
    for group in _groups(indexers, method):
        var = _interp_group(var, group, method, kwargs, mode, tol)
    return var


def _interp_group(var, group, method, kwargs, mode, tol):
    dims = list(group)
    xs = [group[d][0] for d in dims]
    news = [group[d][1] for d in dims]
    origins = [group[d][2] for d in dims]
    sizes = _result_sizes(news)
    rdims = list(dict.fromkeys(itertools.chain.from_iterable(n.dims for n in news)))
    vdims = [d for d in rdims if d in var.dims and d not in dims]      # vectorised over (xarray's vectorize)
    bdims = [d for d in var.dims if d not in dims and d not in vdims]  # carried, trailing
    out_dims = list(dict.fromkeys(itertools.chain.from_iterable(
        (group[d][1].dims if d in group else (d,)) for d in var.dims)))
    for d in vdims:
        if sizes[d] != var.sizes[d]:
            raise ValueError(f"operands cannot be broadcast together with mismatched lengths for dimension "
                             f"{d}: {var.sizes[d]} vs {sizes[d]}")
    opts = _Options(method, kwargs, mode, tol, one_dim=len(dims) == 1)
    from . import _xarray_dask
    lazy = any(_xarray_dask.is_dask(n.data) for n in news)
    broadcast = [n.set_dims({d: sizes[d] for d in rdims}).data for n in news]
    grid, new_f = _float_axes([x.values for x in xs], broadcast, origins)
    for d, g in zip(dims, grid):
        _check_axis(d, g, method, mode)
    pdims = [d for d in rdims if d not in vdims]
    pshape = tuple(sizes[d] for d in pdims)
    data = var.transpose(*(dims + vdims + bdims)).data
    bshape = tuple(var.sizes[d] for d in bdims)
    orthogonal = not vdims and all(n.ndim <= 1 for n in news) and len({d for n in news for d in n.dims}) == sum(
        n.ndim for n in news)
    if mode is None and method in _xarray_dask.DEGREE and method != "slinear":
        npoints = math.prod(pshape)
        counts = [n.size for n in news] if orthogonal else [npoints] * len(news)
        opts.windows = _xarray_dask.use_windows([len(g) for g in grid], _xarray_dask.DEGREE[method], counts,
                                                npoints, math.prod(bshape), orthogonal, _xarray_dask._tol(opts))

    if lazy:
        result = _xarray_dask.interp_lazy(data, grid, new_f, rdims, vdims, pdims, opts, dims)
    elif _xarray_dask.is_dask(data):
        result = _xarray_dask.interp(data, grid, new_f, rdims, vdims, pdims, len(bdims), opts, dims,
                                     _outer(news, new_f, rdims) if orthogonal else None)
    else:
        result = _interp_numpy(np.asarray(data), grid, new_f, rdims, vdims, pdims, opts, dims,
                               _outer(news, new_f, rdims) if orthogonal else None)
    result = result.reshape(tuple(sizes[d] for d in vdims) + pshape + bshape)
    out = xr.Variable(vdims + pdims + bdims, result, attrs=var.attrs)
    return out.transpose(*out_dims) if len(out_dims) > 1 else out


def _outer(news, new_f, rdims):
    """The points are the orthogonal grid of per-axis coordinates (each new
    coordinate a scalar or 1-D along a dimension of its own, none
    vectorised): those coordinates (float64, in the points' C order)."""
    out = []
    for n, f in zip(news, new_f):
        sel = tuple(slice(None) if d in n.dims else 0 for d in rdims)
        out.append(np.asarray(f[sel]).reshape(-1))
    return out


def _points(new_f, rdims, vdims, vindex):
    """The points (P, ngrid) of one vectorised position (all when none)."""
    sel = tuple(vindex[vdims.index(d)] if d in vdims else slice(None) for d in rdims)
    return np.stack([n[sel].ravel() for n in new_f], axis=-1) if new_f else np.empty((1, 0))


def _interp_numpy(values, grid, new_f, rdims, vdims, pdims, opts, dims, outer=None):
    """In memory: one evaluation per vectorised position (one in all where
    the new coordinates share no dimension with the data; ``outer``: their
    orthogonal grid's coordinates, :func:`_outer`)."""
    ng, nv = len(grid), len(vdims)
    vshape = values.shape[ng:ng + nv]
    outs = []
    for vindex in np.ndindex(*vshape):
        block = values[(slice(None),) * ng + vindex]
        outs.append(_evaluate(grid, block, _points(new_f, rdims, vdims, vindex), opts, dims, outer))
    if not nv:
        return outs[0]
    return np.stack(outs).reshape(vshape + outs[0].shape)


# ---------------------------------------------------------------- Dataset


def _interp_dataset(obj, coords, method, assume_sorted, kwargs, method_non_numeric, mode, tol):
    if method not in METHODS:
        raise ValueError(f"{method} is not a valid interpolator for splinelab's interp; "
                         f"the methods are {list(METHODS)}")
    indexers = _validated(obj, coords)
    if not assume_sorted:
        # xarray's sortby, skipped where a coordinate is increasing already
        # (sortby copies every variable along it)
        unsorted = [k for k in indexers if not _increasing(_axis_variable(obj, k).values)]
        if unsorted:
            obj = obj.sortby(unsorted)
    origins = {k: _origin(_axis_variable(obj, k).values) for k in indexers}
    if mode is None and method in ("linear", "nearest"):
        for k, v in indexers.items():
            obj = _localized(obj, k, v)
    axes = {k: _axis_variable(obj, k) for k in indexers}

    variables, reindex = {}, []
    for name, var in obj.variables.items():
        if name in indexers:
            continue
        mine = {k: (axes[k], v, origins[k]) for k, v in indexers.items() if k in var.dims}
        kind = var.dtype.kind
        if not mine:
            variables[name] = var
        elif kind in "uifc":
            variables[name] = _interp_variable(var, mine, method, kwargs, mode, tol)
        elif kind in "Mm":
            variables[name] = _interp_datetime(var, mine, method, kwargs, mode, tol)
        elif kind in "ObU":
            if all(var.sizes[d] == 1 for d in mine):
                variables[name] = xr.Variable(
                    *_broadcast_dims(var.squeeze(), [a[1] for a in mine.values()])).copy(deep=True)
            else:
                reindex.append(name)

    by_dim = {k: v for k, v in indexers.items() if v.dims == (k,)}
    if reindex and by_dim:
        re = obj[reindex].reindex({k: v.values for k, v in by_dim.items()}, method=method_non_numeric)
        for name in reindex:
            variables[name] = re.variables[name]

    coord_names = [n for n in obj.coords if n in variables]
    attached = _indexer_coords(coords, variables, obj)
    for k, v in indexers.items():
        variables[k] = v
        coord_names.append(k)
    for c, cv in attached.items():
        variables[c] = cv
        if c not in coord_names:
            coord_names.append(c)
    # what is not interpolated is copied, as xarray's result is: writing to
    # the result never changes the input
    data_vars = {n: v.copy(deep=True) if v is obj.variables.get(n) else v
                 for n, v in variables.items() if n not in coord_names}
    kept = obj.drop_vars([n for n in obj.variables if n not in coord_names or n in indexers
                          or variables.get(n) is not obj.variables[n]]).coords
    fresh = _fresh_indexed(kept)
    kept = kept.to_dataset().drop_vars(list(fresh)).coords.copy(deep=True)
    new_coords = {**fresh, **{n: variables[n] for n in coord_names if n not in kept and n not in fresh}}
    return xr.Dataset(data_vars, coords=kept, attrs=obj.attrs).assign_coords(new_coords)


def _fresh_indexed(coords):
    """The kept coordinates with a plain pandas index, as variables holding
    a copy of their values (their new index is built on the copy: a deep
    copy of the coordinates keeps the index object, whose values the
    result's coordinate would share with the input's)."""
    from xarray.indexes import PandasIndex
    out = {}
    for n, c in coords.items():
        if type(coords.xindexes.get(n)) is PandasIndex and c.dims == (n,):
            v = c.variable
            out[n] = xr.Variable(v.dims, np.array(v.values, copy=True), v.attrs, v.encoding)
    return out


def _localized(obj, k, new):
    """xarray's ``missing._localize`` for "linear" and "nearest": the
    dataset restricted along ``k`` to the samples from two before the node
    nearest the smallest new coordinate to two after the node nearest the
    largest (every cell a new coordinate falls in, and the end cells of
    points beyond the ends), so in-memory data is read only there (dask
    data: the graph only holds those chunks). Unchanged where the new
    coordinates are lazy (dask), empty or all NaN."""
    import pandas as pd

    from ._xarray_dask import is_dask
    if is_dask(new.data) or new.size == 0:
        return obj
    values = new.values
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)   # all NaN: left whole below
        try:
            lo, hi = np.nanmin(values), np.nanmax(values)
        except (TypeError, ValueError):
            return obj
    if pd.isna(lo) or pd.isna(hi):
        return obj
    index = _axis_variable(obj, k).to_index()
    try:
        imin, imax = index.get_indexer(pd.Index([lo, hi]), method="nearest")
    except (TypeError, ValueError):
        return obj
    if imin < 0 or imax < 0:
        return obj
    return obj.isel({k: slice(max(imin - 2, 0), imax + 2)})


def _indexer_coords(coords, taken, obj):
    """xarray's ``_get_indexers_coords_and_indexes``: the coordinates of the
    DataArray indexers (merged; conflicting values a ``MergeError``) that
    the result holds no variable of yet, an indexer's own coordinate on
    its dimension included (it replaces the new coordinate's values, as in
    xarray: dates labelling new positions stay dates). A dimension
    coordinate that disagrees with the data's is an ``IndexError``."""
    out = {}
    for v in coords.values():
        if not isinstance(v, xr.DataArray):
            continue
        for c, cv in v.coords.items():
            if c in out and not out[c].equals(cv.variable):
                raise xr.MergeError(f"conflicting values for variable {c!r} on objects to be combined")
            out.setdefault(c, cv.variable)
    for c, cv in out.items():
        if c in obj.dims and c in obj.coords and c in taken and not cv.equals(taken[c]):
            raise IndexError(f"dimension coordinate {c!r} conflicts between indexed and indexing objects:\n"
                             f"{obj[c]}\nvs.\n{cv}")
    return {c: cv for c, cv in out.items() if c not in taken}


def _origin(x):
    """The offset of a datetime-like axis' conversion to floats (xarray's:
    its minimum); None for a numeric axis."""
    x = np.asarray(x)
    return x.min() if x.size and (x.dtype.kind in "Mm" or _is_cftime(x)) else None


def _increasing(x):
    x = np.asarray(x)
    if x.dtype.kind in "Mm":
        x = x.view(np.int64)
    elif _is_cftime(x):   # compared date by date (one calendar: a sorted index)
        return bool(np.all(x[1:] > x[:-1]))
    return x.dtype.kind in "uif" and bool(np.all(x[1:] > x[:-1]))


def _broadcast_dims(var, news):
    """A variable broadcast against the new coordinates (xarray's
    ``broadcast_variables``), as (dims, data, attrs)."""
    dims = list(var.dims)
    sizes = dict(var.sizes)
    for n in news:
        for d, s in n.sizes.items():
            if d not in sizes:
                dims.append(d)
                sizes[d] = s
    return dims, np.broadcast_to(var.set_dims(sizes).transpose(*dims).values, [sizes[d] for d in dims]), var.attrs


def _interp_datetime(var, mine, method, kwargs, mode, tol):
    """datetime64 and timedelta64 values interpolated as xarray's interp
    converts them: the integers of their own unit as float64 (NaT as NaN),
    interpolated, rounded back (NaN as NaT); with or without ``mode=`` (its
    'constant' and 'grid-constant' give NaT where they give cval: the cval
    is NaN). Lazy where the data is (dask), as xarray keeps it."""
    from . import _xarray_dask
    nat = np.iinfo(np.int64).min
    xp = _xarray_dask.array_module(var.data)
    ints = var.data.view(np.int64)
    floats = xr.Variable(var.dims, xp.where(ints != nat, ints.astype(np.float64), np.nan), attrs=var.attrs)
    res = _interp_variable(floats, mine, method, kwargs, mode, tol)
    vals = res.data
    xp = _xarray_dask.array_module(vals)
    back = xp.where(xp.isnan(vals), nat, xp.round(xp.nan_to_num(vals)).astype(np.int64))
    return xr.Variable(res.dims, back.view(var.dtype), attrs=res.attrs)


# ---------------------------------------------------------------- accessors


_DOC = """Interpolate onto new coordinates: xarray's ``interp``, splinelab's numbers.

Parameters
----------
coords : dict, optional
    Dimension names to new coordinates: a scalar, a 1-D array (the
    dimension's new coordinate) or a DataArray (its dims broadcast: DataArrays
    sharing a dimension interpolate pointwise), as xarray's ``DataArray.interp``.
    On a datetime64 or cftime axis: dates, or date strings (parsed as xarray
    parses them: into the cftime index's calendar on a cftime axis).
method : str, optional
    "cubic" (default; xarray's default is "linear"), "quintic", "linear",
    "nearest", "slinear" or "pchip". "cubic" and "quintic" are the
    not-a-knot spline (exact, or within ``tol`` of it on windows); the
    others give scipy's numbers.
assume_sorted : bool, optional
    False (default): the interpolated coordinates are sorted first (xarray's
    ``sortby``); True: they must be increasing already.
kwargs : dict, optional
    xarray's keywords for scipy's interpolators: ``fill_value`` (default
    NaN; along one dimension also "extrapolate" or a pair (below, above), and
    None means NaN; along several dimensions None extrapolates),
    ``bounds_error`` (default False), and for "pchip" along one dimension
    ``extrapolate`` (default False). Others are a ``TypeError``.
mode : str, optional
    splinelab's own: one of ndimage's boundary modes ("mirror", "reflect",
    "nearest", "wrap", "grid-wrap", "constant", "grid-constant",
    "grid-mirror"): the spline of degree 0, 1, 3 or 5 (methods "nearest",
    "linear"/"slinear", "cubic", "quintic") with that boundary condition
    through :func:`splinelab.map_coordinates`, on uniformly spaced axes
    only; ``fill_value`` does not apply (the mode decides outside).
tol : float, optional
    With ``mode=``: the tolerance of the certified truncated prefilter
    (:func:`splinelab.map_coordinates`' ``tol``; on dask data chunked
    along an interpolated dimension also of the windows read, default
    1e-12 there: ``splinelab.dask.bound``). For "cubic" and
    "quintic" where they sum windows (few new coordinates for the grid, in
    memory and on dask alike): the certified bound, relative to max|data|,
    on the distance of the result from the whole-grid spline (default
    1e-14).
**coords_kwargs
    The keyword form of ``coords``.

Returns
-------
{ret}
    On the new coordinates; attributes and the coordinates not
    interpolated kept. Lazy (dask) where the data is: see
    :doc:`/coming_from_xarray`.

Raises
------
ValueError
    As xarray: an unknown dimension, new coordinates whose shared
    dimensions disagree in length, too few points on an axis for the method,
    repeated or (``assume_sorted=True``) unsorted coordinates, a point out
    of range with ``bounds_error=True``; each naming the dimension.
    A date string that does not parse, or a day its calendar lacks.
TypeError, IndexError
    As xarray: a non-datetime new coordinate of a datetime or cftime axis,
    dates of another calendar; a multi-dimensional array that is not a
    DataArray.
"""


def _accessor_doc(ret):
    return _DOC.replace("{ret}", ret)


@xr.register_dataarray_accessor("splinelab")
class SplinelabDataArrayAccessor:
    """``da.splinelab``: splinelab's interpolation of a DataArray (registered by ``import splinelab.xarray``)."""

    def __init__(self, obj):
        self._obj = obj

    def interp(self, coords=None, method="cubic", *, assume_sorted=False, kwargs=None, mode=None, tol=None,
               **coords_kwargs):
        da = self._obj
        if da.dtype.kind not in "uifcMm":
            raise TypeError(f"interp only works for a numeric type array. Given {da.dtype}.")
        coords = _coords_dict(coords, coords_kwargs)
        name = "<this-array>" if da.name is None or da.name in da.coords else da.name
        ds = xr.Dataset({name: da.variable}, coords=da.coords)
        out = _interp_dataset(ds, coords, method, assume_sorted, kwargs, "nearest", mode, tol)
        res = out[name]
        res.name = da.name
        return res

    interp.__doc__ = _accessor_doc("DataArray")


@xr.register_dataset_accessor("splinelab")
class SplinelabDatasetAccessor:
    """``ds.splinelab``: splinelab's interpolation of a Dataset (registered by ``import splinelab.xarray``)."""

    def __init__(self, obj):
        self._obj = obj

    def interp(self, coords=None, method="cubic", *, assume_sorted=False, kwargs=None, mode=None, tol=None,
               method_non_numeric="nearest", **coords_kwargs):
        coords = _coords_dict(coords, coords_kwargs)
        return _interp_dataset(self._obj, coords, method, assume_sorted, kwargs, method_non_numeric, mode, tol)

    interp.__doc__ = _accessor_doc("Dataset").replace(
        "**coords_kwargs", "method_non_numeric : str, optional\n    As xarray: how variables that are not "
        "numbers follow the new coordinates (``Dataset.reindex``'s method, default \"nearest\").\n"
        "**coords_kwargs")


del _accessor_doc
