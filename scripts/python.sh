#!/usr/bin/env bash
# Sets up the Python package: a virtual environment `.venv` at the
# repository root (created if missing), the Python packages the extension and
# its tests need (installed only when this list changes), and the extension
# itself built into it with `maturin develop --release`. The build shares the
# workspace's target directory and release profile (python/ is a workspace
# member), so it reuses the compiled rug/GMP/MPFR and splinelab crates.
# Safe and quick to rerun. Afterwards: `.venv/bin/python -c "import splinelab"`.
set -euo pipefail
cd "$(dirname "$0")/.."

py="${PYTHON:-python3}"
if ! command -v "$py" >/dev/null 2>&1; then
  echo "error: $py not found: install Python 3.10 or newer (with venv and pip) and rerun, or set PYTHON=/path/to/python3." >&2
  exit 1
fi
if [ ! -x .venv/bin/python ]; then
  echo "splinelab python: creating .venv with $("$py" --version 2>&1)" >&2
  "$py" -m venv .venv || {
    echo "error: '$py -m venv .venv' failed: install the venv module (Debian: python3-venv) and rerun." >&2
    exit 1
  }
fi

# scipy is pinned to the version that made the committed fixtures.
reqs=(maturin numpy "scipy==1.17.1" "dask[array]" distributed dask-image pytest hypothesis)
# Test extras (issue 45: the local route reads zarr arrays and HDF5 datasets
# a box at a time), pinned; zarr 3.1.6 is the last release for Python 3.11.
# xarray (issue 51: the splinelab accessor, python/tests/test_xarray.py),
# the newest release pip finds for Python 3.11; cftime (its accessor on
# non-standard calendars, python/tests/test_xarray_cftime.py) likewise.
# Installed apart: where they cannot be, the tests that need them fail
# saying so (python/tests/test_local_route.py), the rest still run.
extras=("zarr==3.1.6" "h5py==3.16.0" "xarray==2026.9.0" "cftime==1.6.6.1")
stamp=.venv/.splinelab-requirements
if [ "$(cat "$stamp" 2>/dev/null)" != "${reqs[*]} ${extras[*]}" ]; then
  echo "splinelab python: installing ${reqs[*]}" >&2
  .venv/bin/python -m pip install --quiet --upgrade pip >&2
  .venv/bin/python -m pip install --quiet "${reqs[@]}" >&2
  if .venv/bin/python -m pip install --quiet "${extras[@]}" >&2; then
    echo "${reqs[*]} ${extras[*]}" >"$stamp"
  else
    echo "warning: the test extras ${extras[*]} could not be installed: their tests will fail saying so" >&2
  fi
fi

# The C toolchain, GMP/MPFR and m4 the extension's build needs (quick when present).
bash scripts/setup.sh
[ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
read -r -a features <<<"$(bash scripts/gmp_features.sh)"
# An extension left by a build before the abi3 wheel (issue 38) would be
# imported before the new one: Python prefers the version-tagged name.
rm -f python/splinelab/_splinelab.cpython-*.so
# The extension is built by maturin, not linked as a test binary.
VIRTUAL_ENV="$PWD/.venv" PATH="$PWD/.venv/bin:$PATH" \
  .venv/bin/maturin develop --release --quiet -m python/Cargo.toml "${features[@]+"${features[@]}"}" >&2
.venv/bin/python -c "import splinelab; print('splinelab python package', splinelab.__version__, 'ready in .venv')"
