#!/usr/bin/env bash
# Installs headless Chromium for page checks: Debian's `chromium` and
# `chromium-driver` (the WebDriver server of the same build), and fonts.
# Safe to rerun: installs only what is missing. Prints the browser's version.
#
# Interface (kept small; docs/browser_check.py is the Python side):
#   scripts/chromium.sh            # install if missing; exit 0 when
#                                  # /usr/bin/chromium and /usr/bin/chromedriver run
#   CHROMIUM=/path CHROMEDRIVER=/path   # use other binaries (nothing installed)
# Then docs/browser_check.py opens pages with them (see its docstring).
set -euo pipefail

browser="${CHROMIUM:-/usr/bin/chromium}"
driver="${CHROMEDRIVER:-/usr/bin/chromedriver}"
if [ ! -x "$browser" ] || [ ! -x "$driver" ]; then
  if [ -n "${CHROMIUM:-}${CHROMEDRIVER:-}" ]; then
    echo "error: CHROMIUM/CHROMEDRIVER set but not executable: $browser $driver" >&2
    exit 1
  fi
  if ! command -v apt-get >/dev/null 2>&1; then
    echo "error: chromium and chromedriver missing and no apt-get to install them (Debian: apt-get install chromium chromium-driver)" >&2
    exit 1
  fi
  sudo=""
  [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1 && sudo="sudo"
  if [ "$(id -u)" -ne 0 ] && [ -z "$sudo" ]; then
    echo "error: need root or sudo to install chromium chromium-driver" >&2
    exit 1
  fi
  echo "splinelab chromium: installing chromium chromium-driver fonts-dejavu-core (Debian packages)" >&2
  pkgs=(chromium chromium-driver fonts-dejavu-core)
  if ! DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${pkgs[@]}" >/dev/null 2>&1; then
    $sudo apt-get update -qq >&2
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${pkgs[@]}" >&2
  fi
fi
"$browser" --headless=new --no-sandbox --version
