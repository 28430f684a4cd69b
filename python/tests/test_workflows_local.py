"""The wheel workflow's ``test`` job (.github/workflows/wheels.yml) run here
(gha_local.py: its steps parsed from the YAML, ``bash -e`` for each ``run:``)
against a real wheel built from this checkout.

The wheel: ``maturin build --release`` with the features of scripts/python.sh,
which after it only packages the extension already compiled (cargo finds
nothing to do); not the manylinux_2_28 build of the workflow's ``wheel`` job
(maturin's action in its container), which is not run here. The runner: a
fresh virtual environment (the workflow's ``python``) that sees the packages
of .venv (numpy, scipy, dask, distributed, dask-image, pytest: what the job's
install step asks for) but not its splinelab, with ``PIP_NO_INDEX=1``, so the
install step installs the wheel and finds the rest already there.

Stand-ins: ``actions/checkout`` (the workspace links this checkout's
``python/``), ``actions/setup-python`` (records the version; the
environment's Python 3 is used, not 3.13), ``actions/download-artifact``
(copies the wheel into ``dist/``). Run for real: the install, the doctests of
the installed package from ``$RUNNER_TEMP``, ``splinelab --version``, and the
last step with ``python/tests`` narrowed to ``python/tests/test_check.py``
(the whole suite is this test command itself). Nothing here has run on
GitHub itself.
"""

import os
import pathlib
import shutil
import subprocess
import sys
import sysconfig
import time

import pytest

pytest.importorskip("yaml", reason="scripts/ci_tools.sh installs PyYAML")
import gha_local  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
WHEELS = ROOT / ".github" / "workflows" / "wheels.yml"
MATRIX = {"target": "x86_64", "python": "3.13", "runner": "ubuntu-latest"}


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    out = tmp_path_factory.mktemp("wheelhouse")
    features = subprocess.run(["bash", "scripts/gmp_features.sh"], cwd=ROOT, capture_output=True,
                              text=True, check=True).stdout.split()
    maturin = pathlib.Path(sys.executable).parent / "maturin"
    start = time.perf_counter()
    r = subprocess.run([str(maturin), "build", "--release", "-m", "python/Cargo.toml", "--out", str(out), *features],
                       cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    (wheel,) = out.glob("splinelab-*.whl")
    print(f"wheel built in {time.perf_counter() - start:.1f} s: {wheel.name}")
    return wheel


def runner_python(root):
    """A fresh venv whose site sees .venv's packages but not its splinelab."""
    venv = root / "runner-python"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    shared = root / "preinstalled"
    shared.mkdir()
    for entry in pathlib.Path(sysconfig.get_paths()["purelib"]).iterdir():
        if not entry.name.lower().startswith(("splinelab", "_splinelab", "__editable__.splinelab")):
            (shared / entry.name).symlink_to(entry)
    purelib = subprocess.run([str(venv / "bin" / "python"), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                             capture_output=True, text=True, check=True).stdout.strip()
    pathlib.Path(purelib, "_preinstalled.pth").write_text(f"import site; site.addsitedir({str(shared)!r})\n")
    return venv


def run_test_job(tmp_path, wheel):
    ws = tmp_path / "workspace"
    ws.mkdir()
    (ws / "python").symlink_to(ROOT / "python")
    venv = runner_python(tmp_path)
    seen = {}

    def setup_python(with_, env):
        seen["python-version"] = with_["python-version"]
        return {"python-version": "environment's python3"}

    def download(with_, env):
        assert with_["name"] == f"wheel-{MATRIX['target']}"
        dest = ws / with_["path"]
        dest.mkdir(parents=True, exist_ok=True)
        shutil.copy(wheel, dest)
        return {"download-path": str(dest)}

    def narrow(step, script):
        return script.replace("python/tests\n", "python/tests/test_check.py\n")

    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env.update(PATH=os.pathsep.join([str(venv / "bin"), env["PATH"]]), VIRTUAL_ENV=str(venv), PIP_NO_INDEX="1")
    job = gha_local.run_job(WHEELS, "test", MATRIX, workspace=ws, env=env, edit=narrow, uses={
        "actions/checkout": lambda with_, env: {},
        "actions/setup-python": setup_python,
        "actions/download-artifact": download,
    })
    return job, venv, seen


def test_the_wheel_workflows_test_job_passes_against_a_local_wheel(tmp_path, wheel):
    job, venv, seen = run_test_job(tmp_path, wheel)
    assert not job.failed, job.log[-6000:]
    assert seen["python-version"] == "3.13"
    assert [s.outcome for s in job.steps] == ["success"] * 7, job.log[-6000:]
    assert [s.edited for s in job.steps] == [False] * 6 + [True]
    install, doctests, version, suite = job.steps[3:]
    assert "Successfully installed splinelab-0.1.0" in install.log, install.log
    assert " passed" in doctests.log and "failed" not in doctests.log, doctests.log
    assert version.log.startswith("splinelab "), version.log
    assert " passed" in suite.log and "failed" not in suite.log, suite.log[-3000:]
    # What the steps imported was the wheel, installed into the runner's Python.
    where = subprocess.run([str(venv / "bin" / "python"), "-c", "import splinelab; print(splinelab.__file__)"],
                           capture_output=True, text=True, check=True, cwd=tmp_path).stdout.strip()
    assert where.startswith(str(venv)), where
    assert (venv / "bin" / "splinelab").is_file()
