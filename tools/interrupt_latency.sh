#!/usr/bin/env bash
# Measures how long sweep, tolerance --monte-carlo, range, view and run take to
# exit after a SIGINT with --keep-partial (issue 24: within 0.5 s), and Python's
# run()/tolerance()/sweep() to raise KeyboardInterrupt. Each command is started on
# a long job, signalled after 1 s, and the time from the signal to its exit printed.
# Usage: tools/interrupt_latency.sh [MECHKIN_BINARY] [WORK_DIR]   (tests never time this)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$here/build/mechkin}
work=${2:-$(mktemp -d)}
mkdir -p "$work"
py=/usr/bin/python3
four_bar=$here/mechanisms/parametric-four-bar.json
$py - "$four_bar" "$work/long.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1])); doc["analysis"]["steps"] = 2000000
json.dump(doc, open(sys.argv[2], "w"))
PY

measure() {  # name, command...
  local name=$1; shift
  "$@" >/dev/null 2>&1 &
  local pid=$!
  sleep 1
  local t0; t0=$(date +%s.%N)
  kill -INT "$pid"
  local rc=0; wait "$pid" || rc=$?
  local t1; t1=$(date +%s.%N)
  printf "%-28s exit %3d  %.3f s after SIGINT\n" "$name" "$rc" "$(echo "$t1 - $t0" | bc)"
}
measure "sweep 20000 variants" "$bin" sweep "$four_bar" --samples 20000 -o "$work/s.csv" --keep-partial
measure "tolerance --monte-carlo 1e5" "$bin" tolerance "$four_bar" --monte-carlo 100000 -o "$work/t.txt" --keep-partial
measure "range --steps 1e7" "$bin" range "$four_bar" --steps 10000000 -o "$work/r.txt" --keep-partial
measure "view 2e6 steps" "$bin" view "$work/long.json" --order 0 -o "$work/v.html" --keep-partial
measure "run 2e6 steps" "$bin" run "$work/long.json" -o "$work/r.csv" --keep-partial

PYTHONPATH=${PYTHONPATH:-$here/build/python} $py - "$four_bar" <<'PY'
import os, signal, sys, threading, time
import mechkin
model = mechkin.load(sys.argv[1])
calls = {"run()": lambda: model.run(order=0, bodies=[], steps=3000000),
         "tolerance(monte_carlo=1e5)": lambda: model.tolerance(monte_carlo=100000),
         "sweep(20000 variants)": lambda: mechkin.sweep(model, [{"a": 30 + k * 1e-3} for k in range(20000)])}
for name, call in calls.items():
    sent = []
    timer = threading.Timer(1.0, lambda: (sent.append(time.perf_counter()), os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    try:
        call()
        print("%-28s finished without an interrupt" % name)
    except KeyboardInterrupt:
        print("%-28s KeyboardInterrupt %.3f s after SIGINT" % (name, time.perf_counter() - sent[0]))
PY
