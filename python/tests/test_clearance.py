"""Clearance in Python as in `mechkin run` (issue 28): Model.run(on_contact=...) stops
at the first contact or notes it and goes on, the contact is typed data (time,
bodies, point) equal to the closed form and to the CLI's note, and the clearance
columns of the Motion equal the CLI's table and the closed form. A box on a slider
(20 mm, 100 mm/s) meets a fixed box (20 mm, centred at x = 103.3 mm) at t = 0.833 s;
the slider's box is also given as a mesh file next to the mechanism file."""
import csv
import json
import re
import struct
import subprocess

import numpy as np
import pytest

import mechkin

T0 = (103.3 - 20) / 100  # s: the faces meet


def _slider_past_box():
    return {
        "mechkin": 1, "units": {"length": "mm", "angle": "deg"},
        "ground": {"shapes": [{"type": "box", "size": [20, 20, 20], "center": [103.3, 0, 0]}]},
        "bodies": [{"name": "slider", "position": [0, 0, 0], "shape": {"type": "box", "size": [20, 20, 20]}}],
        "joints": [{"name": "P", "type": "prismatic", "body1": "ground", "body2": "slider",
                    "origin": [0, 0, 0], "axis": [1, 0, 0]}],
        "drivers": [{"name": "push", "type": "translation", "joint": "P", "function": "100*t"}],
        "analysis": {"start": 0, "end": 1, "steps": 100},
        "outputs": [{"name": "gap", "type": "clearance", "body1": "slider", "body2": "ground"}],
    }


def _cli_table(cli, path, *args):
    run = subprocess.run([cli, "run", str(path), "--order", "1", *args], capture_output=True, text=True)
    lines = [r for r in csv.reader(run.stdout.splitlines()) if r and not r[0].startswith("#")]
    head = [h.split(" [")[0] for h in lines[0]]
    return run, head, np.array([[float(x) for x in r] for r in lines[1:]])


def test_report_goes_on_and_the_contact_is_typed(cli, tmp_path):
    doc = _slider_past_box()
    motion = mechkin.loads(doc).run(order=1)  # on_contact="report" is the default, as in the CLI
    assert motion.complete and len(motion) == 101
    assert len(motion.contacts) == 1
    c = motion.first_contact
    print("[measured] contact at %.12f s (closed form %.12f s), point %s" % (c.t, T0, c.point))
    assert abs(c.t - T0) < 1e-9
    assert c.bodies == ("slider", "ground") and c.output == "gap" and not c.at_start
    assert abs(c.point[0] - 93.3) < 1e-6  # on the fixed box's face (mm)
    assert abs(c.driver_values[0] - 0.0833) < 1e-10  # SI: the slide in m
    # The CLI notes the same contact, point and time (as it prints them).
    path = tmp_path / "slider.json"
    path.write_text(json.dumps(doc))
    run, head, rows = _cli_table(cli, path)
    assert run.returncode == 0, run.stderr
    note = re.search(r"bodies `slider` and `ground` come into contact at t = ([0-9.]+) s \(driver `push` = ([0-9.]+) mm\) "
                     r"at \[([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\] mm", run.stderr)
    assert note, run.stderr
    assert float(note.group(1)) == pytest.approx(c.t, abs=1e-3)
    for k in range(3):
        assert float(note.group(3 + k)) == pytest.approx(c.point[k], abs=0.05)
    # The clearance columns: in the Motion like any other, equal to the CLI's table
    # and to the closed form on the clear rows.
    assert rows.shape == motion.values.shape
    for name in ("gap", "gap_t", "gap.point1.x", "gap.point1.y", "gap.point2.z"):
        assert np.abs(motion[name] - rows[:, head.index(name)]).max() <= 1e-12 * max(1, np.abs(rows[:, head.index(name)]).max()), name
    gap, rate = motion.clearance("gap"), motion.clearance("gap", order=1)
    assert gap is not None and np.shares_memory(gap, motion.values)
    clear = motion.t < T0
    closed = 83.3 - 100 * motion.t
    err = np.abs(gap[clear] - closed[clear]).max()
    print("[measured] %d clear rows: clearance off the closed form by %.2e mm" % (clear.sum(), err))
    assert clear.sum() == 84 and err < 1e-9
    assert np.abs(rate[clear] + 100).max() < 1e-9
    p1, p2 = motion.closest_points("gap")
    assert p1.shape == (101, 3)
    assert np.abs(p1[clear, 0] - (motion.t[clear] * 100 + 10)).max() < 1e-9  # the slider's front face
    assert np.abs(p2[clear, 0] - 93.3).max() < 1e-9  # the fixed box's face
    assert np.abs(p1[:, 0] - rows[:, head.index("gap.point1.x")]).max() == 0


