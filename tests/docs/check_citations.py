#!/usr/bin/env python3
"""Every `§<number>` cited in src/ must be a heading of docs/constraints.md.

The code cites the mathematics by section (`constraints.md §3.9`, `(§1.4)`); this
keeps those citations pointing at something. A heading is a Markdown heading line
whose first word is the number, with or without a trailing dot or a leading `§`:
`### 3.9 General revolute rotation driver`, `## 2. General formulas`.

Fails (exit 1), listing file:line and the number, when a cited section has no
heading, when two headings carry the same number, or when docs/constraints.md is
missing. Usage: check_citations.py [SOURCE_DIR]  (default: the repository root).
"""
import os
import re
import sys

CITED_EXTENSIONS = (".hpp", ".cpp", ".js", ".in")
# "§1.3." at the end of a sentence cites 1.3; "§1.2–§1.4" cites 1.2 and 1.4.
CITATION = re.compile(r"§(\d+(?:\.\d+)*)")
HEADING = re.compile(r"^#{1,6}\s+§?(\d+(?:\.\d+)*)\.?(?:\s|$)")


def headings(doc_path):
    """Section number -> line of its heading; duplicates are reported as errors."""
    found, errors = {}, []
    in_code = False
    with open(doc_path, encoding="utf-8") as f:
        for lineno, line in enumerate(f, 1):
            if line.lstrip().startswith("```"):
                in_code = not in_code
                continue
            m = None if in_code else HEADING.match(line)
            if not m:
                continue
            number = m.group(1)
            if number in found:
                errors.append("docs/constraints.md:%d: heading %s repeats the one at line %d"
                              % (lineno, number, found[number]))
            else:
                found[number] = lineno
    return found, errors


def citations(src_dir):
    """(relative path, line, number) for every § citation under src/."""
    out = []
    for root, dirs, files in os.walk(src_dir):
        dirs.sort()
        for name in sorted(files):
            if not name.endswith(CITED_EXTENSIONS):
                continue
            path = os.path.join(root, name)
            with open(path, encoding="utf-8", errors="replace") as f:
                for lineno, line in enumerate(f, 1):
                    for m in CITATION.finditer(line):
                        out.append((path, lineno, m.group(1)))
    return out


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    root = os.path.normpath(root)
    doc = os.path.join(root, "docs", "constraints.md")
    if not os.path.isfile(doc):
        print("FAIL docs/constraints.md is missing: the code's § citations point at it")
        return 1
    found, errors = headings(doc)
    cited = citations(os.path.join(root, "src"))
    if not cited:
        errors.append("no § citation found under %s/src: wrong source directory?" % root)
    for path, lineno, number in cited:
        if number not in found:
            errors.append("%s:%d: §%s has no heading in docs/constraints.md"
                          % (os.path.relpath(path, root), lineno, number))
    for e in errors:
        print("FAIL " + e)
    if errors:
        return 1
    print("ok: %d citations of %d sections in src/ resolve to headings of docs/constraints.md"
          % (len(cited), len({c[2] for c in cited})))
    return 0


if __name__ == "__main__":
    sys.exit(main())
