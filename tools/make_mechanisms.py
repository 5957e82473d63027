#!/usr/bin/env python3
"""Writes the bundled example mechanisms (mechanisms/*.json) with design poses
that are assembled exactly (computed here in closed form), so that Φ = 0 at the
design pose to round-off. Rerun after changing a geometry:
    python3 tools/make_mechanisms.py
"""
import json
import math
import os
import sys

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "mechanisms")


def add(a, b): return [a[i] + b[i] for i in range(3)]
def sub(a, b): return [a[i] - b[i] for i in range(3)]
def mul(s, a): return [s * x for x in a]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def norm(a): return math.sqrt(dot(a, a))
def unit(a): return mul(1 / norm(a), a)
def mid(a, b): return mul(0.5, add(a, b))
def r(v, nd=12): return [round(x, nd) + 0.0 for x in v]


def write(name, doc):
    with open(os.path.join(OUT, name + ".json"), "w") as f:
        json.dump(doc, f, indent=2)
        f.write("\n")


def circle_intersection_2d(p, rp, q, rq, upper=True):
    """Intersection of circles |x-p|=rp, |x-q|=rq in the plane (z=0)."""
    d = math.dist(p[:2], q[:2])
    a = (rp * rp - rq * rq + d * d) / (2 * d)
    h = math.sqrt(max(rp * rp - a * a, 0.0))
    ex = [(q[0] - p[0]) / d, (q[1] - p[1]) / d]
    base = [p[0] + a * ex[0], p[1] + a * ex[1]]
    s = 1 if upper else -1
    return [base[0] - s * h * ex[1], base[1] + s * h * ex[0], 0.0]


def four_bar():
    a, b, c, d = 40.0, 120.0, 80.0, 100.0
    th = math.radians(60)
    A, D = [0.0, 0.0, 0.0], [d, 0.0, 0.0]
    B = [a * math.cos(th), a * math.sin(th), 0.0]
    C = circle_intersection_2d(B, b, D, c, upper=True)
    z = [0, 0, 1]
    write("planar-four-bar", {
        "mechkin": 1, "name": "planar four-bar crank-rocker",
        "description": "Grashof crank-rocker (crank 40, coupler 120, rocker 80, frame 100 mm) built from four spatial "
                       "revolutes: overconstrained (3 redundant equations) but movable. Crank starts at 60 deg.",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "crank", "position": r(mid(A, B))},
                   {"name": "coupler", "position": r(mid(B, C))},
                   {"name": "rocker", "position": r(mid(C, D))}],
        "joints": [
            {"name": "A", "type": "revolute", "body1": "ground", "body2": "crank", "origin": r(A), "axis": z},
            {"name": "B", "type": "revolute", "body1": "crank", "body2": "coupler", "origin": r(B), "axis": z},
            {"name": "C", "type": "revolute", "body1": "coupler", "body2": "rocker", "origin": r(C), "axis": z},
            {"name": "D", "type": "revolute", "body1": "ground", "body2": "rocker", "origin": r(D), "axis": z}],
        "drivers": [{"name": "motor", "type": "rotation", "joint": "A", "function": "360*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 360},
        "outputs": [{"name": "rocker_angle", "type": "joint", "joint": "D"},
                    {"name": "coupler_point", "type": "point", "body": "coupler", "point": r(mid(B, C))}],
        "expect": {"grubler": -2, "mobility": 1, "redundant": 3, "idle": 0, "driven": "full"}})


def offset_slider_crank():
    a, b, e = 40.0, 120.0, 10.0
    th = math.radians(30)
    A = [0.0, 0.0, 0.0]
    B = [a * math.cos(th), a * math.sin(th), 0.0]
    C = [B[0] + math.sqrt(b * b - (e - B[1]) ** 2), e, 0.0]
    z = [0, 0, 1]
    write("offset-slider-crank", {
        "mechkin": 1, "name": "offset slider-crank R-R-R-P",
        "description": "Planar offset slider-crank (crank 40, rod 120, offset 10 mm) with spatial joints: 3 redundant "
                       "equations. Crank starts at 30 deg and turns once per second.",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "crank", "position": r(mid(A, B))},
                   {"name": "rod", "position": r(mid(B, C))},
                   {"name": "slider", "position": r(C)}],
        "joints": [
            {"name": "bearing", "type": "revolute", "body1": "ground", "body2": "crank", "origin": r(A), "axis": z},
            {"name": "crankpin", "type": "revolute", "body1": "crank", "body2": "rod", "origin": r(B), "axis": z},
            {"name": "wristpin", "type": "revolute", "body1": "rod", "body2": "slider", "origin": r(C), "axis": z},
            {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "origin": r(C), "axis": [1, 0, 0]}],
        "drivers": [{"name": "motor", "type": "rotation", "joint": "bearing", "function": "360*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 360},
        "outputs": [{"name": "piston", "type": "point", "body": "slider", "point": r(C)},
                    {"name": "stroke", "type": "joint", "joint": "guide"}],
        "expect": {"grubler": -2, "mobility": 1, "redundant": 3, "idle": 0, "driven": "full"}})


