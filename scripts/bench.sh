#!/usr/bin/env bash
# Runs the criterion benches (benches/benches/*.rs) with the features and the
# release profile the report, the tests and the Python extension use
# (scripts/gmp_features.sh; cargo's bench profile inherits release), so after
# scripts/report.sh it compiles criterion and the bench targets only: no
# second GMP/MPFR build, no workspace crate again. Then writes
# target/bench/summary.json (scripts/bench_summary.py): each benchmark's
# median as a wall-clock figure that `splinelab compare --timings` gates.
#   scripts/bench.sh                          # every bench
#   scripts/bench.sh --bench engine           # one target (arguments go to cargo bench)
#   scripts/bench.sh --bench engine -- prefilter   # criterion's filter after --
#   scripts/bench.sh --no-run                 # build only
#   scripts/splinelab.sh compare --timings --baseline OLD/summary.json \
#     --current target/bench/summary.json --out target/bench-compare
# BENCH_OUT=DIR writes the summary elsewhere.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
[ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
read -r -a features <<<"$(bash scripts/gmp_features.sh)"
target="${CARGO_TARGET_DIR:-target}"
out="${BENCH_OUT:-$target/bench}"
since=$(date +%s)
# `-p splinelab-benches` with the bench targets only: cargo resolves the
# benches' dependencies as the report's (core/Cargo.toml names the features
# that would differ), so GMP/MPFR and the workspace crates are the report's
# artifacts. (`--workspace` would bring every member's dev-dependencies in,
# change their features and rebuild everything, GMP's build script included.)
targets=(--bench '*')
case " $* " in *" --bench "*) targets=() ;; esac
cargo bench -p splinelab-benches "${targets[@]+"${targets[@]}"}" "${features[@]+"${features[@]}"}" "$@"
case " $* " in *" --no-run "*) exit 0 ;; esac
python3 scripts/bench_summary.py "$target/criterion" "$out" --since "$since"
