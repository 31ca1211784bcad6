#!/usr/bin/env bash
# Issue 14 item 7: the ROV hull surveys of SPEC §5 in closed loop (scenarios/missions/rov/): the
# 30 x 5 m section of the parametric hull with horizontal slices at 1.0 m and vertical slices at
# 1.3 m, and a 20 x 5 m stretch of the real DTC hull (needs ../shared/data; skipped with a
# message without it), all in a current. Prints one table row per survey from its summary.json:
# stand-off error (mean, max), heading error, the true camera coverage after the slices and after
# the re-inspection, holes found, mission time and the real-time factor.
#   scripts/rov-experiments.sh [build-dir] [work-dir]
# build-dir holds apps/scantling (default build), work-dir the recordings (default
# /tmp/scantling-rov). ROV_ONLY="hull_survey_vertical" restricts the surveys; ROV_SEED picks the
# seed (default: the scenarios' 1).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"
work="${2:-/tmp/scantling-rov}"
only="${ROV_ONLY:-hull_survey_horizontal hull_survey_vertical dtc_hull_survey}"
cli="$build/apps/scantling"
[[ -x "$cli" ]] || { echo "rov-experiments: $cli not found: build $build first" >&2; exit 1; }
mkdir -p "$work"
seed_args=()
[[ -n "${ROV_SEED:-}" ]] && seed_args=(--seed "$ROV_SEED")
mesh="$root/../shared/data/meshes/dtc-container-ship-hull-model-scale.stl"

printf '%-24s %10s %9s %9s %10s %10s %6s %9s %6s\n' survey standoff_m max_m heading covered_% \
  final_% holes time_s rt_x
for survey in $only; do
  if [[ "$survey" == dtc_hull_survey && ! -f "$mesh" ]]; then
    echo "rov-experiments: $survey skipped: $mesh is absent (../shared/data)"
    continue
  fi
  out="$work/$survey"
  "$cli" mission "$root/scenarios/missions/rov/$survey.yaml" --out "$out" --force --no-progress \
    "${seed_args[@]}" > "$out.txt"
  python3 - "$out/mission/summary.json" "$survey" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
survey = s.get("camera_coverage_survey", {}).get("covered_fraction", 0.0)
final = s.get("camera_coverage", {}).get("covered_fraction", 0.0)
print(f"{sys.argv[2]:<24} {s['stand_off_error_mean_m']:10.3f} {s['stand_off_error_max_m']:9.3f} "
      f"{s['heading_error_mean_deg']:8.2f}° {100 * survey:10.2f} {100 * final:10.2f} "
      f"{s['holes_found']:6d} {s['mission_time_s']:9.1f} {s['real_time_factor']:6.1f}"
      + ("" if s["completed"] else f"  ({s['final_state']})"))
PY
done
