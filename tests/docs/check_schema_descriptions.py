#!/usr/bin/env python3
"""Editors help: schema/mechkin-format-v1.schema.json describes every key.

1. Every property of every object in the schema (top level, $defs, inside
   oneOf/allOf/if/then branches) has a non-empty "description", so an editor
   shows what a key means on completion and hover.
2. A file may name the schema with a top-level "$schema" string: every bundled
   mechanism with "$schema" added still validates, and a non-string "$schema" is
   rejected.
Usage: check_schema_descriptions.py [SOURCE_DIR]  (default: the repository root).
"""
import copy
import json
import os
import sys

import jsonschema


def undescribed(node, pointer, out):
    """JSON pointers of the properties in `node` that lack a description."""
    if isinstance(node, dict):
        props = node.get("properties")
        if isinstance(props, dict):
            for key, sub in props.items():
                text = sub.get("description") if isinstance(sub, dict) else None
                if not (isinstance(text, str) and text.strip()):
                    out.append(pointer + "/properties/" + key)
        for key, sub in node.items():
            undescribed(sub, pointer + "/" + key, out)
    elif isinstance(node, list):
        for k, sub in enumerate(node):
            undescribed(sub, pointer + "/" + str(k), out)
    return out


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    schema = json.load(open(os.path.join(root, "schema", "mechkin-format-v1.schema.json"), encoding="utf-8"))
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    failures = ["%s has no description" % p for p in undescribed(schema, "#", [])]
    mech_dir = os.path.join(root, "mechanisms")
    bundled = sorted(f for f in os.listdir(mech_dir) if f.endswith(".json"))
    for name in bundled:
        doc = json.load(open(os.path.join(mech_dir, name), encoding="utf-8"))
        named = copy.deepcopy(doc)
        named["$schema"] = "../schema/mechkin-format-v1.schema.json"
        errors = list(validator.iter_errors(named))
        if errors:
            failures.append("%s with a \"$schema\" key is rejected: %s" % (name, errors[0].message))
        wrong = copy.deepcopy(doc)
        wrong["$schema"] = 1
        if validator.is_valid(wrong):
            failures.append("%s with a non-string \"$schema\" is accepted" % name)
    for f in failures:
        print("FAIL " + f)
    if failures:
        return 1
    print("ok: every schema property has a description; %d bundled mechanisms validate with a \"$schema\" key"
          % len(bundled))
    return 0


if __name__ == "__main__":
    sys.exit(main())
