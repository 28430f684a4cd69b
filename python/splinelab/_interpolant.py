"""``splinelab.Interpolant``: a reusable spline over one array on the local
route (issue 45), its tiles of coefficients computed when a point first
needs them and kept within a byte budget, its samples changed in place of a
rebuild."""

from __future__ import annotations

import numpy as np

from . import _local
from . import _splinelab as _ext
from ._ndimage import _coordinates, _derivative, _interp_mode, _reflection_sign
from ._validate import _count, _degree, _nan_policy, _opt_float, _threads

#: The default tile cache budget (bytes).
DEFAULT_CACHE_BYTES = 256 * 2**20


def _selected(shape, key):
    """The samples ``a[key]`` selects, as numpy selects them: their indices
    ``(k, ndim)`` in the order of ``a[key]``, and the selection's shape.
    Each axis' index grid is a zero-stride view (no array of the input's
    size); numpy's own indexing raises numpy's IndexError for a key outside."""
    ndim = len(shape)
    grids = [
        np.broadcast_to(np.arange(n, dtype=np.intp).reshape([-1 if b == a else 1 for b in range(ndim)]), shape)
        for a, n in enumerate(shape)
    ]
    sel = [np.asarray(g[key]) for g in grids]
    return np.stack([s.ravel() for s in sel], axis=1).astype(np.int64, copy=False), sel[0].shape


