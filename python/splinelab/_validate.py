"""Argument checks shared by the drop-in, the S-spline functions and `check`."""

from __future__ import annotations

import numbers

import numpy as np

from . import _splinelab as _ext
from .errors import ArgumentTypeError, OrderError

MAX_DEGREE = 199


# The widest integer the extension takes (a Rust usize/u64): a larger or
# negative Python int would otherwise surface as PyO3's OverflowError,
# which names no argument.
MAX_INDEX = 2**63 - 1


def _int(value, what, lo=None, hi=None, error=ValueError):
    """``value`` as an int, refused (naming ``what``) outside ``lo..hi``
    with ``error`` (a ValueError)."""
    if type(value) is int:  # the common case, without the ABC checks
        v = value
    elif isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{what} must be an integer, got {type(value).__name__}")
    else:
        v = int(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        lo_s = "" if lo is None else str(lo)
        hi_s = "" if hi is None else str(hi)
        raise error(f"{what} {v} is outside {lo_s}..{hi_s}")
    return v


def _count(value, what):
    """A non-negative size or count the extension takes as a usize."""
    return _int(value, what, 0, MAX_INDEX)


def _degree(order):
    return _int(order, "order (the spline degree)", 0, MAX_DEGREE, OrderError)


def _degree_or_order(degree, order, default=3):
    """The spline degree from ``degree=`` or the papers' ``order=`` (= degree + 1)."""
    if degree is not None and order is not None:
        raise ValueError("give degree= or order= (= degree + 1), not both")
    if order is not None:
        return _int(order, "order (= degree + 1)", 1, MAX_DEGREE + 1) - 1
    return _int(default if degree is None else degree, "degree", 0, MAX_DEGREE)


def _opt_float(value, what):
    if value is None or type(value) is float:
        return value
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
        raise ArgumentTypeError(f"mode must be a string, got {type(mode).__name__}")
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


NAN_POLICIES = ("propagate", "raise", "local")

# nan_policy="local" uses this tolerance unless ``tol`` is given: the
# engine's constant (1e-12), which the CLI's --nan-policy local reads too.
LOCAL_TOL = _ext.LOCAL_TOL


def _nan_policy(value):
    """``nan_policy``: one of 'propagate' (scipy's pattern, the default),
    'raise' or 'local'."""
    if not isinstance(value, str):
        raise TypeError(f"nan_policy must be a string, got {type(value).__name__}")
    if value not in NAN_POLICIES:
        raise ValueError(f"unknown nan_policy {value!r}: expected 'propagate', 'raise' or 'local'")
    return value


class _DefaultTol:
    """``tol``'s default: None (the exact prefilter), or under
    ``nan_policy='local'`` the documented 1e-12; an explicit ``tol=None``
    stays None (and is refused by 'local', which needs a finite reach)."""

    def __repr__(self):
        return f"<None; {LOCAL_TOL:g} with nan_policy='local'>"


DEFAULT_TOL = _DefaultTol()


def _tol_for(tol, nan_policy, degree):
    """The tolerance a call runs with: ``tol`` as given (checked), its
    default resolved for ``nan_policy``; 'local' without one refused where
    there is a prefilter (degree >= 2) to reach through."""
    if tol is DEFAULT_TOL:
        tol = LOCAL_TOL if nan_policy == "local" else None
    tol = _opt_float(tol, "tol")
    if nan_policy == "local" and tol is None and degree >= 2:
        raise ValueError(
            "nan_policy='local' needs a finite tol: with tol=None the exact recursive prefilter carries a "
            "missing sample along its whole line (every axis), so no output has a finite reach; give tol "
            f"(the default under 'local' is {LOCAL_TOL:g}) or use nan_policy='propagate'"
        )
    return tol


def _flag(value, what):
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{what} must be True or False, got {type(value).__name__}")
    return bool(value)


def _cval(cval, complex_input):
    """``cval`` as the engine takes it: a float for real input, a complex
    for complex input."""
    if type(cval) is float and not complex_input:  # the common case, without the ABC checks
        return cval
    if complex_input:
        if isinstance(cval, (bool, np.bool_)) or not isinstance(cval, numbers.Number):
            raise TypeError(f"cval must be a number, got {type(cval).__name__}")
        return complex(cval)
    if isinstance(cval, numbers.Complex) and not isinstance(cval, numbers.Real):
        raise TypeError("cval is complex but the input is real")
    return _opt_float(cval, "cval")
