#!/usr/bin/env bash
# Sweep throughput (issue "Parametric designs"): 10,000 sampled four-bar variants
# (some do not assemble, some reach limits) on 1 and on 2 threads; prints
# variants per second and the speed-up. Usage: tools/sweep_benchmark.sh [BUILD_DIR] [N]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
n="${2:-10000}"
file="$here/mechanisms/parametric-four-bar.json"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
declare -A rate
for threads in 1 2; do
  start=$(date +%s.%N)
  "$build/mechkin" sweep "$file" --samples "$n" --seed 1 --threads "$threads" -o "$out/sweep$threads.csv"
  end=$(date +%s.%N)
  rate[$threads]=$(echo "$n / ($end - $start)" | bc -l)
  printf "threads %d: %d variants in %.2f s = %.0f variants/s\n" "$threads" "$n" "$(echo "$end - $start" | bc -l)" "${rate[$threads]}"
done
cmp -s "$out/sweep1.csv" "$out/sweep2.csv" && echo "1- and 2-thread summaries identical"
printf "speed-up 1 -> 2 threads: %.2fx\n" "$(echo "${rate[2]} / ${rate[1]}" | bc -l)"
cut -d, -f6 "$out/sweep1.csv" | tail -n +2 | sort | uniq -c | sed 's/^/  status: /'
