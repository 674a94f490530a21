#!/usr/bin/env bash
# Compares two seed sweeps of bench/seed_sweep.sh seed by seed. Between seeds the error spreads
# more than most settings move it, so a change is judged by the paired differences on the same
# seeds, not by two means side by side.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: bench/compare_sweeps.sh BEFORE AFTER

BEFORE and AFTER are sweeps of bench/seed_sweep.sh: their OUT folders, or their sweep.tsv files.
Over the seeds both hold, prints each seed's error before and after, then the mean and median of
each, the mean paired difference (after minus before) with its t statistic, and how many seeds
did better, worse or exactly the same.

example:
  bench/seed_sweep.sh -j 2 1-30 out/before -- --log LOG --relations REL --param fit_score_margin=0
  bench/seed_sweep.sh -j 2 1-30 out/after -- --log LOG --relations REL
  bench/compare_sweeps.sh out/before out/after
EOF
}

fail() {
  echo "compare_sweeps: $*" >&2
  echo "Run with --help for more information." >&2
  exit 2
}

[[ "${1:-}" == "-h" || "${1:-}" == "--help" ]] && { usage; exit 0; }
[[ $# -eq 2 ]] || fail "expected BEFORE AFTER"
files=()
for arg in "$1" "$2"; do
  file="$arg"
  [[ -d "$file" ]] && file="$file/sweep.tsv"
  [[ -f "$file" ]] || fail "'$arg' is neither a sweep's folder nor its sweep.tsv"
  [[ "$(head -n1 "$file")" == $'seed\terror\tunit\tloops\tsearches_applied' ]] ||
    fail "$file: not a sweep.tsv of bench/seed_sweep.sh (its first line is not the header)"
  files+=("$file")
done

awk -F'\t' -v before_file="${files[0]}" -v after_file="${files[1]}" '
  function median(x, n,    i, j, t) {
    for (i = 2; i <= n; ++i)
      for (j = i; j > 1 && x[j - 1] > x[j]; --j) { t = x[j]; x[j] = x[j - 1]; x[j - 1] = t }
    return n % 2 ? x[(n + 1) / 2] : (x[n / 2] + x[n / 2 + 1]) / 2
  }
  FNR == 1 { file++; next }
  file == 1 { before[$1] = $2; before_unit = $3; next }
  !($1 in before) { next }
  {
    if ($3 != before_unit) {
      printf "compare_sweeps: seed %s is in %s in %s and in %s in %s\n", $1, before_unit,
             before_file, $3, after_file > "/dev/stderr"
      bad = 1; exit 2
    }
    ++n; seed[n] = $1; b[n] = before[$1]; a[n] = $2; d[n] = a[n] - b[n]
  }
  END {
    if (bad) exit 2
    if (n == 0) {
      print "compare_sweeps: the two sweeps share no seed" > "/dev/stderr"; exit 1
    }
    f = before_unit == "m" ? "%.4f" : "%.2f"
    g = before_unit == "m" ? "%.5f" : "%.3f"
    for (i = 1; i <= n; ++i) {
      printf "seed %-6s " f " -> " f " %s\n", seed[i], b[i], a[i], before_unit
      sb += b[i]; sa += a[i]; sd += d[i]; sb_[i] = b[i]; sa_[i] = a[i]
      if (b[i] == a[i]) ++same; else if (a[i] < b[i]) ++better; else ++worse
    }
    mean = sd / n
    for (i = 1; i <= n; ++i) ss += (d[i] - mean) ^ 2
    printf "%d seed%s in both: mean " g " -> " g " %s, median " g " -> " g "\n", n,
           n == 1 ? "" : "s", sb / n, sa / n, before_unit, median(sb_, n), median(sa_, n)
    printf "paired difference " g " %s", mean, before_unit
    if (n > 1 && ss > 0) printf " (t = %.2f over %d seeds)", mean / sqrt(ss / (n - 1) / n), n
    printf "; better %d, worse %d, the same %d\n", better, worse, same
  }' "${files[0]}" "${files[1]}"
