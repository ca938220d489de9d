#!/usr/bin/env bash
# The README's first command: install what is missing, build (Release), and render the default
# demo level (cornell_lights) headless on lavapipe with the baseline integrator to out/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh Release
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}"
mkdir -p out
build/bin/lantern render cornell_lights --integrator baseline --frames 16 --average \
  --size 640x360 --out out/demo.png
echo "wrote out/demo.png"
