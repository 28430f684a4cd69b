"""map_coordinates at 10**6 random points, one thread, against scipy 1.17.1
(issue 26's evaluation figure): the minimum of 3 runs each, the prefilter of
the array included on both sides (prefilter=True, scipy's default). Then
the evaluation alone (prefilter=False) on one and two threads, min of 7:
the serial fraction of the evaluation.

    .venv/bin/python python/bench/map_coordinates.py
"""

import time

import numpy as np
from scipy import ndimage

import splinelab


def best(f, rounds=3):
    b = float("inf")
    for _ in range(rounds):
        t0 = time.perf_counter()
        f()
        b = min(b, time.perf_counter() - t0)
    return b


def main():
    rng = np.random.default_rng(0)
    for shape, order in [((1024, 1024), 3), ((1024, 1024), 5), ((128, 128, 128), 3)]:
        a = rng.uniform(-1, 1, shape)
        pts = np.stack([rng.uniform(0, n - 1, 10**6) for n in shape])
        s = best(lambda: ndimage.map_coordinates(a, pts, order=order))
        o = best(lambda: splinelab.map_coordinates(a, pts, order=order, threads=1))
        print(f"{shape} order {order}: scipy {s:.3f} s, ours {o:.3f} s, scipy/ours {s / o:.2f}", flush=True)
        c = splinelab.spline_filter(a, order=order)
        one, two = (
            best(lambda t=t: splinelab.map_coordinates(c, pts, order=order, prefilter=False, threads=t), 7)
            for t in (1, 2)
        )
        print(f"  evaluation only: 1 thread {one * 1e3:.1f} ms, 2 threads {two * 1e3:.1f} ms, "
              f"speed-up {one / two:.2f}", flush=True)


if __name__ == "__main__":
    main()
