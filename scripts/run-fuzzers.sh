#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/: clang, ASan + UBSan, -O1) and runs each for a bounded
# time on a fresh seed corpus (fuzz/make_seeds.sh). Exits 1 on any finding, printing the
# reproducer's path and the command that replays it. docs/fuzzing.md.
#   scripts/run-fuzzers.sh [all|build|seeds|run]     (default: all = build, seeds, run)
# Environment:
#   FUZZ_DIR        build folder (build-fuzz)
#   FUZZ_SECONDS    fuzzing time per target (60)
#   FUZZ_SEED       libFuzzer's random seed (1: the same mutations every run, so a CI finding
#                   is reproducible; 0 lets libFuzzer pick one, for wider local runs)
#   FUZZ_TARGETS    targets to run (all: pcd ply kitti_bin kitti_poses tum config scenario recording structural_map)
#   JOBS            fuzzers run side by side, and build jobs (nproc)
#   FUZZ_KEEP_GOING 1: keep fuzzing after a finding (libFuzzer -fork) to collect several
#   CXX_FUZZ        the clang++ with libFuzzer (clang++-14, Debian's libclang-rt-14-dev)
#   FUZZ_CXX_FLAGS  optimisation and debug flags of the fuzz tree (-O0 -gline-tables-only: the
#                   tree compiles most of the library for the config and scenario targets, and
#                   -O0 halves clang's time on Eigen-heavy files, 47.8 -> 29.3 s for
#                   local_ekf.cpp; the readers run slower per input, which matters less for the
#                   CI's short runs than 5 min of build. Use -O1 for long local campaigns)
#   SCANTLING_CLI   a built scantling, to simulate a real recording seed (build/apps/scantling)
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
fuzz_dir="$(mkdir -p "${FUZZ_DIR:-build-fuzz}" && cd "${FUZZ_DIR:-build-fuzz}" && pwd)"
seconds="${FUZZ_SECONDS:-60}"
fuzz_seed="${FUZZ_SEED:-1}"
jobs="${JOBS:-$(nproc)}"
read -r -a targets <<< "${FUZZ_TARGETS:-pcd ply kitti_bin kitti_poses tum config scenario recording structural_map}"
cxx="${CXX_FUZZ:-clang++-14}"
fuzz_cxx_flags="${FUZZ_CXX_FLAGS:--O0 -gline-tables-only}"
cli="${SCANTLING_CLI:-$root/build/apps/scantling}"

# A memory bomb or a hang is a finding, not a slow pass.
limits=(-rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10)

build() {
  command -v "$cxx" > /dev/null || { echo "run-fuzzers: $cxx not found (make deps)" >&2; exit 2; }
  # Debug: assertions stay on (an internal invariant failing on hostile input is a finding).
  # No precompiled headers: this tree is the one that proves each library file includes what it
  # uses (the others pre-include Eigen, fmt and std).
  # unsigned-integer-overflow: a size computed from a header must not wrap (ignore list: why).
  cmake -S . -B "$fuzz_dir" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG="$fuzz_cxx_flags" \
    -DCMAKE_CXX_FLAGS="-fsanitize-ignorelist=$root/fuzz/ubsan_ignorelist.txt" \
    -DSCANTLING_FUZZ=ON -DSCANTLING_SANITIZE=address,undefined,unsigned-integer-overflow \
    -DSCANTLING_PCH=OFF \
    -DSCANTLING_BUILD_TESTS=OFF > "$fuzz_dir/configure.log"
  # Only the targets asked for: the config target alone pulls odometry, localization,
  # registration, perception and mapping into this tree.
  cmake --build "$fuzz_dir" -j "$jobs" --target "${targets[@]/%/_fuzz}"
}

seeds() { fuzz/make_seeds.sh "$fuzz_dir/seeds" "$cli"; }

# Longest input per target: room for a header and a few dozen records or lines.
max_len() {
  case "$1" in
    recording | scenario) echo 16384 ;;
    kitti_bin) echo 4096 ;;
    *) echo 8192 ;;
  esac
}

dict_of() {
  case "$1" in
    pcd | ply | recording) echo "fuzz/dicts/$1.dict" ;;
    config | scenario) echo fuzz/dicts/yaml.dict ;;
    tum | kitti_poses) echo fuzz/dicts/numbers.dict ;;
    structural_map) echo fuzz/dicts/json.dict ;;
  esac
}

