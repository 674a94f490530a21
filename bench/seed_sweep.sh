#!/usr/bin/env bash
# Runs one `evoslam slam` job over a range of seeds and reports the spread of its error: one
# seed's run says little where a single event (a slip in a fast turn, a loop matched or missed)
# decides it, so docs/accuracy.md quotes the mean, median and worst over seeds, made this way.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: bench/seed_sweep.sh [options] SEEDS OUT -- SLAM_ARGS...

Runs `evoslam slam SLAM_ARGS --seed S --out OUT/seed-S` for every seed S of SEEDS (a range
such as 1-30, a list such as 1,4,7, or both: 1-5,9), then prints one line a seed and the mean,
median, best and worst of its score, and writes them to OUT/sweep.tsv. The score is the mean
translational relation error in metres where the run has relations (--relations), otherwise the
RMS error against the ground truth in centimetres once aligned (a simulated drive).

options:
  -j N               runs N seeds at a time (1; more skews the times, not the errors)
  --evoslam PATH     the evoslam binary (./build/cli/evoslam)
  --simulate ARGS    for every seed S, first `evoslam simulate ARGS --seed S --out OUT/sim-S`,
                     then map its log with --seed 1: the drive varies, SLAM's seed does not
  -h, --help         this text

example:
  bench/seed_sweep.sh 1-30 out/intel-sweep -- --log ../shared/data/intel.clf.bz2 \
    --relations ../shared/data/intel.relations
  bench/seed_sweep.sh --simulate "--world office-cluster --max-range 4" 1-10 out/office4 --
EOF
}

fail() {
  echo "seed_sweep: $*" >&2
  echo "Run with --help for more information." >&2
  exit 2
}

