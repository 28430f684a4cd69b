#!/usr/bin/env bash
# Builds the Python package for distribution: one abi3 wheel (CPython 3.10
# and later, the stable ABI) with GMP and MPFR linked in statically, and the
# sdist, into target/wheels (or the folder given as $1), with a pinned
# maturin that audits the wheel and gives it the most compatible manylinux
# tag its glibc symbols allow. Then checks that the extension needs no
# libgmp/libmpfr at run time.
#   scripts/wheel.sh                  # -> target/wheels/splinelab-*.whl, *.tar.gz
#   pip install target/wheels/splinelab-*.whl   # seconds, no Rust needed
set -euo pipefail
cd "$(dirname "$0")/.."

out="${1:-target/wheels}"
maturin_version=1.16.0 # also python/pyproject.toml and .github/workflows/wheels.yml
py="${PYTHON:-python3}"
tools=target/wheel-tools

if [ "$("$tools/bin/maturin" --version 2>/dev/null)" != "maturin $maturin_version" ]; then
  echo "splinelab wheel: installing maturin $maturin_version into $tools" >&2
  "$py" -m venv "$tools"
  "$tools/bin/python" -m pip install --quiet "maturin==$maturin_version"
fi

[ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
# rug's bundled build: GMP and MPFR compiled from source (cached in
# ~/.cache/gmp-mpfr-sys) and linked statically, so the wheel runs where they
# are absent; gmp_features.sh then prints no flag.
export SPLINELAB_BUNDLED_GMP=1
read -r -a features <<<"$(bash scripts/gmp_features.sh)"

mkdir -p "$out"
rm -f "$out"/splinelab-*.whl "$out"/splinelab-*.tar.gz
"$tools/bin/maturin" build --release --strip -m python/Cargo.toml --out "$out" \
  "${features[@]+"${features[@]}"}"
"$tools/bin/maturin" sdist -m python/Cargo.toml --out "$out"

wheel=$(ls "$out"/splinelab-*.whl)
so=$(mktemp -d)
trap 'rm -rf "$so"' EXIT
"$tools/bin/python" -m zipfile -e "$wheel" "$so"
needed=$(readelf -d "$so"/splinelab/_splinelab*.so | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | tr '\n' ' ')
echo "splinelab wheel: extension needs: $needed" >&2
case "$needed" in
  *libgmp* | *libmpfr*)
    echo "error: the extension links libgmp/libmpfr dynamically; the bundled build was not used" >&2
    exit 1
    ;;
esac
ls -l "$out"/splinelab-*
