"""Downstream clients' own tests with splinelab swapped in for
scipy.ndimage's spline functions, and xarray's own interpolation tests with
the ``splinelab`` accessor in place of ``interp``
(python/tests/downstream/README.md).

Each selection of :data:`CLIENTS` runs twice in its own pytest process,
with ``--splinelab-swap=off`` (scipy, or xarray's own ``interp``) and
``on`` (splinelab), and the two outcome sets are compared: every test must
end the same way in both runs, except the known differences of
:mod:`known`, which must pass on the original and xfail (strictly) on
splinelab. Prints the figures (tests, outcomes, wall-clock and CPU
seconds, calls into the installed functions per run, and the tests whose
calls reached them) and exits 1 on any other difference, 0 otherwise.

    .venv/bin/python python/tests/downstream/run.py [--client NAME ...] [--quick] [--serial] [--json FILE]
"""

from __future__ import annotations

import argparse
import collections
import json
import os
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
    # xarray's own interpolation tests, DataArray.interp / Dataset.interp
    # (and interp_like, interp_calendar through them) -> the accessor.
    "xarray": ["xarray.tests.test_interp", "xarray.tests.test_missing", "xarray.tests.test_calendar_ops"],
}
#: What each client's swap replaces (splinelab_swap's --splinelab-target):
#: scipy's functions unless named here.
TARGETS = {"xarray": "xarray"}
#: The clients that need nothing installed beyond scripts/python.sh's
#: environment (scipy, xarray, dask, cftime): ``--quick`` runs these.
QUICK = ("scipy", "xarray")


class Selection:
    """One pytest process over a client's ``modules`` (its rootdir
    site-packages, so node ids read ``reproject/tests/...``), started at
    once: :meth:`result` waits for it and returns (outcomes, calls, reached,
    seconds, cpu seconds, rc, log): the tests whose calls reached the
    installed functions, wall-clock and the process's own user + system CPU
    time (``os.wait4``'s, its waited-for children included: the steadier
    figure on a shared machine, and its own when two runs overlap)."""

    def __init__(self, modules, swap, workdir, target="scipy"):
        self.modules, self.swap = modules, swap
        self.outcomes = Path(workdir) / f"outcomes-{swap}.json"
        ini = Path(workdir) / f"pytest-{swap}.ini"
        ini.write_text("[pytest]\n")
        cmd = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "splinelab_swap",
               f"--splinelab-swap={swap}", f"--splinelab-target={target}", f"--splinelab-outcomes={self.outcomes}",
               "-c", str(ini), f"--rootdir={sysconfig.get_paths()['purelib']}", "-m", "not remote_data", "-rfE",
               "--pyargs", *modules]
        env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(HERE), os.environ.get("PYTHONPATH", "")]).rstrip(
            os.pathsep), MPLBACKEND="Agg")
        self.log = Path(workdir) / f"log-{swap}.txt"
        self.start = time.perf_counter()
        with open(self.log, "w") as out:
            self.proc = subprocess.Popen(cmd, cwd=workdir, env=env, stdout=out, stderr=subprocess.STDOUT, text=True)

    def done(self):
        """Whether the process has ended (reaped here, its time taken then)."""
        if self.proc.returncode is None:
            pid, status, usage = os.wait4(self.proc.pid, os.WNOHANG)
            if not pid:
                return False
            self.proc.returncode = os.waitstatus_to_exitcode(status)
            self.seconds, self.cpu = time.perf_counter() - self.start, usage.ru_utime + usage.ru_stime
        return True

    def result(self):
        while not self.done():
            time.sleep(0.05)
        seconds, cpu = self.seconds, self.cpu
        log = self.log.read_text()
        if not self.outcomes.exists():
            sys.stdout.write(log[-8000:])
            raise SystemExit(f"pytest wrote no outcomes for {self.modules} (swap {self.swap}), rc "
                             f"{self.proc.returncode}")
        record = json.loads(self.outcomes.read_text())
        return (record["outcomes"], record["calls"], record["reached"], seconds, cpu, self.proc.returncode, log)


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
    parser.add_argument("--quick", action="store_true",
                        help=f"run only the clients that need nothing installed: {', '.join(QUICK)}")
    parser.add_argument("--serial", action="store_true",
                        help="run a client's two selections one after the other (default: at the same time)")
    parser.add_argument("--json", help="write the figures to this file")
    args = parser.parse_args(argv)
    sys.path.insert(0, str(HERE))
    from known import KNOWN

    figures, failed = {}, False
    names = list(args.client or ()) + (list(QUICK) if args.quick else [])
    for name in dict.fromkeys(names) or CLIENTS:
        runs, logs = {}, {}
        target = TARGETS.get(name, "scipy")
        with tempfile.TemporaryDirectory() as workdir:
            # the two runs overlap unless --serial (each one's CPU time is its own)
            started = {}
            for swap in ("off", "on"):
                started[swap] = Selection(CLIENTS[name], swap, workdir, target)
                if args.serial:
                    started[swap] = started[swap].result()
            while not all([isinstance(r, tuple) or r.done() for r in started.values()]):   # each polled
                time.sleep(0.05)
            results = {swap: r if isinstance(r, tuple) else r.result() for swap, r in started.items()}
        for swap, (outcomes, calls, reached, seconds, cpu, rc, logs[swap]) in results.items():
            counts = collections.Counter(outcomes.values())
            reaching = collections.Counter(outcomes.get(n, "absent") for n in reached)
            runs[swap] = {"tests": len(outcomes), "seconds": round(seconds, 1), "cpu_seconds": round(cpu, 1), "rc": rc,
                          **dict(sorted(counts.items())), "calls": {k: v for k, v in calls.items() if v},
                          "reaching": len(reached), "reaching_outcomes": dict(sorted(reaching.items())),
                          "outcomes": outcomes}
            into = ("splinelab" if swap == "on" else "scipy" if target == "scipy" else f"{target}'s own")
            print(f"{name:10s} swap {swap:3s}: {len(outcomes):5d} tests in {seconds:6.1f} s ({cpu:6.1f} s CPU)  "
                  + "  ".join(f"{k} {v}" for k, v in sorted(counts.items()))
                  + f"  ({sum(calls.values())} calls into {into}; {len(reached)} tests reaching them: "
                  + ", ".join(f"{k} {v}" for k, v in sorted(reaching.items())) + ")", flush=True)
        bad = compare(runs["off"]["outcomes"], runs["on"]["outcomes"], KNOWN)
        if not sum(runs["on"]["calls"].values()):
            bad.append(("<no call reached splinelab: the swap missed this client>", "", ""))
        for nodeid, b, s in bad:
            print(f"  DIFFERENT  {nodeid}: {'scipy' if target == 'scipy' else target} {b}, splinelab {s}")
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
