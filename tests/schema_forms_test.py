#!/usr/bin/env python3
"""No "internal error" from any schema-valid file (issue 23).

The schema admits forms the code may not support: every enum value in every slot,
every optional key on every element. This test makes those forms from the repository's
own files and feeds each schema-valid one to `check`, `run`, `range` and `view`:

1. enum forms: for every element of every list (bodies, joints, couplers, drivers,
   outputs, loads, markers) and every key the schema gives an enum, each enum value;
2. optional-key forms: every key some element of the same list carries in another
   file (the donor's value), added to an element that lacks it;
3. section forms: every key of analysis, units, view, expect, ground some file has,
   added where it is missing (branch hints and flips included);
4. top-level forms: every top-level key of any file added to a file that lacks it.

A form is kept once per (list, element type, key, value) signature, in the first file
it validates in. Each command must end with exit 0, 1 or 2 (no signal, no abort) and
print neither "internal error" nor a C++ exception name. Schema-invalid forms are
skipped (the loader's rejection of those is schema_test.py's business).
Usage: schema_forms_test.py SOURCE_DIR MECHKIN_BINARY
"""
import concurrent.futures
import copy
import glob
import json
import os
import subprocess
import sys
import tempfile

import jsonschema

SECTIONS = ["analysis", "units", "view", "expect", "ground", "gravity"]
LISTS = ["bodies", "joints", "couplers", "drivers", "outputs", "loads"]
FORBIDDEN = ["internal error", "std::", "terminate called", "basic_string", "out_of_range", "bad_alloc"]


def load_sources(src):
    files = sorted(glob.glob(os.path.join(src, "mechanisms", "*.json")))
    files += sorted(glob.glob(os.path.join(src, "tests", "data", "*.json")))
    out = []
    for f in files:
        with open(f, encoding="utf-8") as h:
            out.append((os.path.basename(f), json.load(h)))
    return out


def enums_by_key(node, found):
    """Every property name the schema constrains to an enum, with the union of its values."""
    if isinstance(node, dict):
        for key, sub in node.get("properties", {}).items():
            if isinstance(sub, dict) and "enum" in sub:
                found.setdefault(key, [])
                for v in sub["enum"]:
                    if v not in found[key]:
                        found[key].append(v)
        for v in node.values():
            enums_by_key(v, found)
    elif isinstance(node, list):
        for v in node:
            enums_by_key(v, found)
    return found


def elements(doc):
    """(list name, index, element) for every element of the lists, markers of bodies included."""
    for name in LISTS:
        for i, e in enumerate(doc.get(name, []) if isinstance(doc.get(name), list) else []):
            if isinstance(e, dict):
                yield name, i, e
    for i, b in enumerate(doc.get("bodies", [])):
        for k, m in enumerate(b.get("markers", []) if isinstance(b, dict) else []):
            if isinstance(m, dict):
                yield "bodies/%d/markers" % i, k, m


def set_element(doc, where, index, value):
    if "/" in where:
        _, b, _ = where.split("/")
        doc["bodies"][int(b)]["markers"][index] = value
    else:
        doc[where][index] = value


REFERENCES = {"name", "body", "body1", "body2", "joint", "joint1", "joint2", "joints", "frame", "marker",
              "marker1", "marker2", "output", "input", "of", "driver"}


def donors(sources):
    """Per (list name, element type): the first element seen, and key → first value seen."""
    first, keys = {}, {}
    for _, doc in sources:
        for where, _, e in elements(doc):
            sig = (where.split("/")[-1], e.get("type", ""))
            first.setdefault(sig, e)
            for k, v in e.items():
                keys.setdefault(sig, {}).setdefault(k, v)
    return first, keys


def retyped(e, donor):
    """The donor element (another type) on e's references: the same place, another form."""
    m = copy.deepcopy(donor)
    for k in REFERENCES:
        if k in e and k in m:
            m[k] = e[k]
    return m


