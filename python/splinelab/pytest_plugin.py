"""pytest plugin (entry point ``pytest11``): a regression record of your checks.

Inactive unless enabled: ``pytest --splinelab-report DIR`` makes every
:func:`splinelab.testing.assert_check` of the session write its page (the
command line's ``splinelab check --out``: HTML, SVG charts, per-element
``.npy`` and ``summary.json``, written by the engine) into
``DIR/checks/LABEL``, LABEL being the test's node id made file-safe (``-2``,
``-3``, ... for further checks in one test; ``name=`` overrides it). At the
end of the session ``DIR/summary.json`` gathers every check's figures, each
renamed ``LABEL.check.KIND.FIGURE`` with its tolerance unchanged, and
``DIR/index.html`` leads with a chart of each check's worst error against
what its verdict allows (the failures marked) and links every page. ``DIR/checks`` is emptied when the
session starts, so a removed test does not linger.

Two runs (main and a branch, yesterday's CI and today's) then compare with
``splinelab compare --baseline A/summary.json --current B/summary.json
--out C``: a page with one chart per test and a table of every figure,
exit 1 when a figure got worse beyond its own tolerance (0.5 ulps, 0.1
digits; ``splinelab compare --help``) or a check went missing.

Under pytest-xdist the workers write the pages and the controller the
summary.
"""

from __future__ import annotations

import json
import os
import pathlib
import re
import shutil

import pytest


def pytest_addoption(parser):
    group = parser.getgroup("splinelab")
    group.addoption(
        "--splinelab-report",
        metavar="DIR",
        default=None,
        help="write each splinelab.testing.assert_check's page under DIR/checks and DIR/summary.json "
        "for `splinelab compare` (off by default)",
    )


def pytest_configure(config):
    folder = config.getoption("splinelab_report", None)
    if folder is not None:
        worker = hasattr(config, "workerinput")
        config.pluginmanager.register(_Recorder(pathlib.Path(folder).resolve(), worker), "splinelab-recorder")


def _slug(label):
    """A folder name, and a figure-name prefix without dots (``compare``
    groups figures by the part before the first dot)."""
    return re.sub(r"[^A-Za-z0-9_-]+", "_", label).strip("_") or "check"


class _Recorder:
    """Hands each check its folder and writes the session's summary."""

    def __init__(self, root, worker):
        from . import testing

        self.root, self.worker, self.testing = root, worker, testing
        self.checks = root / "checks"
        if not worker:
            shutil.rmtree(self.checks, ignore_errors=True)
        self.checks.mkdir(parents=True, exist_ok=True)
        self.test = "session"
        self.seen = {}
        self.count = (0, 0)
        testing._recorder = self

    def __call__(self, kind, name):
        label = _slug(name or self.test)
        n = self.seen[label] = self.seen.get(label, 0) + 1
        return self.checks / (label if n == 1 else f"{label}-{n}")

    @pytest.hookimpl(hookwrapper=True)
    def pytest_runtest_protocol(self, item, nextitem):
        self.test = item.nodeid
        yield
        self.test = "session"

    def pytest_sessionfinish(self, session):
        if not self.worker:
            self.count = write_summary(self.root)

    def pytest_terminal_summary(self, terminalreporter):
        if not self.worker:
            checks, failed = self.count
            terminalreporter.write_line(
                f"splinelab: {checks} checks ({failed} failed) -> {self.root / 'summary.json'}"
            )

    def pytest_unconfigure(self, config):
        self.testing._recorder = None


def _atomic(path, text):
    tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, path)


def write_summary(root):
    """Gathers ``root/checks/*/summary.json`` into ``root/summary.json`` and
    the session page ``root/index.html`` (a chart of each check's worst
    error against what its verdict allows, then the table of checks, drawn
    by the extension with the report's chart code and stylesheet); returns
    (checks, failed)."""
    from . import _splinelab

    root = pathlib.Path(root)
    folders = sorted(p for p in (root / "checks").iterdir() if p.is_dir() and not p.name.startswith("."))
    checks, figures, pages = [], [], []
    for d in folders:
        page = json.loads((d / "summary.json").read_text(encoding="utf-8"))
        c = page["check"]
        checks.append({
            "label": d.name,
            "kind": c.get("kind"),
            "verdict": c.get("verdict"),
            "n": c.get("n"),
            "worst_ulps": (c.get("worst") or {}).get("ulps", c.get("max_deviation_ulps")),
            "digits_lost": c.get("digits_lost"),
            "page": f"checks/{d.name}/index.html",
        })
        pages.append({"label": d.name, "page": f"checks/{d.name}/index.html", "check": c})
        figures += [{**f, "name": f"{d.name}.{f['name']}"} for f in page["figures"]]
    summary = {"source": "splinelab pytest plugin (--splinelab-report)", "checks": checks, "figures": figures}
    _atomic(root / "summary.json", json.dumps(summary, indent=1))
    for name, text in _splinelab.session_page(json.dumps(pages)):
        _atomic(root / name, text)
    return len(checks), sum(c["verdict"] != "pass" for c in checks)
