"""Small calls (issue 50): the route is decided before any call into the
engine where the shapes and the point count decide it, the same decision
as the engine's pricing of both routes, and a small call makes one call
into the engine, the evaluation (no local route tried and declined, no
explicit points formed). Speed is measured by python/bench/small_calls.py,
not here."""

import numpy as np
import pytest
import scipy.ndimage as ndi
from hypothesis import given, settings
from hypothesis import strategies as st

import splinelab
from splinelab import _local, _modes
from splinelab import _splinelab as ext

MODES = ["constant", "mirror", "reflect", "grid-mirror", "grid-wrap", "wrap", "nearest", "grid-constant"]


@st.composite
def calls(draw):
    ndim = draw(st.integers(1, 3))
    shape = tuple(draw(st.lists(st.integers(1, 48 if ndim < 3 else 16), min_size=ndim, max_size=ndim)))
    k = draw(st.integers(0, 400))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    # Inside, near and outside the grid: the local route locates cval points too.
    flat = np.stack([rng.uniform(-3.0, n + 2.0, k) for n in shape]).reshape(ndim, k)
    d = draw(st.integers(0, 7))
    return dict(shape=shape, flat=flat, d=d, mode=draw(st.sampled_from(MODES)), prefilter=draw(st.booleans()),
                tol=draw(st.sampled_from([None, 1e-6, 1e-12])), exact_edges=draw(st.booleans()))


def _priced(c):
    mode, rule, pad = _local.engine_args(c["mode"], c["d"], c["prefilter"], c["exact_edges"])
    return ext.local_route_cost(list(c["shape"]), np.ascontiguousarray(c["flat"]), c["d"], mode, c["tol"],
                                c["prefilter"], rule, pad)


@settings(max_examples=300, deadline=None)
@given(calls())
def test_the_count_decides_the_global_route_only_where_the_engine_prices_it_so(c):
    """Where ``may_be_local`` (shape and point count alone) says the local
    route cannot win, the engine's pricing of both routes, the points
    located and grouped, prices the local route at least as high as the
    global one; and wherever it is priced, the local route costs at least
    the floor the count alone gives, and the global route what the count
    formula says."""
    k = c["flat"].shape[1]
    local_ns, global_ns, _, _ = _priced(c)
    cost = _local._COST
    filtered = c["prefilter"] and c["d"] >= 2
    assert local_ns >= _local.floor_ns(len(c["shape"]), k, c["d"], filtered, c["tol"]) * (1 - 1e-12)
    per_sample = cost["global"] * len(c["shape"]) * filtered + cost["copy"]
    assert global_ns == pytest.approx(np.prod(c["shape"]) * per_sample, rel=1e-12)
    if not _local.may_be_local(c["shape"], k, c["d"], c["prefilter"], c["tol"]):
        assert local_ns >= global_ns


@settings(max_examples=100, deadline=None)
@given(calls())
def test_the_engine_declines_where_the_count_decides_the_global_route(c):
    """The engine's own decision (``local_map_f64`` unforced) is the global
    route wherever ``may_be_local`` is False."""
    k = c["flat"].shape[1]
    if _local.may_be_local(c["shape"], k, c["d"], c["prefilter"], c["tol"]):
        return
    a = np.random.default_rng(0).normal(size=c["shape"])
    mode, rule, pad = _local.engine_args(c["mode"], c["d"], c["prefilter"], c["exact_edges"])
    nan_policy = "propagate"
    out = ext.local_map_f64(a, np.ascontiguousarray(c["flat"]), c["d"], mode, 0.0, c["tol"], c["prefilter"], None,
                            None, rule, nan_policy, pad, False)
    assert out is None


@settings(max_examples=300, deadline=None)
@given(calls())
def test_the_in_place_decision_is_the_engines(c):
    """``in_place_pays`` (shape, count and degree alone) decides as the
    engine's ``route::in_place_pays`` does, and never for degrees above 1
    (their coefficients are not the samples)."""
    k = c["flat"].shape[1]
    ours = _local.in_place_pays(c["shape"], k, c["d"])
    assert ours == ext.in_place_pays(list(c["shape"]), k, c["d"])
    assert not (ours and c["d"] > 1)


@settings(max_examples=200, deadline=None)
@given(calls(), st.sampled_from([np.float64, np.float32]))
def test_points_read_in_place_are_scipys(c, dtype):
    """Degrees 0 and 1 at points the engine reads in place (and at those
    it reads through its padded copy): scipy's values, every mode, points
    inside, at and beyond the edges. Degree 1 to rounding; degree 0 the
    same sample, except at the half-integers where scipy's ``floor(x +
    0.5)`` in float64 and the exact rounding part (none drawn here)."""
    d = c["d"] % 2
    a = np.random.default_rng(5).normal(size=c["shape"]).astype(dtype)
    kw = dict(order=d, mode=c["mode"], cval=0.25)
    theirs = ndi.map_coordinates(a, c["flat"], **kw)
    ours = splinelab.map_coordinates(a, c["flat"], **kw)
    assert ours.dtype == theirs.dtype
    tol = 0 if d == 0 else (2e-6 if dtype == np.float32 else 1e-14)
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=tol * 4)


