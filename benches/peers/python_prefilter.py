"""The Python package's prefilter against a plain copy of the same bytes
(issue 26's memory wall), one and two threads alternated in one process
(not run by CI).

    bash scripts/python.sh
    .venv/bin/python benches/peers/python_prefilter.py [--rounds 5] [--only 1d|2d|3d]

Prints one JSON object per case and thread count: `ms` (the minimum over
`--rounds` alternated rounds of the minimum of 3 calls: the least disturbed
figure on a shared machine), `copy_ms` (`np.copyto` of the same bytes, same
rounds) and `over_copy`; `cpu_ms` and `copy_cpu_ms`, the same minima of the
process's CPU time (`time.process_time`, every thread): on one thread the
figure that other processes on a busy machine do not inflate by taking the
core away (they still share its caches and memory). Filters write into a preallocated output, so the
figures exclude numpy's allocation (its first touch is the kernel zeroing
pages, the same for every route).
"""
import argparse
import json
import time

import numpy as np

import splinelab


def best(fn, reps=3):
    """(wall, cpu): the minimum of each over `reps` calls, after a warm-up."""
    fn()
    wall, cpu = [], []
    for _ in range(reps):
        t0, c0 = time.perf_counter(), time.process_time()
        fn()
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return min(wall), min(cpu)


def cases(only):
    rng = np.random.default_rng(0)
    x1 = rng.uniform(-1, 1, 10**7)
    x2 = rng.uniform(-1, 1, (4096, 4096))
    x3 = rng.uniform(-1, 1, (256, 256, 256))
    out = []
    if only in (None, "1d"):
        for n in (10**4, 10**5, 10**6):
            xs = x1[:n].copy()
            for tol in (None, 1e-12):
                out.append((f"spline_filter1d 1e{len(str(n)) - 1} degree 3 {'exact' if tol is None else 'tol=1e-12'}", xs,
                            lambda x, o, t, tol=tol: splinelab.spline_filter1d(x, 3, output=o, threads=t, tol=tol)))
        for d in (3, 5):
            out.append((f"spline_filter1d 1e7 degree {d} exact", x1, lambda x, o, t, d=d: splinelab.spline_filter1d(x, d, output=o, threads=t)))
            out.append((f"spline_filter1d 1e7 degree {d} tol=1e-12", x1,
                        lambda x, o, t, d=d: splinelab.spline_filter1d(x, d, output=o, threads=t, tol=1e-12)))
    if only in (None, "2d"):
        for d in (3, 5):
            out.append((f"spline_filter 4096^2 degree {d}", x2, lambda x, o, t, d=d: splinelab.spline_filter(x, d, output=o, threads=t)))
        x2f = x2.astype(np.float32)
        out.append(("spline_filter 4096^2 degree 3 float32", x2f, lambda x, o, t: splinelab.spline_filter(x, 3, output=o, threads=t)))
    if only in (None, "3d"):
        for d in (3, 5):
            out.append((f"spline_filter 256^3 degree {d}", x3, lambda x, o, t, d=d: splinelab.spline_filter(x, d, output=o, threads=t)))
        x3f = x3.astype(np.float32)
        out.append(("spline_filter 256^3 degree 3 float32", x3f, lambda x, o, t: splinelab.spline_filter(x, 3, output=o, threads=t)))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--only", choices=("1d", "2d", "3d"), default=None)
    args = ap.parse_args()
    for name, x, run in cases(args.only):
        o = np.empty_like(x)
        times = {1: [], 2: []}
        copies = []
        for _ in range(args.rounds):
            for t in (1, 2):
                times[t].append(best(lambda: run(x, o, t)))
            copies.append(best(lambda: np.copyto(o, x)))
        c, c_cpu = (min(v) for v in zip(*copies))
        for t in (1, 2):
            ms, cpu = (min(v) for v in zip(*times[t]))
            print(json.dumps({"case": name, "threads": t, "ms": round(ms * 1e3, 3), "copy_ms": round(c * 1e3, 3),
                              "over_copy": round(ms / c, 2), "cpu_ms": round(cpu * 1e3, 3),
                              "copy_cpu_ms": round(c_cpu * 1e3, 3)}), flush=True)
        speedup = min(w for w, _ in times[1]) / min(w for w, _ in times[2])
        print(json.dumps({"case": name, "two_over_one_thread_speedup": round(speedup, 2)}), flush=True)


if __name__ == "__main__":
    main()
