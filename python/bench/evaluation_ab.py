"""Evaluation speed of this build against another build of splinelab (A/B),
one process, one thread, CPU time (time.process_time), alternated (base,
ours, base, ours, ...), the minimum of ROUNDS rounds per side; also checks
that both give the same values, bit for bit (not run by CI):

    # a copy of the other build's package, renamed so both import at once:
    cp -r /path/to/other/python/splinelab /tmp/ab/splinelab_base
    .venv/bin/python python/bench/evaluation_ab.py --base /tmp/ab [--rounds 7] [CASE ...]

Cases: rotate 2048^2 by 30 degrees cubic (float64, float32, and with
prefilter=False: the evaluation alone), rotate quintic mode nearest,
affine_transform 128^3 cubic, map_coordinates at 10^6 random points with
prefilter=False (1024^2 cubic and quintic, 128^3 cubic). One line per case:
base and our times in ms, their ratio, and whether the outputs are identical.
"""

import time

import numpy as np

from ab_builds import parse_ab


def cases():
    rng = np.random.default_rng(0)
    img = rng.uniform(-1, 1, (2048, 2048))
    vol = rng.uniform(-1, 1, (128, 128, 128))
    mat = np.array([[0.9, 0.1, 0.05], [-0.1, 0.95, 0.02], [0.03, -0.02, 1.05]])
    out = {
        "rotate_cubic": (img, lambda f, a: f.rotate(a, 30, order=3, threads=1)),
        "rotate_cubic_f32": (img.astype(np.float32), lambda f, a: f.rotate(a, 30, order=3, threads=1)),
        "rotate_cubic_eval": (img, lambda f, a: f.rotate(a, 30, order=3, prefilter=False, threads=1)),
        "rotate_quintic_nearest": (img, lambda f, a: f.rotate(a, 30, order=5, mode="nearest", threads=1)),
        "affine128_cubic": (vol, lambda f, a: f.affine_transform(a, mat, order=3, threads=1)),
    }
    for shape, order in [((1024, 1024), 3), ((1024, 1024), 5), ((128, 128, 128), 3)]:
        a = rng.uniform(-1, 1, shape)
        pts = np.stack([rng.uniform(0, n - 1, 10**6) for n in shape])
        name = f"map_coordinates_{'x'.join(map(str, shape))}_order{order}"
        out[name] = (a, lambda f, c, p=pts, o=order: f.map_coordinates(c, p, order=o, prefilter=False, threads=1))
    return out


def cpu_time(fn):
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def main():
    args, splinelab, splinelab_base = parse_ab()

    table = cases()
    for name in args.cases or list(table):
        data, call = table[name]
        same = np.array_equal(call(splinelab_base, data), call(splinelab, data))
        tb, to = [], []
        for _ in range(args.rounds):
            tb.append(cpu_time(lambda: call(splinelab_base, data)))
            to.append(cpu_time(lambda: call(splinelab, data)))
        print(f"{name}: base {min(tb) * 1e3:.1f} ms, ours {min(to) * 1e3:.1f} ms, "
              f"x{min(tb) / min(to):.2f}, identical={same}", flush=True)


if __name__ == "__main__":
    main()
