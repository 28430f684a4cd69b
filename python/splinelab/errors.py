"""The exceptions splinelab raises where scipy.ndimage raises ``RuntimeError``.

scipy refuses a bad order, mode, rank, sequence length, output or dtype with
``RuntimeError``; splinelab raised ``ValueError`` or ``TypeError`` there (a
bad value, a bad type). Each class below derives from both, so code written
for scipy (``except RuntimeError``) and code written for splinelab (``except
ValueError``) both catch it. Named after what is wrong; scipy's message for
the same call is in each docstring.
"""

from __future__ import annotations


class OrderError(ValueError, RuntimeError):
    """The spline order (degree) is outside what this function computes
    (splinelab: 0..199, or a degree whose filter cannot be carried in the
    result's dtype; scipy: "spline order not supported")."""


class ModeError(ValueError, RuntimeError):
    """``mode`` is not one of scipy's boundary modes (scipy: "boundary mode
    not supported")."""


class RankError(ValueError, RuntimeError):
    """The input (or the output) has no axes (scipy: "input and output rank
    must be > 0")."""


class SequenceLengthError(ValueError, RuntimeError):
    """A per-axis argument (zoom, shift, offset, ...) does not have one value
    per axis (scipy: "sequence argument must have length equal to input
    rank")."""


class CoordinateShapeError(ValueError, RuntimeError):
    """map_coordinates' coordinates do not have one row per input axis
    (scipy: "invalid shape for coordinate array")."""


class MatrixShapeError(ValueError, RuntimeError):
    """affine_transform's matrix has a shape it does not take (scipy: "no
    proper affine matrix provided", "affine matrix has wrong number of
    rows/columns")."""


class OutputShapeError(ValueError, RuntimeError):
    """An ``output`` array whose shape is not the result's (scipy: "output
    shape not correct")."""


class DtypeError(TypeError, RuntimeError):
    """An input or output dtype the function does not take: not numeric
    (object, strings, ...), or a real output for complex input (scipy:
    "array type ... not supported", "output must have numeric dtype",
    "output must have complex dtype")."""


class ArgumentTypeError(TypeError, RuntimeError):
    """An argument of a type scipy refuses with ``RuntimeError``: a mode
    that is not a string, extra_arguments that is not a tuple,
    extra_keywords that is not a dict."""


class MappingError(TypeError, ValueError):
    """geometric_transform's ``mapping`` is not callable, or returned
    something other than one coordinate per input axis (scipy raises
    TypeError for a return value it cannot read, ValueError for a mapping
    that is not callable)."""
