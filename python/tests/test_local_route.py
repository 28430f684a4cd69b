"""The local route (issue 45) against the global route and scipy, the
readers of arrays that are not in memory, and splinelab.Interpolant.

References: the global route (the exact recursive prefilter of the whole
array: an independent computation) within the local route's stated bound;
scipy live; bit-identity between sources (ndarray, memmap, zarr, h5py, dask
of several chunkings); numpy's own assignment for ``update``."""

import importlib
import pickle

import numpy as np
import pytest
import scipy.ndimage as ndi
from hypothesis import given, settings
from hypothesis import strategies as st

import splinelab
from splinelab import _local

MODES = ["constant", "grid-constant", "nearest", "mirror", "reflect", "grid-mirror", "wrap", "grid-wrap"]


def _extra(name):
    """A test extra, or a failure saying it is missing (scripts/python.sh
    installs it pinned; nothing is skipped silently)."""
    try:
        return importlib.import_module(name)
    except ImportError as e:  # pragma: no cover - the message is the point
        pytest.fail(f"test extra {name!r} is not installed ({e}): scripts/python.sh installs it")


def _route(route, f):
    old = _local.ROUTE
    _local.ROUTE = route
    try:
        return f()
    finally:
        _local.ROUTE = old


def _bound(a, order, ndim, tol, deriv=None):
    """The local route's stated bound against the global one: the
    truncation's ((A + b)**D - A**D) max|s| plus both routes' rounding."""
    if order < 2:
        return 0.0
    fb = splinelab.filter_bound(order, tol=1e-3)
    amp = fb["amplification"]
    u = 2.0**-53 if a.dtype == np.float64 else 2.0**-24
    t = tol if tol is not None else u * amp / 4
    n = splinelab.Interpolant(np.zeros((1,) * ndim, a.dtype), order=order, tol=tol).truncation()["half_width"]
    k = sum(deriv) if deriv else 0
    scale = 2.0**k * max(float(np.abs(a).max()), 1.0)
    return (((amp + t) ** ndim - amp**ndim) + 32 * (n + 8) * u * amp**ndim) * scale


@settings(max_examples=60, deadline=None)
@given(
    shape=st.lists(st.integers(1, 12), min_size=1, max_size=3),
    order=st.sampled_from([0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 15]),
    mode=st.sampled_from(MODES),
    dtype=st.sampled_from([np.float64, np.float32]),
    seed=st.integers(0, 2**32 - 1),
    k=st.integers(1, 12),
    tol=st.sampled_from([None, 1e-9]),
)
def test_local_route_agrees_with_the_global_route(shape, order, mode, dtype, seed, k, tol):
    rng = np.random.default_rng(seed)
    a = rng.uniform(-1, 1, shape).astype(dtype)
    at = np.stack([rng.uniform(-4, n + 3, k) for n in shape])
    at[:, 0] = [n - 1 for n in shape]  # at the edge
    kw = dict(order=order, mode=mode, cval=0.5, tol=tol)

    def run(route):
        try:
            return _route(route, lambda: splinelab.map_coordinates(a, at, **kw))
        except ValueError as e:  # data the filter could overflow (f32, high degree, 3-D)
            assert "could overflow" in str(e), e
            return None

    loc, glo = run("local"), run("global")
    assert (loc is None) == (glo is None)
    if glo is None:
        return
    assert loc.dtype == glo.dtype
    if order < 2:
        np.testing.assert_array_equal(loc, glo)
    else:
        assert np.abs(loc.astype(float) - glo).max() <= _bound(a, order, len(shape), tol)


@pytest.mark.parametrize("mode", MODES)
def test_cubic_matches_scipy_within_1e_13(mode):
    rng = np.random.default_rng(1)
    a = rng.uniform(-1, 1, (300, 400))
    at = np.stack([rng.uniform(-5, 305, 200), rng.uniform(-5, 405, 200)])
    ours = _route("local", lambda: splinelab.map_coordinates(a, at, order=3, mode=mode, cval=0.25))
    want = ndi.map_coordinates(a, at, order=3, mode=mode, cval=0.25)
    assert np.abs(ours - want).max() <= 1e-13 * np.abs(want).max()


