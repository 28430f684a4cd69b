"""scipy.ndimage's mode names and what the engine makes of them: the one
place where a scipy mode becomes the engine's filter rule, its mode, its
point rule and scipy's padding (issue 50: the drop-in, the local route,
the interpolant and the dask wrappers all ask here)."""

from __future__ import annotations

from . import _splinelab as _ext
from ._validate import MAX_DEGREE, _mode
from .errors import ModeError

#: scipy.ndimage's mode names, as its messages list them.
MODES = "mirror, reflect, grid-mirror, grid-wrap, wrap, nearest, grid-constant, constant"
MODE_NAMES = tuple(MODES.split(", "))
#: The filter scipy's spline_filter1d applies under each mode (ni_splines.c
#: has three: the mirror rule, the reflect (half-sample) rule and the
#: periodic one): the engine's mapping (``python/src/scipy_mode.rs``).
SCIPY_FILTER_RULE = {m: _ext.filter_rule(m, False) for m in MODE_NAMES}
#: :func:`filter_rule` of every scipy mode and ``exact_edges``, from the engine.
_FILTER_RULE = {(m, e): _ext.filter_rule(m, e) for m in MODE_NAMES for e in (False, True)}
#: The modes whose points are folded by whole periods.
PERIODIC = ("grid-wrap", "wrap")


def interp_mode(mode):
    """``mode`` checked: a string (ArgumentTypeError) among scipy's names
    (ModeError)."""
    mode = _mode(mode)
    if mode not in SCIPY_FILTER_RULE:
        raise ModeError(f"unknown mode {mode!r}: expected one of {MODES}")
    return mode


def filter_mode(mode, exact_edges):
    """The engine's filter for scipy's ``mode`` (checked: :func:`interp_mode`)."""
    return filter_rule(interp_mode(mode), exact_edges)


def filter_rule(mode, exact_edges):
    """The engine's filter for a known scipy ``mode`` (its rule), or with
    ``exact_edges`` the exact extension for nearest / grid-constant (cval
    0): the engine's mapping, asked once per setting at import."""
    return _FILTER_RULE[mode, bool(exact_edges)]


def engine_args(mode, d, prefilter, exact_edges):
    """scipy's interpolation ``mode`` as the engine's ``(mode, point rule,
    pad)``: 'constant' is the mirror spline with ``cval`` at points outside
    the grid ('cval-outside'); 'wrap' the mirror spline at the point moved
    by whole periods ``n - 1`` ('wrap'); 'nearest' and 'grid-constant' at
    degrees 2 to 5 with the prefilter (and without ``exact_edges``) scipy's
    route, the samples padded by 12 and filtered with scipy's rule
    (:data:`SCIPY_FILTER_RULE`), the point moved by 12; every other mode
    the engine's own, points folded ('fold'), by its canonical name
    ('grid-mirror' is 'reflect'). The engine's mapping
    (``python/src/scipy_mode.rs``, which its one-step common call takes
    too), asked once per setting at import (:data:`_ENGINE_ARGS`): a
    small call makes no call into the engine but its evaluation."""
    try:
        return _ENGINE_ARGS[mode, d, bool(prefilter), bool(exact_edges)]
    except (KeyError, TypeError):
        raise ValueError(f"unknown mode {mode!r} or degree {d!r}") from None


#: :func:`engine_args` of every scipy mode, degree, prefilter and
#: ``exact_edges``, from the engine.
_ENGINE_ARGS = {(m, d, p, e): _ext.engine_args(m, d, p, e)
                for m in MODE_NAMES for d in range(MAX_DEGREE + 1) for p in (False, True)
                for e in (False, True)}
