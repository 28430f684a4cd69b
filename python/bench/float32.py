"""float32 data (issue 42): speed and peak memory of splinelab's default
route (float64 arithmetic, float32 results rounded once) against scipy on
the same calls, and of the ``compute="float32"`` opt-in against another
build's float32 route (not run by CI):

    # speed: one process, alternated, the minimum of ROUNDS wall-clock times
    .venv/bin/python python/bench/float32.py speed [--rounds 7] [--size 2048] [CASE ...]
    # the opt-in against the build before (its float32 route computed in float32):
    cp -r /path/to/other/python/splinelab /tmp/ab/splinelab_base
    .venv/bin/python python/bench/float32.py speed --base /tmp/ab [--threads N] [--clock cpu] [CASE ...]
    # peak memory: each call in a child process, VmHWM above the resident
    # size before the call (/proc/self/clear_refs resets the mark)
    .venv/bin/python python/bench/float32.py memory [--size 4096] [CASE ...]

Cases: map_coordinates at 10^6 random points, zoom by 2, shift, rotate by
30 degrees, affine_transform, spline_filter (scipy's default float64
output, and output=float32) and spline_filter1d, all cubic on a float32
image of SIZE^2 normal noise (map_coordinates: mode='constant', the
others their defaults). Speed columns: scipy, splinelab with threads=1
and with every core (the default), their ratios, splinelab's
compute="float32" opt-in on every core and the default's time over it;
with --base, the base
build's default, splinelab's compute="float32" and their ratio. Memory
columns: the input's and the result's size, scipy's and splinelab's peak
above the resident size before the call (so the result included).
"""

import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

from _peak import reset_peak, rss_kib


def cases(size):
    rng = np.random.default_rng(0)
    img = rng.normal(size=(size, size)).astype(np.float32)
    pts = np.stack([rng.uniform(0, size - 1, 10**6) for _ in range(2)])
    mat = np.array([[0.9, 0.1], [-0.1, 0.95]])
    return img, {
        "map_coordinates": lambda f, a, **k: f.map_coordinates(a, pts, order=3, **k),
        "zoom": lambda f, a, **k: f.zoom(a, 2, order=3, **k),
        "shift": lambda f, a, **k: f.shift(a, (0.3, -1.7), order=3, **k),
        "rotate": lambda f, a, **k: f.rotate(a, 30, order=3, **k),
        "affine_transform": lambda f, a, **k: f.affine_transform(a, mat, offset=(3.0, -2.0), order=3, **k),
        "spline_filter": lambda f, a, **k: f.spline_filter(a, order=3, **k),
        "spline_filter_f32": lambda f, a, **k: f.spline_filter(a, order=3, output=np.float32, **k),
        "spline_filter1d": lambda f, a, **k: f.spline_filter1d(a, order=3, axis=0, **k),
    }


CLOCKS = {"wall": time.perf_counter, "cpu": time.process_time}
clock = CLOCKS["wall"]


def best(fn, rounds_out, key):
    t = clock()
    fn()
    rounds_out.setdefault(key, []).append(clock() - t)


