#!/usr/bin/env python3
"""Fails where code outside the motion layout composes or parses a column name
(issue 32: "no code outside the layout composes or parses a column name").

The layout (src/analysis/motion.cpp) is the one place that joins a subject and a
suffix into "crank.x_t" or "piston.x/d(crank)"; every other consumer finds columns
through the typed accessors (MotionLayout::Find by quantity, SensitivityOf,
EffortOf, PowerOf; in Python the column descriptors' quantity/subject/order/wrt/base).
A composition shows up as a string literal that is a name fragment — "_t", "/d(",
".effort", ".fx" — or a format that builds one ("%s/d(%s)"). Comments and Python
docstrings are not code and are skipped.

Usage: check_column_names.py [ROOT]   Exit 0 when clean; 1 with `file:line: literal` lines."""
import io
import os
import re
import sys
import tokenize

# The layout: motion.cpp and the clearance columns it delegates to (MotionLayout::AddClearance).
LAYOUT = {"src/analysis/motion.cpp", "src/analysis/clearance_columns.cpp"}
FRAGMENT = re.compile(r"^(/d\(|\)|_t+|\.(effort\d*|power|[fm][xyzfgh])(_t+)?)$")
FORMAT = re.compile(r"(%s|\{\w*\})/d\((%s|\{\w*\})\)|(%s|\{\w*\})\.(effort|power)")
CPP_STRING = re.compile(r'"((?:[^"\\\n]|\\.)*)"')


def offending(literal):
    return bool(FRAGMENT.match(literal) and literal != ")") or bool(FORMAT.search(literal))


def without_comment(line):
    """The line up to a // that is not inside a string literal."""
    spans = [m.span() for m in CPP_STRING.finditer(line)]
    for k in (k for k in range(len(line)) if line.startswith("//", k)):
        if not any(a <= k < b for a, b in spans):
            return line[:k]
    return line


def cpp_offences(rel, text):
    found = []
    for n, line in enumerate(text.split("\n"), 1):
        for m in CPP_STRING.finditer(without_comment(line)):
            if offending(m.group(1)):
                found.append("%s:%d: \"%s\"" % (rel, n, m.group(1)))
    return found


def python_offences(rel, text):
    found = []
    prev = tokenize.NEWLINE
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type == tokenize.STRING and prev not in (tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT, tokenize.NL):
            body = re.sub(r"^[rbfuRBFU]*('''|\"\"\"|'|\")", "", tok.string)
            body = re.sub(r"('''|\"\"\"|'|\")$", "", body)
            if offending(body):
                found.append("%s:%d: %s" % (rel, tok.start[0], tok.string))
        if tok.type not in (tokenize.COMMENT, tokenize.NL):
            prev = tok.type
    return found


def offences(root):
    found = []
    for top in ("src", "python/src", "python/mechkin"):
        for folder, _, files in os.walk(os.path.join(root, top)):
            for f in sorted(files):
                path = os.path.join(folder, f)
                rel = os.path.relpath(path, root).replace(os.sep, "/")
                if rel in LAYOUT:
                    continue
                text = open(path, encoding="utf-8", errors="replace").read()
                if f.endswith((".cpp", ".hpp")):
                    found += cpp_offences(rel, text)
                elif f.endswith(".py"):
                    found += python_offences(rel, text)
    return found


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    found = offences(root)
    for line in found:
        print(line + "  (compose nothing outside the layout: use its typed accessors)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
