#!/usr/bin/env bash
# The long validation flythrough (issue 7): every level in content/levels/ flown along its camera
# path for LANTERN_FLYTHROUGH_FRAMES frames (default 1000) with baseline and restir, validation
# layer + synchronization validation on. Each level/integrator runs as its own process (its own
# device); the script prints one line per run (frames, validation errors and warnings, non-finite
# frames, setup and frame times) and exits non-zero if any run failed.
#
# Usage: scripts/validate_flythrough.sh [gtest filter]     e.g. scripts/validate_flythrough.sh '*night_market*'
# Env: LANTERN_FLYTHROUGH_FRAMES (1000), LANTERN_FLYTHROUGH_SIZE (64x36),
#      LANTERN_FLYTHROUGH_BUILD (build) — a build dir with validation_flythrough_test built.
# The short version (30 frames) is the ctest validation_flythrough_test.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${LANTERN_FLYTHROUGH_BUILD:-build}
exe="$build/bin/validation_flythrough_test"
[ -x "$exe" ] || { echo "validate_flythrough.sh: $exe not built (cmake --build $build --target validation_flythrough_test)" >&2; exit 2; }
export LANTERN_FLYTHROUGH_FRAMES=${LANTERN_FLYTHROUGH_FRAMES:-1000}
export LANTERN_FLYTHROUGH_SIZE=${LANTERN_FLYTHROUGH_SIZE:-64x36}
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}"
filter=${1:-*}
failed=0
for test in $("$exe" --gtest_list_tests --gtest_filter="$filter" | awk '/^  /{print prefix $1} /^[^ ]/{prefix=$1}'); do
  start=$(date +%s)
  if out=$("$exe" --gtest_filter="$test" 2>&1); then status=ok; else status=FAILED; failed=1; fi
  echo "$out" | grep '^\[flythrough\]' || echo "$out" | tail -20
  echo "  -> $test: $status in $(( $(date +%s) - start )) s"
done
exit $failed
