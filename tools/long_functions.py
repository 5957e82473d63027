#!/usr/bin/env python3
"""Lists functions in src/ longer than a limit (default 80 lines), by brace
matching from a top-level signature line. Usage: tools/long_functions.py [limit]"""
import glob, re, sys

limit = int(sys.argv[1]) if len(sys.argv) > 1 else 80
found = 0
for path in sorted(glob.glob("src/**/*.cpp", recursive=True) + glob.glob("python/src/*.cpp")):
    lines = open(path).read().split("\n")
    depth, start, name = 0, None, None
    for i, line in enumerate(lines):
        code = re.sub(r'"(\\.|[^"\\])*"', '""', line.split("//")[0])
        if depth <= 1 and start is None and re.search(r"\)\s*(const)?\s*(override)?\s*(->\s*[\w:<>]+)?\s*\{\s*$", code) \
                and not re.match(r"\s*(if|for|while|switch|namespace|class|struct)\b", code):
            start, name, base = i, code.strip()[:70], depth
        depth += code.count("{") - code.count("}")
        if start is not None and depth <= base:
            length = i - start + 1
            if length > limit:
                print("%s:%d: %d lines: %s" % (path, start + 1, length, name))
                found += 1
            start = None
print("%d functions longer than %d lines" % (found, limit))
