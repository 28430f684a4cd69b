"""Runs GitHub Actions steps here, as GitHub's runner runs them: a composite
action's (``action.yml``) or one job of a workflow (``.github/workflows/*.yml``),
parsed from the YAML itself (PyYAML), not copied by hand.

What is done as on GitHub (runner docs: "Workflow syntax", "Metadata syntax",
"Workflow commands"): ``${{ }}`` expressions substituted in ``run:``, ``env:``
and ``with:`` values (contexts ``inputs`` with the action's defaults,
``steps.ID.outputs``/``outcome``/``conclusion``, ``matrix``, ``env``,
``runner``, ``github``; operators ``! == != < <= > >= && ||``; functions
``success() failure() always() cancelled() contains() startsWith()
endsWith() format()``; an ``if:`` without a status function means
``success() && (...)``); ``shell: bash`` as ``bash --noprofile --norc -eo
pipefail {0}``, no shell as ``bash -e {0}``; each step with fresh
``GITHUB_OUTPUT``, ``GITHUB_STEP_SUMMARY``, ``GITHUB_ENV`` and ``GITHUB_PATH``
files (``name=value`` and ``name<<DELIM`` forms read back), the step
summaries joined in order; ``GITHUB_WORKSPACE`` the working directory (or a
step's ``working-directory``), ``GITHUB_ACTION_PATH`` the action's folder,
``RUNNER_TEMP``, ``CI=true``; a failed step skips the later steps but those
whose ``if:`` says ``always()``/``failure()``; ``continue-on-error``.

What is not: a ``uses:`` step runs only if the caller gives a stand-in for
that action (``uses={"actions/upload-artifact": fn}``; ``fn(with_, env)``
returns its outputs, raises to fail the step; ``INPUT_*`` variables of a
JavaScript action are in ``env``); anything else is refused. ``runs-on``,
containers, services, caches and the token are not emulated.
"""

from __future__ import annotations

import dataclasses
import os
import pathlib
import re
import subprocess
import tempfile

STATUS_FUNCTIONS = ("success", "failure", "always", "cancelled")
SHELLS = {
    None: ["bash", "-e", "{0}"],
    "bash": ["bash", "--noprofile", "--norc", "-eo", "pipefail", "{0}"],
    "sh": ["sh", "-e", "{0}"],
    "python": ["python", "{0}"],
}

_TOKEN = re.compile(
    r"\s*(?:(?P<str>'(?:[^']|'')*')|(?P<num>\d+(?:\.\d+)?)"
    r"|(?P<op>==|!=|<=|>=|&&|\|\||[!<>()\[\].,])|(?P<id>[A-Za-z_][A-Za-z0-9_-]*))"
)


class ExpressionError(ValueError):
    """An expression this runner cannot evaluate."""


def _tokens(text):
    pos, out = 0, []
    text = text.strip()
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos:
            raise ExpressionError(f"cannot read {text[pos:]!r} in {text!r}")
        kind = m.lastgroup
        out.append((kind, m.group(kind)))
        pos = m.end()
    return out


def _number(v):
    """GitHub's coercion to a number for comparisons of mixed types."""
    if v is None:
        return 0.0
    if isinstance(v, bool):
        return float(v)
    if isinstance(v, (int, float)):
        return float(v)
    try:
        return float(v) if str(v).strip() else 0.0
    except ValueError:
        return float("nan")


def truthy(v):
    return not (v is None or v is False or v == "" or (isinstance(v, (int, float)) and (v == 0 or v != v)))


def _equal(a, b):
    if isinstance(a, str) and isinstance(b, str):
        return a.casefold() == b.casefold()
    if type(a) is type(b) and not isinstance(a, (int, float)):
        return a == b
    return _number(a) == _number(b)


def _text(v):
    """A value as ``${{ }}`` writes it into a string."""
    if v is None:
        return ""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float) and v.is_integer():
        return str(int(v))
    return str(v)


