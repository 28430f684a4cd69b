"""What a bad call raises, and how a result is stored into integer and
boolean outputs, against scipy 1.17.1 live (issue 42). The parity sweep in
test_fault_sweep.py runs hundreds of hostile calls side by side; these are
the rules it relies on, each checked on its own."""

import numpy as np
import pytest

import splinelab
from splinelab import _dtypes as _dt
from splinelab import errors

ndi = pytest.importorskip("scipy.ndimage")

X = np.random.default_rng(7).uniform(-1, 1, (6, 7))

# Values whose C conversion is out of range or undefined in every integer
# type, and values on either side of the types' limits.
SPECIAL = np.array([np.nan, np.inf, -np.inf, 0.5, -0.5, 0.9999999999999999, 1.5, -1.2, 127.5, 128.0, 255.5, 256.0,
                    -129.0, 32767.9, 65535.5, 65536.0, 70000.7, -70000.7, 2.0**31, -(2.0**31) - 1, 2.0**32 + 0.5,
                    -(2.0**32) + 1, 2.0**53, 2.0**63, -(2.0**63), 2.0**64, 3e19, -3e19, 1e300, -1e300])

INTEGERS = [np.bool_, np.uint8, np.int8, np.uint16, np.int16, np.uint32, np.int32, np.uint64, np.int64]


@pytest.mark.parametrize("dtype", INTEGERS)
def test_c_conversion_is_scipys_bit_for_bit(dtype):
    # A line of one sample is its own coefficient: scipy's filter stores
    # each value by its bare C cast (NI_LineBufferToArray).
    theirs = ndi.spline_filter1d(SPECIAL[:, None], order=3, axis=1, output=dtype).ravel()
    ours = _dt.c_convert(SPECIAL, dtype)
    if dtype is np.bool_:
        np.testing.assert_array_equal(ours, theirs.view(np.uint8) != 0)
        np.testing.assert_array_equal(_dt.c_convert(SPECIAL, np.uint8), theirs.view(np.uint8))
    else:
        np.testing.assert_array_equal(ours, theirs)


def _scipy_by_axis(x, dtype, axes):
    """scipy's filter of ``x`` into ``dtype`` along ``axes``, made of its
    float64 passes and :func:`c_convert`: each axis filtered in float64 from
    what the last one stored (booleans: npy_bool's bytes), then stored."""
    carried = _dt.carried_dtype(dtype)
    for axis in axes:
        x = _dt.c_convert(ndi.spline_filter1d(np.asarray(x, dtype=np.float64), axis=axis), carried)
    return x.astype(dtype)


@pytest.mark.parametrize("dtype", INTEGERS)
@pytest.mark.parametrize("scale", [1.0, 300.0, 1e12])
def test_scipys_integer_filters_are_float64_passes_and_c_conversions(dtype, scale):
    # The model splinelab follows, on scipy's own float64 values: exact
    # (booleans carried as 0/1 instead of their bytes differ in 21 of 42).
    np.testing.assert_array_equal(ndi.spline_filter(X * scale, output=dtype), _scipy_by_axis(X * scale, dtype, [0, 1]))
    np.testing.assert_array_equal(ndi.spline_filter1d(X * scale, output=dtype, axis=0),
                                  _scipy_by_axis(X * scale, dtype, [0]))


@pytest.mark.parametrize("dtype", INTEGERS)
@pytest.mark.parametrize("scale", [1.0, 300.0, 1e12])
def test_filters_store_integers_and_booleans_as_scipy(dtype, scale):
    # splinelab's float64 values differ from scipy's by rounding (its
    # filter is exact, scipy's starts from a truncated sum): the stored
    # integers are equal wherever scipy's value is not within 1e-9 of an
    # integer (a truncation that rounding can tip either way).
    for axis in (0, 1):
        theirs = ndi.spline_filter1d(X * scale, output=dtype, axis=axis)
        ours = splinelab.spline_filter1d(X * scale, output=dtype, axis=axis)
        assert ours.dtype == theirs.dtype
        value = ndi.spline_filter1d(X * scale, axis=axis)
        tipped = np.abs(value - np.round(value)) <= 1e-9 * np.maximum(1.0, np.abs(value))
        np.testing.assert_array_equal(ours[~tipped], theirs[~tipped], err_msg=f"{np.dtype(dtype)} x{scale}")


def test_boolean_results_hold_zero_or_one():
    # scipy's hold the low byte (e.g. 255), which numpy reads as True.
    theirs = ndi.spline_filter(X * 300, output=bool)
    ours = splinelab.spline_filter(X * 300, output=bool)
    assert set(np.unique(theirs.view(np.uint8))) - {0, 1}
    assert set(np.unique(ours.view(np.uint8))) <= {0, 1}
    np.testing.assert_array_equal(ours, theirs)