def forms(sources, schema):
    validator = jsonschema.Draft202012Validator(schema)
    enums = enums_by_key(schema, {})
    first, keys = donors(sources)
    top, sections = {}, {}
    for _, doc in sources:
        for k, v in doc.items():
            top.setdefault(k, v)
            if k in SECTIONS and isinstance(v, dict):
                for key, value in v.items():
                    sections.setdefault(k, {}).setdefault(key, value)
    seen, out = set(), []

    def offer(signature, doc, label):
        if signature in seen or not validator.is_valid(doc):
            return
        seen.add(signature)
        out.append((label, doc))

    def variant(doc, where, i, m):
        d = copy.deepcopy(doc)
        set_element(d, where, i, m)
        return d

    for fname, doc in sources:
        for where, i, e in elements(doc):
            kind, etype = where.split("/")[-1], e.get("type", "")
            for (dkind, dtype), donor in first.items():
                if dkind == kind and dtype != etype:
                    offer((kind, etype, "type", dtype), variant(doc, where, i, retyped(e, donor)),
                          "%s /%s/%d: %s as %s" % (fname, where, i, etype, dtype))
            for key, values in enums.items():
                if key not in e or key == "type":
                    continue
                for v in values:
                    if e.get(key) != v:
                        offer((kind, etype, key, json.dumps(v)), variant(doc, where, i, dict(e, **{key: v})),
                              "%s /%s/%d/%s = %s" % (fname, where, i, key, v))
            for key, v in keys.get((kind, etype), {}).items():
                if key not in e:
                    offer((kind, etype, "+" + key), variant(doc, where, i, dict(e, **{key: v})),
                          "%s /%s/%d + %s" % (fname, where, i, key))
        for section in SECTIONS:
            if not isinstance(doc.get(section), dict) or not isinstance(top.get(section), dict):
                continue
            for key, v in sections.get(section, {}).items():
                if key not in doc[section]:
                    d = copy.deepcopy(doc)
                    d[section][key] = v
                    offer((section, key), d, "%s /%s + %s" % (fname, section, key))
        joints = [j.get("name") for j in doc.get("joints", []) if isinstance(j, dict)]
        if joints and isinstance(doc.get("analysis"), dict):
            for form, branch in (("flip", {"flip": joints[:1]}), ("hint", {"joints": {joints[0]: 10}})):
                d = copy.deepcopy(doc)
                d["analysis"]["branch"] = branch
                offer(("branch", form, len(joints) > 4), d, "%s /analysis/branch %s" % (fname, form))
        for key, v in top.items():
            if key not in doc:
                d = copy.deepcopy(doc)
                d[key] = v
                offer(("top", key), d, "%s + /%s" % (fname, key))
    return out


def commands(binary, path, tmp):
    base = os.path.join(tmp, os.path.basename(path)[:-5])
    return [[binary, "check", path],
            [binary, "run", path, "-o", base + ".csv"],
            [binary, "range", path, "--steps", "16"],
            [binary, "view", path, "-o", base + ".html"]]


def probe(args):
    binary, label, path, tmp = args
    failures = []
    for cmd in commands(binary, path, tmp):
        try:
            r = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
        except subprocess.TimeoutExpired:
            failures.append("%s: %s: timed out" % (label, cmd[1]))
            continue
        text = r.stdout + r.stderr
        if r.returncode not in (0, 1, 2):
            failures.append("%s: %s exit %d: %s" % (label, cmd[1], r.returncode, text[-300:]))
        for word in FORBIDDEN:
            if word in text:
                failures.append("%s: %s printed %r: %s" % (label, cmd[1], word, text[-300:]))
                break
    return failures


def main():
    src, binary = sys.argv[1], sys.argv[2]
    with open(os.path.join(src, "schema", "mechkin-format-v1.schema.json"), encoding="utf-8") as h:
        schema = json.load(h)
    made = forms(load_sources(src), schema)
    # The generator must reach the forms the issue names (a test that cannot fail is a defect).
    assert len(made) >= 80, "only %d schema-valid forms made" % len(made)
    with tempfile.TemporaryDirectory() as tmp:
        jobs = []
        for k, (label, doc) in enumerate(made):
            path = os.path.join(tmp, "form%04d.json" % k)
            analysis = doc.get("analysis")
            if isinstance(analysis, dict) and isinstance(analysis.get("steps"), int):
                analysis["steps"] = min(analysis["steps"], 24)  # the form, not the length of the run
            with open(path, "w", encoding="utf-8") as h:
                json.dump(doc, h)
            jobs.append((binary, label, path, tmp))
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            failures = [f for fs in pool.map(probe, jobs) for f in fs]
    print("schema-valid forms: %d, each through check, run, range, view" % len(made))
    for f in failures:
        print("FAIL", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
