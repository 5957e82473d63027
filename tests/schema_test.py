#!/usr/bin/env python3
"""Keeps schema/mechkin-format-v1.schema.json honest against the loader.

1. Every bundled mechanism validates against the schema (and `mechkin check` accepts it).
2. Every invalid file whose defect is structural is rejected by BOTH the schema and
   the loader. Defects the schema cannot express (name references, duplicates,
   geometry such as non-perpendicular universal axes) are listed in SEMANTIC and
   must still be rejected by the loader.
Usage: schema_test.py SOURCE_DIR MECHKIN_BINARY
"""
import json
import os
import subprocess
import sys

import jsonschema

SEMANTIC = {
    "duplicate-body", "unknown-body-ref", "joint-to-itself", "duplicate-joint", "universal-not-perpendicular",
    "driver-on-spherical", "translation-on-revolute", "driver-unknown-joint", "driver-bad-expression",
    "driver-unknown-function", "driver-table-unsorted", "end-before-start", "orientation-not-rotation",
    "output-sequence-on-revolute", "distance-zero-length",
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
    for f in sorted(os.listdir(mech_dir)):
        if not f.endswith(".json"):
            continue
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
    print("%d passed, %d failed" % (passed, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
