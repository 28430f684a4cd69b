"""The evaluation engine of the drop-in (issue 50: one module, imported by
the functions that evaluate): points to evaluate (scattered, a tensor grid,
an affine map of an output grid) and how a call reaches the extension's
routines, the local route where it reads less (:mod:`splinelab._local`),
scipy's dtype rules around it (:func:`_interpolate`) and scipy's values at
non-finite coordinates. :mod:`splinelab._ndimage` (map_coordinates),
:mod:`splinelab._resample` (zoom, shift, affine_transform, rotate,
geometric_transform) and :mod:`splinelab.dask` call it; scipy's modes
become the engine's in :mod:`splinelab._modes`."""

from __future__ import annotations

import math

import numpy as np

from . import _dtypes as _dt
from . import _local
from . import _splinelab as _ext
from ._modes import PERIODIC, SCIPY_FILTER_RULE, engine_args
from ._validate import _cval


def _refuse_non_finite(a):
    """nan_policy='raise' where no prefilter runs (degrees 0 and 1): the
    first non-finite sample named as the engine names it."""
    if a.dtype.kind not in "fc":
        return
    bad = ~np.isfinite(a)
    if bad.any():
        k = int(np.flatnonzero(bad.ravel())[0])
        v = a.ravel()[k]
        v = v.real if np.isfinite(v.imag) and not np.isfinite(v.real) else (v.imag if np.iscomplexobj(v) else v)
        raise ValueError(f"sample {k} is not finite ({'nan' if np.isnan(v) else 'inf' if v > 0 else '-inf'})")



def _interpolate(input, output, shape, cval, evaluate, *others, compute="float64"):
    """The interpolation functions' dtype handling, as scipy's: every input
    computed in float64 (complex input part by part, ``cval``'s real and
    imaginary parts) and the result of ``output``'s dtype (None: the
    input's) rounded once from it: float32 (and complex64) results by the
    engine as it stores them, float16 by numpy, integer and boolean results
    as scipy rounds them (:func:`splinelab._dtypes.store_rounded`).
    ``compute="float32"``: float32 arithmetic instead (:class:`_dt.Work`).
    ``evaluate(a, cv, work)`` takes the real array the engine reads
    (``work.samples``) and returns the flat values in ``work.dtype``.
    The values are computed into new arrays and only then written into
    ``output``, so an ``output`` that shares memory with ``input`` or the
    coordinates gets the same result as a separate one (scipy's too where it
    reads a prefiltered copy, degrees 2 and above; at degrees 0 and 1 it
    reads samples it has already overwritten)."""
    a = _dt.input_array(input)
    cplx = a.dtype.kind == "c"
    dtype, target = _dt.output_dtype(output, a.dtype, None, cplx)
    _dt.check_output_shape(target, shape)
    cv = _cval(cval, cplx)
    work = _dt.work_for(compute, dtype if dtype.kind != "c" else _dt.real_dtype(dtype))
    if cplx:
        result = np.empty(shape, dtype)
        result.real = evaluate(work.samples(a.real), cv.real, work).reshape(shape)
        result.imag = evaluate(work.samples(a.imag), cv.imag, work).reshape(shape)
    else:
        values = evaluate(work.samples(a), cv, work).reshape(shape)
        if dtype.kind == "b":
            values = _dt.settled(values)  # truncated: see settled
        result = values if values.dtype == dtype else _dt.store_rounded(values, dtype)
    return _dt.deliver(result, target, shape)


def _wrap_axis(x, n):
    """scipy's 'wrap' point rule (``map_coordinate`` in ni_interpolation.c)
    on one axis of ``n`` samples: a coordinate outside ``[0, n - 1]`` moves
    by whole periods ``n - 1`` (the first and last samples overlap) into
    it, with scipy's operations (a C truncating division), so the same
    bits; ``n = 1``: 0."""
    x = np.array(x, dtype=np.float64)
    if n <= 1:
        return np.zeros_like(x)
    sz = float(n - 1)
    low, high = x < 0, x > n - 1
    with np.errstate(invalid="ignore"):  # ±inf becomes NaN: the engine refuses it
        x[low] += sz * (np.trunc(-x[low] / sz) + 1)
        x[high] -= sz * np.trunc(x[high] / sz)
    return x


