"""`Model.range()` and `Model.tolerance()`: the CLI's reports from Python, checked
against the CLI itself and against independent references (closed forms, whole runs)."""
import json
import math
import os
import subprocess

import mechkin


def _cli_json(cli, *args):
    out = subprocess.run([cli, *args, "--format", "json"], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def test_range_finds_the_dead_centres_and_matches_the_cli(root, cli):
    path = os.path.join(root, "tests", "data", "piston-driven-slider-crank.json")
    report = mechkin.load(path).range()
    assert report.ok
    assert report.to_dict() == _cli_json(cli, "range", path)
    piston = report["piston"]
    # Crank 20 mm, rod 50 mm, no offset: the slider's dead centres at 30 and 70 mm from
    # the bearing; the driver reads 0 at the design pose, the slider at 56.904… mm.
    design_x = 10 + math.sqrt(50 ** 2 - (20 * math.sin(math.pi / 3)) ** 2)
    assert piston["lower"]["kind"] == piston["upper"]["kind"] == "limit"
    assert abs(piston["lower"]["value"] - (30 - design_x)) < 1e-9 * 40
    assert abs(piston["upper"]["value"] - (70 - design_x)) < 1e-9 * 40
    assert "driver `piston`" in str(report)


def test_range_of_a_driver_that_is_not_there_says_which_are():
    model = mechkin.loads({"mechkin": 1, "bodies": [{"name": "crank", "position": [1, 0, 0]}],
                           "joints": [{"name": "A", "type": "revolute", "body1": "ground", "body2": "crank",
                                       "origin": [0, 0, 0], "axis": [0, 0, 1]}],
                           "drivers": [{"name": "motor", "type": "rotation", "joint": "A", "function": "360*t"}]})
    report = model.range(driver="motr")
    assert not report.ok
    assert "motr" in report.message and "motor" in report.message
    assert model.range(driver="motor")["motor"]["upper"]["kind"] == "full turn"


def test_tolerance_stack_up_matches_whole_runs_and_the_cli(root, cli):
    path = os.path.join(root, "mechanisms", "parametric-slider-crank.json")
    model = mechkin.load(path)
    report = model.tolerance(monte_carlo=200, seed=7, threads=2)
    assert report.ok
    cli_report = _cli_json(cli, "tolerance", path, "--monte-carlo", "200", "--seed", "7", "--threads", "2")
    assert report.to_dict() == cli_report
    # The worst case of piston.x at its worst row from central differences of whole runs.
    column = report.column("piston.x")
    row = report.t.index(column["t_max_worst_case"])
    worst = 0.0
    for name, tol in report.tolerances.items():
        h = 1e-4 * model.parameters[name]
        up = model.with_parameters(**{name: model.parameters[name] + h}).run(order=0)["piston.x"][row]
        down = model.with_parameters(**{name: model.parameters[name] - h}).run(order=0)["piston.x"][row]
        worst += abs(up - down) / (2 * h) * tol
    assert abs(column["max_worst_case"] - worst) < 1e-6 * worst
    frame = report.to_pandas()
    assert list(frame["t"]) == report.t
    assert frame["piston.x worst_case"].max() == column["max_worst_case"]
    assert "piston.x" in str(report)
