"""Sphinx extension of splinelab's documentation: figures from the report, never typed by hand.

- ``baseline-figures`` (directive): a table of the committed report
  baseline's figures (``reports/baseline/summary.json``) whose names match
  ``:match:`` (a regular expression), with the baseline's provenance
  (profile, commit, date, machine, command) under it, and optionally
  (``:chart: log`` or ``linear``) a bar chart of the same values drawn at
  build time. A pattern that matches nothing is a build error, so a renamed
  figure cannot leave an empty table behind.
- ``baseline`` (role): one figure's value and unit inline,
  ``{baseline}`engine.scipy.map_coordinates.worst_ulps``` → ``68.91 ulps``.
- ``report-chart`` (directive): a chart of the quick report that
  scripts/docs.sh ran for this build (``_generated/extra/report/NAME.svg``),
  shown with its caption; a missing chart is a build error.
- ``cli-man-pages`` (directive): links to the man pages this build wrote.
- ``scipy-arguments`` (directive): every argument and default of the eight
  functions beside scipy.ndimage's (or, with ``:module:`` and ``:names:``,
  of other scipy names: scipy.interpolate's RegularGridInterpolator and
  interpn), from ``inspect.signature`` of both; splinelab's own keywords
  marked; a scipy argument splinelab lacks, or a shared default that
  differs, is a build error.

At ``builder-inited`` it runs the command line's hidden ``cli-docs``
subcommand (through the Python package's entry point) to write
``_generated/cli.md`` (every ``--help``) and ``_generated/extra/man/*.1``.
"""

from __future__ import annotations

import hashlib
import json
import pathlib
import re

from docutils import nodes
from docutils.parsers.rst import directives
from sphinx.util.docutils import SphinxDirective, SphinxRole

HERE = pathlib.Path(__file__).resolve().parent.parent
ROOT = HERE.parent
BASELINE = ROOT / "reports" / "baseline" / "summary.json"
GENERATED = HERE / "_generated"
EXTRA = GENERATED / "extra"

_cache: dict = {}


def baseline() -> dict:
    """The committed baseline, read once per build."""
    if "baseline" not in _cache:
        _cache["baseline"] = json.loads(BASELINE.read_text(encoding="utf-8"))
    return _cache["baseline"]


def figures(pattern: str) -> list[dict]:
    """The baseline's figures whose names match ``pattern`` (in file order)."""
    rx = re.compile(pattern)
    return [f for f in baseline()["figures"] if rx.search(f["name"])]


def fmt(value: float) -> str:
    """A figure's value as the report prints it: 4 significant digits."""
    if value == 0:
        return "0"
    if abs(value) >= 1e5 or abs(value) < 1e-3:
        return f"{value:.3e}"
    return f"{value:.4g}"


def provenance() -> nodes.paragraph:
    """Where the baseline's figures come from: file, profile, commit, date, machine, command."""
    p = baseline()["provenance"]
    para = nodes.paragraph(classes=["baseline-provenance"])
    para += nodes.Text("From the committed report baseline ")
    para += nodes.literal("", "reports/baseline/summary.json")
    para += nodes.Text(
        f" (profile {baseline()['profile']}, splinelab {p['version']}, commit {p['git_commit']}, "
        f"{p['date']}, {p['cpu']}, {p['threads']} threads, {p['rustc']}); regenerate with "
    )
    para += nodes.literal("", p["regenerate"])
    para += nodes.Text(". CI fails a change that moves a gated figure past its tolerance (splinelab compare).")
    return para


def table(head, classes):
    """An empty docutils table with header ``head``: ``(table, tbody)``."""
    out = nodes.table(classes=classes)
    group = nodes.tgroup(cols=len(head))
    out += group
    for _ in head:
        group += nodes.colspec(colwidth=1)
    thead = nodes.thead()
    group += thead
    thead += row(head)
    body = nodes.tbody()
    group += body
    return out, body


def row(cells, literal_first=False):
    """A table row of text cells (the first as code with ``literal_first``)."""
    tr = nodes.row()
    for i, text in enumerate(cells):
        entry = nodes.entry()
        para = nodes.paragraph()
        para += nodes.literal(text, text) if literal_first and i == 0 else nodes.Text(str(text))
        entry += para
        tr += entry
    return tr


