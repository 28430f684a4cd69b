"""One long line under tol= (spline_filter1d's certified blocks) in this
build against another build of splinelab (A/B), one process, CPU time
(time.process_time) on one thread and wall time on two, alternated (base,
ours, base, ours, ...), the minimum of ROUNDS rounds per side, beside a
plain copy of the same bytes (np.copyto); also the largest difference
between the two builds' outputs (not run by CI):

    cp -r /path/to/other/python/splinelab /tmp/ab/splinelab_base
    .venv/bin/python python/bench/prefilter_ab.py --base /tmp/ab [--rounds 7] [CASE ...]

Cases: 1e6 and 1e7 samples, degrees 3 and 5, float64 (tol=1e-12) and
float32 (tol=1e-6), and the exact filter of 1e6 and 1e7 cubic for scale.
"""

import time

import numpy as np

from ab_builds import parse_ab


def cases():
    rng = np.random.default_rng(0)
    x = rng.uniform(-1, 1, 10**7)
    out = {}
    for n in (10**6, 10**7):
        xs = x[:n].copy()
        e = len(str(n)) - 1
        out[f"1e{e}_d3_exact"] = (xs, lambda f, a, o, t: f.spline_filter1d(a, 3, output=o, threads=t))
        for d in (3, 5):
            out[f"1e{e}_d{d}_tol"] = (xs, lambda f, a, o, t, d=d: f.spline_filter1d(a, d, output=o, threads=t, tol=1e-12))
        x32 = xs.astype(np.float32)
        out[f"1e{e}_d3_tol_f32"] = (x32, lambda f, a, o, t: f.spline_filter1d(a, 3, output=o, threads=t, tol=1e-6))
    return out


def timed(fn, clock, reps=3):
    fn()
    best = float("inf")
    for _ in range(reps):
        t0 = clock()
        fn()
        best = min(best, clock() - t0)
    return best


def main():
    args, splinelab, splinelab_base = parse_ab()

    table = cases()
    for name in args.cases or table:
        x, run = table[name]
        o = np.empty_like(x)
        got = {}
        for side, mod in (("base", splinelab_base), ("ours", splinelab)):
            run(mod, x, o, 1)
            got[side] = o.copy()
        diff = float(np.abs(got["base"].astype(np.float64) - got["ours"]).max())
        t = {k: [] for k in ("base1", "ours1", "base2", "ours2", "copy")}
        for _ in range(args.rounds):
            for side, mod in (("base", splinelab_base), ("ours", splinelab)):
                t[side + "1"].append(timed(lambda: run(mod, x, o, 1), time.process_time))
                t[side + "2"].append(timed(lambda: run(mod, x, o, 2), time.perf_counter))
            t["copy"].append(timed(lambda: np.copyto(o, x), time.process_time))
        m = {k: min(v) * 1e3 for k, v in t.items()}
        print(f"{name:18s} 1 thread cpu: base {m['base1']:7.3f} ours {m['ours1']:7.3f} ms "
              f"({m['base1'] / m['ours1']:.2f}x; ours {m['ours1'] / m['copy']:.2f}x copy {m['copy']:.3f})  "
              f"2 threads wall: base {m['base2']:7.3f} ours {m['ours2']:7.3f} ({m['ours2'] / m['copy']:.2f}x copy)  "
              f"max diff {diff:.2e}", flush=True)


if __name__ == "__main__":
    main()
