#!/usr/bin/env bash
# Issue 13 item 2: the closed-loop estimator's consistency and drift on `make run`'s hull-side
# sweep. Runs the mission for seeds 1..N and prints, per seed, the estimate's RMS error and
# its mean position NEES (full 3 × 3 covariance, averaged over the run; 3 when consistent),
# then the average NEES over the seeds with the two-sided 95 % band of the average of N
# independent χ²(3) values, [χ²(3N, 0.025), χ²(3N, 0.975)] / N, and the share of ticks whose
# ANEES over the seeds (diagonal σ of estimates.csv) falls in that band. Then one run with
# the UWB link dropped for the whole flight: the drift without absolute positioning, as the
# final and maximum error in % of the path flown.
#   scripts/mission-consistency.sh [build-dir] [work-dir] [seeds]
# Defaults: build, /tmp/scantling-consistency, 20 seeds (about 3.5 min on 2 cores since the
# wind compensation shortened the mission to 46 s).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"
work="${2:-/tmp/scantling-consistency}"
seeds="${3:-20}"
cli="$build/apps/scantling"
scenario="$root/scenarios/missions/hull_sweep_closed_loop.yaml"
[[ -x "$cli" ]] || { echo "mission-consistency: $cli not found: build $build first" >&2; exit 1; }
mkdir -p "$work"

for s in $(seq 1 "$seeds"); do
  "$cli" mission "$scenario" --out "$work/seed_$s" --seed "$s" --force --no-progress > /dev/null
done
"$cli" mission "$scenario" --out "$work/no_uwb" --force --no-progress \
  --set 'faults=[{sensor: uwb, kind: dropout, start_s: 0, duration_s: 1000}]' > /dev/null

python3 - "$work" "$seeds" <<'PY'
import csv, json, math, sys
work, n = sys.argv[1], int(sys.argv[2])

def chi2_quantile(p, k):
    # Wilson-Hilferty: accurate to ~1e-3 relative for k >= 30.
    z = {0.025: -1.959964, 0.975: 1.959964}[p]
    return k * (1 - 2 / (9 * k) + z * math.sqrt(2 / (9 * k))) ** 3

def truth(d):
    gt = {}
    for line in open(f"{d}/groundtruth.tum"):
        if not line.startswith("#"):
            v = line.split()
            gt[round(float(v[0]), 3)] = tuple(map(float, v[1:4]))
    return gt

lo, hi = chi2_quantile(0.025, 3 * n) / n, chi2_quantile(0.975, 3 * n) / n
per_tick, means = {}, []
print("| seed | completed | estimate RMS (m) | max (m) | mean NEES |")
print("|---|---|---|---|---|")
for s in range(1, n + 1):
    d = f"{work}/seed_{s}"
    summary = json.load(open(f"{d}/mission/summary.json"))
    means.append(summary["position_nees_mean"])
    print(f"| {s} | {'yes' if summary['completed'] else 'no'} | "
          f"{summary['position_error_rms_m']:.3f} | {summary['position_error_max_m']:.3f} | "
          f"{summary['position_nees_mean']:.2f} |")
    gt = truth(d)
    for r in csv.DictReader(open(f"{d}/mission/estimates.csv")):
        t = round(float(r["stamp_s"]), 3)
        if t not in gt:
            continue
        nees = sum(((float(r[a]) - gt[t][i]) / max(float(r["s" + a]), 1e-9)) ** 2
                   for i, a in enumerate("xyz"))
        per_tick.setdefault(t, []).append(nees)
full = [sum(v) / len(v) for v in per_tick.values() if len(v) == n]
inside = sum(lo <= a <= hi for a in full) / max(len(full), 1)
print(f"\nmean NEES over {n} seeds: {sum(means) / n:.2f} (per seed {min(means):.2f} .. "
      f"{max(means):.2f}); 95 % band of a {n}-seed average: [{lo:.2f}, {hi:.2f}]")
print(f"ticks whose {n}-seed ANEES (diagonal σ) is in the band: {100 * inside:.1f} % of {len(full)}; "
      f"below: {100 * sum(a < lo for a in full) / max(len(full), 1):.1f} %")
d = f"{work}/no_uwb"
summary = json.load(open(f"{d}/mission/summary.json"))
path = summary["path_length_m"]
print(f"\nwithout UWB: completed {summary['completed']}, path {path:.1f} m, final error "
      f"{summary['final_position_error_m']:.3f} m ({100 * summary['final_position_error_m'] / path:.2f} % "
      f"of the path), max {summary['position_error_max_m']:.3f} m "
      f"({100 * summary['position_error_max_m'] / path:.2f} %), RMS {summary['position_error_rms_m']:.3f} m")
PY
