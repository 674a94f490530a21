#!/usr/bin/env bash
# Stops the coordinator with SIGSTOP for 8 s while an island job runs on 6 workers, then SIGCONT,
# TRIALS times (default 20), each trial a run of the cluster test that does it once
# (ServiceTest.ACoordinatorStoppedForEightSecondsFailsNoJob: the job must succeed with the
# embedded run's trajectory). Prints each trial's outcome and the count; exits 1 if any failed.
# Takes the binaries of BUILD (default build/, built beforehand), some 25 s a trial.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
trials=${TRIALS:-20}
test_binary="$build/tests/evoslam_cluster_tests"
[[ -x $test_binary ]] || { echo "stall-trials: build $test_binary first" >&2; exit 2; }
logs=$(mktemp -d "${TMPDIR:-/tmp}/evoslam-stall-trials-XXXXXX")
failed=0
for ((i = 1; i <= trials; ++i)); do
  start=$SECONDS
  if "$test_binary" --gtest_filter=ServiceTest.ACoordinatorStoppedForEightSecondsFailsNoJob \
    >"$logs/trial-$i.log" 2>&1; then
    echo "trial $i: the job succeeded ($((SECONDS - start)) s)"
  else
    echo "trial $i: FAILED ($((SECONDS - start)) s), see $logs/trial-$i.log"
    failed=$((failed + 1))
  fi
done
echo "stall trials: $((trials - failed)) of $trials jobs succeeded, $failed failed"
[[ $failed -eq 0 ]] && rm -rf "$logs"
[[ $failed -eq 0 ]]
