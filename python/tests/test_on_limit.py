"""Model.run(on_limit=...) as `mechkin run --on-limit` (issue 25, joint limits): a
crank-rocker whose rocker D has limits [-5, 40] deg inside its swing (about
[-10, 63.7] deg from the design pose) stops at the limit with "stop" and runs to the
end with "report", the joint named; the rows agree with the closed-form four-bar
and with the CLI's table. Mirrors tests/analysis/joint_limits_test.cpp."""
import csv
import json
import math
import subprocess

import numpy as np
import pytest

import mechkin

A, B, C, D, THETA0, STEPS = 40.0, 120.0, 80.0, 100.0, math.radians(60), 72
LO, HI = -5.0, 40.0


def _coupler_point(th):
    """B and C of the four-bar at crank angle th (the branch the C++ helper draws)."""
    bx, by = A * math.cos(th), A * math.sin(th)
    dx, dy = D - bx, -by
    dist = math.hypot(dx, dy)
    al = (B * B - C * C + dist * dist) / (2 * dist)
    h = math.sqrt(B * B - al * al)
    return (bx, by), (bx + (al * dx - h * dy) / dist, by + (al * dy + h * dx) / dist)


def _rocker_coordinate(crank):
    """Joint D's coordinate (deg, 0 at the design pose) at crank driver value `crank` (rad)."""
    angle = lambda th: math.atan2(_coupler_point(th)[1][1], _coupler_point(th)[1][0] - D)
    return math.degrees(math.remainder(angle(THETA0 + crank) - angle(THETA0), 2 * math.pi))


def _limited_crank_rocker():
    (bx, by), (cx, cy) = _coupler_point(THETA0)
    z = [0, 0, 1]
    rev = lambda name, b1, b2, o: {"name": name, "type": "revolute", "body1": b1, "body2": b2, "origin": o, "axis": z}
    return {
        "mechkin": 1, "units": {"length": "mm", "angle": "deg"},
        "bodies": [{"name": "crank", "position": [bx / 2, by / 2, 0]},
                   {"name": "coupler", "position": [(bx + cx) / 2, (by + cy) / 2, 0]},
                   {"name": "rocker", "position": [(cx + D) / 2, cy / 2, 0]}],
        "joints": [rev("A", "ground", "crank", [0, 0, 0]), rev("B", "crank", "coupler", [bx, by, 0]),
                   rev("C", "coupler", "rocker", [cx, cy, 0]),
                   dict(rev("D", "ground", "rocker", [D, 0, 0]), limits=[LO, HI])],
        "drivers": [{"name": "motor", "type": "rotation", "joint": "A", "function": "360*t"}],
        "analysis": {"start": 0, "end": 1, "steps": STEPS},
        "outputs": [{"name": "rocker_angle", "type": "joint", "joint": "D"}],
    }


def _closed_form_error(motion):
    rocker = motion["rocker_angle"]
    return max(abs(rocker[k] - _rocker_coordinate(2 * math.pi * t)) for k, t in enumerate(motion.t))


def test_stop_ends_at_the_rocker_limit():
    motion = mechkin.loads(_limited_crank_rocker()).run(order=1, on_limit="stop")
    assert not motion.complete
    assert motion.stop.kind == "joint_limit"
    assert "joint `D` reaches its" in motion.stop.message, motion.stop.message
    rocker = motion["rocker_angle"]
    assert 1 < len(motion) < STEPS + 1
    assert np.all(rocker >= LO - 1e-12) and np.all(rocker <= HI + 1e-12)
    # The crossing lies between the last row written and the next one (closed form).
    t_next = motion.t[-1] + 1.0 / STEPS
    assert not (LO <= _rocker_coordinate(2 * math.pi * t_next) <= HI)
    err = _closed_form_error(motion)
    print("[measured] stop: %d rows, rows vs closed-form rocker %.2e deg" % (len(motion), err))
    assert err < 1e-8
    # "stop" is the default, as in the CLI.
    assert len(mechkin.loads(_limited_crank_rocker()).run(order=1)) == len(motion)


def test_report_runs_to_the_end_and_notes_the_joint(cli, tmp_path):
    doc = _limited_crank_rocker()
    motion = mechkin.loads(doc).run(order=1, on_limit="report")
    assert motion.complete and motion.stop.kind == "none"
    assert len(motion) == STEPS + 1
    notes = [n for n in motion.notes if "joint `D`" in n]
    assert notes, motion.notes
    rocker = motion["rocker_angle"]
    assert rocker.max() > HI + 10 and rocker.min() < LO - 2  # it went past both limits
    err = _closed_form_error(motion)
    print("[measured] report: %d rows, %d notes on D, rows vs closed-form rocker %.2e deg" % (len(motion), len(notes), err))
    assert err < 1e-8
    # The CLI with --on-limit report writes the same table (and the default stops alike).
    path = tmp_path / "limited.json"
    path.write_text(json.dumps(doc))
    out = tmp_path / "t.csv"
    run = subprocess.run([cli, "run", str(path), "--order", "1", "--on-limit", "report", "-o", str(out)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "joint `D`" in run.stderr
    with open(out) as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")][1:]
    assert len(rows) == len(motion)
    col = motion.names.index("rocker_angle")
    assert max(abs(float(r[col]) - rocker[k]) for k, r in enumerate(rows)) < 1e-9


def test_on_limit_refuses_other_words():
    model = mechkin.loads(_limited_crank_rocker())
    with pytest.raises(ValueError, match="on_limit must be one of"):
        model.run(on_limit="ignore")
    request = mechkin.RunRequest(on_limit="report")
    assert request.on_limit == "report" and "on_limit='report'" in repr(request)
    request.on_limit = "stop"
    assert request.on_limit == "stop"
