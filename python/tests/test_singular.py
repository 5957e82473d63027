"""Issue 23 item 9 from Python: the slider-crank with crank = rod (20 mm, no offset,
100 steps; its change point at t = 0.25 s falls on a row) stops there at every
order, in `Model.run(order=k)` and in `mechkin.sweep(order=k)`: never a silent run
on to the folded branch, where the piston would read 0 instead of 40·cos 2πt."""
import math
import os

import numpy as np
import pytest

import mechkin

HERE = os.path.dirname(os.path.abspath(__file__))
CRANK_ROD = os.path.join(HERE, "..", "..", "tests", "data", "parametric-crank-equals-rod.json")


@pytest.mark.parametrize("order", [0, 1, 2, 3, 4])
def test_run_stops_at_the_change_point_at_every_order(order):
    motion = mechkin.load(CRANK_ROD).run(order=order)
    assert not motion.complete
    assert motion.stop.kind == "singular_position", motion.stop
    assert abs(motion.stop.singular["t"] - 0.25) < 1e-11
    assert abs(motion.stop.singular["driver_values"][0] - math.pi / 2) < 1e-9
    t = motion["t"]
    assert len(t) == 25 and t[-1] == pytest.approx(0.24, abs=1e-12)
    np.testing.assert_allclose(motion["piston.x"], 40 * np.cos(2 * np.pi * t), rtol=0, atol=1e-9)


@pytest.mark.parametrize("order", [0, 1, 2, 3, 4])
def test_sweep_calls_it_singular_at_every_order(order):
    out = mechkin.sweep(mechkin.load(CRANK_ROD), [{"L": 20}, {"L": 21}], order=order, threads=1)
    assert list(out["status"]) == ["singular", "singular"]
    assert list(out["rows"]) == [25, 25]
    for message in out["message"]:
        assert message.startswith("singular position at t = 0.25 s")