@pytest.fixture
def engine_calls(monkeypatch):
    """Every call into the extension's functions, by name, in order."""
    seen = []
    for name in dir(ext):
        f = getattr(ext, name)
        if type(f).__name__ != "builtin_function_or_method":
            continue

        def counted(*args, _f=f, _name=name, **kwargs):
            seen.append(_name)
            return _f(*args, **kwargs)

        monkeypatch.setattr(ext, name, counted)
    return seen


def _small_calls():
    rng = np.random.default_rng(3)
    x, x3 = rng.normal(size=(16, 16)), rng.normal(size=(8, 8, 8))
    pts = rng.uniform(0, 15, (2, 25))
    rot = np.array([[0.9, 0.3], [-0.3, 0.9]])
    yield "map_coordinates", lambda o: splinelab.map_coordinates(x, pts, order=o), "map_coordinates_common"
    small = x[:8, :8].copy()
    yield "map_coordinates 1 point", lambda o: splinelab.map_coordinates(small, np.array([[3.3], [4.6]]), order=o), \
        "map_coordinates_common"
    yield "map_coordinates view", lambda o: splinelab.map_coordinates(x[:8, 3:11], pts / 2, order=o), \
        "map_coordinates_common"
    yield "map_coordinates list", lambda o: splinelab.map_coordinates(small, [[3.3], [4.6]], order=o), \
        "map_coordinates_common map_coordinates"
    yield "map_coordinates float32", lambda o: splinelab.map_coordinates(x.astype(np.float32), pts, order=o), \
        "map_coordinates_common"
    yield "affine_transform", lambda o: splinelab.affine_transform(x, rot, (0.7, -0.2), order=o), "affine_common"
    yield "rotate", lambda o: splinelab.rotate(x, 30, order=o), "affine_common"
    yield "shift", lambda o: splinelab.shift(x, 0.3, order=o), "shift_common"
    yield "zoom", lambda o: splinelab.zoom(x3, 2, order=o), "zoom_common"
    # The mapping's returns read into points by the engine, then one evaluation.
    yield "geometric_transform", lambda o: splinelab.geometric_transform(x, lambda c: (c[0] - 0.3, c[1]), order=o), \
        "mapped_points map_coordinates"
    yield "spline_filter", lambda o: splinelab.spline_filter(x, order=max(o, 2)), "filter_common"
    yield "spline_filter1d", lambda o: splinelab.spline_filter1d(x, order=max(o, 2)), "filter_common"


@pytest.mark.parametrize("order", [0, 1, 3, 5])
@pytest.mark.parametrize("name, call, engine", list(_small_calls()), ids=[c[0] for c in _small_calls()])
def test_a_small_call_makes_one_engine_call_the_evaluation(engine_calls, name, call, engine, order):
    call(order)
    assert engine_calls == engine.split()


@pytest.mark.parametrize("order", [0, 1])
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("output", [None, np.float64, np.float32])
def test_a_filter_of_degree_0_or_1_is_scipys_copy_in_one_call(engine_calls, order, dtype, output):
    """scipy's spline_filter1d of degree 0 or 1 is ``output[...] = input``:
    the same values (float64 to float32 rounded as numpy rounds), a new
    array, one call into the extension (its one step, which copies) and no
    filter."""
    x = np.random.default_rng(4).normal(size=(8, 8)).astype(dtype) * np.float64(1e300 if dtype == np.float64 else 1)
    with np.errstate(over="ignore"):
        theirs = ndi.spline_filter1d(x, order, axis=-1, output=output or x.dtype)
    ours = splinelab.spline_filter1d(x, order, axis=-1, output=output)
    assert engine_calls == ["filter_common"]
    assert ours.dtype == theirs.dtype and not np.shares_memory(ours, x)
    np.testing.assert_array_equal(ours, theirs)


def _common_calls():
    """The calls the one-step path takes (an array, no ``output``, every
    keyword at its default), each with its scipy twin."""
    rng = np.random.default_rng(6)
    for dtype in (np.float64, np.float32):
        x = rng.normal(size=(16, 16)).astype(dtype)
        pts = rng.uniform(-1, 16, (2, 25))
        rot = np.array([[0.9, 0.3], [-0.3, 0.9]])
        for order in (0, 1, 3, 5):
            for mode in ("constant", "mirror", "grid-wrap"):
                kw = dict(order=order, mode=mode, cval=0.5)
                yield "shift", (x, 0.3), kw
                yield "zoom", (x, 1.5), kw
                yield "rotate", (x, 30), kw
                yield "affine_transform", (x, rot, np.array([0.7, -0.2])), kw
                yield "map_coordinates", (x, pts), kw
            if order >= 2:
                yield "spline_filter1d", (x, order), dict(axis=0, output=dtype)
                yield "spline_filter", (x, order), dict(output=dtype)


