#!/usr/bin/env bash
# The README's first command: install what is missing, build (Release), and run the default demo
# level (cornell_lights): in a window when DISPLAY is set (`lantern play`, Esc quits), otherwise
# headless on lavapipe: a 16-frame ReSTIR flythrough capture (out/demo/, frames + timings.csv +
# capture.json), its last frame copied to out/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# Only what the demo runs: the lantern command and its shaders (the tests are test.sh's).
LANTERN_BUILD_TARGETS=lantern bash scripts/build.sh Release
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}"
if [ -n "${DISPLAY:-}" ]; then
  exec build/bin/lantern play cornell_lights "$@"
fi
mkdir -p out
build/bin/lantern capture cornell_lights --integrator restir --frames 16 --size 640x360 \
  --format png --out out/demo "$@"
cp out/demo/frame_0015.png out/demo.png
echo "wrote out/demo/ (frames, timings.csv, capture.json) and out/demo.png"
