#!/usr/bin/python3
"""Scan the IFToMM A02 N-four-bar through its singular positions (issue 23, item 1).

Runs `mechkin run` on N = 1..4 chains (tests/n_four_bar.hpp: crank and N rockers of
length 1 on pivots 1 apart, couplers of length 1), drawn at four crank angles θ0 and
driven at seven rates over [0, 1] s in 50, 100 and 360 steps, at the default
tolerance and at 1e-13: 672 runs. The closed form (docs/singularities.md §4): the
first crank angle of +90° (mod 360°) is a bifurcation, where the run must stop with
"singular position at t = t*"; every −90° before it is a unique passage, which the
run must note ("unique passage ... at t = t*") and pass. A limit of motion is never
right. Prints the number of runs judged otherwise and each of them.

    /usr/bin/python3 tools/n_four_bar_scan.py [build/mechkin]
"""
import itertools
import json
import math
import os
import re
import subprocess
import sys
import tempfile


def n_four_bar(n, theta0_deg, rate_deg, steps):
    th = math.radians(theta0_deg)
    ex, ey = -math.sin(th), math.cos(th)
    rocker = lambda i: "crank" if i == 0 else f"rocker{i}"
    doc = {"mechkin": 1, "name": "N-four-bar", "units": {"length": "m", "angle": "deg"},
           "bodies": [], "joints": []}
    for i in range(n + 1):
        doc["bodies"].append({"name": rocker(i), "position": [i, 0, 0]})
        doc["joints"].append({"name": f"pivot{i}", "type": "revolute", "body1": "ground", "body2": rocker(i),
                              "origin": [i, 0, 0], "axis": [0, 0, 1]})
    for i in range(1, n + 1):
        left, right = [i - 1 + ex, ey, 0], [i + ex, ey, 0]
        doc["bodies"].append({"name": f"coupler{i}", "position": left})
        doc["joints"].append({"name": f"left{i}", "type": "revolute", "body1": rocker(i - 1),
                              "body2": f"coupler{i}", "origin": left, "axis": [0, 0, 1]})
        doc["joints"].append({"name": f"right{i}", "type": "revolute", "body1": f"coupler{i}",
                              "body2": rocker(i), "origin": right, "axis": [0, 0, 1]})
    doc["drivers"] = [{"name": "crank", "type": "rotation", "joint": "pivot0", "function": f"{rate_deg!r}*t"}]
    doc["analysis"] = {"start": 0, "end": 1, "steps": steps}
    return doc


def first_time_at(target_deg, theta0, rate):
    times = [(target_deg + 360 * k - theta0) / rate for k in range(-3, 4)]
    times = [t for t in times if 0 < t <= 1]
    return min(times) if times else None


def misjudged(stderr, returncode, theta0, rate):
    """What is wrong with the run's ending, or '' when it is as the closed form says."""
    why = []
    t_bif = first_time_at(90, theta0, rate)
    stop = re.search(r"json: singular position at t = ([0-9.e-]+)", stderr)
    if t_bif is not None and (returncode != 1 or not stop or abs(float(stop.group(1)) - t_bif) > 1e-6):
        why.append(f"expected a stop at {t_bif:.6f} (exit {returncode})")
    if t_bif is None and returncode != 0:
        why.append(f"exit {returncode}")
    notes = [float(x) for x in re.findall(r"unique passage through a singular position at t = ([0-9.e-]+)", stderr)]
    t_pass = first_time_at(-90, theta0, rate)
    if t_pass is not None and (t_bif is None or t_pass < t_bif) and not any(abs(x - t_pass) < 1e-6 for x in notes):
        why.append(f"no passage note at {t_pass:.6f}")
    if "limit of motion" in stderr:
        why.append("a limit of motion")
    return "; ".join(why)


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "build/mechkin"
    bad, runs = [], 0
    with tempfile.TemporaryDirectory() as tmp:
        path, table = os.path.join(tmp, "n-four-bar.json"), os.path.join(tmp, "table.csv")
        for n, theta0, rate, steps, tol in itertools.product(
                [1, 2, 3, 4], [0, 180, 37, -150], [97, -97, 123, -123, 181, -181, 359], [50, 100, 360], [None, 1e-13]):
            with open(path, "w") as f:
                json.dump(n_four_bar(n, theta0, rate, steps), f)
            args = [binary, "run", path, "-o", table] + (["--tol", str(tol)] if tol else [])
            r = subprocess.run(args, capture_output=True, text=True)
            runs += 1
            why = misjudged(r.stderr, r.returncode, theta0, rate)
            if why:
                bad.append(f"N={n} theta0={theta0} rate={rate} steps={steps} tol={tol or 'default'}: {why}")
    print(f"{runs} runs, {len(bad)} misjudged")
    for line in bad:
        print("  " + line)


if __name__ == "__main__":
    main()