class _Parser:
    def __init__(self, text, ctx):
        self.toks, self.i, self.ctx = _tokens(text), 0, ctx

    def peek(self):
        return self.toks[self.i][1] if self.i < len(self.toks) else None

    def take(self, want=None):
        tok = self.toks[self.i] if self.i < len(self.toks) else (None, None)
        if want is not None and tok[1] != want:
            raise ExpressionError(f"expected {want!r}, found {tok[1]!r}")
        self.i += 1
        return tok

    def parse(self):
        v = self.or_()
        if self.i != len(self.toks):
            raise ExpressionError(f"unexpected {self.peek()!r}")
        return v

    def or_(self):
        v = self.and_()
        while self.peek() == "||":
            self.take()
            w = self.and_()
            v = v if truthy(v) else w
        return v

    def and_(self):
        v = self.eq()
        while self.peek() == "&&":
            self.take()
            w = self.eq()
            v = w if truthy(v) else v
        return v

    def eq(self):
        v = self.cmp()
        while self.peek() in ("==", "!="):
            op = self.take()[1]
            w = self.cmp()
            v = _equal(v, w) if op == "==" else not _equal(v, w)
        return v

    def cmp(self):
        v = self.unary()
        while self.peek() in ("<", "<=", ">", ">="):
            op = self.take()[1]
            a, b = _number(v), _number(self.unary())
            v = {"<": a < b, "<=": a <= b, ">": a > b, ">=": a >= b}[op]
        return v

    def unary(self):
        if self.peek() == "!":
            self.take()
            return not truthy(self.unary())
        return self.postfix()

    def postfix(self):
        v = self.primary()
        while self.peek() in (".", "["):
            if self.take()[1] == ".":
                key = self.take()[1]
            else:
                key = self.or_()
                self.take("]")
            v = v.get(key) if isinstance(v, dict) else None
        return v

    def primary(self):
        kind, tok = self.take()
        if kind == "str":
            return tok[1:-1].replace("''", "'")
        if kind == "num":
            return float(tok)
        if tok == "(":
            v = self.or_()
            self.take(")")
            return v
        if kind != "id":
            raise ExpressionError(f"unexpected {tok!r}")
        if tok in ("true", "false"):
            return tok == "true"
        if tok == "null":
            return None
        if self.peek() == "(":
            self.take()
            args = []
            while self.peek() != ")":
                args.append(self.or_())
                if self.peek() == ",":
                    self.take()
            self.take(")")
            return self.call(tok, args)
        if tok not in self.ctx:
            raise ExpressionError(f"unknown context {tok!r}")
        return self.ctx[tok]

    def call(self, name, args):
        status = self.ctx.get("__failed__", False)
        s = [_text(a) for a in args]
        fns = {
            "success": lambda: not status,
            "failure": lambda: status,
            "always": lambda: True,
            "cancelled": lambda: False,
            "contains": lambda: s[1].casefold() in s[0].casefold()
            if not isinstance(args[0], list) else any(_equal(x, args[1]) for x in args[0]),
            "startsWith": lambda: s[0].casefold().startswith(s[1].casefold()),
            "endsWith": lambda: s[0].casefold().endswith(s[1].casefold()),
            "format": lambda: re.sub(r"\{(\d+)\}", lambda m: s[1 + int(m.group(1))], s[0]),
        }
        if name not in fns:
            raise ExpressionError(f"function {name}() is not supported here")
        return fns[name]()


def evaluate(expr, ctx):
    """The value of one expression (without ``${{ }}``) in ``ctx``."""
    return _Parser(expr, ctx).parse()


def substitute(text, ctx):
    """``text`` with every ``${{ expr }}`` replaced by its value."""
    if not isinstance(text, str):
        return _text(text)
    return re.sub(r"\$\{\{(.*?)\}\}", lambda m: _text(evaluate(m.group(1), ctx)), text, flags=re.S)


def condition(step_if, ctx):
    """Whether a step with ``if: step_if`` runs."""
    if step_if is None:
        return not ctx.get("__failed__", False)
    expr = str(step_if).strip()
    if expr.startswith("${{") and expr.endswith("}}"):
        expr = expr[3:-2]
    if not any(re.search(rf"\b{f}\s*\(", expr) for f in STATUS_FUNCTIONS):
        expr = f"success() && ({expr})"
    return truthy(evaluate(expr, ctx))