class Interpolant:
    """A spline over one array, evaluated at points as
    :func:`splinelab.map_coordinates` evaluates it, on the local route.

    ``Interpolant(input, order=3, mode="mirror", cval=0.0, tol=None,
    nan_policy="propagate", threads=None, cache_bytes=256 MiB)``;
    ``ip(coordinates, derivative=None)`` takes ``map_coordinates``' layout
    (``(ndim, ...)``) and returns float64 values (float32 for float32
    input) of shape ``coordinates.shape[1:]``; ``derivative`` as in
    :func:`splinelab.map_coordinates`.

    ``input``: a numpy array (a memory map is read from its buffer, only
    the pages under the points' windows), or an array-like that is not in
    memory — anything with ``shape``, ``dtype``, ``ndim`` and basic-slice
    ``__getitem__`` (zarr, h5py, dask): read one ``__getitem__`` per box the
    windows need (a dask array: one graph computing only the chunks under
    them). Real dtypes; integers and booleans are computed in float64.
    Modes: scipy's eight, mapped as :func:`splinelab.map_coordinates` maps
    them. ``tol=None``: the half-width certified below the global route's
    own rounding error; a float: that tolerance.

    Coefficients are computed per tile (``32**2`` cells in 2-D) when a point
    first needs them and kept in a cache of ``cache_bytes`` bytes (least
    recently used first out); a budget below one tile is a ValueError
    naming the smallest that works. A value is a function of the current
    samples only: the same bits whatever the cache held.

    ``ip.update(key, values)`` changes the samples as ``a[key] = values``
    would (numpy's IndexError / ValueError, the object unchanged on error;
    a non-finite value follows ``nan_policy``: refused under 'raise') and
    recomputes the coefficients within reach of the changed samples in the
    cached tiles, by the same operations as a rebuild (so the same bits).
    The caller's array is never written: changed samples are kept beside it
    in blocks. The interpolant pickles (its input pickles as the input
    does: a memory map pickles its data, a zarr array its store's address).

    Missing samples: on this route a NaN reaches only the points whose
    windows read it (under every policy; ``'raise'`` refuses a missing
    sample when a window reads it). A non-finite coordinate is a ValueError.

    >>> import numpy as np, splinelab
    >>> a = np.add.outer(np.arange(50.0), np.arange(60.0) ** 2)
    >>> ip = splinelab.Interpolant(a, order=3, mode="mirror")
    >>> bool(abs(ip([[10.0], [20.0]])[0] - a[10, 20]) < 1e-12)
    True
    >>> ip.update((10, 20), 0.0)
    >>> b = a.copy(); b[10, 20] = 0.0
    >>> bool(np.array_equal(ip([[10.5], [19.25]]), splinelab.Interpolant(b)([[10.5], [19.25]])))
    True
    """

    def __init__(self, input, order=3, mode="mirror", cval=0.0, tol=None, nan_policy="propagate", threads=None,
                 cache_bytes=DEFAULT_CACHE_BYTES):
        src = _local.source(input)
        if src.dtype.kind not in "biuf":
            raise TypeError(f"input must have a real (float, integer or bool) dtype, got {src.dtype}")
        if src.ndim == 0 or 0 in src.shape:
            raise ValueError(f"input must have at least one sample on every axis, got shape {src.shape}")
        self._src = src
        self._args = dict(order=order, mode=mode, cval=cval, tol=tol, nan_policy=nan_policy, threads=threads,
                          cache_bytes=cache_bytes)
        self._degree = _degree(order)
        self.mode = _interp_mode(mode)
        cval = _opt_float(cval, "cval")
        self._nan_policy = _nan_policy(nan_policy)
        tol = _opt_float(tol, "tol")
        self._threads = _threads(threads)
        self._work = np.dtype(np.float32) if src.dtype == np.float32 else np.dtype(np.float64)
        engine_mode, self._rule, pad = _local.engine_args(self.mode, self._degree, True, False)
        cls = _ext.LocalSplineF32 if self._work == np.float32 else _ext.LocalSplineF64
        self._engine = cls(list(src.shape), self._degree, engine_mode, cval, tol, self._nan_policy, True, pad,
                           _count(cache_bytes, "cache_bytes"))

    @property
    def shape(self):
        """The sample grid's shape."""
        return tuple(self._src.shape)

    @property
    def ndim(self):
        return len(self._src.shape)

    @property
    def order(self):
        """The spline degree."""
        return self._degree

    def truncation(self):
        """``{'half_width', 'bound', 'tol'}``: the certified convolution's
        half-width, its per-axis bound ``sum_{|j|>n} |c_j|`` and the
        tolerance it was certified for."""
        n, b, t = self._engine.truncation()
        return {"half_width": n, "bound": b, "tol": t}

    def cache_info(self):
        """``{'budget', 'bytes', 'tiles', 'changed_bytes'}`` now."""
        return dict(zip(("budget", "bytes", "tiles", "changed_bytes"), self._engine.cache_info()))

    def _direct(self):
        return isinstance(self._src, np.ndarray) and self._src.dtype == self._work

    def __call__(self, coordinates, derivative=None):
        at = _coordinates(coordinates, self.ndim)
        flat = np.ascontiguousarray(at.reshape(at.shape[0], -1))
        deriv = _derivative(derivative, self.ndim)
        if self._direct():
            values = self._engine.eval(self._src, flat, self._rule, deriv, self._threads)
        else:
            boxes = self._engine.boxes_for_eval(flat, self._rule)
            fetched = _local.fetch(self._src, boxes, self._work)
            values = self._engine.eval_blocks(list(self.shape), fetched, flat, self._rule, deriv, self._threads)
        if deriv:
            values = values * _reflection_sign(flat, self.shape, self.mode, deriv).astype(values.dtype)
        return values.reshape(at.shape[1:])

    def update(self, key, values):
        """Changes the samples as ``a[key] = values`` would and recomputes
        the coefficients within reach (class documentation)."""
        idx, shape = _selected(self.shape, key)
        new = np.empty(shape, self._src.dtype)
        new[...] = values
        new = np.ascontiguousarray(new.ravel(), dtype=self._work)
        if self._direct():
            self._engine.update(self._src, idx, new)
            return
        fetched = _local.fetch(self._src, self._engine.boxes_for_update(idx), self._work)
        self._engine.update_blocks(list(self.shape), fetched, idx, new)

    def __reduce__(self):
        return _rebuild, (self._src, self._args, self._engine.changed_blocks())

    def __repr__(self):
        return f"Interpolant(shape={self.shape}, order={self._degree}, mode={self.mode!r})"


def _rebuild(src, args, changed):
    """An unpickled :class:`Interpolant`: rebuilt, its changed samples restored."""
    ip = Interpolant(src, **args)
    for first, data in changed:
        ip._engine.restore_block(list(first), np.ascontiguousarray(data, dtype=ip._work))
    return ip
