"""Expression outputs through the Python package: the columns come back like any
other, with their descriptors, and equal the formula applied to the other columns."""
import json
import math
import os

import numpy as np

import mechkin

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def four_bar_with_expressions():
    with open(os.path.join(ROOT, "mechanisms", "parametric-four-bar.json")) as f:
        doc = json.load(f)
    doc["outputs"] += [
        {"name": "BD", "type": "distance", "body1": "crank", "point1": ["xb", "yb", 0], "body2": "ground",
         "point2": ["d", 0, 0]},
        {"name": "transmission", "type": "expression", "value": "acos((b^2 + c^2 - BD^2)/(2*b*c))*180/pi"},
    ]
    return doc


def test_transmission_column_equals_the_cosine_rule_of_the_distance_column():
    m = mechkin.loads(four_bar_with_expressions()).run(order=1, bodies=[])
    b, c = 120.0, 80.0
    want = np.degrees(np.arccos((b * b + c * c - m["BD"] ** 2) / (2 * b * c)))
    assert np.max(np.abs(m["transmission"] - want)) < 1e-10
    # its rate by the chain rule over BD and BD_t
    x = (b * b + c * c - m["BD"] ** 2) / (2 * b * c)
    rate = np.degrees(-1 / np.sqrt(1 - x * x) * (-2 * m["BD"] * m["BD_t"] / (2 * b * c)))
    assert np.max(np.abs(m["transmission_t"] - rate)) < 1e-8 * np.max(np.abs(rate))
    # the crank angle of the first row is 60 deg: BD^2 = a^2 + d^2 - 2ad cos 60
    assert math.isclose(m["BD"][0], math.sqrt(40 ** 2 + 100 ** 2 - 2 * 40 * 100 * 0.5), rel_tol=1e-12)


def test_expression_descriptor_says_what_it_is():
    m = mechkin.loads(four_bar_with_expressions()).run(order=1, bodies=[])
    cols = {c["name"]: c for c in m.columns}
    assert cols["transmission"]["quantity"] == "expression"
    assert cols["transmission"]["subject"] == "transmission"
    assert cols["transmission_t"]["order"] == 1
