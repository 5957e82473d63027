#!/usr/bin/env python3
"""Keeps schema/mechkin-format-v1.schema.json honest against the loader.

1. Every bundled mechanism validates against the schema (and `mechkin check` accepts it).
2. Every invalid file whose defect is structural is rejected by BOTH the schema and
   the loader. Defects the schema cannot express (name references, duplicates,
   geometry such as non-perpendicular universal axes) are listed in SEMANTIC and
   must still be rejected by the loader.
3. Markers (issue 22): a file on markers validates (tests/data/four-bar-markers.json
   and every bundled mechanism after `mechkin convert --to markers`); a joint giving
   both global geometry and markers, and a point output giving both a point and a
   marker, are rejected by both the schema and the loader.
Usage: schema_test.py SOURCE_DIR MECHKIN_BINARY
"""
import json
import os
import copy
import subprocess
import sys
import tempfile

import jsonschema

SEMANTIC = {
    "duplicate-body", "unknown-body-ref", "joint-to-itself", "duplicate-joint", "universal-not-perpendicular",
    "driver-on-spherical", "translation-on-revolute", "driver-unknown-joint", "driver-bad-expression",
    "driver-unknown-function", "driver-table-unsorted", "end-before-start", "orientation-not-rotation",
    "output-sequence-on-revolute", "distance-zero-length", "clearance-unknown-body",
    "position-nan-string",  # a string is an expression since parameters: "NaN" names no parameter
}
# Not JSON at all (or not parseable by Python's json): only the loader is asked.
NOT_JSON = {"json-syntax-error", "empty-file", "binary-file", "deeply-nested", "position-huge"}


def main():
    src, exe = sys.argv[1], sys.argv[2]
    schema = json.load(open(os.path.join(src, "schema", "mechkin-format-v1.schema.json")))
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    failures = 0
    passed = 0
    mech_dir = os.path.join(src, "mechanisms")
    # the bundled mechanisms and the worked synthesis examples (mechanisms/synthesis)
    bundled = [f for f in sorted(os.listdir(mech_dir)) if f.endswith(".json")]
    bundled += [os.path.join("synthesis", f) for f in sorted(os.listdir(os.path.join(mech_dir, "synthesis")))
                if f.endswith(".json")]
    for f in bundled:
        errs = list(validator.iter_errors(json.load(open(os.path.join(mech_dir, f)))))
        if errs:
            failures += 1
            print("FAIL bundled %s rejected by the schema: %s" % (f, errs[0].message))
        else:
            passed += 1
    inv_dir = os.path.join(src, "tests", "invalid")
    for line in open(os.path.join(inv_dir, "expected.tsv")):
        name = line.split("\t")[0]
        stem = name[:-5]
        path = os.path.join(inv_dir, name)
        rc = subprocess.run([exe, "check", path], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
        if rc != 1:
            failures += 1
            print("FAIL %s: loader exit %d, expected 1" % (name, rc))
            continue
        if stem in NOT_JSON or stem in SEMANTIC:
            passed += 1
            continue
        doc = json.load(open(path, encoding="latin-1"))
        if validator.is_valid(doc):
            failures += 1
            print("FAIL %s: accepted by the schema but rejected by the loader" % name)
        else:
            passed += 1
    p, f = check_markers(src, exe, validator)
    passed += p
    failures += f
    print("%d passed, %d failed" % (passed, failures))
    return 1 if failures else 0


def loader_rejects(exe, doc):
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(doc, f)
    try:
        return subprocess.run([exe, "check", f.name], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 1
    finally:
        os.unlink(f.name)


def check_markers(src, exe, validator):
    passed, failures = 0, 0

    def expect(ok, what):
        nonlocal passed, failures
        if ok:
            passed += 1
        else:
            failures += 1
            print("FAIL " + what)

    doc = json.load(open(os.path.join(src, "tests", "data", "four-bar-markers.json")))
    errs = list(validator.iter_errors(doc))
    expect(not errs, "four-bar-markers.json rejected by the schema: %s" % (errs[0].message if errs else ""))
    mixed = copy.deepcopy(doc)
    mixed["joints"][1]["origin"] = [20, 34.641016151378, 0]
    expect(not validator.is_valid(mixed), "a joint with both origin and markers accepted by the schema")
    expect(loader_rejects(exe, mixed), "a joint with both origin and markers accepted by the loader")
    half = copy.deepcopy(doc)
    del half["joints"][1]["marker2"]
    expect(not validator.is_valid(half), "a joint with marker1 only accepted by the schema")
    expect(loader_rejects(exe, half), "a joint with marker1 only accepted by the loader")
    both = copy.deepcopy(doc)
    both["outputs"][1]["point"] = [0, 0, 0]
    expect(not validator.is_valid(both), "a point output with both point and marker accepted by the schema")
    expect(loader_rejects(exe, both), "a point output with both point and marker accepted by the loader")
    bad_name = copy.deepcopy(doc)
    bad_name["bodies"][0]["markers"]["9pin"] = {"point": [0, 0, 0]}
    expect(not validator.is_valid(bad_name), "a marker named '9pin' accepted by the schema")
    expect(loader_rejects(exe, bad_name), "a marker named '9pin' accepted by the loader")
    mech_dir = os.path.join(src, "mechanisms")
    for f in sorted(os.listdir(mech_dir)):
        if not f.endswith(".json"):
            continue
        out = subprocess.run([exe, "convert", os.path.join(mech_dir, f), "--to", "markers"], capture_output=True, text=True)
        errs = list(validator.iter_errors(json.loads(out.stdout))) if out.returncode == 0 else ["convert failed"]
        expect(not errs, "%s in the markers form rejected by the schema: %s" % (f, errs[0] if errs else ""))
    return passed, failures


if __name__ == "__main__":
    sys.exit(main())
