"""Figures of the local route (issue 45), measured on this machine.

    .venv/bin/python python/bench/local_route.py --npy /tmp/big.npy [--side 16000] [--scipy] [--global-route]
    .venv/bin/python python/bench/local_route.py --npy - --report-json verify/fixtures/scipy/local_route.json

Makes ``--npy`` (a ``side x side`` float64 array, random in [-1, 1), seed 0)
if it is missing and reads it with ``mmap_mode="r"``; prints one line per
figure. Times are the minimum of ``--repeats`` runs; memory is the peak of
the process's anonymous resident memory (``RssAnon``, sampled every
millisecond by a thread) above its value before the call — the file's
mapped pages are file-backed, not anonymous. ``--scipy`` also times scipy
(the whole array: seconds, a 2 GB float64 copy at 16000**2); ``--report-json``
measures only scipy's figures on the report's sizes and writes them there (the
report reads them: it does not run scipy).
Whether the file was in the page cache before the run is printed
(``fincore``-like: ``mincore`` is not reachable from numpy, so the first
read's speed is printed instead).
"""

import argparse
import json
import threading
import time

import numpy as np


def rss_anon():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("RssAnon:"):
                return int(line.split()[1]) * 1024
    return 0


def peak_anon(f):
    """``(result, seconds, peak anonymous bytes above the start)`` of ``f()``."""
    base = rss_anon()
    peak = [base]
    done = threading.Event()

    def sample():
        while not done.is_set():
            peak[0] = max(peak[0], rss_anon())
            time.sleep(0.001)

    t = threading.Thread(target=sample)
    t.start()
    start = time.perf_counter()
    try:
        out = f()
    finally:
        dt = time.perf_counter() - start
        done.set()
        t.join()
    return out, dt, max(peak[0], rss_anon()) - base


def best(f, repeats):
    """The fastest of ``repeats`` runs: ``(result, seconds, peak bytes)``."""
    runs = [peak_anon(f) for _ in range(repeats)]
    return min(runs, key=lambda r: r[1])


def route(r, f):
    from splinelab import _local

    old = _local.ROUTE
    _local.ROUTE = r
    try:
        return f()
    finally:
        _local.ROUTE = old


def update_figures(repeats):
    """Interpolant.update on a 4096**2 cubic (mirror): one sample, 1000
    scattered samples; the tiles around 10**4 random points cached first;
    each against a rebuild at those points (bit for bit)."""
    import splinelab

    rng = np.random.default_rng(3)
    x = rng.uniform(-1, 1, (4096, 4096))
    at = rng.uniform(0, 4095, (2, 10_000))
    ip = splinelab.Interpolant(x, order=3, mode="mirror")
    ip(at)
    print(f"Interpolant 4096^2 cubic: {ip.cache_info()['tiles']} tiles cached after 10^4 points")
    for count in (1, 1000):
        times = []
        for _ in range(repeats):
            i, j = rng.integers(0, 4096, (2, count))
            v = rng.uniform(-1, 1, count)
            t = time.perf_counter()
            ip.update((i, j), v)
            times.append(time.perf_counter() - t)
            x[i, j] = v
        same = np.array_equal(ip(at), splinelab.Interpolant(x, order=3, mode="mirror")(at))
        print(f"Interpolant.update of {count} scattered samples: {min(times) * 1e3:.3f} ms (min of {repeats}); "
              f"equal to a rebuild bit for bit: {same}")
    t = time.perf_counter()
    splinelab.spline_filter(x, order=3, mode="mirror")
    print(f"full prefilter of 4096^2 (splinelab.spline_filter): {(time.perf_counter() - t) * 1e3:.1f} ms")