def _wrap_coordinates(flat, shape):
    """:func:`_wrap_axis` on every row of ``flat`` (``(ndim, k)``)."""
    return np.stack([_wrap_axis(x, n) for x, n in zip(flat, shape)]) if len(shape) else flat


_F64 = _dt.Work("float64", np.float64)


def _engine(run, *args, work=_F64, filter_rule=None, **keywords):
    """The extension's ``run(*args, **keywords)`` in ``work``'s arithmetic
    (float64, float64 or float32 results; or float32) with ``filter_rule``."""
    return run(*args, out32=work.out32, filter_rule=filter_rule, f32=work.f32, **keywords)


class _Points:
    """Points at which to evaluate: scattered, ``(ndim, k)`` (scipy's
    coordinate array), evaluated point by point; the engine's
    ``map_coordinates``. ``work`` (:class:`_dt.Work`): the arithmetic and
    the values' dtype; ``filter_rule``: prefilter the samples under that
    rule and evaluate them as given coefficients (scipy's 'nearest' and
    'grid-constant')."""

    def __init__(self, flat):
        self.flat = flat

    def shifted(self, pad):
        """The points moved by ``pad`` on every axis (scipy's ``x + 12``)."""
        return type(self)([x + pad for x in self.flat])

    def wrapped(self, shape):
        """The points folded by scipy's 'wrap' rule (:func:`_wrap_axis`)."""
        return type(self)([_wrap_axis(x, n) for x, n in zip(self.flat, shape)])

    def count(self):
        """The number of points."""
        flat = self.flat
        return flat.shape[1] if type(flat) is np.ndarray else np.shape(flat)[1]

    def outside(self, shape):
        """Whether each point lies outside ``[0, n - 1]`` on some axis."""
        limit = np.array(shape, dtype=np.float64)[:, None] - 1.0
        flat = np.asarray(self.flat)
        return ((flat < 0) | (flat > limit)).any(axis=0)

    def run(self, a, d, mode, cv, tol, prefilter, threads, deriv, cval_outside=False, nan_policy="propagate",
            work=_F64, filter_rule=None):
        """The values (flat), ``cval`` (its derivative 0) at points outside
        the grid with ``cval_outside`` (scipy's 'constant')."""
        opts = dict(nan_policy=nan_policy, work=work, filter_rule=filter_rule)
        if cval_outside and not deriv and type(self) is _Points:
            # cval outside decided by the engine per point, in parallel.
            return self.evaluate(a, d, mode, cv, tol, prefilter, threads, None, cval_outside=True, **opts)
        values = self.evaluate(a, d, mode, cv, tol, prefilter, threads, deriv, **opts)
        if cval_outside:
            fill = 0.0 if deriv and any(deriv) else cv
            values = np.where(self.outside(a.shape), np.asarray(fill, values.dtype), values)
        return values

    def evaluate(self, a, d, mode, cv, tol, prefilter, threads, deriv, cval_outside=False, nan_policy="propagate",
                 work=_F64, filter_rule=None):
        flat = np.ascontiguousarray(np.asarray(self.flat, dtype=np.float64))
        return _engine(_ext.map_coordinates, a, flat, d, mode, cv, tol, prefilter, threads, deriv, cval_outside,
                       nan_policy, work=work, filter_rule=filter_rule)

    def finite(self):
        """The points with every non-finite coordinate replaced by 0, and
        per axis the masks (NaN, +inf, -inf) of the originals."""
        rows = [np.asarray(x, dtype=np.float64) for x in self.flat]
        masks = [(np.isnan(x), x == np.inf, x == -np.inf) for x in rows]
        return type(self)([np.where(np.isfinite(x), x, 0.0) for x in rows]), masks

    def combine(self, per_axis):
        """Per point, whether any axis' flag (one bool vector per axis) holds."""
        return np.logical_or.reduce([np.asarray(f) for f in per_axis])


