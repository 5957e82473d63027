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


# --- issue 27: up axis, views, autoplay, plots, exports, paths ---------------------------------

BIG = (1400, 900)
VIEW3D = (slice(40, 890), slice(0, 835))  # the 3D view of a 1400×900 page (left of the 560 px plots)


def colour_masks(img):
    """Where the suspension's lower arm (#1f77b4, blue) and upper arm (#d62728, red) are drawn."""
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return (b > r + 40) & (b > g + 10), (r > g + 60) & (r > b + 60)


def suspension(tmp_path, gravity=None, view=None):
    # The bundled file without its "view" section unless one is given.
    doc = json.load(open(os.path.join(ROOT, "mechanisms", "double-wishbone-suspension.json")))
    doc.pop("view", None)
    if view is not None:
        doc["view"] = view
    if gravity is not None:
        doc["gravity"] = gravity
    src = tmp_path / "susp.json"
    src.write_text(json.dumps(doc))
    return src


def page_data(page):
    import re
    text = open(page).read()
    return json.loads(re.search(r"window\.MECHKIN_DATA=(.*?);</script>", text).group(1))


@pytest.mark.parametrize("how", ["gravity", "flag", "file"])
def test_z_up_mechanism_is_drawn_upright(cli, tmp_path, how):
    # The suspension is drawn z-up (x forward, y outboard): with gravity −z in the file,
    # or with --up z. Its upper arm (z ≈ 435 mm) is then above its lower arm (z ≈ 140 mm)
    # on the screen, and it is the top body: the top rows of the mechanism are red.
    src = suspension(tmp_path, [0, 0, -9810] if how == "gravity" else None, {"up": "z"} if how == "file" else None)
    page = tmp_path / "z.html"
    assert view(cli, str(src), page, *(["--up", "z"] if how == "flag" else [])).returncode == 0
    assert page_data(page)["up"] == [0, 0, 1]
    img = pixels(browser.screenshot(page, tmp_path / "z.png", "t=0.5", size=BIG))[VIEW3D]
    blue, red = colour_masks(img)
    rows_b, rows_r = np.nonzero(blue)[0], np.nonzero(red)[0]
    assert len(rows_b) > 2000 and len(rows_r) > 2000
    assert rows_r.mean() + 150 < rows_b.mean(), (rows_r.mean(), rows_b.mean())
    mech = np.nonzero((np.abs(img - img[5, 5]).sum(axis=2) > 60).any(axis=1))[0]
    top = slice(mech.min(), mech.min() + 40)
    assert red[top].sum() > 5 * blue[top].sum()


def test_without_gravity_or_flag_y_is_up(cli, tmp_path):
    # Today's behaviour for files without gravity: y up, so the suspension (z up in
    # its own axes) lies on its side: the arms are not one above the other.
    page = tmp_path / "y.html"
    assert view(cli, str(suspension(tmp_path)), page).returncode == 0
    assert page_data(page)["up"] == [0, 1, 0]
    img = pixels(browser.screenshot(page, tmp_path / "y.png", "t=0.5", size=BIG))[VIEW3D]
    blue, red = colour_masks(img)
    assert not np.nonzero(red)[0].mean() + 150 < np.nonzero(blue)[0].mean()


