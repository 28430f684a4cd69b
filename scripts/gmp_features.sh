#!/usr/bin/env bash
# Prints the cargo flags that every cargo and maturin call takes:
# `--features splinelab/system-gmp` (link the system's GMP 6.3+ and MPFR
# 4.2+) when both link here; otherwise rug builds them from source (cached
# in ~/.cache/gmp-mpfr-sys, or $GMP_MPFR_SYS_CACHE) and this prints
# `--features splinelab/gmp-no-check`: build them without running their own
# test suites (`make check`), more than half of that C build (233
# CPU-seconds with them, 103 without, on 2 cores; issue 38; core/Cargo.toml
# says why that is safe). SPLINELAB_GMP_CHECK=1 runs the suites anyway (a cache built with
# them serves both). SPLINELAB_BUNDLED_GMP=1 forces the build from source
# (e.g. for a wheel that must run on a machine without them).
set -euo pipefail
from_source() {
  [ "${SPLINELAB_GMP_CHECK:-0}" = 1 ] || echo "--features splinelab/gmp-no-check"
  exit 0
}
[ "${SPLINELAB_BUNDLED_GMP:-0}" = 1 ] && from_source
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
else
  from_source
fi
