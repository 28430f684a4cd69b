"""``action.yml`` run here as GitHub runs a composite action (gha_local.py:
its steps parsed from the YAML, inputs substituted, ``GITHUB_OUTPUT`` and
``GITHUB_STEP_SUMMARY`` files, ``bash --noprofile --norc -eo pipefail``)
against the splinelab installed in this environment (the development build
of scripts/python.sh: ``install: splinelab`` is already satisfied, and
``PIP_NO_INDEX=1`` keeps pip offline).

Not run: ``actions/setup-python`` (``python-version: ''``, the action's way
to use the Python on PATH, so the step is skipped as on GitHub) and
``actions/upload-artifact`` (a stand-in records the folder it would upload
and gives an artifact address). Nothing here has run on GitHub itself.

The scenarios: a passing check; a failing one (the job fails, its page is
written); a check that passes but regressed against a baseline (the compare
fails the job and the step summary names the figure); the same check
against itself (passes). The coefficients are the certified reference moved
by a chosen multiple of each element's stable bound (read from the check's
own reference.npy and bound.npy), so each verdict is known beforehand.
The scenarios' exit codes are written to
target/test-output/action/scenarios.json.
"""

import json
import os
import pathlib
import re
import sys

import numpy as np
import pytest

import splinelab

pytest.importorskip("yaml", reason="scripts/ci_tools.sh installs PyYAML")
import gha_local  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUTPUT = ROOT / "target" / "test-output" / "action"
SAMPLES = np.array([1.0, 2.0, 0.5, 3.0, 1.0, 0.0, 2.0, 1.0, 4.0, 2.5, -1.0, 0.25])
K = 8  # the check's bound_factor
ARTIFACT_URL = "https://github.invalid/OWNER/REPO/actions/runs/1/artifacts/1"


def moved_coefficients(workspace, factor):
    """The reference coefficients with element 5 at reference + factor x its bound."""
    c = splinelab.spline_filter1d(SAMPLES, order=3, mode="mirror")
    splinelab.check("prefilter", samples=SAMPLES, coeffs=c, degree=3, out=workspace / "ref")
    ref, bound = np.load(workspace / "ref" / "reference.npy"), np.load(workspace / "ref" / "bound.npy")
    c = ref.copy()
    c[5] = ref[5] + factor * bound[5]
    return c


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    ws = tmp_path_factory.mktemp("job") / "workspace"
    ws.mkdir()
    np.save(ws / "s.npy", SAMPLES)
    for name, factor in (("good", 0.0), ("worse", 0.5 * K), ("bad", 2 * K)):
        np.save(ws / f"{name}.npy", moved_coefficients(ws, factor))
    return ws


class Uploads:
    """Stand-in for actions/upload-artifact: records what it would upload."""

    def __init__(self, workspace):
        self.workspace, self.calls = workspace, []

    def __call__(self, with_, env):
        path = self.workspace / with_["path"]
        self.calls.append((with_["name"], path, path.is_dir()))
        return {"artifact-id": "1", "artifact-url": ARTIFACT_URL} if path.is_dir() else {}


def run_action(workspace, **inputs):
    env = {**os.environ, "PIP_NO_INDEX": "1"}
    env["PATH"] = os.pathsep.join([str(pathlib.Path(sys.executable).parent), env["PATH"]])
    uploads = Uploads(workspace)
    job = gha_local.run_action(ROOT / "action.yml", {"install": "splinelab", "python-version": "", **inputs},
                               workspace=workspace, env=env, uses={"actions/upload-artifact": uploads})
    assert job.step("install splinelab").outcome == "success", job.log
    assert job.steps[0].outcome == "skipped"  # setup-python: python-version ''
    assert uploads.calls == [("splinelab", workspace / inputs["out"], True)], job.log
    return job


def check_args(coeffs):
    return f"prefilter --samples s.npy --coeffs {coeffs}.npy --degree 3"


def record(name, job):
    OUTPUT.mkdir(parents=True, exist_ok=True)
    path = OUTPUT / "scenarios.json"
    runs = json.loads(path.read_text()) if path.is_file() else {}
    runs[name] = {
        "job_failed": job.failed,
        "exit_code": job.exit_code,
        "steps": {s.name: [s.outcome, s.returncode, s.outputs.get("status")] for s in job.steps},
        "outputs": job.outputs,
    }
    path.write_text(json.dumps(runs, indent=1))
    (OUTPUT / f"{name}.summary.md").write_text(job.summary)


