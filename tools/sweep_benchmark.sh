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

# What a variant costs beyond its run (issue 22: no more than the run plus 5 %):
# instruction counts under callgrind, which the machine's load does not change.
bench="$build/tools/bench_compile"
if [ -x "$bench" ] && command -v valgrind >/dev/null && command -v callgrind_annotate >/dev/null; then
  valgrind --tool=callgrind --callgrind-out-file="$out/cg.out" "$bench" --benchmark_filter=VariantWhole \
    --benchmark_min_time=1 >/dev/null 2>&1
  callgrind_annotate --inclusive=yes "$out/cg.out" 2>/dev/null | awk '
    /mechkin::RunVariant\(/ && !v { gsub(",", "", $1); v = $1 }
    /mechkin::RunMotion\(mechkin::Model const&, mechkin::RunRequest const&\)/ && !r { gsub(",", "", $1); r = $1 }
    /mechkin::WithParameters\(/ && !c { gsub(",", "", $1); c = $1 }
    END { if (v && r) printf "a variant (compile + run + summary): %.1f%% more instructions than its run alone (compile %.1f%%)\n", 100 * (v - r) / r, 100 * c / r }'
  "$bench" --benchmark_filter='Variant|WithParameters' --benchmark_min_time=1 2>/dev/null | grep '^BM_' |
    sed 's/^/  (CPU time, machine load applies) /'
else
  echo "(build tools/bench_compile and install valgrind for the variant-vs-run split)"
fi