def test_default_route_is_local_for_few_points_and_global_for_many():
    a = np.zeros((1000, 1000))
    few = np.full((2, 10), 500.0)
    many = np.random.default_rng(0).uniform(0, 999, (2, 400_000))
    cost = lambda at: _ext_cost(a.shape, at)  # noqa: E731
    local_ns, global_ns = cost(few)[:2]
    assert local_ns < global_ns
    local_ns, global_ns = cost(many)[:2]
    assert local_ns > global_ns


def _ext_cost(shape, at, order=3):
    return splinelab._splinelab.local_route_cost(list(shape), np.ascontiguousarray(at), order, "mirror", None, True,
                                                 "fold", 0)


class Counting:
    """An array-like that counts the samples it is asked for."""

    def __init__(self, a):
        self.a, self.read, self.calls = a, 0, 0
        self.shape, self.dtype, self.ndim = a.shape, a.dtype, a.ndim

    def __getitem__(self, key):
        part = self.a[key]
        self.read += part.size
        self.calls += 1
        return part


class Virtual:
    """A 16000 x 16000 float64 array-like computed where it is read (no
    memory of its size), counting the samples it is asked for."""

    shape, dtype, ndim = (16000, 16000), np.dtype(np.float64), 2

    def __init__(self):
        self.read = 0

    def __getitem__(self, key):
        i, j = (np.arange(16000)[k] for k in key)
        self.read += i.size * j.size
        return np.sin(0.01 * i)[:, None] * np.cos(0.003 * j)[None, :]


def test_array_like_reads_a_few_percent_for_1000_cubic_points():
    # Each isolated cubic point needs its (4 + 2n)**2 samples: n = 29 at the
    # default tol (1.5 % of 16000**2 for 1000 points), 22 at tol=1e-12 (0.9 %).
    at = np.random.default_rng(2).uniform(0, 15999, (2, 1000))
    for tol, n, share in ((None, 29, 0.0151), (1e-12, 22, 0.01)):
        src = Virtual()
        v = splinelab.map_coordinates(src, at, order=3, mode="mirror", tol=tol)
        assert src.read <= 1000 * (4 + 2 * n) ** 2 and src.read <= share * 16000**2, src.read / 16000**2
        want = np.sin(0.01 * at[0]) * np.cos(0.003 * at[1])
        assert np.median(np.abs(v - want)) < 1e-9  # the smooth function it samples


@given(seed=st.integers(0, 2**32 - 1), order=st.integers(0, 5), mode=st.sampled_from(MODES))
@settings(max_examples=25, deadline=None)
def test_array_like_reads_only_the_windows(seed, order, mode):
    rng = np.random.default_rng(seed)
    a = rng.uniform(-1, 1, (300, 300))
    src = Counting(a)
    at = rng.uniform(-3, 302, (2, 3))
    splinelab.map_coordinates(src, at, order=order, mode=mode)
    n = splinelab.Interpolant(a, order=order).truncation()["half_width"] if order > 1 else 0
    side = 32 + order + 2 * n + 24  # a tile's box and scipy's pad
    assert src.read <= 3 * side * side


def test_sources_give_the_same_bits(tmp_path):
    zarr = _extra("zarr")
    h5py = _extra("h5py")
    import dask.array as da

    rng = np.random.default_rng(3)
    a = rng.uniform(-1, 1, (257, 190))
    at = np.stack([rng.uniform(-3, 260, 300), rng.uniform(-3, 193, 300)])
    np.save(tmp_path / "a.npy", a)
    mm = np.load(tmp_path / "a.npy", mmap_mode="r")
    z = zarr.create_array(store=str(tmp_path / "a.zarr"), shape=a.shape, chunks=(50, 64), dtype=a.dtype)
    z[...] = a
    with h5py.File(tmp_path / "a.h5", "w") as f:
        f["a"] = a
    for mode in ("mirror", "nearest", "constant", "wrap"):
        kw = dict(order=3, mode=mode)
        want = _route("local", lambda: splinelab.map_coordinates(a, at, **kw))
        sources = [mm, z, Counting(a)] + [da.from_array(a, chunks=c) for c in ((64, 64), (100, 190), (17, 31))]
        with h5py.File(tmp_path / "a.h5", "r") as f:
            for s in sources + [f["a"]]:
                got = _route("local", lambda: splinelab.map_coordinates(s, at, **kw))
                np.testing.assert_array_equal(got, want, err_msg=f"{type(s).__name__} {mode}")


