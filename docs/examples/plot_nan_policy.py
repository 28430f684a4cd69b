"""
What a NaN does under each ``nan_policy``
=========================================

One missing sample in a 2-D field, zoomed by 2 with a cubic spline. scipy's
recursive prefilter carries the NaN along every line through it, so every output
is NaN (``nan_policy="propagate"``, the default, scipy's pattern);
``nan_policy="raise"`` refuses the input and names the sample; and
``nan_policy="local"`` keeps the NaN within :func:`splinelab.nan_reach` samples,
every other value within a certified bound of the exact spline of *any* filling
of the missing sample.
"""

import os

import matplotlib.pyplot as plt
import numpy as np

import splinelab

QUICK = os.environ.get("SPLINELAB_GALLERY") == "quick"
n = 64 if QUICK else 128
i, j = np.mgrid[0:n, 0:n]
field = np.sin(i / 9.0) * np.cos(j / 13.0)
field[n // 3, n // 2] = np.nan

propagate = splinelab.zoom(field, 2, order=3)
local = splinelab.zoom(field, 2, order=3, nan_policy="local", tol=1e-12)
try:
    splinelab.zoom(field, 2, order=3, nan_policy="raise")
except ValueError as e:
    raised = str(e)
print("raise:", raised)
reach = splinelab.nan_reach(3, 1e-12)
print(f"nan_reach(3, 1e-12) = {reach} samples; NaN outputs: propagate {np.isnan(propagate).mean():.0%}, "
      f"local {np.isnan(local).mean():.2%}")

cmap = plt.get_cmap("viridis").with_extremes(bad="red")
fig, axes = plt.subplots(1, 3, figsize=(10, 3.6), layout="constrained")
axes[0].imshow(propagate, cmap=cmap)
axes[0].set_title('"propagate" (scipy): all NaN')
axes[1].text(0.5, 0.5, "ValueError:\n" + raised.replace(" (", "\n("), ha="center", va="center", wrap=True)
axes[1].set_axis_off()
axes[1].set_title('"raise"')
axes[2].imshow(local, cmap=cmap)
axes[2].set_title(f'"local": NaN within {reach} samples')
for ax in (axes[0], axes[2]):
    ax.set_xticks([])
    ax.set_yticks([])
fig.suptitle("zoom(x, 2, order=3) with one missing sample (NaN in red)")
plt.show()
