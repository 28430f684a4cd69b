"""
The certified truncation width against tolerance and degree
===========================================================

The truncated prefilter convolves with the S-spline coefficients ``c_j``,
``|j| <= n``. :func:`splinelab.truncation_width` gives the smallest half-width
``n`` whose tail ``sum_{|j|>n} |c_j|`` is certified (in MPFR, rounded up) below the
tolerance. The width grows linearly in ``-log10(tol)``, with a slope set by the
degree's largest pole: higher degrees decay more slowly and need wider kernels.
"""

import os

import matplotlib.pyplot as plt
import numpy as np

import splinelab

QUICK = os.environ.get("SPLINELAB_GALLERY") == "quick"
degrees = [2, 3, 5, 9] if QUICK else [2, 3, 4, 5, 7, 9, 13]
tols = np.logspace(-3, -15, 5 if QUICK else 13)

fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
for d in degrees:
    widths = [splinelab.truncation_width(degree=d, tol=t)["n"] for t in tols]
    bounds = [splinelab.filter_bound(d, t)["bound"] for t in tols]
    left.plot(-np.log10(tols), widths, "o-", label=f"degree {d}")
    right.loglog(tols, bounds, "o-", label=f"degree {d}")
    print(f"degree {d}: n = {widths}")
left.set_xlabel("-log10(tol)")
left.set_ylabel("certified half-width n")
left.set_title("truncation_width(degree, tol)['n']")
left.grid(alpha=0.3)
left.legend()
right.loglog(tols, tols, "k:", label="tol")
right.set_xlabel("tol")
right.set_ylabel("certified tail bound b")
right.set_title("filter_bound(degree, tol)['bound'] <= tol")
right.invert_xaxis()
right.grid(alpha=0.3)
plt.show()
