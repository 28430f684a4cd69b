"""scipy.ndimage's resampling functions on the engine: zoom, shift, rotate,
affine_transform and geometric_transform, with scipy 1.17's names,
arguments, defaults and coordinate arithmetic (``_interpolation.py`` and
``NI_ZoomShift`` / ``NI_GeometricTransform`` in ``ni_interpolation.c``:
the same floating-point operations in the same order, so the points are
scipy's to the bit). Each is "the coordinates of every output sample, then
:func:`splinelab.map_coordinates` at them": the prefilter once, then
``(order + 1)**ndim`` multiply-adds per output sample. zoom and shift
(and affine_transform with a diagonal matrix) are separable: their
coordinates are one vector per axis, evaluated by the engine's
tensor-product resampling (``(order + 1)`` multiply-adds per output sample
and axis) when the extension has it.
"""

from __future__ import annotations

import itertools
import math
import numbers
import warnings

import numpy as np

from . import _dtypes as _dt
from . import _splinelab as _ext
from ._doc import fill
from .errors import ArgumentTypeError, MappingError, MatrixShapeError, RankError, SequenceLengthError
from ._engine import _Affine, _affine_points, _direct, _Grid, _interpolate, _map_real, _Points
from ._settings import Settings
from ._validate import DEFAULT_TOL, _flag, _int


def _per_axis(value, ndim, what):
    """scipy's ``_normalize_sequence``: a number for every axis, or one each."""
    if type(value) is float or type(value) is int:  # the common case, without the ABC checks
        return [float(value)] * ndim
    if type(value) is np.ndarray and value.ndim == 1 and value.dtype.kind in "fiu":
        # A vector of real numbers (affine_transform's offsets): numpy's
        # float conversion, the element checks below could not fail.
        if len(value) != ndim:
            raise SequenceLengthError(f"{what} must have one value per axis ({ndim}), got {len(value)}")
        return [float(v) for v in value.tolist()]
    if not isinstance(value, str) and np.iterable(value):
        values = list(value)
        if len(values) != ndim:
            raise SequenceLengthError(f"{what} must have one value per axis ({ndim}), got {len(values)}")
    else:
        values = [value] * ndim
    # A 0-d array counts as its number, as in scipy (np.iterable is False).
    values = [v[()] if isinstance(v, np.ndarray) and v.ndim == 0 else v for v in values]
    for v in values:
        if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Real):
            raise TypeError(f"{what} must be real numbers, got {type(v).__name__}")
    return [float(v) for v in values]


def _at_points(s, input, output, shape, flat_of):
    """The values under the settings ``s`` at the points ``flat_of(a)``
    (``(ndim, prod(shape))``)."""
    points = flat_of(input)
    return _evaluated(s, input, output, shape, points if isinstance(points, _Points) else _Points(points))


def _on_grid(s, input, output, shape, axis_coordinates):
    """The values under the settings ``s`` on the tensor grid of per-axis
    coordinate vectors."""
    return _evaluated(s, input, output, shape, _Grid(axis_coordinates))


def _evaluated(s, input, output, shape, where):
    """The values under the settings ``s`` at ``where`` (a :class:`_Points`
    or :class:`_Grid`): the common call in one step (:func:`_direct`),
    else through the dtype rules of :func:`_interpolate`."""
    values = _direct(input, where, s, output)
    if values is not None:
        return values.reshape(shape)

    def evaluate(a, cv, work):
        return _map_real(a, where, s, cv, work=work)

    return _interpolate(input, output, shape, s.cval, evaluate, compute=s.compute)


def _zoom_shift_coordinates(out_shape, zooms=None, shifts=None, grid_mode=False):
    """``NI_ZoomShift``'s coordinate of output index ``k`` on each axis:
    ``k + shift``, then ``* zoom`` (``grid_mode``: ``+ 0.5``, ``* zoom``,
    ``- 0.5``), in scipy's order of operations."""
    coords = []
    for axis, n in enumerate(out_shape):
        cc = np.arange(n, dtype=np.float64)  # new and contiguous: worked in place
        if shifts is not None:
            cc += shifts[axis]
        if zooms is not None:
            if grid_mode:
                cc += 0.5
                cc *= zooms[axis]
                cc -= 0.5
            else:
                cc *= zooms[axis]
        coords.append(cc)
    return coords


