"""Each stored chunk read at most once a call (issue 51), measured.

    .venv/bin/python python/bench/chunk_reads.py [--side 12000] [--chunk 1000] [--points 1000 100]
        [--dir /tmp/chunk_reads] [--no-scipy] [--repeats 1]

Writes (once; reused when ``--dir`` already holds it) a ``side x side``
float64 zarr 3 array in ``chunk x chunk`` chunks, zarr's default compressor,
random standard-normal samples (seed 0), and times for each point count
(random cubic points, seed 1, the default mode):

(a) ``splinelab.map_coordinates`` reading the zarr array directly;
(b) the same through ``dask.array.from_zarr`` (its blocks are plain reads
    of the zarr array, so the call reads the zarr array itself, with no
    dask graph: ``splinelab._local._dask_reader``); (b') the same through
    dask's graph (one ``dask.compute`` of the parts: the route of every
    other dask array, and of this one before);
(c) reading once, one ``arr[chunk slices]`` after another (each released
    before the next), the chunks the points' windows touch (the boxes the
    local route asks for, mapped to chunks by floor division here);
(d) scipy on the array read whole (the read and the interpolation apart;
    ``--no-scipy`` skips it: seconds).

The store counts its chunk reads (keys ``c/i/j``) in (a) and (b); each
call is checked to read each touched chunk once and to give the bits of
``splinelab.map_coordinates(np.asarray(arr), ...)``. Times: (a)-(c) run in
turn, ``--repeats`` rounds, the fastest of each (the load moves between
rounds, not between the cases of one); memory: the largest peak resident
size above a call's start (``_peak``). (a) reads its chunks on one thread per core (the default) and
on one thread (``threads=1``); (c) on one. The load average is printed
before and after (the figures are wall times: say the load with them).
"""

import argparse
import collections
import contextlib
import os
import pathlib
import tempfile
import time

import numpy as np
from _peak import reset_peak, rss_kib


def count_store_reads(zarr):
    """zarr's local store reads counted per key, on the class (dask reads
    through a copy of the array and its store)."""
    reads = collections.Counter()
    real = zarr.storage.LocalStore.get

    async def get(self, key, prototype=None, byte_range=None):
        reads[key] += 1
        return await real(self, key, prototype, byte_range)

    zarr.storage.LocalStore.get = get
    return reads


def open_array(zarr, path, side, chunk):
    """The benchmark's array at ``path`` (written there first if missing),
    and the counter of its store's reads."""
    reads = count_store_reads(zarr)
    if not (pathlib.Path(path) / "zarr.json").exists():
        z = zarr.create_array(store=str(path), shape=(side, side), chunks=(chunk, chunk), dtype="float64")
        rng = np.random.default_rng(0)
        start = time.perf_counter()
        for i in range(0, side, chunk):  # a row of chunks at a time: bounded memory
            z[i:i + chunk] = rng.standard_normal((min(chunk, side - i), side))
        print(f"wrote {side}x{side} float64 in {chunk}^2 chunks to {path}: {time.perf_counter() - start:.1f} s")
    return zarr.open_array(store=str(path), mode="r"), reads


