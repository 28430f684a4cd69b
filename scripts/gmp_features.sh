#!/usr/bin/env bash
# Prints the cargo flag that links the system's GMP and MPFR
# (`--features splinelab/system-gmp`) when both link here, and nothing
# otherwise: rug then builds them from source (minutes, cached in
# ~/.cache/gmp-mpfr-sys). SPLINELAB_BUNDLED_GMP=1 forces the bundled build
# (e.g. for a wheel that must run on a machine without them).
set -euo pipefail
[ "${SPLINELAB_BUNDLED_GMP:-0}" = 1 ] && exit 0
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
cat >"$probe/p.c" <<'C'
#include <gmp.h>
#include <mpfr.h>
#if MPFR_VERSION_MAJOR < 4
#error "MPFR 4 or newer needed"
#endif
int main(void) { mpfr_t x; mpfr_init2(x, 64); mpfr_clear(x); return 0; }
C
if cc "$probe/p.c" -o "$probe/p" -lmpfr -lgmp >/dev/null 2>&1 && "$probe/p"; then
  echo "--features splinelab/system-gmp"
fi