def test_dask_with_many_points_reads_the_bounding_box_once():
    # Many boxes (100 points in a corner, prefilter=False; too few to read
    # the array whole): one slice of their bounding box, the boxes cut from
    # it: the local route's values, the bounding box read.
    import dask.array as da

    rng = np.random.default_rng(5)
    a = rng.uniform(-1, 1, (35, 250, 150))
    src = Counting(a)
    d = da.from_array(src, chunks=(35, 100, 100), asarray=False)
    at = np.stack([rng.uniform(1, n, 100) for n in (20, 120, 80)])
    for kw in (dict(order=3, prefilter=False), dict(order=1)):
        src.read = 0
        got = splinelab.map_coordinates(d, at, **kw)
        want = _route("local", lambda: splinelab.map_coordinates(a, at, **kw))
        np.testing.assert_array_equal(got, want, err_msg=str(kw))
        assert src.read <= 23 * 123 * 83 < a.size, (kw, src.read)


@pytest.mark.parametrize("kind", ["dask", "counting"])
@pytest.mark.parametrize("kw", [dict(order=0, prefilter=False), dict(order=1), dict(order=3, prefilter=False),
                                dict(order=3, mode="mirror"), dict(order=5, mode="nearest", cval=np.nan)])
def test_array_like_covered_by_its_points_is_read_once_whole(kind, kw):
    # Issue 42: reproject hands dask-image's blocks to map_coordinates with
    # a point in most cells (8.5x scipy's CPU when each point's box was
    # read and sliced on its own). Where the array holds at most
    # k * (_BOX + one point's box) samples it is read once, whole, and
    # evaluated in memory: the bits of the in-memory call, close to scipy.
    import dask.array as da

    rng = np.random.default_rng(6)
    a = rng.uniform(-1, 1, (60, 70))
    src = Counting(a)
    x = da.from_array(src, chunks=(25, 30), asarray=False) if kind == "dask" else src
    at = np.stack([rng.uniform(-2, n + 1, 400) for n in a.shape])
    got = splinelab.map_coordinates(x, at, **kw)
    assert src.read == a.size and (kind == "dask" or src.calls == 1), (src.read, src.calls)
    np.testing.assert_array_equal(got, splinelab.map_coordinates(a, at, **kw))
    np.testing.assert_allclose(got, ndi.map_coordinates(a, at, **kw), rtol=0, atol=1e-13)


def test_array_like_is_read_whole_by_the_stated_cost():
    # Read whole iff size <= k * (_BOX + W), W = (order + 1)**ndim without a
    # prefilter: 3 linear points on a 3 x 10_004 array (W = 4): whole at
    # 30_012 samples, their windows alone at 30_015.
    a3 = np.random.default_rng(7).uniform(-1, 1, (3, 10_005))
    at = np.array([[0.5, 1.0, 1.5], [7.25, 5000.5, 9000.0]])
    for cols, whole in ((10_004, True), (10_005, False)):
        src = Counting(a3[:, :cols])
        got = splinelab.map_coordinates(src, at, order=1)
        assert (src.calls == 1 and src.read == 3 * cols) == whole, (cols, src.calls, src.read)
        np.testing.assert_allclose(got, ndi.map_coordinates(a3[:, :cols], at, order=1), rtol=0, atol=1e-15)


@pytest.mark.parametrize("shape", [(0, 5), (5, 0), (0,)])
@pytest.mark.parametrize("order", [0, 1, 3])
def test_empty_array_like_gives_cval_as_scipy(shape, order):
    # reproject's dask_map_coordinates passes empty dask blocks with
    # cval=nan (its test_reproject_order_method): scipy reads them whole
    # and returns cval under the constant modes.
    import dask.array as da

    at = np.array([[0.5, 1.2], [0.3, 2.0]])[: len(shape)]
    for mode in ("constant", "grid-constant"):
        for src in (da.zeros(shape), Counting(np.zeros(shape))):
            kw = dict(order=order, mode=mode, cval=np.nan, prefilter=False)
            got = splinelab.map_coordinates(src, at, **kw)
            want = ndi.map_coordinates(np.zeros(shape), at, **kw)
            np.testing.assert_array_equal(got, want, err_msg=f"{type(src).__name__} {mode}")


