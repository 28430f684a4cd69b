#!/usr/bin/env bash
# Builds the `splinelab` command (release, linking the system GMP/MPFR when
# scripts/gmp_features.sh finds them) and runs it with the given arguments,
# from the caller's directory. The first build shows cargo's progress.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
[ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
bin="${CARGO_TARGET_DIR:-$root/target}/release/splinelab"
read -r -a features <<<"$(bash "$root/scripts/gmp_features.sh")"
if [ ! -x "$bin" ]; then
  if [ ${#features[@]} -gt 0 ]; then gmp="system GMP/MPFR"; else gmp="GMP/MPFR built from source, add ~4 min"; fi
  echo "splinelab: first build of the release binary ($gmp; about 2 min on 2 cores, seconds afterwards)" >&2
  cargo build --release --manifest-path "$root/Cargo.toml" -p splinelab-reports --bin splinelab "${features[@]+"${features[@]}"}" >&2
else
  cargo build --release --quiet --manifest-path "$root/Cargo.toml" -p splinelab-reports --bin splinelab "${features[@]+"${features[@]}"}" >&2
fi
exec "$bin" "$@"