def test_every_class_is_also_scipys():
    for name in ["OrderError", "ModeError", "RankError", "SequenceLengthError", "CoordinateShapeError",
                 "MatrixShapeError", "OutputShapeError"]:
        assert issubclass(getattr(errors, name), ValueError) and issubclass(getattr(errors, name), RuntimeError)
    for name in ["DtypeError", "ArgumentTypeError"]:
        assert issubclass(getattr(errors, name), TypeError) and issubclass(getattr(errors, name), RuntimeError)
    assert issubclass(errors.MappingError, TypeError) and issubclass(errors.MappingError, ValueError)


CALLS = [
    ("spline_filter", (X,), {"order": 200}, errors.OrderError),
    ("spline_filter1d", (X,), {"order": -1}, errors.OrderError),
    ("zoom", (X, 2), {"order": 10**20}, errors.OrderError),
    ("shift", (X, 0.5), {"mode": "bogus"}, errors.ModeError),
    ("rotate", (X, 30), {"mode": 3}, errors.ArgumentTypeError),
    ("zoom", (np.array(1.0), 2), {}, errors.RankError),
    ("zoom", (X, [2, 2, 2]), {}, errors.SequenceLengthError),
    ("shift", (X, [1, 2, 3]), {}, errors.SequenceLengthError),
    ("map_coordinates", (X, [[1.0]]), {}, errors.CoordinateShapeError),
    ("affine_transform", (X, np.ones((3, 2))), {}, errors.MatrixShapeError),
    ("affine_transform", (X, np.eye(2)), {"output_shape": (6, 7), "output": np.zeros((3, 3))},
     errors.OutputShapeError),
    ("spline_filter", (X,), {"output": "U3"}, errors.DtypeError),
    ("shift", (X.astype(object), 0.5), {}, errors.DtypeError),
    ("geometric_transform", (X, lambda o: o), {"extra_arguments": 0.5}, errors.ArgumentTypeError),
]


@pytest.mark.parametrize("fn, args, kwargs, ours", CALLS, ids=[f"{c[0]}-{c[3].__name__}" for c in CALLS])
def test_refusals_are_scipys_class(fn, args, kwargs, ours):
    with pytest.raises(RuntimeError):
        getattr(ndi, fn)(*args, **kwargs)
    with pytest.raises(ours) as info:
        getattr(splinelab, fn)(*args, **kwargs)
    assert isinstance(info.value, RuntimeError) and str(info.value).strip()


def test_a_mapping_that_returns_the_wrong_thing_is_a_type_error_as_in_scipy():
    for mapping in [lambda o: (o[0],), lambda o: ("a", "b")]:
        with pytest.raises(TypeError):
            ndi.geometric_transform(X, mapping)
        with pytest.raises(errors.MappingError, match="mapping returned"):
            splinelab.geometric_transform(X, mapping)


def test_messages_name_the_argument():
    with pytest.raises(ValueError, match=r"angle must be finite, got inf"):
        splinelab.rotate(X, np.inf)
    with pytest.raises(ValueError, match=r"zoom=1e\+300 gives the output shape"):
        splinelab.zoom(X, 1e300)
    with pytest.raises(ValueError):
        ndi.zoom(X, 1e300)


def test_a_degree_beyond_the_range_names_one_that_fits_and_mpfr():
    # Degree 199's growth bound exceeds float64's range along two axes: the
    # refusal is scipy's class for an unsupported order and names a degree
    # whose filter this data does fit, and the MPFR route.
    with pytest.raises(errors.OrderError, match=r"degree 199 cannot be filtered in float64 along 2 axes") as info:
        splinelab.spline_filter(X, order=199)
    message = str(info.value)
    assert "--prec" in message and "0e0" not in message
    fits = int(message.split("; degree ")[1].split(" ")[0])
    assert 5 < fits < 199
    assert np.isfinite(splinelab.spline_filter(X, order=fits)).all()
    with pytest.raises(errors.OrderError):
        splinelab.spline_filter(X, order=fits + 1)


@pytest.mark.parametrize("call", [
    lambda m: m.zoom(X, (1.5, 0)),
    lambda m: m.zoom(X, 0.05),
    lambda m: m.zoom(X, 0.05, order=1),
    lambda m: m.affine_transform(X, np.eye(2), output_shape=(0, 5)),
    lambda m: m.affine_transform(X, [1, 1], output_shape=(5, 0)),
    lambda m: m.geometric_transform(X, lambda o: o, output_shape=(0, 3)),
    lambda m: m.spline_filter1d(np.zeros(0)),
    lambda m: m.spline_filter(np.zeros((0, 5))),
])
def test_empty_outputs_are_scipys_empty_arrays(call):
    theirs, ours = call(ndi), call(splinelab)
    assert ours.shape == theirs.shape and ours.dtype == theirs.dtype and ours.size == 0


def test_non_finite_affine_matrices_give_scipys_values():
    for matrix, offset in [([[1, np.nan], [0, 1]], 0.0), ([[1, np.inf], [0, 1]], 0.0), (np.eye(2), (0, np.nan))]:
        for mode in ["constant", "nearest", "mirror"]:
            theirs = ndi.affine_transform(X, matrix, offset, mode=mode)
            ours = splinelab.affine_transform(X, matrix, offset, mode=mode)
            np.testing.assert_array_equal(np.isnan(ours), np.isnan(theirs))
            np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-12)
