#!/usr/bin/env bash
# The test command: set up the machine, then run every test (unit, property,
# integration and doc tests), then the Python package's (scripts/python.sh
# builds it into .venv; pytest runs python/tests and the docstring examples,
# with the CI-file linters of scripts/ci_tools.sh and the headless Chromium
# of scripts/chromium.sh for the page checks), then scripts/downstream.sh
# (reproject's, nibabel's, sunpy's and scipy's own interpolation tests with
# splinelab swapped in for scipy.ndimage's and scipy.interpolate's functions,
# xarray's with the accessor swapped in for `.interp`), then the documentation
# (scripts/docs.sh: warnings as errors, every gallery example and the pages'
# doctests run, every local link resolves, every page opens in headless
# Chromium; the gallery at full size, about 10 s of examples, in both profiles).
#   scripts/test.sh            # = --full
#   scripts/test.sh --full     # every downstream client's suite (installs them)
#   scripts/test.sh --quick    # what CI runs (.ci/run): downstream, scipy's and
#                              # xarray's own interpolation tests only (nothing to
#                              # install: both are in .venv already), and
#                              # the CLI fault sweep runs a quarter of its large
#                              # case classes (SPLINELAB_TEST_PROFILE=quick);
#                              # the weekly workflow and --full run the rest
# Other arguments go to `cargo test`.
# Tests run in the release profile and with the same features as the report
# and the Python extension (core/Cargo.toml pins them), so the three compile
# each crate once; each crate's integration tests are one test binary
# (verify/tests/it, reports/tests/it), not one per file (issue 38).
set -euo pipefail
cd "$(dirname "$0")/.."
profile=full
cargo_args=()
for a in "$@"; do
  case "$a" in
    --quick) profile=quick ;;
    --full) profile=full ;;
    *) cargo_args+=("$a") ;;
  esac
done
stamp() { echo "splinelab test ($profile): $1 at $(( $(date +%s) - start )) s" >&2; }
start=$(date +%s)
bash scripts/setup.sh
[ -f "$HOME/.cargo/env" ] && . "$HOME/.cargo/env"
read -r -a features <<<"$(bash scripts/gmp_features.sh)"
SPLINELAB_TEST_PROFILE=$profile cargo test --release --workspace "${features[@]+"${features[@]}"}" "${cargo_args[@]+"${cargo_args[@]}"}"
stamp "Rust tests done"
bash scripts/python.sh
bash scripts/ci_tools.sh
bash scripts/chromium.sh >/dev/null
stamp "Python package, CI tools and Chromium ready"
# The CI-file and page tests fail (not skip) here when a tool is missing.
SPLINELAB_REQUIRE_CHROMIUM=1 .venv/bin/python -m pytest -q -p no:cacheprovider --doctest-modules \
  python/splinelab python/tests
stamp "pytest done"
# Downstream libraries' own tests (and scipy's) with splinelab swapped in.
if [ "$profile" = quick ]; then
  bash scripts/downstream.sh --quick
else
  bash scripts/downstream.sh
fi
stamp "downstream done"
# The documentation site.
bash scripts/docs.sh
stamp "documentation done"