@pytest.mark.parametrize("name, args, kw", list(_common_calls()))
def test_the_common_call_is_scipys_and_the_general_paths_to_the_bit(name, args, kw):
    """The one-step path (no ``output``, defaults) gives scipy's values
    (to rounding) and the general path's bits (``output`` given by the
    name of the dtype it has: every check and dtype rule runs)."""
    x = args[0]
    theirs = getattr(ndi, name)(*args, **kw)
    ours = getattr(splinelab, name)(*args, **kw)
    general = getattr(splinelab, name)(*args, **{**kw, "output": np.dtype(theirs.dtype).name})
    assert ours.dtype == theirs.dtype == general.dtype
    np.testing.assert_array_equal(ours, general)
    tol = 1e-4 if x.dtype == np.float32 else 1e-9
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=tol * max(1.0, np.abs(theirs).max()))


@pytest.mark.parametrize("order", [0, 1])
def test_a_broadcast_view_at_few_points_reads_only_their_samples(order):
    """Degrees 0 and 1 read a C-contiguous array in place; a strided view
    (here a 40000² zero-stride broadcast, 12.8 GB if copied) is not copied
    whole to be read in place but takes the local route's windows:
    scipy's values."""
    huge = np.broadcast_to(np.arange(40000.0), (40000, 40000))
    c = np.array([[0.5, 2.25, 100.7, -3.2], [1.0, 30000.5, 2.5, 39999.9]])
    for mode in ("constant", "mirror", "nearest"):
        theirs = ndi.map_coordinates(huge, c, order=order, mode=mode)
        # Degree 1 to rounding (scipy forms the weights otherwise).
        np.testing.assert_allclose(splinelab.map_coordinates(huge, c, order=order, mode=mode), theirs,
                                   rtol=0, atol=4e-16 * order * 40000)


# scipy's interpolation modes as the engine evaluates them, written out from
# scipy 1.17's ni_interpolation.c / _interpolation.py: 'constant' gives cval
# outside [0, n - 1] and the mirror spline inside; 'wrap' moves points by
# n - 1; 'nearest' and 'grid-constant' pad 12 samples at degrees 2..5 with
# the prefilter (NI_GeometricTransform's npad); the rest fold.
_SCIPY_MODES = {
    "constant": ("mirror", "cval-outside"), "wrap": ("mirror", "wrap"), "mirror": ("mirror", "fold"),
    "reflect": ("reflect", "fold"), "grid-mirror": ("reflect", "fold"), "grid-wrap": ("grid-wrap", "fold"),
    "nearest": ("nearest", "fold"), "grid-constant": ("grid-constant", "fold"),
}


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("d", [0, 1, 2, 3, 5, 6, 9])
@pytest.mark.parametrize("prefilter", [True, False])
@pytest.mark.parametrize("exact_edges", [True, False])
def test_engine_args_are_scipys_modes(mode, d, prefilter, exact_edges):
    padded = mode in ("nearest", "grid-constant") and prefilter and 2 <= d <= 5 and not exact_edges
    assert _local.engine_args(mode, d, prefilter, exact_edges) == (*_SCIPY_MODES[mode], 12 if padded else 0)


# The filter scipy 1.17's spline_filter1d runs under each mode (ni_splines.c:
# the mirror rule, the reflect rule, the periodic rule), and with
# exact_edges the exact extensions of 'nearest' and 'grid-constant'.
_SCIPY_FILTERS = {"mirror": "mirror", "constant": "mirror", "grid-constant": "mirror", "wrap": "mirror",
                  "reflect": "reflect", "grid-mirror": "reflect", "nearest": "reflect", "grid-wrap": "grid-wrap"}


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("exact_edges", [True, False])
def test_filter_rules_are_scipys(mode, exact_edges):
    want = mode if exact_edges and mode in ("nearest", "grid-constant") else _SCIPY_FILTERS[mode]
    assert _modes.filter_rule(mode, exact_edges) == want
    assert _modes.SCIPY_FILTER_RULE[mode] == _SCIPY_FILTERS[mode]


def test_engine_args_refuse_an_unknown_mode():
    with pytest.raises(ValueError, match="unknown mode"):
        _local.engine_args("edge", 3, True, False)


def _outcome(call):
    try:
        v = call()
    except Exception as e:  # noqa: BLE001 (the class and message are compared)
        return type(e), str(e)
    return v.dtype, v.shape, v.tobytes()


