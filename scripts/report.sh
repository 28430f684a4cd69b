#!/usr/bin/env bash
# The main job: set up the machine, build, and write the full report to
# ./report (index.html, summary.json, charts). Extra arguments go to
# `splinelab report`, e.g. `--quick` or `--out DIR`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
out=report
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
bash scripts/splinelab.sh report --out "$out" "${args[@]+"${args[@]}"}"
echo "open $out/index.html"
