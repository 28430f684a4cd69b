"""Issue 18 overhead in CPU time, less sensitive to a loaded machine than wall
time (not run by CI):

    .venv/bin/python python/bench/cpu_overhead.py [--bin $CARGO_TARGET_DIR/release/engine_peer]

CPU time (user+sys of the whole process, all threads) per call: Python
spline_filter1d (into a reused output= and fresh) vs engine_peer filter1d
(CPU of reps=K+1 minus reps=1 runs, divided by K: start-up and data excluded)."""
import argparse
import json
import os
import pathlib
import resource
import subprocess
import sys
import time

import numpy as np

import splinelab

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "benches" / "peers"))
from scipy_ratio import data  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "engine_peer"))
BIN = ap.parse_args().bin


def child_cpu(args):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(args, env=dict(os.environ, RAYON_NUM_THREADS="1"), check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def py_cpu(f, k):
    f()
    t0 = time.process_time()
    for _ in range(k):
        f()
    return (time.process_time() - t0) / k


for n, k in ((1_000_000, 200), (10_000_000, 20)):
    s, buf = data(n), np.empty(n)
    rows = {"kernel": [], "into": [], "fresh": []}
    for _ in range(3):
        full = child_cpu([BIN, "filter1d", "3", str(n), str(k + 1)])
        rows["kernel"].append((full - child_cpu([BIN, "filter1d", "3", str(n), "1"])) / k)
        rows["into"].append(py_cpu(lambda: splinelab.spline_filter1d(s, 3, output=buf, threads=1), k))
        rows["fresh"].append(py_cpu(lambda: splinelab.spline_filter1d(s, 3, threads=1), k))
    m = {key: sorted(v)[1] for key, v in rows.items()}
    print(json.dumps(dict(n=n, cpu_s=m, into_vs_kernel=m["into"] / m["kernel"] - 1,
                          fresh_vs_kernel=m["fresh"] / m["kernel"] - 1)), flush=True)
