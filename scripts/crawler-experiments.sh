#!/usr/bin/env bash
# Issue 15 item 6: the crawler's rectangle missions of SPEC §6 in closed loop
# (scenarios/missions/crawler/): the storage tank's shell (6 x 2 m), the flat 5 x 2 m plate
# with UWB, the 2 x 1 m plate on IMU and wheels only, the real DTC hull's side (needs
# ../shared/data; skipped with a message without it), and 3 x 0.7 m along the Möbius strip
# through its twist, and the 5 x 2 m plate with labelled obstacles and stop-and-map. Prints one
# table row per run from its summary.json: cross-track error
# (mean, max; truth to the intended transects), the share of the rectangle within half a swath
# of the true path, the PF's error against the truth, mission time and the real-time factor;
# then, for the runs with a LiDAR, the stop-and-map's obstacle recall per class (found / in
# view, summed over the stops), precision per sign, and the stops' map and PF poses; then the
# three stiffener drives (DriveBetweenStiffeners, DriveOnStiffener, DriveOnStiffenerSide: the
# corridor from the LiDAR) with the true lateral error from the face's true centre line
# (written in each scenario's comment) while on the corridor, x from -1.4 to 0.6 m. The Möbius
# task run (go_to on the geodesic, transects) reports its transects' cross-track in the first.
#   scripts/crawler-experiments.sh [build-dir] [work-dir]
# build-dir holds apps/scantling (default build), work-dir the recordings (default
# /tmp/scantling-crawler). CRAWLER_ONLY="plate_2x1_imu" restricts the runs; CRAWLER_SEED picks
# the seed (default: the scenarios').
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"
work="${2:-/tmp/scantling-crawler}"
only="${CRAWLER_ONLY:-storage_tank_rectangle plate_5x2_rectangle plate_2x1_imu dtc_hull_rectangle moebius_rectangle plate_5x2_obstacles moebius_tasks plate_5x2_between_stiffeners stiffener_top stiffener_side}"
cli="$build/apps/scantling"
[[ -x "$cli" ]] || { echo "crawler-experiments: $cli not found: build $build first" >&2; exit 1; }
mkdir -p "$work"
seed_args=()
[[ -n "${CRAWLER_SEED:-}" ]] && seed_args=(--seed "$CRAWLER_SEED")
mesh="$root/../shared/data/meshes/dtc-container-ship-hull-model-scale.stl"

printf '| run | completed | transects | cross-track mean (m) | max (m) | coverage (%%) | PF error RMS (m) | max (m) | heading RMS (°) | time (s) | real time |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|\n'
for run in $only; do
  if [[ "$run" == dtc_hull_rectangle && ! -f "$mesh" ]]; then
    echo "crawler-experiments: $run skipped: $mesh is absent (../shared/data)"
    continue
  fi
  out="$work/$run"
  "$cli" mission "$root/scenarios/missions/crawler/$run.yaml" --out "$out" --force --no-progress \
    "${seed_args[@]}" > "$out.txt"
  python3 - "$out/mission/summary.json" "$run" <<'PY'
import json, math, sys
s = json.load(open(sys.argv[1]))
cover = "-" if s['coverage'] is None else f"{100 * s['coverage']:.1f}"
print(f"| {sys.argv[2]} | {'yes' if s['completed'] else 'no'} | {s['transects']} | "
      f"{s['cross_track_mean_m']:.3f} | {s['cross_track_max_m']:.3f} | {cover} | "
      f"{s['position_error_rms_m']:.3f} | {s['position_error_max_m']:.3f} | "
      f"{math.degrees(s['yaw_error_rms_rad']):.2f} | {s['mission_time_s']:.1f} | "
      f"{s['real_time_factor']:.0f}x |")
PY
done
# The stop-and-map figures of the runs that carry a LiDAR (summary.json "stop_and_map").
printf '\n| run | stops | ICP applied | weld bead | bolt | bracket | hole | plate edge | positive precision | negative precision | map pose RMS (m) | PF at stops RMS (m) |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|---|\n'
for run in $only; do
  summary="$work/$run/mission/summary.json"
  [[ -f "$summary" ]] || continue
  python3 - "$summary" "$run" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])).get("stop_and_map")
# Only the runs with labelled obstacles besides the plate's own edges (the stiffener drives'
# webs and flanges are the corridor, not labelled obstacles).
if s and any(kind != "plate_edge" for kind in s["recall"]):
    def rec(kind):
        r = s["recall"].get(kind)
        return f"{r['found']}/{r['in_view']}" if r else "-"
    def prec(sign):
        n = s[f"{sign}_clusters"]
        return f"{s[f'{sign}_precision']:.2f} of {n}" if n else "-"
    print(f"| {sys.argv[2]} | {s['stops']} | {s['stops_icp_applied']} | {rec('weld_bead')} | "
          f"{rec('bolt')} | {rec('bracket')} | {rec('hole')} | {rec('plate_edge')} | "
          f"{prec('positive')} | {prec('negative')} | {s['map_pose_error_rms_m']:.3f} | "
          f"{s['pf_at_stops_error_rms_m']:.3f} |")
PY
done
# The stiffener drives: the true lateral error from the face's true centre line (axis 1 = y,
# 2 = z, and its value, as each scenario's comment gives them), and the corridor the LiDAR gave.
printf '\n| run | completed | corridor width (m) | bounds | lateral error mean (m) | max (m) | ticks |\n'
printf '|---|---|---|---|---|---|---|\n'
for spec in "plate_5x2_between_stiffeners 1 0.0" "stiffener_top 1 0.095" "stiffener_side 2 0.2"; do
  read -r run axis centre <<< "$spec"
  [[ -f "$work/$run/groundtruth.tum" ]] || continue
  python3 - "$work/$run" "$run" "$axis" "$centre" <<'PY'
import json, sys
d, run, axis, centre = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
s = json.load(open(f"{d}/mission/summary.json"))
errors = []
for line in open(f"{d}/groundtruth.tum"):
    if line.startswith("#") or not line.strip():
        continue
    v = [float(x) for x in line.split()]
    if -1.4 <= v[1] <= 0.6:
        errors.append(abs(v[1 + axis] - centre))
corridor = next((json.loads(l) for l in open(f"{d}/mission/events.jsonl")
                 if '"corridor_found"' in l), None)
width = f"{corridor['width_m']:.3f}" if corridor else "-"
bounds = f"{corridor['left']} / {corridor['right']}" if corridor else "-"
mean = sum(errors) / len(errors) if errors else float("nan")
print(f"| {run} | {'yes' if s['completed'] else 'no'} | {width} | {bounds} | {mean:.4f} | "
      f"{max(errors, default=float('nan')):.4f} | {len(errors)} |")
PY
done
echo "crawler-experiments: recordings in $work"
