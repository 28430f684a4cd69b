"""scripts/bench_summary.py: criterion's results as figures `splinelab compare --timings` gates.

A criterion folder laid out as criterion 0.8 writes it (GROUP/…/new/benchmark.json and
estimates.json); the figures must be the medians given, named by group, and only those of
this run (`--since`); a 5x slower median regresses under --timings, not without it.
"""

import json
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]


def bench(root, full_id, median, mtime):
    d = root.joinpath(*full_id.split("/"), "new")
    d.mkdir(parents=True)
    group, _, rest = full_id.partition("/")
    (d / "benchmark.json").write_text(json.dumps({"group_id": group, "full_id": full_id, "value_str": rest}))
    (d / "estimates.json").write_text(json.dumps({"median": {"point_estimate": median}, "mean": {"point_estimate": 0}}))
    for f in d.iterdir():
        os.utime(f, (mtime, mtime))


def summarise(criterion, out, since):
    return subprocess.run([sys.executable, str(ROOT / "scripts" / "bench_summary.py"), str(criterion), str(out),
                           "--since", str(since)], capture_output=True, text=True)


def test_medians_of_this_run_become_figures_that_compare_gates(tmp_path):
    crit = tmp_path / "criterion"
    bench(crit, "engine/prefilter/1000", 1500.0, 2000)
    bench(crit, "knot_insertion/insert_in_place/100", 250.0, 2000)
    bench(crit, "old/left_over", 9.0, 1000)  # an earlier run's: not this one's
    r = summarise(crit, tmp_path / "a", since=1500)
    assert r.returncode == 0, r.stderr
    figures = json.loads((tmp_path / "a" / "summary.json").read_text())["figures"]
    assert {f["name"]: f["value"] for f in figures} == {
        "bench_engine.prefilter/1000": 1500.0, "bench_knot_insertion.insert_in_place/100": 250.0}
    assert all(f["kind"] == "cost" and f["unit"] == "ns" and f["tolerance"] == 4.0 for f in figures)

    bench(tmp_path / "slow", "engine/prefilter/1000", 5 * 1500.0, 2000)
    bench(tmp_path / "slow", "knot_insertion/insert_in_place/100", 250.0, 2000)
    assert summarise(tmp_path / "slow", tmp_path / "b", since=1500).returncode == 0
    compare = [sys.executable, "-m", "splinelab", "compare", "--baseline", str(tmp_path / "a" / "summary.json"),
               "--current", str(tmp_path / "b" / "summary.json"), "--out", str(tmp_path / "cmp")]
    gated = subprocess.run([*compare, "--timings"], capture_output=True, text=True)
    assert gated.returncode == 1 and "REGRESSED bench_engine.prefilter/1000" in gated.stdout, gated.stdout
    assert subprocess.run(compare, capture_output=True, text=True).returncode == 0


def test_no_result_of_this_run_is_an_error(tmp_path):
    bench(tmp_path / "criterion", "old/left_over", 9.0, 1000)
    r = summarise(tmp_path / "criterion", tmp_path / "out", since=1500)
    assert r.returncode == 1 and "no criterion result" in r.stderr
