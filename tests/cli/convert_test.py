#!/usr/bin/env python3
"""`mechkin convert` (issue 22): the same mechanism and the same motion in both forms.

1. Every bundled mechanism converted to markers, that file converted back to
   global, runs to the same table as the original: every motion column within
   1e-12 of its scale (the largest |value| among the columns of its unit — a
   column that is zero in exact arithmetic holds round-off of its quantity's
   size — or 1 when all are 0). The solver's diagnostics (newton_iterations,
   residual, condition, error_bound…) are not motion and are left out. A file
   `run` refuses is refused alike in every form.
2. `check --format json` reports of the original and of the file converted back
   agree (apart from the file name); the markers form has the same counts.
3. --set on the converted parametric files gives the original's table.
4. Expression texts: an unrotated body's marker keeps the parameters; a rotated
   body's does not and stderr names the key; markers that do not coincide are
   refused; the input is never overwritten; -o - writes stdout.
Usage: convert_test.py SOURCE_DIR MECHKIN_BINARY
"""
import copy
import csv
import io
import json
import math
import os
import subprocess
import sys
import tempfile

DIAGNOSTICS = ("newton_iterations", "residual", "condition", "error_bound")
failures = []


def run(exe, *args, stdin=None):
    return subprocess.run([exe, *args], capture_output=True, text=True, input=stdin)


def table(exe, path, *extra):
    # A position tolerance past the comparison's: at the default 1e-10 the Newton
    # solve may stop one iterate earlier in one form (the spatial RUSR at row 241:
    # 3 iterations against 2, a velocity 2.6e-12 of its scale apart).
    out = run(exe, "run", path, "--tol", "1e-12", *extra)
    if out.returncode != 0:
        return None, out.stderr.replace(path, "FILE")
    rows = list(csv.reader(io.StringIO(out.stdout)))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


def unit(name):
    return name[name.find("["):] if "[" in name else ""


def worst_difference(a, b):
    """Largest |a − b| / scale over the motion columns, and its column."""
    head, rows_a = a
    rows_b = b[1]
    scales = {}
    for c, name in enumerate(head):
        if not name.startswith(DIAGNOSTICS):
            m = max((abs(r[c]) for r in rows_a if not math.isnan(r[c])), default=0)
            scales[unit(name)] = max(scales.get(unit(name), 0), m)
    worst, where = 0.0, None
    for c, name in enumerate(head):
        if name.startswith(DIAGNOSTICS):
            continue
        scale = scales[unit(name)] or 1
        for ra, rb in zip(rows_a, rows_b):
            x, y = ra[c], rb[c]
            if math.isnan(x) and math.isnan(y):
                continue
            d = abs(x - y) / scale if not (math.isnan(x) or math.isnan(y)) else math.inf
            if d > worst:
                worst, where = d, name
    return worst, where


def same_table(exe, original, converted, label, *extra):
    a, b = table(exe, original, *extra), table(exe, converted, *extra)
    if a[0] is None or b[0] is None:
        if a != b:
            failures.append("%s: refused differently: %r / %r" % (label, a[1], b[1]))
        return
    if a[0] != b[0] or len(a[1]) != len(b[1]):
        failures.append("%s: columns or rows differ" % label)
        return
    worst, where = worst_difference(a, b)
    print("%-48s %.2e  %s" % (label, worst, where or ""))
    if worst > 1e-12:
        failures.append("%s: column %s differs by %.3g of its scale" % (label, where, worst))


def convert(exe, src, dst, *extra):
    out = run(exe, "convert", src, "-o", dst, *extra)
    if out.returncode != 0:
        failures.append("convert %s: exit %d: %s" % (src, out.returncode, out.stderr))
    return out


def check_json(exe, path):
    out = run(exe, "check", path, "--format", "json")
    report = json.loads(out.stdout)["files"][0]
    report.pop("file", None)
    return report


def roundtrip_markers_original(exe, original, f, tmp):
    """A bundled file written on markers (positions placed by the assembly): to the
    global form and back to markers, each running to the original's table."""
    back = os.path.join(tmp, f[:-5] + ".global.json")
    again = os.path.join(tmp, f[:-5] + ".markers2.json")
    convert(exe, original, back, "--to", "global")
    doc = json.load(open(back))
    if any("marker1" in j for j in doc["joints"]) or any("markers" in b for b in doc["bodies"]):
        failures.append("%s: the global form kept markers" % f)
    same_table(exe, original, back, f + " -> global")
    convert(exe, back, again, "--to", "markers")
    same_table(exe, original, again, f + " -> global -> markers")
    a, g = check_json(exe, original), check_json(exe, back)
    for key in ("mobility", "redundant", "driven"):
        if a["mobility"].get(key) != g["mobility"].get(key):
            failures.append("%s: check's %r differs in the global form" % (f, key))


