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
stamp=.venv/.splinelab-requirements
if [ "$(cat "$stamp" 2>/dev/null)" != "${reqs[*]}" ]; then
  echo "splinelab python: installing ${reqs[*]}" >&2
  .venv/bin/python -m pip install --quiet --upgrade pip >&2
  .venv/bin/python -m pip install --quiet "${reqs[@]}" >&2
  echo "${reqs[*]}" >"$stamp"
fi

[ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
read -r -a features <<<"$(bash scripts/gmp_features.sh)"
# An extension left by a build before the abi3 wheel (issue 38) would be
# imported before the new one: Python prefers the version-tagged name.
rm -f python/splinelab/_splinelab.cpython-*.so
# The extension is built by maturin, not linked as a test binary.
VIRTUAL_ENV="$PWD/.venv" PATH="$PWD/.venv/bin:$PATH" \
  .venv/bin/maturin develop --release --quiet -m python/Cargo.toml "${features[@]+"${features[@]}"}" >&2
.venv/bin/python -c "import splinelab; print('splinelab python package', splinelab.__version__, 'ready in .venv')"
