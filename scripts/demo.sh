#!/usr/bin/env bash
# The README's first command: install what is missing, build (Release), and run the default demo
# level (cornell_lights): in a window when DISPLAY is set (`lantern play`, Esc quits), otherwise
# headless on lavapipe with the baseline integrator, writing out/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh Release
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}"
if [ -n "${DISPLAY:-}" ]; then
  exec build/bin/lantern play cornell_lights "$@"
fi
mkdir -p out
build/bin/lantern render cornell_lights --integrator baseline --frames 16 --average \
  --size 640x360 --out out/demo.png "$@"
echo "wrote out/demo.png"