def _early_copy(input, output, shape):
    """zoom by 1 with the prefilter: scipy returns the input converted
    (``output[...] = input``, numpy's conversion), no interpolation."""
    a = np.asarray(input)
    if isinstance(output, np.ndarray):
        out = output
    else:
        dtype = a.dtype if output is None else np.dtype(output)
        if a.dtype.kind == "c" and dtype.kind != "c":
            dtype = np.promote_types(dtype, np.complex64)
        out = np.empty(shape, dtype)
    with np.errstate(invalid="ignore", over="ignore"):
        np.copyto(out, a, casting="unsafe")
    return out


@fill
def zoom(input, zoom, output=None, order=3, mode="constant", cval=0.0, prefilter=True, *, grid_mode=False,
         tol=DEFAULT_TOL, threads=None, exact_edges=False, nan_policy="propagate", compute="float64"):
    """Resample an array by ``zoom`` per axis (``scipy.ndimage.zoom``).

    The output shape is ``round(n * zoom)`` per axis (Python's ``round``);
    output index ``k`` reads the input at ``k * (n - 1) / (m - 1)``
    (``grid_mode=True``: ``(k + 0.5) * n / m - 0.5``, the pixel edges
    aligned; an axis of one output sample reads index 0).

    Parameters
    ----------
    %(interp_input)s
    zoom : float or sequence of float
        The factor along every axis, or one per axis.
    %(interp_args)s
    grid_mode : bool, optional
        False (default): the first and last samples' centres aligned. True:
        the pixel edges aligned (scipy warns, and so does this, for
        'constant' and 'wrap': 'grid-constant' / 'grid-wrap' are meant).
    %(interp_keywords)s

    Returns
    -------
    ndarray
        The resampled array: a new array of ``output``'s dtype, or
        ``output``.

    Raises
    ------
    %(raises_transform)s
    %(raises)s

    Notes
    -----
    Method: scipy 1.17's coordinate arithmetic (``NI_ZoomShift``: the same
    floating-point operations, so scipy's points to the bit), the
    prefilter, then the engine's separable tensor-product evaluation.
    A zoom of 1 on every axis with the prefilter returns the input
    converted, as scipy. Error: as :func:`map_coordinates`. Cost: the
    prefilter, then ``order + 1`` multiply-adds per output sample and axis.
    Memory beside the input and the result: the coefficients
    (:func:`map_coordinates`) and, per thread, the ``order + 2``
    coefficient slabs an output row reads, resampled along the other axes
    (float64; no array of the whole intermediate), float32 results
    written rounded once a row at a time.

    Examples
    --------
    >>> import numpy as np, splinelab
    >>> splinelab.zoom(np.array([0.0, 1.0, 2.0]), 5 / 3, order=1)
    array([0. , 0.5, 1. , 1.5, 2. ])
    """
    if output is None and grid_mode is False and tol is DEFAULT_TOL and exact_edges is False:
        # The common call in one step (splinelab._ndimage.map_coordinates').
        values = _ext.zoom_common(input, zoom, (order, mode, cval, prefilter, threads, nan_policy, compute))
        if values is not None:
            return values
    a = np.asarray(input)
    if a.ndim < 1:
        raise RankError("input must have at least one dimension")
    zooms = _per_axis(zoom, a.ndim, "zoom")
    out_shape = tuple(int(round(n * z)) for n, z in zip(a.shape, zooms))
    if any(m < 0 for m in out_shape):
        raise ValueError(f"zoom gives a negative output shape {out_shape}")
    s = Settings.of(order, mode, cval, prefilter, tol, threads, exact_edges, nan_policy, compute)
    try:
        _reserve_output(a, output, out_shape)
    except ValueError as e:  # numpy's, for a shape beyond its largest: name the argument
        raise ValueError(f"zoom={zoom!r} gives the output shape {out_shape}, which numpy cannot make: {e}") from None
    if all(z == 1 for z in zooms) and s.prefilter:
        return _early_copy(a, output, out_shape)
    grid_mode = _flag(grid_mode, "grid_mode")
    if grid_mode and s.mode in ("constant", "wrap"):
        better = {"constant": "grid-constant", "wrap": "grid-wrap"}[s.mode]
        warnings.warn(f"It is recommended to use mode = {better} instead of {s.mode} when grid_mode is True.",
                      stacklevel=2)
    num = np.array(a.shape)
    div = np.array(out_shape)
    if not grid_mode:
        num, div = num - 1, div - 1
    factors = np.divide(num, div, out=np.ones(a.ndim, dtype=np.float64), where=div != 0)
    coords = _zoom_shift_coordinates(out_shape, zooms=factors, grid_mode=grid_mode)
    return _on_grid(s, a, output, out_shape, coords)


