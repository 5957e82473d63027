#!/usr/bin/env bash
# The cost of measured error bounds on every row (`run --error-bounds measured`,
# docs/constraints.md §8) against the default (measured near singular positions
# only): wall time of `mechkin run` on bundled mechanisms at 20,000 steps, best of 3.
#   bash tools/error_bounds_cost.sh [build/mechkin]
set -euo pipefail
bin="${1:-build/mechkin}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for name in spatial-slider-crank double-wishbone-suspension bennett-linkage planar-four-bar; do
  /usr/bin/python3 -c "import json,sys; d=json.load(open('mechanisms/$name.json')); d['analysis']['steps']=20000; json.dump(d, open('$tmp/m.json','w'))"
  line="$name:"
  for mode in auto measured; do
    best=""
    for _ in 1 2 3; do
      start=$(date +%s.%N)
      "$bin" run "$tmp/m.json" --error-bounds "$mode" -o "$tmp/t.csv" 2>/dev/null
      t=$(echo "$(date +%s.%N) - $start" | bc)
      if [ -z "$best" ] || (( $(echo "$t < $best" | bc) )); then best=$t; fi
    done
    eval "time_$mode=$best"
    line="$line $mode $(printf '%.3f' "$best") s"
  done
  echo "$line  ratio $(echo "scale=2; $time_measured / $time_auto" | bc)"
done
