#!/usr/bin/env bash
# Prints the cargo flag that links the system's GMP and MPFR (6.3+ and 4.2+)
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
/* rug's gmp-mpfr-sys 1.7 accepts GMP 6.3+ and MPFR 4.2+ (Debian 13; Debian 12 has GMP 6.2). */
#if __GNU_MP_VERSION < 6 || (__GNU_MP_VERSION == 6 && __GNU_MP_VERSION_MINOR < 3)
#error "GMP 6.3 or newer needed"
#endif
#if MPFR_VERSION_MAJOR < 4 || (MPFR_VERSION_MAJOR == 4 && MPFR_VERSION_MINOR < 2)
#error "MPFR 4.2 or newer needed"
#endif
int main(void) { mpfr_t x; mpfr_init2(x, 64); mpfr_clear(x); return 0; }
C
if cc "$probe/p.c" -o "$probe/p" -lmpfr -lgmp >/dev/null 2>&1 && "$probe/p"; then
  echo "--features splinelab/system-gmp"
fi
