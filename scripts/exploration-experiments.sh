#!/usr/bin/env bash
# Issue 16 item 3: the exploration of the large two-level ballast tank (SPEC §8, thesis art. G,
# table G.1; scenarios/missions/explore/ballast_large_explore.yaml) in closed loop, with the
# vanilla gain and with the defect-aware μ, then (EXPLORE_VARIANTS) the planner's improvement
# switched off. Prints one table row per run from its summary.json (the share of the reachable
# free volume mapped, exploration time, plans and their time, path length, detections per image)
# and writes the explored-volume curves as one SVG plot (work-dir/explored_volume.svg).
#   scripts/exploration-experiments.sh [build-dir] [work-dir]
# build-dir holds apps/scantling (default build), work-dir the recordings (default
# /tmp/scantling-explore). EXPLORE_SEED picks the seed (default: the scenario's).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"
work="${2:-/tmp/scantling-explore}"
cli="$build/apps/scantling"
[[ -x "$cli" ]] || { echo "exploration-experiments: $cli not found: build $build first" >&2; exit 1; }
mkdir -p "$work"
seed_args=()
[[ -n "${EXPLORE_SEED:-}" ]] && seed_args=(--seed "$EXPLORE_SEED")
scenario="$root/scenarios/missions/explore/ballast_large_explore.yaml"
# name|overrides
runs="${EXPLORE_VARIANTS:-vanilla|
defect_aware|stack.nbv.defect_aware=true}"

printf '| run | completed | reachable free mapped | explored (m³) | time (s) | plans (failed) | plan time mean / max (s) | path (m) | detections / image | defects mapped | nearest wall (m) | estimate RMS (m) | wall (s) |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|---|---|\n'
while IFS='|' read -r name overrides; do
  [[ -z "$name" ]] && continue
  set_args=()
  for o in $overrides; do set_args+=(--set "$o"); done
  out="$work/$name"
  "$cli" mission "$scenario" --out "$out" --force --no-progress "${seed_args[@]}" \
    "${set_args[@]}" > "$work/$name.txt"
  python3 - "$out/mission/summary.json" "$name" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {'yes' if s['completed'] else 'no'} | {100 * s['reachable_share']:.1f} % of "
      f"{s['reachable_free_m3']:.1f} m³ | {s['explored_m3']:.1f} | {s['exploration_time_s']:.0f} | "
      f"{s['plans']} ({s['plans_failed']}) | {s['plan_time_mean_s']:.3f} / {s['plan_time_max_s']:.3f} | "
      f"{s['path_length_m']:.1f} | {s['detections_per_image']:.2f} | {s['defects_mapped']} of "
      f"{s['defects_in_world']} | {s['min_wall_distance_m']:.2f} | {s['position_error_rms_m']:.3f} | "
      f"{s['wall_time_s']:.0f} |")
EOF
done <<< "$runs"

python3 - "$work" <<'EOF'
# The explored share of the reachable free volume against time, one polyline per run.
import os, sys
work = sys.argv[1]
curves = {}
for name in sorted(os.listdir(work)):
    path = os.path.join(work, name, "mission", "exploration.csv")
    if os.path.isfile(path):
        rows = [l.split() for l in open(path) if not l.startswith("#")]
        curves[name] = [(float(r[0]), float(r[2])) for r in rows]
if not curves:
    sys.exit(0)
t_max = max(t for c in curves.values() for t, _ in c) or 1.0
W, H, L, B = 640, 360, 60, 40
colours = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"]
svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
       f'<rect width="{W}" height="{H}" fill="white"/>',
       f'<line x1="{L}" y1="{H-B}" x2="{W-20}" y2="{H-B}" stroke="black"/>',
       f'<line x1="{L}" y1="20" x2="{L}" y2="{H-B}" stroke="black"/>',
       f'<text x="{W/2}" y="{H-8}" text-anchor="middle">time (s)</text>',
       f'<text x="14" y="{H/2}" transform="rotate(-90 14 {H/2})" text-anchor="middle">reachable free volume mapped (%)</text>']
for k in range(0, 101, 20):
    y = H - B - k / 100 * (H - B - 20)
    svg.append(f'<text x="{L-6}" y="{y+4}" text-anchor="end">{k}</text>')
    svg.append(f'<line x1="{L}" y1="{y}" x2="{W-20}" y2="{y}" stroke="#ddd"/>')
for k in range(6):
    t = t_max * k / 5
    x = L + k / 5 * (W - 20 - L)
    svg.append(f'<text x="{x}" y="{H-B+16}" text-anchor="middle">{t:.0f}</text>')
for i, (name, c) in enumerate(curves.items()):
    pts = " ".join(f"{L + t / t_max * (W - 20 - L):.1f},{H - B - s * (H - B - 20):.1f}" for t, s in c)
    colour = colours[i % len(colours)]
    svg.append(f'<polyline fill="none" stroke="{colour}" stroke-width="2" points="{pts}"/>')
    svg.append(f'<text x="{L+10}" y="{40 + 16 * i}" fill="{colour}">{name}</text>')
svg.append("</svg>")
open(os.path.join(work, "explored_volume.svg"), "w").write("\n".join(svg) + "\n")
print(f"\nplot: {os.path.join(work, 'explored_volume.svg')}")
EOF
