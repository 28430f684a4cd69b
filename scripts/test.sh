#!/usr/bin/env bash
# The test command: set up the machine, then run every test (unit, property,
# integration and doc tests), then the Python package's (scripts/python.sh
# builds it into .venv; pytest runs python/tests and the docstring examples),
# then scripts/downstream.sh (reproject's, nibabel's, sunpy's and scipy's own
# interpolation tests with splinelab swapped in for scipy.ndimage's functions),
# then the documentation (scripts/docs.sh: warnings as errors, every
# gallery example and the pages' doctests run, every local link resolves,
# every page opens in headless Chromium).
# Tests run in the release profile and with the same features as the report
# and the Python extension (core/Cargo.toml pins them), so the three compile
# each crate once; each crate's integration tests are one test binary
# (verify/tests/it, reports/tests/it), not one per file (issue 38).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
[ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
read -r -a features <<<"$(bash scripts/gmp_features.sh)"
cargo test --release --workspace "${features[@]+"${features[@]}"}" "$@"
bash scripts/python.sh
.venv/bin/python -m pytest -q -p no:cacheprovider --doctest-modules python/splinelab python/tests
# Downstream libraries' own tests (and scipy's) with splinelab swapped in.
bash scripts/downstream.sh
# The documentation site (its gallery at full size: about 10 s of examples).
bash scripts/docs.sh
