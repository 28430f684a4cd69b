"""N-D prefilter speed of this build against another build of splinelab
(A/B), one process, CPU time (time.process_time), alternated (base, ours,
base, ours, ...), the minimum of ROUNDS rounds per side, next to a plain
copy of the same bytes (np.copyto, the memory wall); also checks that both
give the same values, bit for bit (not run by CI):

    # a copy of the other build's package, renamed so both import at once:
    cp -r /path/to/other/python/splinelab /tmp/ab/splinelab_base
    .venv/bin/python python/bench/nd_prefilter_ab.py --base /tmp/ab [--rounds 7] [--threads 1] [CASE ...]

Cases: spline_filter of 4096^2 and 256^3 (cubic, quintic, float32 cubic)
and spline_filter1d of 4096^2 along each axis (cubic), written into a
preallocated output. One line per case: base and our times in ms, their
ratio, ours over the copy, and whether the outputs are identical. With
--threads 2 the CPU time adds both threads: quote wall-clock figures from
benches/peers/python_prefilter.py instead.
"""

import argparse
import importlib
import sys

import numpy as np
from evaluation_ab import cpu_time


def cases(threads):
    rng = np.random.default_rng(0)
    x2 = rng.uniform(-1, 1, (4096, 4096))
    x3 = rng.uniform(-1, 1, (256, 256, 256))
    out = {}
    for name, x in (("2d", x2), ("3d", x3)):
        for d in (3, 5):
            out[f"{name}_order{d}"] = (x, lambda f, a, o, d=d: f.spline_filter(a, d, output=o, threads=threads))
        out[f"{name}_order3_f32"] = (x.astype(np.float32),
                                     lambda f, a, o: f.spline_filter(a, 3, output=o, threads=threads))
    for axis in (0, 1):
        out[f"2d_axis{axis}_order3"] = (x2, lambda f, a, o, ax=axis: f.spline_filter1d(a, 3, axis=ax, output=o,
                                                                                         threads=threads))
    return out


def ab_setup():
    """The command line shared by the A/B benches (``--base``, ``--name``,
    ``--threads``, ``--rounds``, cases) and both builds: ``(args, ours, base)``."""
    p = argparse.ArgumentParser()
    p.add_argument("--base", required=True, help="folder holding the other build (package --name)")
    p.add_argument("--name", default="splinelab_base")
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--rounds", type=int, default=7)
    p.add_argument("cases", nargs="*")
    args = p.parse_args()
    sys.path.insert(0, args.base)
    import splinelab

    return args, splinelab, importlib.import_module(args.name)


def main():
    args, splinelab, splinelab_base = ab_setup()
    table = cases(args.threads)
    for name in args.cases or list(table):
        data, call = table[name]
        ob, oo = np.empty_like(data), np.empty_like(data)
        call(splinelab_base, data, ob)
        call(splinelab, data, oo)
        same = np.array_equal(ob, oo)
        tb, to, tc = [], [], []
        for _ in range(args.rounds):
            tb.append(cpu_time(lambda: call(splinelab_base, data, ob)))
            to.append(cpu_time(lambda: call(splinelab, data, oo)))
            tc.append(cpu_time(lambda: np.copyto(oo, data)))
            call(splinelab, data, oo)
        print(f"{name}: base {min(tb) * 1e3:.1f} ms, ours {min(to) * 1e3:.1f} ms, x{min(tb) / min(to):.2f}, "
              f"copy {min(tc) * 1e3:.1f} ms, ours/copy {min(to) / min(tc):.2f}, identical={same}", flush=True)


if __name__ == "__main__":
    main()
