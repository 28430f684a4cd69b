"""Who is right where splinelab and scipy 1.17.1 differ most on a 3-D
quintic zoom (test_resample.py's 3-D case, mode mirror, zoom 1.37): the 300
output samples of largest disagreement judged by ``splinelab.check('interp')``
(the MPFR reference evaluation of the same spline). Not run by CI:

    .venv/bin/python python/bench/resample_accuracy.py

Prints the largest disagreement and each side's worst error there, in ulps
of max|value|.
"""

import numpy as np
from scipy import ndimage

import splinelab

EPS = np.finfo(np.float64).eps


def main():
    x = np.random.default_rng(3).uniform(-1, 1, (24, 25, 27))
    z = 1.37
    out_shape = [int(round(n * z)) for n in x.shape]
    axes = [np.arange(m) * ((n - 1) / (m - 1)) for n, m in zip(x.shape, out_shape)]
    ours, ref = splinelab.zoom(x, z, order=5, mode="mirror"), ndimage.zoom(x, z, order=5, mode="mirror")
    scale = np.abs(ref).max()
    diff = np.abs(ours - ref).ravel()
    top = np.argsort(diff)[-300:]
    idx = np.unravel_index(top, ours.shape)
    coords = np.stack([axes[a][idx[a]] for a in range(3)])
    print(f"largest disagreement: {diff[top[-1]] / (EPS * scale):.1f} ulps of max")
    for name, v in [("splinelab", ours.ravel()[top]), ("scipy", ref.ravel()[top])]:
        r = splinelab.check("interp", samples=x, coordinates=coords, values=v, degree=5, mode="mirror")
        # check's max_ulps_scaled: the largest error in ulps of max|value|
        # over these 300 samples; rescaled to the whole output's max.
        worst = r["max_ulps_scaled"] * np.abs(v).max() / scale
        print(f"{name}: largest error vs MPFR {worst:.1f} ulps of max, verdict {r['verdict']} ({r['verdict_basis']})")


if __name__ == "__main__":
    main()
