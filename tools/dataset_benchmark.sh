#!/usr/bin/env bash
# Dataset sweep benchmark (issue 31; not a test): N sampled four-bar variants
# (mechanisms/parametric-four-bar.json with 360-row runs) written with their
# coupler curves (coupler_point.x, coupler_point.y) into HDF5 by
#   mechkin sweep FILE --samples N --curves coupler_point.x,coupler_point.y --out DIR
# Prints wall and CPU time, throughput per core (variants per CPU-second: the
# machine's load does not change it much), the file size and the peak memory
# (/usr/bin/time -v), for N/10 and N variants (flat memory: the same peak), then
# reads the file with h5py. Usage: tools/dataset_benchmark.sh [BUILD_DIR] [N] [THREADS]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
n="${2:-100000}"
threads="${3:-2}"
work="$(mktemp -d "${TMPDIR:-/tmp}/mechkin-dataset-XXXXXX")"
trap 'rm -rf "$work"' EXIT
file="$work/four-bar-360.json"
/usr/bin/python3 - "$here/mechanisms/parametric-four-bar.json" "$file" <<'PY'
import json, sys
spec = json.load(open(sys.argv[1]))
spec["analysis"]["steps"] = 359  # 360 rows
json.dump(spec, open(sys.argv[2], "w"))
PY
for count in $((n / 10)) "$n"; do
  out="$work/data-$count"
  /usr/bin/time -v "$build/mechkin" sweep "$file" --samples "$count" --seed 1 --threads "$threads" \
    --curves coupler_point.x,coupler_point.y --out "$out" 2> "$work/time.txt"
  grep '^mechkin sweep' "$work/time.txt"
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; print s}' "$work/time.txt")
  cpu=$(awk -F': ' '/User time/ {u = $2} /System time/ {s = $2} END {print u + s}' "$work/time.txt")
  peak=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time.txt")
  size=$(stat -c %s "$out/sweep.h5")
  printf "%d variants, %d threads: wall %.1f s (%.0f variants/s), CPU %.1f s (%.0f variants per CPU-second = per core), " \
    "$count" "$threads" "$wall" "$(echo "$count / $wall" | bc -l)" "$cpu" "$(echo "$count / $cpu" | bc -l)"
  printf "file %.1f MB (%.0f bytes a variant), peak memory %.1f MB\n" "$(echo "$size / 1000000" | bc -l)" \
    "$(echo "$size / $count" | bc -l)" "$(echo "$peak / 1024" | bc -l)"
  if [ "$count" != "$n" ]; then rm -rf "$out"; fi
done
/usr/bin/python3 - "$work/data-$n/sweep.h5" "$build/mechkin" "$file" "$work" <<'PY'
import json, random, subprocess, sys, time
import h5py, numpy as np
path, mechkin, model, work = sys.argv[1:]
start = time.time()
with h5py.File(path, "r") as f:
    curves = f["curves"][()]
    status = f["status"][()]
    names = list(f["status"].attrs["names"])
    parameters, keys, rows = f["parameters"][()], list(f["parameters"].attrs["names"]), f["rows"][()]
    columns = list(f["curves"].attrs["columns"])
print("h5py: curves %s read in %.2f s; statuses: %s" % (curves.shape, time.time() - start,
      ", ".join("%d %s" % (np.sum(status == k), names[k]) for k in np.unique(status))))
# The acceptance: 5 random variants that ran equal `mechkin run --set ...` bit for bit.
ran = [i for i in range(len(status)) if rows[i] > 0]
same = 0
picks = random.Random(31).sample(ran, 5)
for i in picks:
    sets = sum((["--set", "%s=%r" % (k, float(v))] for k, v in zip(keys, parameters[i])), [])
    subprocess.run([mechkin, "run", model, *sets, "--order", "1", "--format", "json", "-o", work + "/run.json",
                    "--quiet"], capture_output=True)
    table = json.load(open(work + "/run.json"))
    heads = [c["name"] for c in table["columns"]]
    run = np.array([[row[heads.index(c)] for c in columns] for row in table["rows"]], dtype=np.float64)
    same += run.tobytes() == np.ascontiguousarray(curves[i, :rows[i]]).tobytes()
print("variants %s against mechkin run --set: %d of 5 equal bit for bit" % (picks, same))
PY