def test_file_view_section_sets_up_axis_panels_and_paused(cli, tmp_path):
    # "view": {"up", "plots", "paused"} in the file: the page uses exactly those panels,
    # the bundled suspension's own "view" draws it z-up, paused opens still, and a
    # column the table lacks is refused naming /view/plots (exit 1, no page).
    import re
    page = tmp_path / "bundled.html"
    assert view(cli, os.path.join(ROOT, "mechanisms", "double-wishbone-suspension.json"), page).returncode == 0
    assert page_data(page)["up"] == [0, 0, 1]
    src = suspension(tmp_path, None, {"plots": [["toe"], ["camber", "wheel_centre.z"]], "paused": True})
    page = tmp_path / "f.html"
    assert view(cli, str(src), page).returncode == 0
    data = page_data(page)
    assert data["paused"] is True and data["up"] == [0, 1, 0]
    attrs, dom = browser.dump_dom(page, "t=0.2", size=BIG)
    panels = re.findall(r'<svg[^>]*class="plot".*?</svg>', dom, re.S)
    assert [re.findall(r'data-name="([^"]+)"', p) for p in panels] == [["toe"], ["camber", "wheel_centre.z"]]
    still = [pixels(browser.screenshot(page, tmp_path / ("s%d.png" % k), "", size=BIG, budget=b))[VIEW3D]
             for k, b in enumerate((900, 1300))]
    assert (np.abs(still[0] - still[1]).sum(axis=2) > 60).sum() == 0
    assert view(cli, str(src), page, "--up", "x").returncode == 0 and page_data(page)["up"] == [1, 0, 0]
    bad = suspension(tmp_path, None, {"plots": [["camber", "nope"]]})
    out = tmp_path / "bad.html"
    r = subprocess.run([cli, "view", str(bad), "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 1 and "/view/plots: no column 'nope'" in r.stderr and "camber" in r.stderr
    assert not out.exists()


def test_standard_views_change_the_picture(cli, tmp_path):
    page = tmp_path / "v.html"
    assert view(cli, os.path.join(ROOT, "mechanisms", "stewart-platform.json"), page, "--up", "z").returncode == 0
    shots = {}
    for v in ("front", "side", "top", "iso"):
        attrs, _ = browser.dump_dom(page, "t=0.3&view=" + v)
        assert attrs.get("data-ready") == "1" and "data-errors" not in attrs
        shots[v] = pixels(browser.screenshot(page, tmp_path / (v + ".png"), "t=0.3&view=" + v, size=BIG))[VIEW3D]
    names = list(shots)
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            changed = (np.abs(shots[names[i]] - shots[names[j]]).sum(axis=2) > 60).sum()
            assert changed > 5000, (names[i], names[j], changed)
    ortho = pixels(browser.screenshot(page, tmp_path / "o.png", "t=0.3&view=iso&ortho=1", size=BIG))[VIEW3D]
    assert (np.abs(ortho - shots["iso"]).sum(axis=2) > 60).sum() > 2000


def test_opens_playing_unless_paused(cli, tmp_path):
    # The page's own clock, read from the DOM after 900 and 1300 ms of virtual time:
    # playing, it has left the first row's time; paused (#paused), it stays there and
    # the picture does not change. (Counting moved pixels in a time window flaked on a
    # loaded machine: how far the animation gets there depends on the frame rate.)
    page = tmp_path / "p.html"
    assert view(cli, os.path.join(ROOT, "mechanisms", "planar-four-bar.json"), page).returncode == 0
    times = page_data(page)["times"]
    t0, span = times[0], times[-1] - times[0]
    played = []
    for budget in (900, 1300):
        attrs, _ = browser.dump_dom(page, "", size=BIG, budget=budget)
        assert attrs.get("data-playing") == "1", (budget, attrs)
        played.append(float(attrs["data-time"]))
        attrs, _ = browser.dump_dom(page, "paused", size=BIG, budget=budget)
        assert attrs.get("data-playing") == "0" and abs(float(attrs["data-time"]) - t0) <= 1e-8 * span, (budget, attrs)
    # Playing, the clock has left t0 and reads differently 400 ms apart. A playing
    # clock is back at t0 on the one frame where the loop wraps (the motion lasts 1 s,
    # about a second after the page loads): one read may land there, not both.
    assert max(played) > t0 + 1e-6 * span and played[0] != played[1], played
    still = [pixels(browser.screenshot(page, tmp_path / ("s%d.png" % k), "paused", size=BIG, budget=b))[VIEW3D]
             for k, b in enumerate((900, 1300))]
    assert (np.abs(still[0] - still[1]).sum(axis=2) > 60).sum() == 0


def test_planar_mechanism_opens_orthographic_along_its_normal(cli, tmp_path):
    # The four-bar moves in z = 0: the page sees the plane's normal and opens square on,
    # orthographic; its pivots (0, 0) and (100, 0) mm are then level on the screen.
    page = tmp_path / "f.html"
    assert view(cli, os.path.join(ROOT, "mechanisms", "planar-four-bar.json"), page).returncode == 0
    data = page_data(page)
    assert np.allclose(np.abs(data["planar"]), [0, 0, 1], atol=1e-9)
    attrs, dom = browser.dump_dom(page, "t=0")
    assert attrs.get("data-camera") == "orthographic"
    attrs, _ = browser.dump_dom(page, "t=0&ortho=0")
    assert attrs.get("data-camera") == "perspective"
    spatial = page_data_of(cli, tmp_path, "bennett-linkage")
    assert spatial["planar"] is None


def page_data_of(cli, tmp_path, name, *args):
    page = tmp_path / (name + ".html")
    view(cli, os.path.join(ROOT, "mechanisms", name + ".json"), page, *args)
    return page_data(page)


@pytest.mark.parametrize("name,up", [("double-wishbone-suspension", "z"), ("stewart-platform", "z"), ("planar-four-bar", "y")])
def test_fit_frames_the_whole_motion(cli, tmp_path, name, up):
    # After the fit on open, the mechanism drawn over its run (four times, union of the
    # drawn boxes) covers at least a third of the 3D view, and no part leaves it.
    page = tmp_path / "m.html"
    assert view(cli, os.path.join(ROOT, "mechanisms", name + ".json"), page, "--up", up).returncode == 0
    union = None
    for t in ("0", "0.25", "0.5", "0.75"):
        img = pixels(browser.screenshot(page, tmp_path / "m.png", "t=" + t, size=BIG))[VIEW3D]
        sat = img.max(axis=2) - img.min(axis=2) > 50  # the bodies' colours (not the grey grid)
        dark = img.max(axis=2) < 110                   # joints, links, paths
        drawn = sat | dark
        union = drawn if union is None else union | drawn
    rows, cols = np.nonzero(union)
    h, w = union.shape
    area = (rows.max() - rows.min()) * (cols.max() - cols.min())
    assert area > h * w / 3, (area, h * w)
    assert rows.min() > 2 and cols.min() > 2 and rows.max() < h - 3 and cols.max() < w - 3


def svg_texts(dom):
    import re
    return re.findall(r"<text[^>]*>([^<]*)</text>", dom)


def test_plots_default_to_the_outputs(cli, tmp_path):
    import re
    page = tmp_path / "d.html"
    assert view(cli, os.path.join(ROOT, "mechanisms", "double-wishbone-suspension.json"), page, "--up", "z").returncode == 0
    attrs, dom = browser.dump_dom(page, "t=0.25", size=BIG)
    assert attrs.get("data-ready") == "1" and "data-errors" not in attrs
    # Two panels: the angles (deg) and the wheel centre (mm), each its own axis.
    panels = re.findall(r'<svg[^>]*class="plot".*?</svg>', dom, re.S)
    assert len(panels) == 2
    assert re.findall(r'data-name="([^"]+)"', panels[0]) == ["camber", "toe"]
    assert re.findall(r'data-name="([^"]+)"', panels[1]) == ["wheel_centre.x", "wheel_centre.y", "wheel_centre.z"]
    for p, unit in zip(panels, ("[deg]", "[mm]")):
        texts = svg_texts(p)
        assert unit in texts and "t [s]" in texts
        ticks = [float(t) for t in re.findall(r'class="tick"[^>]*>([^<]*)<', p)]
        assert len(ticks) >= 8
        assert {0.0, 0.2, 0.4, 0.6, 0.8, 1.0} <= set(ticks)  # the time axis, 0…1 s
        assert len(re.findall(r'class="grid"', p)) == len(ticks)
    # The legend names each series with its unit and its value at the cursor (t = 0.25 s).
    legends = re.findall(r'class="legend">([^<]*)<tspan[^>]*>([^<]*)</tspan>', dom)
    assert [name for name, _ in legends][:2] == ["camber [deg]", "toe [deg]"]
    table = tmp_path / "d.csv"
    subprocess.run([cli, "run", os.path.join(ROOT, "mechanisms", "double-wishbone-suspension.json"), "-o", str(table)],
                   check=True, capture_output=True)
    rows = list(csv.reader(open(table)))
    head = [h.split(" [")[0] for h in rows[0]]
    row = next(r for r in rows[1:] if abs(float(r[0]) - 0.25) < 1e-9)
    camber = float(row[head.index("camber")])
    assert abs(float(legends[0][1].replace("=", "")) - camber) <= 1e-4 * max(1, abs(camber))


def test_drivers_then_body_pose_when_no_outputs(cli, tmp_path):
    doc = json.load(open(os.path.join(ROOT, "mechanisms", "planar-four-bar.json")))
    doc["outputs"] = []
    src = tmp_path / "no-out.json"
    src.write_text(json.dumps(doc))
    page = tmp_path / "n.html"
    view(cli, str(src), page)
    plots = page_data(page)["plots"]
    # No outputs, no driver columns without forces: the crank's (the first moving body's) position.
    assert plots == [["crank.x", "crank.y"]]


def test_plots_option_chooses_the_panels(cli, tmp_path):
    import re
    src = os.path.join(ROOT, "mechanisms", "planar-four-bar.json")
    page = tmp_path / "c.html"
    assert view(cli, src, page, "--plots", "coupler_point.x,coupler_point.y;rocker_angle_t").returncode == 0
    attrs, dom = browser.dump_dom(page, "t=0.2", size=BIG)
    panels = re.findall(r'<svg[^>]*class="plot".*?</svg>', dom, re.S)
    assert [re.findall(r'data-name="([^"]+)"', p) for p in panels] == [["coupler_point.x", "coupler_point.y"], ["rocker_angle_t"]]
    bad = subprocess.run([cli, "view", src, "-o", str(tmp_path / "bad.html"), "--plots", "rocker_angle;nope"],
                         capture_output=True, text=True)
    assert bad.returncode == 2
    assert "no column 'nope'" in bad.stderr and "rocker_angle" in bad.stderr and "coupler_point.x" in bad.stderr
    assert not (tmp_path / "bad.html").exists()


def test_svg_and_csv_export(cli, tmp_path):
    import html
    import re
    import xml.etree.ElementTree as ET
    page = tmp_path / "e.html"
    src = os.path.join(ROOT, "mechanisms", "planar-four-bar.json")
    assert view(cli, src, page).returncode == 0
    _, dom = browser.dump_dom(page, "t=0.2&export=1", size=BIG)
    text = html.unescape(re.search(r'<pre id="export">(.*?)</pre>', dom, re.S).group(1))
    root = ET.fromstring(text.split("?>", 1)[1])  # a standalone SVG document
    ns = "{http://www.w3.org/2000/svg}"
    assert root.tag == ns + "svg"
    series = [p for p in root.iter(ns + "path") if p.get("class") == "series"]
    assert [p.get("data-name") for p in series] == ["coupler_point.x", "coupler_point.y"]
    assert len(series[0].get("d").split("L")) == len(page_data(page)["times"])
    assert "coupler_point.x [mm]" in [t.text for t in root.iter(ns + "text")]
    _, dom = browser.dump_dom(page, "t=0.2&export=csv", size=BIG)
    rows = list(csv.reader(html.unescape(re.search(r'<pre id="export">(.*?)</pre>', dom, re.S).group(1)).splitlines()))
    table = tmp_path / "f.csv"
    subprocess.run([cli, "run", src, "-o", str(table)], check=True, capture_output=True)
    ref = list(csv.reader(open(table)))
    assert rows[0][0] == "t [s]" and "rocker_angle [deg]" in rows[0]
    assert len(rows) == len(ref)  # 73 rows: not decimated
    k, j = rows[0].index("rocker_angle [deg]"), ref[0].index("rocker_angle [deg]")
    assert max(abs(float(a[k]) - float(b[j])) for a, b in zip(rows[1:], ref[1:])) < 1e-7


def test_partial_run_stop_is_marked_on_every_plot(cli, tmp_path):
    import re
    page = tmp_path / "dead.html"
    view(cli, os.path.join(ROOT, "tests", "data", "slider-crank-equal-links.json"), page)
    data = page_data(page)
    kinds = [m["kind"] for m in data["marks"]]
    assert "stop" in kinds and "singular" in kinds
    _, dom = browser.dump_dom(page, size=BIG)
    panels = re.findall(r'<svg[^>]*class="plot".*?</svg>', dom, re.S)
    assert panels and all('class="mark mark-singular"' in p for p in panels)


def test_output_point_paths_are_drawn(cli, tmp_path):
    # The coupler curve: the four-bar with and without its point output differs in the
    # 3D view by a closed curve's pixels.
    doc = json.load(open(os.path.join(ROOT, "mechanisms", "planar-four-bar.json")))
    shots = []
    for keep in (True, False):
        d = json.loads(json.dumps(doc))
        if not keep:
            d["outputs"] = [o for o in d["outputs"] if o["type"] != "point"]
            d["outputs"].append({"name": "p", "type": "distance", "body1": "coupler", "point1": doc["outputs"][1]["point"],
                                 "body2": "ground", "point2": [0, 0, 0]})
        src = tmp_path / ("p%d.json" % keep)
        src.write_text(json.dumps(d))
        page = tmp_path / ("p%d.html" % keep)
        view(cli, str(src), page)
        shots.append(pixels(browser.screenshot(page, tmp_path / ("p%d.png" % keep), "t=0&paused", size=BIG))[VIEW3D])
    assert (np.abs(shots[0] - shots[1]).sum(axis=2) > 30).sum() > 300


def test_set_changes_the_picture(cli, tmp_path):
    # `view --set` as `run --set`: another crank length, another picture (and page data).
    src = os.path.join(ROOT, "mechanisms", "parametric-four-bar.json")
    params = json.load(open(src)).get("parameters", {})
    name, value = "a", params["a"]["value"]  # the crank's length
    a, b = tmp_path / "a.html", tmp_path / "b.html"
    assert view(cli, src, a).returncode == 0
    assert view(cli, src, b, "--set", "%s=%r" % (name, value * 1.1)).returncode == 0
    assert page_data(a)["bodies"][0]["poses"] != page_data(b)["bodies"][0]["poses"]
    bad = subprocess.run([cli, "view", src, "-o", str(tmp_path / "c.html"), "--set", "nope"], capture_output=True, text=True)
    assert bad.returncode == 2


def test_bounds_and_plane_of_a_turning_bar(cli, tmp_path):
    # A bar from the pivot (0, 0, 0) to a tip (1, 0, 0) m turning a full turn about z in
    # 5° steps: the drawn points stay in the disc of radius 1 in z = 0 and reach (±1, ±1)
    # (the steps include 90°, 180°, 270°), so the whole run's box is [−1, 1]² × {0} and
    # the motion is planar with normal ±z.
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
    data = page_data(page)
    assert np.allclose(data["bounds"]["lo"], [-1, -1, 0], atol=1e-9)
    assert np.allclose(data["bounds"]["hi"], [1, 1, 0], atol=1e-9)
    assert np.allclose(np.abs(data["planar"]), [0, 0, 1], atol=1e-9)
    assert data["plots"] == [["tip.x", "tip.y"]]  # the output, without its constant z


def test_a_comment_opener_in_the_name_does_not_stop_the_page(cli, tmp_path):
    # "<!--<script>" in a script puts the HTML parser in its double-escaped state, where
    # the script's own end tag no longer ends it: the page never loaded (issue 24).
    doc = json.load(open(os.path.join(ROOT, "mechanisms", "planar-four-bar.json")))
    doc["name"] = "<!--<script>"
    path = tmp_path / "evil.json"
    path.write_text(json.dumps(doc))
    page = tmp_path / "evil.html"
    assert view(cli, str(path), page).returncode == 0
    html = page.read_text()
    data = html[html.index("window.MECHKIN_DATA="):]
    data = data[:data.index("</script>")]
    assert "<" not in data  # every '<' of the file's text is \u003c inside the data
    attrs, dom = browser.dump_dom(page, "t=0.1")
    assert attrs.get("data-ready") == "1", dom[-2000:]
    assert "data-errors" not in attrs, attrs.get("data-errors")
    assert "&lt;!--&lt;script&gt;" in dom  # the title shows the name as text


def test_a_probe_of_no_body_is_reported_and_the_page_still_loads(cli, tmp_path):
    page = tmp_path / "probe.html"
    assert view(cli, os.path.join(ROOT, "mechanisms", "planar-four-bar.json"), page).returncode == 0
    attrs, dom = browser.dump_dom(page, "probe=99999")
    assert attrs.get("data-ready") == "1", dom[-2000:]
    assert "#probe=99999: no body with that index" in attrs.get("data-errors", ""), attrs
    assert "data-probe" not in attrs


# --- issue 28: clearance marks and contacts ----------------------------------------------------

def _slider_past_mesh_box(tmp_path):
    """A 20 mm box on a slider (given as an OBJ mesh of 6 quads) pushed at 100 mm/s towards
    a fixed 20 mm box centred at x = 103.3 mm: the faces meet at t = 0.833 s."""
    corners = [((k & 1) * 20 - 10, (k >> 1 & 1) * 20 - 10, (k >> 2 & 1) * 20 - 10) for k in range(8)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    (tmp_path / "box.obj").write_text("".join("v %g %g %g\n" % c for c in corners) +
                                      "".join("f %d %d %d %d\n" % tuple(i + 1 for i in q) for q in quads))
    doc = {"mechkin": 1, "name": "slider past a box", "units": {"length": "mm", "angle": "deg"},
           "ground": {"shapes": [{"type": "box", "size": [20, 20, 20], "center": [103.3, 0, 0]}]},
           "bodies": [{"name": "slider", "position": [0, 0, 0], "shape": {"type": "mesh", "file": "box.obj"}}],
           "joints": [{"name": "P", "type": "prismatic", "body1": "ground", "body2": "slider",
                       "origin": [0, 0, 0], "axis": [1, 0, 0]}],
           "drivers": [{"name": "push", "type": "translation", "joint": "P", "function": "100*t"}],
           "analysis": {"start": 0, "end": 1, "steps": 100},
           "outputs": [{"name": "gap", "type": "clearance", "body1": "slider", "body2": "ground"}]}
    src = tmp_path / "slider.json"
    src.write_text(json.dumps(doc))
    return src


def test_clearance_marks_are_the_closest_point_columns_and_contacts_turn_red(cli, tmp_path):
    src = _slider_past_mesh_box(tmp_path)
    page, table = tmp_path / "gap.html", tmp_path / "gap.csv"
    assert view(cli, str(src), page).returncode == 0
    subprocess.run([cli, "run", str(src), "-o", str(table)], check=True, capture_output=True)
    rows = list(csv.reader(open(table)))
    head, values = [h.split(" [")[0] for h in rows[0]], np.array([[float(x) for x in r] for r in rows[1:]])
    cols = [head.index("gap.point%d.%s" % (p, a)) for p in (1, 2) for a in "xyz"]
    data = page_data(page)
    assert [s["type"] for s in data["bodies"][0]["shapes"]] == ["mesh"] and len(data["bodies"][0]["shapes"][0]["triangles"]) == 36
    assert [s["type"] for s in data["ground_shapes"]] == ["box"]
    for row in (0, 37, 50, 83):
        t = values[row, 0]
        attrs, dom = browser.dump_dom(page, "t=%r" % t)
        assert attrs.get("data-ready") == "1" and "data-errors" not in attrs, attrs.get("data-errors")
        name, marks = attrs["data-clearance"].split(":")
        drawn = np.array([float(x) for x in marks.split(",")])
        print("[measured] t = %g s: the page's marks off the table's closest points by %.2e mm" %
              (t, np.abs(drawn - values[row, cols]).max()))
        assert name == "gap" and np.abs(drawn - values[row, cols]).max() < 1e-9
        assert attrs["data-contact"] == "" and attrs["data-red-bodies"] == ""
        assert abs(float(attrs["data-first-contact"]) - 0.833) < 1e-9
        assert "first contact of `slider` and `ground` at t = 0.833 s" in dom
    # After the contact the two bodies' shapes are drawn red (ground −1, the slider 0):
    # more red pixels in the 3D view than before it.
    attrs, _ = browser.dump_dom(page, "t=0.9")
    assert attrs["data-contact"] == "gap" and attrs["data-red-bodies"] == "-1,0"
    def red(t):
        img = pixels(browser.screenshot(page, tmp_path / ("r%s.png" % t), "t=%s&view=front" % t))[60:680, 0:690]
        return ((img[..., 0] > img[..., 1] + 80) & (img[..., 0] > img[..., 2] + 80)).sum()
    before, after = red("0.8"), red("0.9")
    print("[measured] red pixels in the 3D view: %d before the contact, %d after" % (before, after))
    assert after > before + 500
