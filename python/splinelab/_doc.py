"""The numpydoc sections the public functions share, written once.

A docstring names a shared block by a line holding only ``%(name)s``;
:func:`fill` replaces that line with the block, indented as the line is
(scipy's ``_lib.doccer`` works the same way). It runs at import, so
``help()``, Sphinx and the doctests all read the filled text.
"""

from __future__ import annotations

import re
import textwrap

# -- Parameters of the two prefilters (spline_filter1d, spline_filter) ------------
_FILTER = {
    "filter_input": """
input : array_like
    float, integer, bool or complex samples, any strides and shape. Read
    once, strided (and converted when its dtype is not ``output``'s), into
    the C-ordered result, which is then filtered in place: one copy, no
    other. Complex input: the real and imaginary parts through the same
    filter, as scipy.""",
    "filter_order": """
order : int, optional
    The spline **degree**, 0..199 (scipy: 2..5). Degrees 0 and 1 return the
    input, as in scipy. Default 3.""",
    "filter_output": """
output : dtype, str or ndarray, optional
    A dtype or dtype name (default float64; None: the input's dtype), or an
    array of any dtype, byte order and strides to write into (float64 and
    float32 C-contiguous ones directly, others through a temporary;
    ``output=input`` filters in place). Every input is computed in float64,
    as scipy computes it: float64 and float32 input is read where it lies
    (any strides) and widened as it is read. A float32 output is rounded
    after every axis, as scipy rounds it (scipy filters each axis in float64
    line buffers and stores the result in the output): the same accuracy as
    scipy's, and no float64 array of the output's size. Integer and boolean
    results are converted as scipy's filter converts them (truncated toward
    zero, numpy's ``astype``), after every axis; float16 results rounded
    once at the end (scipy refuses float16).""",
    "filter_mode": """
mode : str, optional
    scipy's names and scipy's filters: 'mirror' (default), 'constant',
    'grid-constant' and 'wrap' filter with the mirror rule; 'reflect',
    'grid-mirror' and 'nearest' with the half-sample (reflect) rule;
    'grid-wrap' is periodic (what scipy 1.17 computes, for every degree).""",
    "filter_tol": """
tol : float or None, optional
    None (the exact recursive filter) or a float in (0, 1): certified to
    ``|result - exact| <= bound * max|input|`` with ``bound =
    truncation_width(degree=order, tol=tol)['bound'] < tol``, by the fastest
    route that keeps it: one long line in blocks overlapping by the
    certified width, their recursions side by side in vector lanes and on
    every thread; lines of an N-D array (and short lines) by the exact
    recursion (difference 0). Never slower than ``tol=None``. Default None,
    except under ``nan_policy='local'``: 1e-12. splinelab's own keyword.""",
    "filter_nan_policy": """
nan_policy : {'propagate', 'raise', 'local'}, optional
    What NaN and ±inf samples (missing data) do. splinelab's own keyword.

    - 'propagate' (default): scipy's pattern. The recursive filter carries a
      non-finite sample along its whole line, so every coefficient of every
      line through it along a filtered axis is non-finite (after every axis
      of an N-D array: all of them); other lines as usual.
    - 'raise': ``ValueError("sample k is not finite (nan)")`` naming the
      first (flat index in C order, and its value).
    - 'local': missing samples are filled with 0 and a coefficient is NaN
      only where a missing sample lies within the certified half-width ``n``
      of ``tol`` along every filtered axis (folded by the mode;
      ``nan_reach(order, tol) - (order // 2 + 1)``). Every other coefficient
      is within ``((A + b)**k - (A - b)**k) * max|finite input|`` over ``k``
      filtered axes (``A``, ``b``: :func:`splinelab.filter_bound`'s
      amplification and bound) of the exact coefficients of the input with
      its missing samples filled by ANY values of magnitude at most
      ``max|finite input|``. Needs a finite ``tol`` (default 1e-12;
      ``tol=None`` is refused: no finite reach).

    Integer and boolean input has no NaN; complex input: a NaN in either
    part, that part's pattern.""",
    "filter_compute": """
compute : {'float64', 'float32'}, optional
    'float64' (default: scipy's arithmetic) or 'float32' (splinelab's own):
    float32 arithmetic on float32 samples (other input converted to float32
    first), the result then converted into ``output``. Error about
    ``amplification * 6e-8`` relative per axis (``A = 1.73`` for cubics, 3.3
    for quintics: :func:`splinelab.filter_bound`), against float64's
    rounding of scipy's float32 output; speed: python/bench/float32.py.""",
}