@fill
def shift(input, shift, output=None, order=3, mode="constant", cval=0.0, prefilter=True, *, tol=DEFAULT_TOL,
          threads=None, exact_edges=False, nan_policy="propagate", compute="float64"):
    """Shift an array by ``shift`` samples per axis (``scipy.ndimage.shift``).

    Output index ``k`` reads the input at ``k - shift``.

    Parameters
    ----------
    %(interp_input)s
    shift : float or sequence of float
        The shift along every axis, or one per axis.
    %(interp_args)s
    %(interp_keywords)s

    Returns
    -------
    ndarray
        The shifted array: a new array of ``output``'s dtype, or ``output``.

    Raises
    ------
    %(raises_transform)s
    %(raises)s

    Notes
    -----
    Method, error and memory as :func:`zoom` (scipy's ``NI_ZoomShift``
    coordinates, separable evaluation). Cost: the prefilter, then
    ``order + 1`` multiply-adds per sample and axis.

    Examples
    --------
    >>> import numpy as np, splinelab
    >>> splinelab.shift(np.array([0.0, 1.0, 4.0, 9.0]), 1, order=1, mode="nearest")
    array([0., 0., 1., 4.])
    """
    if output is None and tol is DEFAULT_TOL and exact_edges is False:
        # The common call in one step (splinelab._ndimage.map_coordinates').
        values = _ext.shift_common(input, shift, (order, mode, cval, prefilter, threads, nan_policy, compute))
        if values is not None:
            return values
    a = np.asarray(input)
    if a.ndim < 1:
        raise RankError("input must have at least one dimension")
    shifts = [-s for s in _per_axis(shift, a.ndim, "shift")]
    s = Settings.of(order, mode, cval, prefilter, tol, threads, exact_edges, nan_policy, compute)
    coords = _zoom_shift_coordinates(a.shape, shifts=shifts)
    return _on_grid(s, a, output, a.shape, coords)


def _affine_parts(matrix, offset, ndim, out_ndim):
    """scipy's matrix forms: (ndim,) diagonal, (ndim, out_ndim), and the
    homogeneous (ndim, ndim + 1) / (ndim + 1, ndim + 1) whose last column is
    the offset (then ``offset`` is ignored, as scipy)."""
    m = np.asarray(matrix, dtype=np.float64)
    if m.ndim not in (1, 2) or m.shape[0] < 1:
        raise MatrixShapeError(f"matrix must be 1-D or 2-D, got shape {m.shape}")
    if m.ndim == 2 and m.shape[1] == ndim + 1 and m.shape[0] in (ndim, ndim + 1):
        if m.shape[0] == ndim + 1:
            expected = [0] * ndim + [1]
            if not np.all(m[ndim] == expected):
                raise MatrixShapeError(f"homogeneous matrix of shape {m.shape}: bottom row must be {expected}")
        offset = m[:ndim, ndim]
        m = m[:ndim, :ndim]
    if m.shape[0] != ndim:
        raise MatrixShapeError(f"matrix has {m.shape[0]} rows, expected {ndim} (the input's dimensions)")
    if m.ndim == 2 and m.shape[1] != out_ndim:
        raise MatrixShapeError(f"matrix has {m.shape[1]} columns, expected {out_ndim} (the output's dimensions)")
    offsets = np.asarray(_per_axis(offset if np.ndim(offset) else float(offset), ndim, "offset"))
    return np.ascontiguousarray(m), offsets


def _finite(*arrays):
    """Whether every element of the (small) arrays is finite: Python's test
    on their elements, a quarter of numpy's isfinite-and-all on a matrix."""
    return all(math.isfinite(v) for a in arrays for v in a.ravel().tolist())


