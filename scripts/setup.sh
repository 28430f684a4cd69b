#!/usr/bin/env bash
# Installs what splinelab's build needs on a fresh machine: a C toolchain,
# the system GMP and MPFR (Debian's libgmp-dev, libmpfr-dev: rug links them,
# see scripts/gmp_features.sh) and m4 (only for the fallback, where rug builds
# GMP and MPFR from source), plus Rust. Safe to run repeatedly.
set -euo pipefail

have_header() { printf '#include <%s>\n' "$1" | cc -E -x c - >/dev/null 2>&1; }

need=()
command -v cc >/dev/null 2>&1 || need+=(gcc)
command -v make >/dev/null 2>&1 || need+=(make)
command -v m4 >/dev/null 2>&1 || need+=(m4)
optional=()
have_header gmp.h || optional+=(libgmp-dev)
have_header mpfr.h || optional+=(libmpfr-dev)

apt_install() {
  local sudo=""
  [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1 && sudo="sudo"
  if [ "$(id -u)" -ne 0 ] && [ -z "$sudo" ]; then return 1; fi
  if ! $sudo apt-get install -y -qq "$@" >&2 2>/dev/null; then
    $sudo apt-get update -qq >&2 && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "$@" >&2
  fi
}

if [ ${#need[@]} -gt 0 ]; then
  echo "splinelab setup: installing ${need[*]} (the C toolchain rug's build needs)" >&2
  if ! command -v apt-get >/dev/null 2>&1; then
    echo "error: missing ${need[*]} and no apt-get to install them; install them with your package manager and rerun." >&2
    exit 1
  fi
  apt_install "${need[@]}" || {
    echo "error: need root or sudo to install ${need[*]}; install them by hand and rerun." >&2
    exit 1
  }
fi

if [ ${#optional[@]} -gt 0 ]; then
  echo "splinelab setup: installing ${optional[*]} (system GMP/MPFR: saves building them from source)" >&2
  if ! command -v apt-get >/dev/null 2>&1 || ! apt_install "${optional[@]}"; then
    echo "splinelab setup: could not install ${optional[*]}; rug will build GMP and MPFR from source on the first build (a few minutes, then cached)" >&2
  fi
fi

if ! command -v cargo >/dev/null 2>&1; then
  [ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
fi
if ! command -v cargo >/dev/null 2>&1; then
  echo "error: cargo not found: install Rust 1.95 or newer (https://rustup.rs) and rerun." >&2
  exit 1
fi