_X = np.random.default_rng(11).normal(size=(9, 7))
_PTS = np.random.default_rng(12).uniform(-2, 9, (2, 3, 4))
_ODD_CALLS = {
    "points (2, 3, 4)": lambda: splinelab.map_coordinates(_X, _PTS, order=1),
    "one point (2,)": lambda: splinelab.map_coordinates(_X, np.array([2.5, 3.25]), order=3),
    "float32": lambda: splinelab.map_coordinates(_X.astype(np.float32), _PTS, order=3, mode="reflect"),
    "int cval": lambda: splinelab.map_coordinates(_X, _PTS, order=1, cval=2),
    "huge int cval": lambda: splinelab.map_coordinates(_X, _PTS, order=1, cval=10**400),
    "numpy cval": lambda: splinelab.map_coordinates(_X, _PTS, order=1, cval=np.float32(0.5)),
    "bool cval": lambda: splinelab.map_coordinates(_X, _PTS, order=1, cval=True),
    "complex cval": lambda: splinelab.map_coordinates(_X, _PTS, order=1, cval=0j),
    "nan cval": lambda: splinelab.map_coordinates(_X, _PTS, order=0, cval=np.nan),
    "float order": lambda: splinelab.map_coordinates(_X, _PTS, order=1.0),
    "bool order": lambda: splinelab.map_coordinates(_X, _PTS, order=True),
    "numpy order": lambda: splinelab.map_coordinates(_X, _PTS, order=np.int64(3)),
    "order 6": lambda: splinelab.map_coordinates(_X, _PTS, order=6),
    "order 200": lambda: splinelab.map_coordinates(_X, _PTS, order=200),
    "order -1": lambda: splinelab.map_coordinates(_X, _PTS, order=-1),
    "int prefilter": lambda: splinelab.map_coordinates(_X, _PTS, order=3, prefilter=1),
    "no prefilter": lambda: splinelab.map_coordinates(_X, _PTS, order=3, prefilter=False),
    "numpy prefilter": lambda: splinelab.map_coordinates(_X, _PTS, order=3, prefilter=np.True_),
    "bad mode": lambda: splinelab.map_coordinates(_X, _PTS, order=1, mode="edge"),
    "bytes mode": lambda: splinelab.map_coordinates(_X, _PTS, order=1, mode=b"mirror"),
    "wrap": lambda: splinelab.map_coordinates(_X, _PTS, order=3, mode="wrap"),
    "nearest cubic": lambda: splinelab.map_coordinates(_X, _PTS, order=3, mode="nearest"),
    "grid-constant linear": lambda: splinelab.map_coordinates(_X, _PTS, order=1, mode="grid-constant", cval=3.0),
    "threads 1": lambda: splinelab.map_coordinates(_X, _PTS, order=3, threads=1),
    "threads 0": lambda: splinelab.map_coordinates(_X, _PTS, order=3, threads=0),
    "threads True": lambda: splinelab.map_coordinates(_X, _PTS, order=3, threads=True),
    "threads 10**6": lambda: splinelab.map_coordinates(_X, _PTS, order=3, threads=10**6),
    "nan_policy raise": lambda: splinelab.map_coordinates(_X, _PTS, order=3, nan_policy="raise"),
    "nan_policy bad": lambda: splinelab.map_coordinates(_X, _PTS, order=3, nan_policy="omit"),
    "compute float32": lambda: splinelab.map_coordinates(_X.astype(np.float32), _PTS, order=3, compute="float32"),
    "compute bad": lambda: splinelab.map_coordinates(_X, _PTS, order=3, compute="float16"),
    "non-finite point": lambda: splinelab.map_coordinates(_X, np.array([[np.nan, 1.0], [2.0, 3.0]]), order=1),
    "infinite point, cubic": lambda: splinelab.map_coordinates(_X, np.array([[np.inf], [2.0]]), order=3),
    "nan sample": lambda: splinelab.map_coordinates(np.where(_X > 1, np.nan, _X), _PTS, order=1),
    "wrong rows": lambda: splinelab.map_coordinates(_X, _PTS[:1], order=1),
    "0-d coordinates": lambda: splinelab.map_coordinates(_X, np.array(1.0), order=1),
    "float32 coordinates": lambda: splinelab.map_coordinates(_X, _PTS.astype(np.float32), order=1),
    "big-endian coordinates": lambda: splinelab.map_coordinates(_X, _PTS.astype(">f8"), order=1),
    "strided coordinates": lambda: splinelab.map_coordinates(_X, _PTS[:, ::2], order=1),
    "strided input": lambda: splinelab.map_coordinates(_X[::2], _PTS / 2, order=1),
    "Fortran input": lambda: splinelab.map_coordinates(np.asfortranarray(_X), _PTS, order=3),
    "int input": lambda: splinelab.map_coordinates(_X.astype(np.int32), _PTS, order=1),
    "matrix input": lambda: splinelab.map_coordinates(np.asmatrix(_X), _PTS, order=1),
    "empty input": lambda: splinelab.map_coordinates(np.empty((0, 3)), _PTS, order=1),
    "empty points": lambda: splinelab.map_coordinates(_X, np.empty((2, 0)), order=3),
    "0-d input": lambda: splinelab.map_coordinates(np.array(1.0), np.empty((0, 2)), order=1),
    "1-d input": lambda: splinelab.map_coordinates(_X[0], _PTS[:1], order=5, mode="grid-wrap"),
}


