#!/usr/bin/env python3
"""Writes numpy.inv: the numpy names these pages cross-reference.

numpy's published inventory (https://numpy.org/doc/stable/objects.inv)
cannot be downloaded on this project's machines (only package registries
are reachable, and no Debian package of this release ships numpy's HTML
documentation), so this file lists the names the pages and docstrings link
to, at the addresses numpy's documentation gives them: autosummary pages
``reference/generated/NAME.html#NAME`` (the layout of every numpy release
since 1.x: numpy 1.13's published inventory has ``numpy.memmap``,
``numpy.ndarray``, ``numpy.load``, ``numpy.pad``, ``numpy.asarray`` and
``numpy.dtype`` exactly there), the scalar types on
``reference/arrays.scalars.html`` and the random generator on
``reference/random/generator.html``. Add a name here when a page needs it,
then run ``python docs/_intersphinx/make_numpy_inv.py``; where the network
allows, replace the file by the published one instead (README.md).
"""

import pathlib
import zlib

GENERATED = "reference/generated/{0}.html#{0}"

ENTRIES = [
    ("numpy.ndarray", "py:class", GENERATED),
    ("numpy.memmap", "py:class", GENERATED),
    ("numpy.dtype", "py:class", GENERATED),
    ("numpy.load", "py:function", GENERATED),
    ("numpy.save", "py:function", GENERATED),
    ("numpy.asarray", "py:function", GENERATED),
    ("numpy.pad", "py:function", GENERATED),
    ("numpy.isnan", "py:data", GENERATED),
    ("numpy.allclose", "py:function", GENERATED),
    ("numpy.lib.format.open_memmap", "py:function", GENERATED),
    ("numpy.exceptions.AxisError", "py:exception", GENERATED),
    ("numpy.float64", "py:attribute", "reference/arrays.scalars.html#{0}"),
    ("numpy.float32", "py:attribute", "reference/arrays.scalars.html#{0}"),
    ("numpy.random.default_rng", "py:function", "reference/random/generator.html#{0}"),
    ("numpy.random.Generator", "py:class", "reference/random/generator.html#{0}"),
]


def main():
    lines = []
    for name, role, uri in sorted(ENTRIES):
        lines.append(f"{name} {role} 1 {uri.format(name)} -")
    header = (
        "# Sphinx inventory version 2\n# Project: NumPy\n# Version: stable\n"
        "# The remainder of this file is compressed using zlib.\n"
    )
    out = pathlib.Path(__file__).with_name("numpy.inv")
    out.write_bytes(header.encode() + zlib.compress(("\n".join(lines) + "\n").encode()))
    print(f"{out}: {len(lines)} names")


if __name__ == "__main__":
    main()
