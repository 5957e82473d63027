#!/usr/bin/env python3
"""Writes tests/invalid/*.json: one broken mechanism file per case, derived from
a valid base, and tests/invalid/expected.tsv: file <TAB> JSON pointer the loader
must name. Rerun: python3 tools/make_invalid_corpus.py"""
import copy
import json
import os

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "invalid")
BASE = {
    "mechkin": 1, "name": "base", "units": {"length": "mm", "angle": "deg"},
    "bodies": [{"name": "crank", "position": [20, 0, 0]}, {"name": "rod", "position": [70, 0, 0]},
               {"name": "slider", "position": [140, 0, 0]}],
    "joints": [
        {"name": "bearing", "type": "revolute", "body1": "ground", "body2": "crank", "origin": [0, 0, 0], "axis": [0, 0, 1]},
        {"name": "pin", "type": "spherical", "body1": "crank", "body2": "rod", "origin": [40, 0, 0]},
        {"name": "wrist", "type": "universal", "body1": "rod", "body2": "slider", "origin": [140, 0, 0],
         "axis1": [0, 0, 1], "axis2": [0, 1, 0]},
        {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "origin": [140, 0, 0], "axis": [1, 0, 0]}],
    "drivers": [{"name": "motor", "type": "rotation", "joint": "bearing", "function": "360*t"}],
    "analysis": {"start": 0, "end": 1, "steps": 10},
    "outputs": [{"name": "piston", "type": "point", "body": "slider", "point": [140, 0, 0]}],
}

cases = []


def case(name, pointer, mutate=None, text=None):
    cases.append((name, pointer, mutate, text))


def setp(path, value):
    def f(d):
        cur = d
        for k in path[:-1]:
            cur = cur[k]
        cur[path[-1]] = value
    return f


def delp(path):
    def f(d):
        cur = d
        for k in path[:-1]:
            cur = cur[k]
        del cur[path[-1]]
    return f


case("unknown-top-key", "/bodys", lambda d: d.__setitem__("bodys", []))
case("unknown-joint-key", "/joints/0/axsi", lambda d: d["joints"][0].__setitem__("axsi", [0, 0, 1]))
case("missing-version", "/mechkin", delp(["mechkin"]))
case("wrong-version", "/mechkin", setp(["mechkin"], 2))
case("missing-bodies", "/bodies", delp(["bodies"]))
case("body-missing-position", "/bodies/1/position", delp(["bodies", 1, "position"]))
case("position-wrong-type", "/bodies/0/position", setp(["bodies", 0, "position"], "0,0,0"))
case("position-two-components", "/bodies/0/position", setp(["bodies", 0, "position"], [1, 2]))
case("position-nan-string", "/bodies/0/position/1", setp(["bodies", 0, "position"], [0, "NaN", 0]))
case("position-huge", "", None,
     json.dumps(BASE).replace('"position": [20, 0, 0]', '"position": [1e999, 0, 0]'))
case("duplicate-body", "/bodies/1/name", setp(["bodies", 1, "name"], "crank"))
case("ground-as-body", "/bodies/2/name", setp(["bodies", 2, "name"], "ground"))
case("bad-body-name", "/bodies/0/name", setp(["bodies", 0, "name"], "crank arm"))
case("unknown-body-ref", "/joints/1/body2", setp(["joints", 1, "body2"], "rodd"))
case("joint-to-itself", "/joints/1/body2", setp(["joints", 1, "body2"], "crank"))
case("duplicate-joint", "/joints/1/name", setp(["joints", 1, "name"], "bearing"))
case("unknown-joint-type", "/joints/0/type", setp(["joints", 0, "type"], "revolut"))
case("zero-axis", "/joints/0/axis", setp(["joints", 0, "axis"], [0, 0, 0]))
case("axis-on-spherical", "/joints/1/axis", lambda d: d["joints"][1].__setitem__("axis", [0, 0, 1]))
case("universal-not-perpendicular", "/joints/2/axis2", setp(["joints", 2, "axis2"], [0, 1, 1]))
case("screw-missing-pitch", "/joints/0/pitch", setp(["joints", 0, "type"], "screw"))
case("distance-zero-length", "/joints/1/length",
     setp(["joints", 1], {"name": "pin", "type": "distance", "body1": "crank", "body2": "rod",
                          "point1": [40, 0, 0], "point2": [50, 0, 0], "length": 0}))