_ROT = np.array([[0.9, 0.3], [-0.3, 0.9]])
_X32 = _X.astype(np.float32)
_ODD_SHIFTS = {
    "shift": lambda: splinelab.shift(_X, 0.3, order=1),
    "shift cubic": lambda: splinelab.shift(_X, 0.3, order=3, mode="grid-wrap"),
    "shift int": lambda: splinelab.shift(_X, 2, order=0),
    "shift huge int": lambda: splinelab.shift(_X, 10**400, order=0),
    "shift tuple": lambda: splinelab.shift(_X, (0.5, -1.25), order=1, cval=-1.0),
    "shift list of ints": lambda: splinelab.shift(_X, [1, -2], order=1),
    "shift array": lambda: splinelab.shift(_X, np.array([0.5, 2.0]), order=1),
    "shift int array": lambda: splinelab.shift(_X, np.array([1, 2]), order=1),
    "shift short tuple": lambda: splinelab.shift(_X, (0.5,), order=1),
    "shift nested": lambda: splinelab.shift(_X, [[0.5], [1.0]], order=1),
    "shift bool": lambda: splinelab.shift(_X, True, order=1),
    "shift complex": lambda: splinelab.shift(_X, 1j, order=1),
    "shift nan": lambda: splinelab.shift(_X, np.nan, order=1),
    "shift inf": lambda: splinelab.shift(_X, (np.inf, 0.0), order=3),
    "shift -0.0": lambda: splinelab.shift(_X, -0.0, order=1),
    "shift float32": lambda: splinelab.shift(_X.astype(np.float32), 0.25, order=3),
    "shift 1-d": lambda: splinelab.shift(_X[0], 0.25, order=5, mode="reflect"),
    "shift 0-d": lambda: splinelab.shift(np.array(1.0), 0.25, order=1),
    "shift empty": lambda: splinelab.shift(np.empty((0, 4)), 0.25, order=1),
    "shift view": lambda: splinelab.shift(_X[::2, 1:], 0.25, order=1),
    "shift wrap": lambda: splinelab.shift(_X, 0.25, order=3, mode="wrap"),
    "shift nearest cubic": lambda: splinelab.shift(_X, 0.25, order=3, mode="nearest"),
    "shift bad mode": lambda: splinelab.shift(_X, 0.25, order=1, mode="edge"),
    "shift threads 0": lambda: splinelab.shift(_X, 0.25, order=1, threads=0),
    "shift list input": lambda: splinelab.shift(_X.tolist(), 0.25, order=1),
    "shift int input": lambda: splinelab.shift(_X.astype(np.int16), 0.25, order=1),
}
_ODD_AFFINES = {
    "affine": lambda: splinelab.affine_transform(_X, _ROT, order=1),
    "affine offset": lambda: splinelab.affine_transform(_X, _ROT, 0.5, order=3, mode="mirror"),
    "affine int offset": lambda: splinelab.affine_transform(_X, _ROT, 2, order=1),
    "affine offset tuple": lambda: splinelab.affine_transform(_X, _ROT, (0.5, -1), order=0, cval=np.nan),
    "affine offset array": lambda: splinelab.affine_transform(_X, _ROT, np.array([0.5, 1.5]), order=1),
    "affine offset short": lambda: splinelab.affine_transform(_X, _ROT, (0.5,), order=1),
    "affine offset nan": lambda: splinelab.affine_transform(_X, _ROT, np.nan, order=1),
    "affine matrix nan": lambda: splinelab.affine_transform(_X, _ROT * np.nan, order=1),
    "affine matrix inf": lambda: splinelab.affine_transform(_X, np.array([[np.inf, 0], [0, 1.0]]), order=3),
    "affine list matrix": lambda: splinelab.affine_transform(_X, _ROT.tolist(), order=1),
    "affine int matrix": lambda: splinelab.affine_transform(_X, np.eye(2, dtype=int), order=1),
    "affine Fortran matrix": lambda: splinelab.affine_transform(_X, np.asfortranarray(_ROT), order=1),
    "affine diagonal": lambda: splinelab.affine_transform(_X, np.array([0.5, 2.0]), order=1),
    "affine homogeneous": lambda: splinelab.affine_transform(_X, np.eye(3), order=1),
    "affine 3x2": lambda: splinelab.affine_transform(_X, np.ones((3, 2)), order=1),
    "affine output_shape": lambda: splinelab.affine_transform(_X, _ROT, output_shape=(4, 5), order=1),
    "affine float32": lambda: splinelab.affine_transform(_X.astype(np.float32), _ROT, order=3),
    "affine 1-d": lambda: splinelab.affine_transform(_X[0], np.array([[0.7]]), order=3),
    "affine 3-d": lambda: splinelab.affine_transform(np.ones((3, 4, 5)), np.eye(3) * 0.9, order=1),
    "affine empty": lambda: splinelab.affine_transform(np.empty((0, 3)), _ROT, order=1),
    "affine view": lambda: splinelab.affine_transform(_X[::2], _ROT, order=3),
    "affine wrap": lambda: splinelab.affine_transform(_X, _ROT, order=1, mode="wrap"),
    "affine grid-constant cubic": lambda: splinelab.affine_transform(_X, _ROT, order=3, mode="grid-constant"),
    "affine order 7": lambda: splinelab.affine_transform(_X, _ROT, order=7),
    "affine bad order": lambda: splinelab.affine_transform(_X, _ROT, order="3"),
    "affine nan_policy": lambda: splinelab.affine_transform(_X, _ROT, order=3, nan_policy="raise"),
    "rotate": lambda: splinelab.rotate(_X, 30, order=1),
    "rotate cubic no reshape": lambda: splinelab.rotate(_X, -75.5, order=3, reshape=False, mode="reflect"),
    "rotate 90": lambda: splinelab.rotate(_X, 90, order=0),
    "rotate float32": lambda: splinelab.rotate(_X32, 30, order=3),
    "rotate 3-d": lambda: splinelab.rotate(_PTS, 30, order=1, cval=np.nan),
    "rotate 3-d axes (0, 2)": lambda: splinelab.rotate(_PTS, 12, axes=(0, 2), order=3, mode="grid-wrap"),
    "rotate 3-d view": lambda: splinelab.rotate(_PTS[:, ::-1], 12, axes=(2, 1), order=0),
    "rotate 4-d": lambda: splinelab.rotate(np.ones((2, 3, 4, 5)), 40, axes=(1, 3), order=1),
    "rotate wrap": lambda: splinelab.rotate(_X, 30, order=3, mode="wrap"),
    "rotate nan angle": lambda: splinelab.rotate(_X, np.nan, order=1),
    "rotate bad axes": lambda: splinelab.rotate(_X, 30, axes=(0, 0), order=1),
    "rotate 1-d": lambda: splinelab.rotate(_X[0], 30, order=1),
    "rotate to empty": lambda: splinelab.rotate(np.ones((1, 0)), 30, order=1),
    "rotate list": lambda: splinelab.rotate(_X.tolist(), 30, order=1),
    "rotate int": lambda: splinelab.rotate(_X.astype(np.uint8), 30, order=1),
}
_ODD_ZOOMS = {
    "zoom": lambda: splinelab.zoom(_X, 2, order=1),
    "zoom float": lambda: splinelab.zoom(_X, 1.5, order=3, mode="mirror"),
    "zoom tuple": lambda: splinelab.zoom(_X, (0.5, 1.75), order=1, cval=2.0),
    "zoom ties": lambda: splinelab.zoom(_X, (0.5, 1.5), order=0),  # 4.5 and 10.5 round to even
    "zoom to 1": lambda: splinelab.zoom(_X, 0.1, order=1),
    "zoom to 0": lambda: splinelab.zoom(_X, 0.01, order=1),
    "zoom by 1": lambda: splinelab.zoom(_X, 1, order=3),
    "zoom by 1, no prefilter": lambda: splinelab.zoom(_X, 1.0, order=3, prefilter=False),
    "zoom negative": lambda: splinelab.zoom(_X, -2, order=1),
    "zoom nan": lambda: splinelab.zoom(_X, np.nan, order=1),
    "zoom inf": lambda: splinelab.zoom(_X, np.inf, order=1),
    "zoom huge": lambda: splinelab.zoom(_X, 1e300, order=1),
    "zoom array": lambda: splinelab.zoom(_X, np.array([2.0, 0.5]), order=1),
    "zoom short": lambda: splinelab.zoom(_X, [2.0], order=1),
    "zoom grid_mode": lambda: splinelab.zoom(_X, 2, order=1, grid_mode=True, mode="grid-constant"),
    "zoom float32": lambda: splinelab.zoom(_X.astype(np.float32), 2, order=3),
    "zoom 1-d of 1": lambda: splinelab.zoom(np.array([2.5]), 3, order=1),
    "zoom 3-d": lambda: splinelab.zoom(np.ones((2, 3, 4)), 1.7, order=5, mode="grid-wrap"),
    "zoom view": lambda: splinelab.zoom(_X[:, ::3], 2, order=1),
    "zoom wrap": lambda: splinelab.zoom(_X, 2, order=3, mode="wrap"),
    "zoom empty": lambda: splinelab.zoom(np.empty((0, 3)), 2, order=1),
}
_ODD_FILTERS = {
    "filter1d": lambda: splinelab.spline_filter1d(_X, 3),
    "filter1d axis 0": lambda: splinelab.spline_filter1d(_X, 5, axis=0, mode="reflect"),
    "filter1d axis -2": lambda: splinelab.spline_filter1d(_X, 2, axis=-2, mode="grid-wrap"),
    "filter1d axis 2": lambda: splinelab.spline_filter1d(_X, 3, axis=2),
    "filter1d axis -3": lambda: splinelab.spline_filter1d(_X, 3, axis=-3),
    "filter1d axis None": lambda: splinelab.spline_filter1d(_X, 3, axis=None),
    "filter1d axis 1.0": lambda: splinelab.spline_filter1d(_X, 3, axis=1.0),
    "filter1d axis numpy": lambda: splinelab.spline_filter1d(_X, 3, axis=np.int64(0)),
    "filter1d float32 in": lambda: splinelab.spline_filter1d(_X32, 3),
    "filter1d float32 in, None out": lambda: splinelab.spline_filter1d(_X32, 3, output=None),
    "filter1d float32 out": lambda: splinelab.spline_filter1d(_X, 3, output=np.float32),
    "filter1d dtype out": lambda: splinelab.spline_filter1d(_X, 3, output=np.dtype("float32")),
    "filter1d str out": lambda: splinelab.spline_filter1d(_X, 3, output="float32"),
    "filter1d float out": lambda: splinelab.spline_filter1d(_X32, 3, output=float),
    "filter1d big-endian out": lambda: splinelab.spline_filter1d(_X, 3, output=np.dtype(">f8")),
    "filter1d int out": lambda: splinelab.spline_filter1d(_X, 3, output=np.int32),
    "filter1d array out": lambda: splinelab.spline_filter1d(_X, 3, output=np.empty((9, 7))),
    "filter1d nearest": lambda: splinelab.spline_filter1d(_X, 3, mode="nearest"),
    "filter1d nearest exact": lambda: splinelab.spline_filter1d(_X, 3, mode="nearest", exact_edges=True),
    "filter1d grid-constant exact": lambda: splinelab.spline_filter1d(_X, 4, mode="grid-constant", exact_edges=True),
    "filter1d exact_edges 1": lambda: splinelab.spline_filter1d(_X, 3, exact_edges=1),
    "filter1d wrap": lambda: splinelab.spline_filter1d(_X, 3, mode="wrap"),
    "filter1d bad mode": lambda: splinelab.spline_filter1d(_X, 3, mode="edge"),
    "filter1d order 1": lambda: splinelab.spline_filter1d(_X, 1),
    "filter1d order 9": lambda: splinelab.spline_filter1d(_X, 9),
    "filter1d order 200": lambda: splinelab.spline_filter1d(_X, 200),
    "filter1d threads 0": lambda: splinelab.spline_filter1d(_X, 3, threads=0),
    "filter1d nan_policy": lambda: splinelab.spline_filter1d(_X, 3, nan_policy="raise"),
    "filter1d nan sample": lambda: splinelab.spline_filter1d(np.where(_X > 1, np.nan, _X), 3),
    "filter1d view": lambda: splinelab.spline_filter1d(_X[::2, ::-1], 3),
    "filter1d Fortran": lambda: splinelab.spline_filter1d(np.asfortranarray(_X), 3, axis=0),
    "filter1d empty": lambda: splinelab.spline_filter1d(np.empty((0, 4)), 3),
    "filter1d 0-d": lambda: splinelab.spline_filter1d(np.array(2.0), 3),
    "filter1d int input": lambda: splinelab.spline_filter1d(_X.astype(np.int64), 3),
    "filter1d complex": lambda: splinelab.spline_filter1d(_X + 1j, 3),
    "filter": lambda: splinelab.spline_filter(_X, 3),
    "filter float32": lambda: splinelab.spline_filter(_X32, 5, output=np.float32, mode="grid-mirror"),
    "filter 3-d": lambda: splinelab.spline_filter(np.ones((3, 4, 5)), 2, mode="constant"),
    "filter 1-d": lambda: splinelab.spline_filter(_X[0], 3),
    "filter 0-d": lambda: splinelab.spline_filter(np.array(2.0), 3),
    "filter order 0": lambda: splinelab.spline_filter(_X, 0),
}