class _Grid(_Points):
    """The tensor grid of one coordinate vector per axis (zoom, shift),
    evaluated separably by the engine (``degree + 1`` multiply-adds per
    output sample and axis); values flat in C order."""

    def run(self, a, d, mode, cv, tol, prefilter, threads, deriv, cval_outside=False, nan_policy="propagate",
            work=_F64, filter_rule=None):
        """As :meth:`_Points.run`; ``cval`` (0 for a derivative) written by
        the engine into the slabs of output indices outside ``[0, n - 1]``
        on some axis (no mask of the whole output, no second output
        array)."""
        return self.evaluate(a, d, mode, cv, tol, prefilter, threads, deriv, cval_outside=cval_outside,
                             nan_policy=nan_policy, work=work, filter_rule=filter_rule)

    def count(self):
        return math.prod(len(x) for x in self.flat)

    def evaluate(self, a, d, mode, cv, tol, prefilter, threads, deriv, cval_outside=False, nan_policy="propagate",
                 work=_F64, filter_rule=None):
        axes = [np.ascontiguousarray(x, dtype=np.float64) for x in self.flat]
        return _engine(_ext.resample, a, axes, d, mode, cv, tol, prefilter, list(deriv or [0] * a.ndim), threads,
                       nan_policy, work=work, filter_rule=filter_rule, cval_outside=cval_outside).reshape(-1)

    def combine(self, per_axis):
        """Per grid point (C order), whether any axis' flag holds."""
        flags = np.zeros([len(x) for x in self.flat], dtype=bool)
        for axis, f in enumerate(per_axis):
            shape = [1] * len(per_axis)
            shape[axis] = -1
            flags = flags | np.asarray(f).reshape(shape)
        return flags.reshape(-1)


def _affine_points(m, offsets, out_shape):
    """The points ``m @ o + offset`` of every output index ``o`` as an
    array ``(ndim, prod(out_shape))``: for a matrix or offset that is not
    finite, whose NaN and infinite points then get scipy's values there
    (the engine generates finite points only), and for the local route
    (:meth:`_Affine.explicit`)."""
    index = np.indices(out_shape, dtype=np.float64).reshape(len(out_shape), -1)
    with np.errstate(invalid="ignore", over="ignore"):
        return m @ index + offsets[:, None]


class _Affine(_Points):
    """The points ``matrix @ o + offset`` of every output index ``o``
    (affine_transform, rotate), generated by the engine where they are
    evaluated (no coordinate array; scipy's operations, so its bits)."""

    def __init__(self, matrix, offset, out_shape, shift=0.0, wrap=False):
        self.matrix, self.offset, self.out_shape = matrix, offset, tuple(out_shape)
        self.shift, self.wrap = shift, wrap

    def count(self):
        return math.prod(self.out_shape)

    def shifted(self, pad):
        return _Affine(self.matrix, self.offset, self.out_shape, self.shift + pad, self.wrap)

    def wrapped(self, shape):
        return _Affine(self.matrix, self.offset, self.out_shape, self.shift, True)

    def explicit(self):
        """The points as an array ``(ndim, count)`` (:func:`_affine_points`:
        the engine's values to rounding), for the local route."""
        return _affine_points(self.matrix, self.offset, self.out_shape)

    def run(self, a, d, mode, cv, tol, prefilter, threads, deriv, cval_outside=False, nan_policy="propagate",
            work=_F64, filter_rule=None):
        if deriv:
            raise ValueError("derivatives are taken by map_coordinates, not by the affine resampling")
        rule = "wrap" if self.wrap else "cval-outside" if cval_outside else "fold"
        return _engine(_ext.affine, a, self.matrix, self.offset, list(self.out_shape), d, mode, cv, tol, prefilter,
                       self.shift, rule, threads, nan_policy, work=work, filter_rule=filter_rule).reshape(-1)


_F32_OUT = _dt.work_for("float64", np.dtype(np.float32))
_NATIVE = {np.dtype(np.float64): _F64, np.dtype(np.float32): _F32_OUT}


