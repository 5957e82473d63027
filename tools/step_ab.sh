#!/bin/bash
# Interleaved per-step timing of several mechkin binaries (builds of different commits):
# each round runs `BIN run FILE --stats` once per binary, in turn, so that a change in
# the machine's speed during the measurement reaches every binary alike. Prints, per
# binary, the best and the median over the rounds of the run's own per-step median.
#   tools/step_ab.sh ROUNDS FILE BIN...
#   tools/step_ab.sh 20 mechanisms/spatial-slider-crank.json /tmp/old/mechkin build/mechkin
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 ROUNDS FILE BIN..." >&2
  exit 2
fi
rounds=$1 file=$2
shift 2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for _ in $(seq "$rounds"); do
  line=""
  for bin in "$@"; do
    # A failed run prints no per-step line and counts as nan (it must not end the script).
    step=$({ "$bin" run "$file" -o "$out/table.csv" --stats 2>&1 || true; } | sed -n 's/^per step: \([0-9.]*\) us solve.*/\1/p')
    line="$line ${step:-nan}"
  done
  echo "$line"
done | /usr/bin/python3 -c '
import statistics, sys
names = sys.argv[1:]
rows = [[float(v) for v in line.split()] for line in sys.stdin]
for j, name in enumerate(names):
    col = [r[j] for r in rows]
    print("%-40s best %.3f us  median %.3f us  (%d rounds)" % (name, min(col), statistics.median(col), len(col)))
' "$@"