def spatial_slider_crank():
    a, b, ey, ez = 0.10, 0.30, 0.02, 0.05
    th = 0.0
    A = [0.0, 0.0, 0.0]
    B = [a * math.cos(th), a * math.sin(th), 0.0]
    C = [B[0] + math.sqrt(b * b - (ey - B[1]) ** 2 - ez ** 2), ey, ez]
    u = unit(sub(C, B))
    axis2 = [0.0, 0.0, 1.0]              # fixed in the slider
    axis1 = unit(cross(axis2, u))        # fixed in the rod, perpendicular to axis2
    write("spatial-slider-crank", {
        "mechkin": 1, "name": "spatial slider-crank R-S-U-P",
        "description": "Crank 0.10 m about z, rod 0.30 m, slider on a line along x offset by y = 0.02, z = 0.05 m. "
                       "The universal joint stops the rod spinning about its own axis: no redundancy, no idle freedom.",
        "units": {"length": "m", "angle": "deg"},
        "bodies": [{"name": "crank", "position": r(mid(A, B))},
                   {"name": "rod", "position": r(mid(B, C))},
                   {"name": "slider", "position": r(C)}],
        "joints": [
            {"name": "bearing", "type": "revolute", "body1": "ground", "body2": "crank", "origin": r(A), "axis": [0, 0, 1]},
            {"name": "pin", "type": "spherical", "body1": "crank", "body2": "rod", "origin": r(B)},
            {"name": "wrist", "type": "universal", "body1": "rod", "body2": "slider", "origin": r(C),
             "axis1": r(axis1, 15), "axis2": axis2},
            {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "origin": r(C), "axis": [1, 0, 0]}],
        "drivers": [{"name": "motor", "type": "rotation", "joint": "bearing", "function": "360*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 360},
        "outputs": [{"name": "piston", "type": "point", "body": "slider", "point": r(C)},
                    {"name": "crank_angle", "type": "joint", "joint": "bearing"}],
        "expect": {"grubler": 1, "mobility": 1, "redundant": 0, "idle": 0, "driven": "full"}})


def rocker_point(D, e1, e2, c, phi):
    return add(D, add(mul(c * math.cos(phi), e1), mul(c * math.sin(phi), e2)))


def spatial_four_bars():
    # Crank about z at the origin, rocker about x at D; coupler length from the design pose.
    # Crank 30, coupler 105, rocker 80 mm, rocker pivot at (40, 20, 40): the crank turns
    # fully (for every crank angle the coupler sphere meets the rocker circle with margin;
    # checked over 360 degrees in steps of 1 degree).
    a, b, c = 30.0, 105.0, 80.0
    A = [0.0, 0.0, 0.0]
    D = [40.0, 20.0, 40.0]
    th = math.radians(40)
    B = [a * math.cos(th), a * math.sin(th), 0.0]
    # Rocker angle with |C - B| = b: (D-B)·u terms give K1 cos(phi) + K2 sin(phi) = K0.
    d = sub(D, B)
    K1, K2, K0 = 2 * c * d[1], 2 * c * d[2], b * b - dot(d, d) - c * c
    phi = math.atan2(K2, K1) + math.acos(K0 / math.hypot(K1, K2))
    C = rocker_point(D, [0, 1, 0], [0, 0, 1], c, phi)
    assert abs(norm(sub(C, B)) - b) < 1e-9
    u = unit(sub(C, B))
    axis1 = [0.0, 0.0, 1.0]            # in the crank, parallel to its bearing
    axis2 = unit(cross(axis1, u))      # in the coupler
    common = {"units": {"length": "mm", "angle": "deg"},
              "drivers": [{"name": "motor", "type": "rotation", "joint": "input", "function": "360*t"}],
              "analysis": {"start": 0, "end": 1, "steps": 360}}
    write("spatial-four-bar-rusr", dict({
        "mechkin": 1, "name": "spatial four-bar R-U-S-R",
        "description": "Input crank (30 mm) about z, output rocker (80 mm) about x on skew axes, coupler 105 mm; the "
                       "universal joint at the crank end removes the coupler's spin, so the count (1) is the true mobility.",
        "bodies": [{"name": "crank", "position": r(mid(A, B))},
                   {"name": "coupler", "position": r(mid(B, C))},
                   {"name": "rocker", "position": r(mid(C, D))}],
        "joints": [
            {"name": "input", "type": "revolute", "body1": "ground", "body2": "crank", "origin": r(A), "axis": [0, 0, 1]},
            {"name": "U", "type": "universal", "body1": "crank", "body2": "coupler", "origin": r(B),
             "axis1": axis1, "axis2": r(axis2, 15)},
            {"name": "S", "type": "spherical", "body1": "coupler", "body2": "rocker", "origin": r(C)},
            {"name": "output", "type": "revolute", "body1": "ground", "body2": "rocker", "origin": r(D), "axis": [1, 0, 0]}],
        "outputs": [{"name": "output_angle", "type": "joint", "joint": "output"}],
        "expect": {"grubler": 1, "mobility": 1, "redundant": 0, "idle": 0, "driven": "full"}}, **common))
    write("rssr-function-generator", dict({
        "mechkin": 1, "name": "RSSR function generator",
        "description": "Spatial R-S-S-R: the coupler between two spherical joints can spin about its own axis, an idle "
                       "freedom (count 2, true mobility 2). `run` refuses it (driven: under, the spin is not driven); a distance joint "
                       "instead of the coupler body removes it (r-ss-r-distance-link.json).",
        "bodies": [{"name": "crank", "position": r(mid(A, B))},
                   {"name": "coupler", "position": r(mid(B, C))},
                   {"name": "rocker", "position": r(mid(C, D))}],
        "joints": [
            {"name": "input", "type": "revolute", "body1": "ground", "body2": "crank", "origin": r(A), "axis": [0, 0, 1]},
            {"name": "S1", "type": "spherical", "body1": "crank", "body2": "coupler", "origin": r(B)},
            {"name": "S2", "type": "spherical", "body1": "coupler", "body2": "rocker", "origin": r(C)},
            {"name": "output", "type": "revolute", "body1": "ground", "body2": "rocker", "origin": r(D), "axis": [1, 0, 0]}],
        "outputs": [{"name": "output_angle", "type": "joint", "joint": "output"}],
        "expect": {"grubler": 2, "mobility": 2, "redundant": 0, "idle": 1, "driven": "under"}}, **common))
    write("r-ss-r-distance-link", dict({
        "mechkin": 1, "name": "R-SS-R with a distance link",
        "description": "The RSSR function generator modelled lean: the coupler is a distance joint, not a body.",
        "bodies": [{"name": "crank", "position": r(mid(A, B))},
                   {"name": "rocker", "position": r(mid(C, D))}],
        "joints": [
            {"name": "input", "type": "revolute", "body1": "ground", "body2": "crank", "origin": r(A), "axis": [0, 0, 1]},
            {"name": "coupler", "type": "distance", "body1": "crank", "body2": "rocker", "point1": r(B), "point2": r(C)},
            {"name": "output", "type": "revolute", "body1": "ground", "body2": "rocker", "origin": r(D), "axis": [1, 0, 0]}],
        "outputs": [{"name": "output_angle", "type": "joint", "joint": "output"}],
        "expect": {"grubler": 1, "mobility": 1, "redundant": 0, "idle": 0, "driven": "full"}}, **common))


def hooke():
    beta = math.radians(30)
    s2 = [math.cos(beta), math.sin(beta), 0.0]
    write("hooke-joint-30deg", {
        "mechkin": 1, "name": "Hooke joint, shafts at 30 deg",
        "description": "Two shafts in bearings whose axes meet at 30 deg, coupled by a universal joint at the "
                       "intersection. The cross centre is fixed by both bearings: 3 redundant equations.",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "input_shaft", "position": [-50, 0, 0]},
                   {"name": "output_shaft", "position": r(mul(50, s2))}],
        "joints": [
            {"name": "bearing1", "type": "revolute", "body1": "ground", "body2": "input_shaft", "origin": [-100, 0, 0], "axis": [1, 0, 0]},
            {"name": "cross", "type": "universal", "body1": "input_shaft", "body2": "output_shaft", "origin": [0, 0, 0],
             "axis1": [0, 0, 1], "axis2": r([-math.sin(beta), math.cos(beta), 0.0], 15)},
            {"name": "bearing2", "type": "revolute", "body1": "ground", "body2": "output_shaft", "origin": r(mul(100, s2)), "axis": r(s2, 15)}],
        "drivers": [{"name": "motor", "type": "rotation", "joint": "bearing1", "function": "360*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 360},
        "outputs": [{"name": "output_angle", "type": "joint", "joint": "bearing2"}],
        "expect": {"grubler": -2, "mobility": 1, "redundant": 3, "idle": 0, "driven": "full"}})


def rotz(t): return [[math.cos(t), -math.sin(t), 0], [math.sin(t), math.cos(t), 0], [0, 0, 1]]
def rotx(t): return [[1, 0, 0], [0, math.cos(t), -math.sin(t)], [0, math.sin(t), math.cos(t)]]
def matmul(A, B): return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
def matvec(A, v): return [sum(A[i][k] * v[k] for k in range(3)) for i in range(3)]


def bennett():
    a, alpha, beta = 100.0, math.radians(30), math.radians(60)
    b = a * math.sin(beta) / math.sin(alpha)
    th1 = math.radians(70)
    # Bennett closure: tan(θ1/2) tan(θ2/2) = sin((β+α)/2) / sin((β−α)/2), θ3 = 2π − θ1, θ4 = 2π − θ2.
    th2 = 2 * math.atan(math.sin((beta + alpha) / 2) / math.sin((beta - alpha) / 2) / math.tan(th1 / 2))
    links = [(th1, a, alpha), (th2, b, beta), (2 * math.pi - th1, a, alpha), (2 * math.pi - th2, b, beta)]
    R, p = [[1, 0, 0], [0, 1, 0], [0, 0, 1]], [0.0, 0.0, 0.0]
    frames = []
    for th, length, tw in links:
        frames.append((R, p))
        R1 = matmul(R, rotz(th))
        p = add(p, matvec(R1, [length, 0, 0]))
        R = matmul(R1, rotx(tw))
    err = norm(p) + sum(abs(R[i][j] - (1 if i == j else 0)) for i in range(3) for j in range(3))
    if err > 1e-9:
        # Try the other sign convention of the closure relation.
        sys.exit("Bennett closure failed: %g" % err)
    joints = [(f[1], [f[0][i][2] for i in range(3)]) for f in frames]
    names = ["link1", "link2", "link3"]
    body_pos = [mid(joints[k][0], joints[k + 1][0]) for k in range(3)]
    js = []
    pairs = [("ground", "link1"), ("link1", "link2"), ("link2", "link3"), ("link3", "ground")]
    for k in range(4):
        js.append({"name": "J%d" % (k + 1), "type": "revolute", "body1": pairs[k][0], "body2": pairs[k][1],
                   "origin": r(joints[k][0]), "axis": r(joints[k][1], 15)})
    write("bennett-linkage", {
        "mechkin": 1, "name": "Bennett linkage",
        "description": "Spatial 4R loop with a1 = a3 = 100 mm, a2 = a4 = 173.2 mm, twists 30/60 deg and "
                       "a/sin(alpha) = b/sin(beta): the count says -2, yet it moves with one degree of freedom.",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": names[k], "position": r(body_pos[k])} for k in range(3)],
        "joints": js,
        "drivers": [{"name": "motor", "type": "rotation", "joint": "J1", "function": "90*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 100},
        "outputs": [{"name": "theta2", "type": "joint", "joint": "J2"}],
        "expect": {"grubler": -2, "mobility": 1, "redundant": 3, "idle": 0, "driven": "full"}})


def screw_jack():
    write("screw-jack", {
        "mechkin": 1, "name": "screw jack",
        "description": "A lead screw turning in a bearing lifts a nut that a guide keeps from turning; lead 5 mm per "
                       "revolution, 10 turns in 10 s. The nut's axis is fixed twice (guide and screw): 4 redundant equations.",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "screw", "position": [0, 0, 100]},
                   {"name": "nut", "position": [0, 0, 50]}],
        "joints": [
            {"name": "bearing", "type": "revolute", "body1": "ground", "body2": "screw", "origin": [0, 0, 0], "axis": [0, 0, 1]},
            {"name": "thread", "type": "screw", "body1": "screw", "body2": "nut", "origin": [0, 0, 50], "axis": [0, 0, 1], "pitch": 5},
            {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "nut", "origin": [0, 0, 50], "axis": [0, 0, 1]}],
        "drivers": [{"name": "crank", "type": "rotation", "joint": "bearing", "function": "360*t"}],
        "analysis": {"start": 0, "end": 10, "steps": 200},
        "outputs": [{"name": "lift", "type": "joint", "joint": "guide"},
                    {"name": "turns", "type": "joint", "joint": "bearing"}],
        "expect": {"grubler": -3, "mobility": 1, "redundant": 4, "idle": 0, "driven": "full"}})


def stewart_points():
    rb, rp, h = 0.5, 0.3, 0.6
    base, plat = [], []
    for k in range(3):
        for s in (-1, 1):
            ab = math.radians(120 * k + s * 15)
            ap = math.radians(120 * k + 60 - s * 45)
            base.append([rb * math.cos(ab), rb * math.sin(ab), 0.0])
            plat.append([rp * math.cos(ap), rp * math.sin(ap), h])
    return base, plat


def stewart():
    base, plat = stewart_points()
    drivers = []
    for k in range(6):
        L = norm(sub(plat[k], base[k]))
        amp = 0.02 * (1 if k % 2 == 0 else -1)
        drivers.append({"name": "leg%d" % (k + 1), "type": "distance", "body1": "ground", "point1": r(base[k]),
                        "body2": "platform", "point2": r(plat[k]),
                        "function": "%.15g + %g*sin(2*pi*t)" % (L, amp)})
    write("stewart-platform", {
        "mechkin": 1, "name": "Stewart-Gough platform (distance drivers)",
        "description": "6-6 Stewart-Gough platform; each leg is a driven distance between a base and a platform point, "
                       "so the platform is the only body: 6 freedoms, 6 drivers.",
        "units": {"length": "m", "angle": "deg"},
        "bodies": [{"name": "platform", "position": [0, 0, 0.6]}],
        "joints": [],
        "drivers": drivers,
        "analysis": {"start": 0, "end": 1, "steps": 100},
        "outputs": [{"name": "centre", "type": "point", "body": "platform", "point": [0, 0, 0.6]}],
        "expect": {"grubler": 6, "mobility": 6, "redundant": 0, "idle": 0, "driven": "full"},
        "view": {"up": "z"}})
    bodies = [{"name": "platform", "position": [0, 0, 0.6]}]
    joints, drv = [], []
    for k in range(6):
        B, P = base[k], plat[k]
        u = unit(sub(P, B))
        m = mid(B, P)
        cyl, pis = "cylinder%d" % (k + 1), "piston%d" % (k + 1)
        bodies += [{"name": cyl, "position": r(mid(B, m))}, {"name": pis, "position": r(mid(m, P))}]
        joints += [{"name": "base%d" % (k + 1), "type": "spherical", "body1": "ground", "body2": cyl, "origin": r(B)},
                   {"name": "slide%d" % (k + 1), "type": "prismatic", "body1": cyl, "body2": pis, "origin": r(m), "axis": r(u, 15)},
                   {"name": "top%d" % (k + 1), "type": "spherical", "body1": pis, "body2": "platform", "origin": r(P)}]
        amp = 0.02 * (1 if k % 2 == 0 else -1)
        drv.append({"name": "actuator%d" % (k + 1), "type": "translation", "joint": "slide%d" % (k + 1),
                    "function": "%g*sin(2*pi*t)" % amp})
    write("stewart-platform-sps-legs", {
        "mechkin": 1, "name": "Stewart-Gough platform, S-P-S legs as bodies",
        "description": "The same platform with each leg modelled as a cylinder and a piston: every leg can spin about "
                       "its own axis without moving anything else (6 idle freedoms, so driven: under and `run` refuses it; "
                       "stewart-platform.json models the legs as driven distances).",
        "units": {"length": "m", "angle": "deg"},
        "bodies": bodies, "joints": joints, "drivers": drv,
        "analysis": {"start": 0, "end": 1, "steps": 100},
        "outputs": [{"name": "centre", "type": "point", "body": "platform", "point": [0, 0, 0.6]}],
        "expect": {"grubler": 12, "mobility": 12, "redundant": 0, "idle": 6, "driven": "under"},
        "view": {"up": "z"}})


def five_bar():
    l1, l2, l3, l4, d = 50.0, 120.0, 120.0, 50.0, 80.0
    A, E = [0.0, 0.0, 0.0], [d, 0.0, 0.0]
    t1, t4 = math.radians(100), math.radians(80)
    B = [l1 * math.cos(t1), l1 * math.sin(t1), 0.0]
    D = [d + l4 * math.cos(t4), l4 * math.sin(t4), 0.0]
    C = circle_intersection_2d(B, l2, D, l3, upper=True)
    z = [0, 0, 1]
    write("five-bar", {
        "mechkin": 1, "name": "planar five-bar, two drivers",
        "description": "Planar 5R linkage (two degrees of freedom) driven by both ground cranks; spatial revolutes "
                       "make 3 equations redundant.",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "left_crank", "position": r(mid(A, B))}, {"name": "left_link", "position": r(mid(B, C))},
                   {"name": "right_link", "position": r(mid(C, D))}, {"name": "right_crank", "position": r(mid(D, E))}],
        "joints": [
            {"name": "A", "type": "revolute", "body1": "ground", "body2": "left_crank", "origin": r(A), "axis": z},
            {"name": "B", "type": "revolute", "body1": "left_crank", "body2": "left_link", "origin": r(B), "axis": z},
            {"name": "C", "type": "revolute", "body1": "left_link", "body2": "right_link", "origin": r(C), "axis": z},
            {"name": "D", "type": "revolute", "body1": "right_link", "body2": "right_crank", "origin": r(D), "axis": z},
            {"name": "E", "type": "revolute", "body1": "ground", "body2": "right_crank", "origin": r(E), "axis": z}],
        "drivers": [{"name": "left_motor", "type": "rotation", "joint": "A", "function": "20*sin(2*pi*t)"},
                    {"name": "right_motor", "type": "rotation", "joint": "E", "function": "-20*sin(2*pi*t)"}],
        "analysis": {"start": 0, "end": 1, "steps": 100},
        "outputs": [{"name": "tool", "type": "point", "body": "left_link", "point": r(C)}],
        "expect": {"grubler": -1, "mobility": 2, "redundant": 3, "idle": 0, "driven": "full"}})


