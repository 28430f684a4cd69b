"""Each stored chunk read at most once a call (issue 51): map_coordinates and
Interpolant on array-likes that expose their chunk grid (zarr, h5py, dask).

References: the in-memory call on the same samples (the local route gives
the same bits whichever reader supplies them); the boxes one read per box
asks for (an array-like without a chunk grid: today's reads), from which
the touched chunks are marked on a mask of the array, independently of
the grouping by chunk under test; zarr's own store calls, counted."""

import collections
import itertools
import re

import numpy as np
import pytest
import scipy.ndimage as ndi
from hypothesis import given, settings
from hypothesis import strategies as st

import splinelab
from splinelab import _local
from test_local_route import MODES, _extra, _route


class Recording:
    """An in-memory array-like that records the key of every read; with
    ``chunks`` it exposes a chunk grid (dask's sizes per axis or zarr's
    edge per axis), without it none."""

    def __init__(self, a, chunks=None):
        self.a, self.keys = a, []
        self.shape, self.dtype, self.ndim = a.shape, a.dtype, a.ndim
        if chunks is not None:
            self.chunks = chunks

    def __getitem__(self, key):
        self.keys.append(key)
        return self.a[key].copy()


def _chunk_list(shape, chunks):
    """Every chunk as ``((start, stop), ...)``, from the sizes per axis or one
    edge per axis (numpy's cumulative sums: independent of the reader's edges)."""
    axes = []
    for n, c in zip(shape, chunks):
        sizes = list(c) if isinstance(c, tuple) else [c] * (n // c) + ([n % c] if n % c else [])
        ends = np.cumsum(sizes)
        axes.append([(int(e - s), int(e)) for s, e in zip(sizes, ends) if s])
    return list(itertools.product(*axes))


def _touched(shape, keys, chunks):
    """The chunks holding a sample some key reads."""
    mask = np.zeros(shape, bool)
    for k in keys:
        mask[k] = True
    return {c for c in _chunk_list(shape, chunks) if mask[tuple(slice(*ab) for ab in c)].any()}


def _holder(key, chunk_list):
    """The one chunk that holds the read ``key`` whole (None: it spans chunks)."""
    inside = [c for c in chunk_list if all(c[a][0] <= key[a].start and key[a].stop <= c[a][1]
                                           for a in range(len(c)))]
    return inside[0] if len(inside) == 1 else None


def _assert_each_touched_chunk_read_once(shape, chunks, box_keys, chunk_keys):
    """Every read lies in one chunk, no chunk is read twice, and the chunks
    read are those the boxes touch (untouched ones never)."""
    chunk_list = _chunk_list(shape, chunks)
    held = [_holder(k, chunk_list) for k in chunk_keys]
    assert None not in held, [k for k, h in zip(chunk_keys, held) if h is None]
    assert len(set(held)) == len(held), collections.Counter(held).most_common(3)
    assert set(held) == _touched(shape, box_keys, chunks)


def _chunking(draw, n, style):
    """One axis' chunking: random sizes summing to ``n``, or one edge."""
    if style == "edge":
        return draw(st.integers(1, n))
    cuts = sorted(set(draw(st.lists(st.integers(1, n - 1), max_size=6)))) if n > 1 else []
    return tuple(int(b - a) for a, b in zip([0, *cuts], [*cuts, n]))


def _points(rng, shape, chunks, k):
    """``k`` random points, points on and beside chunk boundaries and the
    array's edges (and beyond them)."""
    at = np.stack([rng.uniform(-3, n + 2, k) for n in shape])
    edges = []
    for n, c in zip(shape, chunks):
        cuts = np.cumsum(c)[:-1] if isinstance(c, tuple) else np.arange(c, n, c)
        near = np.concatenate([cuts - 0.5, cuts, cuts - 1e-9, [0.0, n - 1.0, -0.75, n - 0.25]])
        edges.append(rng.choice(near, k))
    return np.concatenate([at, np.stack(edges)], axis=1)


@st.composite
def _cases(draw):
    ndim = draw(st.integers(1, 3))
    top = {1: 400, 2: 90, 3: 24}[ndim]
    shape = tuple(draw(st.lists(st.integers(1, top), min_size=ndim, max_size=ndim)))
    style = draw(st.sampled_from(["sizes", "edge"]))
    return shape, tuple(_chunking(draw, n, style) for n in shape)


@settings(max_examples=60, deadline=None)
@given(case=_cases(), order=st.integers(0, 5), mode=st.sampled_from(MODES),
       dtype=st.sampled_from([np.float64, np.float32]), prefilter=st.booleans(), seed=st.integers(0, 2**32 - 1))
def test_chunk_grid_gives_the_in_memory_bits_reading_each_touched_chunk_once(case, order, mode, dtype, prefilter,
                                                                               seed):
    shape, chunks = case
    rng = np.random.default_rng(seed)
    a = rng.standard_normal(shape).astype(dtype)
    at = _points(rng, shape, chunks, 4)
    kw = dict(order=order, mode=mode, cval=0.25, prefilter=prefilter)
    want = _route("local", lambda: splinelab.map_coordinates(a, at, **kw))
    boxes, chunked = Recording(a), Recording(a, chunks)
    np.testing.assert_array_equal(_route("local", lambda: splinelab.map_coordinates(boxes, at, **kw)), want)
    np.testing.assert_array_equal(_route("local", lambda: splinelab.map_coordinates(chunked, at, **kw)), want)
    _assert_each_touched_chunk_read_once(shape, chunks, boxes.keys, chunked.keys)


def test_few_points_leave_the_other_chunks_unread():
    # 5 cubic points of 600 x 700 in 50 x 70 chunks (120 chunks): each
    # window (~62 samples a side at the default tol) touches at most 4.
    rng = np.random.default_rng(1)
    a = rng.standard_normal((600, 700))
    at = np.array([[50.0, 300.2, 599.0, 10.0, 420.7], [70.0, 5.5, 699.0, 350.0, 139.9]])
    boxes, chunked = Recording(a), Recording(a, (50, 70))
    want = splinelab.map_coordinates(a, at, order=3)
    np.testing.assert_array_equal(splinelab.map_coordinates(boxes, at, order=3), want)
    np.testing.assert_array_equal(splinelab.map_coordinates(chunked, at, order=3), want)
    _assert_each_touched_chunk_read_once(a.shape, (50, 70), boxes.keys, chunked.keys)
    assert 5 <= len(chunked.keys) <= 20
    np.testing.assert_allclose(want, ndi.map_coordinates(a, at, order=3), rtol=0, atol=1e-13)


def test_groups_of_chunks_are_read_one_after_another(monkeypatch):
    # A budget below one chunk part: every part read on its own (one read
    # per group), each chunk still once, the same bits.
    rng = np.random.default_rng(2)
    a = rng.standard_normal((300, 300))
    at = rng.uniform(0, 299, (2, 40))
    want = _route("local", lambda: splinelab.map_coordinates(a, at, order=3))
    sizes = []
    real = _local._read
    monkeypatch.setattr(_local, "_read", lambda src, keys, threads: sizes.append(len(keys)) or real(src, keys, threads))
    monkeypatch.setattr(_local, "_GROUP_BYTES", 1)
    src = Recording(a, (64, 64))
    np.testing.assert_array_equal(_route("local", lambda: splinelab.map_coordinates(src, at, order=3)), want)
    assert sizes == [1] * len(src.keys) and len(src.keys) == 25


def test_interpolant_reads_each_touched_chunk_once_a_call():
    rng = np.random.default_rng(3)
    a = rng.standard_normal((400, 300))
    chunks = ((100, 150, 150), (64, 64, 64, 64, 44))
    ref = splinelab.Interpolant(a, order=3, mode="nearest")
    boxes, chunked = Recording(a), Recording(a, chunks)
    ip_boxes = splinelab.Interpolant(boxes, order=3, mode="nearest")
    ip = splinelab.Interpolant(chunked, order=3, mode="nearest")
    for at in (rng.uniform(-2, 401, (2, 30)), np.array([[99.5, 100.0, 250.0], [63.99, 128.0, 299.0]])):
        boxes.keys.clear(), chunked.keys.clear()
        want = ref(at)
        np.testing.assert_array_equal(ip_boxes(at), want)
        np.testing.assert_array_equal(ip(at), want)
        _assert_each_touched_chunk_read_once(a.shape, chunks, boxes.keys, chunked.keys)
    # An update reads what the recomputed tiles need, a chunk once.
    boxes.keys.clear(), chunked.keys.clear()
    for x in (ref, ip_boxes, ip):
        x.update((slice(98, 103), 64), 2.5)
    _assert_each_touched_chunk_read_once(a.shape, chunks, boxes.keys, chunked.keys)
    at = np.array([[100.0, 101.3], [64.0, 66.6]])
    np.testing.assert_array_equal(ip(at), ref(at))


def _count_store_reads(zarr, monkeypatch):
    """zarr's local store reads counted per key (chunk keys ``c/i/j``), on
    the class: dask reads through a copy of the array and its store."""
    reads = collections.Counter()
    real = zarr.storage.LocalStore.get

    async def get(self, key, prototype=None, byte_range=None):
        reads[key] += 1
        return await real(self, key, prototype, byte_range)

    monkeypatch.setattr(zarr.storage.LocalStore, "get", get)
    return reads


def _counted_zarr(tmp_path, monkeypatch, a, chunks):
    """``a`` written to a zarr array in ``chunks``, and the counter of its
    store's reads (:func:`_count_store_reads`)."""
    zarr = _extra("zarr")
    reads = _count_store_reads(zarr, monkeypatch)
    z = zarr.create_array(store=str(tmp_path / "a.zarr"), shape=a.shape, chunks=chunks, dtype=a.dtype)
    z[...] = a
    return z, reads


@pytest.mark.parametrize("mode", MODES)
def test_zarr_h5py_and_dask_give_the_in_memory_bits(tmp_path, mode):
    zarr, h5py = _extra("zarr"), _extra("h5py")
    import dask.array as da

    rng = np.random.default_rng(4)
    a = rng.standard_normal((230, 170))
    at = np.concatenate([rng.uniform(-3, 233, (2, 60)),
                         [[0.0, 229.0, 37.0, 36.5, 74.0, 229.9, -0.4], [0.0, 169.0, 53.0, 52.99, 106.0, 0.2, 168.6]]],
                        axis=1)
    kw = dict(order=3, mode=mode, cval=-1.5)
    want = _route("local", lambda: splinelab.map_coordinates(a, at, **kw))
    z = zarr.create_array(store=str(tmp_path / f"{mode}.zarr"), shape=a.shape, chunks=(37, 53), dtype=a.dtype)
    z[...] = a
    with h5py.File(tmp_path / f"{mode}.h5", "w") as f:
        f.create_dataset("chunked", data=a, chunks=(41, 29), compression="gzip")
        f.create_dataset("contiguous", data=a)
        assert f["contiguous"].chunks is None
        irregular = da.from_array(a, chunks=((30, 200), (17, 150, 3)))
        sources = [z, f["chunked"], f["contiguous"], da.from_zarr(z), irregular]
        for src in sources:
            got = _route("local", lambda: splinelab.map_coordinates(src, at, **kw))
            np.testing.assert_array_equal(got, want, err_msg=type(src).__name__)
            np.testing.assert_array_equal(splinelab.Interpolant(src, order=3, mode=mode, cval=-1.5)(at), want)


def test_zarr_chunks_are_decompressed_once_on_the_default_route(tmp_path, monkeypatch):
    # 40 cubic points of 1500 x 1200 in 100 x 100 chunks (180 chunks), the
    # default route (the windows, not the whole array): each chunk the
    # windows touch fetched from the store once, the others never.
    import dask.array as da

    rng = np.random.default_rng(5)
    a = rng.standard_normal((1500, 1200))
    z, reads = _counted_zarr(tmp_path, monkeypatch, a, (100, 100))
    at = np.stack([rng.uniform(0, 1499, 40), rng.uniform(0, 1199, 40)])
    want = splinelab.map_coordinates(a, at, order=3)
    boxes = Recording(a)
    np.testing.assert_array_equal(splinelab.map_coordinates(boxes, at, order=3), want)
    touched = {f"c/{c[0][0] // 100}/{c[1][0] // 100}" for c in _touched(a.shape, boxes.keys, (100, 100))}
    for src in (z, da.from_zarr(z)):
        reads.clear()
        np.testing.assert_array_equal(splinelab.map_coordinates(src, at, order=3), want)
        chunk_reads = {k: n for k, n in reads.items() if k.startswith("c/")}
        assert set(chunk_reads) == touched and set(chunk_reads.values()) == {1}, (len(chunk_reads), len(touched))
        assert len(touched) < 180


def test_dask_computes_each_touched_chunk_once():
    import dask.array as da

    rng = np.random.default_rng(6)
    a = rng.standard_normal((500, 400))
    chunks = ((120, 130, 250), (100, 100, 100, 100))
    at = np.stack([rng.uniform(0, 499, 25), rng.uniform(0, 399, 25)])
    want = _route("local", lambda: splinelab.map_coordinates(a, at, order=5, mode="mirror"))
    boxes, leaf = Recording(a), Recording(a)
    d = da.from_array(leaf, chunks=chunks, asarray=False)
    leaf.keys.clear()  # dask's probe of an empty slice for the array's meta
    for src in (boxes, d):
        got = _route("local", lambda: splinelab.map_coordinates(src, at, order=5, mode="mirror"))
        np.testing.assert_array_equal(got, want)
    _assert_each_touched_chunk_read_once(a.shape, chunks, boxes.keys, leaf.keys)


@pytest.mark.parametrize("chunks", ["auto", (64,), ((100, 100), (300,)), (0, 5), lambda: (5, 5)])
def test_without_a_chunk_grid_one_read_per_box(chunks):
    # Anything that is not a chunk grid of the array's shape: today's
    # reads, one per box, the same bits.
    rng = np.random.default_rng(7)
    a = rng.standard_normal((300, 300))
    at = rng.uniform(0, 299, (2, 6))
    boxes, odd = Recording(a), Recording(a, chunks)
    want = _route("local", lambda: splinelab.map_coordinates(boxes, at, order=3))
    np.testing.assert_array_equal(_route("local", lambda: splinelab.map_coordinates(odd, at, order=3)), want)
    assert odd.keys == boxes.keys


@pytest.mark.parametrize("kw", [dict(order=-1), dict(order=2.5), dict(mode="edge"), dict(mode=3), dict(cval="x"),
                                dict(coordinates=np.ones((1, 5)))])
def test_bad_input_is_refused_as_scipy_refuses_it(kw):
    # The class scipy raises (splinelab's are subclasses of it), with the
    # in-memory call's message.
    a = np.random.default_rng(8).standard_normal((50, 60))
    kw = dict(coordinates=np.ones((2, 5)), order=3) | kw
    with pytest.raises(Exception) as scipy_error:
        ndi.map_coordinates(a, **kw)
    with pytest.raises(scipy_error.type) as in_memory:
        splinelab.map_coordinates(a, **kw)
    with pytest.raises(scipy_error.type, match=re.escape(str(in_memory.value))):
        splinelab.map_coordinates(Recording(a, (10, 10)), **kw)


@pytest.mark.parametrize("kw, error, message", [
    (dict(order=200), splinelab.errors.OrderError, "order (the spline degree) 200 is outside 0..199"),
    (dict(order=2.0), TypeError, "order (the spline degree) must be an integer, got float"),
    (dict(mode="edge"), splinelab.errors.ModeError, "edge"),
    (dict(cval="x"), TypeError, "cval must be a real number or None, got str"),
    (dict(nan_policy="skip"), ValueError, "unknown nan_policy 'skip'"),
    (dict(tol="x"), TypeError, "tol must be a real number or None, got str"),
    (dict(threads=0), ValueError, "threads=0 is outside 1..256"),
    (dict(cache_bytes=-1), ValueError, "cache_bytes -1 is outside 0.."),
])
def test_interpolant_refuses_bad_settings_as_before(kw, error, message):
    # The classes and messages of the checks before the settings object.
    with pytest.raises(error, match=re.escape(message)):
        splinelab.Interpolant(Recording(np.zeros((20, 20)), (8, 8)), **kw)


def _dask_tasks_run():
    """A dask callback counting the tasks dask's local schedulers run."""
    from dask.callbacks import Callback

    class Count(Callback):
        def __init__(self):
            super().__init__()
            self.n = 0

        def _pretask(self, key, dsk, state):
            self.n += 1

    return Count()


def test_plain_from_zarr_reads_the_store_directly(tmp_path, monkeypatch):
    # da.from_zarr, with dask's chunks or coarser ones: its blocks are plain
    # reads of the zarr array, so the call reads the zarr array itself (no
    # dask task runs) with zarr's own chunks: each stored chunk the windows
    # touch fetched once (also where one dask block holds four of them),
    # the in-memory bits.
    import dask.array as da

    rng = np.random.default_rng(9)
    a = rng.standard_normal((600, 500))
    z, reads = _counted_zarr(tmp_path, monkeypatch, a, (50, 50))
    at = np.stack([rng.uniform(-2, 601, 30), rng.uniform(-2, 501, 30)])
    want = splinelab.map_coordinates(a, at, order=3, mode="mirror")
    boxes = Recording(a)
    np.testing.assert_array_equal(_route("local", lambda: splinelab.map_coordinates(boxes, at, order=3, mode="mirror")),
                                  want)
    touched = {f"c/{c[0][0] // 50}/{c[1][0] // 50}" for c in _touched(a.shape, boxes.keys, (50, 50))}
    for src in (da.from_zarr(z), da.from_zarr(z, chunks=(100, 100)), da.from_zarr(z, inline_array=True)):
        reads.clear()
        with _dask_tasks_run() as tasks:
            got = _route("local", lambda: splinelab.map_coordinates(src, at, order=3, mode="mirror"))
            np.testing.assert_array_equal(got, want)
            chunk_reads = {k: n for k, n in reads.items() if k.startswith("c/")}
            np.testing.assert_array_equal(splinelab.Interpolant(src, order=3, mode="mirror")(at), want)
        assert set(chunk_reads) == touched and set(chunk_reads.values()) == {1}, (len(chunk_reads), len(touched))
        assert tasks.n == 0


def test_other_dask_graphs_are_computed_by_dask():
    # Blocks that are not plain reads of one array-like (arithmetic, a
    # slice, a lock to honour, a scheduler that is not dask's local one):
    # dask computes them, each touched block once; the in-memory bits.
    import dask
    import dask.array as da

    rng = np.random.default_rng(10)
    a = rng.standard_normal((300, 260))
    at = np.stack([rng.uniform(0, 239, 20), rng.uniform(0, 259, 20)])
    chunks = ((70, 90, 140), (60, 200))
    runs = []

    def counting_get(dsk, keys, **kw):
        runs.append(len(keys))
        return dask.local.get_sync(dsk, keys, **kw)

    leaf = Recording(a)
    plain = da.from_array(leaf, chunks=chunks, asarray=False)
    cases = [(da.from_array(a, chunks=chunks) * 1.0, {}), (da.from_array(leaf, chunks=chunks)[:240], {}),
             (da.from_array(leaf, chunks=chunks, lock=True), {}), (plain, dict(scheduler=counting_get))]
    for src, config in cases:
        want = _route("local", lambda: splinelab.map_coordinates(np.asarray(src), at, order=3))
        leaf.keys.clear()
        with dask.config.set(**config), _dask_tasks_run() as tasks:
            got = _route("local", lambda: splinelab.map_coordinates(src, at, order=3))
        np.testing.assert_array_equal(got, want)
        assert tasks.n > 0 or runs, src.name
    assert runs  # the custom scheduler ran the reads
    # The leaf read through dask's getters: each touched block once.
    boxes = Recording(np.asarray(plain[:240]))
    _route("local", lambda: splinelab.map_coordinates(boxes, at, order=3))
    locked = da.from_array(leaf, chunks=chunks, lock=True)
    leaf.keys.clear()  # dask's probe of an empty slice for the array's meta
    _route("local", lambda: splinelab.map_coordinates(locked, at, order=3))
    _assert_each_touched_chunk_read_once(a.shape, chunks, boxes.keys, leaf.keys)


def test_a_plain_leaf_is_read_as_dask_would_read_it(tmp_path):
    # The leaf of a plain from_array graph (here a recording array-like, and
    # xarray's lazily indexed zarr variable) is read with no dask task: on
    # threads under dask's threaded scheduler (as dask's lock-free getters
    # were called), on this thread under the synchronous one; each touched
    # block once; the in-memory bits.
    import os
    import threading

    import dask
    import dask.array as da

    xr = _extra("xarray")
    _extra("zarr")
    rng = np.random.default_rng(11)
    a = rng.standard_normal((400, 300))
    at = np.stack([rng.uniform(0, 399, 12), rng.uniform(0, 299, 12)])
    chunks = ((100, 150, 150), (90, 210))
    want = _route("local", lambda: splinelab.map_coordinates(a, at, order=3))
    boxes = Recording(a)
    _route("local", lambda: splinelab.map_coordinates(boxes, at, order=3))

    class Threads(Recording):
        def __getitem__(self, key):
            self.where.append(threading.get_ident())
            return super().__getitem__(key)

    main = threading.get_ident()
    for scheduler in ("threads", "sync"):
        leaf = Threads(a)
        src = da.from_array(leaf, chunks=chunks, asarray=False)
        leaf.keys.clear()  # dask's probe of an empty slice for the array's meta
        leaf.where = []
        with dask.config.set(scheduler=scheduler), _dask_tasks_run() as tasks:
            np.testing.assert_array_equal(_route("local", lambda: splinelab.map_coordinates(src, at, order=3)), want)
        assert tasks.n == 0
        _assert_each_touched_chunk_read_once(a.shape, chunks, boxes.keys, leaf.keys)
        on_main = {w == main for w in leaf.where}
        assert on_main == ({True} if scheduler == "sync" or os.cpu_count() == 1 else {False}), scheduler
    xr.DataArray(a, dims=("y", "x"), name="v").to_dataset().to_zarr(
        tmp_path / "x.zarr", encoding={"v": {"chunks": (64, 64)}}, consolidated=False)
    v = xr.open_zarr(tmp_path / "x.zarr", consolidated=False).v.data
    with _dask_tasks_run() as tasks:
        np.testing.assert_array_equal(_route("local", lambda: splinelab.map_coordinates(v, at, order=3)), want)
    assert tasks.n == 0
