"""Argument checks shared by the drop-in, the S-spline functions and `check`."""

from __future__ import annotations

import numbers

import numpy as np

MAX_DEGREE = 199


# The widest integer the extension takes (a Rust usize/u64): a larger or
# negative Python int would otherwise surface as PyO3's OverflowError,
# which names no argument.
MAX_INDEX = 2**63 - 1


def _int(value, what, lo=None, hi=None):
    """``value`` as an int, refused (naming ``what``) outside ``lo..hi``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{what} must be an integer, got {type(value).__name__}")
    v = int(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        lo_s = "" if lo is None else str(lo)
        hi_s = "" if hi is None else str(hi)
        raise ValueError(f"{what} {v} is outside {lo_s}..{hi_s}")
    return v


def _count(value, what):
    """A non-negative size or count the extension takes as a usize."""
    return _int(value, what, 0, MAX_INDEX)


def _degree(order):
    return _int(order, "order (the spline degree)", 0, MAX_DEGREE)


def _degree_or_order(degree, order, default=3):
    """The spline degree from ``degree=`` or the papers' ``order=`` (= degree + 1)."""
    if degree is not None and order is not None:
        raise ValueError("give degree= or order= (= degree + 1), not both")
    if order is not None:
        return _int(order, "order (= degree + 1)", 1, MAX_DEGREE + 1) - 1
    return _int(default if degree is None else degree, "degree", 0, MAX_DEGREE)


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
