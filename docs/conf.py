"""Sphinx configuration of splinelab's documentation (built by scripts/docs.sh).

Everything the build reads is in the repository: the package's own
docstrings (autodoc/autosummary, numpydoc), the gallery scripts in
``examples/`` (sphinx-gallery, executed at build time), the committed report
baseline ``reports/baseline/summary.json`` (the ``baseline-figures``
directive of ``_ext/splinelab_docs.py``) and intersphinx inventories bundled
in ``_intersphinx/`` (no network at build time). Warnings are errors
(``-W --keep-going -n`` in scripts/docs.sh).
"""

import os
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE / "_ext"))

import splinelab  # noqa: E402  (the built extension in .venv: scripts/python.sh)

project = "splinelab"
author = "the splinelab developers"
copyright = "the splinelab developers"
release = version = splinelab.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "myst_parser",
    "splinelab_docs",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_generated", "_intersphinx", "examples", "README.md", "**/README.md", "_templates",
                    "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip"]
templates_path = ["_templates"]
nitpicky = True

# -- MyST (Markdown pages) ---------------------------------------------------
myst_enable_extensions = ["colon_fence", "dollarmath", "deflist"]
myst_heading_anchors = 4

# -- autodoc / autosummary / numpydoc ----------------------------------------
autosummary_generate = True
autodoc_default_options = {"members": False}
autodoc_typehints = "none"  # the docstrings state the types (numpydoc)
numpydoc_show_class_members = False
# Types in Parameters / Returns / Raises link where they name something
# documented (numpy's, Python's, ours); the plain words below stay text.
numpydoc_xref_param_type = True
# numpydoc links array_like and scalar to numpy's glossary and scalar page by
# default; the bundled numpy.inv has neither (docs/_intersphinx/README.md), so
# they map to themselves and stay text.
numpydoc_xref_aliases = {"ndarray": "numpy.ndarray", "dtype": "numpy.dtype", "callable": "callable",
                         "array_like": "array_like", "scalar": "scalar"}
numpydoc_xref_ignore = {"optional", "or", "of", "array_like", "scalar", "sequence", "index", "ints", "type",
                        "default", "DataArray", "Dataset"}  # xarray's: no bundled inventory
# numpydoc's validation: every check but the ones listed (See Also, an
# extended summary and an example everywhere, one-line summaries, closing
# quotes on their own line, capitalised descriptions, infinitive verbs), so
# every parameter is documented, in the signature's order, with a type, and
# every docstring has its sections. MAX_DEGREE is an int (its doc is int's).
numpydoc_validation_checks = {"all", "SA01", "EX01", "ES01", "SS06", "GL02", "PR08", "SS02", "SS05"}
numpydoc_validation_exclude = {r"^splinelab\.MAX_DEGREE$"}

# -- intersphinx: inventories bundled in the repository ----------------------
# Provenance of each file: docs/_intersphinx/README.md.
_INV = HERE / "_intersphinx"
intersphinx_mapping = {
    "python": ("https://docs.python.org/3", str(_INV / "python.inv")),
    "numpy": ("https://numpy.org/doc/stable", str(_INV / "numpy.inv")),
    "scipy": ("https://docs.scipy.org/doc/scipy", str(_INV / "scipy.inv")),
    "dask": ("https://docs.dask.org/en/stable", str(_INV / "dask.inv")),
}
intersphinx_timeout = 1

# -- sphinx-gallery -----------------------------------------------------------
# SPLINELAB_GALLERY=quick (CI) runs every example with its small sizes
# (each script reads the variable); the full profile the same scripts at
# their documented sizes.
_gallery_profile = os.environ.get("SPLINELAB_GALLERY", "full")
sphinx_gallery_conf = {
    "examples_dirs": str(HERE / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "download_all_examples": False,
    "show_memory": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "reference_url": {"splinelab": None},
    "doc_module": ("splinelab",),
    "backreferences_dir": "_generated/backreferences",
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "run_stale_examples": True,
    # Each example's page shows its own run time; the summary page of all
    # run times loads its table script from a CDN, which this offline site
    # does not reach.
    "write_computation_times": False,
}

# -- HTML -----------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"splinelab {release}"
html_static_path = ["_static"]
html_css_files = ["splinelab.css"]
html_theme_options = {
    "navigation_with_keys": False,
    "show_prev_next": True,
    "header_links_before_dropdown": 5,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_sidebars = {"index": [], "search": []}
html_favicon = "_static/favicon.svg"
# The theme's light/dark switch starts from this mode (without it the theme
# logs "Got invalid theme mode" on a first visit).
html_context = {"default_mode": "auto"}
html_show_sourcelink = False
html_copy_source = False
html_last_updated_fmt = None

# Generated reference material (scripts/docs.sh writes it before the build):
# the command line's --help page and man pages, the Rust API (cargo doc) and
# the quick report, copied beside the site and linked from it.
# scripts/docs.sh puts the quick report and the rustdoc there; the
# extension writes the man pages at builder-inited.
(HERE / "_generated" / "extra").mkdir(parents=True, exist_ok=True)
html_extra_path = ["_generated/extra"]
