"""Criterion's results as a summary.json that ``splinelab compare`` reads.

    python3 scripts/bench_summary.py CRITERION_DIR OUT_DIR [--since EPOCH_SECONDS]

Reads every ``CRITERION_DIR/**/new/benchmark.json`` and its ``estimates.json``
(written by criterion at or after ``--since``: the benchmarks of this run,
not older ones left in the folder) and writes ``OUT_DIR/summary.json`` with
one figure per benchmark: its median time (criterion's point estimate, in
ns) as a wall-clock cost named ``bench_GROUP.REST`` (GROUP: the first part of
criterion's id, one chart per group in the compare page), with the report's
noise band (4x). ``splinelab compare --timings --baseline OLD/summary.json
--current OUT_DIR/summary.json --out DIR`` gates them; without
``--timings`` they are shown, not gated (wall-clock figures on a shared
machine). Standard library only. Exit 1 when no benchmark was found.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import platform
import re
import sys
import time

TIME_BAND = 4.0  # as the report's wall-clock figures (reports/src/report/mod.rs)


def figure_name(full_id):
    group, _, rest = full_id.partition("/")
    safe = lambda s: re.sub(r"[^A-Za-z0-9_/=+-]+", "_", s).strip("_")  # noqa: E731
    return f"bench_{safe(group)}." + (safe(rest) or "median")


def collect(criterion, since):
    """(figure, directory) per benchmark written at or after `since`."""
    figures = []
    for bench in sorted(pathlib.Path(criterion).glob("**/new/benchmark.json")):
        estimates = bench.with_name("estimates.json")
        if not estimates.is_file() or estimates.stat().st_mtime < since:
            continue
        meta = json.loads(bench.read_text())
        median = json.loads(estimates.read_text())["median"]["point_estimate"]
        figures.append({
            "name": figure_name(meta["full_id"]),
            "value": median,
            "kind": "cost",
            "unit": "ns",
            "better": "lower",
            "tolerance": TIME_BAND,
            "floor": 0.0,
            "over": "criterion benches",
            "criterion_id": meta["full_id"],
        })
    return figures


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("criterion", help="criterion's output folder (target/criterion)")
    p.add_argument("out", help="folder for summary.json")
    p.add_argument("--since", type=float, default=0.0, help="ignore results older than this (epoch seconds)")
    a = p.parse_args(argv)
    figures = collect(a.criterion, a.since)
    if not figures:
        print(f"error: no criterion result in {a.criterion} newer than {a.since}", file=sys.stderr)
        return 1
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    summary = {
        "source": "scripts/bench.sh: criterion medians (ns)",
        "provenance": {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "cpu": platform.processor()
                       or platform.machine(), "threads": os.cpu_count()},
        "figures": figures,
    }
    tmp = out / f".summary.json.tmp{os.getpid()}"
    tmp.write_text(json.dumps(summary, indent=1))
    os.replace(tmp, out / "summary.json")
    print(f"{len(figures)} benchmark medians -> {out / 'summary.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
