#!/usr/bin/env python3
"""What writing the whole motion table costs over the solve (issue 32: the full table
within 2x of the solve-only run at 100,000 rows, peak memory < 50 MiB).

    /usr/bin/python3 tools/table_cost.py [build/mechkin] [--steps 100000] [--rounds 5]

Runs the spatial slider-crank over STEPS steps ROUNDS times, `run FILE -o full.csv
--stats`: every column (99). Its solve is what `--stats` measures of the same run (the
per-step solve time times the steps: position to jerk, the diagnostics and the error
bounds); the table is everything else (the columns' values, formatting and writing them,
on a second thread). A run that writes fewer columns is no solve-only reference: with
`--bodies ''` it solves no block at all. Prints each run's wall time, solve time and peak
resident memory, then the best of each and the ratio full / solve. Wall time: run it on
an idle machine.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def timed(cmd):
    """(wall seconds, solve seconds from --stats, peak resident MiB) of one run of cmd."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    stats = proc.stderr.read().decode()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit("%s failed: %s" % (" ".join(cmd), stats))
    steps = int(re.search(r"steps: (\d+)", stats).group(1))
    per_step_us = float(re.search(r"per step: ([0-9.]+) us solve", stats).group(1))
    return wall, steps * per_step_us * 1e-6, usage.ru_maxrss / 1024.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cli", nargs="?", default=os.path.join(ROOT, "build", "mechkin"))
    parser.add_argument("--steps", type=int, default=100000)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    with open(os.path.join(ROOT, "mechanisms", "spatial-slider-crank.json")) as f:
        doc = json.load(f)
    doc["analysis"]["steps"] = args.steps
    with tempfile.TemporaryDirectory() as tmp:
        model = os.path.join(tmp, "slider-crank-%d.json" % args.steps)
        with open(model, "w") as f:
            json.dump(doc, f)
        cmd = [args.cli, "run", model, "-o", os.path.join(tmp, "full.csv"), "--stats"]
        runs = []
        for round_index in range(args.rounds):
            wall, solve, peak = timed(cmd)
            runs.append((wall, solve, peak))
            print("round %d: %.3f s wall, solve %.3f s, %.1f MiB peak" % (round_index + 1, wall, solve, peak))
        wall = min(r[0] for r in runs)
        solve = min(r[1] for r in runs)
        peak = max(r[2] for r in runs)
        print("best of %d: full table %.3f s wall, solve %.3f s: full / solve = %.2fx; peak %.1f MiB"
              % (args.rounds, wall, solve, wall / solve, peak))

if __name__ == "__main__":
    main()
