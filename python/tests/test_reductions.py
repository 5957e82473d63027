"""Reductions through the Python package: Motion.reductions carries the file's
reductions (value, where, gradient), the same numbers after pickling."""
import json
import math
import os
import pickle

import mechkin

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def transmission_with_reductions():
    with open(os.path.join(ROOT, "mechanisms", "four-bar-transmission-angle.json")) as f:
        doc = json.load(f)
    doc["analysis"]["steps"] = 50
    doc["outputs"] = [o for o in doc["outputs"] if o["type"] != "reduction"]
    doc["outputs"] += [
        {"name": "mu_min", "type": "reduction", "of": "transmission", "reduce": "min"},
        {"name": "BD_rms", "type": "reduction", "of": "BD", "reduce": "rms"},
    ]
    return doc


def test_minimum_transmission_angle_and_where():
    m = mechkin.loads(transmission_with_reductions()).run(bodies=[], sensitivity=["b"])
    r = m.reductions["mu_min"]
    # cos mu_min = (b^2 + c^2 - (d - a)^2)/(2bc) at crank angle 0 (t = 5/6 s)
    assert math.isclose(r["value"], math.degrees(math.acos(17200 / 19200)), abs_tol=1e-7)
    assert math.isclose(r["t"], 5 / 6, abs_tol=1e-6)
    assert r["located"] and r["problem"] is None
    assert set(r["gradient"]) == {"b"}
    # rms of BD over a whole turn: sqrt(a^2 + d^2)
    assert math.isclose(m.reductions["BD_rms"]["value"], math.sqrt(40 ** 2 + 100 ** 2), rel_tol=1e-12)
    again = pickle.loads(pickle.dumps(m))
    assert again.reductions["mu_min"]["value"] == r["value"]
