#!/usr/bin/env bash
# Issue 12: absolute localisation experiments (SPEC §7; docs/results.md "Absolute localisation").
# Simulates the mock-up inspection flight (and, for the consistency study, N seeds of the short
# mock-up flight), runs `scantling localize` in every configuration and prints one table row per
# run from its summary.json: fused error (mean, std, p95, max), VIO alone, accepted and all
# registrations, NEES, frame outcomes, time per tracking / re-localisation frame.
#   scripts/localization-experiments.sh [build-dir] [work-dir] [seeds]
# build-dir holds apps/scantling (default build), work-dir the recordings and outputs (default
# /tmp/scantling-localization), seeds the runs of the consistency study (default 20).
# LOCALIZATION_ONLY="rates nees" restricts the groups (rates, start, filters, sources, landmarks,
# nees).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"
work="${2:-/tmp/scantling-localization}"
seeds="${3:-20}"
only="${LOCALIZATION_ONLY:-rates start filters sources landmarks nees}"
cli="$build/apps/scantling"
[[ -x "$cli" ]] || { echo "localization-experiments: $cli not found: build $build first" >&2; exit 1; }
mkdir -p "$work"

simulate() {  # scenario-name seed
  local out="$work/rec_$1_$2"
  [[ -d "$out" ]] || "$cli" sim "$root/scenarios/$1.yaml" --out "$out" --seed "$2" --no-progress >/dev/null
  echo "$out"
}

row() {  # label recording [localize options...]
  local label="$1" rec="$2"
  shift 2
  local out="$work/out_${label// /_}"
  "$cli" localize "$rec" --out "$out" --no-progress "$@" >/dev/null
  python3 - "$label" "$out/summary.json" <<'PY'
import json, sys
label, path = sys.argv[1], sys.argv[2]
s = json.load(open(path))
f, v, a, r = s["fused_error_m"], s["vio_alone_error_m"], s["accepted_registration_error_m"], s["all_registrations_error_m"]
frames = " ".join(f"{k} {n}" for k, n in s["frames"].items())
print(f"| {label} | {f['mean']:.3f} ± {f['std']:.3f} | {f['p95']:.3f} | {f['max']:.3f} | "
      f"{v['mean']:.3f} ± {v['std']:.3f} | {a['mean']:.3f} ± {a['std']:.3f} ({a['count']}) | "
      f"{r['mean']:.3f} ± {r['std']:.3f} ({r['count']}) | {s['nees']['mean']:.2f} "
      f"[{s['nees']['band_95'][0]:.2f}, {s['nees']['band_95'][1]:.2f}] | "
      f"{s['tracking_ms']['mean']:.0f} / {s['relocalization_ms']['mean']:.0f} | {frames} |")
PY
}

header() {
  echo
  echo "### $1"
  echo
  echo "| run | fused mean ± std (m) | fused p95 | fused max | VIO alone (m) | accepted registrations (m, n) | all registrations (m, n) | NEES [95 % band] | ms tracking / re-loc. | frames |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
}

flight="$(simulate mockup_inspection_flight 3)"  # the scenario's seed (VIO 0.166 m)
sources_config="$root/config/localization/sources_pipeline.yaml"
ours_global_config="$work/ours_global.yaml"
printf 'global_every_frame: true\n' >"$ours_global_config"

if [[ " $only " == *" rates "* ]]; then
  header "Mock-up flight, known start, registration rate (EKF, ICP tracking)"
  for rate in 0.1 1 3 10; do row "rate $rate Hz" "$flight" --rate "$rate"; done
fi
if [[ " $only " == *" start "* ]]; then
  header "Mock-up flight, unknown (kidnapped) start"
  for rate in 0.1 10; do row "unknown start $rate Hz" "$flight" --start unknown --rate "$rate"; done
fi
if [[ " $only " == *" filters "* ]]; then
  header "Mock-up flight, EKF vs UKF, ICP vs Stein-ICP tracking (1 Hz)"
  row "ekf icp 1 Hz" "$flight" --rate 1 --filter ekf
  row "ukf icp 1 Hz" "$flight" --rate 1 --filter ukf
  row "ekf stein 1 Hz" "$flight" --rate 1 --method stein
fi
if [[ " $only " == *" sources "* ]]; then
  header "Mock-up flight, every frame registered globally (the sources' pipeline) at 0.1 Hz"
  row "FPFH + robust, motion filter, EKF" "$flight" --rate 0.1 --config "$sources_config"
  row "correlative, motion filter, EKF" "$flight" --rate 0.1 --config "$ours_global_config"
fi
if [[ " $only " == *" landmarks "* ]]; then
  header "Mock-up flight, known start, hierarchical landmarks (art. B) instead of ICP"
  for rate in 1 10; do row "landmarks $rate Hz" "$flight" --method landmarks --rate "$rate"; done
fi
if [[ " $only " == *" nees "* ]]; then
  header "Consistency: $seeds seeds of the short mock-up flight (10 Hz, known start)"
  for seed in $(seq 1 "$seeds"); do
    row "seed $seed" "$(simulate ballast_mockup_l515 "$seed")"
  done
  # Pooled over the seeds: mean NEES of all samples and the 95 % band of that mean.
  python3 - "$work" "$seeds" <<'PY'
import json, math, sys
work, seeds = sys.argv[1], int(sys.argv[2])
total = n = 0
for seed in range(1, seeds + 1):
    s = json.load(open(f"{work}/out_seed_{seed}/summary.json"))["nees"]
    total += s["mean"] * s["samples"]
    n += s["samples"]
k = 6 * n
band = [k * (1 - 2 / (9 * k) + z * math.sqrt(2 / (9 * k))) ** 3 / n for z in (-1.959964, 1.959964)]
print(f"\nPooled over {seeds} seeds: mean NEES {total / n:.2f} over {n} samples, "
      f"95 % band of the mean [{band[0]:.2f}, {band[1]:.2f}] (6-DoF)")
PY
fi
