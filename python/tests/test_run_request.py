"""Python as a binding of the same run request (issue 32): run(tol=T) accepts and
refuses exactly what `mechkin run --tol T` and `mechkin view --tol T` do, with the
same message; order 1 with inertia gives the forces of an order-2 run in Python and
the CLI alike; sweeps are DataFrames; help() on the public classes lists the fields."""
import json
import math
import os
import pydoc
import subprocess

import numpy as np
import pytest

import mechkin

TOLS = ["1e-16", "1e-15", "1e-3", "5e-3", "0", "-1", "nan"]
FORCE_QUANTITIES = {"driver_effort", "driver_power", "joint_force", "joint_moment", "joint_force_local",
                    "joint_moment_local", "kinetic_energy", "potential_energy", "energy_balance"}


def _four_bar_with_inertia(root):
    with open(os.path.join(root, "mechanisms", "planar-four-bar.json")) as f:
        doc = json.load(f)
    doc["units"]["mass"] = "kg"
    doc["gravity"] = [0, -9810, 0]
    for b in doc["bodies"]:
        b["inertia"] = {"mass": 1.5, "center": b["position"], "moments": [[200, 0, 0], [0, 300, 0], [0, 0, 400]]}
    doc["analysis"]["steps"] = 24
    return doc


def test_run_tol_accepts_and_refuses_as_run_and_view_do(cli, root, tmp_path):
    path = os.path.join(root, "mechanisms", "planar-four-bar.json")
    model = mechkin.load(path)
    for text in TOLS:
        run = subprocess.run([cli, "run", path, "--tol", text, "-o", str(tmp_path / "t.csv")],
                             capture_output=True, text=True)
        view = subprocess.run([cli, "view", path, "--tol", text, "--max-frames", "10", "-o", str(tmp_path / "t.html")],
                              capture_output=True, text=True)
        try:
            model.run(tol=float(text), bodies=[])
            accepted, message = True, ""
        except ValueError as e:
            accepted, message = False, str(e)
        assert (run.returncode == 0) == accepted and (view.returncode == 0) == accepted, (text, run.stderr)
        assert mechkin.RunRequest(tol=float(text)).is_valid() == (accepted, message)
        if not accepted:
            assert run.returncode == view.returncode == 2
            assert run.stderr.splitlines()[0] == "--tol: " + message
            assert view.stderr.splitlines()[0] == "--tol: " + message
            assert "[1e-15, 1e-3]" in message
            # range, tolerance and sweep take the same range, with the same words
            with pytest.raises(ValueError) as e:
                model.range(tol=float(text))
            assert str(e.value) == message
            with pytest.raises(ValueError) as e:
                mechkin.sweep(model, [{}], tol=float(text))
            assert str(e.value) == message


def test_order_is_checked_by_the_request_too(cli, root):
    path = os.path.join(root, "mechanisms", "planar-four-bar.json")
    run = subprocess.run([cli, "run", path, "--order", "5"], capture_output=True, text=True)
    with pytest.raises(ValueError) as e:
        mechkin.load(path).run(order=5)
    assert run.returncode == 2 and run.stderr.splitlines()[0] == "--order: " + str(e.value)


def test_order_one_with_inertia_gives_the_forces_of_order_two(cli, root, tmp_path):
    doc = _four_bar_with_inertia(root)
    model = mechkin.loads(doc)
    one, two = model.run(order=1), model.run(order=2)
    assert one.complete and two.complete
    forces = [c["name"] for c in one.columns if c["quantity"] in FORCE_QUANTITIES]
    assert len(forces) == 2 + 4 * 12 + 3  # effort, power; 12 reaction components per joint; 3 energies
    assert max(c["order"] for c in one.columns) == 1
    for name in one.names:
        np.testing.assert_array_equal(one[name], two[name], err_msg=name)
    driver = model.drivers[0]
    assert abs(one.effort(driver)[0]) > 1  # held against gravity: a real torque
    # the CLI's order-1 table carries the same numbers (shortest round-trip digits)
    path = tmp_path / "four-bar-inertia.json"
    path.write_text(json.dumps(doc))
    out = subprocess.run([cli, "run", str(path), "--order", "1", "-o", "-"], capture_output=True, text=True, check=True)
    header = [h.split(" [")[0] for h in out.stdout.splitlines()[0].split(",")]
    table = np.array([[float(x) for x in line.split(",")] for line in out.stdout.splitlines()[1:]])
    assert header == one.names
    np.testing.assert_array_equal(table, one.values)