class BaselineFigures(SphinxDirective):
    """The table (and chart) of the baseline figures matching ``:match:``."""

    option_spec = {
        "match": directives.unchanged_required,
        "chart": lambda a: directives.choice(a, ("log", "linear", "none")),
        "caption": directives.unchanged,
        "strip": directives.unchanged,
    }

    def run(self):
        self.env.note_dependency(str(BASELINE))
        pattern = self.options["match"]
        found = figures(pattern)
        if not found:
            raise self.error(f"baseline-figures: no figure of {BASELINE.name} matches {pattern!r}")
        strip = self.options.get("strip", "")
        out = []
        if self.options.get("chart", "none") != "none":
            out.append(self._chart(found, strip))
        out.append(self._table(found, strip))
        out.append(provenance())
        return out

    def _table(self, found, strip):
        figures_table, body = table(["figure", "value", "unit", "tolerance"], ["baseline-figures"])
        for f in found:
            name = f["name"][len(strip):] if strip and f["name"].startswith(strip) else f["name"]
            tolerance = fmt(f["tolerance"]) if f.get("tolerance") is not None else "-"
            if f.get("better"):
                tolerance += f" ({f['better']} is better)"
            body += row([name, fmt(f["value"]), f.get("unit", ""), tolerance], literal_first=True)
        if "caption" in self.options:
            title = nodes.title("", self.options["caption"])
            figures_table.insert(0, title)
        return figures_table

    def _chart(self, found, strip):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        names = [f["name"][len(strip):] if strip and f["name"].startswith(strip) else f["name"] for f in found]
        values = [f["value"] for f in found]
        unit = found[0].get("unit", "")
        log = self.options["chart"] == "log"
        key = hashlib.sha256(json.dumps([self.options["match"], log, values]).encode()).hexdigest()[:16]
        target = GENERATED / "baseline" / f"{key}.png"
        target.parent.mkdir(parents=True, exist_ok=True)
        height = 0.9 + 0.28 * len(names)
        fig, ax = plt.subplots(figsize=(8.0, height), dpi=110, layout="constrained")
        shown = [max(v, 1e-300) for v in values] if log else values
        ax.barh(range(len(names)), shown, color="#3465a4")
        ax.set_yticks(range(len(names)), names, fontsize=8)
        ax.invert_yaxis()
        if log:
            ax.set_xscale("log")
        ax.set_xlabel(unit)
        ax.grid(axis="x", alpha=0.3)
        fig.savefig(target)
        plt.close(fig)
        # A "/"-rooted uri is relative to the source folder: Sphinx copies it.
        image = nodes.image(uri="/" + str(target.relative_to(HERE)), alt=self.options.get("caption", "baseline figures"))
        figure = nodes.figure("", image)
        figure += nodes.caption("", self.options.get("caption", "") + " (bars: the table below).")
        return figure


class BaselineRole(SphinxRole):
    """``{baseline}`NAME``` → the value and unit of figure NAME."""

    def run(self):
        self.env.note_dependency(str(BASELINE))
        exact = [f for f in baseline()["figures"] if f["name"] == self.text]
        if len(exact) != 1:
            msg = self.inliner.reporter.error(f"baseline: no figure named {self.text!r}", line=self.lineno)
            return [self.inliner.problematic(self.rawtext, self.rawtext, msg)], [msg]
        f = exact[0]
        text = f"{fmt(f['value'])} {f.get('unit', '')}".strip()
        return [nodes.inline(self.rawtext, text, classes=["baseline-value"], ids=[])], []


class ReportChart(SphinxDirective):
    """A chart of this build's quick report, with a caption."""

    required_arguments = 1
    option_spec = {"caption": directives.unchanged_required}

    def run(self):
        name = self.arguments[0]
        path = EXTRA / "report" / name
        if not path.is_file():
            raise self.error(f"report-chart: {path} is missing (scripts/docs.sh writes the quick report there)")
        uri = "/" + str(path.relative_to(HERE))
        image = nodes.image(uri=uri, alt=self.options["caption"])
        figure = nodes.figure("", image)
        figure += nodes.caption(
            "", self.options["caption"] + " (from this build's quick report: "
            "python -m splinelab report --quick)."
        )
        return [figure]


class ManPages(SphinxDirective):
    """A list of links to the man pages this build wrote."""

    def run(self):
        pages = sorted((EXTRA / "man").glob("*.1"))
        if not pages:
            raise self.error("cli-man-pages: no man page was generated")
        depth = self.env.docname.count("/")
        up = "../" * depth
        items = nodes.bullet_list()
        for p in pages:
            ref = nodes.reference("", p.name, refuri=f"{up}man/{p.name}", internal=False)
            items += nodes.list_item("", nodes.paragraph("", "", ref))
        return [items]


class PytestPluginOptions(SphinxDirective):
    """The pytest plugin's options, as its ``pytest_addoption`` registers them."""

    def run(self):
        from splinelab import pytest_plugin

        recorded = []

        class Group:
            def addoption(self, *names, **kw):
                recorded.append((names, kw))

        class Parser:
            def getgroup(self, name, description=""):
                return Group()

            def addoption(self, *names, **kw):
                recorded.append((names, kw))

        pytest_plugin.pytest_addoption(Parser())
        if not recorded:
            raise self.error("the pytest plugin registers no option")
        out = nodes.definition_list()
        for names, kw in recorded:
            meta = kw.get("metavar")
            term = ", ".join(f"{n} {meta}" if meta else n for n in names)
            default = kw.get("default")
            text = kw.get("help", "") + (f" Default: {default}." if default is not None else " Default: off.")
            item = nodes.definition_list_item()
            item += nodes.term("", "", nodes.literal(term, term))
            item += nodes.definition("", nodes.paragraph("", text))
            out += item
        return [out]


