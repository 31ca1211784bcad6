#!/usr/bin/env bash
# UAV3D experiment (SPEC §9, RESULTS-TO-REPRODUCE 4.7, docs/results.md): the helix baseline
# (Table 1) and the point-density planner (Tables 2–3) around the simulated cylinder, printed as
# markdown tables. Builds its one small target (scantling_uav3d_experiment), then runs it.
# Usage: scripts/uav3d-experiments.sh [frame_rate_hz=30] [seed=1] [max_rotations=100] [disparity_sigma_px=0.3]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SCANTLING_BUILD_DIR:-$root/build}"
cmake --build "$build" -j2 --target scantling_uav3d_experiment >&2
exec "$build/apps/scantling_uav3d_experiment" "${1:-30}" "${2:-1}" "${3:-100}" "${4:-0.3}"
