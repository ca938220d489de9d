#!/usr/bin/env bash
# The README's raw-vs-denoised pairs (issue 13): for each level (default: every level under
# content/levels), `lantern capture` of ReSTIR at the preset along the level's path, the last
# frame kept twice: denoised (automatic exposure) and raw at the denoised run's exposure (read
# from its capture.json), so the two differ only by the denoiser and what ReSTIR renders for it
# (temporal_permutation=denoised: the raw run is what EXR output shows). Writes
# docs/levels/LEVEL_denoised.png and docs/levels/LEVEL_raw.png.
# Usage: scripts/screenshots.sh [LEVEL ...] [--size WxH] [--frames N] [--preset P]
set -euo pipefail
cd "$(dirname "$0")/.."
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}"
lantern=build/bin/lantern
[ -x "$lantern" ] || { echo "screenshots: build first (bash scripts/build.sh)" >&2; exit 2; }
size=320x180 frames=16 preset=balanced levels=()
while [ $# -gt 0 ]; do
  case "$1" in
    --size) size=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --preset) preset=$2; shift 2 ;;
    --*) echo "screenshots: unknown argument '$1' (see the usage line in $0)" >&2; exit 2 ;;
    *) levels+=("$1"); shift ;;
  esac
done
if [ ${#levels[@]} -eq 0 ]; then
  for f in content/levels/*.json; do levels+=("$(basename "$f" .json)"); done
fi
out=$(mktemp -d /tmp/screenshots.XXXXXX)
trap 'rm -rf "$out"' EXIT
mkdir -p docs/levels
last=$(printf 'frame_%04d.png' $((frames - 1)))
for level in "${levels[@]}"; do
  echo "screenshots: $level" >&2
  "$lantern" capture "$level" --integrator restir --preset "$preset" --size "$size" \
    --frames "$frames" --format png --output denoised --quiet --out "$out/$level.denoised"
  exposure=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["exposure"])' \
    "$out/$level.denoised/capture.json")
  "$lantern" capture "$level" --integrator restir --preset "$preset" --size "$size" \
    --frames "$frames" --format png --output raw --exposure "$exposure" --quiet \
    --out "$out/$level.raw"
  cp "$out/$level.denoised/$last" "docs/levels/${level}_denoised.png"
  cp "$out/$level.raw/$last" "docs/levels/${level}_raw.png"
done
