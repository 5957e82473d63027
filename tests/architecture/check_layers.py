#!/usr/bin/env python3
"""Fails on an include that runs up the layers, and on a JSON include outside the
layers that read and write files.

The layers, lowest first; each may include only its own folder and the ones below
(the CMake targets mechkin_<layer> link the same way, CMakeLists.txt):
    math → joints → spec → importers → model → constraints → kinematics → mobility → analysis → io → cli
nlohmann/json may be included only in src/spec and src/io (and the allow-list).

Usage: check_layers.py [SOURCE_DIR]   (default: the repository holding this file)
Exit 0 when clean; 1 with one `file:line: problem` line per offence."""
import os
import re
import sys

from planted import check_main

LAYERS = ["math", "joints", "spec", "importers", "model", "constraints", "kinematics", "mobility", "analysis", "io", "cli"]
JSON_LAYERS = {"spec", "io"}
# Files allowed a JSON include outside spec and io: none (the loader became src/spec,
# the CLI's report text comes from src/io). Keep it empty.
JSON_ALLOWED = set()

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def offences(root):
    rank = {name: i for i, name in enumerate(LAYERS)}
    found = []
    src = os.path.join(root, "src")
    for folder, _, files in os.walk(src):
        for f in sorted(files):
            path = os.path.join(folder, f)
            rel = os.path.relpath(path, root).replace(os.sep, "/")
            layer = rel.split("/")[1] if rel.count("/") >= 2 else None
            if layer not in rank:
                continue
            try:
                lines = open(path, encoding="utf-8", errors="replace").read().split("\n")
            except OSError:
                continue
            for n, line in enumerate(lines, 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                target = m.group(2)
                top = target.split("/")[0]
                if m.group(1) == '"' and top in rank and rank[top] > rank[layer]:
                    found.append("%s:%d: layer '%s' includes \"%s\" from the higher layer '%s'"
                                 % (rel, n, layer, target, top))
                if target.startswith("nlohmann/") and layer not in JSON_LAYERS and rel not in JSON_ALLOWED:
                    found.append("%s:%d: <%s> outside src/spec and src/io (layer '%s')" % (rel, n, target, layer))
    return found


def main():
    return check_main(offences, "layering", "src")


if __name__ == "__main__":
    sys.exit(main())
