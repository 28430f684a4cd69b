#!/usr/bin/env bash
# Builds the documentation site: docs/_build/html/index.html.
#   scripts/docs.sh               # everything; the gallery at its documented sizes
#   scripts/docs.sh --quick       # the gallery's quick profile (CI: scripts/test.sh)
#   scripts/docs.sh --no-browser  # skip the headless-Chromium check
#   scripts/docs.sh --no-rustdoc  # skip cargo doc (a local iteration on the pages)
# Steps (docs/building.md): the package into .venv (scripts/python.sh), the
# pinned documentation tools into the same .venv, the Rust API (cargo doc
# --no-deps), the quick report, Sphinx with warnings as errors and nitpicky
# references (no network: intersphinx reads docs/_intersphinx), a check that
# every local href/src of the built HTML exists, the Markdown pages' doctests,
# and headless Chromium over every page. Prints each step's time.
# SPLINELAB_BUILD_LOCK=FILE runs each compile under `flock FILE` (a shared
# machine's build lock).
set -euo pipefail
cd "$(dirname "$0")/.."

profile=full
browser=1
rustdoc=1
for arg in "$@"; do
  case "$arg" in
    --quick) profile=quick ;;
    --no-browser) browser=0 ;;
    --no-rustdoc) rustdoc=0 ;;
    *) echo "usage: scripts/docs.sh [--quick] [--no-browser] [--no-rustdoc]" >&2; exit 2 ;;
  esac
done

lock=()
[ -n "${SPLINELAB_BUILD_LOCK:-}" ] && lock=(flock "$SPLINELAB_BUILD_LOCK")
start=$(date +%s)
step=$start
took() { local now; now=$(date +%s); echo "splinelab docs: $1 in $((now - step)) s" >&2; step=$now; }

"${lock[@]+"${lock[@]}"}" bash scripts/python.sh >&2
took "package built into .venv"

# The documentation tools, pinned; installed only when this list changes.
reqs=("sphinx==9.0.4" "numpydoc==1.11.0" "sphinx-gallery==0.22.1" "myst-parser==5.2.0"
  "pydata-sphinx-theme==0.24.0" "matplotlib==3.11.2" "selenium==4.51.0")
stamp=.venv/.splinelab-docs-requirements
if [ "$(cat "$stamp" 2>/dev/null)" != "${reqs[*]}" ]; then
  echo "splinelab docs: installing ${reqs[*]}" >&2
  .venv/bin/python -m pip install --quiet "${reqs[@]}" >&2
  echo "${reqs[*]}" >"$stamp"
fi
took "documentation tools"

gen=docs/_generated
rm -rf docs/_build "$gen" docs/auto_examples docs/api/generated docs/sg_execution_times.rst
mkdir -p "$gen/extra"
if [ "$rustdoc" = 1 ]; then
  [ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
  read -r -a features <<<"$(bash scripts/gmp_features.sh)"
  "${lock[@]+"${lock[@]}"}" cargo doc --release --no-deps --workspace --lib --quiet "${features[@]+"${features[@]}"}" >&2
  cp -r "${CARGO_TARGET_DIR:-target}/doc" "$gen/extra/rust"
  # rustdoc of a workspace has no root page (its help and settings pages
  # link one): the list of the crates.
  {
    echo '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>splinelab: Rust API</title></head><body>'
    echo '<h1>splinelab: the Rust crates</h1><ul>'
    for crate in splinelab splinelab_verify splinelab_reports splinelab_benches _splinelab; do
      [ -f "$gen/extra/rust/$crate/index.html" ] && echo "<li><a href=\"$crate/index.html\">$crate</a></li>"
    done
    echo '</ul><p><a href="../index.html">Back to the documentation</a></p></body></html>'
  } >"$gen/extra/rust/index.html"
  took "Rust API (cargo doc --no-deps --workspace)"
else
  mkdir -p "$gen/extra/rust"
  echo '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>Rust API</title></head><body><p>Built without the Rust API (scripts/docs.sh --no-rustdoc).</p></body></html>' >"$gen/extra/rust/index.html"
  for crate in splinelab splinelab_verify splinelab_reports splinelab_benches; do
    mkdir -p "$gen/extra/rust/$crate" && cp "$gen/extra/rust/index.html" "$gen/extra/rust/$crate/index.html"
  done
fi

.venv/bin/python -m splinelab report --quick --quiet --out "$gen/extra/report" >&2
# The site's icon at its root, where browsers ask for it (the report's page names none).
cp docs/_static/favicon.ico "$gen/extra/favicon.ico"
took "quick report"

SPLINELAB_GALLERY=$profile .venv/bin/python -m sphinx -W --keep-going -n -q -b html docs docs/_build/html
took "Sphinx (gallery profile $profile)"

.venv/bin/python docs/check_links.py docs/_build/html
took "local links"

# The pages' examples (>>>) run; pytest's own plugin autoload stays on (the
# splinelab plugin is inactive without --splinelab-report).
.venv/bin/python -m pytest -q -p no:cacheprovider --doctest-glob='*.md' --doctest-glob=index.rst docs/*.md docs/index.rst README.md
took "Markdown doctests"

if [ "$browser" = 1 ]; then
  bash scripts/chromium.sh >&2
  .venv/bin/python docs/browser_check.py --site docs/_build/html --shots docs/_build/html/_screenshots
  took "headless Chromium"
fi
echo "splinelab docs: docs/_build/html/index.html ($(($(date +%s) - start)) s in all)"