def planar_table():
    write("planar-xy-table", {
        "mechkin": 1, "name": "block on a planar joint",
        "description": "A block slides and turns on a table (planar joint). Two distance drivers from fixed anchors "
                       "and an absolute rotation driver about the table normal position it.",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "block", "position": [100, 100, 0]}],
        "joints": [{"name": "table", "type": "planar", "body1": "ground", "body2": "block", "origin": [100, 100, 0], "normal": [0, 0, 1]}],
        "drivers": [
            {"name": "cable_x", "type": "distance", "body1": "ground", "point1": [0, 100, 0], "body2": "block",
             "point2": [100, 100, 0], "function": "100 + 20*t"},
            {"name": "cable_y", "type": "distance", "body1": "ground", "point1": [100, 0, 0], "body2": "block",
             "point2": [100, 100, 0], "function": "100 + 10*t"},
            {"name": "turn", "type": "rotation", "body": "block", "axis": [0, 0, 1], "function": "45*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 50},
        "outputs": [{"name": "corner", "type": "point", "body": "block", "point": [120, 100, 0]}],
        "expect": {"grubler": 3, "mobility": 3, "redundant": 0, "idle": 0, "driven": "full"}})


def cylindrical_spindle():
    write("cylindrical-spindle", {
        "mechkin": 1, "name": "drilling spindle on a cylindrical joint",
        "description": "A spindle turns and feeds along its axis in one cylindrical joint: a rotation and a "
                       "translation driver on the same joint.",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "spindle", "position": [0, 0, 50]}],
        "joints": [{"name": "quill", "type": "cylindrical", "body1": "ground", "body2": "spindle", "origin": [0, 0, 50], "axis": [0, 0, -1]}],
        "drivers": [{"name": "spin", "type": "rotation", "joint": "quill", "function": "3600*t"},
                    {"name": "feed", "type": "translation", "joint": "quill", "function": "5*t^2"}],
        "analysis": {"start": 0, "end": 2, "steps": 200},
        "outputs": [{"name": "tip", "type": "point", "body": "spindle", "point": [5, 0, 0]},
                    {"name": "quill", "type": "joint", "joint": "quill"}],
        "expect": {"grubler": 2, "mobility": 2, "redundant": 0, "idle": 0, "driven": "full"}})


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    four_bar(); offset_slider_crank(); spatial_slider_crank(); spatial_four_bars(); hooke(); bennett()
    screw_jack(); stewart(); five_bar(); planar_table(); cylindrical_spindle()
    print("wrote", len([f for f in os.listdir(OUT) if f.endswith(".json")]), "files to", os.path.normpath(OUT))


