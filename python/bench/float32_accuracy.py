"""The float32 accuracy sweep of issue 42 (python/tests/float32_sweep.py:
the eight functions, orders 0-5, every mode, 1-D to 3-D) on scipy and on
splinelab side by side (not run by CI):

    .venv/bin/python python/bench/float32_accuracy.py

One line per library and dtype (float32, complex64, float16; splinelab
also with compute="float32"): outputs compared, the share equal to the
float64 result rounded once (each library's own float64 result on the
widened data), the largest distance in units in the last place of the
narrow dtype and the call where it is, and the calls refused (scipy
refuses float16). Also spline_filter with output=float32 on 2-D and 3-D
data, where scipy rounds after every axis: the largest distance of each
library's result from its float64 result rounded once.
"""

import os
import sys

import numpy as np
import scipy.ndimage as ndi

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))

import splinelab  # noqa: E402
from float32_sweep import MODES, data, sweep, ulps  # noqa: E402


def main():
    print(f"{'library':<28}{'dtype':<10}{'outputs':>9}{'equal %':>10}{'worst ulps':>12}  where; refused")
    rows = [("scipy 1.17.1", ndi, {}), ("splinelab", splinelab, {}),
            ("splinelab compute=float32", splinelab, {"compute": "float32"})]
    for dtype in (np.float32, np.complex64, np.float16):
        for label, lib, kw in rows:
            count, equal, worst, where, refused = sweep(lib, dtype, **kw)
            share = 100.0 * equal / count if count else float("nan")
            print(f"{label:<28}{np.dtype(dtype).name:<10}{count:>9}{share:>10.3f}{worst:>12.3g}  {where}; {refused}")
    print()
    print("spline_filter(x, output=float32), orders 2-5, every mode: worst ulps from float64 rounded once")
    for shape in ((64, 48), (20, 18, 16)):
        x = data(shape, np.float32, seed=5)
        worst = {"scipy": 0.0, "splinelab": 0.0}
        for order in (2, 3, 4, 5):
            for mode in MODES:
                ref = splinelab.spline_filter(x.astype(np.float64), order=order, mode=mode).astype(np.float32)
                for label, lib in (("scipy", ndi), ("splinelab", splinelab)):
                    got = lib.spline_filter(x, order=order, mode=mode, output=np.float32)
                    worst[label] = max(worst[label], float(ulps(got, ref).max()))
        print(f"  {shape}: scipy {worst['scipy']:.3g}, splinelab {worst['splinelab']:.3g}")


if __name__ == "__main__":
    main()
