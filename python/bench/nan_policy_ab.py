"""nan_policy's cost where no sample is missing: this build's 'propagate'
(the default) and 'local' against another build (the one before
nan_policy) on the same calls, one process, CPU time, alternated (base,
propagate, local, base, ...), the minimum of ROUNDS rounds; 'local' is
compared with the base's call at the same ``tol`` (its default 1e-12, the
truncated route), 'propagate' with the base's default call. Also checks
that the values are the same bits (not run by CI):

    # a copy of the other build's package, renamed so both import at once:
    cp -r /path/to/other/python/splinelab /tmp/ab/splinelab_base
    .venv/bin/python python/bench/nan_policy_ab.py --base /tmp/ab [--rounds 7] [--threads 1] [CASE ...]

One line per case: base / propagate (ratio base/ours: > 1 is faster) and
base at tol / local.
"""

import numpy as np
from evaluation_ab import cpu_time
from nd_prefilter_ab import ab_setup

TOL = 1e-12


def cases(threads):
    rng = np.random.default_rng(0)
    x2 = rng.uniform(-1, 1, (2048, 2048))
    s2 = rng.uniform(-1, 1, (512, 512))
    x3 = rng.uniform(-1, 1, (96, 96, 96))
    line = rng.uniform(-1, 1, 2_000_000)
    pts = rng.uniform(0, 511, (2, 1_000_000))
    kw = dict(threads=threads)
    return {
        "spline_filter_2048sq_order3": lambda f, **k: f.spline_filter(x2, 3, **kw, **k),
        "spline_filter_96cube_order5_f32": lambda f, **k: f.spline_filter(x3.astype(np.float32), 5,
                                                                          output=np.float32, **kw, **k),
        "spline_filter1d_line_2e6_order3": lambda f, **k: f.spline_filter1d(line, 3, **kw, **k),
        "map_coordinates_512sq_1e6pts_order3": lambda f, **k: f.map_coordinates(s2, pts, order=3, **kw, **k),
        "zoom_512sq_x2_order3": lambda f, **k: f.zoom(s2, 2, order=3, **kw, **k),
        "zoom_512sq_x2_order1": lambda f, **k: f.zoom(s2, 2, order=1, **kw, **k),
        "rotate_512sq_order3": lambda f, **k: f.rotate(s2, 30, order=3, **kw, **k),
        "shift_96cube_nearest_order3": lambda f, **k: f.shift(x3, 0.3, order=3, mode="nearest", **kw, **k),
    }


def main():
    args, splinelab, base = ab_setup()
    table = cases(args.threads)
    for name in args.cases or list(table):
        call = table[name]
        runs = {
            "base": lambda: call(base),
            "propagate": lambda: call(splinelab),
            "base_tol": lambda: call(base, tol=TOL),
            "local": lambda: call(splinelab, nan_policy="local", tol=TOL),
        }
        same = np.array_equal(runs["base"](), runs["propagate"]()) and np.array_equal(runs["base_tol"](),
                                                                                        runs["local"]())
        times = {k: [] for k in runs}
        for _ in range(args.rounds):
            for k, run in runs.items():
                times[k].append(cpu_time(run))
        t = {k: min(v) * 1e3 for k, v in times.items()}
        print(f"{name}: base {t['base']:.1f} ms, propagate {t['propagate']:.1f} ms "
              f"(x{t['base'] / t['propagate']:.3f}); base tol {t['base_tol']:.1f} ms, local {t['local']:.1f} ms "
              f"(x{t['base_tol'] / t['local']:.3f}); identical={same}", flush=True)


if __name__ == "__main__":
    main()
