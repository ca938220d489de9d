#!/usr/bin/env bash
# Checks every shipped level against its frame-time budget (content/budgets/<level>.json) with
# `lantern bench --budget`: exit 3 names the passes over budget. Speed is measured here, never
# asserted in ctest. Usage: scripts/check_budgets.sh [LEVEL...] (default: every budgeted level).
set -euo pipefail
cd "$(dirname "$0")/.."
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}"
lantern=build/bin/lantern
[ -x "$lantern" ] || { echo "check_budgets: build first (bash scripts/build.sh)" >&2; exit 2; }
levels=("$@")
if [ ${#levels[@]} -eq 0 ]; then
  for f in content/budgets/*.json; do levels+=("$(basename "$f" .json)"); done
fi
status=0
for level in "${levels[@]}"; do
  budget="content/budgets/$level.json"
  [ -f "$budget" ] || { echo "check_budgets: no budget $budget" >&2; exit 2; }
  # The budget names its size, integrator and preset; bench refuses a mismatch.
  read -r size integrator preset < <(python3 -c "import json,sys; b=json.load(open('$budget')); print('%dx%d' % tuple(b['size']), b['integrator'], b.get('preset','balanced'))")
  echo "== $level ($integrator $preset $size)"
  set +e
  "$lantern" bench "$level" --integrator "$integrator" --preset "$preset" --size "$size" \
    --frames "${BUDGET_FRAMES:-40}" --warmup 5 --quiet --budget "$budget"
  code=$?
  set -e
  if [ $code -ne 0 ]; then status=$code; fi
done
exit $status
