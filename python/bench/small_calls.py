"""Small calls (issue 50): splinelab against scipy.ndimage on the arrays that
loops call by the thousand, where a fixed cost per call decides (not run by
CI):

    .venv/bin/python python/bench/small_calls.py [--quick] [--rounds 7] [--threads both|default|1]
        [--only REGEX] [--json PATH]

The eight functions at 8², 16², 32², 64², 128², 16³ and 32³ (float64 and
float32 normal noise), orders 0, 1, 3 and 5, their default modes;
map_coordinates at 1, 25, 64 and N/4 random points inside the grid (N the
number of samples); spline_filter1d along the last axis; affine_transform
with a small rotation and an offset, rotate by 30 degrees (default axes
and reshape), shift by 0.3 on every axis, zoom by 2, geometric_transform
with a Python mapping (a shift by 0.3). Also the calls of issue 50's own
table (25 cubic points on 43², reproject's call). One process; each case
times scipy and splinelab alternately (which goes first alternates too),
each a batch of calls lasting about 2 ms, and keeps the minimum per call
over ``--rounds`` rounds (at least 7 for the figures). splinelab runs with
its default threads and with ``threads=1`` (``--threads``); scipy has one.

Printed: one line per case (scipy µs, splinelab µs, their ratio), then the
largest ratio per function and size, the count of cases above 1.0 and 1.05,
and the fixed cost of a call (one point on 8², order 1, float64) beside
scipy's. ``small_calls/before.txt`` and ``.json``: the full run before issue
50's changes (2-core machine, shared with builds); ``after.*`` the same
after them. ``--quick``: 8², 16², 32² and 16³, orders 1 and 3, float64 only
(a minute). ``--json PATH`` writes every case as a record.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import platform
import re
import subprocess
import sys
import time

import numpy as np
import scipy
import scipy.ndimage as ndi

import splinelab

SIZES = [(8, 8), (16, 16), (32, 32), (64, 64), (128, 128), (16, 16, 16), (32, 32, 32)]
QUICK_SIZES = [(8, 8), (16, 16), (32, 32), (16, 16, 16)]
ORDERS = [0, 1, 3, 5]
QUICK_ORDERS = [1, 3]
DTYPES = [np.float64, np.float32]
FUNCS = ["spline_filter1d", "spline_filter", "map_coordinates", "affine_transform", "shift", "zoom", "rotate",
         "geometric_transform"]


def _rotation(ndim, angle=0.3):
    m = np.eye(ndim)
    c, s = math.cos(angle), math.sin(angle)
    m[:2, :2] = [[c, s], [-s, c]]
    return m


def cases(sizes, orders, dtypes, funcs):
    """``(name, shape, points, order, dtype, call)``: ``call(lib, **kw)``
    runs the case on ``lib`` (scipy.ndimage or splinelab)."""
    rng = np.random.default_rng(0)
    out = []
    for shape in sizes:
        n = math.prod(shape)
        for dtype in dtypes:
            x = rng.normal(size=shape).astype(dtype)
            for order in orders:
                def add(name, call, points=None, x=x, order=order):
                    if name in funcs:
                        out.append((name, shape, points, order, np.dtype(dtype).name, call))

                add("spline_filter1d", lambda f, x=x, order=order, **k: f.spline_filter1d(x, order, axis=-1,
                                                                                           output=x.dtype, **k))
                if order >= 2:  # scipy's spline_filter refuses orders 0 and 1
                    add("spline_filter", lambda f, x=x, order=order, **k: f.spline_filter(x, order, output=x.dtype,
                                                                                           **k))
                for k in sorted({1, 25, 64, n // 4}):
                    pts = np.stack([rng.uniform(0, m - 1, k) for m in shape])
                    add("map_coordinates", lambda f, x=x, order=order, pts=pts, **kw: f.map_coordinates(
                        x, pts, order=order, **kw), points=k)
                mat, off = _rotation(len(shape)), np.full(len(shape), 0.7)
                add("affine_transform", lambda f, x=x, order=order, mat=mat, off=off, **k: f.affine_transform(
                    x, mat, off, order=order, **k))
                add("shift", lambda f, x=x, order=order, **k: f.shift(x, 0.3, order=order, **k))
                add("zoom", lambda f, x=x, order=order, **k: f.zoom(x, 2, order=order, **k))
                add("rotate", lambda f, x=x, order=order, **k: f.rotate(x, 30, order=order, **k))

                def mapping(o):
                    return tuple(c - 0.3 for c in o)

                add("geometric_transform", lambda f, x=x, order=order, **k: f.geometric_transform(
                    x, mapping, order=order, **k))
    return out


def issue_cases():
    """The calls of issue 50's table (float64, cubic, default threads)."""
    rng = np.random.default_rng(1)
    out = []
    for k, n in ((64, 16), (25, 43)):
        x = rng.normal(size=(n, n))
        pts = np.stack([rng.uniform(0, n - 1, k) for _ in range(2)])
        out.append(("map_coordinates", (n, n), k, 3, "float64",
                    lambda f, x=x, pts=pts, **kw: f.map_coordinates(x, pts, order=3, **kw)))
    x16, x32 = rng.normal(size=(16, 16)), rng.normal(size=(32, 32, 32))
    out.append(("shift", (16, 16), None, 1, "float64", lambda f, **k: f.shift(x16, 0.3, order=1, **k)))
    out.append(("rotate", (16, 16), None, 3, "float64", lambda f, **k: f.rotate(x16, 30, order=3, **k)))
    out.append(("rotate", (32, 32, 32), None, 3, "float64",
                lambda f, **k: f.rotate(x32, 30, axes=(0, 1), order=3, **k)))
    return out


