#!/usr/bin/env python3
"""The README's closed-form error figures for issue 11, from the installed package:

    /usr/bin/python3 tools/closed_form_errors.py      (or PYTHONPATH=build/python)

Bennett 40/65 deg over a turn (Bennett's closure), the piston-driven slider-crank
toward its dead centre (geometry stored exactly, and 20/50 mm), and the input
limit of a non-Grashof four-bar (the same mechanisms as the C++ tests)."""
import json
import math
import os

import numpy as np

import mechkin

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def rot(axis, angle):
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]], float)
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k


def bennett(alpha, beta, theta1):
    k = math.sin((beta + alpha) / 2) / math.sin((beta - alpha) / 2)
    theta2 = 2 * math.atan2(k * math.cos(theta1 / 2), math.sin(theta1 / 2))
    a = 100.0
    b = a * math.sin(beta) / math.sin(alpha)
    r, p, origin, axis = np.eye(3), np.zeros(3), [], []
    for th, length, tw in ((theta1, a, alpha), (theta2, b, beta), (2 * math.pi - theta1, a, alpha), (2 * math.pi - theta2, b, beta)):
        origin.append(p.copy())
        axis.append(r[:, 2].copy())
        r = r @ rot((0, 0, 1), th)
        p = p + r @ np.array([length, 0, 0])
        r = r @ rot((1, 0, 0), tw)
    names, pairs = ["link1", "link2", "link3"], [("ground", "link1"), ("link1", "link2"), ("link2", "link3"), ("link3", "ground")]
    return {"mechkin": 1, "units": {"length": "mm", "angle": "deg"},
            "bodies": [{"name": names[i], "position": list((origin[i] + origin[i + 1]) / 2)} for i in range(3)],
            "joints": [{"name": "J%d" % (i + 1), "type": "revolute", "body1": pairs[i][0], "body2": pairs[i][1],
                        "origin": list(origin[i]), "axis": list(axis[i])} for i in range(4)],
            "drivers": [{"name": "motor", "type": "rotation", "joint": "J1", "function": "360*t"}],
            "outputs": [{"name": "theta1", "type": "joint", "joint": "J1"}, {"name": "theta2", "type": "joint", "joint": "J2"}],
            "analysis": {"start": 0, "end": 1, "steps": 360}}, k, theta2


def bennett_error(tol):
    alpha, beta, theta1 = math.radians(40), math.radians(65), math.radians(70)
    doc, k, theta2 = bennett(alpha, beta, theta1)
    m = mechkin.loads(doc).run(tol=tol, si=True, bodies=[])
    t1, t2 = theta1 + m["theta1"], theta2 + m["theta2"]
    want = 2 * np.arctan2(k * np.cos(t1 / 2), np.sin(t1 / 2))
    return m.complete, len(m.reselections), np.abs(np.angle(np.exp(1j * (t2 - want)))).max()


def piston_doc(unit, a, b, bx, by):
    """The piston-driven slider-crank of tests/analysis/accuracy_target_test.cpp: the crank
    angle is atan2(by, bx)·cos(πt/2), the dead centre at t = 1; run to t = 0.998."""
    th0, cx = math.atan2(by, bx), bx + math.sqrt(b * b - by * by)
    fn = "%.17g*cos(%.17g*cos(pi*t/2)) + sqrt(%.17g - %.17g*sin(%.17g*cos(pi*t/2))^2) - %.17g" % (
        a, th0, b * b, a * a, th0, cx)
    rev = lambda n, b1, b2, x, y: {"name": n, "type": "revolute", "body1": b1, "body2": b2, "origin": [x, y, 0], "axis": [0, 0, 1]}
    return {"mechkin": 1, "units": {"length": unit, "angle": "deg"},
            "bodies": [{"name": "crank", "position": [bx / 2, by / 2, 0]},
                       {"name": "rod", "position": [(bx + cx) / 2, by / 2, 0]},
                       {"name": "slider", "position": [cx, 0, 0]}],
            "joints": [rev("A", "ground", "crank", 0, 0), rev("B", "crank", "rod", bx, by), rev("C", "rod", "slider", cx, 0),
                       {"name": "P", "type": "prismatic", "body1": "ground", "body2": "slider", "origin": [cx, 0, 0],
                        "axis": [1, 0, 0]}],
            "drivers": [{"name": "piston", "type": "translation", "joint": "P", "function": fn}],
            "outputs": [{"name": "crank_angle", "type": "joint", "joint": "A"}],
            "analysis": {"start": 0, "end": 0.998, "steps": 499}}, th0


