"""The Python package against the CLI (the independent front end over the same
core), plus zero-copy views, pickling, threads, errors and partial runs."""
import csv
import glob
import io
import json
import os
import pickle
import subprocess
import sys
import threading

import numpy as np
import pytest

import mechkin

BUNDLED = sorted(glob.glob(os.path.join(os.path.dirname(__file__), "..", "..", "mechanisms", "*.json")))


def cli_table(cli, path, tmp_path, *args):
    out = tmp_path / (os.path.basename(path) + ".csv")
    proc = subprocess.run([cli, "run", path, "-o", str(out), *args], capture_output=True, text=True)
    if not out.exists():
        return proc.returncode, None, None, None
    lines = out.read_text().splitlines()
    note = lines[0] if lines[0].startswith("#") else None
    body = lines[1:] if note else lines
    rows = list(csv.reader(body))
    return proc.returncode, note, rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


def test_one_liner_from_the_issue(root):
    m = mechkin.load(os.path.join(root, "mechanisms/spatial-slider-crank.json"))
    assert m.run().to_pandas().shape == (361, 99)


@pytest.mark.parametrize("path", BUNDLED, ids=[os.path.basename(p) for p in BUNDLED])
def test_every_number_equals_the_cli_table(cli, tmp_path, path):
    code, note, header, values = cli_table(cli, path, tmp_path)
    motion = mechkin.load(path).run()
    assert motion.complete == (code == 0)
    if header is None:  # refused before the first row: no table from either
        assert len(motion) == 0 and motion.stop.kind in ("refused", "assembly_failed")
        return
    assert [c["name"] + (" [%s]" % c["unit"] if c["unit"] else "") for c in motion.columns] == header
    # The CLI writes the shortest round-trip form: the doubles are identical.
    assert values.shape == motion.values.shape
    np.testing.assert_array_equal(values, motion.values)
    assert (note is not None) == (not motion.complete)


def test_to_csv_writes_the_cli_file_byte_for_byte(cli, tmp_path, root):
    path = os.path.join(root, "mechanisms/screw-jack.json")
    subprocess.run([cli, "run", path, "-o", str(tmp_path / "cli.csv")], check=True, capture_output=True)
    mechkin.load(path).run().to_csv(tmp_path / "py.csv")
    assert (tmp_path / "cli.csv").read_bytes() == (tmp_path / "py.csv").read_bytes()


def test_options_reach_the_core_as_on_the_cli(cli, tmp_path, root):
    path = os.path.join(root, "mechanisms/planar-four-bar.json")
    _, _, header, values = cli_table(cli, path, tmp_path, "--order", "4", "--si", "--formulation", "p",
                                     "--bodies", "coupler", "--tol", "1e-12")
    motion = mechkin.load(path).run(order=4, si=True, formulation="p", bodies=["coupler"], tol=1e-12)
    np.testing.assert_array_equal(values, motion.values)


def test_arrays_are_views_of_the_core_buffer(root):
    motion = mechkin.load(os.path.join(root, "mechanisms/spatial-slider-crank.json")).run()
    assert motion.t.base is not None
    assert np.shares_memory(motion.t, motion.values)
    assert np.shares_memory(motion["piston.x_tt"], motion.values)
    rod = motion.body("rod")
    for view in (rod.position(0), rod.position(2), rod.angular_velocity(1), rod.euler_parameters()):
        assert np.shares_memory(view, motion.values)
    assert not motion.values.flags.writeable
    with pytest.raises(ValueError):
        motion.t[0] = 1.0


