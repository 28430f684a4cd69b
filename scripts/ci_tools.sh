#!/usr/bin/env bash
# Installs the pinned tools the CI-file tests use (python/tests/ci-requirements.txt:
# zizmor, check-jsonschema with GitHub's schemas vendored in it, PyYAML) into
# .venv, only when that file changes (a stamp in .venv). scripts/test.sh runs it
# after scripts/python.sh; run it yourself before `pytest python/tests/test_ci_*.py`.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x .venv/bin/python ] || bash scripts/python.sh
reqs=python/tests/ci-requirements.txt
stamp=.venv/.splinelab-ci-tools
want="$(sha256sum <"$reqs")"
if [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  echo "splinelab ci tools: installing $(grep -v '^#' "$reqs" | tr '\n' ' ')" >&2
  .venv/bin/python -m pip install --quiet -r "$reqs" >&2
  echo "$want" >"$stamp"
fi