def read_commands_file(path):
    """``name=value`` lines and ``name<<DELIM`` ... ``DELIM`` blocks."""
    out, lines = {}, pathlib.Path(path).read_text(encoding="utf-8").splitlines()
    k = 0
    while k < len(lines):
        line = lines[k]
        if "<<" in line and ("=" not in line or line.index("<<") < line.index("=")):
            name, delim = line.split("<<", 1)
            end = lines.index(delim, k + 1)
            out[name] = "\n".join(lines[k + 1:end])
            k = end + 1
            continue
        if "=" in line:
            name, value = line.split("=", 1)
            out[name] = value
        k += 1
    return out


@dataclasses.dataclass
class StepResult:
    """What one step did."""

    index: int
    id: str | None
    name: str
    outcome: str  # success, failure or skipped
    conclusion: str
    returncode: int | None = None
    outputs: dict = dataclasses.field(default_factory=dict)
    log: str = ""
    edited: bool = False  # the caller changed its script (see run_steps)


@dataclasses.dataclass
class JobResult:
    """A job's (or a composite action's) steps, outputs and step summary."""

    steps: list
    summary: str
    outputs: dict
    failed: bool

    def step(self, key):
        """The step with this id or name."""
        return next(s for s in self.steps if key in (s.id, s.name))

    @property
    def exit_code(self):
        """The exit status of the step that failed the job (0 when none did)."""
        return next((s.returncode or 1 for s in self.steps if s.conclusion == "failure"), 0)

    @property
    def log(self):
        return "".join(f"--- step {s.index} {s.name} ({s.outcome})\n{s.log}" for s in self.steps)


def _step_name(k, step):
    return step.get("name") or step.get("id") or step.get("uses") or str(step.get("run", "")).split("\n")[0][:60]