def speed(args):
    global clock
    import scipy.ndimage as ndi

    import splinelab

    base = None
    if args.base:
        sys.path.insert(0, args.base)
        import splinelab_base as base
    # Both builds default to one thread per core; --threads N passes the same
    # threads=N to both (a loaded machine times one thread with less noise).
    threads = {} if args.threads is None else {"threads": args.threads}
    clock = CLOCKS[args.clock]
    img, all_cases = cases(args.size)
    names = args.cases or list(all_cases)
    print(f"float32 {args.size}^2, cubic, min of {args.rounds} alternated rounds ({args.clock} ms; "
          f"{os.cpu_count()} cores, threads={args.threads})")
    if base is None:
        print(f"{'case':<20}{'scipy':>9}{'sl 1 thr':>10}{'sl all':>9}{'scipy/1':>9}{'scipy/all':>10}"
              f"{'sl f32':>9}{'all/f32':>9}")
    else:
        print(f"{'case':<20}{'base f32':>10}{'compute=f32':>13}{'ratio':>8}")
    for name in names:
        call = all_cases[name]
        times = {}
        for _ in range(args.rounds):
            if base is None:
                best(lambda: call(ndi, img), times, "scipy")
                best(lambda: call(splinelab, img, threads=1), times, "one")
                best(lambda: call(splinelab, img), times, "all")
                best(lambda: call(splinelab, img, compute="float32"), times, "f32")
            else:
                best(lambda: call(base, img, **threads), times, "base")
                best(lambda: call(splinelab, img, compute="float32", **threads), times, "opt")
        m = {k: 1e3 * min(v) for k, v in times.items()}
        if base is None:
            print(f"{name:<20}{m['scipy']:>9.1f}{m['one']:>10.1f}{m['all']:>9.1f}"
                  f"{m['scipy'] / m['one']:>9.2f}{m['scipy'] / m['all']:>10.2f}"
                  f"{m['f32']:>9.1f}{m['all'] / m['f32']:>9.2f}")
        else:
            print(f"{name:<20}{m['base']:>10.1f}{m['opt']:>13.1f}{m['base'] / m['opt']:>8.2f}")


def child(lib, name, size):
    """One call in this (child) process: ``{peak, result}`` in bytes, the
    peak above the resident size just before the call."""
    if lib == "scipy":
        import scipy.ndimage as f
    else:
        import splinelab as f
    img, all_cases = cases(size)
    call = all_cases[name]
    small = img[:64, :64].copy()
    all_cases[name](f, small)  # imports, pools, caches
    before = reset_peak()
    out = call(f, img)
    peak = rss_kib("VmHWM")
    return {"peak": (peak - before) * 1024, "result": out.nbytes, "input": img.nbytes}


def memory(args):
    img_bytes = args.size * args.size * 4
    names = args.cases or list(cases(8)[1])
    print(f"float32 {args.size}^2 input ({img_bytes / 2**20:.0f} MiB), cubic; peak above the resident size "
          "before the call, result included (MiB)")
    print(f"{'case':<20}{'result':>8}{'scipy':>9}{'splinelab':>11}{'ratio':>8}")
    for name in names:
        got = {}
        for lib in ("scipy", "splinelab"):
            r = subprocess.run([sys.executable, __file__, "_child", lib, name, str(args.size)], capture_output=True,
                               text=True, check=True)
            got[lib] = json.loads(r.stdout)
        mib = {k: v["peak"] / 2**20 for k, v in got.items()}
        print(f"{name:<20}{got['scipy']['result'] / 2**20:>8.0f}{mib['scipy']:>9.1f}{mib['splinelab']:>11.1f}"
              f"{mib['splinelab'] / mib['scipy']:>8.2f}")


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "_child":
        print(json.dumps(child(sys.argv[2], sys.argv[3], int(sys.argv[4]))))
        return
    p = argparse.ArgumentParser()
    p.add_argument("what", choices=("speed", "memory"))
    p.add_argument("--rounds", type=int, default=7)
    p.add_argument("--size", type=int, default=None)
    p.add_argument("--base", default=None, help="folder holding the other build as splinelab_base")
    p.add_argument("--threads", type=int, default=None, help="with --base: threads=N for both builds")
    # cpu: the process' CPU time (all threads), less disturbed than wall time
    # by other jobs on a loaded machine; with --threads 1 it is the speed.
    p.add_argument("--clock", choices=tuple(CLOCKS), default="wall")
    p.add_argument("cases", nargs="*")
    args = p.parse_intermixed_args()
    if args.what == "speed":
        args.size = args.size or 2048
        speed(args)
    else:
        args.size = args.size or 4096
        memory(args)


if __name__ == "__main__":
    main()
