"""splinelab.testing.assert_check and the pytest plugin (--splinelab-report).

References: scipy 1.17.1's spline_filter1d as a peer (its coefficients
pass), and coefficients moved off the certified reference by a chosen
multiple of each element's stable bound (read from the check's own
reference.npy and bound.npy), so the expected excess is known before the
check runs.
"""

import json
import math
import re
import subprocess
import sys

import numpy as np
import pytest
import scipy.ndimage

import splinelab
from splinelab.testing import assert_check

pytest_plugins = ["pytester"]

SAMPLES = np.array([1.0, 2.0, 0.5, 3.0, 1.0, 0.0, 2.0, 1.0, 4.0, 2.5, -1.0, 0.25])
K = 8  # the check's bound_factor: an element fails beyond K x its stable bound


def reference_and_bound(tmp_path, coeffs):
    splinelab.check("prefilter", samples=SAMPLES, coeffs=coeffs, degree=3, out=tmp_path / "ref")
    return np.load(tmp_path / "ref" / "reference.npy"), np.load(tmp_path / "ref" / "bound.npy")


def moved(tmp_path, index, factor):
    """scipy's coefficients with element `index` at reference + factor x bound."""
    c = scipy.ndimage.spline_filter1d(SAMPLES, order=3, mode="mirror")
    ref, bound = reference_and_bound(tmp_path, c)
    c[index] = ref[index] + factor * bound[index]
    return c, bound[index]


def test_scipys_coefficients_pass_and_the_dict_is_check_s():
    c = scipy.ndimage.spline_filter1d(SAMPLES, order=3, mode="mirror")
    r = assert_check("prefilter", samples=SAMPLES, coeffs=c, degree=3)
    assert r == splinelab.check("prefilter", samples=SAMPLES, coeffs=c, degree=3)
    assert r["verdict_basis"] == "stable-bound" and r["worst_excess"]["excess"] < 1


def test_within_the_bound_passes(tmp_path):
    c, _ = moved(tmp_path, 5, 0.5 * K)
    r = assert_check("prefilter", samples=SAMPLES, coeffs=c, degree=3)
    assert r["worst_excess"]["index"] == 5
    assert r["worst_excess"]["excess"] == pytest.approx(0.5 * K, rel=0.02)


def test_beyond_the_bound_raises_with_the_summary(tmp_path):
    c, bound = moved(tmp_path, 5, 2 * K)
    with pytest.raises(AssertionError) as e:
        assert_check("prefilter", samples=SAMPLES, coeffs=c, degree=3)
    text = str(e.value)
    assert text.startswith("check prefilter: fail (12 elements, f64 ulps)")
    assert "worst: index 5 " in text
    m = re.search(
        r"stable bound: worst excess ([0-9.]+) at index 5 \(error ([0-9.e+-]+), bound ([0-9.e+-]+), \w+\); "
        r"digits lost beyond the conditioning ([0-9.]+); over 8 × bound: 1",
        text,
    )
    assert m, text
    excess, error, b, lost = map(float, m.groups())
    assert excess == pytest.approx(2 * K, rel=0.02)
    assert b == bound and error == pytest.approx(2 * K * bound, rel=0.02)
    assert lost == pytest.approx(math.log10(2 * K), abs=0.01)


def test_nan_fails_and_bad_input_is_a_value_error():
    c = scipy.ndimage.spline_filter1d(SAMPLES, order=3, mode="mirror")
    c[2] = np.nan
    with pytest.raises(AssertionError, match="non-finite 1"):
        assert_check("prefilter", samples=SAMPLES, coeffs=c, degree=3)
    with pytest.raises(ValueError, match="unknown check kind"):
        assert_check("prefiltr", samples=SAMPLES, coeffs=c)
    with pytest.raises(ValueError):
        assert_check("prefilter", samples=SAMPLES, coeffs=c[:-1], degree=3)


def test_cond_has_no_bound_so_it_needs_max_ulps():
    nodes = np.linspace(0.0, 1.0, 6)
    with pytest.raises(ValueError, match="needs max_ulps"):
        assert_check("cond", nodes=nodes, values=[1.0], basis="bernstein", norm="inf")
    # 1.0 is no condition number of a 6-node Vandermonde matrix (cond >= 1, > 1 here).
    with pytest.raises(AssertionError, match="over --max-ulps 4 \\(1\\)"):
        assert_check("cond", nodes=nodes, values=[1.0], basis="bernstein", norm="inf", max_ulps=4)