def _direct(a, points, s, output):
    """The values (flat) of the common call in one step, or None where it is
    not one: a float64 or float32 array in memory (not empty), no
    ``output``, a real ``cval``, float64 arithmetic, a mode the engine
    evaluates without padding or moving the points, and (points or an
    affine map) too many points for the local route. There every rule of
    :func:`_interpolate`, :func:`_map_real` and :func:`_map_points` is the
    identity (the input read where it lies, the result in its dtype), so
    this is their call into the engine, without their checks. A
    non-finite coordinate gives None: the general path refuses it or
    gives scipy's values there."""
    if type(a) is not np.ndarray or output is not None or s.compute != "float64" or not a.size:
        return None
    work = _NATIVE.get(a.dtype)
    cv = s.cval
    if work is None or not (type(cv) is float or type(cv) is int):
        return None
    d, prefilter, tol = s.degree, s.prefilter, s.tol
    if type(points) is not _Grid and _may_be_local(a, points, d, prefilter, tol):
        return None
    mode, rule, pad = engine_args(s.mode, d, prefilter, s.exact_edges)
    if pad or rule == "wrap":
        return None
    try:
        if type(points) is _Grid and all(type(x) is np.ndarray and x.dtype == np.float64 for x in points.flat):
            # zoom's and shift's axes: :meth:`_Grid.run`'s call, without its layers.
            return _ext.resample(a, points.flat, d, mode, float(cv), tol, prefilter, [0] * a.ndim, s.threads,
                                 s.nan_policy, out32=work.out32, f32=False, cval_outside=rule == "cval-outside")
        if type(points) is _Points and type(points.flat) is np.ndarray and points.flat.dtype == np.float64:
            # map_coordinates' points: :meth:`_Points.run`'s call, without
            # its layers (a microsecond of a small call's five).
            return _ext.map_coordinates(a, points.flat, d, mode, float(cv), tol, prefilter, s.threads, None,
                                        rule == "cval-outside", s.nan_policy, out32=work.out32, f32=False)
        if type(points) is _Affine and not points.wrap:
            # affine_transform's and rotate's map: :meth:`_Affine.run`'s call, without its layers.
            return _ext.affine(a, points.matrix, points.offset, list(points.out_shape), d, mode, float(cv), tol,
                               prefilter, points.shift, rule, s.threads, s.nan_policy, out32=work.out32, f32=False)
        return points.run(a, d, mode, float(cv), tol, prefilter, s.threads, None,
                          cval_outside=rule == "cval-outside", nan_policy=s.nan_policy, work=work)
    except _ext.NonFiniteCoordinateError:
        return None


def _map_real(a, flat, s, cv, deriv=None, work=_F64):
    """map_coordinates of a real array the engine reads (``work.samples``)
    at ``flat`` (``(ndim, k)``, or a :class:`_Points`) under the settings
    ``s`` (:class:`splinelab._settings.Settings`; ``cv`` its ``cval`` for
    this array, a float): the values (or the partial derivative ``deriv``),
    flat, in ``work.dtype``. A non-finite coordinate: refused under
    'raise', else scipy's value there (:func:`_at_non_finite`)."""
    points = flat if isinstance(flat, _Points) else _Points(flat)
    if a.size == 0 and s.mode in ("constant", "grid-constant"):
        # An empty axis puts every point outside the grid: cval, as scipy
        # (its other modes read outside the array there; the engine refuses
        # an empty signal).
        return np.full(points.count(), 0.0 if deriv else cv, work.dtype)
    try:
        return _map_points(a, points, s, cv, deriv, work)
    except _ext.NonFiniteCoordinateError:
        if s.nan_policy == "raise" or isinstance(points, _Affine):
            raise
        return _at_non_finite(a, points, s, cv, deriv, work)


#: The largest affine output offered to the local route: its points are
#: formed explicitly to price it (16 bytes per point and axis).
_AFFINE_LOCAL_MAX = 1 << 16


def _may_be_local(a, points, d, prefilter, tol):
    """Whether the local route may take ``points`` on the in-memory array
    ``a`` (:func:`splinelab._local.may_be_local`; always where the route is
    forced). Not scattered points of degree 0 or 1 on a C-contiguous array,
    which the engine reads in place (:func:`splinelab._local.in_place_pays`)
    and no window reads beat; a strided view (a broadcast one among them)
    would be copied whole first, so its windows are read instead."""
    if _local.ROUTE == "local":
        return True
    if type(points) is _Points and a.flags.c_contiguous and _local.in_place_pays(a.shape, points.count(), d):
        return False
    return _local.may_be_local(a.shape, points.count(), d, prefilter, tol)


