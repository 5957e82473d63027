#!/usr/bin/env bash
# Times `mechkin check` on large generated models: the 1000- and 5000-loop chains
# (tools/make_chain.py, spatial and --revolute), 1000 free bodies with no joints,
# a chain of 5000 bodies hung from the ground by spherical joints (10,002 idle
# freedoms whose pairs overlap along the chain), and a file with 3000 chained parameters (p0 = 1, p_k = "p_{k-1}+1"), also
# chained the other way (p2999 = 1, p_k = "p_{k+1}+1").
# Usage: tools/check_scaling.sh [MECHKIN_BINARY] [WORK_DIR]
#   (defaults: build/mechkin, a temporary folder). Prints one line per model:
#   wall-clock seconds, user+system CPU seconds, peak memory, exit status, model.
#   One run each; the wall clock is noisy on a loaded machine, the CPU time less so.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$here/build/mechkin}
work=${2:-$(mktemp -d)}
py=/usr/bin/python3
mkdir -p "$work"

$py "$here/tools/make_chain.py" 1000 "$work/chain-1000.json"
$py "$here/tools/make_chain.py" 1000 "$work/chain-1000-revolute.json" --revolute
$py "$here/tools/make_chain.py" 5000 "$work/chain-5000.json"
$py "$here/tools/make_chain.py" 5000 "$work/chain-5000-revolute.json" --revolute
$py - "$work" <<'EOF'
import json, sys
work = sys.argv[1]
bodies = [{"name": "b%d" % i, "position": [0.1 * i, 0.0, 0.0]} for i in range(1000)]
json.dump({"mechkin": 1, "name": "1000 free bodies", "units": {"length": "m", "angle": "deg"},
           "bodies": bodies, "joints": []}, open(work + "/free-1000.json", "w"), indent=1)
n = 5000
json.dump({"mechkin": 1, "name": "5000 bodies on spherical joints", "units": {"length": "m", "angle": "deg"},
           "bodies": [{"name": "b%d" % i, "position": [0.1 * i, 0.02 * (i % 3), 0.0]} for i in range(n)],
           "joints": [{"name": "s%d" % i, "type": "spherical", "body1": "b%d" % (i - 1) if i else "ground",
                       "body2": "b%d" % i, "origin": [0.1 * i - 0.05, 0.01 * (i % 2), 0.0]} for i in range(n)]},
          open(work + "/spherical-chain-5000.json", "w"), indent=1)
params = {"p0": 1}
for k in range(1, 3000):
    params["p%d" % k] = "p%d+1" % (k - 1)
json.dump({"mechkin": 1, "name": "3000 chained parameters", "units": {"length": "m", "angle": "deg"},
           "parameters": params,
           "bodies": [{"name": "b", "position": ["p2999", 0, 0]}],
           "joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "b",
                       "origin": [0, 0, 0], "axis": [0, 0, 1]}],
           "drivers": [{"name": "d", "type": "rotation", "joint": "j", "function": "360*t"}],
           "analysis": {"start": 0, "end": 1, "steps": 10}},
          open(work + "/parameters-3000.json", "w"), indent=1)
reverse = {"p2999": 1}
for k in range(2998, -1, -1):
    reverse["p%d" % k] = "p%d+1" % (k + 1)
json.dump({"mechkin": 1, "name": "3000 parameters chained backwards", "units": {"length": "m", "angle": "deg"},
           "parameters": reverse,
           "bodies": [{"name": "b", "position": ["p0", 0, 0]}],
           "joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "b",
                       "origin": [0, 0, 0], "axis": [0, 0, 1]}],
           "drivers": [{"name": "d", "type": "rotation", "joint": "j", "function": "360*t"}],
           "analysis": {"start": 0, "end": 1, "steps": 10}},
          open(work + "/parameters-3000-backwards.json", "w"), indent=1)
EOF

for m in chain-1000 chain-1000-revolute chain-5000 chain-5000-revolute free-1000 spherical-chain-5000 parameters-3000 parameters-3000-backwards; do
  set +e
  /usr/bin/time -f "%e %U %S %M" -o "$work/$m.time" "$bin" check "$work/$m.json" >/dev/null 2>&1
  rc=$?
  set -e
  read -r wall user sys kb < <(tail -1 "$work/$m.time")
  printf "%-26s %6.2f s wall  %6.2f s cpu  %5d MiB  exit %d\n" "$m" "$wall" "$(awk -v u="$user" -v s="$sys" 'BEGIN { print u + s }')" $((kb / 1024)) $rc
done
