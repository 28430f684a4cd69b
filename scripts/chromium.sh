#!/usr/bin/env bash
# Installs the headless browser the page checks use: Debian's `chromium`,
# `chromium-driver` (the WebDriver server of the same build, for
# docs/browser_check.py) and a font, through apt (never a browser download of
# its own), unless they are already there. Prints the browser's path on
# stdout. Safe to rerun: a no-op once installed. Needs root or sudo the first
# time.
#   scripts/chromium.sh                       # -> /usr/bin/chromium
#   CHROMIUM=/path CHROMEDRIVER=/path scripts/chromium.sh   # use those, install nothing
# Python sides: scripts/pagecheck.py (DevTools pipe, standard library only:
# the CI pages and the report) and docs/browser_check.py (the documentation site).
set -euo pipefail

browser="${CHROMIUM:-}"
[ -n "$browser" ] || browser=$(command -v chromium || command -v chromium-browser || true)
driver="${CHROMEDRIVER:-$(command -v chromedriver || true)}"
if [ -z "$browser" ] || [ -z "$driver" ]; then
  if [ -n "${CHROMIUM:-}${CHROMEDRIVER:-}" ]; then
    echo "error: CHROMIUM/CHROMEDRIVER set but not both usable: '${CHROMIUM:-}' '${CHROMEDRIVER:-}'" >&2
    exit 1
  fi
  if ! command -v apt-get >/dev/null 2>&1; then
    echo "error: no Chromium and no apt-get: install chromium and chromium-driver with your package manager, or set CHROMIUM and CHROMEDRIVER" >&2
    exit 1
  fi
  sudo=""
  [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1 && sudo="sudo"
  if [ "$(id -u)" -ne 0 ] && [ -z "$sudo" ]; then
    echo "error: need root or sudo to install chromium chromium-driver" >&2
    exit 1
  fi
  pkgs=(chromium chromium-driver fonts-dejavu-core)
  echo "splinelab: installing ${pkgs[*]} (Debian packages, for the headless page checks)" >&2
  if ! DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${pkgs[@]}" >&2 2>/dev/null; then
    $sudo apt-get update -qq >&2
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${pkgs[@]}" >&2
  fi
  browser=$(command -v chromium)
fi
echo "$browser"
