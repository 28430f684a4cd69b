"""map_coordinates at 10**6 random points against scipy 1.17.1 (issue 26's
evaluation figure), one process, A/B alternated (scipy, ours, scipy, ours,
...), the minimum of ROUNDS rounds per side (not run by CI):

    .venv/bin/python python/bench/map_coordinates.py [--rounds 5] [--threads 1 2]

Per case (1024^2 cubic and quintic, 128^3 cubic, float64) and thread count,
one JSON object: "full_ratio" with the prefilter of the array on both
sides (prefilter=True, scipy's default), "eval_ratio" for the evaluation
alone (prefilter=False on both sides, the same coefficients), the times
behind them in seconds, and, for more than one thread count, "eval_speedup"
(the evaluation's time on the first thread count over this one: the serial
fraction). scipy is single-threaded.
"""

import argparse
import json
import time

import numpy as np
from scipy import ndimage

import splinelab


def timed(fn):
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def alternated(a, b, rounds):
    """The minimum times of ``a`` and ``b`` over ``rounds`` alternated rounds."""
    ta, tb = [], []
    for _ in range(rounds):
        ta.append(timed(a))
        tb.append(timed(b))
    return min(ta), min(tb)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    args = p.parse_args()
    rng = np.random.default_rng(0)
    for shape, order in [((1024, 1024), 3), ((1024, 1024), 5), ((128, 128, 128), 3)]:
        a = rng.uniform(-1, 1, shape)
        pts = np.stack([rng.uniform(0, n - 1, 10**6) for n in shape])
        c = ndimage.spline_filter(a, order=order, mode="mirror")
        first_eval = None
        for threads in args.threads:
            s_full, o_full = alternated(
                lambda: ndimage.map_coordinates(a, pts, order=order),
                lambda: splinelab.map_coordinates(a, pts, order=order, threads=threads), args.rounds)
            s_eval, o_eval = alternated(
                lambda: ndimage.map_coordinates(c, pts, order=order, prefilter=False),
                lambda: splinelab.map_coordinates(c, pts, order=order, prefilter=False, threads=threads),
                args.rounds)
            first_eval = first_eval or o_eval
            row = {"case": f"{'x'.join(map(str, shape))}_order{order}", "threads": threads,
                   "scipy_full_s": round(s_full, 4), "ours_full_s": round(o_full, 4),
                   "full_ratio": round(s_full / o_full, 2),
                   "scipy_eval_s": round(s_eval, 4), "ours_eval_s": round(o_eval, 4),
                   "eval_ratio": round(s_eval / o_eval, 2)}
            if len(args.threads) > 1:
                row["eval_speedup"] = round(first_eval / o_eval, 2)
            print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
