#!/usr/bin/env bash
# Builds the `splinelab` command (release, linking the system GMP/MPFR when
# scripts/gmp_features.sh finds them) and runs it with the given arguments,
# from the caller's directory. The first build shows cargo's progress.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
[ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
bin="${CARGO_TARGET_DIR:-$root/target}/release/splinelab"
read -r -a features <<<"$(bash "$root/scripts/gmp_features.sh")"
quiet=(--quiet)
if [ ! -x "$bin" ]; then
  quiet=()
  if [ "${features[*]-}" = "--features splinelab/system-gmp" ]; then
    gmp="linking the system GMP/MPFR"
  else
    gmp="and GMP/MPFR from source first unless ~/.cache/gmp-mpfr-sys has them"
  fi
  echo "splinelab: first build of the release binary (about 3 min on 2 cores, 4 with GMP/MPFR from source, see docs/getting_started.md; $gmp); later runs rebuild in seconds" >&2
fi
cargo build --release "${quiet[@]+"${quiet[@]}"}" --manifest-path "$root/Cargo.toml" -p splinelab-reports \
  --bin splinelab "${features[@]+"${features[@]}"}" >&2
exec "$bin" "$@"
