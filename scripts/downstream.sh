#!/usr/bin/env bash
# Downstream clients' own tests with splinelab swapped in for scipy.ndimage's
# spline functions (python/tests/downstream/README.md): installs the pinned
# clients of python/tests/downstream/requirements.txt into .venv (only when
# that file changes; scipy and numpy held at the versions scripts/python.sh
# installed), then runs each client's selection on scipy and on splinelab and
# compares the outcomes. Arguments go to run.py (--client NAME, --json FILE).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x .venv/bin/python ] || bash scripts/python.sh
reqs=python/tests/downstream/requirements.txt
stamp=.venv/.splinelab-downstream
want="$(sha256sum <"$reqs")"
# scipy's own tests need no client installed: `--client scipy` alone skips the install.
only_scipy=0
[ "$*" = "--client scipy" ] && only_scipy=1
if [ "$only_scipy" = 0 ] && [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  held=$(.venv/bin/python -c 'import numpy, scipy; print(f"numpy=={numpy.__version__} scipy=={scipy.__version__}")')
  echo "splinelab downstream: installing $(grep -v '^#' "$reqs" | tr '\n' ' ')(holding $held)" >&2
  # shellcheck disable=SC2086
  .venv/bin/python -m pip install --quiet -r "$reqs" $held >&2
  echo "$want" >"$stamp"
fi
.venv/bin/python python/tests/downstream/run.py "$@"
