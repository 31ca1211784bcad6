#!/usr/bin/env bash
# Installs every Debian 12 package scantling builds against. Idempotent: packages already
# present are skipped, `apt-get update` runs only when the package lists are missing or a
# package is not known to apt yet.
#   scripts/install-deps.sh           build, test and run dependencies
#   scripts/install-deps.sh --bench   plus the comparison baselines used by `make bench`
set -euo pipefail

packages=(
  build-essential cmake make git pkg-config clang-format clang-tidy
  libeigen3-dev libnanoflann-dev libtbb-dev libyaml-cpp-dev nlohmann-json3-dev
  libcli11-dev libspdlog-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev
  libassimp-dev libembree-dev libceres-dev liboctomap-dev zlib1g-dev libpng-dev
  # Canny edges in the sonar image (perception; cmake/FindOpenCVImgproc.cmake)
  libopencv-core-dev libopencv-imgproc-dev
  # CGAL's surface-mesh shortest path for the crawler's paths on meshes (planning/mesh_path.cpp;
  # header-only, pulls the GMP/MPFR/Boost headers)
  libcgal-dev
  # make fuzz: clang with libFuzzer and the ASan/UBSan runtimes (libclang_rt.fuzzer-x86_64.a)
  clang-14 libclang-rt-14-dev
  # plots of the experiments (scripts/d52-experiments.sh; docs/results.md)
  gnuplot-nox
)
if [[ "${1:-}" == "--bench" ]]; then
  # Open3D for the in-process baselines; robin-map for KISS-ICP built from ../shared/baselines
  packages+=(libopen3d-dev robin-map-dev)
elif [[ $# -gt 0 ]]; then
  echo "install-deps.sh: unknown option '$1' (expected --bench or nothing)" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo_cmd=(sudo)
  else
    echo "install-deps: need root (or sudo) to install: ${missing[*]}" >&2
    exit 1
  fi
fi

export DEBIAN_FRONTEND=noninteractive
if [[ -z "$(ls -A /var/lib/apt/lists 2>/dev/null | grep -v -e '^lock$' -e '^partial$' -e '^auxfiles$')" ]] ||
   ! apt-cache show "${missing[0]}" >/dev/null 2>&1; then
  echo "install-deps: apt-get update"
  "${sudo_cmd[@]}" apt-get update
fi
echo "install-deps: apt-get install -y ${missing[*]}"
"${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
echo "install-deps: done"
