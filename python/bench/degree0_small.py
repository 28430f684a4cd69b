"""Issue 50's degree-0 kernel and few-point figures, scipy and splinelab
alternated in one process, CPU time (time.process_time) per call, the
minimum of ROUNDS rounds of loops of LOOP calls (not run by CI):

- affine_transform at order 0 (a rotation by 0.3 rad about the centre) on
  64^2 and 128^2: ns per output, threads=None and threads=1; the results are
  checked equal to scipy's bit for bit;
- map_coordinates of 64 points on 32^3 at orders 0 and 1 (the whole call:
  orders 0/1 copy the input into padded coefficients, scipy reads it).

    .venv/bin/python python/bench/degree0_small.py [--rounds 7] [--loop 300] [--base DIR]

--base: a folder holding another build importable as ``splinelab_base``
(as ``ab_builds.py``), timed alternated with this one ("before").
"""

import argparse
import os
import sys
import time

import numpy as np
import scipy.ndimage as ndi

import splinelab as sl


def per_call(fn, loop, rounds):
    fn()
    best = float("inf")
    for _ in range(rounds):
        t0 = time.process_time()
        for _ in range(loop):
            fn()
        best = min(best, (time.process_time() - t0) / loop)
    return best


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--rounds", type=int, default=7)
    p.add_argument("--loop", type=int, default=300)
    p.add_argument("--base", help="folder holding the other build as splinelab_base")
    args = p.parse_args()
    builds = {"splinelab": sl}
    if args.base:
        sys.path.insert(0, args.base)
        import splinelab_base

        builds = {"before": splinelab_base, "splinelab": sl}
    rng = np.random.default_rng(0)
    print(f"load {os.getloadavg()[0]:.2f} (cores {os.cpu_count()})")
    c, s = np.cos(0.3), np.sin(0.3)
    m = np.array([[c, -s], [s, c]])
    for n in (64, 128):
        a = rng.standard_normal((n, n))
        off = np.array([n / 2, n / 2]) - m @ np.array([n / 2, n / 2])
        assert np.array_equal(ndi.affine_transform(a, m, off, order=0), sl.affine_transform(a, m, off, order=0))
        for threads in (None, 1):
            ts = per_call(lambda: ndi.affine_transform(a, m, off, order=0), args.loop, args.rounds)
            line = f"affine order 0 {n}^2 threads={threads}: scipy {ts * 1e9 / n / n:5.1f} ns/output"
            for name, mod in builds.items():
                tl = per_call(lambda: mod.affine_transform(a, m, off, order=0, threads=threads), args.loop, args.rounds)
                line += f", {name} {tl * 1e9 / n / n:5.1f} ({tl / ts:.2f}x)"
            print(line)
    a = rng.standard_normal((32, 32, 32))
    q = rng.uniform(0, 31, (3, 64))
    for order in (0, 1):
        ts = per_call(lambda: ndi.map_coordinates(a, q, order=order), args.loop, args.rounds)
        for threads in (None, 1):
            line = f"map_coordinates 64 points on 32^3 order {order} threads={threads}: scipy {ts * 1e6:5.1f} us"
            for name, mod in builds.items():
                tl = per_call(lambda: mod.map_coordinates(a, q, order=order, threads=threads), args.loop, args.rounds)
                line += f", {name} {tl * 1e6:5.1f} us ({tl / ts:.2f}x)"
            print(line)


if __name__ == "__main__":
    main()
