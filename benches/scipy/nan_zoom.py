"""scipy's answer for an image with missing pixels, read by the report's
"Missing data" part (reports/src/report/engine_nan.rs, issue 37).

A smooth 64x64 field with three pixels masked as NaN (two adjacent, one
alone), zoomed by 1.5 with scipy.ndimage.zoom(order=3, mode='mirror'): the
recursive prefilter carries a NaN along every line, then along every axis,
so every one of the 96x96 outputs is NaN. The report sets it beside
splinelab's nan_policy="local" result of the same call.

Files written beside this script (float64 .npy):
  nan_field.npy        the 64x64 input, NaN at (16, 20), (16, 21), (44, 46)
  nan_zoom_scipy.npy   zoom(nan_field, 1.5, order=3, mode='mirror'), 96x96

Run once with scipy 1.17.1 (not by CI: the report needs no Python):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install scipy==1.17.1 numpy
    /tmp/venv/bin/python benches/scipy/nan_zoom.py
"""
import pathlib

import numpy as np
import scipy
from scipy import ndimage

HERE = pathlib.Path(__file__).resolve().parent
MISSING = [(16, 20), (16, 21), (44, 46)]


def field(n=64):
    """A smooth field in about [-1.3, 1.3]: two waves and a gentle bowl."""
    i, j = np.meshgrid(np.arange(n, dtype=float), np.arange(n, dtype=float), indexing="ij")
    return np.sin(2 * np.pi * i / 37) * np.cos(2 * np.pi * j / 53) + 0.3 * ((i - 30) / 32) ** 2


def main():
    a = field()
    for p in MISSING:
        a[p] = np.nan
    z = ndimage.zoom(a, 1.5, order=3, mode="mirror")
    np.save(HERE / "nan_field.npy", a)
    np.save(HERE / "nan_zoom_scipy.npy", z)
    print(f"scipy {scipy.__version__}: zoom {a.shape} -> {z.shape}, "
          f"{np.isnan(z).sum()} of {z.size} outputs NaN")


if __name__ == "__main__":
    main()
