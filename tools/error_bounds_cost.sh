#!/usr/bin/env bash
# The cost of error bounds measured on more rows (docs/constraints.md §8): wall time of
# `mechkin run` on bundled mechanisms at 20,000 steps, best of 3, interleaved, for
#   auto      the default (rows near singular positions measured whole, a sample of
#             the others: src/analysis/bound_sampling.hpp),
#   measured  `--error-bounds measured` (every row),
#   baseline  the default of another build, when given (e.g. one from before the samples).
#   bash tools/error_bounds_cost.sh [build/mechkin] [baseline-mechkin]
set -euo pipefail
shopt -s inherit_errexit  # a failed run inside $(seconds ...) stops the script
bin="${1:-build/mechkin}"
baseline="${2:-}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
seconds() {  # wall time of one run: binary, then its arguments
  local start
  start=$(date +%s.%N)
  "$@" -o "$tmp/t.csv" 2>/dev/null || { echo "error_bounds_cost.sh: failed: $*" >&2; exit 1; }
  echo "$(date +%s.%N) - $start" | bc
}
for name in spatial-slider-crank double-wishbone-suspension bennett-linkage planar-four-bar; do
  /usr/bin/python3 -c "import json,sys; d=json.load(open('mechanisms/$name.json')); d['analysis']['steps']=20000; json.dump(d, open('$tmp/m.json','w'))"
  best_auto=""; best_measured=""; best_baseline=""
  for _ in 1 2 3; do
    t=$(seconds "$bin" run "$tmp/m.json" --error-bounds auto)
    if [ -z "$best_auto" ] || (( $(echo "$t < $best_auto" | bc) )); then best_auto=$t; fi
    t=$(seconds "$bin" run "$tmp/m.json" --error-bounds measured)
    if [ -z "$best_measured" ] || (( $(echo "$t < $best_measured" | bc) )); then best_measured=$t; fi
    if [ -n "$baseline" ]; then
      t=$(seconds "$baseline" run "$tmp/m.json")
      if [ -z "$best_baseline" ] || (( $(echo "$t < $best_baseline" | bc) )); then best_baseline=$t; fi
    fi
  done
  line="$name: auto $(printf '%.3f' "$best_auto") s, measured $(printf '%.3f' "$best_measured") s (ratio $(echo "scale=2; $best_measured / $best_auto" | bc))"
  if [ -n "$baseline" ]; then
    line="$line, baseline $(printf '%.3f' "$best_baseline") s (auto/baseline $(echo "scale=3; $best_auto / $best_baseline" | bc))"
  fi
  echo "$line"
done