def test_knot_insertion_default_threshold():
    # Inserting x = 1.5 into the linear B-spline (t = 0,0,1,2,3,3, c = 0,1,4,9) by
    # Boehm's rule, exactly: c' = 0, 1, 2.5, 4, 9 (alpha = 1/2 at the new knot).
    before = ([0, 0, 1, 2, 3, 3], [0, 1, 4, 9], 1)
    after = ([0, 0, 1, 1.5, 2, 3, 3], [0, 1, 2.5, 4, 9], 1)
    assert assert_check("knot-insertion", before=before, after=after)["identical"]
    wrong = ([0, 0, 1, 1.5, 2, 3, 3], [0, 1, 2.6, 4, 9], 1)
    with pytest.raises(AssertionError, match="check knot-insertion: fail"):
        assert_check("knot-insertion", before=before, after=wrong)


SESSION = """
import numpy as np
from splinelab.testing import assert_check

def test_prefilter():
    s = np.load("samples.npy")
    assert_check("prefilter", samples=s, coeffs=np.load("coeffs.npy"), degree=3)

def test_two_checks():
    s = np.load("samples.npy")
    for d in (2, 3):
        assert_check("prefilter", samples=s, coeffs=np.load(f"coeffs{d}.npy"), degree=d)
"""


def session(pytester, coeffs, report):
    np.save(pytester.path / "samples.npy", SAMPLES)
    np.save(pytester.path / "coeffs.npy", coeffs)
    for d in (2, 3):
        np.save(pytester.path / f"coeffs{d}.npy", scipy.ndimage.spline_filter1d(SAMPLES, order=d, mode="mirror"))
    pytester.makepyfile(test_session=SESSION)
    args = [] if report is None else ["--splinelab-report", str(report)]
    return pytester.runpytest_subprocess(*args)


def compare(base, current, out):
    return subprocess.run(
        [sys.executable, "-m", "splinelab", "compare", "--baseline", str(base / "summary.json"),
         "--current", str(current / "summary.json"), "--out", str(out)],
        capture_output=True, text=True,
    )


def test_plugin_is_inactive_without_its_option(pytester):
    c = scipy.ndimage.spline_filter1d(SAMPLES, order=3, mode="mirror")
    session(pytester, c, None).assert_outcomes(passed=2)
    assert not list(pytester.path.rglob("summary.json"))


def test_plugin_records_runs_that_compare_judges(pytester, tmp_path):
    good = scipy.ndimage.spline_filter1d(SAMPLES, order=3, mode="mirror")
    worse, _ = moved(tmp_path, 5, 0.5 * K)  # still passes: half the allowance
    runs = {}
    for name, c in (("a", good), ("b", good), ("worse", worse)):
        session(pytester, c, tmp_path / name).assert_outcomes(passed=2)
        runs[name] = tmp_path / name
    summary = json.loads((runs["a"] / "summary.json").read_text())
    labels = [c["label"] for c in summary["checks"]]
    assert labels == ["test_session_py_test_prefilter", "test_session_py_test_two_checks",
                      "test_session_py_test_two_checks-2"]
    assert all((runs["a"] / c["page"]).is_file() for c in summary["checks"])
    names = {f["name"] for f in summary["figures"]}
    assert "test_session_py_test_prefilter.check.prefilter.max_ulps" in names
    assert len(names) == len(summary["figures"])

    same = compare(runs["a"], runs["b"], tmp_path / "cmp_same")
    assert same.returncode == 0, same.stdout + same.stderr
    assert " 0 regressed" in same.stdout and "profiles differ" not in same.stdout

    drift = compare(runs["a"], runs["worse"], tmp_path / "cmp_worse")
    assert drift.returncode == 1, drift.stdout + drift.stderr
    regressed = {line.split()[1].rstrip(":") for line in drift.stdout.splitlines() if line.startswith("REGRESSED")}
    assert "test_session_py_test_prefilter.check.prefilter.worst_excess" in regressed
    assert all(r.startswith("test_session_py_test_prefilter.") for r in regressed)
    assert (tmp_path / "cmp_worse" / "index.html").is_file()


def test_plugin_records_a_failing_check(pytester, tmp_path):
    bad, _ = moved(tmp_path, 5, 2 * K)
    result = session(pytester, bad, tmp_path / "run")
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(["*AssertionError: check prefilter: fail*", "*page: *test_prefilter*",
                                 "splinelab: 3 checks (1 failed)*"])
    checks = json.loads((tmp_path / "run" / "summary.json").read_text())["checks"]
    assert [c["verdict"] for c in checks] == ["fail", "pass", "pass"]


def test_console_script_runs_the_command_line(tmp_path):
    r = subprocess.run([sys.executable, "-m", "splinelab", "--version"], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.startswith("splinelab ")
    r = subprocess.run([sys.executable, "-m", "splinelab", "check", "prefilter"], capture_output=True, text=True)
    assert r.returncode == 2 and "--samples" in r.stderr
