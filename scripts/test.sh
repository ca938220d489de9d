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

# CI also runs the reliability checks (README "Bad input"): the cpu tests that need only the
# engine under ASan + UBSan (GCC; measured ~6 CPU-min to build, 34 s to run), and a 30 s libFuzzer
# run per level loader (clang build-fuzz). Both fail CI on any sanitizer report or fuzz crash.
if [ "${CI:-}" = "true" ]; then
  LANTERN_ASAN_TARGETS="engine_ecs_test fuzz_replay_test level_test perf_test world_test layout_test shared_math_test" \
    bash scripts/sanitize.sh -L cpu
  bash scripts/fuzz.sh 30
fi