jobs=1
evoslam=./build/cli/evoslam
simulate=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    -j) [[ $# -ge 2 ]] || fail "-j needs a number"; jobs="$2"; shift 2 ;;
    --evoslam) [[ $# -ge 2 ]] || fail "--evoslam needs a path"; evoslam="$2"; shift 2 ;;
    --simulate) [[ $# -ge 2 ]] || fail "--simulate needs its arguments"; simulate="$2"; shift 2 ;;
    --) break ;;
    -*) fail "unknown option '$1'" ;;
    *) break ;;
  esac
done
[[ $# -ge 3 && "$3" == "--" ]] || fail "expected SEEDS OUT -- SLAM_ARGS..."
seeds_arg="$1"
out="$2"
shift 3
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || fail "-j: '$jobs' is not a positive whole number"
[[ -x "$evoslam" ]] || fail "--evoslam: '$evoslam' is not an executable file (build first)"

seeds=()
IFS=',' read -ra parts <<<"$seeds_arg"
for part in "${parts[@]}"; do
  if [[ "$part" =~ ^([0-9]+)-([0-9]+)$ ]]; then
    first=$((10#${BASH_REMATCH[1]}))
    last=$((10#${BASH_REMATCH[2]}))
    ((first <= last)) || fail "seeds: '$part' runs backwards"
    for ((s = first; s <= last; ++s)); do seeds+=("$s"); done
  elif [[ "$part" =~ ^[0-9]+$ ]]; then
    seeds+=("$((10#$part))")
  else
    fail "seeds: '$part' is neither a seed nor a range such as 1-30"
  fi
done
mkdir -p "$out" || fail "cannot create '$out'"

# One seed: its runs' output goes to OUT/seed-S.log, so a failure can be read afterwards.
run_seed() {
  local s="$1"
  shift
  local log="$out/seed-$s.log"
  if [[ -n "$simulate" ]]; then
    # shellcheck disable=SC2086  # the simulation's arguments are split as a shell would
    "$evoslam" simulate $simulate --seed "$s" --out "$out/sim-$s" >"$log" 2>&1 &&
      "$evoslam" slam --log "$out/sim-$s/log.clf" "$@" --seed 1 --out "$out/seed-$s" >>"$log" 2>&1
  else
    "$evoslam" slam "$@" --seed "$s" --out "$out/seed-$s" >"$log" 2>&1
  fi
}

# At most `jobs` seeds run at once; the oldest is waited for first. Progress goes to a terminal
# only, so a pipe or a CI log gets the results alone.
failed=()
pids=()
names=()
done_count=0
progress() {
  if [[ -t 2 ]]; then
    printf '\rseed_sweep: %d of %d seeds done' "$done_count" "${#seeds[@]}" >&2
  fi
}
wait_oldest() {
  wait "${pids[0]}" || failed+=("${names[0]}")
  pids=("${pids[@]:1}")
  names=("${names[@]:1}")
  done_count=$((done_count + 1))
  progress
}
progress
for s in "${seeds[@]}"; do
  run_seed "$s" "$@" &
  pids+=("$!")
  names+=("$s")
  if ((${#pids[@]} >= jobs)); then wait_oldest; fi
done
while ((${#pids[@]} > 0)); do wait_oldest; done
if [[ -t 2 ]]; then printf '\r\033[K' >&2; fi

# A run's score, its unit, the loops it found and the searches it applied: the error from
# report.json, at full precision (the relation error against --relations, else the aligned error
# against the ground truth), the counts from summary.txt.
score_of() {
  awk '
    FNR == 1 { file++ }
    file == 1 && /^ "[a-z_]+": [{]/ { block = $1 }
    # A simulated drive scores its consecutive poses as relations too; its own error is the
    # aligned one.
    file == 1 && block == "\"relation_errors\":" && /"source": "ground truth/ { block = "" }
    file == 1 && block == "\"relation_errors\":" && /"translation_mean_m"/ && rel == "" {
      rel = $2; sub(/,$/, "", rel)
    }
    file == 1 && block == "\"absolute_errors\":" && /"aligned_rms_translation_m"/ && gt == "" {
      gt = $2; sub(/,$/, "", gt)
    }
    file == 2 && /^  loops found:/ { loops = $3 }
    file == 2 && /^  global searches:/ { applied = $4 }
    END {
      if (rel != "") print rel, "m", loops + 0, applied + 0
      else if (gt != "") printf "%.15g cm %d %d\n", gt * 100, loops, applied
    }' "$1/report.json" "$1/summary.txt"
}

tsv="$out/sweep.tsv"
unscored=0
printf 'seed\terror\tunit\tloops\tsearches_applied\n' >"$tsv"
for s in "${seeds[@]}"; do
  run="$out/seed-$s"
  [[ " ${failed[*]} " == *" $s "* || ! -f "$run/summary.txt" ]] && continue
  read -r error unit loops applied < <(score_of "$run") || true
  if [[ -z "${error:-}" ]]; then
    echo "seed_sweep: seed $s: $run/report.json has no relation or ground-truth error" \
      "(no --relations?)" >&2
    unscored=$((unscored + 1))
    continue
  fi
  printf '%s\t%s\t%s\t%s\t%s\n' "$s" "$error" "$unit" "$loops" "$applied" >>"$tsv"
done

# Metres to a tenth of a millimetre, centimetres to a tenth of a millimetre too; the mean and
# median one digit finer, since they are what settings are compared by.
awk -F'\t' '
  NR == 1 { next }
  {
    seed[++n] = $1; e[n] = $2; unit = $3
    f = unit == "m" ? "%.4f" : "%.2f"
    printf "seed %-6s " f " %s  loops found %s, searches applied %s\n", $1, $2, $3, $4, $5
  }
  END {
    if (n == 0) exit
    for (i = 1; i <= n; ++i) { v[i] = e[i]; sum += e[i] }
    for (i = 2; i <= n; ++i)  # insertion sort, for the median
      for (j = i; j > 1 && v[j - 1] > v[j]; --j) { t = v[j]; v[j] = v[j - 1]; v[j - 1] = t }
    median = n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
    best = 1; worst = 1
    for (i = 2; i <= n; ++i) { if (e[i] < e[best]) best = i; if (e[i] > e[worst]) worst = i }
    f = unit == "m" ? "%.4f" : "%.2f"
    g = unit == "m" ? "%.5f" : "%.3f"
    printf "%d seed%s: mean " g " %s, median " g ", best " f " (seed %s), worst " f " (seed %s)\n",
           n, n == 1 ? "" : "s", sum / n, unit, median, e[best], seed[best], e[worst], seed[worst]
  }' "$tsv"

for s in "${failed[@]}"; do
  log="$out/seed-$s.log"
  why=$(grep -m1 'error' "$log" 2>/dev/null || head -n1 "$log" 2>/dev/null || true)
  echo "seed_sweep: seed $s failed${why:+: $why} (all of it in $log)" >&2
done
((${#failed[@]} == 0 && unscored == 0)) || exit 1
