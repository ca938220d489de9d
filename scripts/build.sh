#!/usr/bin/env bash
# Configures and builds Lantern (Release by default) into build/. Uses ccache when present.
# Usage: scripts/build.sh [BUILD_TYPE] [extra cmake args...]
# Env: LANTERN_BUILD_TARGETS: the targets to build (default: all; the demo builds only `lantern`
# and the shaders it loads, not the test suite).
set -euo pipefail
cd "$(dirname "$0")/.."
build_type=${1:-Release}
shift || true
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="$build_type" -DLANTERN_WERROR="$werror" \
  "${launcher[@]}" "$@" >/dev/null
read -r -a targets <<<"${LANTERN_BUILD_TARGETS:-all}"
cmake --build build -j "$(nproc)" --target "${targets[@]}"
