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
# velocity, nees, column, defects). velocity: the VIO's body velocity instead of its pose
# (--vio velocity, art. E's T265 input). column: art. F's tables F.1/F.2 (the legged base's loop
# in the distillation column, `--method column`): x, y, yaw error of the raw registrations and
# of the fused pose. defects: the defect survey flight (scenarios/mockup_defect_survey.yaml),
# every defect the camera saw against the world's.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"
work="${2:-/tmp/scantling-localization}"
seeds="${3:-20}"
only="${LOCALIZATION_ONLY:-rates start filters sources landmarks velocity nees column defects}"
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

flight=""
for group in rates start filters sources landmarks velocity; do
  if [[ " $only " == *" $group "* ]]; then
    flight="$(simulate mockup_inspection_flight 3)"  # the scenario's seed (VIO 0.166 m)
    break
  fi
done
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
if [[ " $only " == *" velocity "* ]]; then
  header "Inspection flight, the VIO's velocity instead of its pose (--vio velocity)"
  row "velocity, EKF, 10 Hz" "$flight" --vio velocity
  row "velocity, UKF, 0.5 Hz (art. E)" "$flight" --vio velocity --filter ukf --rate 0.5
  row "pose, UKF, 0.5 Hz" "$flight" --filter ukf --rate 0.5
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
if [[ " $only " == *" column "* ]]; then
  # Art. F, table F.1's rows: signed error (estimate - truth) of x, y (m) and yaw (deg); mean and
  # std signed, 95th percentile and max of the absolute error. Raw: every tracking frame the
  # 3-DoF registration produced a pose for (accepted or rejected by the gates; re-localisations
  # after a VIO dropout are counted apart); fused: the filter's pose at every VIO sample
  # (trajectory.tum), the stretches without registrations included.
  column="$(simulate column_legged_azure 12)"  # the scenario's seed
  out="$work/out_column"
  "$cli" localize "$column" --out "$out" --no-progress --method column >/dev/null
  python3 - "$column/groundtruth.tum" "$out" <<'PY'
import bisect, csv, json, math, sys
gt_path, out = sys.argv[1], sys.argv[2]

def tum(path):
    rows = []
    for line in open(path):
        if line.strip() and not line.startswith("#"):
            t, x, y, z, qx, qy, qz, qw = map(float, line.split()[:8])
            rows.append((t, x, y, math.degrees(math.atan2(2 * (qw * qz + qx * qy),
                                                          1 - 2 * (qy * qy + qz * qz)))))
    return rows

gt = tum(gt_path)
gt_t = [r[0] for r in gt]

def truth(t):  # nearest ground-truth sample (200 Hz: < 2.5 ms away)
    i = bisect.bisect_left(gt_t, t)
    if i > 0 and (i == len(gt) or t - gt_t[i - 1] < gt_t[i] - t):
        i -= 1
    return gt[i]

def errors(samples):  # [(t, x, y, yaw_deg)] -> three lists of signed errors
    ex, ey, eyaw = [], [], []
    for t, x, y, yaw in samples:
        _, tx, ty, tyaw = truth(t)
        ex.append(x - tx)
        ey.append(y - ty)
        eyaw.append((yaw - tyaw + 180.0) % 360.0 - 180.0)
    return ex, ey, eyaw

def stats(v):
    n = len(v)
    mean = sum(v) / n
    std = math.sqrt(sum((a - mean) ** 2 for a in v) / max(n - 1, 1))
    a = sorted(abs(x) for x in v)
    return mean, std, a[min(n - 1, int(math.ceil(0.95 * n)) - 1)], a[-1]

raw, accepted, outcomes, reloc, ms, warnings = [], [], {}, {}, [], []
for r in csv.DictReader(open(f"{out}/events.csv")):
    if r["kind"] != "frame":
        warnings.append(f"{float(r['stamp_s']):.1f} s {r['gate']}: {r['message']}")
        continue
    key = r["gate"] or r["outcome"]
    outcomes[key] = outcomes.get(key, 0) + 1
    if r["mode"] == "relocalization":  # after a VIO dropout: the correlative search, not art. F
        reloc[r["outcome"]] = reloc.get(r["outcome"], 0) + 1
    elif r["x"]:
        raw.append((float(r["stamp_s"]), float(r["x"]), float(r["y"]), float(r["yaw_deg"])))
        if r["outcome"] == "registered":
            accepted.append(raw[-1])
        ms.append(float(r["compute_ms"]))
fused = [(t, x, y, yaw) for t, x, y, yaw in tum(f"{out}/trajectory.tum")]