#: Each timed batch lasts about this long (seconds).
BATCH = 2e-3


def _batch(call, reps):
    t = time.perf_counter()
    for _ in range(reps):
        call()
    return (time.perf_counter() - t) / reps


def _reps(call):
    """Calls per batch: about :data:`BATCH` seconds (at least one)."""
    t = _batch(call, 1)
    return max(1, min(10_000, int(BATCH / max(t, 1e-7))))


def measure(call, threads, rounds):
    """Minimum seconds per call over ``rounds`` alternated rounds: scipy's,
    splinelab's (``threads``: None, the default, or a count)."""
    kw = {} if threads is None else {"threads": threads}
    ours = lambda: call(splinelab, **kw)  # noqa: E731
    theirs = lambda: call(ndi)  # noqa: E731
    ours(), theirs()  # warm: pools, caches
    reps = (_reps(theirs), _reps(ours))
    best = [math.inf, math.inf]
    for r in range(rounds):
        order = (0, 1) if r % 2 == 0 else (1, 0)
        for i in order:
            best[i] = min(best[i], _batch((theirs, ours)[i], reps[i]))
    return best


def _shape(shape):
    return "x".join(map(str, shape))


def run(case_list, thread_settings, rounds, only, quiet=False):
    records = []
    for name, shape, points, order, dtype, call in case_list:
        label = f"{name} {_shape(shape)}" + (f" k={points}" if points is not None else "")
        if only and not re.search(only, label):
            continue
        for threads in thread_settings:
            theirs, ours = measure(call, threads, rounds)
            rec = dict(function=name, shape=list(shape), points=points, order=order, dtype=dtype,
                       threads="default" if threads is None else threads, scipy_us=theirs * 1e6,
                       splinelab_us=ours * 1e6, ratio=ours / theirs)
            records.append(rec)
            if not quiet:
                print(f"{label:<34} order {order} {dtype:<7} threads {rec['threads']!s:<7} "
                      f"scipy {rec['scipy_us']:10.1f} us  splinelab {rec['splinelab_us']:10.1f} us  "
                      f"ratio {rec['ratio']:6.2f}", flush=True)
    return records