def _local_candidates(points):
    """The explicit points ``(ndim, k)`` the local route may take
    (:mod:`splinelab._local` decides by cost): map_coordinates' points, and
    those of an affine map (affine_transform, rotate) with a small output,
    whose few samples a large input gives from their windows alone (issue
    45); None for grids (zoom, shift: outputs as large as the input)."""
    if type(points) is _Points:
        return points.flat
    if type(points) is _Affine and not points.shift and not points.wrap and points.count() <= _AFFINE_LOCAL_MAX:
        return points.explicit()
    return None


def _map_points(a, points, s, cv, deriv, work=_F64):
    """:func:`_map_real` at finite points: on the local route where it
    reads less than the global one (:mod:`splinelab._local`; float64
    arithmetic only, and float32 samples only for float32 results, which
    it rounds once as the global route does)."""
    d, mode, prefilter, tol, threads = s.degree, s.mode, s.prefilter, s.tol, s.threads
    nan_policy = s.nan_policy
    flat = None
    if not work.f32 and (a.dtype == np.float64 or work.out32) and _may_be_local(a, points, d, prefilter, tol):
        flat = _local_candidates(points)
    if flat is not None:
        local = _local.try_map(a, flat, s, cv, deriv)
        if local is not None:
            return local.astype(work.dtype, copy=False)
    engine_mode, rule, pad = engine_args(mode, d, prefilter, s.exact_edges)
    if pad:
        # scipy's route (_prepad_for_spline_filter): pad 12, filter with
        # its rule, evaluate the coefficients at x + 12 as given (the
        # engine does both in one coefficient array: the padded copy and
        # that array, as scipy holds).
        if nan_policy == "raise":
            _refuse_non_finite(a)  # named in the input, not in the padded copy
        kind = {"mode": "edge"} if mode == "nearest" else {"mode": "constant", "constant_values": cv}
        return points.shifted(pad).run(np.pad(a, pad, **kind), d, engine_mode, cv, tol, True, threads, deriv,
                                       nan_policy=nan_policy, work=work, filter_rule=SCIPY_FILTER_RULE[mode])
    opts = dict(nan_policy=nan_policy, work=work)
    if rule == "wrap":
        # The mirror spline (scipy filters 'wrap' with the mirror rule and
        # reads the window with it) at the point folded with period n - 1.
        return points.wrapped(a.shape).run(a, d, engine_mode, cv, tol, prefilter, threads, deriv, **opts)
    # scipy's 'constant': no interpolation beyond the edges.
    return points.run(a, d, engine_mode, cv, tol, prefilter, threads, deriv, cval_outside=rule == "cval-outside",
                      **opts)


def _at_non_finite(a, points, s, cv, deriv, work=_F64):
    """Values at points some of whose coordinates are NaN or ±inf, as scipy
    1.17.1 gives them (its C casts the coordinate to an integer, undefined
    behaviour; measured on every mode and order): under the periodic modes
    a NaN or -inf coordinate gives ``cval``, +inf the sample at index 0 on
    that axis for order 0 and NaN above; 'nearest' gives that sample for
    order 0 and NaN above; 'grid-constant' ``cval`` for order 0 and NaN
    above; every other mode ``cval``. The finite points as usual (the
    non-finite coordinates replaced by 0, which also gives the index-0
    samples)."""
    clean, masks = points.finite()
    values = _map_points(a, clean, s, cv, deriv, work).copy()
    d, mode = s.degree, s.mode
    bad = points.combine([n | p | m for n, p, m in masks])
    if mode in PERIODIC:
        to_cval = points.combine([n | m for n, _, m in masks])
        nan = bad & ~to_cval & (d >= 1)
        keep = bad & ~to_cval & (d == 0)
    elif mode in ("nearest", "grid-constant"):
        to_cval = bad & (mode == "grid-constant") & (d == 0)
        nan = bad & (d >= 1)
        keep = bad & (mode == "nearest") & (d == 0)
    else:
        to_cval, nan, keep = bad, np.zeros_like(bad), np.zeros_like(bad)
    fill = 0.0 if deriv and any(deriv) else cv
    values[bad & to_cval & ~keep] = fill
    values[nan] = np.nan
    return values