def bricard():
    # Trihedral Bricard 6R on the skew hexagon of a unit cube (five 1 m rods and
    # ground, as in the IFToMM benchmark A04): each joint axis is perpendicular
    # to both links it connects. Count 0, yet it moves with one degree of freedom.
    P = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 1], [0, 1, 1], [0, 0, 1]]
    axes = [[0, 1, 0], [0, 0, 1], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 0, 0]]
    names = ["rod1", "rod2", "rod3", "rod4", "rod5"]
    bodies = [{"name": names[k], "position": mid(P[k], P[k + 1])} for k in range(5)]
    links = ["ground"] + names + ["ground"]
    joints = [{"name": "R%d" % (k + 1), "type": "revolute", "body1": links[k], "body2": links[k + 1],
               "origin": P[k], "axis": axes[k]} for k in range(6)]
    write("bricard-mechanism", {
        "mechkin": 1, "name": "Bricard mechanism (trihedral, cube hexagon)",
        "description": "Five 1 m rods and ground on the skew hexagon of a unit cube, each revolute axis perpendicular "
                       "to its two links (the IFToMM A04 geometry): Grubler count 0, true mobility 1, one redundant equation.",
        "units": {"length": "m", "angle": "deg"},
        "bodies": bodies, "joints": joints,
        "drivers": [{"name": "motor", "type": "rotation", "joint": "R1", "function": "60*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 100},
        "outputs": [{"name": "R4_angle", "type": "joint", "joint": "R4"}],
        "expect": {"grubler": 0, "mobility": 1, "redundant": 1, "idle": 0, "driven": "full"}})


# ---- couplers between joint coordinates (issue 25) --------------------------------

def revolute(name, b1, b2, origin, axis=(0, 0, 1)):
    return {"name": name, "type": "revolute", "body1": b1, "body2": b2, "origin": list(origin), "axis": list(axis)}


def planetary():
    # Sun 24, planets 18, ring 60 teeth (z_r = z_s + 2 z_p), module 1 mm: the planets'
    # centres on a 21 mm circle. Each mesh is written relative to the carrier, so the
    # second and third planets' meshes repeat the Willis relation: 2 redundant couplers.
    zs, zp, zr, a = 24, 18, 60, 21.0
    bodies = [{"name": "sun", "position": [0.0, 0.0, 0.0]}, {"name": "ring", "position": [0.0, 0.0, 0.0]},
              {"name": "carrier", "position": [0.0, 0.0, 0.0]}]
    joints = [revolute("sun_bearing", "ground", "sun", (0, 0, 0)), revolute("ring_bearing", "ground", "ring", (0, 0, 0)),
              revolute("carrier_bearing", "ground", "carrier", (0, 0, 0))]
    couplers = []
    for k in range(3):
        phi = 2 * math.pi * k / 3
        c = r([a * math.cos(phi), a * math.sin(phi), 0.0])
        name = "planet%d" % (k + 1)
        bodies.append({"name": name, "position": c})
        joints.append(revolute(name + "_pin", "carrier", name, c))
        couplers.append({"name": "sun_mesh%d" % (k + 1), "type": "coupling",
                         "joints": [name + "_pin", "sun_bearing", "carrier_bearing"], "coefficients": [zp, zs, -zs]})
        couplers.append({"name": "ring_mesh%d" % (k + 1), "type": "coupling",
                         "joints": [name + "_pin", "ring_bearing", "carrier_bearing"], "coefficients": [zp, -zr, zr]})
    write("planetary-gear-train", {
        "mechkin": 1, "name": "planetary gear train",
        "description": "Sun (24 teeth), three planets (18) on a carrier, ring (60). The sun turns 1 rev/s and the ring "
                       "-0.25 rev/s; the carrier follows the Willis equation w_c = (z_s w_s + z_r w_r)/(z_s + z_r). "
                       "Each mesh is a coupling relative to the carrier (z_p th_p + z_s th_s - z_s th_c = 0, "
                       "z_p th_p - z_r th_r + z_r th_c = 0); the second and third planets repeat the relation.",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": bodies, "joints": joints, "couplers": couplers,
        "drivers": [{"name": "sun_motor", "type": "rotation", "joint": "sun_bearing", "function": "360*t"},
                    {"name": "ring_motor", "type": "rotation", "joint": "ring_bearing", "function": "-90*t"}],
        "analysis": {"start": 0, "end": 4, "steps": 200},
        "outputs": [{"name": "carrier_angle", "type": "joint", "joint": "carrier_bearing"},
                    {"name": "planet_spin", "type": "joint", "joint": "planet1_pin"}],
        "expect": {"grubler": 0, "mobility": 2, "redundant": 2, "driven": "full"}})


def rack_pinion_steering():
    # Pinion (pitch radius 8 mm) on the steering column turns about z; the rack slides
    # along x; tie rods (distance links) from the rack ends to steering arms on the two
    # knuckles, which turn about z on their kingpins.
    # Tie rods along the rack (100 mm), steering arms (110 mm) across them: far from a toggle.
    rho, half, king_x, king_y = 8.0, 300.0, 420.0, -100.0
    arm = [-20.0, 108.0]  # right steering arm from its kingpin (mirrored on the left)
    bodies = [{"name": "column", "position": [0.0, 0.0, 0.0]}, {"name": "rack", "position": [0.0, rho, 0.0]}]
    joints = [revolute("column_bearing", "ground", "column", (0, 0, 0)),
              {"name": "rack_guide", "type": "prismatic", "body1": "ground", "body2": "rack",
               "origin": [0.0, rho, 0.0], "axis": [1, 0, 0]}]
    for side, sx in (("right", 1), ("left", -1)):
        pivot = [sx * king_x, king_y, 0.0]
        arm_end = [pivot[0] + sx * arm[0], pivot[1] + arm[1], 0.0]
        bodies.append({"name": side + "_knuckle", "position": pivot})
        joints.append(revolute(side + "_kingpin", "ground", side + "_knuckle", pivot))
        joints.append({"name": side + "_tie_rod", "type": "distance", "body1": "rack", "body2": side + "_knuckle",
                       "point1": [sx * half, rho, 0.0], "point2": arm_end})
    write("rack-and-pinion-steering", {
        "mechkin": 1, "name": "rack-and-pinion steering",
        "description": "A steering column turns a pinion of pitch radius 8 mm on a rack (rack travel = 8 mm x steering "
                       "angle in radians); tie rods from the rack ends turn the two knuckles on their kingpins. The "
                       "wheel turns +-90 deg; the rack carries a 500 N road force, the column's torque is 500 N x 8 mm.",
        "units": {"length": "mm", "angle": "deg", "mass": "kg", "force": "N"},
        "bodies": bodies, "joints": joints,
        "couplers": [{"name": "steering_gear", "type": "rack_pinion", "joint1": "column_bearing", "joint2": "rack_guide",
                      "pitch_radius": rho}],
        "drivers": [{"name": "steering_wheel", "type": "rotation", "joint": "column_bearing", "function": "90*sin(pi*t)"}],
        "loads": [{"name": "road", "type": "force", "body": "rack", "point": [0.0, rho, 0.0], "components": [500, 0, 0]}],
        "analysis": {"start": 0, "end": 2, "steps": 200},
        "outputs": [{"name": "rack_travel", "type": "joint", "joint": "rack_guide"},
                    {"name": "right_wheel", "type": "joint", "joint": "right_kingpin"},
                    {"name": "left_wheel", "type": "joint", "joint": "left_kingpin"}],
        "expect": {"grubler": 1, "mobility": 1, "redundant": 0, "driven": "full"}})


def differential():
    # Open differential: case (carrier) and the two axle shafts on one axis (x):
    # theta_left + theta_right = 2 theta_case.
    x = (1, 0, 0)
    write("open-differential", {
        "mechkin": 1, "name": "open differential",
        "description": "The case turns 1 rev/s; the left axle is held 10 deg behind it and back (a corner); the right "
                       "axle follows th_left + th_right = 2 th_case (a coupling of three joint coordinates).",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "case", "position": [0.0, 0.0, 0.0]}, {"name": "left_axle", "position": [-100.0, 0.0, 0.0]},
                   {"name": "right_axle", "position": [100.0, 0.0, 0.0]}],
        "joints": [revolute("case_bearing", "ground", "case", (0, 0, 0), x),
                   revolute("left_bearing", "ground", "left_axle", (-100, 0, 0), x),
                   revolute("right_bearing", "ground", "right_axle", (100, 0, 0), x)],
        "couplers": [{"name": "spider_gears", "type": "coupling", "joints": ["left_bearing", "right_bearing", "case_bearing"],
                      "coefficients": [1, 1, -2]}],
        "drivers": [{"name": "drive_shaft", "type": "rotation", "joint": "case_bearing", "function": "360*t"},
                    {"name": "left_wheel", "type": "rotation", "joint": "left_bearing", "function": "360*t - 10*sin(pi*t)"}],
        "analysis": {"start": 0, "end": 2, "steps": 100},
        "outputs": [{"name": "right_angle", "type": "joint", "joint": "right_bearing"}],
        "expect": {"grubler": 2, "mobility": 2, "redundant": 0, "driven": "full"}})


