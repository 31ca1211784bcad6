#!/usr/bin/env bash
# Runs every benchmark executable of a benchmark build and prints its results, ending each
# executable's output with a table of scantling / baseline time ratios.
#   scripts/run-benchmarks.sh <bench-build-dir> [extra google-benchmark flags...]
# e.g. scripts/run-benchmarks.sh build-bench --benchmark_filter=voxel
# BENCH_REPETITIONS (default 5): repetitions per benchmark; the median is reported.
set -euo pipefail

if [[ $# -lt 1 ]]; then
  echo "usage: $0 <bench-build-dir> [google-benchmark flags...]" >&2
  exit 2
fi
build_dir="$1"
shift

bench_dir="$build_dir/bench"
mapfile -t executables < <(find "$bench_dir" -maxdepth 1 -type f -name 'scantling_bench_*' \
  -perm -u+x 2>/dev/null | sort)
if [[ ${#executables[@]} -eq 0 ]]; then
  echo "run-benchmarks: no scantling_bench_* executable in $bench_dir" \
    "(configure with -DSCANTLING_BUILD_BENCH=ON and build first)" >&2
  exit 1
fi

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)," \
  "load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"

status=0
for exe in "${executables[@]}"; do
  echo
  echo "== $(basename "$exe")"
  if ! "$exe" --benchmark_repetitions="${BENCH_REPETITIONS:-5}" \
      --benchmark_report_aggregates_only=true "$@"; then
    echo "run-benchmarks: $(basename "$exe") failed" >&2
    status=1
  fi
done
exit "$status"
