"""pytest plugin: splinelab's functions in place of scipy.ndimage's (and
scipy.interpolate's ``RegularGridInterpolator`` and ``interpn``), to run
another library's own tests (or scipy's) on splinelab.

Load it with ``-p`` (the folder on ``PYTHONPATH``); ``--splinelab-swap=on``
replaces ``scipy.ndimage.<name>`` / ``scipy.interpolate.<name>`` by
``splinelab.<name>`` for every name of :data:`SWAPPED` in
``pytest_load_initial_conftests``, before any conftest or test module of the
client is imported, so a client's module-level
``from scipy.ndimage import map_coordinates`` binds splinelab's function and
``ndimage.map_coordinates(...)`` finds it at call time. ``off`` runs the
same selection on scipy (the baseline run.py compares with). Either way
the installed functions are counting wrappers (``functools.wraps``: same
name, signature and docstring; a class is a subclass whose ``__init__``
counts), so each run says how many calls (constructions) reached them.
``--splinelab-outcomes=FILE`` writes each test's outcome and the calls per
function (JSON).

Known differences (:mod:`known`) are marked ``xfail(strict=True)`` with
their reason when the swap is on: each must still fail (a fixed one turns
into a strict XPASS failure and is removed from the list).
"""

from __future__ import annotations

import functools
import json

import pytest

# scipy's functions and classes that splinelab replaces, by module.
SWAPPED = {
    "scipy.ndimage": (
        "map_coordinates",
        "zoom",
        "shift",
        "rotate",
        "affine_transform",
        "geometric_transform",
        "spline_filter",
        "spline_filter1d",
    ),
    "scipy.interpolate": ("RegularGridInterpolator", "interpn"),
}


def pytest_addoption(parser):
    group = parser.getgroup("splinelab")
    group.addoption("--splinelab-swap", choices=("on", "off"), default="on",
                    help="replace scipy.ndimage's spline functions by splinelab's (default on)")
    group.addoption("--splinelab-outcomes", default=None, metavar="FILE",
                    help="write each test's outcome and the calls per function to FILE (JSON)")


def install(use_splinelab):
    """Put counting wrappers of splinelab's functions (``use_splinelab``) or
    of scipy's own in scipy.ndimage; returns the calls counter (name ->
    calls), which shows that the client's calls reached the functions
    installed."""
    import importlib

    import splinelab

    try:
        # scipy's own tests look their functions up in scipy's array-API
        # capabilities table (make_xp_test_case): ours take scipy's entries.
        from scipy._lib._array_api import xp_capabilities_table as table
    except ImportError:
        table = {}
    calls = {name: 0 for names in SWAPPED.values() for name in names}
    for module_name, names in SWAPPED.items():
        module = importlib.import_module(module_name)
        for name in names:
            original = getattr(module, name)
            wrapper = _counted(name, getattr(splinelab, name) if use_splinelab else original, calls)
            if original in table:
                table[wrapper] = table[original]
            setattr(module, name, wrapper)
    return calls


def _counted(name, function, calls):
    if isinstance(function, type):
        # A class: a subclass of the same name whose construction counts
        # (class attributes such as RegularGridInterpolator._ALL_METHODS and
        # isinstance stay as they were).
        init = function.__init__

        @functools.wraps(init)
        def __init__(self, *args, **kwargs):
            calls[name] += 1
            init(self, *args, **kwargs)

        return type(function.__name__, (function,), {"__init__": __init__, "__doc__": function.__doc__,
                                                     "__module__": function.__module__,
                                                     "__qualname__": function.__qualname__})

    @functools.wraps(function)
    def counted(*args, **kwargs):
        calls[name] += 1
        return function(*args, **kwargs)

    return counted


@pytest.hookimpl(tryfirst=True)
def pytest_load_initial_conftests(early_config, parser, args):
    on = early_config.known_args_namespace.splinelab_swap == "on"
    early_config._splinelab_swap = on
    early_config._splinelab_calls = install(on)


def pytest_report_header(config):
    import scipy

    import splinelab

    return (f"splinelab swap: {'on' if config._splinelab_swap else 'off'} (scipy {scipy.__version__}, splinelab "
            f"{splinelab.__version__})")


def pytest_collection_modifyitems(config, items):
    if not config._splinelab_swap:
        return
    from known import KNOWN

    for item in items:
        reason = KNOWN.get(item.nodeid)
        if reason is not None:
            item.add_marker(pytest.mark.xfail(reason=reason, strict=True))


class _Outcomes:
    """Each test's outcome: passed, failed (setup, call or teardown),
    skipped, xfailed, xpassed."""

    def __init__(self, path, calls):
        self.path, self.calls = path, calls
        self.outcomes = {}

    def pytest_runtest_logreport(self, report):
        # A failure in any phase decides; otherwise the call's outcome, or
        # the setup's (a skip) when there was no call.
        if hasattr(report, "wasxfail"):
            outcome = "xfailed" if report.skipped else "xpassed"
        else:
            outcome = report.outcome
        if self.outcomes.get(report.nodeid) != "failed" and (report.when != "teardown" or outcome == "failed"):
            self.outcomes[report.nodeid] = outcome

    def pytest_collectreport(self, report):
        if report.failed:
            self.outcomes[report.nodeid or "<collection>"] = "error"

    def pytest_sessionfinish(self):
        with open(self.path, "w") as f:
            json.dump({"outcomes": self.outcomes, "calls": self.calls}, f, indent=0, sort_keys=True)


def pytest_configure(config):
    path = config.getoption("splinelab_outcomes")
    if path:
        config.pluginmanager.register(_Outcomes(path, config._splinelab_calls), "splinelab_outcomes")
