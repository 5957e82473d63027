#!/usr/bin/env python3
"""A chain of N parallelogram windows written by markers only (no body positions):
rocker k (length 1) on the ground pivot (k, 0), coupler k (length 1) from rocker
k-1's tip to rocker k's, rocker 0 driven; every coupler starts 0.2 rad off level,
so `mechkin check` must close N loops (2N + 1 bodies).

Usage: make_marker_chain.py N > chain.json ; time build/mechkin check chain.json
"""
import json
import math
import sys


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
    tilt = {"point": [1, 0, 0], "axis": [0, 0, 1], "x_axis": [math.cos(-1.0), math.sin(-1.0), 0]}
    ground, bodies, joints = {}, [], []
    for k in range(n + 1):
        ground["P%d" % k] = {"point": [k, 0, 0], "x_axis": [math.cos(1.2), math.sin(1.2), 0]}
        bodies.append({"name": "rocker%d" % k, "markers": {"pivot": {"point": [0, 0, 0]}, "tip": tilt}})
        joints.append({"name": "G%d" % k, "type": "revolute", "body1": "ground", "marker1": "P%d" % k,
                       "body2": "rocker%d" % k, "marker2": "pivot"})
        if k == 0:
            continue
        bodies.append({"name": "coupler%d" % k, "markers": {"a": {"point": [0, 0, 0]}, "b": {"point": [1, 0, 0]}}})
        joints.append({"name": "A%d" % k, "type": "revolute", "body1": "rocker%d" % (k - 1), "marker1": "tip",
                       "body2": "coupler%d" % k, "marker2": "a"})
        joints.append({"name": "B%d" % k, "type": "revolute", "body1": "coupler%d" % k, "marker1": "b",
                       "body2": "rocker%d" % k, "marker2": "tip"})
    doc = {"mechkin": 1, "name": "marker chain of %d windows" % n, "ground": {"markers": ground}, "bodies": bodies,
           "joints": joints, "drivers": [{"name": "motor", "type": "rotation", "joint": "G0", "function": "0.1*t"}],
           "analysis": {"start": 0, "end": 1, "steps": 10}}
    json.dump(doc, sys.stdout)


if __name__ == "__main__":
    main()
