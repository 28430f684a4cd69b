"""Data types as scipy.ndimage 1.17 handles them: which arrays are taken,
what ``output`` means, the dtype the engine computes in, and how a float64
result is stored into an integer, boolean or complex output.

Every input is computed in float64 by default, as scipy computes it: the
engine reads float64 and float32 arrays as they lie (widened exactly as it
reads them, no converted copy) and writes float32 results rounded once
from float64 (:class:`Work`). ``compute="float32"`` opts into float32
arithmetic (float32 samples and results, the route before issue 42).

scipy computes every value in float64 and stores it with a C conversion
(``ni_interpolation.c``, ``CASE_INTERP_OUT_INT`` / ``_UINT``): the
interpolation functions round half away from zero and saturate (``t + 0.5``
or ``t - 0.5`` in float64, clamped to the type's range, then truncated);
the filters (``NI_LineBufferToArray``) truncate without rounding or
clamping: a bare C cast, whose result outside the type's range is what
x86-64 gives (:func:`c_convert`; numpy's ``astype`` differs there, e.g. a
negative value into uint64). Booleans are scipy's ``npy_bool``, an unsigned
char: the low byte of the truncated value (so 0.5 is False, -1.2 is True),
which the filters read back as 0..255 when they filter the next axis.
:func:`store_rounded` and :func:`store_truncated` reproduce both bit for
bit, including what x86-64 gives where the C conversion is undefined (NaN,
out of range), as measured on scipy 1.17.1 (python/tests/test_dtypes.py
compares them live). A boolean result holds 0 or 1 (scipy's holds the low
byte itself, which numpy reads as True wherever it is not 0).
"""

from __future__ import annotations

import warnings

import numpy as np

from .errors import DtypeError, OutputShapeError

_NATIVE = frozenset((np.dtype(np.float64), np.dtype(np.float32)))  # hashed: a small call's lookup
COMPUTE = ("float64", "float32")


def compute_name(compute):
    """``compute`` checked: 'float64' (the default: scipy's arithmetic) or
    'float32' (the opt-in float32 arithmetic)."""
    if compute not in COMPUTE:
        raise ValueError(f"compute must be one of {COMPUTE}, got {compute!r}")
    return compute


def engine_samples(a, f32=False):
    """The array the engine reads for samples ``a`` (real): in float64
    arithmetic ``a`` itself where it is native float64 or float32 (read
    where it lies, any strides), else a copy it reads exactly: float32 for
    float16, non-native float32 and integers and booleans of at most 16 bits
    (exact, half the bytes of float64), float64 for the others. In float32
    arithmetic (``f32``) ``a`` as float32."""
    if f32:
        return a.astype(np.float32, copy=False)
    if a.dtype in _NATIVE:
        return a
    exact32 = (a.dtype.kind == "f" and a.dtype.itemsize <= 4) or (a.dtype.kind in "biu" and a.dtype.itemsize <= 2)
    return a.astype(np.float32 if exact32 else np.float64)


class Work:
    """How the engine computes one call: ``f32`` (float32 arithmetic, the
    opt-in) or float64, and the dtype of the values it returns: float32
    where the result part is float32 (each value rounded once from float64
    by the engine) or the arithmetic is float32, float64 otherwise (then
    stored into the result's dtype by :func:`store_rounded`: one rounding
    for float16, scipy's for integers)."""

    def __init__(self, compute, result_part):
        self.f32 = compute_name(compute) == "float32"
        self.out32 = self.f32 or np.dtype(result_part) == np.float32
        self.dtype = np.dtype(np.float32 if self.out32 else np.float64)

    def samples(self, a):
        """The array the engine reads for ``a`` (:func:`engine_samples`)."""
        return engine_samples(a, self.f32)


_WORK = {}


def work_for(compute, result_part):
    """The :class:`Work` of ``compute`` and a result part's dtype, made once
    per pair (read only; a small call would otherwise spend a microsecond
    on it)."""
    key = (compute, result_part)
    work = _WORK.get(key)
    if work is None:
        work = _WORK[key] = Work(compute, result_part)
    return work


def input_array(input, what="input"):
    """``input`` as an array of a numeric dtype scipy takes: bool, integer,
    float or complex."""
    a = np.asarray(input)
    if a.dtype.kind not in "biufc":
        raise DtypeError(f"{what} must be a numeric (bool, integer, float or complex) array, got dtype {a.dtype}")
    return a


