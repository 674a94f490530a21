#!/usr/bin/env bash
# Installs, builds and runs the whole test suite: every test on the Release build, then the unit
# tests again under AddressSanitizer and UndefinedBehaviorSanitizer (accuracy tests, which need
# optimised code to run in reasonable time, are left out of the sanitizer pass).
set -euo pipefail
cd "$(dirname "$0")/.."
./deploy/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DEVOSLAM_SANITIZE=ON \
  -DEVOSLAM_BUILD_BENCH=OFF -DCMAKE_UNITY_BUILD=ON
cmake --build build-asan -j"$(nproc)"
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -LE accuracy
