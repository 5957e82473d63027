"""Foreign files (URDF, MJCF, SDFormat, FreeCAD) loaded by the Python package
(issue 26): mechkin.load imports them as `mechkin run FILE --drive ...` does."""
import math
import os
import pickle
import subprocess

import numpy as np
import pytest

import mechkin

A, B, C, D = 0.04, 0.12, 0.08, 0.10  # crank, coupler, rocker, frame (m)


def closed_form_b_and_c(t):
    """Joints B and C of the open crank-rocker branch, crank at 60° + 360° t."""
    th = math.pi / 3 + 2 * math.pi * np.asarray(t)
    bx, by = A * np.cos(th), A * np.sin(th)
    e, beta = np.hypot(bx - D, by), np.arctan2(by, bx - D)
    psi = np.arccos((C * C + e * e - B * B) / (2 * C * e))
    return np.stack([bx, by], 1), np.stack([D + C * np.cos(beta - psi), C * np.sin(beta - psi)], 1)


def rotation(e):
    """The rotation matrices of rows of Euler parameters (e0, e1, e2, e3)."""
    e0, e1, e2, e3 = e.T
    return np.stack([np.stack([1 - 2 * (e2 * e2 + e3 * e3), 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2)], -1),
                     np.stack([2 * (e1 * e2 + e0 * e3), 1 - 2 * (e1 * e1 + e3 * e3), 2 * (e2 * e3 - e0 * e1)], -1),
                     np.stack([2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), 1 - 2 * (e1 * e1 + e2 * e2)], -1)], 1)


# URDF and SDFormat close the loop with a fourth revolute (3 redundant equations, as the
# native planar four-bar); MJCF with a `connect` equality, a spherical joint (1).
@pytest.mark.parametrize("name,redundant", [("four-bar.urdf", 3), ("four-bar.xml", 1), ("four-bar.sdf", 3)])
def test_imported_four_bar_runs_to_the_closed_form(root, name, redundant):
    model = mechkin.load(os.path.join(root, "mechanisms/imported", name), drive={"A": "2*pi*t"})
    report = model.check()
    assert report.mobility["mobility"] == 1 and report.mobility["redundant"] == redundant
    motion = model.run(tol=1e-14)
    assert motion.values.shape[0] == 361  # the default span 0:1:360
    b, c = closed_form_b_and_c(motion["t"])
    # Every format puts the coupler's frame at its parent joint B; joint C, a point fixed
    # in the coupler, is carried there by the coupler's rotation from the written pose.
    coupler = motion.body("coupler")
    origin, turn = coupler.position(), rotation(coupler.euler_parameters())
    c_in_coupler = turn[0].T @ np.array([c[0, 0], c[0, 1], 0] - origin[0])
    c_path = origin + turn @ c_in_coupler
    assert np.max(np.abs(origin[:, :2] - b)) < 1e-13
    assert np.max(np.abs(c_path[:, :2] - c)) < 1e-12 and np.max(np.abs(c_path[:, 2])) < 1e-12


def test_span_and_the_cli_give_the_same_table(root, cli, tmp_path):
    path = os.path.join(root, "mechanisms/imported/four-bar.urdf")
    motion = mechkin.load(path, drive={"A": "2*pi*t"}, span=(0, 0.5, 10)).run()
    out = tmp_path / "cli.csv"
    subprocess.run([cli, "run", path, "--drive", "A=2*pi*t", "--span", "0:0.5:10", "-o", str(out)], check=True)
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    assert table.shape == motion.values.shape
    assert np.array_equal(table[:, 0], motion["t"])
    assert np.max(np.abs(table - motion.values)) < 1e-12


def test_an_imported_model_pickles(root):
    model = mechkin.load(os.path.join(root, "mechanisms/imported/four-bar.urdf"), drive={"A": "2*pi*t"})
    again = pickle.loads(pickle.dumps(model))
    # The pickle holds the imported mechanism file's text (what `mechkin import` writes);
    # compiled again it runs as the imported spec to rounding (1e-16 m seen; the
    # diagnostics' condition estimates and bounds to a few parts in 1e4).
    first, second = model.run(), again.run()
    motion_columns = [k for k, c in enumerate(first.columns)
                      if c["quantity"] not in ("newton_iterations", "residual", "condition", "error_bound")]
    assert first.columns == second.columns
    assert np.allclose(first.values[:, motion_columns], second.values[:, motion_columns], rtol=1e-12, atol=1e-12)


def test_a_malformed_file_names_its_line(tmp_path):
    bad = tmp_path / "bad.urdf"
    bad.write_text('<robot name="r">\n  <link name="a"/>\n  <link name="b"/>\n  <joint name="j" type="warp">\n'
                   '    <parent link="a"/><child link="b"/>\n  </joint>\n</robot>\n')
    with pytest.raises(mechkin.FormatError) as e:
        mechkin.load(bad, drive={"j": "t"})
    assert "bad.urdf:4" in str(e.value) and "warp" in str(e.value)


def test_drive_and_span_are_refused_for_a_mechanism_file(root):
    with pytest.raises(ValueError, match="for imported"):
        mechkin.load(os.path.join(root, "mechanisms/planar-four-bar.json"), drive={"A": "t"})
    with pytest.raises(ValueError, match="end > start"):
        mechkin.load(os.path.join(root, "mechanisms/imported/four-bar.urdf"), drive={"A": "t"}, span=(1, 0, 10))
