"""
A memory-mapped array sampled at a few points
=============================================

Data on disk, read through :class:`numpy.memmap` (here a ``.npy`` file opened with
:func:`numpy.lib.format.open_memmap`), can be passed to
:func:`splinelab.map_coordinates` as any array: the function reads it once into
its result and filters that. The file here is written block by block with a known
smooth function, so the interpolated values at a few hundred points along a
curve can be compared with the function itself.
"""

import os
import pathlib
import tempfile

import matplotlib.pyplot as plt
import numpy as np

import splinelab

QUICK = os.environ.get("SPLINELAB_GALLERY") == "quick"
n = 512 if QUICK else 2048  # 2 MiB or 32 MiB of float64 on disk


def field(i, j):
    return np.sin(i / 37.0) * np.cos(j / 53.0) + 0.25 * np.sin((i + j) / 71.0)


folder = pathlib.Path(tempfile.mkdtemp())
path = folder / "field.npy"
disk = np.lib.format.open_memmap(path, mode="w+", dtype=np.float64, shape=(n, n))
for start in range(0, n, 256):  # written in blocks, as a large file would be
    i = np.arange(start, min(start + 256, n))[:, None]
    disk[start:start + len(i)] = field(i, np.arange(n)[None, :])
disk.flush()
del disk

data = np.load(path, mmap_mode="r")  # a read-only numpy.memmap
print(type(data).__name__, data.shape, f"{data.nbytes / 2**20:.0f} MiB on disk")
t = np.linspace(0, 1, 300)
points = np.array([(n - 1) * (0.1 + 0.8 * t), (n - 1) * (0.5 + 0.4 * np.sin(2 * np.pi * t))])
values = splinelab.map_coordinates(data, points, order=5, mode="mirror")
error = np.abs(values - field(*points))
print(f"max |value - field| over {len(t)} points: {error.max():.2e}")

fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 5), layout="constrained", sharex=True)
top.plot(t, values, label="map_coordinates(memmap, order=5)")
top.plot(t, field(*points), "k:", label="the function")
top.set_ylabel("value")
top.legend()
bottom.semilogy(t, np.maximum(error, 1e-17))
bottom.set_xlabel("position along the curve")
bottom.set_ylabel("|error|")
fig.suptitle(f"{n} x {n} float64 .npy file, memory-mapped, sampled at {len(t)} points")
plt.show()
path.unlink()
folder.rmdir()
