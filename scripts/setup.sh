#!/usr/bin/env bash
# Installs what splinelab's build needs on a fresh machine: a C toolchain and
# m4 (rug builds GMP and MPFR from source), plus Rust. Safe to run repeatedly.
set -euo pipefail

need=()
command -v cc >/dev/null 2>&1 || need+=(gcc)
command -v make >/dev/null 2>&1 || need+=(make)
command -v m4 >/dev/null 2>&1 || need+=(m4)

if [ ${#need[@]} -gt 0 ]; then
  echo "splinelab setup: installing ${need[*]} (needed to build GMP/MPFR for rug)" >&2
  if command -v apt-get >/dev/null 2>&1; then
    sudo=""
    [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1 && sudo="sudo"
    if [ "$(id -u)" -ne 0 ] && [ -z "$sudo" ]; then
      echo "error: need root or sudo to install ${need[*]}; install them by hand and rerun." >&2
      exit 1
    fi
    $sudo apt-get update -qq >&2
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${need[@]}" >&2
  else
    echo "error: missing ${need[*]} and no apt-get to install them; install them with your package manager and rerun." >&2
    exit 1
  fi
fi

if ! command -v cargo >/dev/null 2>&1; then
  [ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
fi
if ! command -v cargo >/dev/null 2>&1; then
  echo "error: cargo not found: install Rust 1.95 or newer (https://rustup.rs) and rerun." >&2
  exit 1
fi
