#!/usr/bin/env bash
# Downstream clients' own tests with splinelab swapped in for scipy.ndimage's
# spline functions, and xarray's own interpolation tests with the accessor in
# place of interp (python/tests/downstream/README.md): installs the pinned
# clients of python/tests/downstream/requirements.txt into .venv (only when
# that file changes; scipy and numpy held at the versions scripts/python.sh
# installed), then runs each client's selection on the original and on
# splinelab and compares the outcomes. Arguments go to run.py (--client NAME,
# --quick: scipy's and xarray's own suites, which need nothing installed;
# --serial, --json FILE).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x .venv/bin/python ] || bash scripts/python.sh
reqs=python/tests/downstream/requirements.txt
stamp=.venv/.splinelab-downstream
want="$(sha256sum <"$reqs")"
# scipy's and xarray's own tests need no client installed (scripts/python.sh
# installs both): --quick, or --client scipy / --client xarray only, skips the install.
builtin=0
prev=
for a in "$@"; do
  case "$a" in
    --quick) [ "$builtin" = 0 ] && builtin=1 ;;
  esac
  if [ "$prev" = --client ]; then
    case "$a" in
      scipy | xarray) [ "$builtin" = 0 ] && builtin=1 ;;
      *) builtin=2 ;;
    esac
  fi
  prev=$a
done
if [ "$builtin" != 1 ] && [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  held=$(.venv/bin/python -c 'import numpy, scipy; print(f"numpy=={numpy.__version__} scipy=={scipy.__version__}")')
  echo "splinelab downstream: installing $(grep -v '^#' "$reqs" | tr '\n' ' ')(holding $held)" >&2
  # shellcheck disable=SC2086
  .venv/bin/python -m pip install --quiet -r "$reqs" $held >&2
  echo "$want" >"$stamp"
fi
.venv/bin/python python/tests/downstream/run.py "$@"
