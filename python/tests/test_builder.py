"""mechkin.Mechanism, the Python builder: what it builds is the file's own form,
compiled by the C++ reader, so a built mechanism runs to the CLI's table."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import mechkin

PISTON = [0.395127091267, 0.02, 0.05]


def spatial_slider_crank():
    """mechanisms/spatial-slider-crank.json, element by element."""
    m = mechkin.Mechanism("spatial slider-crank R-S-U-P", units={"length": "m", "angle": "deg"})
    m.add_body("crank", position=[0.05, 0.0, 0.0])
    m.add_body("rod", position=[0.247563545634, 0.01, 0.025])
    m.add_body("slider", position=PISTON)
    m.add_joint("bearing", "revolute", "ground", "crank", origin=[0.0, 0.0, 0.0], axis=[0, 0, 1])
    m.add_joint("pin", "spherical", "crank", "rod", origin=[0.1, 0.0, 0.0])
    m.add_joint("wrist", "universal", "rod", "slider", origin=PISTON,
                axis1=[-0.067612340378281, 0.997711667481428, 0.0], axis2=[0.0, 0.0, 1.0])
    m.add_joint("guide", "prismatic", "ground", "slider", origin=PISTON, axis=[1, 0, 0])
    m.add_driver("motor", "rotation", joint="bearing", function="360*t")
    m.set_analysis(start=0, end=1, steps=360)
    m.add_output("piston", "point", body="slider", point=PISTON)
    m.add_output("crank_angle", "joint", joint="bearing")
    m.set_expect(grubler=1, mobility=1, redundant=0, idle=0, driven="full")
    return m


def test_builder_runs_the_bundled_slider_crank_to_the_cli_table_bit_for_bit(cli, root, tmp_path):
    path = os.path.join(root, "mechanisms", "spatial-slider-crank.json")
    subprocess.run([cli, "run", path, "-o", str(tmp_path / "cli.csv")], check=True, capture_output=True)
    built = spatial_slider_crank().compile()
    built.run().to_csv(str(tmp_path / "built.csv"))
    assert (tmp_path / "built.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()


def test_builder_dict_is_the_bundled_file(root):
    with open(os.path.join(root, "mechanisms", "spatial-slider-crank.json")) as f:
        bundled = json.load(f)
    bundled.pop("description")
    assert spatial_slider_crank().to_dict() == bundled


def four_bar_by_markers(crank=0.1):
    """A planar four-bar written by its link lengths: markers only, loop closed by the
    positions of a drawing at crank angle 0 (rocker pivot 0.4 m away)."""
    m = mechkin.Mechanism("four-bar by markers", units={"length": "m", "angle": "rad"})
    m.add_parameter("crank", crank)
    m.add_parameter("coupler", 0.35)
    m.add_parameter("rocker", 0.3)
    m.add_parameter("frame", 0.4)
    m.add_marker("ground", "bearing", point=[0, 0, 0])
    m.add_marker("ground", "pivot", point=["frame", 0, 0])
    # Drawn with the crank along x: the coupler and rocker close the triangle.
    c2 = (0.35 ** 2 + (0.4 - crank) ** 2 - 0.3 ** 2) / (2 * 0.35 * (0.4 - crank))
    phi = math.acos(c2)  # coupler's angle from +x
    end = [crank + 0.35 * math.cos(phi), 0.35 * math.sin(phi), 0]
    rocker_angle = math.atan2(end[1], end[0] - 0.4)
    m.add_body("crank", position=[0, 0, 0], markers={"bearing": dict(point=[0, 0, 0]), "pin": dict(point=["crank", 0, 0])})
    m.add_body("coupler", position=[crank, 0, 0], orientation={"axis": [0, 0, 1], "angle": phi},
               markers={"pin": dict(point=[0, 0, 0]), "end": dict(point=["coupler", 0, 0])})
    m.add_body("rocker", position=[0.4, 0, 0], orientation={"axis": [0, 0, 1], "angle": rocker_angle},
               markers={"pivot": dict(point=[0, 0, 0]), "end": dict(point=["rocker", 0, 0])})
    m.add_joint("bearing", "revolute", "ground", "crank", marker1="bearing", marker2="bearing")
    m.add_joint("crankpin", "revolute", "crank", "coupler", marker1="pin", marker2="pin")
    m.add_joint("endpin", "revolute", "coupler", "rocker", marker1="end", marker2="end")
    m.add_joint("pivot", "revolute", "ground", "rocker", marker1="pivot", marker2="pivot")
    m.add_driver("motor", "rotation", joint="bearing", function="0.5*t")
    m.set_analysis(start=0, end=1, steps=10)
    m.add_output("tip", "point", body="rocker", marker="end")
    return m, rocker_angle


def test_marker_four_bar_from_the_builder_follows_freudenstein():
    m, _ = four_bar_by_markers()
    motion = m.compile().run(order=1)
    a, b, c, d = 0.1, 0.35, 0.3, 0.4
    for k, t in enumerate(motion.t):
        theta = 0.5 * t
        # rocker tip: circle of radius c about (d, 0) at distance b from the crank pin
        px, py = a * math.cos(theta), a * math.sin(theta)
        x, y = motion["tip.x"][k], motion["tip.y"][k]
        assert math.hypot(x - d, y) == pytest.approx(c, abs=1e-9)
        assert math.hypot(x - px, y - py) == pytest.approx(b, abs=1e-9)


def test_with_parameters_compiles_the_same_model_as_the_file_with_the_value(tmp_path):
    m, _ = four_bar_by_markers()
    nominal = m.compile()
    variant = nominal.with_parameters(coupler=0.36)
    direct = mechkin.loads(m.to_dict()).with_parameters(coupler=0.36)
    assert variant.parameters["coupler"] == 0.36
    np.testing.assert_array_equal(variant.run(order=1).values, direct.run(order=1).values)
    assert not np.array_equal(variant.run(order=1)["tip.x"], nominal.run(order=1)["tip.x"])
    # a variant pickles with its override
    import pickle
    assert pickle.loads(pickle.dumps(variant)).parameters["coupler"] == 0.36


def test_builder_refuses_duplicates_and_unknown_bodies_at_once():
    m = mechkin.Mechanism("x")
    m.add_body("a")
    with pytest.raises(ValueError, match="duplicate body name 'a'"):
        m.add_body("a")
    with pytest.raises(ValueError, match="unknown body 'b'"):
        m.add_marker("b", "p", point=[0, 0, 0])
    with pytest.raises(ValueError, match="unknown joint type 'hinge'"):
        m.add_joint("j", "hinge", "ground", "a")
    with pytest.raises(ValueError, match="3 components"):
        m.add_marker("a", "p", point=[0, 0])


def test_compile_errors_name_the_pointer_into_to_dict():
    m = mechkin.Mechanism("x")
    m.add_body("a", position=[0, 0, 0])
    m.add_joint("j", "revolute", "ground", "a", marker1="nowhere", marker2="nowhere")
    with pytest.raises(mechkin.FormatError) as err:
        m.compile()
    pointers = [d.pointer for d in err.value.diagnostics]
    assert "/joints/0/marker1" in pointers


def test_builder_gear_pair_is_the_bundled_geared_crank_and_runs(root):
    """A coupler from the builder (add_gear) gives the bundled file's dict, and the
    compiled model turns the crank at −1/4 of the motor."""
    with open(os.path.join(root, "mechanisms", "geared-slider-crank.json")) as f:
        bundled = json.load(f)
    m = mechkin.Mechanism(bundled["name"], description=bundled["description"], units=bundled["units"])
    for b in bundled["bodies"]:
        m.add_body(b["name"], position=b["position"])
    for j in bundled["joints"]:
        m.add_joint(j["name"], j["type"], j["body1"], j["body2"], **{k: v for k, v in j.items() if k not in (
            "name", "type", "body1", "body2")})
    m.add_gear("mesh", "motor_bearing", "crank_bearing", -0.25, pitch_radius=16.0, pressure_angle=20.0)
    for d in bundled["drivers"]:
        m.add_driver(d["name"], d["type"], d["function"], joint=d["joint"])
    m.set_analysis(**bundled["analysis"])
    for o in bundled["outputs"]:
        m.add_output(o["name"], o["type"], joint=o["joint"])
    m.set_expect(**bundled["expect"])
    assert m.to_dict() == bundled
    model = m.compile()
    assert model.couplers == [{"name": "mesh", "type": "gear", "joints": ["motor_bearing", "crank_bearing"]}]
    table = model.run(order=1)
    t = np.asarray(table["t"])
    crank = np.asarray(table["crank_angle"])
    assert np.max(np.abs(crank - (-0.25 * 1440 * t))) < 1e-9
    with pytest.raises(ValueError):
        m.add_coupler("mesh", "gear", joint1="a", joint2="b", ratio=1)
    with pytest.raises(ValueError):
        m.add_coupler("other", "gears")