def run_steps(steps, *, workspace, ctx, env=None, action_path=None, uses=None, edit=None, defaults=None):
    """Runs ``steps`` (parsed YAML); returns a :class:`JobResult` and the
    final expression contexts.

    ``ctx``: the expression contexts (``inputs``, ``matrix``, ...; ``steps``,
    ``runner``, ``github`` are added). ``env``: the process environment the
    steps start from (workflow/job ``env:`` already merged by the caller).
    ``edit(step, script) -> script`` may change a ``run:`` script before it
    runs (the result records ``edited``); ``defaults``: ``{"shell": ...,
    "working-directory": ...}`` of the workflow or job.
    """
    workspace = pathlib.Path(workspace)
    uses = uses or {}
    defaults = defaults or {}
    temp = pathlib.Path(tempfile.mkdtemp(prefix="runner-temp-", dir=workspace.parent))
    env = dict(os.environ if env is None else env)
    env.update({
        "CI": "true", "GITHUB_ACTIONS": "true", "RUNNER_OS": "Linux", "RUNNER_TEMP": str(temp),
        "GITHUB_WORKSPACE": str(workspace),
    })
    if action_path is not None:
        env["GITHUB_ACTION_PATH"] = str(action_path)
    ctx = {**ctx, "steps": {}, "runner": {"os": "Linux", "temp": str(temp)},
           "github": {"workspace": str(workspace), "action_path": str(action_path or "")},
           "env": dict(ctx.get("env", {})), "__failed__": False}
    results, summary = [], []
    for k, step in enumerate(steps):
        name = _step_name(k, step)
        sid = step.get("id")
        if not condition(step.get("if"), ctx):
            results.append(StepResult(k, sid, name, "skipped", "skipped"))
            if sid:
                ctx["steps"][sid] = {"outputs": {}, "outcome": "skipped", "conclusion": "skipped"}
            continue
        files = {n: temp / f"{n.lower()}_{k}" for n in ("GITHUB_OUTPUT", "GITHUB_STEP_SUMMARY", "GITHUB_ENV", "GITHUB_PATH")}
        for f in files.values():
            f.write_text("")
        step_env = {**env, **{n: str(f) for n, f in files.items()}}
        step_env.update({key: substitute(v, ctx) for key, v in (step.get("env") or {}).items()})
        result = StepResult(k, sid, name, "success", "success")
        if "uses" in step:
            action = step["uses"].split("@", 1)[0]
            if action not in uses:
                raise NotImplementedError(f"step {k} uses {step['uses']}: no stand-in given for {action}")
            with_ = {key: substitute(v, ctx) for key, v in (step.get("with") or {}).items()}
            step_env.update({f"INPUT_{key.upper().replace(' ', '_')}": v for key, v in with_.items()})
            try:
                result.outputs = dict(uses[action](with_, step_env) or {})
                result.returncode = 0
            except Exception as e:  # a failed action fails its step, as on GitHub
                result.outcome, result.returncode, result.log = "failure", 1, f"{action}: {e}\n"
        else:
            script = substitute(step["run"], ctx)
            if edit is not None:
                new = edit(step, script)
                result.edited, script = new != script, new
            path = temp / f"step_{k}.sh"
            path.write_text(script, encoding="utf-8")
            shell = step.get("shell", defaults.get("shell"))
            argv = [a.replace("{0}", str(path)) for a in SHELLS[shell]]
            cwd = workspace / step.get("working-directory", defaults.get("working-directory", "."))
            p = subprocess.run(argv, cwd=cwd, env=step_env, stdin=subprocess.DEVNULL,
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            result.returncode, result.log = p.returncode, p.stdout
            result.outcome = "success" if p.returncode == 0 else "failure"
            result.outputs = read_commands_file(files["GITHUB_OUTPUT"])
        if result.outcome == "failure":
            result.conclusion = "success" if step.get("continue-on-error") else "failure"
            ctx["__failed__"] = ctx["__failed__"] or result.conclusion == "failure"
        summary.append(files["GITHUB_STEP_SUMMARY"].read_text(encoding="utf-8"))
        env.update(read_commands_file(files["GITHUB_ENV"]))
        added = [p for p in files["GITHUB_PATH"].read_text().splitlines() if p]
        if added:
            env["PATH"] = os.pathsep.join([*reversed(added), env.get("PATH", "")])
        if sid:
            ctx["steps"][sid] = {"outputs": result.outputs, "outcome": result.outcome, "conclusion": result.conclusion}
        results.append(result)
    return JobResult(results, "".join(summary), {}, ctx["__failed__"]), ctx


def run_action(action_yml, inputs, *, workspace, env=None, uses=None):
    """Runs a composite action (its ``runs.steps``) with ``inputs`` (the
    action's defaults filled in) and evaluates its ``outputs``."""
    import yaml

    action_yml = pathlib.Path(action_yml)
    spec = yaml.safe_load(action_yml.read_text(encoding="utf-8"))
    if spec["runs"]["using"] != "composite":
        raise NotImplementedError("only composite actions run here")
    unknown = set(inputs) - set(spec.get("inputs", {}))
    if unknown:
        raise KeyError(f"inputs the action does not declare: {sorted(unknown)}")
    full = {name: str(d.get("default", "")) for name, d in spec.get("inputs", {}).items()}
    full.update({k: str(v) for k, v in inputs.items()})
    job, ctx = run_steps(spec["runs"]["steps"], workspace=workspace, ctx={"inputs": full}, env=env,
                         action_path=action_yml.parent, uses=uses)
    job.outputs = {name: substitute(o.get("value", ""), ctx) for name, o in spec.get("outputs", {}).items()}
    return job


def run_job(workflow_yml, job_id, matrix, *, workspace, env=None, uses=None, edit=None):
    """Runs one job of a workflow for one ``matrix`` combination (the
    workflow's and the job's ``env:`` and ``defaults.run`` applied)."""
    import yaml

    wf = yaml.safe_load(pathlib.Path(workflow_yml).read_text(encoding="utf-8"))
    job = wf["jobs"][job_id]
    variables = {**(wf.get("env") or {}), **(job.get("env") or {})}
    ctx = {"matrix": matrix, "env": {}}
    for key, v in variables.items():
        ctx["env"][key] = substitute(v, ctx)
    defaults = {**((wf.get("defaults") or {}).get("run") or {}), **((job.get("defaults") or {}).get("run") or {})}
    base = dict(os.environ if env is None else env)
    base.update(ctx["env"])
    result, _ = run_steps(job["steps"], workspace=workspace, ctx=ctx, env=base, uses=uses, edit=edit,
                          defaults=defaults)
    return result
