"""`mechkin view --live` (issue 30) in headless Chromium: the page re-solves the file in
the browser with mechkin's WebAssembly core when a slider moves, and its numbers are
the CLI's. The page's test hooks (src/io/viewer/live.js): `#live=NAME:VALUE,...` moves
the sliders after load exactly as a hand does (the input's value, then its input
event), the last table as CSV in #export, the outcome in the body's data-live-*.
Needs the module (CMake MECHKIN_LIVE, Debian's emscripten); the README's test command
builds it."""
import csv
import json
import io
import os
import re
import subprocess
import sys

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import view_screenshot as browser  # noqa: E402

FOUR_BAR = os.path.join(ROOT, "mechanisms", "parametric-four-bar.json")


@pytest.fixture(scope="module")
def page(cli, tmp_path_factory):
    out = tmp_path_factory.mktemp("live") / "live.html"
    proc = subprocess.run([cli, "view", "--live", FOUR_BAR, "-o", str(out)], capture_output=True, text=True)
    assert proc.returncode == 0 and out.exists(), proc.stderr
    return out


def live(page, moves):
    """The page after the scripted slider moves: (body attributes, the last table)."""
    attrs, dom = browser.dump_dom(page, "live=" + ",".join("%s:%r" % m for m in moves), budget=20000)
    assert attrs.get("data-live-ready") == "1", {k: v[:200] for k, v in attrs.items()}
    text = re.search(r'id="export"[^>]*>(.*?)</', dom, re.S).group(1)
    return attrs, table(text.replace("&amp;", "&"))


def table(text):
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], np.array([[float(v) for v in r] for r in rows[1:] if r])


def cli_table(cli, tmp_path, *sets):
    out = tmp_path / "run.csv"
    args = [a for s in sets for a in ("--set", s)]
    proc = subprocess.run([cli, "run", FOUR_BAR, *args, "-o", str(out)], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    return table(out.read_text())


def motion_columns(names):
    """Every column but the round-off diagnostics (residual, error_bound*): those are
    the size of the last unit in the place (WebAssembly's libm and fused operations
    are not the native build's), and are compared by what they say instead."""
    return [i for i, n in enumerate(names) if not n.startswith(("residual", "error_bound"))]


def same_run(names, values, expected):
    """The worst difference of the motion columns relative to each column's scale, after
    checking that both runs' residuals met the file's tolerance (1e-10)."""
    at = names.index("residual")
    assert values[:, at].max() <= 1e-10 and expected[:, at].max() <= 1e-10
    cols = motion_columns(names)
    scale = np.maximum(np.abs(expected[:, cols]).max(axis=0), 1e-300)
    return (np.abs(values[:, cols] - expected[:, cols]) / scale).max()


def coupler_curve(attrs, move):
    """The first trace (the coupler point) as the page drew it after move `move`."""
    state, points = attrs["data-live-move-%d" % move].split(";", 1)
    return state, np.array([[float(x) for x in p.split()] for p in points.split("|")])


def test_a_crank_slider_re_solves_to_the_cli_numbers(cli, page, tmp_path):
    attrs, (names, values) = live(page, [("a", 45)])
    state, curve = coupler_curve(attrs, 0)
    assert state == "ok" and attrs["data-live-set"] == "a=45"
    cli_names, expected = cli_table(cli, tmp_path, "a=45")
    assert names == cli_names and values.shape == expected.shape == (73, len(names))
    # The same numbers as `mechkin run --set a=45` to 1e-12 of each column's scale.
    assert len(motion_columns(names)) > 90  # the bodies, outputs and their rates
    worst = same_run(names, values, expected)
    assert worst <= 1e-12, worst
    # And a different mechanism: the coupler curve moved (the 40 mm crank's is the CLI's
    # default run), by millimetres, not round-off.
    _, default = cli_table(cli, tmp_path)
    at = names.index("coupler.x [mm]")
    assert np.abs(values[:, at] - default[:, at]).max() > 1
    assert np.abs(curve[:, :2]).max() > 10  # the page drew the curve it solved
    assert attrs["data-live-mobility"] == "1"


def test_where_the_loop_cannot_close_the_last_pose_stays(cli, page, tmp_path):
    # A frame of 85 mm keeps the crank-rocker whole (Grashof: 40 + 120 < 80 + 85); then a
    # 160 mm coupler: |b − c| = 80 mm exceeds the 73.7 mm from B to D at the design pose,
    # no assembly, and the file's acos says so.
    attrs, (names, values) = live(page, [("d", 85), ("b", 160)])
    first, _ = coupler_curve(attrs, 0)
    second, _ = coupler_curve(attrs, 1)
    assert (first, second) == ("ok", "failed")
    assert attrs["data-live-message"].startswith("cannot close: "), attrs["data-live-message"]
    # The table kept is the last valid one: d = 85, b at its value.
    _, expected = cli_table(cli, tmp_path, "d=85")
    assert values.shape == expected.shape
    assert same_run(names, values, expected) <= 1e-12


def test_a_slider_after_a_failure_starts_from_the_value_in_use(cli, page, tmp_path):
    # The failed coupler move puts b back (to the override and to its slider); the next
    # move (the crank) re-solves with d = 85, b = 120, a = 42 (Grashof: 42 + 120 < 80 + 85),
    # as the CLI does.
    attrs, (names, values) = live(page, [("d", 85), ("b", 160), ("a", 42)])
    assert attrs["data-live-kept"] == "b=120"
    assert coupler_curve(attrs, 2)[0] == "ok" and attrs["data-live-message"] == ""
    cli_names, expected = cli_table(cli, tmp_path, "d=85", "a=42")
    assert names == cli_names and same_run(names, values, expected) <= 1e-12


def test_what_the_live_core_leaves_out_is_refused_by_name(cli, tmp_path):
    doc = json.load(open(FOUR_BAR))
    for b in doc["bodies"]:
        b["shape"] = {"type": "box", "size": [5, 5, 5]}
    doc["outputs"] = doc.get("outputs", []) + [{"name": "gap", "type": "clearance", "body1": "crank", "body2": "rocker"}]
    src = tmp_path / "with-clearance.json"
    src.write_text(json.dumps(doc))
    out = tmp_path / "page.html"
    proc = subprocess.run([cli, "view", "--live", str(src), "-o", str(out)], capture_output=True, text=True)
    assert proc.returncode == 1 and not out.exists()
    assert "output `gap`: the live page cannot measure clearance outputs" in proc.stderr, proc.stderr