def _mapped(row, **kw):
    """geometric_transform of _X with a mapping returning ``row(index)``."""
    return lambda: splinelab.geometric_transform(_X, lambda o: row(o), order=1, **kw)


# The rows a mapping may return: the engine reads exact tuples and lists of
# Python floats and ints, and hands every other row to the Python loop.
_ODD_MAPPINGS = {
    "mapping floats": _mapped(lambda o: (o[0] - 0.3, o[1] + 0.25)),
    "mapping ints": _mapped(lambda o: (o[1], o[0])),
    "mapping list": _mapped(lambda o: [o[0] * 0.5, o[1] * 1.5]),
    "mapping big ints": _mapped(lambda o: (2**53 + 1 + o[0], -(2**62) - 1)),
    "mapping huge int": _mapped(lambda o: (2**70, 1.0)),
    "mapping nan inf": _mapped(lambda o: (float("nan") if o[0] == 3 else o[0], float("inf") if o[1] == 2 else 0.5)),
    "mapping nan raise": _mapped(lambda o: (float("nan"), 0.0), nan_policy="raise"),
    "mapping bools": _mapped(lambda o: (True, False)),
    "mapping numpy float64": _mapped(lambda o: (np.float64(o[0]) / 3, o[1])),
    "mapping numpy float32": _mapped(lambda o: (np.float32(o[0]) / 3, o[1])),
    "mapping array": _mapped(lambda o: np.array(o) * 0.5),
    "mapping float subclass": _mapped(lambda o: (type("F", (float,), {})(o[0] / 3), 1.0)),
    "mapping mixed": _mapped(lambda o: (o[0], 0.5) if o[0] % 2 else [o[0] / 7, 2]),
    "mapping short": _mapped(lambda o: (o[0],)),
    "mapping long at one index": _mapped(lambda o: (1.0, 2.0, 3.0) if o == (4, 5) else (1.0, 2.0)),
    "mapping not a sequence": _mapped(lambda o: 1.0),
    "mapping string": _mapped(lambda o: "ab"),
    "mapping text items": _mapped(lambda o: ("1.5", 2.0)),
    "mapping complex": _mapped(lambda o: (1j, 2.0)),
    "mapping None": _mapped(lambda o: None),
    "mapping raises": _mapped(lambda o: 1 / 0),
    "mapping extra": lambda: splinelab.geometric_transform(_X, lambda o, a, b=0: (o[0] + a, o[1] - b), order=3,
                                                           extra_arguments=(0.5,), extra_keywords={"b": 2}),
    "mapping empty output": lambda: splinelab.geometric_transform(_X, lambda o: o, output_shape=(0, 3)),
    "mapping 3-d": lambda: splinelab.geometric_transform(np.ones((2, 3, 4)), lambda o: (o[0], o[1] * 0.5, o[2])),
}
_ODD = [("map_coordinates_common", n, f) for n, f in _ODD_CALLS.items()] + \
       [("mapped_points", n, f) for n, f in _ODD_MAPPINGS.items()] + \
       [("filter_common", n, f) for n, f in _ODD_FILTERS.items()] + \
       [("zoom_common", n, f) for n, f in _ODD_ZOOMS.items()] + \
       [("shift_common", n, f) for n, f in _ODD_SHIFTS.items()] + \
       [("affine_common", n, f) for n, f in _ODD_AFFINES.items()]


