#!/usr/bin/env bash
# Light-count scaling (issue 12, goal 3): `lantern bench` on the light_panels level, whose
# geometry, occluders and total power stay fixed while its ceiling panels are subdivided into
# 10^3..10^6 emissive triangles, for ReSTIR (a preset, default balanced) and the baseline,
# alternating per count, --rounds times (medians over rounds). Prints per count the frame ms (GPU
# median), its G-buffer part (all gbuffer* passes: the panels' triangles are drawn, so it grows
# with the count) and the rest ("lighting"), the ReSTIR passes, and the growth over the smallest
# count, also in units of the calibration workload each bench times in the same run. With
# --compare KEY=VALUE, every round and count also benches ReSTIR with that setting right after the
# plain one (the same frames, alternating: a change measured through the machine's swings) and
# prints its frame beside the plain one and its own growth, as the median of the rounds' ratios.
# Usage: scripts/light_scaling.sh [--size WxH] [--frames N] [--warmup N] [--rounds N]
#                                 [--preset P] [--counts "1000 10000 100000 1000000"]
#                                 [--set KEY=VALUE]... (passed to every bench, e.g. gbuffer=visibility)
#                                 [--compare KEY=VALUE] (e.g. restir.light_spread=1000)
set -euo pipefail
source "$(dirname "$0")/bench_common.sh"
size=320x180 frames=20 warmup=5 rounds=1 preset=balanced counts="1000 10000 100000 1000000"
compare=""
sets=()
bench_options light_scaling size frames warmup rounds preset counts set compare -- "$@"
bench_setup light_scaling
for n in $counts; do
  # The shipped level with only its emitter count changed (the generator checks the count).
  python3 - "$n" "$out/light_panels_$n.json" <<'PY'
import json, sys
level = json.load(open("content/levels/light_panels.json"))
level["generators"][0]["emitter_triangles"] = int(sys.argv[1])
level.pop("budgets", None)  # its path is relative to content/levels; the budget is for 10^3 only
json.dump(level, open(sys.argv[2], "w"), indent=2)
PY
done
for r in $(seq 1 "$rounds"); do
  for n in $counts; do
    runs=(restir baseline)
    [ -z "$compare" ] || runs=(restir compared baseline)
    for run in "${runs[@]}"; do
      echo "light_scaling: round $r, $n emitters, $run ($size, $warmup + $frames frames)" >&2
      integrator=$run extra=()
      [ "$run" != compared ] || { integrator=restir; extra=(--set "$compare"); }
      "$lantern" bench "$out/light_panels_$n.json" --integrator "$integrator" --preset "$preset" \
        --size "$size" --frames "$frames" --warmup "$warmup" --quiet "${sets[@]}" "${extra[@]}" \
        --json "$out/$run.$n.$r.json" >/dev/null
    done
  done
done
python3 - "$out" "$preset" "$size" "$rounds" "$compare" $counts <<'PY'
import json, statistics, sys
out, preset, size, rounds, compare = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5]
counts = sys.argv[6:]
passes = ["restir.initial", "restir.temporal", "restir.spatial", "restir.shade"]
def figures(integrator, n):
    """Medians over rounds of: frame, gbuffer (all gbuffer* passes), lighting (= frame - gbuffer), passes."""
    rows = []
    for r in range(1, rounds + 1):
        j = json.load(open(f"{out}/{integrator}.{n}.{r}.json"))
        frame = j["frame_ms"]["median"]
        gb = sum(s["median"] for k, s in j["passes"].items() if k == "gbuffer" or k.startswith("gbuffer."))
        rows.append([frame, gb, frame - gb] + [j["passes"].get(p, {}).get("median", float("nan")) for p in passes]
                    + [frame / j["calibration_ms"]])
    return [statistics.median(c) for c in zip(*rows)]
print(f"light_panels at {size}, {rounds} round(s): GPU ms (medians); ReSTIR {preset}")
print(f"{'emitters':>9} | {'baseline':>8} {'gbuffer':>7} {'light':>7} | {'restir':>8} {'gbuffer':>7} "
      f"{'light':>7} | {'ratio':>6} | " + " ".join(f"{p.split('.')[1]:>8}" for p in passes))
table = {}
for n in counts:
    b, r = figures("baseline", n), figures("restir", n)
    table[n] = (b, r)
    print(f"{int(n):>9} | {b[0]:8.2f} {b[1]:7.2f} {b[2]:7.2f} | {r[0]:8.2f} {r[1]:7.2f} {r[2]:7.2f} | "
          f"{r[0] / b[0]:5.2f}x | " + " ".join(f"{v:8.2f}" for v in r[3:-1]))
(b0, r0), (b1, r1) = table[counts[0]], table[counts[-1]]
print(f"growth {counts[0]} -> {counts[-1]}: restir frame {r1[0] / r0[0]:.2f}x "
      f"(lighting without the G-buffer {r1[2] / r0[2]:.2f}x), baseline frame {b1[0] / b0[0]:.2f}x "
      f"(lighting {b1[2] / b0[2]:.2f}x); goal: restir frame <= 1.3x")
print(f"  in units of the calibration workload timed in the same runs (less sensitive to other "
      f"jobs): restir frame {r1[-1] / r0[-1]:.2f}x, baseline frame {b1[-1] / b0[-1]:.2f}x")
if compare:
    def frames(run, n):
        return [json.load(open(f"{out}/{run}.{n}.{r}.json"))["frame_ms"]["median"] for r in range(1, rounds + 1)]
    lo, hi = counts[0], counts[-1]
    def growth(run):
        ratios = sorted(h / l for h, l in zip(frames(run, hi), frames("restir", lo)))
        return f"{statistics.median(ratios):.2f}x ({ratios[0]:.2f}-{ratios[-1]:.2f}x)"
    print(f"with --set {compare} (ReSTIR alternating with the plain runs, medians of the rounds' ratios):")
    for n in counts:
        ratios = [c / p for c, p in zip(frames("compared", n), frames("restir", n))]
        print(f"{int(n):>9} | frame {statistics.median(frames('compared', n)):8.2f} ms, "
              f"{statistics.median(ratios):.2f}x the plain ({min(ratios):.2f}-{max(ratios):.2f}x)")
    print(f"growth {lo} -> {hi} over the plain {lo} frame: plain {growth('restir')}, "
          f"with --set {compare} {growth('compared')}")
PY
