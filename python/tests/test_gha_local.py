"""The local Actions runner (gha_local.py) against GitHub's documented rules
("Evaluate expressions in workflows and actions", "Workflow commands"):
string comparison ignores case, ``&&``/``||`` return an operand, a missing
property is null, an ``if:`` without a status function means
``success() && (...)``, a failed step skips the rest but ``always()``
steps, ``continue-on-error`` keeps the job green, outputs in both file forms.
"""

import pytest

import gha_local

CTX = {"inputs": {"x": "", "y": "Yes", "python-version": "3.12"}, "matrix": {"python": "3.10"}, "__failed__": False}


@pytest.mark.parametrize("expr, want", [
    ("inputs.x != ''", False),
    ("inputs.y == 'yes'", True),  # strings compare without case
    ("inputs.python-version", "3.12"),
    ("matrix.python != '3.10'", False),
    ("inputs.missing", None),
    ("inputs.x || 'fallback'", "fallback"),
    ("inputs.y && 'then'", "then"),
    ("!inputs.x", True),
    ("contains('Hello', 'ELL') && startsWith('abc', 'A') && endsWith('abc', 'c')", True),
    ("format('{0}-{1}', 'a', inputs.y)", "a-Yes"),
    ("3 > 2 && 1 == '1'", True),
    ("(inputs.x == '') && (matrix['python'] == '3.10')", True),
])
def test_expressions(expr, want):
    assert gha_local.evaluate(expr, CTX) == want


def test_substitution_writes_values_as_strings():
    assert gha_local.substitute("v=${{ inputs.y }} n=${{ 1 == 1 }} m=${{ inputs.missing }}.", CTX) == "v=Yes n=true m=."


def test_conditions_follow_the_job_status():
    ok, failed = dict(CTX), {**CTX, "__failed__": True}
    assert gha_local.condition(None, ok) and not gha_local.condition(None, failed)
    assert not gha_local.condition("inputs.y == 'yes'", failed)  # success() && (...)
    assert gha_local.condition("${{ always() }}", failed) and gha_local.condition("failure()", failed)


def test_a_failed_step_skips_the_rest_but_always_and_outputs_are_read(tmp_path):
    ws = tmp_path / "ws"
    ws.mkdir()
    steps = [
        {"id": "a", "shell": "bash", "run": 'echo "v=1" >>"$GITHUB_OUTPUT"; printf "m<<EOF\\nx\\ny\\nEOF\\n" >>"$GITHUB_OUTPUT"'},
        {"id": "b", "shell": "bash", "run": "exit 3", "continue-on-error": True},
        {"id": "c", "shell": "bash", "run": "false | true"},  # pipefail: the pipe fails
        {"id": "d", "run": "echo never"},
        {"id": "e", "if": "always()", "shell": "bash", "env": {"V": "${{ steps.a.outputs.v }}"},
         "run": 'echo "saw $V" >>"$GITHUB_STEP_SUMMARY"'},
    ]
    job, ctx = gha_local.run_steps(steps, workspace=ws, ctx={})
    assert [s.outcome for s in job.steps] == ["success", "failure", "failure", "skipped", "success"]
    assert job.step("a").outputs == {"v": "1", "m": "x\ny"}
    assert job.step("b").conclusion == "success" and job.step("b").returncode == 3
    assert job.failed and job.exit_code == 1 and job.summary == "saw 1\n"
