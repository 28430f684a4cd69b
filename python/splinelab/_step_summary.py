"""The GitHub Actions step summary of the splinelab action (``action.yml``).

``python -m splinelab._step_summary OUT [--artifact NAME] [--url URL]
[--pytest-status N] [--check-status N] [--compare-status N]`` prints, in
Markdown, the verdict of every check the action ran (``OUT/pytest/summary.json``
of the pytest plugin, ``OUT/check/summary.json`` of ``splinelab check``) and the
compare's (``OUT/compare/compare.json``: the regressed figures by name, baseline
and current value), then where the pages are in the uploaded artifact (linked
when ``--url`` gives the artifact's address). A status given for a step whose
files are missing is reported as such (the step failed before writing them).
The action appends this to ``$GITHUB_STEP_SUMMARY``.
"""

from __future__ import annotations

import argparse
import json
import pathlib

PASS, FAIL = "✅ pass", "❌ fail"


def _num(x):
    """Four significant digits, as the pages print figures."""
    return "-" if x is None else f"{x:.4g}"


def _code(text):
    return "`" + str(text).replace("`", "'") + "`"


def _read(path):
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def _checks_table(rows):
    """Markdown table of (label, kind, verdict, worst ulps, digits lost, page)."""
    lines = ["| check | kind | verdict | worst (ulps) | digits lost | page |", "|---|---|---|---|---|---|"]
    for label, kind, verdict, worst, lost, page in rows:
        word = PASS if verdict == "pass" else FAIL
        lines.append(f"| {_code(label)} | {kind} | {word} | {_num(worst)} | {_num(lost)} | {_code(page)} |")
    return lines


def _checks(out):
    """Rows of the checks the action ran, and the pages present."""
    rows, pages = [], []
    session = _read(out / "pytest" / "summary.json")
    if session is not None:
        pages.append("pytest/index.html")
        rows += [
            (c["label"], c.get("kind"), c.get("verdict"), c.get("worst_ulps"), c.get("digits_lost"),
             f"pytest/{c['page']}")
            for c in session.get("checks", [])
        ]
    single = _read(out / "check" / "summary.json")
    if single is not None:
        pages.append("check/index.html")
        c = single["check"]
        worst = (c.get("worst") or {}).get("ulps", c.get("max_deviation_ulps"))
        rows.append(("splinelab check", c.get("kind"), c.get("verdict"), worst, c.get("digits_lost"),
                     "check/index.html"))
    return rows, pages


def _compare(out):
    """Lines on the compare, its page when present, and whether it failed."""
    cmp = _read(out / "compare" / "compare.json")
    if cmp is None:
        return [], [], False
    rows = {r["name"]: r for r in cmp.get("rows", [])}
    compared = len(rows)
    if not cmp.get("failed"):
        head = f"**Compare** with {_code(cmp['baseline'])}: ✅ no gated figure regressed ({compared} compared)"
        return [head], ["compare/index.html"], False
    regressed, missing = cmp.get("regressed", []), cmp.get("missing", [])
    lines = [
        f"**Compare** with {_code(cmp['baseline'])}: ❌ {len(regressed)} figure(s) regressed"
        + (f", {len(missing)} missing" if missing else "")
        + f" ({compared} compared)",
    ]
    if regressed:
        lines += ["", "| figure | baseline | current | unit | tolerance |", "|---|---|---|---|---|"]
        for name in regressed:
            r = rows[name]
            lines.append(
                f"| {_code(name)} | {_num(r['baseline'])} | {_num(r['current'])} | {r['unit']} | {_num(r['tolerance'])} |"
            )
    if missing:
        lines += ["", "Missing from the current run: " + ", ".join(_code(m) for m in missing)]
    return lines, ["compare/index.html"], True


def summary(out, artifact="splinelab", url="", statuses=None):
    """The Markdown step summary of the action's output folder ``out``."""
    out = pathlib.Path(out)
    statuses = statuses or {}
    rows, pages = _checks(out)
    compare_lines, compare_pages, compare_failed = _compare(out)
    failed_steps = [f"{step} exited {code}" for step, code in statuses.items() if code not in (None, "", "0")]
    bad = failed_steps or compare_failed or any(r[2] != "pass" for r in rows)
    lines = [f"### splinelab: {FAIL if bad else PASS}", ""]
    if failed_steps:
        lines += ["Steps: " + "; ".join(failed_steps) + ".", ""]
    if rows:
        lines += _checks_table(rows) + [""]
    if compare_lines:
        lines += compare_lines + [""]
    pages += compare_pages
    if pages:
        where = f"[{_code(artifact)}]({url})" if url else _code(artifact)
        lines.append(f"Pages in the artifact {where}: " + ", ".join(_code(p) for p in pages) + ".")
    else:
        lines.append("No page was written.")
    return "\n".join(lines) + "\n"


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m splinelab._step_summary", description=__doc__.splitlines()[0])
    p.add_argument("out", help="the action's output folder")
    p.add_argument("--artifact", default="splinelab", help="the uploaded artifact's name")
    p.add_argument("--url", default="", help="the uploaded artifact's address")
    for step in ("pytest", "check", "compare"):
        p.add_argument(f"--{step}-status", default="", help=f"the {step} step's exit status, if it ran")
    a = p.parse_args(argv)
    statuses = {"pytest": a.pytest_status, "splinelab check": a.check_status, "compare": a.compare_status}
    # The compare's own exit 1 (a regression) is reported through compare.json.
    if statuses["compare"] == "1":
        statuses["compare"] = ""
    print(summary(a.out, a.artifact, a.url, statuses), end="")


if __name__ == "__main__":
    main()
