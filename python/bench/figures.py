"""Figures for issue 18's closing note (not run by CI). Prints JSON lines.

    bash scripts/python.sh
    cargo build --release -p splinelab-benches --bin engine_peer
    .venv/bin/python python/bench/figures.py --bin $CARGO_TARGET_DIR/release/engine_peer [--big 8192]

1. overhead: splinelab.spline_filter1d (threads=1) at N = 1e6 and 1e7
   against the Rust kernel alone (engine_peer filter1d, RAYON_NUM_THREADS=1:
   copy into a reused buffer + filter), same data, A/B alternated, medians;
   the Python call both into a reused `output=` array (the same work) and
   with a fresh result array (plus numpy's own fresh/reused copy for scale);
2. scipy: throughput ratio against scipy.ndimage.spline_filter1d /
   spline_filter in the same run (ratio = scipy_s / ours_s);
3. seam: dask seam error (max |chunked - exact|) of splinelab.dask and of
   dask-image at their defaults, degrees 3, 5, 2048^2 in 4 x 4 chunks;
4. cluster: wall time of a 2-worker LocalCluster (processes: routes
   truncated and recursive, 4 x 4 and 2 x 2 chunks; thread workers in one
   process: both routes, 4 x 4) against one process on big^2
   (generate, filter, reduce to max|c|).
"""

import argparse
import json
import os
import pathlib
import subprocess
import sys
import time

import numpy as np
from scipy import ndimage

import splinelab
import splinelab.dask as sld

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "benches" / "peers"))
from scipy_ratio import data, median_time  # noqa: E402  (the same data as the engine bench)

ROUNDS = 3
OVERHEAD_ROUNDS = 7


def emit(**kw):
    print(json.dumps(kw), flush=True)


def rust_kernel(binary, degree, n, reps):
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    out = subprocess.run([binary, "filter1d", str(degree), str(n), str(reps)], env=env, check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)["seconds"]