def test_stop_ends_the_run_at_the_contact(cli, tmp_path):
    doc = _slider_past_box()
    motion = mechkin.loads(doc).run(order=1, on_contact="stop")
    assert not motion.complete and motion.stop.kind == "contact"
    assert "come into contact at t = 0.833 s" in motion.stop.message, motion.stop.message
    assert len(motion) == 84 and motion.t[-1] < T0 < motion.t[-1] + 0.01
    assert abs(motion.first_contact.t - T0) < 1e-9
    path = tmp_path / "slider.json"
    path.write_text(json.dumps(doc))
    run, head, rows = _cli_table(cli, path, "--on-contact", "stop")
    assert run.returncode == 1
    assert rows.shape == motion.values.shape
    assert np.abs(rows[:, head.index("gap")] - motion["gap"]).max() == 0


def test_on_contact_is_validated_by_the_run_request():
    model = mechkin.loads(_slider_past_box())
    with pytest.raises(ValueError, match="on_contact must be one of stop, report, not 'ignore'"):
        model.run(on_contact="ignore")
    request = mechkin.RunRequest(on_contact="stop")
    assert request.on_contact == "stop" and "on_contact='stop'" in repr(request)
    request.on_contact = "report"
    assert request.on_contact == "report"
    with pytest.raises(ValueError, match="on_contact must be one of"):
        request.on_contact = "halt"
    assert not model.run(order=1, request=mechkin.RunRequest(order=1, on_contact="stop")).complete


def test_a_mesh_file_next_to_the_mechanism_measures_like_the_box(tmp_path):
    # The slider's box as a binary STL of 12 triangles in metres, in a file in mm: scale 1000.
    corners = [((k & 1) * 0.02 - 0.01, (k >> 1 & 1) * 0.02 - 0.01, (k >> 2 & 1) * 0.02 - 0.01) for k in range(8)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tris = [t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]
    data = b"\0" * 80 + struct.pack("<I", len(tris))
    for t in tris:
        data += struct.pack("<12f", 0, 0, 0, *[x for i in t for x in corners[i]]) + b"\0\0"
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "box.stl").write_bytes(data)
    doc = _slider_past_box()
    doc["bodies"][0]["shape"] = {"type": "mesh", "file": "parts/box.stl", "scale": 1000}
    path = tmp_path / "mesh.json"
    path.write_text(json.dumps(doc))
    mesh = mechkin.load(str(path)).run(order=1)
    box = mechkin.loads(_slider_past_box()).run(order=1)
    clear = box.t < T0
    err = np.abs(mesh.clearance("gap")[clear] - box.clearance("gap")[clear]).max()
    print("[measured] mesh (float32 STL, m → mm) against the box: %.2e mm" % err)
    assert err < 1e-5  # float32 corners of 0.01 m: 1e-10 m
    assert abs(mesh.first_contact.t - box.first_contact.t) < 1e-7
    # Loaded from text without a path, the relative file is not found: the message says where.
    with pytest.raises(mechkin.FormatError, match=r"/bodies/0/shape/file: mesh file 'parts/box.stl'"):
        mechkin.loads(doc)