def test_dask_with_few_points_computes_only_their_chunks():
    import dask.array as da

    rng = np.random.default_rng(4)
    a = rng.uniform(-1, 1, (2000, 2000))
    src = Counting(a)
    d = da.from_array(src, chunks=(250, 250), asarray=False)  # 64 chunks
    at = np.array([[1000.3, 1010.0], [20.5, 30.25]])
    v = splinelab.map_coordinates(d, at, order=3, mode="mirror")
    # The windows lie in 2 of the 64 chunks (a few more with the margin).
    assert src.read <= 4 * 250 * 250, src.read
    want = _route("local", lambda: splinelab.map_coordinates(a, at, order=3, mode="mirror"))
    np.testing.assert_array_equal(v, want)
    # splinelab.dask's own default tolerance is 1e-12: the same bits as the
    # in-memory call at that tolerance.
    src.read = 0
    w = splinelab.dask.map_coordinates(d, da.from_array(at, chunks=(2, 1)), order=3, mode="mirror").compute()
    assert src.read <= 4 * 250 * 250, src.read
    want = _route("local", lambda: splinelab.map_coordinates(a, at, order=3, mode="mirror", tol=1e-12))
    np.testing.assert_array_equal(w, want)


def test_array_like_without_slicing_is_a_type_error():
    class NoSlice:
        shape, dtype, ndim = (3, 3), np.dtype(float), 2

    with pytest.raises(TypeError, match="shape, dtype, ndim and basic-slice __getitem__"):
        splinelab.Interpolant(NoSlice())
    with pytest.raises(TypeError, match="shape, dtype, ndim and basic-slice __getitem__"):
        splinelab.Interpolant(object())


def test_a_missing_sample_reaches_only_the_windows_that_read_it():
    a = np.random.default_rng(5).uniform(-1, 1, (400, 400))
    a[200, 200] = np.nan
    at = np.array([[200.5, 260.0, 10.0], [200.0, 200.0, 10.0]])
    v = _route("local", lambda: splinelab.map_coordinates(a, at, order=3, mode="mirror"))
    assert np.isnan(v[0]) and np.isfinite(v[1:]).all()
    with pytest.raises(ValueError, match="sample 80200 is not finite"):
        _route("local", lambda: splinelab.map_coordinates(a, at, order=3, mode="mirror", nan_policy="raise"))
    far = np.array([[10.0], [10.0]])
    assert np.isfinite(_route("local", lambda: splinelab.map_coordinates(a, far, order=3, nan_policy="raise"))).all()


# ------------------------------------------------------------ Interpolant


def test_interpolant_matches_map_coordinates_and_its_derivatives():
    rng = np.random.default_rng(6)
    a = rng.uniform(-1, 1, (80, 90))
    at = np.stack([rng.uniform(-3, 83, 50), rng.uniform(-3, 93, 50)])
    for mode in MODES:
        ip = splinelab.Interpolant(a, order=3, mode=mode)
        want = _route("local", lambda: splinelab.map_coordinates(a, at, order=3, mode=mode))
        np.testing.assert_array_equal(ip(at), want)
        d = _route("local", lambda: splinelab.map_coordinates(a, at, order=3, mode=mode, derivative=(1, 0)))
        np.testing.assert_array_equal(ip(at, derivative=(1, 0)), d)


@settings(max_examples=30, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    mode=st.sampled_from(MODES),
    order=st.sampled_from([1, 2, 3, 5]),
    steps=st.lists(st.tuples(st.integers(0, 39), st.integers(0, 49), st.integers(1, 4)), min_size=1, max_size=6),
)
def test_update_agrees_with_a_rebuild_bit_for_bit(seed, mode, order, steps):
    rng = np.random.default_rng(seed)
    a = rng.uniform(-1, 1, (40, 50))
    at = np.stack([rng.uniform(-2, 41, 60), rng.uniform(-2, 51, 60)])
    ip = splinelab.Interpolant(a, order=order, mode=mode)
    ip(at)  # cache tiles, which the updates must recompute
    b = a.copy()
    for i, j, w in steps:
        vals = rng.uniform(-5, 5, (w, w))
        key = (slice(i, i + w), slice(j, j + w))
        b[key] = vals[: b[key].shape[0], : b[key].shape[1]]
        ip.update(key, b[key])
        np.testing.assert_array_equal(ip(at), splinelab.Interpolant(b, order=order, mode=mode)(at))
    assert np.array_equal(a, a)  # the caller's array is not written
    np.testing.assert_array_equal(pickle.loads(pickle.dumps(ip))(at), ip(at))


