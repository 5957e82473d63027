#!/usr/bin/env python3
"""What writing the whole motion table costs over the solve (issue 32: the full table
within 2x of the solve-only run at 100,000 rows, peak memory < 50 MiB).

    /usr/bin/python3 tools/table_cost.py [build/mechkin] [--steps 100000] [--rounds 5]

Runs the spatial slider-crank over STEPS steps, interleaved ROUNDS times:
  full:       `run FILE -o full.csv`, every column (99);
  solve-only: `run FILE --bodies '' --outputs '' -o thin.csv`, the same solve (every
              body is still solved: the constraints need them) writing only the time
              and diagnostic columns (8).
Prints each run's wall time and peak resident memory, then the best of each and the
ratio full / solve-only. Wall time, so run it on an idle machine.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def timed(cmd):
    """(wall seconds, peak resident MiB) of one run of cmd."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.exit("%s failed (%d): %s" % (" ".join(cmd), proc.returncode, proc.stderr.read().decode()))
    return wall, usage.ru_maxrss / 1024.0


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
        runs = {"full": [args.cli, "run", model, "-o", os.path.join(tmp, "full.csv")],
                "solve-only": [args.cli, "run", model, "--bodies", "", "--outputs", "", "-o",
                               os.path.join(tmp, "thin.csv")]}
        results = {name: [] for name in runs}
        for round_index in range(args.rounds):
            for name, cmd in runs.items():
                wall, peak = timed(cmd)
                results[name].append((wall, peak))
                print("round %d %-10s %.3f s wall, %.1f MiB peak" % (round_index + 1, name, wall, peak))
        best = {name: min(w for w, _ in r) for name, r in results.items()}
        peak = max(p for _, p in results["full"])
        print("best of %d: full %.3f s, solve-only %.3f s: full / solve-only = %.2fx; full table's peak %.1f MiB"
              % (args.rounds, best["full"], best["solve-only"], best["full"] / best["solve-only"], peak))


if __name__ == "__main__":
    main()