def roundtrip_bundled(src, exe, tmp):
    mech = os.path.join(src, "mechanisms")
    for f in sorted(os.listdir(mech)):
        if not f.endswith(".json"):
            continue
        original = os.path.join(mech, f)
        if any("marker1" in j for j in json.load(open(original))["joints"]):
            roundtrip_markers_original(exe, original, f, tmp)
            continue
        markers = os.path.join(tmp, f[:-5] + ".markers.json")
        back = os.path.join(tmp, f[:-5] + ".global.json")
        convert(exe, original, markers, "--to", "markers")
        convert(exe, markers, back)  # the default: the other form
        doc = json.load(open(markers))
        if any("origin" in j or "point1" in j for j in doc["joints"]):
            failures.append("%s: the markers form kept global joint geometry" % f)
        if "markers" in open(back).read():
            failures.append("%s: the global form kept markers" % f)
        same_table(exe, original, markers, f + " -> markers")
        same_table(exe, original, back, f + " -> markers -> global")
        again = os.path.join(tmp, f[:-5] + ".markers2.json")
        convert(exe, back, again, "--to", "markers")
        if open(again).read() != open(markers).read():
            failures.append("%s: converting the global form back to markers gives another file" % f)
        if json.load(open(back)) != json.load(open(original)):
            failures.append("%s: markers -> global does not give the original document back" % f)
        if check_json(exe, original) != check_json(exe, back):
            failures.append("%s: check reports of the original and the converted-back file differ" % f)
        a, m = check_json(exe, original), check_json(exe, markers)
        for key in ("valid", "bodies", "joints", "drivers", "grubler", "expect", "errors"):
            if a.get(key) != m.get(key):
                failures.append("%s: check's %r differs in the markers form: %r / %r" % (f, key, a.get(key), m.get(key)))
        for key in ("mobility", "redundant", "driven"):
            if a["mobility"].get(key) != m["mobility"].get(key):
                failures.append("%s: check's mobility.%s differs in the markers form" % (f, key))


def parametric_set(src, exe, tmp):
    cases = {"parametric-four-bar": ["--set", "a=45", "--set", "d=95"],
             "parametric-slider-crank": ["--set", "crank=45", "--set", "offset=4"]}
    for stem, sets in cases.items():
        original = os.path.join(src, "mechanisms", stem + ".json")
        markers = os.path.join(tmp, stem + ".markers.json")
        back = os.path.join(tmp, stem + ".global.json")
        text = open(markers).read()
        if '"xb - xb/2"' not in text and '"pin_x - pin_x/2"' not in text:
            failures.append("%s: the markers form lost the parameter expressions" % stem)
        same_table(exe, original, markers, stem + " --set, markers", *sets)
        same_table(exe, original, back, stem + " --set, back", *sets)
        moved = table(exe, original, *sets)[1][0] != table(exe, original)[1][0]
        if not moved:
            failures.append("%s: --set changed nothing (the test would not see a lost dependence)" % stem)


# An open chain fully driven: the crank drawn rotated by 30 deg (its marker of the
# elbow cannot keep "r"), the arm unrotated (its marker keeps "r" exactly).
ROTATED = {
    "mechkin": 1, "units": {"length": "mm", "angle": "deg"},
    "parameters": {"r": 40},
    "bodies": [{"name": "crank", "position": [10, 0, 0], "orientation": {"axis": [0, 0, 1], "angle": 30}},
               {"name": "arm", "position": ["r", 10, 0]}],
    "joints": [
        {"name": "bearing", "type": "revolute", "body1": "ground", "body2": "crank", "origin": [0, 0, 0],
         "axis": [0, 0, 1]},
        {"name": "elbow", "type": "revolute", "body1": "crank", "body2": "arm", "origin": ["r", 0, 0],
         "axis": [0, 0, 1]}],
    "drivers": [{"name": "motor", "type": "rotation", "joint": "bearing", "function": "20*sin(2*pi*t)"},
                {"name": "bend", "type": "rotation", "joint": "elbow", "function": "45*t"}],
    "analysis": {"start": 0, "end": 1, "steps": 20},
    "outputs": [{"name": "tip", "type": "point", "body": "arm", "point": ["r", 30, 0]}]}