def overhead(binary):
    """Per N, A/B alternated: the Python call writing into a reused array
    (`output=buf`: the kernel's work, copy into a reused buffer + filter,
    plus argument handling and the finite check fused into the copy), the
    plain call (a fresh result array each time), the kernel alone, and
    numpy's own copy into a fresh / a reused array for scale."""
    for n in (1_000_000, 10_000_000):
        s, buf = data(n), np.empty(n)
        reps = 21 if n <= 1_000_000 else 9
        t = {k: [] for k in ("into", "fresh", "rust", "np_fresh", "np_into")}
        for _ in range(OVERHEAD_ROUNDS):
            t["into"].append(median_time(lambda: splinelab.spline_filter1d(s, 3, output=buf, threads=1), reps))
            t["rust"].append(rust_kernel(binary, 3, n, reps))
            t["fresh"].append(median_time(lambda: splinelab.spline_filter1d(s, 3, threads=1), reps))
            t["np_fresh"].append(median_time(lambda: np.copyto(np.empty_like(s), s), reps))
            t["np_into"].append(median_time(lambda: np.copyto(buf, s), reps))
        m = {k: sorted(v)[len(v) // 2] for k, v in t.items()}
        emit(figure="overhead", n=n, degree=3, rounds=OVERHEAD_ROUNDS, python_s=m["fresh"], python_into_s=m["into"],
             rust_s=m["rust"], overhead=m["fresh"] / m["rust"] - 1, overhead_into=m["into"] / m["rust"] - 1,
             numpy_copy_fresh_s=m["np_fresh"], numpy_copy_into_s=m["np_into"])


def versus_scipy():
    for degree in (3, 5):
        for n in (10_000, 1_000_000, 10_000_000):
            s, reps = data(n), max(3, min(101, 10_000_000 // n))
            a = [(median_time(lambda: ndimage.spline_filter1d(s, degree, mode="mirror"), reps),
                  median_time(lambda: splinelab.spline_filter1d(s, degree, threads=1), reps)) for _ in range(ROUNDS)]
            report("spline_filter1d", degree, n, a)
        for shape in [(2048, 2048), (4096, 4096), (256, 256, 256)]:
            x = data(int(np.prod(shape))).reshape(shape)
            a = [(median_time(lambda: ndimage.spline_filter(x, degree, mode="mirror"), 3),
                  median_time(lambda: splinelab.spline_filter(x, degree, threads=1), 3)) for _ in range(ROUNDS)]
            report("spline_filter", degree, "x".join(map(str, shape)), a)


def report(case, degree, n, pairs):
    sc = sorted(p[0] for p in pairs)[ROUNDS // 2]
    ours = sorted(p[1] for p in pairs)[ROUNDS // 2]
    emit(figure="scipy", case=case, degree=degree, n=n, threads=1, scipy_s=sc, ours_s=ours, ratio=sc / ours)


def seams():
    import dask.array as da
    from dask_image.ndinterp import spline_filter as di_filter

    x = np.random.default_rng(18).uniform(-1, 1, (2048, 2048))
    for degree in (3, 5):
        exact = splinelab.spline_filter(x, degree)
        d = da.from_array(x, chunks=512)
        ours = np.abs(sld.spline_filter(d, degree).compute(scheduler="threads") - exact).max()
        theirs = np.abs(di_filter(d, degree).compute(scheduler="threads") - exact).max()
        emit(figure="seam", degree=degree, ours=ours, ours_tol=sld.DEFAULT_TOL, ours_depth=sld.depth(degree),
             certified=splinelab.filter_bound(degree, sld.DEFAULT_TOL, 2)["total"], dask_image=theirs)


def cluster(big):
    """Generate uniform(-1, 1), filter (cubic), reduce to max|c|: a 2-worker
    LocalCluster (data generated on the workers) per route and chunking,
    against one process (numpy data, exact filter, 1 thread / all cores)."""
    import dask.array as da
    import distributed

    def one_process(threads):
        t0 = time.perf_counter()
        x = np.random.default_rng(0).uniform(-1, 1, (big, big))
        m = np.abs(splinelab.spline_filter(x, 3, threads=threads)).max()
        return time.perf_counter() - t0, m

    def timed(client, route, split):
        x = da.random.default_rng(0).uniform(-1, 1, (big, big), chunks=big // split)
        t0 = time.perf_counter()
        m = client.compute(abs(sld.spline_filter(x, 3, route=route)).max()).result()
        return time.perf_counter() - t0, m

    runs = {}
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as lc, distributed.Client(lc) as client:
        for route in ("truncated", "recursive"):
            for split in (4, 2):
                runs[f"{route}_{split}x{split}"] = timed(client, route, split)
    # Two thread workers in one process: no pickling of chunks and halos.
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as lc, distributed.Client(lc) as client:
        timed(client, "recursive", 8)  # warm-up
        for route in ("truncated", "recursive"):
            runs[f"threads_{route}_4x4"] = timed(client, route, 4)
    t1, m1 = one_process(1)
    t2, m2 = one_process(None)
    emit(figure="cluster", n=big, degree=3, cluster_2_workers_s=runs["truncated_4x4"][0],
         cluster_s={k: v[0] for k, v in runs.items()}, one_process_1_thread_s=t1, one_process_all_cores_s=t2,
         max_c=[runs["truncated_4x4"][1], m1, m2], max_c_runs={k: v[1] for k, v in runs.items()})


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "engine_peer"))
    ap.add_argument("--big", type=int, default=8192)
    ap.add_argument("--only", choices=["overhead", "scipy", "seam", "cluster"])
    a = ap.parse_args()
    steps = {"overhead": lambda: overhead(a.bin), "scipy": versus_scipy, "seam": seams,
             "cluster": lambda: cluster(a.big)}
    for name, step in steps.items():
        if a.only in (None, name):
            step()


if __name__ == "__main__":
    main()
