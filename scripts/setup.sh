#!/usr/bin/env bash
# Installs surfcert's build and test dependencies (Debian 12 packages only) and builds it.
# Usage: scripts/setup.sh [build-dir] [extra cmake args...]   (run as root on a fresh machine)
# Benchmark peers (Open CASCADE: libocct-*-dev; FCL: libfcl-dev) are not installed here: the
# library and the tests never need them; bench/install_peers.sh installs them for the benchmarks
# that compare against them (trace_bench, distance_peers_bench, float_atlas), which build when
# CMake finds them (SURFCERT_BENCH_OCCT / SURFCERT_BENCH_FCL).
set -euo pipefail
cd "$(dirname "$0")/.."
pkgs="build-essential cmake libgmp-dev libmpfr-dev libmpfi-dev libflint-dev libflint-arb-dev
      libcalcium-dev libcgal-dev libboost-dev libgtest-dev libcli11-dev libtbb-dev librsvg2-bin libxml2-utils python3
      pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest python3-matplotlib
      clang libclang-rt-14-dev"  # clang + libFuzzer runtime: scripts/fuzz.sh only (builds use g++)
pkgs="$pkgs libsimdjson-dev"  # simdjson: the batch's fast line reader (app/src/batch_line.cpp)
pkgs="$pkgs openmpi-bin libopenmpi-dev"  # MPI (optional): `surfcert batch --mpi` (app/src/batch_mpi.cpp)
missing=""
for p in $pkgs; do dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"; done
if [ -n "$missing" ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  # shellcheck disable=SC2086
  apt-get install -y -qq $missing >/dev/null
fi
build="${1:-build}"; shift || true
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