def notes_and_refusals(exe, tmp):
    path = os.path.join(tmp, "rotated.json")
    json.dump(ROTATED, open(path, "w"))
    out = convert(exe, path, os.path.join(tmp, "rotated.markers.json"))
    notes = [line for line in out.stderr.splitlines() if "note:" in line]
    if len(notes) != 1 or "/joints/1/origin" not in notes[0] or "body 'crank'" not in notes[0]:
        failures.append("rotated body: not one note naming /joints/1/origin on the crank: %r" % out.stderr)
    conv = json.load(open(os.path.join(tmp, "rotated.markers.json")))
    if conv["bodies"][1]["markers"]["elbow"]["point"] != [0, -10, 0]:
        failures.append("the arm's elbow marker is not r - r, -10: %r" % conv["bodies"][1]["markers"]["elbow"])
    crank_elbow = conv["bodies"][0]["markers"]["elbow"]["point"]
    if abs(crank_elbow[0] - 30 * math.cos(math.radians(30))) > 1e-12 or abs(crank_elbow[1] + 15) > 1e-12:
        failures.append("the crank's elbow marker is not (r - 10) turned by -30 deg: %r" % crank_elbow)
    same_table(exe, path, os.path.join(tmp, "rotated.markers.json"), "rotated crank -> markers")
    # At r = 50 the arm's marker follows; the crank's stays at r = 40: the tables part.
    a = table(exe, path, "--set", "r=50")
    b = table(exe, os.path.join(tmp, "rotated.markers.json"), "--set", "r=50")
    if worst_difference(a, b)[0] < 1e-3:
        failures.append("--set r=50 moved the rotated crank's marker though the note says it cannot")
    # A body that already has a marker named after the joint gets a suffixed one.
    taken = copy.deepcopy(ROTATED)
    taken["bodies"][1]["markers"] = {"elbow": {"point": [1, 2, 3]}}
    json.dump(taken, open(os.path.join(tmp, "taken.json"), "w"))
    out = run(exe, "convert", os.path.join(tmp, "taken.json"))
    conv = json.loads(out.stdout) if out.returncode == 0 else {"joints": [{}, {}]}
    if conv["joints"][1].get("marker2") != "elbow_2" or conv["bodies"][1]["markers"].get("elbow") != {"point": [1, 2, 3]}:
        failures.append("a taken marker name: %r" % conv["joints"][1])
    # Markers that do not coincide at the design pose cannot become one global frame.
    bad = json.load(open(os.path.join(tmp, "rotated.markers.json")))
    bad["bodies"][1]["markers"]["elbow"]["point"] = [5, -10, 0]
    json.dump(bad, open(os.path.join(tmp, "apart.json"), "w"))
    # Markers 5 mm apart in the drawing: the assembly closes them (positions are only
    # a sketch) and moves the arm, whose output is a global design point: convert
    # refuses, naming it, and writes nothing; on a marker, the file converts.
    out = run(exe, "convert", os.path.join(tmp, "apart.json"), "-o", os.path.join(tmp, "apart.global.json"))
    if out.returncode != 1 or "/outputs/0" not in out.stderr or "body 'arm'" not in out.stderr:
        failures.append("markers apart: exit %d, %r" % (out.returncode, out.stderr))
    if os.path.exists(os.path.join(tmp, "apart.global.json")):
        failures.append("markers apart: a file was written")
    bad["bodies"][1]["markers"]["tip"] = {"point": [5, 20, 0]}
    bad["outputs"][0] = {"name": "tip", "type": "point", "body": "arm", "marker": "tip"}
    json.dump(bad, open(os.path.join(tmp, "apart_marker.json"), "w"))
    out = run(exe, "convert", os.path.join(tmp, "apart_marker.json"), "-o", os.path.join(tmp, "apart.global.json"))
    if out.returncode != 0:
        failures.append("markers apart, output on a marker: exit %d, %r" % (out.returncode, out.stderr))
    else:
        same_table(exe, os.path.join(tmp, "apart_marker.json"), os.path.join(tmp, "apart.global.json"),
                   "markers apart in the sketch -> global")
    out = run(exe, "convert", path, "-o", path)
    if out.returncode != 1 or json.load(open(path)) != ROTATED:
        failures.append("convert -o INPUT: exit %d, or the input changed" % out.returncode)
    out = run(exe, "convert", path, "-o", "-")
    if out.returncode != 0 or json.loads(out.stdout)["joints"][0].get("marker1") != "bearing":
        failures.append("convert -o -: exit %d" % out.returncode)
    out = run(exe, "convert", path, "--to", "sideways")
    if out.returncode != 2:
        failures.append("--to sideways: exit %d, expected 2" % out.returncode)
    out = run(exe, "convert", os.path.join(tmp, "missing.json"))
    if out.returncode != 1 or "cannot open" not in out.stderr:
        failures.append("missing file: exit %d, %r" % (out.returncode, out.stderr))


def written_on_markers(src, exe, tmp):
    """A file written on markers by hand (default marker frames, a point output on a marker)."""
    original = os.path.join(src, "tests", "data", "four-bar-markers.json")
    back = os.path.join(tmp, "four-bar-markers.global.json")
    convert(exe, original, back)
    doc = json.load(open(back))
    if "ground" in doc or any("markers" in b for b in doc["bodies"]):
        failures.append("four-bar-markers: markers left in the global form")
    tracer = doc["outputs"][1]
    if "marker" in tracer or [round(x, 9) for x in tracer["point"]] != [76.940482998, 53.556126406, 0]:
        failures.append("four-bar-markers: the tracer output is not the coupler's origin: %r" % tracer)
    same_table(exe, original, back, "four-bar-markers.json -> global")
    # Already on markers: --to markers changes nothing.
    same = run(exe, "convert", original, "--to", "markers")
    if same.returncode != 0 or json.loads(same.stdout) != json.load(open(original)):
        failures.append("four-bar-markers --to markers is not the same document")
    same_table(exe, os.path.join(src, "mechanisms", "planar-four-bar.json"), back, "planar-four-bar vs four-bar-markers -> global")


def main():
    src, exe = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        roundtrip_bundled(src, exe, tmp)
        written_on_markers(src, exe, tmp)
        parametric_set(src, exe, tmp)
        notes_and_refusals(exe, tmp)
    for f in failures:
        print("FAIL", f)
    print("%d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