# -- Parameters of the interpolating functions ----------------------------------------
_INTERP = {
    "interp_input": """
input : array_like
    The samples: bool, integer, float or complex (scipy's dtypes), any
    strides. Every input is computed in float64, as scipy computes it
    (complex: complex128, part by part).""",
    "interp_output": """
output : dtype, str or ndarray, optional
    None (the input's dtype), a dtype, a dtype name or an array of any
    dtype, byte order and strides (it may share memory with the input: the
    values are written into it once they are all computed). Results are the
    float64 values rounded once: float32, complex64 and float16 by
    rounding, integer and boolean as scipy rounds them (half away from
    zero, saturated).""",
    "interp_order": """
order : int, optional
    The spline **degree**, 0..199 (scipy: 0..5). Degree 0 picks the nearest
    sample and degree 1 is multilinear, both without a prefilter, as in
    scipy. Default 3.""",
    "interp_mode": """
mode : str, optional
    scipy's eight modes, computed as scipy 1.17 computes them (default
    'constant'): :func:`splinelab.map_coordinates` says how each extends
    the samples.""",
    "cval": """
cval : scalar, optional
    The value outside the grid in 'constant' and 'grid-constant' (may be
    complex for complex input). Default 0.0.""",
    "prefilter": """
prefilter : bool, optional
    True (default): ``input`` holds samples, prefiltered first. False:
    ``input`` already holds the coefficients (e.g. from
    :func:`splinelab.spline_filter` with the same mode), evaluated as given,
    as scipy does (``tol`` does not apply).""",
    "interp_tol": """
tol : float or None, optional
    The prefilter's tolerance, as in :func:`splinelab.spline_filter1d`
    (None: the exact recursive filter; under ``nan_policy='local'`` default
    1e-12). splinelab's own keyword.""",
    "interp_nan_policy": """
nan_policy : {'propagate', 'raise', 'local'}, optional
    What NaN and ±inf samples do, as in :func:`splinelab.spline_filter1d`:
    'propagate' (default, scipy's pattern), 'raise', or 'local' (a missing
    sample reaches the results within :func:`splinelab.nan_reach`
    ``(order, tol)`` input samples; elsewhere within the bound stated
    there). splinelab's own keyword.""",
    "interp_compute": """
compute : {'float64', 'float32'}, optional
    'float64' (default, scipy's arithmetic) or 'float32' (splinelab's own):
    float32 samples and arithmetic, error about ``(A + 1) * 6e-8`` of
    ``max|input|`` (``A``: :func:`splinelab.filter_bound`'s amplification)
    where float64's is that of one rounding of the result; speed in
    python/bench/float32.py.""",
}

# -- Shared by both ---------------------------------------------------------------------
_COMMON = {
    "threads": """
threads : int or None, optional
    None (default: one per core) or the number of threads, 1..256.
    splinelab's own keyword.""",
    "exact_edges": """
exact_edges : bool, optional
    Default False. True: 'nearest' and 'grid-constant' use the exact
    spline of the signal extended by its end samples / by zeros (scipy has
    no such filter; its map_coordinates approximates it by padding 12
    samples). splinelab's own keyword.""",
    "raises": """
splinelab.errors.OrderError
    ``order`` outside 0..199, or a degree whose filter the result's dtype
    cannot carry (the message names one that fits).
splinelab.errors.ModeError
    ``mode`` is not one of scipy's eight.
splinelab.errors.ArgumentTypeError
    ``mode`` is not a string.
splinelab.errors.DtypeError
    An input or output dtype that is not numeric, or a real output for
    complex input.
splinelab.errors.OutputShapeError
    An ``output`` array whose shape is not the result's.
ValueError
    ``tol`` outside (0, 1), ``threads`` outside 1..256, an unknown
    ``nan_policy`` (or ``compute``), a read-only ``output``, a non-finite
    sample under ``nan_policy='raise'``, samples large enough to overflow
    the filter.
TypeError
    An argument of the wrong type (``tol``, ``threads``, ``nan_policy``,
    a flag that is not a bool).
MemoryError
    An output or a work array that cannot be allocated (before any work).""",
    "raises_transform": """
splinelab.errors.RankError
    An input (or output) without axes.
splinelab.errors.SequenceLengthError
    A per-axis argument without one value per axis.""",
}

