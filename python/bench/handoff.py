"""Whether a threads=2 call really runs on two cores right after Python
has kept a core busy (not run by CI): before each call the calling thread
spins for SPIN ms (as scipy does between two of our calls in the other
benchmarks), then map_coordinates at 10**6 random points on a 1024^2
cubic spline (prefilter=False) runs with threads=1 and threads=2:

    .venv/bin/python python/bench/handoff.py [--rounds 15] [--spin 80]

One JSON line per thread count: wall and CPU time (process_time) of each
call, min and median. Two workers on two cores give CPU time about twice
the wall time; two workers sharing one core (the woken worker left on its
waker's CPU) give CPU time equal to the wall time. Meaningful on a quiet
machine only (another process on the second core looks the same).
"""

import argparse
import json
import time

import numpy as np

import splinelab


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rounds", type=int, default=15)
    p.add_argument("--spin", type=float, default=80.0)
    args = p.parse_args()
    rng = np.random.default_rng(0)
    c = rng.uniform(-1, 1, (1024, 1024))
    pts = np.stack([rng.uniform(0, n - 1, 10**6) for n in c.shape])
    for threads in (1, 2):
        call = lambda: splinelab.map_coordinates(c, pts, order=3, prefilter=False, threads=threads)  # noqa: E731
        call()
        walls, cpus = [], []
        for _ in range(args.rounds):
            t = time.perf_counter()
            while time.perf_counter() - t < args.spin / 1e3:
                pass
            w, p0 = time.perf_counter(), time.process_time()
            call()
            walls.append(time.perf_counter() - w)
            cpus.append(time.process_time() - p0)
        ms = lambda v: round(v * 1e3, 2)  # noqa: E731
        print(json.dumps({"threads": threads, "wall_min_ms": ms(min(walls)),
                          "wall_median_ms": ms(sorted(walls)[len(walls) // 2]),
                          "cpu_over_wall_median": round(sorted(c / w for c, w in zip(cpus, walls))[len(walls) // 2], 2),
                          "wall_ms": [ms(w) for w in walls]}), flush=True)


if __name__ == "__main__":
    main()
