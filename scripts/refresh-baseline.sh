#!/usr/bin/env bash
# Refreshes the committed regression baseline from a quick report on this
# machine. Run it deliberately, when a change is meant to move a figure, and
# commit reports/baseline/summary.json with a message saying why. CI never
# runs this: it compares against the committed file.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/report.sh --quick --out target/baseline-report
mkdir -p reports/baseline
cp target/baseline-report/summary.json reports/baseline/summary.json
echo "baseline refreshed: reports/baseline/summary.json (review the diff, then commit)"