class ScipyArguments(SphinxDirective):
    """Every argument and default of the eight functions beside scipy.ndimage's,
    read from ``inspect.signature`` of both at build time: a table per function,
    splinelab's own keywords marked, any scipy argument splinelab lacks (or a
    default that differs) a build error, so the table cannot drift from either.
    ``:module: scipy.interpolate`` with ``:names: RegularGridInterpolator
    RegularGridInterpolator.__call__ interpn`` does the same for other names (a
    class: its constructor's arguments)."""

    OURS = "no: splinelab's own"
    FUNCTIONS = ("spline_filter1d", "spline_filter", "map_coordinates", "affine_transform", "shift", "zoom",
                 "rotate", "geometric_transform")
    option_spec = {"module": directives.unchanged, "names": directives.unchanged}

    @staticmethod
    def _lookup(root, dotted):
        for part in dotted.split("."):
            root = getattr(root, part)
        return root

    def run(self):
        import importlib
        import inspect

        import scipy
        import splinelab

        module_name = self.options.get("module", "scipy.ndimage")
        module = importlib.import_module(module_name)
        names = self.options.get("names", " ".join(self.FUNCTIONS)).split()
        self.column = f"in {module_name}"
        out = [nodes.paragraph("", f"Read at build time from inspect.signature of scipy {scipy.__version__}'s "
                                   f"{module_name} and of splinelab {splinelab.__version__}.")]
        for name in names:
            # a method's own `self` is no argument a caller passes
            theirs = {a: p for a, p in inspect.signature(self._lookup(module, name)).parameters.items() if a != "self"}
            ours = {a: p for a, p in inspect.signature(self._lookup(splinelab, name)).parameters.items() if a != "self"}
            missing = [a for a in theirs if a not in ours]
            if missing:
                raise self.error(f"scipy-arguments: splinelab.{name} lacks scipy's {missing}")
            rows = []
            for arg, p in ours.items():
                mine = self._default(p)
                if arg in theirs:
                    scipys = self._default(theirs[arg])
                    if (scipys, self._kind(theirs[arg])) != (mine, self._kind(p)):
                        raise self.error(f"scipy-arguments: {name}({arg}=) is {self._kind(p)}, default {mine}; "
                                         f"scipy's {self._kind(theirs[arg])}, default {scipys}")
                    rows.append([arg, mine, self._kind(p), "yes, the same"])
                else:
                    rows.append([arg, mine, self._kind(p), self.OURS])
            out.append(self._section(name, rows))
        return out

    @staticmethod
    def _default(p):
        import inspect

        if p.default is inspect.Parameter.empty:
            return "(required)"
        d = p.default
        return f"numpy.{d.__name__}" if isinstance(d, type) else repr(d)

    @staticmethod
    def _kind(p):
        import inspect

        return "keyword-only" if p.kind is inspect.Parameter.KEYWORD_ONLY else "positional or keyword"

    def _section(self, name, rows):
        from sphinx import addnodes

        ref = addnodes.pending_xref("", refdomain="py", reftype="obj", reftarget=f"splinelab.{name}",
                                    refexplicit=False, refwarn=True, refdoc=self.env.docname)
        ref += nodes.literal("", f"splinelab.{name}")
        title = nodes.paragraph("", "", nodes.strong("", "", ref))
        arguments, body = table(["argument", "default", "passed", self.column], ["scipy-arguments"])
        for cells in rows:
            tr = row(cells, literal_first=True)
            if cells[-1] == self.OURS:
                tr["classes"].append("splinelab-only")
                tr.children[-1].children[0].children[0] = nodes.strong("", cells[-1])
            body += tr
        return nodes.container("", title, arguments, classes=["scipy-arguments"])


def generate_cli_docs(app):
    """``splinelab cli-docs``: the --help page and the man pages."""
    from splinelab.__main__ import main

    (EXTRA / "man").mkdir(parents=True, exist_ok=True)
    status = main(["cli-docs", "--man", str(EXTRA / "man"), "--markdown", str(GENERATED / "cli.md")])
    if status != 0:
        raise RuntimeError(f"splinelab cli-docs exited {status}")


def setup(app):
    app.add_directive("baseline-figures", BaselineFigures)
    app.add_directive("report-chart", ReportChart)
    app.add_directive("cli-man-pages", ManPages)
    app.add_directive("pytest-plugin-options", PytestPluginOptions)
    app.add_directive("scipy-arguments", ScipyArguments)
    app.add_role("baseline", BaselineRole())
    app.connect("builder-inited", generate_cli_docs)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
