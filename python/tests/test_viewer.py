"""`mechkin view` in a real browser (headless Chromium with software WebGL) and
its glTF export against the motion table."""
import csv
import glob
import json
import os
import struct
import subprocess
import sys

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import view_screenshot as browser  # noqa: E402

BUNDLED = sorted(glob.glob(os.path.join(ROOT, "mechanisms", "*.json")))
RUNNABLE = [p for p in BUNDLED if "rssr" not in p and "sps-legs" not in p]  # the others are refused by `run`


def view(cli, path, out, *args):
    proc = subprocess.run([cli, "view", path, "-o", str(out), *args], capture_output=True, text=True)
    assert out.exists(), proc.stderr
    return proc


@pytest.mark.parametrize("path", RUNNABLE, ids=[os.path.basename(p) for p in RUNNABLE])
def test_page_loads_without_errors(cli, tmp_path, path):
    page = tmp_path / "page.html"
    assert view(cli, path, page).returncode == 0
    assert page.stat().st_size < 3_000_000  # three.js (850 kB) + the scene and table
    attrs, dom = browser.dump_dom(page, "t=0.1")
    assert attrs.get("data-ready") == "1", dom[-2000:]
    assert "data-errors" not in attrs, attrs.get("data-errors")


def pixels(png):
    from PIL import Image
    return np.asarray(Image.open(png).convert("RGB")).astype(int)


def test_scene_moves_between_two_times(cli, tmp_path):
    page = tmp_path / "sc.html"
    view(cli, os.path.join(ROOT, "mechanisms", "spatial-slider-crank.json"), page)
    a = pixels(browser.screenshot(page, tmp_path / "a.png", "t=0.1"))
    b = pixels(browser.screenshot(page, tmp_path / "b.png", "t=0.6"))
    scene = (slice(60, 680), slice(0, 690))  # the 3D view, left of the plots
    changed = np.abs(a[scene] - b[scene]).sum(axis=2) > 60
    assert changed.sum() > 500, changed.sum()
    # The plot panel's cursor moves too, but the 3D region alone differs.


def test_a_body_is_drawn_where_its_pose_puts_it(cli, tmp_path):
    # One moving body on a revolute: a bar from the pivot to a tip point.
    doc = {"mechkin": 1, "name": "one bar", "units": {"length": "m", "angle": "deg"},
           "bodies": [{"name": "bar", "position": [0.5, 0, 0]}],
           "joints": [{"name": "pivot", "type": "revolute", "body1": "ground", "body2": "bar", "origin": [0, 0, 0], "axis": [0, 0, 1]}],
           "drivers": [{"name": "motor", "type": "rotation", "joint": "pivot", "function": "360*t"}],
           "outputs": [{"name": "tip", "type": "point", "body": "bar", "point": [1, 0, 0]}],
           "analysis": {"start": 0, "end": 1, "steps": 72}}
    src = tmp_path / "bar.json"
    src.write_text(json.dumps(doc))
    page = tmp_path / "bar.html"
    view(cli, str(src), page)
    for t in ("0.1", "0.35", "0.8"):
        # The page projects the middle of the bar with its camera and reads back the
        # pixel drawn there: it must be the bar's colour (#1f77b4, blue; Lambert shading).
        attrs, _ = browser.dump_dom(page, "t=%s&probe=0" % t)
        x, y, color, r, g, b = attrs["data-probe"].split(",")
        assert color == "1f77b4"
        r, g, b = int(r), int(g), int(b)
        assert b > r + 40 and b > g + 10, (t, r, g, b)
    # And the background elsewhere: the probe is not trivially blue (the tip at t = 0.1
    # is not where the middle is at t = 0.6).
    a = pixels(browser.screenshot(page, tmp_path / "a.png", "t=0.1"))
    c = pixels(browser.screenshot(page, tmp_path / "c.png", "t=0.6"))
    assert (np.abs(a - c).sum(axis=2) > 60).sum() > 200


def test_a_body_shape_is_drawn(cli, tmp_path):
    # The same scene with and without a sphere on the slider: the shape adds pixels
    # in the 3D view, and the page loads without errors.
    doc = json.load(open(os.path.join(ROOT, "mechanisms", "spatial-slider-crank.json")))
    pages = []
    for with_shape in (False, True):
        if with_shape:
            doc["bodies"][-1]["shape"] = {"type": "sphere", "radius": 0.04}
        src = tmp_path / ("s%d.json" % with_shape)
        src.write_text(json.dumps(doc))
        page = tmp_path / ("s%d.html" % with_shape)
        assert view(cli, str(src), page).returncode == 0
        attrs, _ = browser.dump_dom(page, "t=0.3")
        assert attrs.get("data-ready") == "1" and "data-errors" not in attrs
        pages.append(pixels(browser.screenshot(page, tmp_path / ("s%d.png" % with_shape), "t=0.3")))
    scene = (slice(60, 680), slice(0, 690))
    assert (np.abs(pages[0][scene] - pages[1][scene]).sum(axis=2) > 60).sum() > 300