def output_dtype(output, input_dtype, default, complex_input):
    """The result dtype and the array to write into (scipy's ``output``:
    None for ``default``, a dtype, a dtype name, or an array). ``default``
    None: scipy's (:func:`default_output`), formed only where it is read.

    Complex input with a real dtype given as a type or dtype is promoted to
    complex with a warning, as scipy does; a real dtype name or a real array
    is refused with :class:`~splinelab.errors.DtypeError` (a TypeError that is
    also scipy's RuntimeError)."""
    target = None
    if isinstance(output, np.ndarray):
        target, dtype = output, output.dtype
        if complex_input and dtype.kind != "c":
            raise DtypeError(f"output must have a complex dtype for complex input, got {dtype}")
    else:
        try:
            if output is None:
                dtype = np.dtype(default_output(input_dtype, complex_input) if default is None else default)
            else:
                dtype = np.dtype(output)
        except TypeError as e:
            raise DtypeError(f"output must be a dtype, a dtype name or an array: {e}") from None
        if complex_input and dtype.kind != "c":
            if isinstance(output, str):
                raise DtypeError(f"output must have a complex dtype for complex input, got {output!r}")
            warnings.warn("promoting specified output dtype to complex", stacklevel=4)
            dtype = np.promote_types(dtype, np.complex64)
    if dtype.kind not in "biufc":
        raise DtypeError(f"output must have a numeric dtype, got {dtype}")
    return dtype, target


def default_output(input_dtype, complex_input):
    """scipy's ``output=None``: the input's dtype (complex input: at least complex64)."""
    native = np.dtype(input_dtype).newbyteorder("=")  # scipy: dtype=input.dtype.name
    if complex_input:
        return np.promote_types(native, np.complex64)
    return native


def real_dtype(dtype):
    """The real dtype of one part of a complex dtype (itself when real)."""
    dtype = np.dtype(dtype)
    if dtype.kind != "c":
        return dtype
    return np.empty(0, dtype).real.dtype


def _round_signed(t, info, itemsize):
    r = np.where(t > 0, t + 0.5, t - 0.5)
    lo, hi = float(info.min), float(info.max)
    nan = np.isnan(r)
    # NaN converts to the type's minimum for 32 and 64 bits and to 0 below
    # (x86-64: cvttsd2si to 32 bits, then truncated to the narrow type).
    nan_value = info.min if itemsize >= 4 else 0
    if itemsize < 8:
        r = np.clip(np.where(nan, 0.0, r), lo, hi)
        out = np.trunc(r).astype(info.dtype)
    else:
        # Above 2**63 scipy stores the maximum; 2**63 itself (not above the
        # maximum as a double) converts to the minimum.
        fits = ~nan & (r > lo) & (r < hi)
        out = np.where(fits, np.trunc(np.where(fits, r, 0.0)), 0.0).astype(info.dtype)
        out = np.where(r > hi, info.max, out)
        out = np.where(r == hi, info.min, out)
        out = np.where(r <= lo, info.min, out)
    return np.where(nan, nan_value, out).astype(info.dtype)


def _round_unsigned(t, info, itemsize):
    r = np.where(t > 0, t + 0.5, 0.0)  # NaN > 0 is false: NaN stores 0
    hi = float(info.max)
    if itemsize < 8:
        r = np.minimum(r, hi)
    else:
        # (double) UINT64_MAX is 2**64, which converts to 0 on x86-64.
        r = np.where(r >= hi, 0.0, r)
    return np.trunc(r).astype(info.dtype)


def _truncated(t, bits):
    """x86-64's ``cvttsd2si`` to a ``bits``-bit register (as int64): ``t``
    truncated toward zero, the register's minimum where that does not fit
    (NaN, infinities, out of range)."""
    lo = -(2.0 ** (bits - 1))
    fits = (t >= lo) & (t < -lo)  # False for NaN
    out = np.trunc(np.where(fits, t, 0.0)).astype(np.int64)
    return np.where(fits, out, np.int64(lo))


