#!/usr/bin/env bash
# Issue 11: LiODOM against KISS-ICP 1.2.3 on the same recordings, in one run. Builds KISS-ICP
# and its driver from ../shared/baselines (skips with a message when that folder is absent),
# simulates the recordings that are missing, runs both odometries as whole processes on 1 and
# on 2 threads, and prints one row per recording: drift of both, frames per second of both
# (sweeps / wall time of the process, reading the sweeps included), their ratios, and whether
# our 1- and 2-thread trajectories are bit-identical.
#   scripts/odometry-vs-kiss.sh [build-dir] [work-dir]
# build-dir holds apps/scantling (default build-bench); work-dir holds the recordings (~3.5 GB,
# default /tmp/scantling-odometry, shared with scripts/odometry-experiments.sh).
# ODOMETRY_VS_KISS_ONLY="urban kitti16" restricts the rows (labels below);
# ODOMETRY_VS_KISS_THREADS (default "1 2") the thread counts.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build-bench}"
work="${2:-/tmp/scantling-odometry}"
baselines="${SCANTLING_BASELINES_DIR:-$root/../shared/baselines}"
data="${SCANTLING_SHARED_DATA_DIR:-$root/../shared/data}"
threads_list="${ODOMETRY_VS_KISS_THREADS:-1 2}"
only="${ODOMETRY_VS_KISS_ONLY:-}"
cli="$build/apps/scantling"

if [[ ! -f "$baselines/kiss-icp-driver/CMakeLists.txt" ]]; then
  echo "SKIP: LiODOM vs KISS-ICP: $baselines/kiss-icp-driver is absent (set" \
    "SCANTLING_BASELINES_DIR to a copy of ../shared/baselines)"
  exit 0
fi
if [[ ! -x "$cli" ]]; then
  echo "odometry-vs-kiss: $cli not found: build $build first" >&2
  exit 1
fi

kiss_build="$build/kiss-icp"
cmake -S "$baselines/kiss-icp-driver" -B "$kiss_build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$kiss_build" -j "$(nproc)" >/dev/null
kiss="$kiss_build/kiss_icp_driver"
mkdir -p "$work"

# label | recording (scenario name, or a folder of sweeps) | our arguments | KISS max/min range
rows=(
  "urban|urban_drive_hdl64|--preset kitti|100 0"
  "kitti16|$data/lidar-scans|--preset kitti|100 0"
  "hull_os1|hull_sweep_os1|--preset os1_drone|100 0"
  "tank_os1|storage_tank_orbit_os1|--preset os1_drone|100 0"
  "ballast_os0|ballast_large_os0|--preset confined|20 0"
)

now() { date +%s.%N; }
fps() { python3 -c "import sys; print(f'{int(sys.argv[1]) / (float(sys.argv[3]) - float(sys.argv[2])):.1f}')" "$@"; }
ratio() { python3 -c "import sys; a, b = map(float, sys.argv[1:]); print(f'{a / b:.2f}' if b else 'n/a')" "$@"; }
drift() {  # eval json → "RTE x %" (paths over 100 m) or "ATE x % of path"
  python3 -c "
import json, sys
j = json.load(open(sys.argv[1]))
if j.get('rte_percent') is not None: print(f\"RTE {j['rte_percent']:.3f} %\")
elif j.get('ate_percent_of_path') is not None: print(f\"ATE {j['ate_percent_of_path']:.2f} %\")
else: print('n/a')" "$1"
}

# Recording folder of a row: simulated into work-dir when missing.
recording_of() {
  local source="$1"
  if [[ -d "$source" ]]; then
    echo "$source"
    return
  fi
  local rec="$work/$source"
  if [[ ! -f "$rec/summary.json" ]]; then
    echo "odometry-vs-kiss: simulating $source into $rec" >&2
    "$cli" sim "$root/scenarios/$source.yaml" --out "$rec" --force --no-progress >/dev/null
  fi
  echo "$rec"
}

echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%dT%H:%MZ)"
printf "| recording | sweeps | path m | LiODOM drift | KISS-ICP drift |"
for t in $threads_list; do printf " fps %s thr: LiODOM / KISS (×) |" "$t"; done
printf " 1 = 2 thr |\n|---|---|---|---|---|"
for _ in $threads_list; do printf -- "---|"; done
printf -- "---|\n"

for row in "${rows[@]}"; do
  IFS='|' read -r label source args ranges <<<"$row"
  [[ -n "$only" && " $only " != *" $label "* ]] && continue
  if [[ "$source" == /* && ! -d "$source" ]]; then
    echo "SKIP: $label: $source is absent"
    continue
  fi
  rec="$(recording_of "$source")"
  sweeps_dir="$rec"
  [[ -d "$rec/lidar" ]] && sweeps_dir="$rec/lidar"
  n=$(find "$sweeps_dir" -maxdepth 1 \( -name '*.pcd' -o -name '*.bin' \) | wc -l)
  cat "$sweeps_dir"/* >/dev/null  # both read from the page cache
  cells=""
  first_ours=""
  identical="yes"
  ours_json="" kiss_json=""
  for t in $threads_list; do
    ours="$work/vs-kiss-$label-ours-${t}thr.txt"
    theirs="$work/vs-kiss-$label-kiss-${t}thr.txt"
    start=$(now)
    # shellcheck disable=SC2086
    "$cli" odometry "$rec" --out "$ours" $args --threads "$t" --no-progress >"$ours.log"
    ours_fps=$(fps "$n" "$start" "$(now)")
    start=$(now)
    # shellcheck disable=SC2086
    "$kiss" "$sweeps_dir" "$theirs" $ranges "$t" >"$theirs.log" 2>&1
    kiss_fps=$(fps "$n" "$start" "$(now)")
    cells+=" $ours_fps / $kiss_fps ($(ratio "$ours_fps" "$kiss_fps")) |"
    if [[ -z "$first_ours" ]]; then
      first_ours="$ours"
      gt="${ours%.txt}_gt.txt"
      if [[ -f "$gt" ]]; then
        ours_json="$ours.json" kiss_json="$theirs.json"
        "$cli" eval --gt "$gt" --est "$ours" --json --no-plots >"$ours_json"
        "$cli" eval --gt "$gt" --est "$theirs" --json --no-plots >"$kiss_json"
      fi
    elif ! cmp -s "$first_ours" "$ours"; then
      identical="NO"
    fi
  done
  if [[ -n "$ours_json" ]]; then
    path=$(python3 -c "import json,sys; print(f\"{json.load(open(sys.argv[1]))['path_length_m']:.0f}\")" "$ours_json")
    printf "| %s | %s | %s | %s | %s |%s %s |\n" "$label" "$n" "$path" "$(drift "$ours_json")" \
      "$(drift "$kiss_json")" "$cells" "$identical"
  else
    printf "| %s | %s | — | (no ground truth) | |%s %s |\n" "$label" "$n" "$cells" "$identical"
  fi
done
