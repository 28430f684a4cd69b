"""The headline case of issue 42 (not run by CI): 300x300 float32 normal
noise, 10^5 random points, cubic, mode='mirror', map_coordinates; each
library's float32 result against the float64 computation on the widened
data (scipy's float64 result: the reference of the issue's table):

    .venv/bin/python python/bench/float32_headline.py

One line per route (scipy 1.17.1, splinelab's default, splinelab
compute="float32"): max error / max|input|, the largest error in float32
ulps of the reference rounded to float32 (and the mean), and the share of
points failing ``rtol=1e-7`` (numpy's ``isclose`` with ``atol=0``).
"""

import numpy as np
import scipy.ndimage as ndi

import splinelab


def main():
    rng = np.random.default_rng(0)
    img = rng.normal(size=(300, 300)).astype(np.float32)
    pts = np.stack([rng.uniform(0, 299, 10**5) for _ in range(2)])
    ref = ndi.map_coordinates(img.astype(np.float64), pts, order=3, mode="mirror")
    ref_sl = splinelab.map_coordinates(img.astype(np.float64), pts, order=3, mode="mirror")
    print(f"reference: scipy's float64 result; splinelab's float64 result differs from it by "
          f"{np.abs(ref_sl - ref).max() / np.abs(img).max():.2g} of max|input|")
    step = np.spacing(np.abs(ref.astype(np.float32))).astype(np.float64)
    print(f"{'route':<28}{'maxerr/max|in|':>16}{'max ulps':>12}{'mean ulps':>11}{'fail rtol1e-7 %':>17}")
    routes = (("scipy 1.17.1", lambda: ndi.map_coordinates(img, pts, order=3, mode="mirror")),
              ("splinelab", lambda: splinelab.map_coordinates(img, pts, order=3, mode="mirror")),
              ("splinelab compute=float32",
               lambda: splinelab.map_coordinates(img, pts, order=3, mode="mirror", compute="float32")))
    for label, call in routes:
        got = call()
        assert got.dtype == np.float32, got.dtype
        err = np.abs(got.astype(np.float64) - ref)
        ulp = err / step
        fail = ~np.isclose(got.astype(np.float64), ref, rtol=1e-7, atol=0)
        print(f"{label:<28}{err.max() / np.abs(img).max():>16.2g}{ulp.max():>12.3g}{ulp.mean():>11.3g}"
              f"{100.0 * fail.mean():>17.3f}")


if __name__ == "__main__":
    main()