def _reserve_output(a, output, shape):
    """Allocates the result and lets it go, as scipy allocates its output
    before any work: a result numpy cannot allocate, or a shape it cannot
    make, raises numpy's MemoryError or ValueError (scipy's) at once, before
    the prefilter runs or the points are formed. Untouched, the pages cost
    nothing."""
    if isinstance(output, np.ndarray):
        return
    a = _dt.input_array(a)
    if a.dtype.kind != "c":
        # Real input: no promotion, so no warning to silence (the context
        # manager costs more than the rest of a small call's checks).
        dtype, _ = _dt.output_dtype(output, a.dtype, None, False)
    else:
        with warnings.catch_warnings():  # the promotion warning comes with the result
            warnings.simplefilter("ignore")
            dtype, _ = _dt.output_dtype(output, a.dtype, None, True)
    np.empty(shape, dtype)


def _output_shape(output_shape, output, default):
    if output_shape is None:
        return tuple(output.shape) if isinstance(output, np.ndarray) else tuple(default)
    shape = tuple(_int(n, "output_shape") for n in output_shape)
    if any(n < 0 for n in shape):
        raise ValueError(f"output_shape must not be negative, got {shape}")
    return shape


@fill
def affine_transform(input, matrix, offset=0.0, output_shape=None, output=None, order=3, mode="constant",
                     cval=0.0, prefilter=True, *, tol=DEFAULT_TOL, threads=None, exact_edges=False,
                     nan_policy="propagate", compute="float64"):
    """Apply an affine transformation (``scipy.ndimage.affine_transform``).

    Output index ``o`` reads the input at ``matrix @ o + offset`` (the
    "pull" direction, as scipy).

    Parameters
    ----------
    %(interp_input)s
    matrix : ndarray
        (ndim,) a diagonal (evaluated separably, as scipy's zoom/shift:
        ``(o + offset / m) * m``), (ndim, out_ndim), or homogeneous
        (ndim, ndim + 1) / (ndim + 1, ndim + 1) with the offset in its last
        column.
    offset : float or sequence of float, optional
        Added to ``matrix @ o``; one value or one per axis. Default 0.0.
    output_shape : tuple of int, optional
        Defaults to ``output``'s shape or the input's.
    %(interp_args)s
    %(interp_keywords)s

    Returns
    -------
    ndarray
        The transformed array, shape ``output_shape``: a new array of
        ``output``'s dtype, or ``output``.

    Raises
    ------
    splinelab.errors.MatrixShapeError
        A matrix of a shape it does not take (or a diagonal with an output
        of another rank).
    %(raises_transform)s
    %(raises)s

    Notes
    -----
    Method: scipy 1.17's coordinate arithmetic (``NI_GeometricTransform``),
    the prefilter, then the B-spline weights of each point. Error: as
    :func:`map_coordinates`. Cost: the prefilter, then
    ``(order + 1)**ndim`` multiply-adds per output sample. Memory beside
    the input and the result: the coefficients only (the points are
    generated where they are evaluated; float32 results rounded once, 2048
    at a time).

    Examples
    --------
    A transpose:

    >>> import numpy as np, splinelab
    >>> x = np.arange(12.0).reshape(3, 4)
    >>> splinelab.affine_transform(x, [[0, 1], [1, 0]], output_shape=(4, 3), order=1)[1]
    array([1., 5., 9.])
    """
    if output is None and output_shape is None and tol is DEFAULT_TOL and exact_edges is False:
        # The common call in one step (splinelab._ndimage.map_coordinates').
        values = _ext.affine_common(input, matrix, offset,
                                    (order, mode, cval, prefilter, threads, nan_policy, compute))
        if values is not None:
            return values
    a = np.asarray(input)
    if a.ndim < 1:
        raise RankError("input must have at least one dimension")
    out_shape = _output_shape(output_shape, output, a.shape)
    if len(out_shape) < 1:
        raise RankError("output must have at least one dimension")
    m, offsets = _affine_parts(matrix, offset, a.ndim, len(out_shape))
    s = Settings.of(order, mode, cval, prefilter, tol, threads, exact_edges, nan_policy, compute)
    return _affine(s, a, m, offsets, out_shape, output)


def _affine(s, a, m, offsets, out_shape, output):
    """affine_transform under the settings ``s`` of a checked matrix ``m``
    (a diagonal or ``(ndim, out_ndim)``) and offset (one per axis)."""
    _reserve_output(a, output, out_shape)
    if m.ndim == 1:
        if len(out_shape) != a.ndim:
            raise MatrixShapeError(f"a diagonal matrix needs an output of {a.ndim} dimensions, got {out_shape}")
        with np.errstate(divide="ignore", invalid="ignore"):
            shifts = offsets / m
        coords = _zoom_shift_coordinates(out_shape, zooms=m, shifts=shifts)
        return _on_grid(s, a, output, out_shape, coords)
    if not _finite(m, offsets):
        return _at_points(s, a, output, out_shape, lambda _: _affine_points(m, offsets, out_shape))
    return _at_points(s, a, output, out_shape, lambda _: _Affine(m, offsets, out_shape))


