#!/usr/bin/env bash
# Paper 004's experiment (Tables 1-2) on a simulated lab: the three variants of the immune method
# over seeds 1..N on office-boxes (a 10 x 10 m office with boxes, a route of about 30 m, 25
# segments). Prints, per variant, the mean and standard deviation of the best f1 reached, the mean
# number of fitness evaluations until the search stopped, and the median aligned RMS error
# against the ground truth with its spread.
# Usage: bench/immune_table.sh [BUILD_DIR] [SEEDS] [OUT_DIR]
set -euo pipefail
build=${1:-build}
seeds=${2:-10}
out=${3:-$(mktemp -d -t evoslam-immune-table-XXXXXX)}
evoslam="$build/cli/evoslam"
for variant in immune moea duckett; do
  for seed in $(seq 1 "$seeds"); do
    dir="$out/$variant-$seed"
    [[ -f "$dir/report.json" ]] && continue
    "$evoslam" slam --method immune --variant "$variant" --world office-boxes --seed "$seed" \
      --out "$dir" > /dev/null 2>&1
  done
done
python3 - "$out" "$seeds" <<'PY'
import json, statistics, sys
out, seeds = sys.argv[1], int(sys.argv[2])
print(f"{'variant':8} | best f1 mean +- sd | evaluations mean | aligned RMS error median (min-max), m")
odometry = []
for variant in ("immune", "moea", "duckett"):
    f1, evals, err = [], [], []
    for seed in range(1, seeds + 1):
        r = json.load(open(f"{out}/{variant}-{seed}/report.json"))
        f1.append(r["immune"]["objectives"][0])
        evals.append(int(r.get("evaluations", 0)))
        err.append(r["absolute_errors"]["aligned_rms_translation_m"])
        if variant == "immune":
            odometry.append(r["odometry_absolute_errors"]["aligned_rms_translation_m"])
    sd = statistics.stdev(f1) if len(f1) > 1 else 0.0
    print(f"{variant:8} | {statistics.mean(f1):8.1f} +- {sd:6.1f} | {statistics.mean(evals):16.0f} |"
          f" {statistics.median(err):.3f} ({min(err):.3f}-{max(err):.3f})")
print(f"odometry | {'':18} | {'':16} | {statistics.median(odometry):.3f} "
      f"({min(odometry):.3f}-{max(odometry):.3f})")
PY
echo "runs in $out"
