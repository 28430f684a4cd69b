"""The certified tol route at the memory wall (issue 50): spline_filter1d(x,
3, output=dst, tol=1e-12) of 10^7 float64 samples into a given output, on one
and two threads, beside np.copyto of the same bytes, alternated in one
process (copy, tol 1T, tol 2T, exact 1T per round), the minimum of ROUNDS
rounds of min-of-3 each. One thread: CPU time (time.process_time), which a
loaded machine does not inflate; two threads: wall time (CPU time would add
the threads up). The machine's load is printed beside the figures: on a
shared 2-core machine wall times of long calls stretch more than short ones
(a 4 ms copy fits in one time slice, a 40 ms call does not), so compare
ratios measured in the same run only (not run by CI):

    .venv/bin/python python/bench/tol_wall.py [--rounds 7] [--n 10000000] [--base DIR]

--base: a folder holding another build importable as ``splinelab_base``
(as ``ab_builds.py``), whose tol route is timed in the same rounds ("before").
"""

import argparse
import os
import sys
import time

import numpy as np

import splinelab as sl
from prefilter_ab import timed  # min of 3 after a warm-up, by the given clock


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--rounds", type=int, default=7)
    p.add_argument("--n", type=int, default=10**7)
    p.add_argument("--base", help="folder holding the other build as splinelab_base")
    args = p.parse_args()
    x = np.random.default_rng(7).standard_normal(args.n)
    dst = np.empty_like(x)
    cases = {
        "copy_1T_cpu": (lambda: np.copyto(dst, x), time.process_time),
        "copy_1T_wall": (lambda: np.copyto(dst, x), time.perf_counter),
        "tol_1T_cpu": (lambda: sl.spline_filter1d(x, 3, output=dst, threads=1, tol=1e-12), time.process_time),
        "tol_2T_wall": (lambda: sl.spline_filter1d(x, 3, output=dst, threads=2, tol=1e-12), time.perf_counter),
        "exact_1T_cpu": (lambda: sl.spline_filter1d(x, 3, output=dst, threads=1), time.process_time),
    }
    if args.base:
        sys.path.insert(0, args.base)
        import splinelab_base as base

        cases["before_tol_1T_cpu"] = (
            lambda: base.spline_filter1d(x, 3, output=dst, threads=1, tol=1e-12), time.process_time)
        cases["before_tol_2T_wall"] = (
            lambda: base.spline_filter1d(x, 3, output=dst, threads=2, tol=1e-12), time.perf_counter)
    best = {k: float("inf") for k in cases}
    for _ in range(args.rounds):
        for k, (fn, clock) in cases.items():
            best[k] = min(best[k], timed(fn, clock))
    ms = {k: v * 1e3 for k, v in best.items()}
    copy = ms["copy_1T_cpu"]
    print(f"n={args.n} rounds={args.rounds} load {os.getloadavg()[0]:.2f} (cores {os.cpu_count()})")
    print(f"np.copyto          1T cpu {copy:7.2f} ms   (wall {ms['copy_1T_wall']:.2f})")
    print(f"tol=1e-12 cubic    1T cpu {ms['tol_1T_cpu']:7.2f} ms   {ms['tol_1T_cpu'] / copy:.2f}x copy (goal <= 2)")
    print(f"tol=1e-12 cubic    2T wall {ms['tol_2T_wall']:6.2f} ms   {ms['tol_2T_wall'] / copy:.2f}x copy (goal <= 1.2)")
    print(f"exact cubic        1T cpu {ms['exact_1T_cpu']:7.2f} ms   {ms['exact_1T_cpu'] / copy:.2f}x copy")
    if args.base:
        print(f"before: tol 1T cpu {ms['before_tol_1T_cpu']:.2f} ms ({ms['before_tol_1T_cpu'] / copy:.2f}x copy), "
              f"2T wall {ms['before_tol_2T_wall']:.2f} ms ({ms['before_tol_2T_wall'] / copy:.2f}x copy)")


if __name__ == "__main__":
    main()