case("driver-on-spherical", "/drivers/0/joint", setp(["drivers", 0, "joint"], "pin"))
case("translation-on-revolute", "/drivers/0/joint", setp(["drivers", 0, "type"], "translation"))
case("driver-unknown-joint", "/drivers/0/joint", setp(["drivers", 0, "joint"], "bearin"))
case("driver-bad-expression", "/drivers/0/function", setp(["drivers", 0, "function"], "360*t +* 2"))
case("driver-unknown-function", "/drivers/0/function", setp(["drivers", 0, "function"], "sinh(t)"))
case("driver-table-unsorted", "/drivers/0/function/table/2/0",
     setp(["drivers", 0, "function"], {"table": [[0, 0], [0.5, 10], [0.4, 20]]}))
case("driver-number-function", "/drivers/0/function", setp(["drivers", 0, "function"], 360))
case("end-before-start", "/analysis/end", setp(["analysis", "end"], 0))
case("zero-steps", "/analysis/steps", setp(["analysis", "steps"], 0))
case("view-unknown-up-axis", "/view/up", setp(["view"], {"up": "w"}))
case("view-plot-not-a-list", "/view/plots/0", setp(["view"], {"plots": ["piston.x"]}))
case("fractional-steps", "/analysis/steps", setp(["analysis", "steps"], 2.5))
case("unknown-length-unit", "/units/length", setp(["units", "length"], "mmm"))
case("unknown-angle-unit", "/units/angle", setp(["units", "angle"], "degree"))
case("orientation-two-forms", "/bodies/0/orientation",
     setp(["bodies", 0, "orientation"], {"axis": [0, 0, 1], "angle": 10, "euler_parameters": [1, 0, 0, 0]}))
case("orientation-not-rotation", "/bodies/0/orientation/matrix",
     setp(["bodies", 0, "orientation"], {"matrix": [[1, 0, 0], [0, 1, 0], [0, 0, -1]]}))
case("orientation-zero-quaternion", "/bodies/0/orientation/euler_parameters",
     setp(["bodies", 0, "orientation"], {"euler_parameters": [0, 0, 0, 0]}))
case("output-unknown-type", "/outputs/0/type", setp(["outputs", 0, "type"], "velocity"))
case("output-sequence-on-revolute", "/outputs/0/sequence",
     setp(["outputs", 0], {"name": "p", "type": "joint", "joint": "bearing", "sequence": "ZYX"}))
case("expect-bad-driven", "/expect/driven", lambda d: d.__setitem__("expect", {"driven": "fully"}))
case("json-syntax-error", "", None, '{"mechkin": 1, "bodies": [ }')
case("empty-file", "", None, "")
case("binary-file", "", None, "\x00\x01\x02\xff\xfe garbage")
case("deeply-nested", "", None, "[" * 100000 + "]" * 100000)
case("top-level-array", "", None, "[1, 2, 3]")
case("bodies-not-array", "/bodies", setp(["bodies"], {"crank": {}}))
# Clearance shapes and outputs (issue 28).
case("shape-negative-radius", "/bodies/0/shape/radius",
     setp(["bodies", 0, "shape"], {"type": "sphere", "radius": -5, "center": [20, 0, 0]}))
case("convex-three-points", "/bodies/1/shapes/1/points",
     setp(["bodies", 1, "shapes"], [{"type": "capsule", "radius": 3, "length": 80, "axis": [1, 0, 0]},
                                    {"type": "convex", "points": [[0, 0, 0], [10, 0, 0], [0, 10, 0]]}]))
case("shape-unknown-kind", "/bodies/2/shape/type", setp(["bodies", 2, "shape"], {"type": "cone", "radius": 5, "length": 10}))


def clearance_to_unknown_body(d):
    d["bodies"][0]["shape"] = {"type": "box", "size": [40, 5, 5]}
    d["bodies"][2]["shape"] = {"type": "box", "size": [20, 10, 10]}
    d["outputs"].append({"type": "clearance", "body1": "crank", "body2": "slidr"})


case("clearance-unknown-body", "/outputs/1/body2", clearance_to_unknown_body)

if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    for f in os.listdir(OUT):
        if f.endswith(".json") or f == "expected.tsv":
            os.remove(os.path.join(OUT, f))
    with open(os.path.join(OUT, "expected.tsv"), "w") as tsv:
        for name, pointer, mutate, text in cases:
            if text is None:
                d = copy.deepcopy(BASE)
                mutate(d)
                text = json.dumps(d, indent=1) + "\n"
            with open(os.path.join(OUT, name + ".json"), "w", encoding="latin-1", newline="") as f:
                f.write(text)
            tsv.write("%s.json\t%s\n" % (name, pointer))
    print("wrote", len(cases), "invalid files")
