"""Downstream clients' own tests with splinelab swapped in for
scipy.ndimage's spline functions (python/tests/downstream/README.md).

Each selection of :data:`CLIENTS` runs twice in its own pytest process,
with ``--splinelab-swap=off`` (scipy) and ``on`` (splinelab), and the two
outcome sets are compared: every test must end the same way in both runs,
except the known differences of :mod:`known`, which must pass on scipy and
xfail (strictly) on splinelab. Prints the figures (tests, outcomes,
wall-clock and CPU seconds, and calls into the installed functions per
run) and exits 1 on any other difference, 0 otherwise.

    .venv/bin/python python/tests/downstream/run.py [--client NAME ...] [--json FILE]
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import resource
import subprocess
import sys
import sysconfig
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent

# Each client's own test modules that reach scipy.ndimage's interpolation,
# as shipped in its wheel (versions pinned in requirements.txt). Tests marked
# remote_data (network) are deselected for every client.
CLIENTS = {
    # scipy's own interpolation tests: the drop-in's reference suite
    # (ndimage's, and interpolate's RegularGridInterpolator / interpn).
    "scipy": ["scipy.ndimage.tests.test_interpolation", "scipy.ndimage.tests.test_splines",
              "scipy.interpolate.tests.test_rgi"],
    # reproject_interp -> reproject._array_utils.map_coordinates ->
    # scipy.ndimage.map_coordinates (cval=nan), dask-image's spline_filter.
    "reproject": ["reproject.interpolation.tests.test_core", "reproject.tests.test_array_utils"],
    # resample_from_to / resample_to_output / conform -> affine_transform.
    "nibabel": ["nibabel.tests.test_processing", "nibabel.cmdline.tests.test_conform"],
    # sunpy.image.transform.affine_transform(method="scipy") ->
    # scipy.ndimage.affine_transform; sunpy.image.resample -> map_coordinates.
    "sunpy": ["sunpy.image.tests.test_transform", "sunpy.image.tests.test_resample"],
}


def run_selection(modules, swap, workdir):
    """One pytest process over ``modules`` (its rootdir site-packages, so
    node ids read ``reproject/tests/...``); returns (outcomes, calls,
    seconds, cpu seconds, rc, log): wall-clock and the process's user +
    system CPU time (the steadier figure on a shared machine)."""
    outcomes = Path(workdir) / f"outcomes-{swap}.json"
    ini = Path(workdir) / "pytest.ini"
    ini.write_text("[pytest]\n")
    cmd = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "splinelab_swap",
           f"--splinelab-swap={swap}", f"--splinelab-outcomes={outcomes}", "-c", str(ini),
           f"--rootdir={sysconfig.get_paths()['purelib']}", "-m", "not remote_data", "-rfE", "--pyargs", *modules]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(HERE), os.environ.get("PYTHONPATH", "")]).rstrip(os.pathsep),
               MPLBACKEND="Agg")
    start, cpu = time.perf_counter(), _child_cpu()
    proc = subprocess.run(cmd, cwd=workdir, env=env, capture_output=True, text=True)
    seconds, cpu = time.perf_counter() - start, _child_cpu() - cpu
    if not outcomes.exists():
        sys.stdout.write(proc.stdout[-4000:] + proc.stderr[-4000:])
        raise SystemExit(f"pytest wrote no outcomes for {modules} (swap {swap}), rc {proc.returncode}")
    record = json.loads(outcomes.read_text())
    return record["outcomes"], record["calls"], seconds, cpu, proc.returncode, proc.stdout


def _child_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def compare(base, swapped, known):
    """The differences that are not known ones: (nodeid, scipy's, splinelab's)."""
    bad = []
    for nodeid in sorted(set(base) | set(swapped)):
        b, s = base.get(nodeid, "absent"), swapped.get(nodeid, "absent")
        if b == s:
            continue
        if nodeid in known and b == "passed" and s == "xfailed":
            continue
        bad.append((nodeid, b, s))
    return bad


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--client", action="append", choices=sorted(CLIENTS), help="run only these (repeatable)")
    parser.add_argument("--json", help="write the figures to this file")
    args = parser.parse_args(argv)
    sys.path.insert(0, str(HERE))
    from known import KNOWN

    figures, failed = {}, False
    for name in args.client or CLIENTS:
        runs, logs = {}, {}
        for swap in ("off", "on"):
            with tempfile.TemporaryDirectory() as workdir:
                outcomes, calls, seconds, cpu, rc, logs[swap] = run_selection(CLIENTS[name], swap, workdir)
            counts = collections.Counter(outcomes.values())
            runs[swap] = {"tests": len(outcomes), "seconds": round(seconds, 1), "cpu_seconds": round(cpu, 1), "rc": rc,
                          **dict(sorted(counts.items())), "calls": {k: v for k, v in calls.items() if v},
                          "outcomes": outcomes}
            print(f"{name:10s} swap {swap:3s}: {len(outcomes):5d} tests in {seconds:6.1f} s ({cpu:6.1f} s CPU)  "
                  + "  ".join(f"{k} {v}" for k, v in sorted(counts.items()))
                  + f"  ({sum(calls.values())} calls into {'splinelab' if swap == 'on' else 'scipy'})", flush=True)
        bad = compare(runs["off"]["outcomes"], runs["on"]["outcomes"], KNOWN)
        if not sum(runs["on"]["calls"].values()):
            bad.append(("<no call reached splinelab: the swap missed this client>", "", ""))
        for nodeid, b, s in bad:
            print(f"  DIFFERENT  {nodeid}: scipy {b}, splinelab {s}")
        if bad:
            print(logs["on"][-6000:])
        known = sorted(n for n, o in runs["on"]["outcomes"].items() if o == "xfailed" and n in KNOWN)
        for nodeid in known:
            print(f"  known      {nodeid}: {KNOWN[nodeid]}")
        failed |= bool(bad)
        figures[name] = {swap: {k: v for k, v in r.items() if k != "outcomes"} for swap, r in runs.items()}
        figures[name]["modules"] = CLIENTS[name]
        figures[name]["different"] = [list(t) for t in bad]
        figures[name]["known"] = known
    if args.json:
        Path(args.json).write_text(json.dumps(figures, indent=1))
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
