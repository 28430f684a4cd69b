"""``splinelab.Interpolant``: a reusable spline over one array on the local
route (issue 45), its tiles of coefficients computed when a point first
needs them and kept within a byte budget, its samples changed in place of a
rebuild."""

from __future__ import annotations

import numpy as np

from . import _local
from ._ndimage import _coordinates, _derivative, _reflection_sign
from ._settings import Settings
from ._validate import _count

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
    """A spline over one array, evaluated as :func:`splinelab.map_coordinates` evaluates it, on the local route.

    Coefficients are computed per tile (``32**2`` cells in 2-D) when a point
    first needs them and kept in a cache of ``cache_bytes`` bytes (least
    recently used first out). A value is a function of the current samples
    only: the same bits whatever the cache held. ``ip(coordinates,
    derivative=None)`` evaluates (:meth:`__call__`); :meth:`update` changes
    samples in place of a rebuild. splinelab's own class (scipy has none).

    Parameters
    ----------
    input : array_like
        A numpy array (a memory map is read from its buffer, only the pages
        under the points' windows), or an array-like that is not in memory —
        anything with ``shape``, ``dtype``, ``ndim`` and basic-slice
        ``__getitem__`` (zarr, h5py, dask): where it exposes its chunk grid
        (``chunks``), each stored chunk the windows touch read once a call;
        else one ``__getitem__`` per box the windows need. Real dtypes;
        integers and booleans are computed in float64, float32 samples in
        float64 (each result rounded once to float32). The caller's array is
        never written.
    order : int, optional
        The spline degree, 0..199. Default 3.
    mode : str, optional
        scipy's eight, mapped as :func:`splinelab.map_coordinates` maps
        them. Default 'mirror'.
    cval : float, optional
        The value outside the grid in 'constant' and 'grid-constant'.
        Default 0.0.
    tol : float or None, optional
        None (default): the half-width certified below the global route's
        own rounding error; a float: that tolerance.
    nan_policy : {'propagate', 'raise', 'local'}, optional
        On this route a NaN reaches only the points whose windows read it
        (under every policy); 'raise' refuses a missing sample when a window
        reads it. Default 'propagate'.
    threads : int or None, optional
        None (default: one per core) or the number of threads, 1..256.
    cache_bytes : int, optional
        The tile cache's budget in bytes (default 256 MiB).

    Raises
    ------
    TypeError
        An input that is not of a real dtype.
    ValueError
        An input without a sample on some axis; a ``cache_bytes`` below one
        tile (the message names the smallest that works); bad ``tol``,
        ``threads`` or ``nan_policy``.
    splinelab.errors.OrderError
        ``order`` outside 0..199.
    splinelab.errors.ModeError
        ``mode`` is not one of scipy's eight.

    See Also
    --------
    splinelab.map_coordinates : The same values, one call at a time.

    Notes
    -----
    Method: the prefilter as the truncated convolution of half-width
    :func:`splinelab.truncation_width` (certified for ``tol``), computed per
    tile from the samples within that half-width, then the B-spline weights
    of each point. Error: with ``tol=None`` below the global route's own
    rounding error; with a ``tol``, at most ``bound * max|input|`` per
    axis beyond it (:meth:`truncation`). Cost: per new tile, the samples it
    reads with a margin of the half-width convolved; per point,
    ``(order + 1)**ndim`` multiply-adds. The interpolant pickles (its input
    pickles as the input does: a memory map pickles its data, a zarr array
    its store's address).

    Examples
    --------
    >>> import numpy as np, splinelab
    >>> a = np.add.outer(np.arange(50.0), np.arange(60.0) ** 2)
    >>> ip = splinelab.Interpolant(a, order=3, mode="mirror")
    >>> bool(abs(ip([[10.0], [20.0]])[0] - a[10, 20]) < 1e-12)
    True

    An update gives the bits of an interpolant rebuilt on the changed
    samples:

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
        self._settings = s = Settings.interpolant(order, mode, cval, tol, nan_policy, threads)
        self.mode = s.mode
        self._work = np.dtype(np.float32) if src.dtype == np.float32 else np.dtype(np.float64)
        self._engine, self._rule = _local.engine(src.shape, s, s.cval, self._work, _count(cache_bytes, "cache_bytes"),
                                                 False)

    @property
    def shape(self):
        """The sample grid's shape."""
        return tuple(self._src.shape)

    @property
    def ndim(self):
        """The number of axes of the sample grid."""
        return len(self._src.shape)

    @property
    def order(self):
        """The spline degree."""
        return self._settings.degree

    def truncation(self):
        """The certified truncation of the prefilter.

        Returns
        -------
        dict
            ``{'half_width', 'bound', 'tol'}``: the convolution's half-width
            ``n``, its per-axis bound ``sum_{|j|>n} |c_j|`` and the tolerance
            it was certified for.
        """
        n, b, t = self._engine.truncation()
        return {"half_width": n, "bound": b, "tol": t}

    def cache_info(self):
        """The tile cache now.

        Returns
        -------
        dict
            ``{'budget', 'bytes', 'tiles', 'changed_bytes'}``: the budget,
            the bytes and tiles of coefficients held, and the bytes of
            changed samples kept beside the input (:meth:`update`).
        """
        return dict(zip(("budget", "bytes", "tiles", "changed_bytes"), self._engine.cache_info()))

    def _direct(self):
        return isinstance(self._src, np.ndarray) and self._src.dtype == self._work

    def __call__(self, coordinates, derivative=None):
        """The spline's values (or a partial derivative) at the points.

        Parameters
        ----------
        coordinates : array_like
            ``map_coordinates``' layout: shape ``(ndim, ...)``, one row per
            axis.
        derivative : sequence of int, optional
            One order per axis, as in :func:`splinelab.map_coordinates`.

        Returns
        -------
        ndarray
            Shape ``coordinates.shape[1:]``; float64 (float32 for float32
            input).

        Raises
        ------
        splinelab.errors.CoordinateShapeError
            ``coordinates`` without one row per axis.
        ValueError
            A non-finite coordinate, or a bad ``derivative``.
        """
        at = _coordinates(coordinates, self.ndim)
        flat = np.ascontiguousarray(at.reshape(at.shape[0], -1))
        deriv = _derivative(derivative, self.ndim)
        if self._direct():
            values = self._engine.eval(self._src, flat, self._rule, deriv, self._settings.threads)
        else:
            boxes = self._engine.boxes_for_eval(flat, self._rule)
            fetched = _local.fetch(self._src, boxes, self._work, self._settings.threads)
            values = self._engine.eval_blocks(list(self.shape), fetched, flat, self._rule, deriv,
                                              self._settings.threads)
        if deriv:
            values = values * _reflection_sign(flat, self.shape, self.mode, deriv).astype(values.dtype)
        return values.reshape(at.shape[1:])

    def update(self, key, values):
        """Change the samples as ``a[key] = values`` would.

        The coefficients within reach of the changed samples are recomputed
        in the cached tiles, by the same operations as a rebuild (so the
        same bits). The caller's array is never written: changed samples
        are kept beside it in blocks (:meth:`cache_info`'s
        ``changed_bytes``).

        Parameters
        ----------
        key : index
            Any numpy index of the sample grid (basic or advanced).
        values : array_like
            Broadcast to the selection, as numpy assigns. A non-finite value
            follows ``nan_policy``: refused under 'raise'.

        Raises
        ------
        IndexError
            ``key`` outside the grid (numpy's); the object is unchanged.
        ValueError
            ``values`` that do not broadcast (numpy's), or a non-finite value
            under ``nan_policy='raise'``; the object is unchanged.
        """
        idx, shape = _selected(self.shape, key)
        new = np.empty(shape, self._src.dtype)
        new[...] = values
        new = np.ascontiguousarray(new.ravel(), dtype=self._work)
        if self._direct():
            self._engine.update(self._src, idx, new)
            return
        fetched = _local.fetch(self._src, self._engine.boxes_for_update(idx), self._work, self._settings.threads)
        self._engine.update_blocks(list(self.shape), fetched, idx, new)

    def __reduce__(self):
        return _rebuild, (self._src, self._args, self._engine.changed_blocks())

    def __repr__(self):
        return f"Interpolant(shape={self.shape}, order={self.order}, mode={self.mode!r})"


def _rebuild(src, args, changed):
    """An unpickled :class:`Interpolant`: rebuilt, its changed samples restored."""
    ip = Interpolant(src, **args)
    for first, data in changed:
        ip._engine.restore_block(list(first), np.ascontiguousarray(data, dtype=ip._work))
    return ip
