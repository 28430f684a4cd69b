"""pytest plugin: splinelab's functions in place of scipy.ndimage's (and
scipy.interpolate's ``RegularGridInterpolator`` and ``interpn``), or the
``splinelab`` accessor in place of xarray's ``interp``, to run another
library's own tests (or scipy's, or xarray's) on splinelab.

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
``--splinelab-outcomes=FILE`` writes each test's outcome, the calls per
function and the tests whose calls reached the installed functions (JSON).

``--splinelab-target=xarray`` swaps xarray's instead:
``xarray.DataArray.interp`` and ``xarray.Dataset.interp`` become wrappers
with xarray's signatures that call ``obj.splinelab.interp`` with the same
arguments (xarray's default method, "linear", passed on) where the method
is one the accessor offers (:data:`splinelab.xarray.METHODS`), and
xarray's own ``interp`` otherwise (``off``: xarray's own always, counting
the same calls). Everything that calls ``interp`` reaches it:
``interp_like``, ``xarray.coding.calendar_ops.interp_calendar``, a
DataArray's ``interp`` of its own temporary Dataset (counted once: only the
outermost call of a test's call counts).

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


#: xarray's methods that the accessor stands in for (``--splinelab-target=xarray``).
XARRAY_SWAPPED = ("DataArray.interp", "Dataset.interp")


def pytest_addoption(parser):
    group = parser.getgroup("splinelab")
    group.addoption("--splinelab-swap", choices=("on", "off"), default="on",
                    help="replace scipy.ndimage's spline functions by splinelab's (default on)")
    group.addoption("--splinelab-target", choices=("scipy", "xarray"), default="scipy",
                    help="what the swap replaces: scipy's functions (default) or xarray's interp")
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


def install_xarray(use_splinelab):
    """Put counting wrappers of ``interp`` on xarray's DataArray and
    Dataset: with ``use_splinelab`` each calls the accessor where it offers
    the method, else xarray's own. Returns the calls counter (the
    outermost calls with one of the accessor's methods)."""
    import inspect

    import xarray as xr

    from splinelab.xarray import METHODS

    calls = {name: 0 for name in XARRAY_SWAPPED}
    depth = [0]
    for cls in (xr.DataArray, xr.Dataset):
        name = f"{cls.__name__}.interp"
        original = cls.interp
        signature = inspect.signature(original)

        def interp(self, *args, _name=name, _original=original, _signature=signature, **kwargs):
            try:
                bound = _signature.bind(self, *args, **kwargs)
            except TypeError:
                return _original(self, *args, **kwargs)   # xarray's own error
            bound.apply_defaults()
            a = bound.arguments
            if a["method"] not in METHODS:
                return _original(self, *args, **kwargs)
            outermost = not depth[0]
            calls[_name] += outermost
            depth[0] += 1
            try:
                if not use_splinelab:
                    return _original(self, *args, **kwargs)
                extra = {"method_non_numeric": a["method_non_numeric"]} if "method_non_numeric" in a else {}
                return self.splinelab.interp(a["coords"], a["method"], assume_sorted=a["assume_sorted"],
                                             kwargs=a["kwargs"], **extra, **a["coords_kwargs"])
            finally:
                depth[0] -= 1

        cls.interp = functools.wraps(original)(interp)
    return calls


@pytest.hookimpl(tryfirst=True)
def pytest_load_initial_conftests(early_config, parser, args):
    on = early_config.known_args_namespace.splinelab_swap == "on"
    early_config._splinelab_swap = on
    early_config._splinelab_target = early_config.known_args_namespace.splinelab_target
    early_config._splinelab_calls = (install_xarray if early_config._splinelab_target == "xarray" else install)(on)


def pytest_report_header(config):
    import scipy

    import splinelab

    what = "xarray's interp" if config._splinelab_target == "xarray" else "scipy's functions"
    return (f"splinelab swap of {what}: {'on' if config._splinelab_swap else 'off'} (scipy {scipy.__version__}, "
            f"splinelab {splinelab.__version__})")


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
    skipped, xfailed, xpassed; and the tests during which a call reached
    the installed functions."""

    def __init__(self, path, calls):
        self.path, self.calls = path, calls
        self.outcomes = {}
        self.reached = []

    @pytest.hookimpl(hookwrapper=True)
    def pytest_runtest_protocol(self, item, nextitem):
        before = sum(self.calls.values())
        yield
        if sum(self.calls.values()) > before:
            self.reached.append(item.nodeid)

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
            json.dump({"outcomes": self.outcomes, "calls": self.calls, "reached": sorted(self.reached)}, f,
                      indent=0, sort_keys=True)


def pytest_configure(config):
    path = config.getoption("splinelab_outcomes")
    if path:
        config.pluginmanager.register(_Outcomes(path, config._splinelab_calls), "splinelab_outcomes")