def _sincos_degrees(angle):
    """``(cos, sin)`` of ``angle`` degrees: the angle reduced exactly to
    ``[-45, 45]`` about a multiple of 90 (``fmod`` and the subtraction are
    exact), so multiples of 90 give exact 0 and ±1 as scipy's
    ``special.cosdg`` / ``sindg`` do; elsewhere within an ulp of them."""
    x = math.fmod(float(angle), 360.0)
    q = round(x / 90.0)
    r = math.radians(x - 90.0 * q)
    s, c = math.sin(r), math.cos(r)
    return [(c, s), (-s, c), (-c, -s), (s, -c)][q % 4]


def _rotation(angle, axes, shape, reshape):
    """scipy.ndimage.rotate's geometry: the sorted plane ``axes``, the 2x2
    matrix from output to input, its offset, the output plane's and the
    whole output's shape (shared by the NumPy and dask rotations)."""
    ndim = len(shape)
    if ndim < 2:
        raise ValueError("input array should be at least 2D")
    axes = list(axes)
    if len(axes) != 2:
        raise ValueError("axes should contain exactly two values")
    if not all(float(ax).is_integer() for ax in axes):
        raise ValueError("axes should contain only integer values")
    axes = [int(ax) + ndim if ax < 0 else int(ax) for ax in axes]
    if not all(0 <= ax < ndim for ax in axes) or axes[0] == axes[1]:
        raise ValueError(f"invalid rotation plane specified: {axes}")
    axes.sort()
    if not math.isfinite(angle):
        # scipy's cosdg/sindg give 0 or NaN there: an empty or constant image.
        raise ValueError(f"angle must be finite, got {angle}")
    c, s = _sincos_degrees(angle)
    rot = np.array([[c, s], [-s, c]])
    # scipy's numpy arithmetic (its matrix products: the same bits), on
    # the plane's two sizes picked out in Python.
    iy, ix = shape[axes[0]], shape[axes[1]]
    in_plane = np.array([iy, ix])
    if reshape:
        bounds = rot @ [[0, 0, iy, iy], [0, ix, 0, ix]]
        out_plane = (bounds.max(axis=1) - bounds.min(axis=1) + 0.5).astype(int)  # np.ptp's max - min
    else:
        out_plane = in_plane.copy()
    offset = (in_plane - 1) / 2 - rot @ ((out_plane - 1) / 2)
    out_shape = [int(n) for n in shape]
    out_shape[axes[0]], out_shape[axes[1]] = out_plane.tolist()
    return axes, rot, offset, out_plane, tuple(out_shape)


