#!/usr/bin/env bash
# Issue 11, item 1: 1 against 2 threads for every benchmarked algorithm of ours, from one run.
# Runs scantling's own cases ("…/ours/1thr" and "…/ours/2thr") of the benchmark executables
# and prints, per case, both wall times and the speed-up (time on 1 thread / time on 2).
#   scripts/thread-scaling.sh [bench-build-dir] [extra google-benchmark flags...]
# BENCH_REPETITIONS (default 3): repetitions per case; the median is used.
# THREAD_SCALING_FILTER: a narrower Google Benchmark filter (default: every "/ours/[12]thr").
# A full run takes about half an hour on 2 cores (the simulated-tank registration cases).
set -euo pipefail
build="${1:-build-bench}"
shift || true
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%dT%H:%MZ)"
for exe in parallel odometry registration sim core; do
  bin="$build/bench/scantling_bench_$exe"
  if [[ ! -x "$bin" ]]; then
    echo "thread-scaling: $bin not built (configure with -DSCANTLING_BUILD_BENCH=ON)" >&2
    exit 1
  fi
  # The executables print their own tables; the figures are taken from the JSON file.
  "$bin" --benchmark_filter="${THREAD_SCALING_FILTER:-/ours/[12]thr}" \
    --benchmark_repetitions="${BENCH_REPETITIONS:-3}" --benchmark_report_aggregates_only=true \
    --benchmark_out="$out/$exe.json" --benchmark_out_format=json "$@" >/dev/null 2>&1
done

python3 - "$out"/*.json <<'EOF'
import json, re, sys
times = {}
for path in sys.argv[1:]:
    text = open(path).read()
    if not text.strip():  # the filter matched nothing in that executable
        continue
    for b in json.loads(text)["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        m = re.match(r"(.*)/ours/([12])thr", b["run_name"])
        if m:
            unit = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
            times.setdefault(m.group(1), {})[m.group(2)] = b["real_time"] * unit
print("| case | 1 thread ms | 2 threads ms | speed-up |")
print("|---|---|---|---|")
for name, t in sorted(times.items()):
    if "1" in t and "2" in t:
        print(f"| {name} | {t['1']:.2f} | {t['2']:.2f} | {t['1'] / t['2']:.2f} |")
EOF