def test_body_accessors_pick_the_right_columns(root):
    motion = mechkin.load(os.path.join(root, "mechanisms/spatial-slider-crank.json")).run(order=4)
    rod = motion.body("rod")
    np.testing.assert_array_equal(rod.position(2)[:, 1], motion["rod.y_tt"])
    np.testing.assert_array_equal(rod.position(0)[:, 2], motion["rod.z"])
    np.testing.assert_array_equal(rod.angular_velocity(3)[:, 0], motion["rod.wx_tt"])
    np.testing.assert_array_equal(rod.euler_parameters()[:, 3], motion["rod.e3"])
    d = motion.diagnostics
    assert d["error_bound"].shape == (len(motion), 5)
    np.testing.assert_array_equal(d["error_bound"][:, 4], motion["error_bound_tttt"])
    # Velocity vs a central difference of the position (independent check of the column pick).
    t, x, v = motion.t, rod.position(0)[:, 0], rod.position(1)[:, 0]
    fd = (x[2:] - x[:-2]) / (t[2:] - t[:-2])
    assert np.max(np.abs(fd - v[1:-1])) < 1e-3 * np.max(np.abs(v))


def test_model_and_motion_pickle(root):
    model = mechkin.load(os.path.join(root, "mechanisms/bennett-linkage.json"))
    motion = model.run()
    model2 = pickle.loads(pickle.dumps(model))
    assert model2.bodies == model.bodies and model2.name == model.name
    np.testing.assert_array_equal(model2.run().values, motion.values)
    motion2 = pickle.loads(pickle.dumps(motion))
    np.testing.assert_array_equal(motion2.values, motion.values)
    assert motion2.names == motion.names and motion2.complete
    assert np.shares_memory(motion2.t, motion2.values)


def test_runs_from_two_threads_equal_serial_runs(root):
    model = mechkin.load(os.path.join(root, "mechanisms/spatial-slider-crank.json"))
    reference = model.run().values
    results = [None] * 1000

    def work(first):
        for k in range(first, 1000, 2):
            results[k] = model.run().values

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    for r in results:
        np.testing.assert_array_equal(r, reference)


def test_format_error_carries_every_diagnostic():
    bad = {"mechkin": 1, "bodies": [{"name": "a", "position": [0, 0]}],
           "joints": [{"name": "j", "type": "hinge", "body1": "ground", "body2": "a"}]}
    with pytest.raises(mechkin.FormatError) as err:
        mechkin.loads(bad)
    pointers = [d.pointer for d in err.value.diagnostics]
    assert "/bodies/0/position" in pointers and "/joints/0/type" in pointers
    assert all(d.message for d in err.value.diagnostics)


def test_bad_arguments_raise_value_error(root):
    model = mechkin.load(os.path.join(root, "mechanisms/planar-four-bar.json"))
    with pytest.raises(ValueError, match="no body named"):
        model.run(bodies=["nope"])
    with pytest.raises(ValueError):
        model.run(order=7)
    with pytest.raises(ValueError):
        model.run(solver="magic")


def test_partial_run_returns_rows_and_a_typed_stop(cli, tmp_path, root):
    # Slider-crank with crank = rod: the dead centre at crank angle 90° stops the run.
    path = os.path.join(root, "tests/data/slider-crank-equal-links.json")
    motion = mechkin.load(path).run()
    assert not motion.complete
    assert motion.stop.kind == "singular_position" and motion.stop
    assert abs(motion.stop.singular["driver_values"][0] - np.pi / 2) < 1e-6
    code, note, header, values = cli_table(cli, path, tmp_path)
    assert code == 1 and note.startswith("# PARTIAL TABLE")
    np.testing.assert_array_equal(values, motion.values)


def test_a_limit_of_motion_and_reselections_reach_python(root):
    # The piston driven 0.5 mm past the stroke end of a 20/50 mm slider-crank.
    doc = json.load(open(os.path.join(root, "tests/data/piston-driven-slider-crank.json")))
    x0 = 20 * np.cos(np.pi / 3) + np.sqrt(50 ** 2 - (20 * np.sin(np.pi / 3)) ** 2)
    doc["drivers"][0]["function"] = "%.17g*t" % (70.5 - x0)
    doc["analysis"] = {"start": 0, "end": 1, "steps": 100}
    motion = mechkin.loads(doc).run()
    assert not motion.complete and motion.stop.kind == "solve_failed"
    assert motion.stop.limit["fold"]
    assert abs(motion.stop.limit["driver_values"][0] - (70 - x0) * 1e-3) < 4e-11  # 1e-9 of the 40 mm stroke
    assert motion.reselections == []


