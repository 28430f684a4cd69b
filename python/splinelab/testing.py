"""Accuracy assertions for your own test suite (pytest or any runner).

:func:`assert_check` takes the same inputs as :func:`splinelab.check` and
raises ``AssertionError`` when the check fails, with the command line's
summary as the message: the worst element (index, ulps, relative and
absolute error), the correct digits, and against the stable bound the worst
excess (error / bound, the element's error and bound) and the digits lost
beyond what the problem's conditioning explains.

No tolerance to choose: the verdict is the check's default, every element
within ``8 ×`` the error a backward-stable computation would make from the
problem's own conditioning (``splinelab.check``'s ``stable_bound``), so the
threshold follows the data and never drifts with edits to the test.
``max_ulps=`` adds a gate of your own; ``cond`` has no stable bound and
needs it.

With the pytest plugin enabled (``pytest --splinelab-report DIR``, see
:mod:`splinelab.pytest_plugin`), each call also writes its page and
figures under ``DIR``, and ``DIR/summary.json`` feeds ``splinelab compare``.

>>> import numpy as np, splinelab
>>> from splinelab.testing import assert_check
>>> s = np.array([1.0, 2.0, 0.5, 3.0, 1.0, 0.0, 2.0, 1.0])
>>> c = splinelab.spline_filter1d(s, order=3, mode="mirror")
>>> assert_check("prefilter", samples=s, coeffs=c, degree=3)["verdict"]
'pass'
>>> c[0] *= 1 + 1e-9  # a bug: the first coefficient off by 1e-9
>>> assert_check("prefilter", samples=s, coeffs=c, degree=3)  # doctest: +ELLIPSIS
Traceback (most recent call last):
    ...
AssertionError: check prefilter: fail (8 elements, f64 ulps)
...
"""

from __future__ import annotations

import os
from typing import Any

from ._check import _run

__all__ = ["assert_check"]

# Set by the pytest plugin while it is enabled: (kind, name) -> folder for
# the check's page, or None to write nothing.
_recorder = None


def assert_check(kind: str, /, *, name: str | None = None, **inputs: Any) -> dict[str, Any]:
    """Check your numbers as :func:`splinelab.check` does; raise unless the verdict is 'pass'.

    Parameters
    ----------
    kind : str
        The check's kind, as :func:`splinelab.check` (positional only).
    name : str, optional
        Labels the check in the pytest plugin's report (default: the test's
        node id, ``-2``, ``-3``, ... for further checks in one test).
    **inputs
        :func:`splinelab.check`'s keywords for ``kind``; ``out=`` writes
        the check's page there instead of the plugin's folder.

    Returns
    -------
    dict
        The check's dict, on a pass.

    Raises
    ------
    AssertionError
        The verdict is not 'pass'; the message is the command line's
        summary (and the page's folder where one was written).
    ValueError
        A kind judged without a stable bound and without ``max_ulps``
        (``cond``), which could only fail on NaN.

    Notes
    -----
    Cost: the check's (one certified reference per element, see
    :func:`splinelab.check`), plus the page when it is written.

    Examples
    --------
    >>> import numpy as np, splinelab
    >>> from splinelab.testing import assert_check
    >>> s = np.array([1.0, 2.0, 0.5, 3.0, 1.0, 0.0, 2.0, 1.0])
    >>> assert_check("prefilter", samples=s, coeffs=splinelab.spline_filter1d(s), degree=3)["verdict"]
    'pass'
    """
    __tracebackhide__ = True  # pytest shows the caller's line, not this one
    if inputs.get("out") is None and _recorder is not None:
        inputs["out"] = _recorder(kind, name)
    result, summary = _run(kind, inputs)
    if result.get("verdict_basis") == "finite-only":
        raise ValueError(
            f"assert_check({kind!r}) needs max_ulps=: {result.get('no_verdict_reason') or 'no stable bound'}"
        )
    if result["verdict"] != "pass":
        where = f"\npage: {os.fspath(inputs['out'])}" if inputs.get("out") is not None else ""
        raise AssertionError(summary.rstrip() + where)
    return result
