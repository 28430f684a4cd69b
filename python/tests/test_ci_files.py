"""The CI files users copy (``action.yml``, ``.github/workflows/*.yml``), linted
offline as the project's own CI.

- zizmor (the GitHub Actions security linter), ``--offline``: no finding of
  medium severity or more (unpinned actions, broad token permissions,
  persisted credentials, template injection, ...);
- GitHub's workflow and action JSON schemas, as check-jsonschema 0.39.0
  vendors them (``--builtin-schema vendor.github-workflows`` /
  ``vendor.github-actions``, from https://json.schemastore.org/github-workflow
  and https://json.schemastore.org/github-action; the copies in its 0.39.0
  wheel are dated 2026-10-26, their sha256 below), so no network is needed:
  both tools run with proxies that lead nowhere, so a download would fail;
- the project's own rules, read from the YAML: every ``uses:`` pinned to a
  40-hex commit with its version in a comment, every workflow job with its
  own ``permissions:``, every checkout with ``persist-credentials: false``,
  no ``${{ }}`` inside a ``run:`` script.

Each linter is shown to fail on a file with the faults it must catch, so a
pass is not vacuous. The tools are pinned in ci-requirements.txt
(scripts/ci_tools.sh installs them).
"""

import hashlib
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

yaml = pytest.importorskip("yaml", reason="scripts/ci_tools.sh installs the CI test tools")

ROOT = pathlib.Path(__file__).resolve().parents[2]
WORKFLOWS = sorted((ROOT / ".github" / "workflows").glob("*.yml"))
ACTION = ROOT / "action.yml"
SCHEMA_SHA256 = {
    "github-workflows.json": "d10c9f4656e1bd5bc6727e9b35080e017dc167154726fca93da33c7a6bd1c4f3",
    "github-actions.json": "224326cc5a334bdb97b56b6fc320cd4381ba7d61b477b425ed506e6a420b52ba",
}
SEVERITY = ["informational", "low", "medium", "high"]
OFFLINE = {"HTTP_PROXY": "http://127.0.0.1:9", "HTTPS_PROXY": "http://127.0.0.1:9", "NO_PROXY": ""}
TOKENS = ("GH_TOKEN", "GITHUB_TOKEN", "ZIZMOR_GITHUB_TOKEN")

BAD_WORKFLOW = """\
name: bad
on: pull_request_target
jobs:
  greet:
    runs-on: ubuntu-latest
    steps:
      - uses: actions/checkout@v4
      - run: echo "${{ github.event.pull_request.title }}"
"""


def tool(name):
    path = shutil.which(name, path=str(pathlib.Path(sys.executable).parent))
    if path is None:
        pytest.skip(f"{name} is not installed: run scripts/ci_tools.sh")
    return path


def run(argv, cwd=ROOT):
    env = {k: v for k, v in os.environ.items() if k not in TOKENS} | OFFLINE
    return subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True)


def zizmor_findings(paths, cwd=ROOT):
    """Every finding zizmor --offline reports on `paths`, as (severity, audit, file)."""
    r = run([tool("zizmor"), "--offline", "--format", "json", "--persona", "regular", *map(str, paths)], cwd)
    assert r.stdout.strip(), r.stderr
    found = []
    for f in json.loads(r.stdout):
        where = f["locations"][0]["symbolic"]["key"]["Local"]["verbatim_path"]
        found.append((f["determinations"]["severity"].lower(), f["ident"], where))
    return r.returncode, found


def test_zizmor_finds_nothing_of_medium_severity_or_more():
    code, found = zizmor_findings([*WORKFLOWS, ACTION])
    serious = [f for f in found if SEVERITY.index(f[0]) >= SEVERITY.index("medium")]
    assert serious == [], serious
    r = run([tool("zizmor"), "--offline", "--min-severity", "medium", *map(str, [*WORKFLOWS, ACTION])])
    assert r.returncode == 0, r.stdout + r.stderr


def test_zizmor_fails_a_workflow_with_the_faults_it_must_catch(tmp_path):
    bad = tmp_path / ".github" / "workflows" / "bad.yml"
    bad.parent.mkdir(parents=True)
    bad.write_text(BAD_WORKFLOW)
    code, found = zizmor_findings([bad], cwd=tmp_path)
    audits = {a for s, a, _ in found if SEVERITY.index(s) >= SEVERITY.index("medium")}
    assert {"unpinned-uses", "template-injection", "artipacked", "excessive-permissions", "dangerous-triggers"} <= audits, found
    r = run([tool("zizmor"), "--offline", "--min-severity", "medium", str(bad)], tmp_path)
    assert r.returncode != 0


def test_the_vendored_schemas_are_the_recorded_ones():
    import check_jsonschema

    vendor = pathlib.Path(check_jsonschema.__file__).parent / "builtin_schemas" / "vendor"
    for name, digest in SCHEMA_SHA256.items():
        assert hashlib.sha256((vendor / name).read_bytes()).hexdigest() == digest, name


def schema_check(schema, paths):
    return run([tool("check-jsonschema"), "--builtin-schema", schema, *map(str, paths)])


def test_githubs_schemas_accept_the_workflows_and_the_action():
    r = schema_check("vendor.github-workflows", WORKFLOWS)
    assert r.returncode == 0, r.stdout + r.stderr
    r = schema_check("vendor.github-actions", [ACTION])
    assert r.returncode == 0, r.stdout + r.stderr


def test_githubs_schemas_refuse_a_misspelled_key(tmp_path):
    wf = tmp_path / "w.yml"
    wf.write_text(BAD_WORKFLOW.replace("runs-on", "runs_on"))
    assert schema_check("vendor.github-workflows", [wf]).returncode == 1
    act = tmp_path / "action.yml"
    act.write_text(ACTION.read_text().replace("runs:\n  using: composite", "runs:\n  using: compost"))
    assert schema_check("vendor.github-actions", [act]).returncode == 1


def steps_of(path):
    spec = yaml.safe_load(path.read_text())
    if "runs" in spec:
        return [("action", s) for s in spec["runs"]["steps"]]
    return [(job, s) for job, j in spec["jobs"].items() for s in j.get("steps", [])]


@pytest.mark.parametrize("path", [*WORKFLOWS, ACTION], ids=lambda p: p.name)
def test_every_uses_is_pinned_to_a_commit_with_its_version(path):
    lines = [line for line in path.read_text().splitlines() if re.match(r"\s*(- )?uses:", line)]
    assert lines, "no uses: to check"
    for line in lines:
        assert re.search(r"uses: [\w.-]+/[\w./-]+@[0-9a-f]{40} # v\d+(\.\d+)*$", line), line


@pytest.mark.parametrize("path", WORKFLOWS, ids=lambda p: p.name)
def test_every_job_has_its_own_permissions_and_checkouts_keep_no_token(path):
    spec = yaml.safe_load(path.read_text())
    assert spec.get("permissions") == {}, "the workflow grants nothing by default"
    for name, job in spec["jobs"].items():
        assert "permissions" in job, name
        assert all(v in ("read", "none") for v in job["permissions"].values()), (name, job["permissions"])
    for job, step in steps_of(path):
        if step.get("uses", "").startswith("actions/checkout@"):
            assert step.get("with", {}).get("persist-credentials") is False, job


@pytest.mark.parametrize("path", [*WORKFLOWS, ACTION], ids=lambda p: p.name)
def test_no_expression_is_expanded_inside_a_script(path):
    for job, step in steps_of(path):
        assert "${{" not in step.get("run", ""), (job, step.get("name"), step["run"])
