#!/usr/bin/env python3
"""Python-package overhead and thread scaling (issue: import mechkin).

1. A 100,000-step run of the spatial slider-crank through `model.run()` against
   the CLI on the same file: `mechkin run --stats` (median solve time per step ×
   rows) and the CLI's whole wall time writing the full table.
2. 1,000 runs of the bundled slider-crank: serially, then from 2 threads.

Usage: PYTHONPATH=build/python /usr/bin/python3 tools/bench_python.py [build/mechkin]"""
import json, os, re, subprocess, sys, tempfile, threading, time

import mechkin

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
cli = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "mechkin")
src = os.path.join(root, "mechanisms", "spatial-slider-crank.json")
doc = json.load(open(src))
doc["analysis"] = {"start": 0, "end": 100, "steps": 100000}
tmp = tempfile.mkdtemp()
big = os.path.join(tmp, "slider-crank-100k.json")
json.dump(doc, open(big, "w"))

model = mechkin.load(big)
best_py = min(_time for _time in (lambda: [(lambda t0: (model.run(), time.perf_counter() - t0)[1])(time.perf_counter()) for _ in range(3)])())
best_cli, solve = 1e9, 1e9
for _ in range(3):
    t0 = time.perf_counter()
    p = subprocess.run([cli, "run", big, "-o", os.path.join(tmp, "t.csv"), "--stats"], capture_output=True, text=True)
    best_cli = min(best_cli, time.perf_counter() - t0)
    us = float(re.search(r"per step: ([0-9.]+) us solve", p.stderr).group(1))
    solve = min(solve, us * 1e-6 * 100001)
print("100,000 steps: python model.run() %.3f s; CLI solve (median step x rows) %.3f s -> ratio %.2f; "
      "CLI wall with full CSV table %.3f s" % (best_py, solve, best_py / solve, best_cli))

small = mechkin.load(src)
t0 = time.perf_counter()
for _ in range(1000):
    small.run()
serial = time.perf_counter() - t0
def work():
    for _ in range(500):
        small.run()
threads = [threading.Thread(target=work) for _ in range(2)]
t0 = time.perf_counter()
for th in threads: th.start()
for th in threads: th.join()
parallel = time.perf_counter() - t0
print("1,000 slider-crank runs: serial %.2f s, 2 threads %.2f s -> speed-up %.2fx" % (serial, parallel, serial / parallel))
