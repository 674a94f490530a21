#!/usr/bin/env bash
# Installs, builds, then runs the main job on a built-in default: paper 002's reduced-search-space
# SLAM, embedded in this process, on a simulated drive through the office cluster (ten furnished
# offices on a hallway, 1,823 scans, odometry whose heading drifts) -> out/demo/slam/. Then, in a
# second, localization in a known map: the s-shaped corridor of the L1/L2 comparative study with
# DE/rand/1/exp on F3 -> out/demo/sim/, out/demo/localize/.
set -euo pipefail
cd "$(dirname "$0")/.."
./deploy/build.sh
./build/cli/evoslam slam --out out/demo/slam
./build/cli/evoslam simulate --world s-corridor --noise-uniform 0.2 --seed 1 --out out/demo/sim
./build/cli/evoslam localize --map out/demo/sim/world.lines --log out/demo/sim/log.clf \
  --fitness f3 --estimator 2d --optimizer de --strategy rand1exp --population 25 --generations 25 \
  --window 0.6 --seed 1 --out out/demo/localize
echo "demo: the SLAM map with its trajectory is out/demo/slam/map_trajectory.png"