# -- splinelab.dask -------------------------------------------------------------------
_DASK = {
    "dask_order": """
order : int, optional
    The spline **degree**, 0..199 (scipy's ``order``). Default 3.""",
    "dask_mode": """
mode : str, optional
    scipy's names, as the function of the same name in ``splinelab``
    (its default too).""",
    "dask_cval": """
cval : scalar, optional
    The value outside the grid in 'constant' and 'grid-constant'. Default
    0.0.""",
    "dask_tol": """
tol : float, optional
    The certified per-axis truncation tolerance, in (0, 1) (default 1e-12):
    the overlap is the half-width certified for it plus the spline's
    support (:func:`depth`). None is refused (no certified overlap).""",
    "dask_output": """
output : dtype, optional
    The result's dtype, as the function of the same name in
    ``splinelab``.""",
    "dask_chunks": """
chunks : tuple or str, optional
    The output's chunks (default: the input's chunk size).""",
    "dask_threads": """
threads : int, optional
    Threads per block (default 1: dask already runs blocks in parallel).""",
    "dask_route": """
route : {'truncated', 'recursive'}, optional
    'truncated' (default: the recursion per padded block with zeros beyond
    it, bound ``b`` per axis) or 'recursive' (the block's own mirror
    extension, ``2 b`` at half the tolerance); the module documentation
    says why, :func:`bound` gives the certified error of either.""",
    "dask_nan_policy": """
nan_policy : {'propagate', 'raise', 'local'}, optional
    'propagate' (default, scipy's whole-array pattern by a global
    reduction), 'raise' (when the block holding the sample is computed) or
    'local' (the unchunked pattern whatever the chunking); module
    documentation.""",
    "dask_compute": """
compute : {'float64', 'float32'}, optional
    'float64' (default: every block computed in float64, float32 blocks
    read as they lie, float32 results rounded as the unchunked functions
    round them) or 'float32' (the opt-in float32 arithmetic, as
    :func:`splinelab.spline_filter`).""",
    "dask_prefilter": """
prefilter : bool, optional
    True (default, scipy's): the input is the samples, prefiltered by the
    certified chunked filter. False: the input is taken as the spline's
    coefficients already (scipy's ``prefilter=False``). dask-image's
    ``prefilter`` defaults to False; splinelab's does not.""",
    "dask_output_chunks": """
output_chunks : tuple or str, optional
    dask-image's name for ``chunks``; passing both is a TypeError.""",
    "dask_filter_chunks": """
output_chunks : tuple or str, optional
    The result's chunks (default: the input's). dask-image accepts this
    keyword and ignores it; here the result is rechunked to it.""",
    "dask_depth": """
depth : int, optional
    dask-image's overlap per filtered axis. The overlap used is
    ``max(depth, depth(order, tol, route))``: never less than the certified
    one (a larger one only reads more), so the bound stands either way.""",
    "dask_raises": """
ValueError
    ``tol=None`` or outside (0, 1), an unknown ``route`` or ``nan_policy``,
    and the bad values :func:`splinelab.map_coordinates` refuses.
splinelab.errors.OrderError
    ``order`` outside 0..199.
splinelab.errors.ModeError
    ``mode`` is not one of scipy's eight.
TypeError
    A keyword given under both its splinelab and its dask-image name
    (``chunks`` and ``output_chunks``, the input and ``image``).""",
}

BLOCKS = {**_FILTER, **_INTERP, **_COMMON, **_DASK}
# The runs of parameters most functions list in the same order.
_RUNS = {
    "filter_keywords": ("filter_tol", "threads", "exact_edges", "filter_nan_policy", "filter_compute"),
    "interp_engine": ("interp_tol", "threads", "exact_edges"),
    "interp_tail": ("interp_nan_policy", "interp_compute"),
    "interp_keywords": ("interp_tol", "threads", "exact_edges", "interp_nan_policy", "interp_compute"),
    "interp_args": ("interp_output", "interp_order", "interp_mode", "cval", "prefilter"),
    "dask_tail": ("dask_threads", "dask_route", "dask_nan_policy", "dask_compute"),
    "dask_resample": ("dask_order", "dask_mode", "dask_cval"),
    "dask_resample_keywords": ("dask_tol", "dask_output", "dask_chunks", "dask_threads", "dask_route",
                               "dask_nan_policy", "dask_compute", "dask_prefilter", "dask_output_chunks"),
}
BLOCKS.update({run: "\n".join(BLOCKS[name].strip("\n") for name in names) for run, names in _RUNS.items()})

_LINE = re.compile(r"^([ \t]*)%\((\w+)\)s[ \t]*$", re.M)


def fill(func):
    """``func`` with each ``%(name)s`` line of its docstring replaced by
    ``BLOCKS[name]``, indented as the line (a no-op under ``python -OO``)."""
    if func.__doc__:
        func.__doc__ = _LINE.sub(lambda m: textwrap.indent(BLOCKS[m.group(2)].strip("\n"), m.group(1)), func.__doc__)
    return func
