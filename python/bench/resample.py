"""Resampling speed against scipy.ndimage 1.17.1 (issue 27), one process,
A/B alternated, minimum of ROUNDS rounds per side (not run by CI):

    .venv/bin/python python/bench/resample.py [--rounds 5] [--threads 1 2] [--quick]

Cases: zoom 2048^2 x2 (cubic, quintic), rotate 2048^2 by 30 degrees
(cubic), affine_transform 128^3 (cubic), each in float64 and float32
(scipy computes float32 input in float64 and rounds; ours computes in
float32). Prints one JSON object per case and thread count:
{"case", "dtype", "threads", "scipy_s", "ours_s", "ratio"} (ratio =
scipy_s / ours_s; scipy is single-threaded). --quick: 1024^2 and 96^3.
"""

import argparse
import json
import time

import numpy as np
from scipy import ndimage

import splinelab


def cases(quick):
    n, m = (1024, 96) if quick else (2048, 128)
    rng = np.random.default_rng(0)
    img = rng.uniform(-1, 1, (n, n))
    vol = rng.uniform(-1, 1, (m, m, m))
    mat = np.array([[0.9, 0.1, 0.05], [-0.1, 0.95, 0.02], [0.03, -0.02, 1.05]])
    return [
        (f"zoom{n}x2_cubic", img, lambda f, a, **k: f.zoom(a, 2, order=3, **k)),
        (f"zoom{n}x2_quintic", img, lambda f, a, **k: f.zoom(a, 2, order=5, **k)),
        (f"rotate{n}_30deg_cubic", img, lambda f, a, **k: f.rotate(a, 30, order=3, **k)),
        (f"affine{m}^3_cubic", vol, lambda f, a, **k: f.affine_transform(a, mat, order=3, **k)),
    ]


def timed(fn):
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    p.add_argument("--quick", action="store_true")
    args = p.parse_args()
    for name, data, call in cases(args.quick):
        for dtype in (np.float64, np.float32):
            a = data.astype(dtype)
            ref = call(ndimage, a)
            for threads in args.threads:
                ours = call(splinelab, a, threads=threads)
                assert ours.dtype == ref.dtype and ours.shape == ref.shape
                s, o = [], []
                for _ in range(args.rounds):  # alternated: scipy, ours, scipy, ours, ...
                    s.append(timed(lambda: call(ndimage, a)))
                    o.append(timed(lambda: call(splinelab, a, threads=threads)))
                print(json.dumps({"case": name, "dtype": np.dtype(dtype).name, "threads": threads,
                                  "scipy_s": round(min(s), 4), "ours_s": round(min(o), 4),
                                  "ratio": round(min(s) / min(o), 2)}), flush=True)


if __name__ == "__main__":
    main()