def page_verdict(folder):
    return json.loads((folder / "summary.json").read_text())["check"]["verdict"]


@pytest.fixture(scope="module")
def passing(workspace):
    """The passing scenario's job; its check's summary.json is the others' baseline."""
    job = run_action(workspace, check=check_args("good"), out="out-pass")
    record("passing check", job)
    return job


def test_a_passing_check_passes_the_job_and_writes_its_page(workspace, passing):
    job = passing
    assert not job.failed and job.exit_code == 0, job.log
    assert job.step("check").outputs["status"] == "0"
    assert page_verdict(workspace / "out-pass" / "check") == "pass"
    assert (workspace / "out-pass" / "check" / "index.html").is_file()
    assert job.step("compare").outcome == "skipped" and job.outputs == {"regressed": "", "page": ""}
    assert "### splinelab: ✅ pass" in job.summary
    assert "| `splinelab check` | prefilter | ✅ pass |" in job.summary
    assert f"Pages in the artifact [`splinelab`]({ARTIFACT_URL}): `check/index.html`." in job.summary


def test_a_failing_check_fails_the_job_and_still_writes_its_page(workspace):
    job = run_action(workspace, check=check_args("bad"), out="out-fail")
    record("failing check", job)
    assert job.failed and job.exit_code == 1, job.log
    assert job.step("check").outputs["status"] == "1"
    verdict = job.step("verdict")
    assert verdict.conclusion == "failure" and "::error::splinelab check failed (exit 1)" in verdict.log
    assert page_verdict(workspace / "out-fail" / "check") == "fail"
    assert (workspace / "out-fail" / "check" / "index.html").is_file()
    assert "### splinelab: ❌ fail" in job.summary and "| ❌ fail |" in job.summary


def test_a_regression_against_the_baseline_fails_the_job_and_is_named(workspace, passing):
    job = run_action(workspace, check=check_args("worse"), baseline="out-pass/check/summary.json",
                     out="out-regress")
    record("compare with a regression", job)
    assert job.step("check").outputs["status"] == "0", "the check itself passes: only the compare fails"
    compare = job.step("compare")
    assert compare.outputs["status"] == "1" and job.outputs["regressed"] == "true", job.log
    assert job.outputs["page"] == "out-regress/compare/index.html"
    assert "REGRESSED check.prefilter.worst_excess" in compare.log
    assert job.failed and job.exit_code == 1
    assert "a figure regressed" in job.step("verdict").log
    assert "### splinelab: ❌ fail" in job.summary, job.summary
    assert re.search(r"❌ \d+ figure\(s\) regressed", job.summary), job.summary
    assert "| `check.prefilter.worst_excess` |" in job.summary, job.summary
    moved = json.loads((workspace / "out-regress" / "compare" / "compare.json").read_text())
    assert "check.prefilter.worst_excess" in moved["regressed"] and moved["failed"] is True


def test_the_same_check_against_its_own_baseline_passes(workspace, passing):
    job = run_action(workspace, check=check_args("good"), baseline="out-pass/check/summary.json",
                     out="out-same")
    record("compare without a regression", job)
    assert not job.failed and job.exit_code == 0, job.log
    assert job.step("compare").outputs["status"] == "0" and job.outputs["regressed"] == "false"
    assert "✅ no gated figure regressed" in job.summary
    assert "`compare/index.html`" in job.summary


def test_a_pytest_run_is_recorded_and_summarised(workspace):
    (workspace / "test_accuracy.py").write_text(
        "import numpy as np\nfrom splinelab.testing import assert_check\n\n"
        "def test_good():\n"
        "    assert_check('prefilter', samples=np.load('s.npy'), coeffs=np.load('good.npy'), degree=3)\n\n"
        "def test_bad():\n"
        "    assert_check('prefilter', samples=np.load('s.npy'), coeffs=np.load('bad.npy'), degree=3)\n"
    )
    job = run_action(workspace, pytest="-q -p no:cacheprovider test_accuracy.py", out="out-pytest")
    record("pytest run", job)
    assert job.step("pytest").outputs["status"] == "1" and job.failed
    session = json.loads((workspace / "out-pytest" / "pytest" / "summary.json").read_text())
    assert [c["verdict"] for c in session["checks"]] == ["fail", "pass"]
    assert (workspace / "out-pytest" / "pytest" / "index.html").is_file()
    assert "| `test_accuracy_py_test_bad` | prefilter | ❌ fail |" in job.summary, job.summary
    assert "`pytest/checks/test_accuracy_py_test_good/index.html`" in job.summary
