#!/usr/bin/env bash
# The README's second command: install what is missing, build, run the whole test suite (ctest).
# Tests run under Xvfb so the window test has a display; GPU tests run on lavapipe with the
# Vulkan validation layers on (LANTERN_VALIDATION=1 is set per test by CMake).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh Release
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}"
xvfb-run -a -s "-screen 0 1280x720x24" \
  ctest --test-dir build --output-on-failure --timeout 600 -j "$(nproc)" "$@"
