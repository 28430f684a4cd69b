"""Argument checks shared by the drop-in, the S-spline functions and `check`."""

from __future__ import annotations

import numbers

import numpy as np

MAX_DEGREE = 199


def _int(value, what):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{what} must be an integer, got {type(value).__name__}")
    return int(value)


def _degree(order):
    d = _int(order, "order (the spline degree)")
    if not 0 <= d <= MAX_DEGREE:
        raise ValueError(f"order (the spline degree) {d} is outside 0..{MAX_DEGREE}")
    return d


def _opt_float(value, what):
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{what} must be a real number or None, got {type(value).__name__}")
    return float(value)


# The most threads= accepted: the CLI's clamp of RAYON_NUM_THREADS
# (reports/src/threads.rs). A larger request is refused, not clamped: an
# explicit argument that cannot be honoured is an error, and 10**6 would
# otherwise start a million threads.
MAX_THREADS = 256


def _threads(threads):
    if threads is None:
        return None
    n = _int(threads, "threads")
    if not 1 <= n <= MAX_THREADS:
        raise ValueError(f"threads={n} is outside 1..{MAX_THREADS} (None: one thread per core)")
    return n


def _mode(mode):
    if not isinstance(mode, str):
        raise TypeError(f"mode must be a string, got {type(mode).__name__}")
    return mode


# scipy.ndimage's spline_filter1d has three filters only (ni_splines.c): the
# mirror rule, the reflect (half-sample) rule and the periodic one; every
# mode name maps onto one of them. nearest and grid-constant are *not* the
# spline of the edge- or constant-extended signal there (map_coordinates
# approximates that by padding 12 samples first).


def _real_array(input, what="input"):
    a = np.asarray(input)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"{what} must be a real (float or integer) array, got dtype {a.dtype}")
    return a
