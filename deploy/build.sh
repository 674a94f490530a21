#!/usr/bin/env bash
# Installs the dependencies and builds evoslam (Release) into build/.
# Usage: deploy/build.sh [extra cmake -D options]
# A unity build compiles each module's sources as a few large units, which parses the heavy
# headers (Eigen, protobuf, gtest) a few times instead of once per file: about three times less
# compile time for a build from scratch. For editing, configure without it.
set -euo pipefail
cd "$(dirname "$0")/.."
./deploy/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON "$@"
cmake --build build -j"$(nproc)"