def test_the_engine_reads_a_mappings_rows_as_numpy_does():
    """mapped_points reads exact tuples and lists of Python floats and
    ints as numpy's float64 conversion does (column k = row k), and
    declines (None) anything else, which the Python loop then reads."""
    rows = [(0.5, -1), [2**53 + 1, float("nan")], (1e308, -0.0), (-(2**63), float("-inf"))]
    got = ext.mapped_points(rows, 2)
    assert got.dtype == np.float64 and got.shape == (2, 4) and got.flags.c_contiguous
    np.testing.assert_array_equal(got, np.array(rows, dtype=np.float64).T)
    assert ext.mapped_points([], 3).shape == (3, 0)
    for bad in ([(1.0,)], [(1.0, 2.0, 3.0)], [(1.0, np.float32(2))], [(1.0, np.float64(2))], [(1.0, True)],
                ((1.0, 2.0),), [np.array([1.0, 2.0])], [(1.0, 2**64)], [(1.0, "2")], [None]):
        assert ext.mapped_points(bad, 2) is None, bad


@pytest.mark.filterwarnings("ignore::PendingDeprecationWarning")  # np.asmatrix's
@pytest.mark.filterwarnings("ignore:promoting specified output dtype to complex")  # scipy warns too
@pytest.mark.parametrize("step, name, call", _ODD, ids=[n for _, n, _ in _ODD])
def test_the_one_step_path_answers_every_call_as_the_general_path(monkeypatch, step, name, call):
    """Every call (common or not, good or bad) gets from map_coordinates,
    shift and affine_transform the general path's answer: the same bytes,
    dtype and shape, or the same exception class and message; the one step
    only recognises exact types and hands everything else on."""
    ours = _outcome(call)
    monkeypatch.setattr(ext, step, lambda *args: None)
    assert ours == _outcome(call)