def test_plots_against_a_column(cli, tmp_path):
    # "#x=NAME" (or the "against" menu) puts a column on the plot's horizontal axis:
    # the axis is labelled with it and the curve spans its range.
    import re
    page = tmp_path / "x.html"
    view(cli, os.path.join(ROOT, "mechanisms", "spatial-slider-crank.json"), page)
    attrs, dom = browser.dump_dom(page, "t=0.3")
    assert "t [s]" in re.findall(r"<text[^>]*>([^<]*)</text>", dom)
    attrs, dom = browser.dump_dom(page, "t=0.3&x=crank_angle")
    assert attrs.get("data-ready") == "1" and "data-errors" not in attrs
    assert "crank_angle [deg]" in re.findall(r"<text[^>]*>([^<]*)</text>", dom)
    path = re.search(r'<path d="M([0-9.]+),[0-9.]+[^"]*L([0-9.]+),[0-9.]+"', dom)
    assert path and float(path.group(1)) < float(path.group(2))  # from the smallest angle to the largest


def read_glb(path):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67 and version == 2 and length == len(data)
    jlen, jtype = struct.unpack_from("<II", data, 12)
    assert jtype == 0x4E4F534A
    doc = json.loads(data[20:20 + jlen])
    blen, btype = struct.unpack_from("<II", data, 20 + jlen)
    assert btype == 0x004E4942
    return doc, data[28 + jlen:28 + jlen + blen]


def accessor(doc, buf, k):
    a = doc["accessors"][k]
    v = doc["bufferViews"][a["bufferView"]]
    comps = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[a["type"]]
    dtype = {5126: np.float32, 5125: np.uint32}[a["componentType"]]
    start = v["byteOffset"] + a.get("byteOffset", 0)
    assert start + a["count"] * comps * np.dtype(dtype).itemsize <= v["byteOffset"] + v["byteLength"] <= len(buf)
    return np.frombuffer(buf, dtype=dtype, count=a["count"] * comps, offset=start).reshape(a["count"], comps)


@pytest.mark.parametrize("name", ["spatial-slider-crank", "bennett-linkage", "stewart-platform"])
def test_gltf_matches_the_table(cli, tmp_path, name):
    src = os.path.join(ROOT, "mechanisms", name + ".json")
    glb, table = tmp_path / "m.glb", tmp_path / "m.csv"
    subprocess.run([cli, "view", src, "-o", str(tmp_path / "m.html"), "--gltf", str(glb)], check=True, capture_output=True)
    subprocess.run([cli, "run", src, "--si", "--order", "0", "-o", str(table)], check=True, capture_output=True)
    doc, buf = read_glb(glb)
    rows = list(csv.reader(open(table)))
    head, values = [h.split(" [")[0] for h in rows[0]], np.array([[float(x) for x in r] for r in rows[1:]])
    model = json.load(open(src))
    bodies = [b["name"] for b in model["bodies"]]
    assert len(doc["nodes"]) == len(bodies) + 1 and doc["nodes"][0]["name"] == "ground"
    anim = doc["animations"][0]
    assert len(anim["channels"]) == 2 * len(bodies)
    for a in doc["accessors"]:
        accessor(doc, buf, doc["accessors"].index(a))  # every accessor lies inside its view and the buffer
    for m in doc["materials"]:
        assert m["pbrMetallicRoughness"]["metallicFactor"] == 0
    size = np.abs(values[:, 1:]).max()
    for ch in anim["channels"]:
        node = doc["nodes"][ch["target"]["node"]]["name"]
        s = anim["samplers"][ch["sampler"]]
        times, out = accessor(doc, buf, s["input"])[:, 0], accessor(doc, buf, s["output"])
        assert abs(times[0] - values[0, 0]) < 1e-6 and abs(times[-1] - values[-1, 0]) < 1e-6
        if ch["target"]["path"] == "translation":
            want = values[:, [head.index(node + c) for c in (".x", ".y", ".z")]]
            assert np.abs(out - want).max() < 1e-6 * max(size, 1), node
        else:
            e = values[:, [head.index(node + c) for c in (".e1", ".e2", ".e3", ".e0")]]
            assert np.abs(np.abs((out * e).sum(axis=1)) - 1).max() < 1e-6, node


def test_partial_motion_is_marked(cli, tmp_path):
    page = tmp_path / "dead.html"
    proc = view(cli, os.path.join(ROOT, "tests", "data", "slider-crank-equal-links.json"), page)
    assert proc.returncode == 1
    attrs, dom = browser.dump_dom(page)
    assert attrs.get("data-ready") == "1"
    assert "run stopped at t =" in dom and "singular position" in dom


def test_long_runs_are_decimated(cli, tmp_path):
    doc = json.load(open(os.path.join(ROOT, "mechanisms", "spatial-slider-crank.json")))
    doc["analysis"] = {"start": 0, "end": 100, "steps": 100000}
    src = tmp_path / "long.json"
    src.write_text(json.dumps(doc))
    page = tmp_path / "long.html"
    view(cli, str(src), page)
    assert page.stat().st_size < 6_000_000
    attrs, _ = browser.dump_dom(page, "t=50")
    assert attrs.get("data-ready") == "1" and "data-errors" not in attrs
