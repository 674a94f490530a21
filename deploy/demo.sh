#!/usr/bin/env bash
# Installs, builds, then runs the main job on a built-in default: simulates the s-shaped corridor
# of the L1/L2 comparative study (219 scans, 361 beams, uniform noise of 20 cm bandwidth) and
# localizes in it with DE/rand/1/exp on F3. Results go to out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
./deploy/build.sh
./build/cli/evoslam simulate --world s-corridor --noise-uniform 0.2 --seed 1 --out out/demo/sim
./build/cli/evoslam localize --map out/demo/sim/world.lines --log out/demo/sim/log.clf \
  --fitness f3 --estimator 2d --optimizer de --strategy rand1exp --pop 25 --gen 25 \
  --window 0.6 --seed 1 --out out/demo/localize