def piston_errors(exact):
    """Worst error / scale per order. exact: crank 34, rod 50, pin (16, 30) in 1/64 m, which
    the file stores exactly; else 20/50 mm at 60°, whose rounded coordinates move the answer."""
    doc, th0 = piston_doc("m", 34 / 64, 50 / 64, 16 / 64, 30 / 64) if exact else \
        piston_doc("mm", 20.0, 50.0, 10.0, 10 * math.sqrt(3))
    m = mechkin.loads(doc).run(order=3, si=True, bodies=[])
    w = math.pi / 2
    c, s = np.cos(w * m.t), np.sin(w * m.t)
    want = [th0 * (c - 1), -th0 * w * s, -th0 * w * w * c, th0 * w ** 3 * s]
    names = ["crank_angle", "crank_angle_t", "crank_angle_tt", "crank_angle_ttt"]
    return [np.abs(m[n] - want[k]).max() / (th0 * w ** k) for k, n in enumerate(names)]


def non_grashof_limit_error():
    g, a, b, c, th = 100.0, 70.0, 40.0, 60.0, math.pi / 3
    bx, by = a * math.cos(th), a * math.sin(th)
    dx, dy = g - bx, -by
    d = math.hypot(dx, dy)
    aa = (b * b - c * c + d * d) / (2 * d)
    h = math.sqrt(b * b - aa * aa)
    cx, cy = bx + aa * dx / d - h * dy / d, by + aa * dy / d + h * dx / d
    rev = lambda n, b1, b2, x, y: {"name": n, "type": "revolute", "body1": b1, "body2": b2, "origin": [x, y, 0], "axis": [0, 0, 1]}
    doc = {"mechkin": 1, "units": {"length": "mm", "angle": "deg"},
           "bodies": [{"name": "crank", "position": [bx / 2, by / 2, 0]},
                      {"name": "coupler", "position": [(bx + cx) / 2, (by + cy) / 2, 0]},
                      {"name": "rocker", "position": [(cx + g) / 2, cy / 2, 0]}],
           "joints": [rev("A", "ground", "crank", 0, 0), rev("B", "crank", "coupler", bx, by),
                      rev("C", "coupler", "rocker", cx, cy), rev("D", "ground", "rocker", g, 0)],
           "drivers": [{"name": "motor", "type": "rotation", "joint": "A", "function": "90*t"}],
           "analysis": {"start": 0, "end": 1, "steps": 90}}
    m = mechkin.loads(doc).run()
    limit = math.acos((a * a + g * g - (b + c) ** 2) / (2 * a * g))
    return abs(m.stop.limit["driver_values"][0] - (limit - th))


if __name__ == "__main__":
    for tol in (1e-10, 1e-12):
        done, reselections, err = bennett_error(tol)
        print("Bennett 40/65, tol %g: complete %s, %d re-selections, largest error %.2g rad" % (tol, done, reselections, err))
    for exact, what in ((True, "stored exactly"), (False, "20/50 mm, rounded")):
        print("piston toward its dead centre (%s), worst error / scale (angle, velocity, acceleration, jerk): %s"
              % (what, ", ".join("%.2g" % e for e in piston_errors(exact))))
    print("non-Grashof four-bar, input limit located to %.2g rad" % non_grashof_limit_error())