@fill
def rotate(input, angle, axes=(1, 0), reshape=True, output=None, order=3, mode="constant", cval=0.0,
           prefilter=True, *, tol=DEFAULT_TOL, threads=None, exact_edges=False, nan_policy="propagate",
           compute="float64"):
    """Rotate an array by ``angle`` degrees in the plane of ``axes`` (``scipy.ndimage.rotate``).

    About the centre ``(n - 1) / 2`` of the plane, the matrix
    ``[[c, s], [-s, c]]`` from output to input.

    Parameters
    ----------
    %(interp_input)s
    angle : float
        In degrees; multiples of 90 give exact 0 and ±1 as scipy's.
    axes : tuple of 2 ints, optional
        The plane of the rotation. Default ``(1, 0)``.
    reshape : bool, optional
        True (default): the plane enlarged to hold the whole rotated input
        (``(extent + 0.5)`` truncated, as scipy).
    %(interp_args)s
    %(interp_keywords)s

    Returns
    -------
    ndarray
        The rotated array: a new array of ``output``'s dtype, or ``output``.

    Raises
    ------
    ValueError
        An input of fewer than two dimensions, or ``axes`` that are not a
        plane of it (scipy's messages).
    %(raises)s

    Notes
    -----
    Method: :func:`affine_transform` with the rotation's matrix; arrays of
    more than two dimensions are rotated plane by plane (each plane
    prefiltered on its own, as scipy). Error and memory as
    :func:`affine_transform`. Cost: the prefilter, then
    ``(order + 1)**2`` multiply-adds per output sample.

    Examples
    --------
    >>> import numpy as np, splinelab
    >>> splinelab.rotate(np.arange(6.0).reshape(2, 3), 90, order=1)
    array([[2., 5.],
           [1., 4.],
           [0., 3.]])
    """
    a = np.asarray(input)
    ndim = a.ndim
    axes, rot, offset, out_plane, out_shape = _rotation(angle, axes, a.shape, reshape)
    if output is None and tol is DEFAULT_TOL and exact_edges is False:
        # The common call in one step per plane (affine_transform's).
        values = _rotate_common(a, axes, rot, offset, out_plane.tolist(), out_shape,
                                (order, mode, cval, prefilter, threads, nan_policy, compute))
        if values is not None:
            return values
    if ndim == 2:
        # affine_transform's checks of the matrix, offset and shape cannot
        # fail on the rotation's own: the settings are the first that can.
        s = Settings.of(order, mode, cval, prefilter, tol, threads, exact_edges, nan_policy, compute)
        return _affine(s, a, rot, offset, out_shape, output)
    kwargs = dict(order=order, mode=mode, cval=cval, prefilter=prefilter, tol=tol, threads=threads,
                  exact_edges=exact_edges, nan_policy=nan_policy, compute=compute)
    # Plane by plane, as scipy (each plane prefiltered on its own), each
    # written into its slice of the result.
    if isinstance(output, np.ndarray):
        _dt.check_output_shape(output, out_shape)
        full = output
    else:
        cplx = a.dtype.kind == "c"
        dtype, _ = _dt.output_dtype(output, a.dtype, _dt.default_output(a.dtype, cplx), cplx)
        full = np.empty(out_shape, dtype)
    plane_shape = tuple(int(n) for n in out_plane)
    for index in itertools.product(*[[slice(None)] if ax in axes else range(a.shape[ax]) for ax in range(ndim)]):
        affine_transform(a[index], rot, offset, plane_shape, full[index], **kwargs)
    return full


def _rotate_common(a, axes, rot, offset, plane, out_shape, settings):
    """:func:`rotate`'s common call: each plane of ``a`` (the array
    itself in 2-D) through affine_transform's one step
    (``_ext.affine_common``) into its slice of the result; None where the
    step declines (on the first plane: every plane has the same shape and
    settings)."""
    if a.ndim == 2:
        return _ext.affine_common(a, rot, offset, settings, plane)
    full = None
    for index in itertools.product(*[[slice(None)] if ax in axes else range(n) for ax, n in enumerate(a.shape)]):
        values = _ext.affine_common(a[index], rot, offset, settings, plane)
        if values is None:
            return None
        if full is None:
            full = np.empty(out_shape, values.dtype)
        full[index] = values
    return full


def _mapped_points(mapping, extra, kwargs, ndim, out_shape):
    """``mapping`` called at every output index (a tuple of ints, C order),
    its coordinates as an array ``(ndim, prod(out_shape))``: the calls made
    by ``map`` and the returns read by ``np.fromiter`` (the loops in C: a
    Python loop and ``np.array`` of the tuples took twice scipy's time on
    16², issue 50). A return that is not ``ndim`` numbers is named, with
    its index, by the loop that stores them one by one; unlike scipy, the
    mapping has then been called at every index. Rows that are all tuples
    or lists of ``ndim`` Python numbers are read by the engine at once
    (``np.fromiter`` and its transposed copy were a fifth of a small call)."""
    indices = itertools.product(*[range(n) for n in out_shape])
    call = mapping if not extra and not kwargs else (lambda index: mapping(index, *extra, **kwargs))
    rows = list(map(call, indices))
    points = _ext.mapped_points(rows, ndim)  # None unless every row is ndim Python numbers
    if points is not None:
        return points
    for k, p in enumerate(rows) if set(map(len, rows)) - {ndim} else ():
        if len(p) != ndim:
            index = next(itertools.islice(itertools.product(*[range(n) for n in out_shape]), k, None))
            raise MappingError(f"mapping returned {len(p)} coordinates at {index}, expected {ndim}")
    try:
        flat = np.fromiter(itertools.chain.from_iterable(rows), np.float64, count=len(rows) * ndim)
        return np.ascontiguousarray(flat.reshape(len(rows), ndim).T)
    except (TypeError, ValueError):
        pass
    points = np.empty((ndim, len(rows)))
    for k, (p, index) in enumerate(zip(rows, itertools.product(*[range(n) for n in out_shape]))):
        try:
            points[:, k] = p
        except (TypeError, ValueError) as e:
            raise MappingError(f"mapping returned {p!r} at {index}: not {ndim} numbers ({e})") from None
    return points