@given(calls())
@settings(max_examples=150, deadline=None)
def test_the_one_step_path_leaves_to_python_exactly_the_calls_the_local_route_may_take(c):
    """The one step declines (None) where ``may_be_local`` (the Python
    layer's pricing, itself tested against the engine's above) says the
    local route may read less, and evaluates everywhere else the settings
    are common; degrees 0 and 1 read in place where ``in_place_pays``."""
    mode, d, prefilter = c["mode"], c["d"], c["prefilter"]
    if mode == "wrap" or (mode in ("nearest", "grid-constant") and prefilter and 2 <= d <= 5):
        return  # not the one step's: scipy's moved or padded points
    a = np.random.default_rng(1).normal(size=c["shape"])
    flat = np.ascontiguousarray(c["flat"])
    k = flat.shape[1]
    local = not (d <= 1 and _local.in_place_pays(a.shape, k, d)) and _local.may_be_local(a.shape, k, d, prefilter,
                                                                                             None)
    got = ext.map_coordinates_common(a, flat, (d, mode, 0.5, prefilter, None, "propagate", "float64"))
    assert (got is None) == local
    if got is not None:
        want = splinelab.map_coordinates(a, flat, order=d, mode=mode, cval=0.5, prefilter=prefilter,
                                         output=np.float64)
        np.testing.assert_array_equal(got, want)
