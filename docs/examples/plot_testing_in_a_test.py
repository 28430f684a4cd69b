"""
``splinelab.testing`` in a test
===============================

:func:`splinelab.testing.assert_check` is an assertion for your own test suite:
it raises ``AssertionError`` with the check's summary when your numbers are less
accurate than the problem's conditioning allows. Here a small test file checks
two implementations of the cubic prefilter: scipy's, and a hand-written truncated
convolution with too few taps. pytest runs it with the splinelab plugin enabled
(``--splinelab-report DIR``), which writes each check's page and a
``summary.json`` that ``splinelab compare`` can gate in CI.
"""

import json
import pathlib
import subprocess
import sys
import tempfile
import textwrap

import matplotlib.pyplot as plt
import numpy as np

folder = pathlib.Path(tempfile.mkdtemp())
(folder / "test_prefilter.py").write_text(textwrap.dedent('''
    import numpy as np
    from scipy import ndimage
    from splinelab.testing import assert_check

    x = np.random.default_rng(0).uniform(-1, 1, 200)

    def short_convolution(samples, taps=4):
        """A cubic prefilter truncated after `taps` coefficients: c_j = sqrt(3) (sqrt(3) - 2)^|j|."""
        pole = np.sqrt(3) - 2
        kernel = np.sqrt(3) * pole ** np.abs(np.arange(-taps, taps + 1))
        padded = np.pad(samples, taps, mode="reflect")  # numpy's "reflect" is scipy's "mirror"
        return np.convolve(padded, kernel, mode="valid")

    def test_scipy_prefilter():
        assert_check("prefilter", samples=x, coeffs=ndimage.spline_filter1d(x, order=3, mode="mirror"),
                     degree=3, mode="mirror")

    def test_short_convolution():
        assert_check("prefilter", samples=x, coeffs=short_convolution(x), degree=3, mode="mirror")
'''))
run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "--splinelab-report",
                      str(folder / "accuracy"), str(folder / "test_prefilter.py")],
                     capture_output=True, text=True, cwd=folder)
print(run.stdout[-2500:])
summary = json.loads((folder / "accuracy" / "summary.json").read_text())
for c in summary["checks"]:
    print(c["label"], c["verdict"], "digits lost:", c["digits_lost"])

labels = [c["label"].removeprefix("test_prefilter_py_") for c in summary["checks"]]
lost = [c["digits_lost"] for c in summary["checks"]]
fig, ax = plt.subplots(figsize=(7, 3), layout="constrained")
ax.barh(labels, lost, color=["#4e9a06" if c["verdict"] == "pass" else "#cc0000" for c in summary["checks"]])
ax.axvline(np.log10(8), color="k", ls=":", label="fail: more than log10(8) digits lost")
ax.set_xlabel("digits lost beyond the problem's conditioning (from DIR/summary.json)")
ax.legend(loc="lower right")
plt.show()
