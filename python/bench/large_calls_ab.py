"""Large calls (issue 50: unchanged or faster by the small-call changes):
this build against another build of splinelab (A/B), default threads,
wall clock, one process, alternated (which goes first alternates), the
minimum of ROUNDS rounds per side (not run by CI):

    # a copy of the other build's package, renamed so both import at once:
    cp -r /path/to/other/python/splinelab /tmp/ab/splinelab_base
    .venv/bin/python python/bench/large_calls_ab.py --base /tmp/ab [--rounds 7] [CASE ...]

Cases: spline_filter 1024^2 cubic, spline_filter1d of 10^6 samples, zoom
512^2 by 2, shift, rotate by 30 degrees and affine_transform of 512^2
(cubic), map_coordinates at 10^5 random points on 512^2 (cubic and
linear) and at 100 points of a 4096^2 float32 image (the local route).
One line per case: base and our times in ms and their ratio.
"""

import math
import time

import numpy as np

from ab_builds import parse_ab


def cases():
    rng = np.random.default_rng(0)
    x, x1k, line = rng.normal(size=(512, 512)), rng.normal(size=(1024, 1024)), rng.normal(size=10**6)
    pts, few = rng.uniform(0, 511, (2, 10**5)), rng.uniform(0, 4095, (2, 100))
    big = rng.normal(size=(4096, 4096)).astype(np.float32)
    m = np.array([[0.9, 0.2], [-0.2, 0.9]])
    return {
        "spline_filter_1024": lambda f: f.spline_filter(x1k, 3),
        "spline_filter1d_1e6": lambda f: f.spline_filter1d(line, 3),
        "zoom_512": lambda f: f.zoom(x, 2, order=3),
        "shift_512": lambda f: f.shift(x, 0.3, order=3),
        "rotate_512": lambda f: f.rotate(x, 30, order=3),
        "affine_512": lambda f: f.affine_transform(x, m, order=3),
        "map_coordinates_1e5_cubic": lambda f: f.map_coordinates(x, pts, order=3),
        "map_coordinates_1e5_linear": lambda f: f.map_coordinates(x, pts, order=1),
        "map_coordinates_100_of_4096_local": lambda f: f.map_coordinates(big, few, order=3),
    }


def main():
    args, ours, base = parse_ab()
    libs = {"ours": ours, "base": base}
    for name, call in cases().items():
        if args.cases and name not in args.cases:
            continue
        best = {k: math.inf for k in libs}
        for lib in libs.values():
            call(lib)
        for r in range(args.rounds):
            for k in (("ours", "base") if r % 2 == 0 else ("base", "ours")):
                t = time.perf_counter()
                call(libs[k])
                best[k] = min(best[k], time.perf_counter() - t)
        print(f"{name:<36} base {best['base'] * 1e3:8.2f} ms  ours {best['ours'] * 1e3:8.2f} ms  "
              f"ours/base {best['ours'] / best['base']:.2f}", flush=True)


if __name__ == "__main__":
    main()
