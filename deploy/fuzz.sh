#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (AddressSanitizer and UBSan on) and runs each for
# FUZZ_SECONDS (default 150, so the five targets take 12.5 minutes). A crash stops the run with a
# non-zero exit and leaves the crashing input in build-fuzz/crashes/.
set -euo pipefail
cd "$(dirname "$0")/.."
./deploy/install-deps.sh --dev
seconds=${FUZZ_SECONDS:-150}
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DEVOSLAM_BUILD_FUZZ=ON -DEVOSLAM_BUILD_TESTS=OFF -DEVOSLAM_BUILD_BENCH=OFF
targets=(decode_client_request decode_worker_message decode_coordinator_message
         decode_island_checkpoint decode_upload_chunks)
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]/#/fuzz_}"
mkdir -p build-fuzz/crashes
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t"
  echo "fuzz: $t for ${seconds} s"
  "build-fuzz/tests/fuzz/fuzz_$t" "build-fuzz/corpus/$t" -max_total_time="$seconds" \
    -max_len=65536 -print_final_stats=1 -artifact_prefix=build-fuzz/crashes/"$t"- 2>&1 |
    grep -E "^(stat::|#[0-9]+ *DONE|==[0-9]+==|SUMMARY|artifact_prefix)" || true
  if ls build-fuzz/crashes/"$t"-* > /dev/null 2>&1; then
    echo "fuzz: $t crashed; inputs in build-fuzz/crashes/" >&2
    exit 1
  fi
done
echo "fuzz: no crash in ${#targets[@]} targets x ${seconds} s"
