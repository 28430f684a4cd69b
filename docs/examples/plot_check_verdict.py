"""
Checking your own implementation with ``check``
===============================================

:func:`splinelab.check` judges numbers you computed against a reference
computed from your exact inputs (MPFR at two precisions that must agree, or
exact rationals), and against the error a backward-stable computation would make
there from the problem's own conditioning: an element fails when its error
exceeds 8 times that *stable bound*. No tolerance to choose.

Here the numbers under test are scipy's quintic prefilter of 8 samples, with the
half-sample ``reflect`` rule (whose causal initialisation for short lines loses
digits: scipy issue gh-24550) and with the whole-sample ``mirror`` rule.
"""

import pathlib
import tempfile

import matplotlib.pyplot as plt
import numpy as np
from scipy import ndimage

import splinelab

samples = np.random.default_rng(3).uniform(-1, 1, 8)
folder = pathlib.Path(tempfile.mkdtemp())
results = {}
for mode in ("reflect", "mirror"):
    coeffs = ndimage.spline_filter1d(samples, order=5, mode=mode)
    r = splinelab.check("prefilter", samples=samples, coeffs=coeffs, degree=5, mode=mode, out=folder / mode)
    results[mode] = r
    w = r["worst_excess"]
    print(f"{mode:8s}: verdict {r['verdict']}, correct digits >= {r['digits_min']:.2f}, "
          f"worst excess {w['excess']:.3g} x the stable bound at index {w['index']}, "
          f"digits lost beyond the conditioning {r['digits_lost']:.2f}")

fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
for mode, marker in (("reflect", "o"), ("mirror", "s")):
    error = np.load(folder / mode / "error.npy")
    bound = np.load(folder / mode / "bound.npy")
    ax.semilogy(np.abs(error) / bound, marker + "-", label=f"{mode}: {results[mode]['verdict']}")
ax.axhline(8, color="k", ls=":", label="fail above 8 x the stable bound")
ax.set_xlabel("coefficient index")
ax.set_ylabel("|error| / stable bound")
ax.set_title("scipy 1.17's quintic prefilter of 8 samples, judged by splinelab.check")
ax.legend()
ax.grid(alpha=0.3)
plt.show()
