#!/usr/bin/env bash
# test.sh - installs what is missing, builds facet warning-free, and runs every test (ctest), then the pipeline's
# property tests built by Clang and built for aarch64 (run under qemu-user), then the tests under ASan+UBSan, then
# the threading and determinism tests under ThreadSanitizer.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
# Each stage says what it took, so a slow run shows where its time went (docs/DEVELOPING.md lists the usual costs).
run_start=$SECONDS
stage_start=$SECONDS
stage() {
  echo "test.sh: $1 took $((SECONDS - stage_start)) s (run so far $((SECONDS - run_start)) s)"
  stage_start=$SECONDS
}

scripts/deps.sh
stage "dependencies"
jobs=$(nproc)
# ccache (found by CMakeLists.txt) keys on paths relative to the checkout, so every clone on a machine shares hits.
export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=true

# The AVX-512 clones of the hot loops are compiled only where this CPU could run (and so test) them.
avx512=OFF
grep -qw avx512f /proc/cpuinfo && avx512=ON
cmake --preset release -DFACET_DISPATCH_AVX512=$avx512 >/dev/null
cmake --build --preset release -j "$jobs"
stage "release build"
ctest --preset release -j "$jobs"
stage "release tests"

# The pipeline's property tests built by Clang and run: its lane code's Clang forms against the same oracles.
cmake --preset clang >/dev/null
cmake --build --preset clang -j "$jobs"
stage "Clang build"
ctest --preset clang -j "$jobs"
stage "Clang property tests"

# The same property tests and goldens built for aarch64 and run under qemu-user.
scripts/test-aarch64.sh
stage "aarch64 build and tests"

if [ "${FACET_SKIP_SANITIZE:-0}" != 1 ]; then
  cmake --preset asan >/dev/null
  cmake --build --preset asan -j "$jobs"
  stage "sanitizer build"
  ctest --preset asan -j "$jobs"
  stage "sanitizer tests"
  # The tests that draw on several threads (CMakePresets.json names them), in a build of their binary alone.
  cmake --preset tsan >/dev/null
  cmake --build --preset tsan -j "$jobs"
  stage "ThreadSanitizer build"
  ctest --preset tsan -j "$jobs"
  stage "ThreadSanitizer tests"
fi
