#!/usr/bin/env bash
# Visibility backends A/B (issue 12): `lantern bench LEVEL` for the baseline and ReSTIR with
# --set visibility=A and =B alternating in one run, --rounds times, on this binary. Prints per
# integrator and backend the medians over rounds of the frame (GPU and wall ms), the passes that
# shade and trace (the shading pass, the host's visibility.host and the blocked-pixel rewrite),
# ReSTIR's resampling passes, the ReSTIR/baseline ratio per backend, and B/A per round.
# Usage: scripts/visibility_ab.sh [LEVEL] [--size WxH] [--frames N] [--warmup N] [--rounds N]
#                                 [--preset P] [--backends "bvh host"]
set -euo pipefail
source "$(dirname "$0")/bench_common.sh"
level=night_market size=320x180 frames=12 warmup=3 rounds=3 preset=balanced backends="bvh host"
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then level=$1; shift; fi
bench_options visibility_ab size frames warmup rounds preset backends -- "$@"
bench_setup visibility_ab
for r in $(seq 1 "$rounds"); do
  for integrator in baseline restir; do
    for v in $backends; do
      echo "visibility_ab: round $r, $integrator, visibility=$v ($level $size, $warmup + $frames frames)" >&2
      "$lantern" bench "$level" --integrator "$integrator" --preset "$preset" --size "$size" \
        --frames "$frames" --warmup "$warmup" --quiet --set "visibility=$v" \
        --json "$out/$integrator.$v.$r.json" >/dev/null
    done
  done
done
python3 - "$out" "$level" "$size" "$preset" "$rounds" $backends <<'PY'
import json, statistics, sys
out, level, size, preset, rounds, backends = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]), sys.argv[6:]
shading = {"baseline": ["integrators.baseline", "visibility.host", "integrators.baseline_occluded"],
           "restir": ["restir.shade", "visibility.host", "restir.shade_occluded"]}
resampling = ["restir.initial", "restir.temporal", "restir.spatial"]
def run(integrator, v, r):
    return json.load(open(f"{out}/{integrator}.{v}.{r}.json"))
def med(values):
    return statistics.median(values)
def col(integrator, v, key):
    values = []
    for r in range(1, rounds + 1):
        j = run(integrator, v, r)
        if key == "frame":
            values.append(j["frame_ms"]["median"])
        elif key == "wall":
            values.append(j["frame_wall_ms"]["median"])
        elif key == "host_rays":
            values.append(j.get("host_visibility", {}).get("rays_per_second", 0.0) / 1e6)
        else:
            values.append(j["passes"].get(key, {}).get("median", 0.0))
    return med(values)
print(f"{level} at {size}, ReSTIR {preset}, {rounds} round(s) alternating {' / '.join(backends)}: "
      f"GPU ms, medians over rounds")
for integrator in ["baseline", "restir"]:
    names = shading[integrator] + (resampling if integrator == "restir" else [])
    print(f"  {integrator:8s} {'backend':8s} {'frame':>8} {'wall':>8} " +
          " ".join(f"{n.split('.', 1)[1][:16]:>16}" for n in names) + f" {'host Mrays/s':>12}")
    for v in backends:
        print(f"  {'':8s} {v:8s} {col(integrator, v, 'frame'):8.1f} {col(integrator, v, 'wall'):8.1f} " +
              " ".join(f"{col(integrator, v, n):16.2f}" for n in names) +
              f" {col(integrator, v, 'host_rays'):12.2f}")
for v in backends:
    ratios = [run("restir", v, r)["frame_ms"]["median"] / run("baseline", v, r)["frame_ms"]["median"]
              for r in range(1, rounds + 1)]
    print(f"  ReSTIR / baseline frame, {v}: {med(ratios):.2f}x (rounds: "
          + ", ".join(f"{x:.2f}" for x in ratios) + ")")
if len(backends) == 2:
    a, b = backends
    for integrator in ["baseline", "restir"]:
        for key, label in [("frame", "frame"), ("wall", "wall")]:
            field = "frame_ms" if key == "frame" else "frame_wall_ms"
            ratios = [run(integrator, b, r)[field]["median"] / run(integrator, a, r)[field]["median"]
                      for r in range(1, rounds + 1)]
            print(f"  {integrator} {label} {b}/{a}: {med(ratios):.2f}x (rounds: "
                  + ", ".join(f"{x:.2f}" for x in ratios) + ")")
PY