@fill
def geometric_transform(input, mapping, output_shape=None, output=None, order=3, mode="constant", cval=0.0,
                        prefilter=True, extra_arguments=(), extra_keywords=None, *, vectorized=False,
                        tol=DEFAULT_TOL, threads=None, exact_edges=False, nan_policy="propagate",
                        compute="float64"):
    """Apply an arbitrary coordinate mapping (``scipy.ndimage.geometric_transform``).

    Output index ``o`` reads the input at ``mapping(o)``.

    Parameters
    ----------
    %(interp_input)s
    mapping : callable
        ``mapping(out_index, *extra_arguments, **extra_keywords)`` takes a
        tuple of integers (an output index) and returns the input
        coordinates (a sequence of ``input.ndim`` numbers), called once per
        output sample as scipy does.
    output_shape : tuple of int, optional
        Defaults to the input's shape.
    %(interp_args)s
    extra_arguments : tuple, optional
        Passed to ``mapping`` after the index.
    extra_keywords : dict, optional
        Passed to ``mapping`` as keywords.
    vectorized : bool, optional
        splinelab's own keyword. True: ``mapping(indices, ...)`` takes an
        array of shape ``(out_ndim, *output_shape)`` of float64 output
        indices (``numpy.indices``) and returns an array of shape
        ``(input.ndim, *output_shape)``: one call, no Python loop. Default
        False.
    %(interp_keywords)s

    Returns
    -------
    ndarray
        The transformed array, shape ``output_shape``: a new array of
        ``output``'s dtype, or ``output``.

    Raises
    ------
    splinelab.errors.MappingError
        ``mapping`` is not callable, or returned something other than one
        coordinate per input axis.
    splinelab.errors.ArgumentTypeError
        ``extra_arguments`` that is not a sequence or ``extra_keywords``
        that is not a mapping.
    splinelab.errors.RankError
        An input (or output) without axes.
    %(raises)s

    Notes
    -----
    Method: the points from ``mapping``, then :func:`map_coordinates` at
    them. Error and memory as :func:`map_coordinates` (under
    ``nan_policy='raise'`` a non-finite coordinate is a ValueError). Cost:
    the prefilter, ``(order + 1)**ndim`` multiply-adds per sample, and the
    mapping.

    Examples
    --------
    >>> import numpy as np, splinelab
    >>> x = np.arange(5.0) ** 2
    >>> splinelab.geometric_transform(x, lambda o: (o[0] / 2,), output_shape=(3,), order=1)
    array([0. , 0.5, 1. ])
    """
    a = np.asarray(input)
    if a.ndim < 1:
        raise RankError("input must have at least one dimension")
    if not callable(mapping):
        raise MappingError(f"mapping must be callable, got {type(mapping).__name__}")
    out_shape = _output_shape(output_shape, None, a.shape)
    if len(out_shape) < 1:
        raise RankError("output must have at least one dimension")
    try:
        kwargs = {} if extra_keywords is None else dict(extra_keywords)
        extra = tuple(extra_arguments)
    except (TypeError, ValueError) as e:
        raise ArgumentTypeError(f"extra_arguments must be a sequence and extra_keywords a mapping: {e}") from None
    s = Settings.of(order, mode, cval, prefilter, tol, threads, exact_edges, nan_policy, compute)
    _reserve_output(a, output, out_shape)
    if vectorized:
        points = np.asarray(mapping(np.indices(out_shape, dtype=np.float64), *extra, **kwargs), dtype=np.float64)
        if points.shape != (a.ndim, *out_shape):
            raise MappingError(f"mapping returned shape {points.shape}, expected {(a.ndim, *out_shape)}")
        points = points.reshape(a.ndim, -1)
    else:
        points = _mapped_points(mapping, extra, kwargs, a.ndim, out_shape)
    if s.nan_policy == "raise" and not np.isfinite(points).all():
        raise ValueError("mapping returned a non-finite coordinate")
    return _at_points(s, a, output, out_shape, lambda _: points)