def summary(records):
    print("\nlargest ratio (splinelab / scipy) per function and size, over orders, dtypes, points and threads:")
    shapes = sorted({tuple(r["shape"]) for r in records}, key=lambda s: (len(s), s))
    names = [f for f in FUNCS if any(r["function"] == f for r in records)]
    print(f"{'':<20}" + "".join(f"{_shape(s):>10}" for s in shapes))
    for f in names:
        row = []
        for s in shapes:
            rs = [r["ratio"] for r in records if r["function"] == f and tuple(r["shape"]) == s]
            row.append(f"{max(rs):10.2f}" if rs else f"{'':>10}")
        print(f"{f:<20}" + "".join(row))
    above = [r for r in records if r["ratio"] > 1.0]
    above5 = [r for r in records if r["ratio"] > 1.05]
    print(f"\n{len(records)} cases: {len(above)} above 1.0, {len(above5)} above 1.05; "
          f"median ratio {np.median([r['ratio'] for r in records]):.2f}, max {max(r['ratio'] for r in records):.2f}")


def fixed_cost(rounds):
    """One point on 8², order 1, float64: the fixed cost of a call."""
    x = np.random.default_rng(2).normal(size=(8, 8))
    pts = np.array([[3.3], [4.6]])
    call = lambda f, **k: f.map_coordinates(x, pts, order=1, **k)  # noqa: E731
    out = {}
    for threads in (None, 1):
        theirs, ours = measure(call, threads, max(rounds, 15))
        key = "default" if threads is None else "1"
        out[key] = dict(scipy_us=theirs * 1e6, splinelab_us=ours * 1e6, excess_us=(ours - theirs) * 1e6)
        print(f"fixed cost (map_coordinates, 1 point on 8x8, order 1, float64, threads {key}): scipy "
              f"{theirs * 1e6:.1f} us, splinelab {ours * 1e6:.1f} us ({(ours - theirs) * 1e6:+.1f} us)")
    return out


def provenance(argv, load_before):
    """What the report states beside the figures (it does not run Python):
    the command, the date (UTC), the commit (``+dirty`` with uncommitted
    changes), the machine and its load average before and after the run."""
    def git(*args):
        try:
            return subprocess.run(["git", *args], capture_output=True, text=True, check=True).stdout.strip()
        except (OSError, subprocess.CalledProcessError):
            return ""
    commit = git("rev-parse", "--short", "HEAD") or "unknown"
    if git("status", "--porcelain", "--untracked-files=no"):
        commit += "+dirty"
    return dict(command=" ".join([".venv/bin/python", "python/bench/small_calls.py", *argv]),
                date=datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%MZ"), commit=commit,
                machine=f"{platform.machine()}, {os.cpu_count()} cores, {platform.system()}",
                load_before=[round(x, 2) for x in load_before], load_after=[round(x, 2) for x in os.getloadavg()])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="8², 16², 32², 16³; orders 1, 3; float64")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--threads", choices=("both", "default", "1"), default="both")
    ap.add_argument("--only", help="a regular expression the case's label must match ('map_coordinates 8x8')")
    ap.add_argument("--json", help="write every case to this file")
    args = ap.parse_args(argv)
    load_before = os.getloadavg()
    threads = {"both": [None, 1], "default": [None], "1": [1]}[args.threads]
    sizes, orders, dtypes = (QUICK_SIZES, QUICK_ORDERS, [np.float64]) if args.quick else (SIZES, ORDERS, DTYPES)
    print(f"splinelab {splinelab.__version__}, scipy {scipy.__version__}, numpy {np.__version__}, "
          f"python {platform.python_version()}, {args.rounds} rounds")
    fixed = fixed_cost(args.rounds)
    print("\nissue 50's table:")
    issue = run(issue_cases(), [None], args.rounds, None)
    print()
    records = run(cases(sizes, orders, dtypes, FUNCS), threads, args.rounds, args.only)
    if records:
        summary(records)
    if args.json:
        argv = sys.argv[1:] if argv is None else list(argv)
        prov = provenance(argv, load_before)  # before the file is opened: a tracked one would read as a change
        with open(args.json, "w") as fh:
            json.dump(dict(argv=argv, provenance=prov, scipy=scipy.__version__,
                           splinelab=splinelab.__version__, rounds=args.rounds, fixed_cost=fixed, issue_table=issue,
                           cases=records), fh, indent=1)


if __name__ == "__main__":
    main()