def test_run_request_is_a_typed_object():
    r = mechkin.RunRequest(order=1, tol=1e-12, solver="ceres", bodies=["crank"])
    assert (r.order, r.tol, r.solver, r.formulation, r.bodies, r.outputs, r.forces) == \
        (1, 1e-12, "ceres", "omega", ["crank"], None, None)
    assert "order=1" in repr(r) and "solver='ceres'" in repr(r)
    with pytest.raises(ValueError, match="solver must be one of newton, ceres"):
        r.solver = "gauss"
    r.forces = False
    assert r.forces is False


def test_sweep_returns_a_dataframe_consistent_with_motion(root):
    pd = pytest.importorskip("pandas")
    model = mechkin.load(os.path.join(root, "mechanisms", "parametric-four-bar.json"))
    variants = [{"a": 30.0, "b": 120.0}, {"a": 30.0, "b": 5.0}]
    df = mechkin.sweep(model, variants, threads=1)
    assert isinstance(df, pd.DataFrame) and len(df) == 2
    assert list(df.columns[:9]) == ["a", "b", "status", "message", "rows", "t_stop", "max_condition",
                                    "t_max_condition", df.columns[8]]
    assert list(df["status"]) == ["complete", "invalid"]
    assert math.isnan(df["t_stop"][0]) and df["rows"][0] == 73
    motion = model.with_parameters(a=30.0, b=120.0).run(order=1, bodies=[])
    units = motion.units()
    summarised = [c[:-4] for c in df.columns if c.endswith(" min")]
    assert summarised == [n for n in motion.names if n in units and n + " min" in df.columns]
    assert summarised, "no summary column"
    for name in summarised:  # named as the Motion names them, units stated once in attrs
        assert df[name + " min"][0] == motion[name].min() and df[name + " max"][0] == motion[name].max()
        assert df.attrs["units"][name + " min"] == units[name]
    assert df.attrs["units"]["t_stop"] == "s"


def _help(obj):
    return pydoc.render_doc(obj, renderer=pydoc.plaintext)


def test_help_on_model_motion_and_check_report_lists_the_fields(root):
    model = mechkin.load(os.path.join(root, "mechanisms", "bennett-linkage.json"))
    for cls, fields in [
            (mechkin.Model, ["bodies", "joints", "drivers", "outputs", "units", "parameters", "analysis", "warnings",
                             "run", "check", "range", "tolerance", "with_parameters"]),
            (mechkin.Motion, ["values", "columns", "names", "complete", "stop", "t", "units", "effort", "reaction",
                              "to_pandas", "diagnostics"]),
            (mechkin.CheckReport, ["file", "valid", "ok", "errors", "warnings", "bodies", "joints", "grubler",
                                   "dof_after_drivers_count", "mobility", "expect", "to_dict"]),
            (mechkin.MobilityReport, ["mobility", "redundant", "driven", "idle", "verdict"]),
            (mechkin.RunRequest, ["order", "tol", "solver", "formulation", "forces", "sensitivity", "is_valid"])]:
        text = _help(cls)
        for f in fields:
            assert f in text, (cls, f)
        # every public member documents itself
        for name in dir(cls):
            if not name.startswith("_"):
                assert (getattr(cls, name).__doc__ or "").strip(), (cls.__name__, name)
    report = model.check()
    assert isinstance(report, mechkin.CheckReport) and isinstance(report.mobility, mechkin.MobilityReport)
    assert report.mobility.mobility == 1 and report.mobility.redundant == 3 and report.mobility["redundant"] == 3
    assert repr(report).startswith("CheckReport(") and "mobility=1" in repr(report)
    motion = model.run(order=1)
    assert "rows" in repr(motion) and repr(model).startswith("Model(")
