#!/usr/bin/env bash
# Installs the headless browser the page checks use (scripts/pagecheck.py):
# Debian's `chromium` package, through apt (never a browser download of its
# own), unless a Chromium is already there ($CHROMIUM, or `chromium` /
# `chromium-browser` on PATH). Prints the browser's path on stdout. Safe to
# rerun: a no-op once installed. Needs root or sudo the first time.
#   scripts/chromium.sh                       # -> /usr/bin/chromium
#   python3 scripts/pagecheck.py report/index.html --screenshots /tmp/shots
set -euo pipefail

found() {
  for b in "${CHROMIUM:-}" chromium chromium-browser; do
    [ -n "$b" ] && command -v "$b" 2>/dev/null && return 0
  done
  return 1
}

found && exit 0
if ! command -v apt-get >/dev/null 2>&1; then
  echo "error: no Chromium and no apt-get: install Chromium with your package manager, or set CHROMIUM=/path/to/chrome" >&2
  exit 1
fi
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
echo "splinelab: installing Debian's chromium (headless page checks)" >&2
if ! $sudo apt-get install -y -qq --no-install-recommends chromium >&2 2>/dev/null; then
  $sudo apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends chromium >&2
fi
found
