"""The downstream tests that fail with splinelab swapped in, each with its
reason (README.md in this folder). splinelab_swap marks them
xfail(strict=True) when swapped, and run.py requires each to pass on scipy:
a fixed one shows as a strict XPASS failure, and its entry goes.

Only differences where splinelab is more accurate than scipy belong here,
each with the figure that shows it. There are none at present: reproject's
37 float32 tests (two routes compared at ``rtol=1e-7`` on float32 data)
pass since float32 input is computed in float64 and rounded once, as scipy
computes it (issue 42), and its NaN-coordinate test passes under
``nan_policy="propagate"`` (issue 37, scipy's values at NaN coordinates).
"""

KNOWN: dict[str, str] = {}