def report_json(path, repeats):
    """scipy's figures for the report's sizes (quick: 2048**2 points,
    1024**2 update; full: 8192**2, 4096**2), written to ``path``."""
    import os
    import tempfile

    import scipy.ndimage as ndi

    out = {}
    rng = np.random.default_rng(1)
    for side in (2048, 8192):
        with tempfile.TemporaryDirectory() as d:
            f = os.path.join(d, "a.npy")
            np.save(f, np.random.default_rng(0).uniform(-1, 1, (side, side)))
            a = np.load(f, mmap_mode="r")
            at = rng.uniform(0, side - 1, (2, 1000))
            _, dt, mem = best(lambda: ndi.map_coordinates(a, at, order=3, mode="mirror"), repeats)
            del a
        out[str(side)] = {"map_coordinates_1000_s": dt, "map_coordinates_1000_mb": mem / 2**20}
        print(f"scipy map_coordinates, 1000 cubic points, memory-mapped {side}^2: {dt:.3f} s, +{mem / 2**20:.0f} MB")
    for side in (1024, 4096):
        x = np.random.default_rng(2).uniform(-1, 1, (side, side))
        _, dt, _ = best(lambda: ndi.spline_filter(x, order=3, mode="mirror"), repeats)
        out.setdefault(str(side), {})["spline_filter_s"] = dt
        print(f"scipy spline_filter, cubic, {side}^2: {dt:.3f} s")
    out["scipy"] = __import__("scipy").__version__
    with open(path, "w") as f:
        json.dump(out, f, indent=1, sort_keys=True)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--report-json", help="only measure scipy's figures for the report into this file")
    p.add_argument("--npy", required=True)
    p.add_argument("--side", type=int, default=16000)
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--scipy", action="store_true")
    p.add_argument("--global-route", action="store_true", help="also time the global route at 1000 points")
    p.add_argument("--json")
    args = p.parse_args()
    import os

    if args.report_json:
        report_json(args.report_json, args.repeats)
        return
    import splinelab

    if not os.path.exists(args.npy):
        a = np.lib.format.open_memmap(args.npy, mode="w+", dtype=np.float64, shape=(args.side, args.side))
        rng = np.random.default_rng(0)
        for i in range(0, args.side, 1000):
            a[i:i + 1000] = rng.uniform(-1, 1, (min(1000, args.side - i), args.side))
        a.flush()
        del a
    a = np.load(args.npy, mmap_mode="r")
    side = a.shape[0]
    t0 = time.perf_counter()
    np.asarray(a[::97, ::1000]).sum()
    print(f"file {args.npy}: shape {a.shape}, first strided read of {side // 97 + 1} rows in "
          f"{time.perf_counter() - t0:.4f} s (page cache warm if well under 0.1 s)")
    rng = np.random.default_rng(1)
    at = rng.uniform(0, side - 1, (2, 1000))
    out = {}

    v, dt, mem = best(lambda: splinelab.map_coordinates(a, at, order=3, mode="mirror"), args.repeats)
    print(f"local  order 3, 1000 points, default tol, mirror: {dt * 1e3:.1f} ms, +{mem / 2**20:.1f} MB anon")
    out["local_1000_cubic_s"], out["local_1000_cubic_anon_bytes"] = dt, mem
    one = np.array([[side / 2 + 0.3], [side / 3 + 0.6]])
    _, dt1, mem1 = best(lambda: splinelab.map_coordinates(a, one, order=1, mode="mirror"), args.repeats * 4)
    print(f"local  order 1, one point: {dt1 * 1e3:.3f} ms, +{mem1 / 2**20:.2f} MB anon")
    at4 = rng.uniform(0, side - 1, (2, 10_000))
    _, dt5, mem5 = best(lambda: splinelab.map_coordinates(a, at4, order=5, mode="mirror", tol=1e-12), args.repeats)
    print(f"local  order 5, 10^4 points, tol=1e-12: {dt5:.3f} s, +{mem5 / 2**20:.1f} MB anon")
    for k in (10**3, 10**4, 10**5, 10**6):
        c = splinelab._splinelab.local_route_cost([side, side], rng.uniform(0, side - 1, (2, k)), 3, "mirror", None,
                                                   True, "fold", 0)
        print(f"cost estimate, cubic, {k} random points: local {c[0] / 1e9:.2f} s, global {c[1] / 1e9:.2f} s "
              f"(tile {c[2]}, {c[3]} tiles) -> {'local' if c[0] < c[1] else 'global'}")
    if args.global_route:
        g, dtg, memg = best(lambda: route("global", lambda: splinelab.map_coordinates(a, at, order=3, mode="mirror")),
                            1)
        print(f"global order 3, 1000 points: {dtg:.2f} s, +{memg / 2**20:.0f} MB anon; "
              f"max|local - global| = {np.abs(v - g).max():.2e}")
        out["global_1000_cubic_s"], out["global_1000_cubic_anon_bytes"] = dtg, memg
    if args.scipy:
        import scipy.ndimage as ndi

        s, dts, mems = best(lambda: ndi.map_coordinates(a, at, order=3, mode="mirror"), 1)
        print(f"scipy  order 3, 1000 points: {dts:.2f} s, +{mems / 2**20:.0f} MB anon; "
              f"max|local - scipy| / max|scipy| = {np.abs(v - s).max() / np.abs(s).max():.2e}")
        _, dts1, mems1 = best(lambda: ndi.map_coordinates(a, one, order=1, mode="mirror"), args.repeats)
        print(f"scipy  order 1, one point: {dts1 * 1e3:.3f} ms, +{mems1 / 2**20:.2f} MB anon")
        out.update(scipy_1000_cubic_s=dts, scipy_1000_cubic_anon_bytes=mems, scipy_order1_one_point_s=dts1)
    update_figures(args.repeats)
    if args.json:
        out["side"] = side
        with open(args.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
