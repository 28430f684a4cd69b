"""Throughput ratio of splinelab's engine to scipy.ndimage 1.17 on the same
data, A/B alternated (not run by CI).

    cargo build --release -p splinelab-benches --bin engine_peer
    python3 benches/peers/scipy_ratio.py [--bin target/release/engine_peer] [--threads 1]
        [--rounds 3] [--stat median|min] [--only KIND]

For each case, runs scipy and our `engine_peer` binary alternately
`--rounds` times (each side reports the median of its own repetitions,
excluding process start-up; the rounds are then summarised by `--stat`: the
median, or the minimum, which on a shared machine is the least disturbed),
and prints one JSON object per case:
{"case", "threads", "scipy_s", "ours_s", "ratio", "memcpy_s", "ours_over_memcpy"}
(ratio = scipy_s / ours_s, > 1 means we are faster; memcpy_s is the median
time of `np.copyto` of the same bytes — the array for the filters, the
points for eval2d — taken in the same rounds, one thread: the memory wall
each route is measured against, ours_over_memcpy = ours_s / memcpy_s). scipy is single-threaded; ours uses
RAYON_NUM_THREADS = --threads, except the `blocks1d` cases (the 1-D
block route), which always use both cores (RAYON_NUM_THREADS=2). The
`tol1d` cases time the `tol=1e-12` route of one line (what
`splinelab.spline_filter1d(x, tol=1e-12)` runs) against scipy's exact filter.
"""
import argparse
import json
import os
import subprocess
import time

import numpy as np
from scipy import ndimage

ROUNDS = 3


def data(total):
    i = np.arange(total, dtype=np.int64)
    return (((i * 7919) % 2003).astype(np.float64) - 1001.0) / 1001.0


def median_time(fn, reps):
    fn()
    t = []
    for _ in range(reps):
        t0 = time.perf_counter()
        fn()
        t.append(time.perf_counter() - t0)
    return sorted(t)[len(t) // 2]


def scipy_case(kind, degree, n, reps):
    if kind in ("filter1d", "blocks1d", "tol1d"):
        s = data(n)
        return median_time(lambda: ndimage.spline_filter1d(s, degree, mode="mirror"), reps)
    if kind in ("filter2d", "filter3d"):
        dims = (n, n) if kind == "filter2d" else (n, n, n)
        a = data(int(np.prod(dims))).reshape(dims)
        return median_time(lambda: ndimage.spline_filter(a, degree, mode="mirror"), reps)
    if kind == "eval2d":
        a = data(n * n).reshape(n, n)
        c = ndimage.spline_filter(a, degree, mode="mirror")
        k = np.arange(1_000_000, dtype=np.int64)
        span = (n - 1) * 100
        pts = np.stack([((k * 7919) % span) / 100.0, ((k * 104729) % span) / 100.0])
        return median_time(
            lambda: ndimage.map_coordinates(c, pts, order=degree, mode="mirror", prefilter=False), reps)
    raise ValueError(kind)


def case_bytes(kind, n):
    """The elements a plain copy moves for the case (f64)."""
    if kind in ("filter1d", "blocks1d", "tol1d"):
        return n
    if kind == "filter2d":
        return n * n
    if kind == "filter3d":
        return n ** 3
    if kind == "eval2d":
        return 2 * 1_000_000
    raise ValueError(kind)


def memcpy_case(kind, n, reps):
    src = data(case_bytes(kind, n))
    dst = np.empty_like(src)
    return median_time(lambda: np.copyto(dst, src), reps)


def ours_case(binary, threads, kind, degree, n, reps):
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    out = subprocess.run([binary, kind, str(degree), str(n), str(reps)],
                         env=env, check=True, capture_output=True, text=True).stdout
    return json.loads(out)["seconds"]


CASES = [
    ("filter1d", 3, 10_000, 200), ("filter1d", 3, 1_000_000, 9), ("filter1d", 3, 10_000_000, 3),
    ("filter1d", 5, 10_000, 200), ("filter1d", 5, 1_000_000, 9), ("filter1d", 5, 10_000_000, 3),
    ("blocks1d", 3, 1_000_000, 9), ("blocks1d", 3, 10_000_000, 3),
    ("blocks1d", 5, 1_000_000, 9), ("blocks1d", 5, 10_000_000, 3),
    ("tol1d", 3, 1_000_000, 9), ("tol1d", 3, 10_000_000, 3),
    ("tol1d", 5, 1_000_000, 9), ("tol1d", 5, 10_000_000, 3),
    ("filter2d", 3, 4096, 3), ("filter2d", 5, 4096, 3),
    ("filter3d", 3, 256, 3), ("filter3d", 5, 256, 3),
    ("eval2d", 3, 1024, 5),
]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default_bin = os.path.join(here, "..", "..", "target", "release", "engine_peer")
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.environ.get("ENGINE_PEER", default_bin))
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--only", default=None, help="run only this kind")
    ap.add_argument("--rounds", type=int, default=ROUNDS, help="alternated rounds per case")
    ap.add_argument("--stat", choices=("median", "min"), default="median",
                    help="summary of the rounds (min: the least disturbed, on a shared machine)")
    args = ap.parse_args()
    pick = (lambda v: sorted(v)[len(v) // 2]) if args.stat == "median" else min
    for kind, degree, n, reps in CASES:
        if args.only and kind != args.only:
            continue
        threads = 2 if kind == "blocks1d" else args.threads
        ours, theirs, copies = [], [], []
        for _ in range(max(args.rounds, 1)):
            theirs.append(scipy_case(kind, degree, n, reps))
            ours.append(ours_case(args.bin, threads, kind, degree, n, reps))
            copies.append(memcpy_case(kind, n, reps))
        s, o, c = pick(theirs), pick(ours), pick(copies)
        print(json.dumps({"case": f"{kind} degree {degree} n {n}", "threads": threads,
                          "scipy_s": s, "ours_s": o, "ratio": s / o,
                          "memcpy_s": c, "ours_over_memcpy": o / c}), flush=True)


if __name__ == "__main__":
    main()
