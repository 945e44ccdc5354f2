#!/usr/bin/env bash
# test-aarch64.sh - builds facet's portable layers and the pipeline's property tests for 64-bit ARM (Debian's
# g++-aarch64-linux-gnu) and runs them under qemu-user: the oracle and property tests, and the goldens drawn byte
# for byte as the x86-64 build draws them. Installs what is missing (scripts/deps.sh).
# Usage: scripts/test-aarch64.sh [BUILD_DIR]   (default build-aarch64)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build-aarch64}
scripts/deps.sh
export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=true
# -O1: the tests check bytes, not speed (speed under QEMU is no measure), and -O1 compiles faster than -O2 or -O3.
cmake -S tests/portable -B "$build" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$PWD/cmake/aarch64-linux-gnu.cmake" \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" >/dev/null
cmake --build "$build" -j "$(nproc)"
ctest --test-dir "$build" -j "$(nproc)" --output-on-failure
