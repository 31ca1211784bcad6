#!/usr/bin/env bash
# Issue 4, item 4: LiODOM against the scan-to-scan point-to-plane ICP baseline on the
# simulator's scenarios. Simulates each scenario (unless its recording exists), runs both
# odometries and prints one table row per run from `scantling eval --json`.
#   scripts/odometry-experiments.sh [build-dir] [work-dir]
# Recordings take ~3.5 GB in work-dir (default /tmp/scantling-odometry).
set -euo pipefail
build="${1:-build}"
work="${2:-/tmp/scantling-odometry}"
cli="$build/apps/scantling"
mkdir -p "$work"

# scenario | extra odometry arguments | label
runs=(
  "urban_drive_hdl64|--preset kitti|urban drive, HDL-64E, 1.18 km"
  "ballast_large_os0|--preset confined|large ballast tank, OS0-64"
  "storage_tank_orbit_os1|--preset os1_drone|storage tank orbit, OS1-64"
  "hull_sweep_os1|--preset os1_drone|hull side in dock, OS1-64"
  "hull_sweep_os1|--config config/odometry/examples/hull_side_vio.yaml --prior vio|hull side + VIO prior"
)

metric() {  # json key
  python3 -c "import json,sys; v=json.load(open(sys.argv[1])).get(sys.argv[2]); print('n/a' if v is None else (f'{v:.4f}' if isinstance(v,float) else v))" "$1" "$2"
}

printf "| run | method | path m | rte %% | ate m | ate %% of path | median ms (extract/register/map) |\n"
printf "|---|---|---|---|---|---|---|\n"
for entry in "${runs[@]}"; do
  IFS='|' read -r scenario extra label <<<"$entry"
  rec="$work/$scenario"
  if [[ ! -f "$rec/summary.json" ]]; then
    "$cli" sim "scenarios/$scenario.yaml" --out "$rec" --force --no-progress >/dev/null
  fi
  for method in liodom icp; do
    tag="$scenario-$method-$(echo "$extra" | tr -c 'a-z0-9' '_' | cut -c1-40)"
    # shellcheck disable=SC2086
    "$cli" odometry "$rec" --out "$work/$tag.txt" --method "$method" $extra --no-progress \
      >"$work/$tag.log" 2>"$work/$tag.err"
    "$cli" eval --gt "$work/${tag}_gt.txt" --est "$work/$tag.txt" --json --no-plots >"$work/$tag.json"
    times=$(grep median_ms "$work/$tag.log" | sed 's/median_ms: //')
    printf "| %s | %s | %s | %s | %s | %s | %s |\n" "$label" "$method" \
      "$(metric "$work/$tag.json" path_length_m)" "$(metric "$work/$tag.json" rte_percent)" \
      "$(metric "$work/$tag.json" ate_rmse_m)" "$(metric "$work/$tag.json" ate_percent_of_path)" \
      "$times"
  done
done