run_one() {
  local t="$1" findings="$fuzz_dir/findings/$1" corpus="$fuzz_dir/corpus/$1"
  local args=("${limits[@]}" -max_total_time="$seconds" -max_len="$(max_len "$t")"
              -artifact_prefix="$findings/" -print_final_stats=1 -seed="$fuzz_seed")
  [[ -z "$(dict_of "$t")" ]] || args+=(-dict="$(dict_of "$t")")
  [[ "${FUZZ_KEEP_GOING:-0}" == 1 ]] && args+=(-fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1)
  mkdir -p "$findings" "$corpus" "$scratch/$t"
  local rc=0
  # A hard bound besides libFuzzer's own: its timeout handler can deadlock when the alarm
  # interrupts malloc (a memory-bombing input), and CI must not hang.
  TMPDIR="$scratch/$t" ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    timeout -k 10 $((seconds + 120)) "$fuzz_dir/fuzz/${t}_fuzz" "${args[@]}" "$corpus" \
    "$fuzz_dir/seeds/$t" > "$fuzz_dir/logs/$t.log" 2>&1 || rc=$?
  echo "$rc" > "$fuzz_dir/logs/$t.rc"
  if [[ $rc -eq 124 || $rc -eq 137 ]]; then keep_hung_inputs "$t"; fi
}

# After a hard timeout: the targets write each input into their scratch folder before reading
# it, and only a normal exit removes that folder, so what is left is the input that hung.
keep_hung_inputs() {
  local t="$1" f
  for f in "$scratch/$t"/scantling-fuzz-*/*; do
    [[ -f "$f" ]] && cp "$f" "$fuzz_dir/findings/$t/hang-$(basename "$(dirname "$f")")-$(basename "$f")"
  done
  echo "run-fuzzers: $t stopped after $((seconds + 120)) s: a hang (inputs kept as hang-*)" >> "$fuzz_dir/logs/$t.log"
}

run() {
  # The targets write every input to a file: in memory (/dev/shm) when there is one. Removed at
  # the end even after a crash.
  scratch="$fuzz_dir/tmp"
  [[ -w /dev/shm ]] && scratch="$(mktemp -d /dev/shm/scantling-fuzz.XXXXXX)"
  rm -rf "$fuzz_dir/findings" "$fuzz_dir/logs" "$fuzz_dir/tmp"
  mkdir -p "$fuzz_dir/logs"
  local t status=0
  for t in "${targets[@]}"; do
    [[ -x "$fuzz_dir/fuzz/${t}_fuzz" ]] || { echo "run-fuzzers: no target ${t}_fuzz" >&2; exit 2; }
    while (( $(jobs -rp | wc -l) >= jobs )); do wait -n || true; done
    echo "run-fuzzers: $t for ${seconds} s"
    run_one "$t" &
  done
  wait
  for t in "${targets[@]}"; do
    if [[ "$(cat "$fuzz_dir/logs/$t.rc")" != 0 || -n "$(ls -A "$fuzz_dir/findings/$t")" ]]; then
      report "$t"
      status=1
    fi
  done
  rm -rf "$scratch"
  [[ $status -eq 0 ]] && echo "run-fuzzers: no findings (${#targets[@]} targets x ${seconds} s)"
  return $status
}

# Prints the findings of target $1, or why it failed without one.
report() {
  local t="$1" log="$fuzz_dir/logs/$1.log" f found=0
  for f in "$fuzz_dir/findings/$t"/*; do
    [[ -e "$f" ]] || continue
    found=1
    echo "run-fuzzers: FINDING in $t: $f"
    echo "  reproduce: $fuzz_dir/fuzz/${t}_fuzz $f"
  done
  [[ $found -eq 1 ]] || echo "run-fuzzers: $t failed without a reproducer (see $log)"
  grep -m 3 -E "ERROR: |runtime error|FINDING|SUMMARY" "$log" | sed 's/^/  /' || true
  echo "  log: $log"
}

case "${1:-all}" in
  build) build ;;
  seeds) seeds ;;
  run) run ;;
  all) build && seeds && run ;;
  *) echo "usage: $0 [all|build|seeds|run]" >&2; exit 2 ;;
esac