def geared_crank():
    # A motor pinion (16 teeth) drives the crank gear (64 teeth): theta_crank = -theta_motor/4;
    # the crank (50 mm) and a 150 mm connecting rod (distance link) drive a slider on x.
    a, b, th = 50.0, 150.0, math.radians(30)
    B = [a * math.cos(th), a * math.sin(th), 0.0]
    W = [B[0] + math.sqrt(b * b - B[1] * B[1]), 0.0, 0.0]
    write("geared-slider-crank", {
        "mechkin": 1, "name": "slider-crank driven through a gear pair",
        "description": "A motor pinion (16 teeth) meshes with the crank gear (64 teeth), ratio -1/4; crank 50 mm, "
                       "connecting rod 150 mm (a distance link), slider on the x axis. The motor turns 4 rev/s. Module 2 mm "
                       "(pitch radii 16 and 64 mm, 20 degree pressure angle): the bearings' reactions carry the tooth force.",
        "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "motor", "position": [-80.0, 0.0, 0.0]}, {"name": "crank", "position": [0.0, 0.0, 0.0]},
                   {"name": "slider", "position": r(W)}],
        "joints": [revolute("motor_bearing", "ground", "motor", (-80, 0, 0)),
                   revolute("crank_bearing", "ground", "crank", (0, 0, 0)),
                   {"name": "rod", "type": "distance", "body1": "crank", "body2": "slider", "point1": r(B), "point2": r(W)},
                   {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "origin": r(W),
                    "axis": [1, 0, 0]}],
        # Module 2 mm: pitch radii 16 and 64 mm on centres 80 mm apart; the bearings carry the tooth force.
        "couplers": [{"name": "mesh", "type": "gear", "joint1": "motor_bearing", "joint2": "crank_bearing", "ratio": -0.25,
                      "pitch_radius": 16.0, "pressure_angle": 20.0}],
        "drivers": [{"name": "motor", "type": "rotation", "joint": "motor_bearing", "function": "1440*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 360},
        "outputs": [{"name": "crank_angle", "type": "joint", "joint": "crank_bearing"},
                    {"name": "stroke", "type": "joint", "joint": "guide"}],
        "expect": {"grubler": 1, "mobility": 1, "redundant": 0, "driven": "full"}})


if __name__ == "__main__":
    bricard()
    planetary(); rack_pinion_steering(); differential(); geared_crank()