def touched_chunks(shape, chunk, at):
    """The chunks ``(i, j)`` the windows of the points ``at`` touch: the
    boxes the local route reads (its engine's plan), by floor division."""
    from splinelab import _local
    from splinelab._settings import Settings
    from splinelab._validate import DEFAULT_TOL

    s = Settings.of(3, "constant", 0.0, True, DEFAULT_TOL, None, False)
    spline, rule = _local.engine(shape, s, 0.0, np.float64)
    out = set()
    for lo, hi in spline.boxes_for_eval(np.ascontiguousarray(at), rule):
        spans = [range(l // chunk, (h - 1) // chunk + 1) for l, h in zip(lo, hi)]
        out.update((i, j) for i in spans[0] for j in spans[1])
    return sorted(out)


@contextlib.contextmanager
def dask_graph(on):
    """With ``on``: dask arrays read through their graph (the reading of a
    plain from-zarr array's store directly turned off)."""
    from splinelab import _local

    real = _local._dask_reader
    if on:
        _local._dask_reader = lambda darr, boxes, grid: (darr, grid)
    try:
        yield
    finally:
        _local._dask_reader = real


def chunk_reads(reads):
    """The counted reads of chunk keys, by key."""
    return {k: n for k, n in reads.items() if k.startswith("c/")}


def run(z, reads, at, chunk, repeats, whole):
    """Prints (a)-(d) for the points ``at``; asserts the bits and the reads."""
    import dask.array as da
    import scipy.ndimage as ndi

    import splinelab

    k = at.shape[1]
    chunks = touched_chunks(z.shape, chunk, at)
    want = {f"c/{i}/{j}" for i, j in chunks}

    def read_touched():
        for i, j in chunks:  # each released before the next is read, as (a) releases its groups
            z[i * chunk:(i + 1) * chunk, j * chunk:(j + 1) * chunk]

    cases = (("(a) zarr directly", z, None, False), ("(a) zarr directly, threads=1", z, 1, False),
             ("(b) dask.array.from_zarr", da.from_zarr(z), None, False),
             ("(b') dask.array.from_zarr through dask's graph", da.from_zarr(z), None, True))
    results, times, peaks = {}, collections.defaultdict(list), collections.defaultdict(float)
    for _ in range(repeats):
        start = time.perf_counter()
        read_touched()
        times["c"].append(time.perf_counter() - start)
        for name, src, threads, graph in cases:
            reads.clear()
            base = reset_peak()
            with dask_graph(graph):
                start = time.perf_counter()
                results[name] = splinelab.map_coordinates(src, at, order=3, threads=threads)
                times[name].append(time.perf_counter() - start)
            peaks[name] = max(peaks[name], (rss_kib("VmHWM") - base) / 1024)
            got = chunk_reads(reads)
            assert set(got) == want and set(got.values()) == {1}, (name, len(got), len(want))
    t_c = min(times["c"])
    print(f"{k} points: (c) reading the {len(chunks)} touched chunks once: {t_c:.2f} s")
    for name, *_ in cases:
        t = min(times[name])
        print(f"{k} points: {name}: {t:.2f} s, {len(want)} chunk reads (each once a call), "
              f"peak +{peaks[name]:.0f} MB; {t / t_c:.2f}x (c)")
    ref = splinelab.map_coordinates(whole, at, order=3)
    for name, v in results.items():
        assert np.array_equal(v, ref), name
    print(f"{k} points: (a), (b) and the in-memory call: the same bits")
    return ref


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--side", type=int, default=12000)
    p.add_argument("--chunk", type=int, default=1000)
    p.add_argument("--points", type=int, nargs="+", default=[1000, 100])
    p.add_argument("--dir", default=None, help="where the zarr array is kept (default: a temporary directory)")
    p.add_argument("--no-scipy", action="store_true", help="skip (d): scipy on the array read whole")
    p.add_argument("--repeats", type=int, default=1)
    args = p.parse_args()
    import zarr

    print("load average (1, 5, 15 min): {:.2f} {:.2f} {:.2f}".format(*os.getloadavg()))
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(args.dir or tmp) / f"a{args.side}_{args.chunk}.zarr"
        z, reads = open_array(zarr, path, args.side, args.chunk)
        start = time.perf_counter()
        whole = np.asarray(z[...])
        t_read = time.perf_counter() - start
        print(f"read whole: {t_read:.2f} s ({whole.nbytes / 2**30:.2f} GiB)")
        at_all = np.random.default_rng(1).uniform(0, args.side - 1, (2, max(args.points)))
        for k in args.points:
            at = np.ascontiguousarray(at_all[:, :k])
            ref = run(z, reads, at, args.chunk, args.repeats, whole)
            if not args.no_scipy:
                import scipy.ndimage as ndi

                start = time.perf_counter()
                v = ndi.map_coordinates(whole, at, order=3)
                t = time.perf_counter() - start
                print(f"{k} points: (d) scipy: {t_read + t:.2f} s ({t_read:.2f} s read whole + {t:.2f} s), "
                      f"max |splinelab - scipy| {np.abs(ref - v).max():.1e}")
    print("load average (1, 5, 15 min): {:.2f} {:.2f} {:.2f}".format(*os.getloadavg()))


if __name__ == "__main__":
    main()
