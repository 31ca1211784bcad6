#!/usr/bin/env bash
# Issue 13 item 5: D5.2's HIL experiments (figures 11-18) in closed loop: go-to-point A -> B,
# sweeping 8 x 5 m, vertical inspection 9 x 3 m, each in a 5 m/s wind with gusts, with the VTP
# follower off and on (scenarios/missions/d52/). Prints one table row per run from its
# summary.json (mean and max distance of the true path to the intended one while the mission
# ran, completion time, estimate error) and the off/on ratio of the deviations, and draws each
# experiment's top and front views (intended path, follower off, follower on) with gnuplot.
#   scripts/d52-experiments.sh [build-dir] [work-dir] [figures-dir]
# build-dir holds apps/scantling (default build), work-dir the recordings (default
# /tmp/scantling-d52), figures-dir the SVG plots (default: work-dir). D52_ONLY="goto_ab"
# restricts the experiments; D52_SEED picks the seed (default: the scenarios' 1); D52_SET adds
# one --set override to every run (e.g. D52_SET=stack.wind_compensation=false).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"
work="${2:-/tmp/scantling-d52}"
figures="${3:-$work}"
only="${D52_ONLY:-goto_ab sweep_8x5 vertical_9x3}"
cli="$build/apps/scantling"
[[ -x "$cli" ]] || { echo "d52-experiments: $cli not found: build $build first" >&2; exit 1; }
mkdir -p "$work" "$figures"
seed_args=()
[[ -n "${D52_SEED:-}" ]] && seed_args=(--seed "$D52_SEED")
[[ -n "${D52_SET:-}" ]] && seed_args+=(--set "$D52_SET")

run() {  # experiment follower(on|off)
  local out="$work/$1_$2" vtp=true
  [[ "$2" == off ]] && vtp=false
  "$cli" mission "$root/scenarios/missions/d52/$1.yaml" --out "$out" --force --no-progress \
    --set "stack.manager.tracking.use_vtp=$vtp" "${seed_args[@]}" > /dev/null
}

# Every 20th ground-truth pose (10 Hz) as "x y z" lines, and the intended polyline (start first).
paths() {  # experiment
  for f in off on; do
    awk 'NR > 1 && (NR - 2) % 20 == 0 { print $2, $3, $4 }' "$work/$1_$f/groundtruth.tum" \
      > "$work/$1_$f.xyz"
  done
  { awk 'NR == 2 { print $2, $3, $4 }' "$work/$1_on/groundtruth.tum"
    awk -F, 'NR > 1 { print $2, $3, $4 }' "$work/$1_on/mission/intended_path.csv"; } \
    > "$work/$1_intended.xyz"
}

plot() {  # experiment
  command -v gnuplot > /dev/null || { echo "d52-experiments: gnuplot not found (make deps)" >&2; return; }
  gnuplot <<GP
set terminal svg size 900,900 font "sans,12" background "white"
set output "$figures/d52_$1.svg"
set multiplot layout 2,1 title "D5.2 $1: 5 m/s wind with gusts, follower off and on (closed loop)"
set grid
set key outside right
set size ratio -1
set title "top view"
set xlabel "x (m)"; set ylabel "y (m)"
plot "$work/$1_intended.xyz" u 1:2 w lp lc rgb "black" dt 2 pt 7 ps 0.5 t "intended", \
     "$work/$1_off.xyz" u 1:2 w l lc rgb "#d62728" t "follower off", \
     "$work/$1_on.xyz" u 1:2 w l lc rgb "#1f77b4" t "follower on"
set title "front view (from the hull)"
set xlabel "x (m)"; set ylabel "z (m)"
plot "$work/$1_intended.xyz" u 1:3 w lp lc rgb "black" dt 2 pt 7 ps 0.5 t "intended", \
     "$work/$1_off.xyz" u 1:3 w l lc rgb "#d62728" t "follower off", \
     "$work/$1_on.xyz" u 1:3 w l lc rgb "#1f77b4" t "follower on"
unset multiplot
GP
}

printf '| experiment | follower | completed | time (s) | deviation mean (m) | deviation max (m) | estimate RMS (m) |\n'
printf '|---|---|---|---|---|---|---|\n'
for e in $only; do
  for f in off on; do
    run "$e" "$f"
    python3 - "$e" "$f" "$work/${e}_$f/mission/summary.json" <<'PY'
import json, sys
e, f, path = sys.argv[1:4]
s = json.load(open(path))
print(f"| {e} | {f} | {'yes' if s['completed'] else 'no'} | {s['mission_time_s']:.1f} | "
      f"{s['path_deviation_mean_m']:.3f} | {s['path_deviation_max_m']:.3f} | "
      f"{s['position_error_rms_m']:.3f} |")
PY
  done
  paths "$e"
  plot "$e"
done
for e in $only; do
  python3 - "$e" "$work/${e}_off/mission/summary.json" "$work/${e}_on/mission/summary.json" <<'PY'
import json, sys
e, off, on = sys.argv[1], json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
ratio = lambda k: off[k] / on[k] if on[k] > 0 else float("inf")
print(f"{e}: off/on deviation ratio mean {ratio('path_deviation_mean_m'):.2f}, "
      f"max {ratio('path_deviation_max_m'):.2f}")
PY
done
echo "d52-experiments: recordings in $work, plots in $figures/d52_*.svg"
