"""The float32 accuracy sweep of issue 42, shared by the test
(``test_float32.py``, which asserts splinelab's bar) and the figures script
(``python/bench/float32_accuracy.py``, which runs the same sweep on scipy
side by side).

Every one of the eight functions, orders 0-5, every mode, 1-D to 3-D, on
narrow data (float32, complex64 or float16 samples of normal noise): each
call's result is compared with the same call on the data widened exactly
(float64 / complex128) rounded once to the narrow dtype. A result equal to
it is what scipy's rule gives (compute in float64, round once); the
distance is counted in units in the last place of the narrow dtype.

Outputs: the interpolation functions return the input's dtype (scipy's
``output=None``); ``spline_filter1d`` and 1-D ``spline_filter`` write the
narrow dtype (one axis: one rounding, scipy's rule too); an N-D
``spline_filter`` writes scipy's default float64 (complex128): scipy rounds
a float32 output after every axis, which ``test_float32`` measures apart.
"""

import math

import numpy as np

MODES = ("mirror", "reflect", "grid-mirror", "grid-wrap", "wrap", "nearest", "grid-constant", "constant")
ORDERS = tuple(range(6))
SHAPES = {1: (37,), 2: (11, 10), 3: (6, 5, 7)}
WIDE = {np.dtype(np.float32): np.float64, np.dtype(np.float16): np.float64, np.dtype(np.complex64): np.complex128}


def data(shape, dtype, seed=0):
    """Normal noise of ``shape`` in ``dtype`` (complex: both parts)."""
    rng = np.random.default_rng(seed)
    x = rng.normal(size=shape)
    if np.dtype(dtype).kind == "c":
        x = x + 1j * rng.normal(size=shape)
    return x.astype(dtype)


def calls(nd, shape):
    """``(name, call)`` for the eight functions on arrays of ``shape``:
    ``call(lib, x, order, mode, out)``, ``out`` the output dtype of a
    filter (None: the function's own rule)."""
    rng = np.random.default_rng(nd)
    points = np.stack([rng.uniform(-2, n + 1, 60) for n in shape])
    matrix = np.eye(nd) * 0.93 + 0.07
    centre = [(n - 1) / 2 for n in shape]

    def mapping(o):
        return tuple(0.9 * (c - centre[a]) + centre[a] + 0.3 for a, c in enumerate(o))

    out = [
        ("spline_filter1d", lambda lib, x, o, m, dt: lib.spline_filter1d(x, order=o, mode=m, output=dt)),
        ("spline_filter", lambda lib, x, o, m, dt: lib.spline_filter(x, order=o, mode=m, output=dt)),
        ("map_coordinates", lambda lib, x, o, m, dt: lib.map_coordinates(x, points, order=o, mode=m)),
        ("affine_transform", lambda lib, x, o, m, dt: lib.affine_transform(x, matrix, offset=0.4, order=o, mode=m)),
        ("shift", lambda lib, x, o, m, dt: lib.shift(x, [0.37 - a for a in range(nd)], order=o, mode=m)),
        ("zoom", lambda lib, x, o, m, dt: lib.zoom(x, 1.37, order=o, mode=m)),
        ("geometric_transform", lambda lib, x, o, m, dt: lib.geometric_transform(x, mapping, order=o, mode=m)),
    ]
    if nd >= 2:
        out.append(("rotate", lambda lib, x, o, m, dt: lib.rotate(x, 23.0, order=o, mode=m, reshape=False)))
    return out


def filter_output(name, nd, dtype, wide):
    """The output dtype of a filter call (narrow where one axis is filtered)."""
    one_axis = name == "spline_filter1d" or nd == 1
    return (np.dtype(dtype), np.dtype(wide)) if one_axis else (np.dtype(wide), np.dtype(wide))


def ulps(got, want):
    """|got - want| in units in the last place of ``want``'s dtype (want
    the rounded reference); NaN and equal infinities count 0."""
    got, want = np.asarray(got), np.asarray(want)
    if want.dtype.kind == "c":
        return np.maximum(ulps(got.real, want.real), ulps(got.imag, want.imag))
    same = (got == want) | (np.isnan(got) & np.isnan(want))
    step = np.spacing(np.abs(want)).astype(np.float64)
    with np.errstate(invalid="ignore", over="ignore"):
        d = np.abs(got.astype(np.float64) - want.astype(np.float64)) / step
    return np.where(same, 0.0, np.where(np.isfinite(d), d, math.inf))


def sweep(lib, dtype, **kw):
    """Run the sweep with ``lib`` (splinelab or scipy.ndimage) on data of
    ``dtype``: ``(count, equal, worst, worst_case, refused)`` — outputs
    compared, how many equal the rounded reference, the largest distance in
    ulps and where, and how many calls refused the narrow dtype (scipy:
    float16). ``kw`` goes to splinelab's calls (``compute=``)."""
    dtype = np.dtype(dtype)
    wide = WIDE[dtype]
    count = equal = refused = 0
    worst, worst_case = 0.0, None
    for nd, shape in SHAPES.items():
        x = data(shape, dtype, seed=nd)
        xw = x.astype(wide)
        for name, call in calls(nd, shape):
            for order in ORDERS:
                for mode in MODES:
                    if name.startswith("spline_filter"):
                        out, out_wide = filter_output(name, nd, dtype, wide)
                    else:
                        out = out_wide = None
                    try:
                        got = call(_with(lib, kw), x, order, mode, out)
                    except RuntimeError:
                        refused += 1
                        continue
                    want = call(lib, xw, order, mode, out_wide).astype(got.dtype)
                    d = ulps(got, want)
                    count += d.size
                    equal += int((d == 0).sum())
                    if d.size and d.max() > worst:
                        worst, worst_case = float(d.max()), (name, nd, order, mode)
    return count, equal, worst, worst_case, refused


class _with:
    """``lib`` with keyword arguments ``kw`` added to every call."""

    def __init__(self, lib, kw):
        self.lib, self.kw = lib, kw

    def __getattr__(self, name):
        f = getattr(self.lib, name)
        return (lambda *a, **k: f(*a, **k, **self.kw)) if self.kw else f
