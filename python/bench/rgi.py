"""RegularGridInterpolator against scipy's: time and peak memory (issue 49).

Each case runs in a child process (one library, one case), so the peak is
that call's alone: VmHWM above the resident size just before construction
(/proc/self/clear_refs resets the mark), against the values' bytes.

    .venv/bin/python python/bench/rgi.py                 # every case, both libraries
    .venv/bin/python python/bench/rgi.py --lib splinelab  # splinelab only
    .venv/bin/python python/bench/rgi.py --cases 300x300x40 --lib scipy

Cases (jittered spacing, standard normal values, cubic, construction plus
10^5 points inside the grid): 100x100x40 and 300x300x40 float64 (the issue's),
2000x2000 float64, 10000x10000 float32 (scipy #23783; scipy is not run on it:
its design matrix alone is 1.6e9 non-zeros). The accuracy column is the
largest distance from splinelab's exact spline at the points, relative to
max|values| (scipy's iterative gcrotmk solve stops at atol=1e-6).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time

import numpy as np

from _peak import reset_peak, rss_kib

CASES = {
    "100x100x40": ((100, 100, 40), "float64"),
    "300x300x40": ((300, 300, 40), "float64"),
    "2000x2000": ((2000, 2000), "float64"),
    "10000x10000": ((10000, 10000), "float32"),
}
SCIPY_SKIPS = {"10000x10000"}
POINTS = 100_000


def data(name):
    shape, dtype = CASES[name]
    rng = np.random.default_rng(7)
    grid = [np.cumsum(rng.uniform(0.5, 1.5, n)) for n in shape]
    values = rng.standard_normal(shape).astype(dtype)
    xi = np.column_stack([rng.uniform(g[0], g[-1], POINTS) for g in grid])
    return grid, values, xi


def child(lib, name):
    grid, values, xi = data(name)
    if lib == "scipy":
        from scipy.interpolate import RegularGridInterpolator
    else:
        from splinelab import RegularGridInterpolator
    before = reset_peak()
    t0 = time.perf_counter()
    f = RegularGridInterpolator(grid, values, method="cubic")
    t1 = time.perf_counter()
    out = f(xi)
    t2 = time.perf_counter()
    peak = rss_kib("VmHWM")
    np.save(f"/tmp/rgi_{lib}_{name}.npy", out)
    return {
        "lib": lib,
        "case": name,
        "build_s": t1 - t0,
        "eval_s": t2 - t1,
        "peak_bytes": (peak - before) * 1024,
        "values_bytes": values.nbytes,
    }


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cases", nargs="*", default=list(CASES))
    p.add_argument("--lib", choices=["both", "scipy", "splinelab"], default="both")
    p.add_argument("--json", help="write the rows here")
    p.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    a = p.parse_args()
    if a.child:
        print(json.dumps(child(*a.child)))
        return
    libs = ["splinelab", "scipy"] if a.lib == "both" else [a.lib]
    rows = []
    print(f"{'case':>12} {'lib':>9} {'build s':>9} {'1e5 pts s':>9} {'peak/values':>11} {'vs exact':>9}")
    for name in a.cases:
        for lib in libs:
            if lib == "scipy" and name in SCIPY_SKIPS:
                continue
            r = subprocess.run([sys.executable, __file__, "--child", lib, name],
                               capture_output=True, text=True)
            if r.returncode != 0:
                print(f"{name:>12} {lib:>9} failed: {r.stderr.strip().splitlines()[-1:]}")
                continue
            row = json.loads(r.stdout)
            ours = np.load(f"/tmp/rgi_splinelab_{name}.npy") if lib == "scipy" else None
            if ours is not None:
                _, values, _ = data(name)
                theirs = np.load(f"/tmp/rgi_scipy_{name}.npy")
                row["rel_dist_from_exact"] = float(np.abs(theirs - ours).max() / np.abs(values).max())
            rows.append(row)
            dist = row.get("rel_dist_from_exact")
            print(f"{name:>12} {lib:>9} {row['build_s']:9.3f} {row['eval_s']:9.3f} "
                  f"{row['peak_bytes'] / row['values_bytes']:11.2f} "
                  f"{'' if dist is None else f'{dist:9.1e}'}")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(rows, fh, indent=1)


if __name__ == "__main__":
    main()
