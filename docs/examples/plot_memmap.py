"""
A memory-mapped array sampled at a few points
=============================================

A ``.npy`` file of 32 GiB (float64, 65536 x 65536: more than the 24 GiB of memory of the
machine these pages were written on;
4096 x 4096 in the quick profile), opened with ``np.load(..., mmap_mode="r")``, is
sampled at 300 points along a curve by :func:`splinelab.map_coordinates`, which takes
the local route by itself for so few points (:doc:`/large_arrays`): it reads only the
samples under the points' windows (the certified half-width around each tile) and
prefilters those, never the whole array.

The file is sparse: only a 600 x 600 block around the curve is written with a known
smooth function; every other sample reads as 0. So the values match the function only
if every window lies inside the written block — the comparison below is the evidence
that nothing outside was needed. Then a :class:`splinelab.Interpolant` over the same
memory map takes the same points (the same bits), and
:meth:`~splinelab.Interpolant.update` adds a bump to a block of samples without
writing the file or rebuilding the interpolant.
"""

import os
import pathlib
import tempfile
import time

import matplotlib.pyplot as plt
import numpy as np

import splinelab

QUICK = os.environ.get("SPLINELAB_GALLERY") == "quick"
n = 4096 if QUICK else 65536  # 128 MiB or 32 GiB of float64, apparent size


def field(i, j):
    return np.sin(i / 37.0) * np.cos(j / 53.0) + 0.25 * np.sin((i + j) / 71.0)


folder = pathlib.Path(tempfile.mkdtemp())
path = folder / "field.npy"
disk = np.lib.format.open_memmap(path, mode="w+", dtype=np.float64, shape=(n, n))
lo, hi = n // 2 - 300, n // 2 + 300  # the only block written
disk[lo:hi, lo:hi] = field(np.arange(lo, hi)[:, None], np.arange(lo, hi)[None, :])
disk.flush()
del disk
size = os.stat(path)
print(f"{n} x {n} float64: {size.st_size / 2**30:.2f} GiB apparent, "
      f"{size.st_blocks * 512 / 2**20:.0f} MiB allocated on disk")

data = np.load(path, mmap_mode="r")  # a read-only numpy.memmap
t = np.linspace(0, 1, 300)
points = np.array([n // 2 - 200 + 400 * t, n // 2 + 150 * np.sin(2 * np.pi * t)])
started = time.perf_counter()
values = splinelab.map_coordinates(data, points, order=5, mode="mirror")
print(f"map_coordinates of {len(t)} points: {time.perf_counter() - started:.2f} s")
error = np.abs(values - field(*points))
print(f"max |value - field| over {len(t)} points: {error.max():.2e}")

# %%
# The same spline, kept: an Interpolant
# -------------------------------------
# ``Interpolant`` keeps the tiles of coefficients it computed (within a byte
# budget) for the next call, and gives the same bits as ``map_coordinates``.
# ``update(key, values)`` changes samples as ``a[key] = values`` would — here a
# Gaussian bump (width 6 samples) on a 97 x 97 block under the curve — and
# recomputes only the cached coefficients within reach; the memory map is not
# written.

ip = splinelab.Interpolant(data, order=5, mode="mirror")
print("Interpolant gives map_coordinates' bits:", bool(np.array_equal(ip(points), values)))
ci, cj = n // 2 + 100, n // 2 - 150  # on the curve (t = 0.75)
bi, bj = np.arange(ci - 48, ci + 49)[:, None], np.arange(cj - 48, cj + 49)[None, :]


def bump(i, j):
    return np.exp(-((i - ci) ** 2 + (j - cj) ** 2) / (2 * 6.0**2))


ip.update((slice(ci - 48, ci + 49), slice(cj - 48, cj + 49)), field(bi, bj) + bump(bi, bj))
after = ip(points)
changed = np.abs(after - field(*points) - bump(*points))
print(f"after update: max |value - (field + bump)| = {changed.max():.2e}; "
      f"cache {ip.cache_info()}; the file unchanged: {bool(np.all(data[ci, cj - 2:cj + 3] == field(ci, np.arange(cj - 2, cj + 3))))}")

fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 5), layout="constrained", sharex=True)
top.plot(t, values, label="map_coordinates(memmap, order=5)")
top.plot(t, after, label="Interpolant after update")
top.plot(t, field(*points), "k:", label="the function")
top.set_ylabel("value")
top.legend(fontsize=8)
bottom.semilogy(t, np.maximum(error, 1e-17), label="map_coordinates vs field")
bottom.semilogy(t, np.maximum(changed, 1e-17), label="after update vs field + bump")
bottom.set_xlabel("position along the curve")
bottom.set_ylabel("|error|")
bottom.legend(fontsize=8)
fig.suptitle(f"{n} x {n} float64 .npy file, memory-mapped, sampled at {len(t)} points")
plt.show()
del data, ip
path.unlink()
folder.rmdir()
