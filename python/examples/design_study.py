#!/usr/bin/env python3
"""Design study: how the coupler (rod) length of the offset slider-crank moves
the piston's stroke and its peak acceleration. Each variant is the bundled file
with one number changed, loaded from a dict; a plot is drawn when matplotlib is
installed (apt-get install python3-matplotlib), else a table is printed.

    /usr/bin/python3 python/examples/design_study.py [--plot study.png]
"""
import argparse
import os

import numpy as np

import mechkin

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def slider_crank(crank, rod, offset, start_deg=30.0):
    """A planar offset slider-crank (mm, deg) drawn assembled at the crank angle `start_deg`."""
    th = np.radians(start_deg)
    pin = np.array([crank * np.cos(th), crank * np.sin(th), 0.0])
    wrist = np.array([pin[0] + np.sqrt(rod ** 2 - (pin[1] - offset) ** 2), offset, 0.0])
    v = lambda p: [float(x) for x in p]
    return {
        "mechkin": 1, "name": "slider-crank %g/%g/%g" % (crank, rod, offset),
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "crank", "position": v(pin / 2)}, {"name": "rod", "position": v((pin + wrist) / 2)},
                   {"name": "slider", "position": v(wrist)}],
        "joints": [
            {"name": "bearing", "type": "revolute", "body1": "ground", "body2": "crank", "origin": [0, 0, 0], "axis": [0, 0, 1]},
            {"name": "crankpin", "type": "revolute", "body1": "crank", "body2": "rod", "origin": v(pin), "axis": [0, 0, 1]},
            {"name": "wristpin", "type": "spherical", "body1": "rod", "body2": "slider", "origin": v(wrist)},
            {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "origin": v(wrist), "axis": [1, 0, 0]}],
        "drivers": [{"name": "motor", "type": "rotation", "joint": "bearing", "function": "360*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 360},
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--plot", help="write a PNG with matplotlib")
    args = ap.parse_args()
    print("%8s %12s %16s" % ("rod [mm]", "stroke [mm]", "peak |a| [mm/s²]"))
    curves = []
    for rod in (60.0, 80.0, 120.0, 160.0, 240.0):
        model = mechkin.loads(slider_crank(40.0, rod, 10.0), source="rod %g mm" % rod)
        motion = model.run(order=2)
        if not motion.complete:
            print("%8g  does not complete: %s" % (rod, motion.stop.message.splitlines()[0]))
            continue
        x = motion.body("slider").position(0)[:, 0]
        a = motion.body("slider").position(2)[:, 0]
        print("%8g %12.4f %16.1f" % (rod, x.max() - x.min(), np.abs(a).max()))
        curves.append((rod, motion.t, a))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        if args.plot:
            print("matplotlib is not installed: no plot (apt-get install python3-matplotlib)")
        return
    if args.plot:
        for rod, t, a in curves:
            plt.plot(t, a, label="rod %g mm" % rod)
        plt.xlabel("t [s]")
        plt.ylabel("slider acceleration [mm/s²]")
        plt.legend()
        plt.savefig(args.plot, dpi=120)
        print("plot written to", args.plot)


if __name__ == "__main__":
    main()
