"""
Bernstein conditioning
======================

The Vandermonde matrix of polynomial interpolation is far better conditioned in
the Bernstein basis than in the monomial one (seed 001). Here numpy computes
``cond_2`` of both matrices for equispaced nodes in f64, and
:func:`splinelab.check` ``("cond", ...)`` computes the same condition numbers in
MPFR from the exact nodes and says how many digits numpy's got right. The
reference values come back in the check's folder (``reference.npy``).
"""

import os
import pathlib
import tempfile
from math import comb

import matplotlib.pyplot as plt
import numpy as np

import splinelab

QUICK = os.environ.get("SPLINELAB_GALLERY") == "quick"
degrees = list(range(2, 21 if QUICK else 31, 2 if QUICK else 1))


def vandermonde(nodes, basis):
    n = len(nodes) - 1
    if basis == "monomial":
        return np.vander(nodes, n + 1, increasing=True)
    return np.array([[comb(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)] for t in nodes])


node_sets = [np.linspace(0, 1, n + 1) for n in degrees]
folder = pathlib.Path(tempfile.mkdtemp())
fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
for basis, color in (("bernstein", "C0"), ("monomial", "C3")):
    ours = np.array([np.linalg.cond(vandermonde(x, basis)) for x in node_sets])
    r = splinelab.check("cond", nodes=node_sets, values=ours, basis=basis, norm="2", out=folder / basis)
    reference = np.load(folder / basis / "reference.npy")
    digits = np.clip(-np.log10(np.abs(ours - reference) / reference + 1e-17), 0, 17)
    left.semilogy(degrees, reference, "-", color=color, label=f"{basis}: MPFR reference")
    left.semilogy(degrees, ours, "x", color=color, label=f"{basis}: numpy, f64")
    right.plot(degrees, digits, "o-", color=color, label=basis)
    print(f"{basis:10s}: cond_2 at degree {degrees[-1]} = {reference[-1]:.3e}; numpy's f64 value has "
          f"{digits[-1]:.1f} correct digits ({r['reference_bits']} bits reference)")
left.set_xlabel("degree")
left.set_ylabel("cond_2 of the Vandermonde matrix")
left.set_title("equispaced nodes on [0, 1]")
left.legend(fontsize=8)
left.grid(alpha=0.3)
right.set_xlabel("degree")
right.set_ylabel("correct digits of numpy.linalg.cond")
right.set_title("judged by splinelab.check('cond')")
right.legend()
right.grid(alpha=0.3)
plt.show()