def test_check_report_has_the_cli_json_fields(cli, root):
    path = os.path.join(root, "mechanisms/bennett-linkage.json")
    cli_report = json.loads(subprocess.run([cli, "check", path, "--format", "json"], capture_output=True,
                                           text=True).stdout)["files"][0]
    report = mechkin.load(path).check()
    assert report.to_dict() == cli_report
    assert report.mobility["mobility"] == 1 and report.mobility["redundant"] == 3 and report.grubler == -2 and report.ok


def test_to_pandas_names_and_missing_pandas_message(root, monkeypatch):
    motion = mechkin.load(os.path.join(root, "mechanisms/screw-jack.json")).run()
    df = motion.to_pandas()
    assert list(df.columns) == motion.names
    assert df.attrs["units"]["t"] == "s"
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(ImportError, match="python3-pandas"):
        motion.to_pandas()


def test_examples_run(root):
    env = dict(os.environ)
    study = subprocess.run([sys.executable, os.path.join(root, "python/examples/design_study.py")],
                           capture_output=True, text=True, env=env)
    assert study.returncode == 0, study.stderr
    rows = [l.split() for l in study.stdout.splitlines()[1:]]
    strokes = [float(r[1]) for r in rows]
    # Stroke of an offset slider-crank: sqrt((b+a)^2 - e^2) - sqrt((b-a)^2 - e^2), a=40, e=10.
    for rod, stroke in zip((60.0, 80.0, 120.0, 160.0, 240.0), strokes):
        exact = np.sqrt((rod + 40) ** 2 - 100) - np.sqrt((rod - 40) ** 2 - 100)
        assert abs(stroke - exact) < 0.05, (rod, stroke, exact)  # sampled every degree
    gate = subprocess.run([sys.executable, os.path.join(root, "python/examples/ci_check.py")] + BUNDLED,
                          capture_output=True, text=True, env=env)
    assert gate.returncode == 0, gate.stdout
    assert gate.stdout.strip().endswith("%d passed, 0 failed" % len(BUNDLED))


def test_forces_views_and_cli(cli, tmp_path, root):
    doc = json.load(open(os.path.join(root, "mechanisms/spatial-slider-crank.json")))
    for b, mass in zip(doc["bodies"], (1.0, 2.0, 3.0)):
        b["inertia"] = {"mass": mass, "center": b["position"], "moments": [[0.01, 0, 0], [0, 0.02, 0], [0, 0, 0.03]]}
    doc["gravity"] = [0, -9.81, 0]
    path = tmp_path / "sc-forces.json"
    path.write_text(json.dumps(doc))
    motion = mechkin.load(str(path)).run()
    assert motion["motor.effort"].shape == (361,)
    np.testing.assert_array_equal(motion.effort("motor"), motion["motor.effort"])
    np.testing.assert_array_equal(motion.effort("motor", 1), motion["motor.effort_t"])
    force, moment = motion.reaction("pin")
    np.testing.assert_array_equal(force[:, 1], motion["pin.fy"])
    np.testing.assert_array_equal(moment[:, 2], motion["pin.mz"])
    assert np.shares_memory(force, motion.values)
    _, joint_moment = motion.reaction("bearing", frame="joint")
    assert np.abs(joint_moment[:, 2]).max() < 1e-9 * np.abs(motion.effort("motor")).max()  # revolute: no axial moment
    assert np.abs(motion["energy_balance"]).max() < 1e-10 * np.abs(motion.power("motor")).max()
    _, _, header, values = cli_table(cli, str(path), tmp_path)
    np.testing.assert_array_equal(values, motion.values)
    again = pickle.loads(pickle.dumps(motion))
    np.testing.assert_array_equal(again.effort("motor"), motion.effort("motor"))
    assert mechkin.load(str(path)).run(forces=False).values.shape[1] < motion.values.shape[1]
