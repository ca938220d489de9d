#!/usr/bin/env bash
# Issue 12's report table: `lantern bench LEVEL` of the baseline and of ReSTIR at each preset, at
# each size, the configurations alternating within every round (--rounds times), on this binary.
# Prints per size a Markdown table of medians over rounds: the GPU frame, its ratio to the
# baseline (the median of each round's own ratio: rounds see the same load), the G-buffer (every
# gbuffer.* pass), ReSTIR's resampling passes (initial with its BSDF candidates' closest hits,
# restir.initial_rays and visibility.host_closest, where a preset has them), the shading (the
# integrator's shading pass, the host's visibility.host and the blocked-pixel rewrite) and the
# shadow rays per second.
# Usage: scripts/frame_table.sh [LEVEL] [--sizes "320x180 640x360"] [--frames N] [--warmup N]
#                               [--rounds N] [--presets "fast balanced quality"]
set -euo pipefail
source "$(dirname "$0")/bench_common.sh"
level=night_market sizes="320x180 640x360" frames=12 warmup=3 rounds=3
presets="fast balanced quality"
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then level=$1; shift; fi
bench_options frame_table sizes frames warmup rounds presets -- "$@"
bench_setup frame_table
for r in $(seq 1 "$rounds"); do
  for size in $sizes; do
    for config in baseline $presets; do
      integrator=restir preset=$config
      if [ "$config" = baseline ]; then integrator=baseline preset=balanced; fi
      echo "frame_table: round $r/$rounds, $size, $config" >&2
      "$lantern" bench "$level" --integrator "$integrator" --preset "$preset" --size "$size" \
        --frames "$frames" --warmup "$warmup" --quiet --json "$out/$size.$config.$r.json" >/dev/null
    done
  done
done
python3 - "$out" "$level" "$rounds" "$frames" "$warmup" "$sizes" baseline $presets <<'PY'
import json, statistics, sys
out, level, rounds, frames, warmup, sizes = sys.argv[1:7]
rounds = int(rounds)
configs = sys.argv[7:]
resampling = ["restir.presample", "restir.initial", "restir.temporal", "restir.spatial"]

def row(d):
    p = {k: v["median"] for k, v in d["passes"].items()}
    closest = [p[k] for k in ("restir.initial_rays", "visibility.host_closest") if k in p]
    if closest and "restir.initial" in p:
        p["restir.initial"] += sum(closest)
    shading = sum(v for k, v in p.items()
                  if k in ("restir.shade", "integrators.baseline", "visibility.host")
                  or k.endswith("_occluded"))
    host = d.get("host_visibility", {}).get("rays_per_second", 0.0)
    rays = host if host > 0 else d["rays_per_second"]["shadow"]
    return {"frame": d["frame_ms"]["median"],
            "gbuffer": sum(v for k, v in p.items() if k.startswith("gbuffer")),
            **{k: p.get(k, float("nan")) for k in resampling},
            "shading": shading, "rays": rays}

print(f"{level}: `lantern bench {level} --integrator I --preset P --size S --frames {frames} "
      f"--warmup {warmup}`, configurations alternating, {rounds} round(s), GPU ms (medians)")
for size in sizes.split():
    runs = {c: [row(json.load(open(f"{out}/{size}.{c}.{r}.json"))) for r in range(1, rounds + 1)]
            for c in configs}
    print(f"\n| {size} | frame | x baseline | G-buffer | presample | initial | temporal | "
          "spatial | shading + host rays | shadow rays/s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for c in configs:
        med = {k: statistics.median(r[k] for r in runs[c]) for k in runs[c][0]}
        ratio = statistics.median(a["frame"] / b["frame"] for a, b in zip(runs[c], runs["baseline"]))
        cells = ["" if med[k] != med[k] else f"{med[k]:.1f}" for k in resampling]
        name = c if c == "baseline" else f"ReSTIR {c}"
        print(f"| {name} | {med['frame']:.1f} | {ratio:.2f}x | {med['gbuffer']:.1f} | "
              + " | ".join(cells) + f" | {med['shading']:.1f} | {med['rays'] / 1e6:.2f} M |")
PY