def c_convert(t, dtype):
    """Values ``t`` (float64) converted to the integer or boolean ``dtype``
    as a C cast ``(type) t`` compiles for x86-64 (gcc, SSE2): narrow types
    take the low bits of a truncation to 32 bits, ``unsigned int`` of one
    to 64 bits, ``long`` truncates to 64 bits, ``unsigned long`` subtracts
    2**63 first from values at or above it; outside the range the register's
    minimum (``INT_MIN``, ``LONG_MIN``) is what is cut. ``bool`` (scipy's
    ``npy_bool``, an unsigned char) is the low byte, True where not 0."""
    t = np.asarray(t, dtype=np.float64)
    dtype = np.dtype(dtype)
    if dtype.kind == "b":
        return c_convert(t, np.uint8) != 0
    unsigned = np.dtype(f"u{dtype.itemsize}")
    if dtype.itemsize < 4 or dtype == np.int32:
        bits = _truncated(t, 32)
    elif dtype == np.uint64:
        big = t >= 2.0**63
        bits = np.where(big, _truncated(np.where(big, t - 2.0**63, 0.0), 64) ^ np.int64(-(2**63)), _truncated(t, 64))
    else:
        bits = _truncated(t, 64)
    # The low bytes of the two's-complement register, as the type.
    return bits.view(np.uint64).astype(unsigned).view(dtype)


def _to_bool(t):
    return c_convert(t, np.bool_)


# How far (in units in the last place of max(|t|, 1)) a computed value may
# lie from an integer and still count as on it where it is truncated: the
# evaluation's rounding is within about 2·ndim·(degree + 1) ulps of the
# coefficients' magnitude (the separable sums' bound,
# interpolant/separable.rs), a few ulps for the small-amplitude data
# (masks, labels, flat regions) whose exact values are integers.
NOISE_ULPS = 16


def settled(t):
    """``t`` (float64) with each value within :data:`NOISE_ULPS` ulps of an
    integer moved onto it, for a truncating store (booleans; the filters'
    integers): an identity transform of a boolean mask gives 1, computed as
    1 - 2 ulps, which truncation would make False. So the stored result is
    the exact value's, not the rounding's; scipy stores its own rounding's,
    which lands on either side (2 of 20 True samples of
    ``affine_transform(mask, identity, order=3)`` are False in scipy 1.17.1;
    18 were in splinelab without this). Rounded stores (integers from the
    interpolation functions) need none: a value a few ulps from a
    half-integer is as likely a faithful value at a point a few ulps from
    where the exact half lies."""
    t = np.asarray(t, dtype=np.float64)
    with np.errstate(invalid="ignore", over="ignore"):
        grid = np.round(t)
        near = np.abs(t - grid) <= NOISE_ULPS * np.spacing(np.maximum(np.abs(t), 1.0))
    return np.where(near, grid, t)


def store_rounded(t, dtype):
    """Values ``t`` (float64 or float32) as scipy's interpolation functions
    store them into ``dtype``: integers rounded half away from zero and
    saturated, booleans as scipy's unsigned-char conversion, floats and
    complex as numpy converts them."""
    dtype = np.dtype(dtype)
    if dtype.kind in "fc":
        return np.asarray(t).astype(dtype)
    t = np.asarray(t, dtype=np.float64)
    if dtype.kind == "b":
        return _to_bool(t)
    info = np.iinfo(dtype)
    if dtype.kind == "u":
        return _round_unsigned(t, info, dtype.itemsize)
    return _round_signed(t, info, dtype.itemsize)


def store_truncated(t, dtype):
    """Values ``t`` as scipy's filters store them into ``dtype``: a plain C
    conversion (:func:`c_convert`: integers truncated toward zero, out of
    range as x86-64 gives; bool as scipy's unsigned-char conversion, so
    0.9999 is False); floats and complex as numpy converts them."""
    if np.dtype(dtype).kind in "biu":
        return c_convert(np.asarray(t, dtype=np.float64), dtype)
    with np.errstate(invalid="ignore", over="ignore"):
        return np.asarray(t).astype(np.dtype(dtype))


def carried_dtype(dtype):
    """The dtype scipy's filters carry from one axis to the next for a
    result of ``dtype``: ``npy_bool``'s bytes (0..255, read back as values)
    for bool, ``dtype`` itself otherwise."""
    return np.dtype(np.uint8) if np.dtype(dtype).kind == "b" else np.dtype(dtype)


def check_output_shape(target, shape):
    """Refuse an ``output`` array (``target``, None: none given) of another
    shape than ``shape`` with :class:`OutputShapeError`."""
    if target is not None and tuple(target.shape) != tuple(shape):
        raise OutputShapeError(f"output has shape {tuple(target.shape)}, expected {tuple(shape)}")


def deliver(result, target, shape):
    """``result`` written into ``target`` (any dtype, byte order or
    strides) when given, else returned."""
    if target is None:
        return result
    check_output_shape(target, shape)
    if not target.flags.writeable:
        raise ValueError("output is read-only")
    np.copyto(target, result, casting="unsafe")
    return target