def test_update_refuses_as_numpy_and_changes_nothing():
    a = np.arange(20.0).reshape(4, 5)
    ip = splinelab.Interpolant(a, order=3)
    at = np.array([[1.5], [2.5]])
    before = ip(at)
    for key, values in [((4, 0), 1.0), ((0, slice(0, 2)), [1.0, 2.0, 3.0]), (([0, 9],), 0.0)]:
        b = a.copy()
        with pytest.raises(Exception) as want:
            b[key] = values
        with pytest.raises(type(want.value)) as got:
            ip.update(key, values)
        assert str(got.value) == str(want.value)
        np.testing.assert_array_equal(ip(at), before)
    with pytest.raises(ValueError, match="is not finite"):
        splinelab.Interpolant(a, nan_policy="raise").update((1, 1), np.nan)
    ip.update((1, 1), np.nan)  # propagate: only the windows that read it
    assert np.isnan(ip(at)).all()


def test_cache_too_small_names_the_smallest_that_works():
    a = np.zeros((100, 100))
    with pytest.raises(ValueError, match=r"the smallest that works is (\d+)") as e:
        splinelab.Interpolant(a, cache_bytes=1000)
    smallest = int(e.value.args[0].rsplit(" ", 1)[1])
    ip = splinelab.Interpolant(a, cache_bytes=smallest)
    assert ip(np.array([[1.0, 90.0], [1.0, 90.0]])).shape == (2,)
    assert ip.cache_info()["bytes"] <= smallest


def test_interpolant_reads_array_likes_and_pickles(tmp_path):
    import dask.array as da

    rng = np.random.default_rng(7)
    a = rng.uniform(-1, 1, (120, 130))
    at = np.stack([rng.uniform(0, 119, 40), rng.uniform(0, 129, 40)])
    want = splinelab.Interpolant(a)(at)
    for src in (Counting(a), da.from_array(a, chunks=(30, 40))):
        ip = splinelab.Interpolant(src)
        np.testing.assert_array_equal(ip(at), want)
        ip.update((slice(10, 12), 5), [7.0, 8.0])
        b = a.copy()
        b[10:12, 5] = [7.0, 8.0]
        np.testing.assert_array_equal(ip(at), splinelab.Interpolant(b)(at))
    ip = pickle.loads(pickle.dumps(splinelab.Interpolant(da.from_array(a, chunks=50))))
    np.testing.assert_array_equal(ip(at), want)


@pytest.mark.parametrize("mode", ["constant", "mirror", "nearest", "wrap"])
def test_small_affine_outputs_of_a_large_input_take_the_local_route(mode, monkeypatch):
    """affine_transform and rotate with a small output_shape (issue 45):
    the points go to the local route (its entry point is called and
    answers), within the local route's bound of the global route's
    engine-generated points, and within 1e-13 max|x| of scipy."""
    rng = np.random.default_rng(7)
    x = rng.standard_normal((600, 700))
    m, off = np.array([[0.9, 0.2], [-0.15, 1.1]]), np.array([211.3, 305.7])
    calls = []
    real = splinelab._splinelab.local_map_f64

    def spy(*args):
        out = real(*args)
        calls.append(out is not None)
        return out

    monkeypatch.setattr(splinelab._splinelab, "local_map_f64", spy)
    got = splinelab.affine_transform(x, m, off, output_shape=(9, 11), order=3, mode=mode)
    assert calls == [True]
    want = _route("global", lambda: splinelab.affine_transform(x, m, off, output_shape=(9, 11), order=3, mode=mode))
    assert np.abs(got - want).max() <= _bound(x, 3, 2, None)
    ref = ndi.affine_transform(x, m, off, output_shape=(9, 11), order=3, mode=mode)
    assert np.abs(got - ref).max() <= 1e-13 * np.abs(x).max()
