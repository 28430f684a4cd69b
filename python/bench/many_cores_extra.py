"""splinelab's own many-core rows, beside ../shared/bench/many_cores.py (issues 49-51).

Runs on the 16-core device machine after many_cores.py (same wheel, same process
conventions: min of N after a warm-up, times in ms, one JSON row per case) and
writes extra.json into $BENCH_OUT:

- rgi_*: RegularGridInterpolator cubic construction + 10^5 points with 1..16
  threads (scipy only on the small case: its iterative solve takes minutes),
- small_*: the fixed cost of tiny calls (issue 50), scipy vs splinelab,
- affine_8000sq_f32: the in-memory twin of issue 51's cluster case,
- tol_1e7_into: the certified tol route of 10^7 samples into a given output
  against np.copyto of the same bytes (issue 50's memory wall).

    BENCH_OUT=$OUT python3 python/bench/many_cores_extra.py
"""
import json
import os
import time

import numpy as np
import scipy
import scipy.ndimage as ndi
from scipy.interpolate import RegularGridInterpolator as SciRGI

import splinelab as sl

THREADS = [1, 2, 4, 8, 16]
rng = np.random.default_rng(7)
out = {"scipy": scipy.__version__, "splinelab": sl.__version__, "cores": os.cpu_count(), "rows": []}


def tmin(f, n=5):
    f()
    best = 1e9
    for _ in range(n):
        t = time.perf_counter()
        f()
        best = min(best, time.perf_counter() - t)
    return best


def row(name, timings, **extra):
    r = {"case": name, **{k: round(v * 1e3, 4) for k, v in timings.items()}, **extra}
    out["rows"].append(r)
    print(json.dumps(r), flush=True)


def guarded(f):
    try:
        f()
    except Exception as e:  # noqa: BLE001 - one failed case must not stop the others
        print("case failed:", repr(e)[:300], flush=True)
        out.setdefault("errors", []).append(repr(e)[:300])


def rgi_case(shape, with_scipy):
    grid = [np.cumsum(rng.uniform(0.5, 1.5, n)) for n in shape]
    values = rng.standard_normal(shape)
    xi = np.column_stack([rng.uniform(g[0], g[-1], 100_000) for g in grid])
    t = {}
    for k in THREADS:
        t[f"sl_{k}T"] = tmin(lambda: sl.RegularGridInterpolator(grid, values, method="cubic", threads=k)(xi), n=3)
    extra = {}
    if with_scipy:
        t0 = time.perf_counter()
        ref = SciRGI(grid, values, method="cubic")(xi)
        t["scipy_1T"] = time.perf_counter() - t0
        ours = sl.RegularGridInterpolator(grid, values, method="cubic")(xi)
        extra["scipy_vs_exact_rel"] = float(np.max(np.abs(ref - ours)) / np.max(np.abs(values)))
    row("rgi_cubic_" + "x".join(map(str, shape)), t, **extra)


def small_cases():
    img8 = rng.standard_normal((8, 8))
    img43 = rng.standard_normal((43, 43))
    img16 = rng.standard_normal((16, 16))
    p1 = np.array([[3.3], [4.1]])
    p25 = rng.uniform(0, 42, (2, 25))
    cases = {
        "small_mapc_1pt_8sq_o1": (lambda m: m.map_coordinates(img8, p1, order=1)),
        "small_mapc_25pt_43sq_o3": (lambda m: m.map_coordinates(img43, p25, order=3)),
        "small_shift_16sq_o1": (lambda m: m.shift(img16, 0.3, order=1)),
        "small_rotate_16sq_o3": (lambda m: m.rotate(img16, 10, order=3, reshape=False)),
    }
    for name, f in cases.items():
        row(name, {"scipy_1T": tmin(lambda: f(ndi), n=200), "sl_default": tmin(lambda: f(sl), n=200)})


def affine_case():
    img = rng.standard_normal((8000, 8000)).astype(np.float32)
    c, s = np.cos(0.1), np.sin(0.1)
    m = np.array([[c, -s], [s, c]])
    off = np.array([4000, 4000]) - m @ np.array([4000, 4000])
    t = {"scipy_1T": tmin(lambda: ndi.affine_transform(img, m, off, order=3), n=1)}
    for k in THREADS:
        t[f"sl_{k}T"] = tmin(lambda: sl.affine_transform(img, m, off, order=3, threads=k), n=2)
    ref = ndi.affine_transform(img.astype(np.float64), m, off, order=3)
    ours = sl.affine_transform(img.astype(np.float64), m, off, order=3)
    row("affine_8000sq_f32_cubic", t, f64_sl_vs_scipy_rel=float(np.max(np.abs(ours - ref)) / np.max(np.abs(ref))))


def tol_case():
    x = rng.standard_normal(10**7)
    dst = np.empty_like(x)
    t = {"copy_1T": tmin(lambda: np.copyto(dst, x))}
    for k in THREADS:
        t[f"sl_tol_{k}T"] = tmin(lambda: sl.spline_filter1d(x, 3, output=dst, threads=k, tol=1e-12))
        t[f"sl_exact_{k}T"] = tmin(lambda: sl.spline_filter1d(x, 3, output=dst, threads=k))
    row("tol_1e7_cubic_into", t)


guarded(lambda: rgi_case((60, 60, 20), True))
guarded(lambda: rgi_case((300, 300, 40), False))
guarded(lambda: rgi_case((4000, 4000), False))
guarded(small_cases)
guarded(tol_case)
guarded(affine_case)
json.dump(out, open(os.path.join(os.environ.get("BENCH_OUT", "."), "extra.json"), "w"), indent=1)