def vio_alone(path):  # the VIO's poses with its start put on the first true pose
    rows = [r for r in csv.DictReader(open(path)) if r["valid"] == "1"]
    _, gx, gy, gyaw = truth(float(rows[0]["stamp_s"]))
    def planar(r):  # x, y, yaw of a VIO row
        qx, qy, qz, qw = (float(r[k]) for k in ("qx", "qy", "qz", "qw"))
        return float(r["x"]), float(r["y"]), math.atan2(2 * (qw * qz + qx * qy),
                                                        1 - 2 * (qy * qy + qz * qz))
    x0, y0, a0 = planar(rows[0])
    da = math.radians(gyaw) - a0
    c, s_ = math.cos(da), math.sin(da)
    out_rows = []
    for r in rows:
        x, y, a = planar(r)
        dx, dy = x - x0, y - y0
        out_rows.append((float(r["stamp_s"]), gx + c * dx - s_ * dy, gy + s_ * dx + c * dy,
                         math.degrees(a + da)))
    return out_rows

vio = vio_alone(f"{gt_path.rsplit('/', 1)[0]}/vio.csv")
print("\n### Article F, table F.1 (simulation): legged base in the column, --method column\n")
print("| Table F.1, scantling | x (m) | y (m) | yaw (deg) |")
print("|---|---|---|---|")
for name, samples in (("raw registration", raw), ("whole pipeline", fused),
                      ("(raw, only those the gates accepted)", accepted), ("(VIO alone)", vio)):
    cols = [stats(e) for e in errors(samples)]
    for k, label in enumerate(("mean", "std", "95th percentile of abs", "max abs")):
        cells = " | ".join(f"{c[k]:.4f}" if j < 2 else f"{c[k]:.3f}" for j, c in enumerate(cols))
        print(f"| {name} {label} | {cells} |")
print(f"\nraw registrations: {len(raw)} ({len(accepted)} accepted); fused samples: {len(fused)}")
print("frames: " + " ".join(f"{k} {n}" for k, n in sorted(outcomes.items())))
print("re-localisation frames (not in the table): " +
      (" ".join(f"{k} {n}" for k, n in sorted(reloc.items())) or "none"))
print("warnings: " + ("; ".join(warnings) or "none"))
if ms:
    ms.sort()
    print(f"time per registered frame: mean {sum(ms) / len(ms):.0f} ms, median {ms[len(ms) // 2]:.0f} ms")
s = json.load(open(f"{out}/summary.json"))
for key in ("fused_error_m", "vio_alone_error_m", "fused_yaw_error_deg"):
    v = s[key]
    print(f"{key}: mean {v['mean']:.4f} std {v['std']:.4f} p95 {v['p95']:.4f} max {v['max']:.4f}")
PY
fi
if [[ " $only " == *" defects "* ]]; then
  survey="$(simulate mockup_defect_survey 3)"  # the scenario's seed
  out="$work/out_defects"
  "$cli" localize "$survey" --out "$out" --no-progress >/dev/null
  python3 - "$out/defects.json" "$survey/world/metadata.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
world = json.load(open(sys.argv[2]))
print("\n### Defects: survey flight through the mock-up (--method icp, 10 Hz tracking)\n")
print("| defect | kind, surface | views | location (ours) | error (m) | largest σ (m) | right frame | right longitudinal |")
print("|---|---|---|---|---|---|---|---|")
errors = []
for x in d["defects"]:
    truth = world["defects"][x["id"]]
    surface = world["surfaces"][truth["surface_tag"]]["name"]
    t = x["truth"]
    errors.append(t["error_m"])
    print(f"| {x['id']} | {truth['kind']}, {surface} | {x['views']} | {x['location']['text']} | "
          f"{t['error_m']:.4f} | {x['largest_sigma_m']:.4f} | {'yes' if t['right_frame'] else 'NO'} | "
          f"{'yes' if t['right_longitudinal'] else 'NO'} |")
seen = {x["id"] for x in d["defects"]}
unseen = [w["id"] for w in world["defects"] if w["id"] not in seen]
errors.sort()
n = len(errors)
print(f"\n{n} defects mapped from {d['sightings']} sightings ({d['lifted']} lifted; not lifted: "
      f"{d['not_lifted']}); never in the camera's view: {unseen}")
if n:
    print(f"error: mean {sum(errors) / n:.4f} m, max {errors[-1]:.4f} m; within 0.05 m: "
          f"{sum(e <= 0.05 for e in errors)}/{n}; right frame "
          f"{sum(x['truth']['right_frame'] for x in d['defects'])}/{n}, right longitudinal "
          f"{sum(x['truth']['right_longitudinal'] for x in d['defects'])}/{n}")
PY
fi
