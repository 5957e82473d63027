#!/usr/bin/env python3
"""Fails where code outside src/joints names a joint type instead of reading its
descriptor (issue 32, docs/joints.md): a joint type is one file in src/joints and
one line in src/joints/registry.cpp, and no switch elsewhere knows the list.

Offences, in src/ outside src/joints:
  * `JointType::` (an enumerator of joint types);
  * `switch` on a joint's type member (`switch (j.type)`, `switch (jt->type)`);
  * a comparison with a joint type's name literal (`== "revolute"`, `!= "screw"`, ...;
    "distance" is also a driver and output type, so it is not listed).
Usage: check_joint_types.py [SOURCE_DIR]   (default: the repository holding this file)
Exit 0 when clean; 1 with one `file:line: problem` line per offence."""
import os
import re
import sys

from planted import check_main

NAMES = ["revolute", "prismatic", "screw", "cylindrical", "universal", "spherical", "planar"]
SOURCE_ENDINGS = (".cpp", ".hpp", ".h", ".cc", ".in")
PATTERNS = [
    (re.compile(r"\bJointType::"), "names a joint type enumerator"),
    (re.compile(r"\bswitch\s*\(\s*[\w.\->\[\]]*(?:\.|->)type\s*\)"), "switches on a joint's type"),
    (re.compile(r'[=!]=\s*"(%s)"|"(%s)"\s*[=!]=' % ("|".join(NAMES), "|".join(NAMES))),
     "compares with a joint type's name"),
]
COMMENT = re.compile(r"//.*$")


def offences(root):
    found = []
    src = os.path.join(root, "src")
    for folder, _, files in os.walk(src):
        for f in sorted(files):
            path = os.path.join(folder, f)
            rel = os.path.relpath(path, root).replace(os.sep, "/")
            if rel.startswith("src/joints/") or not f.endswith(SOURCE_ENDINGS):
                continue
            try:
                lines = open(path, encoding="utf-8", errors="replace").read().split("\n")
            except OSError:
                continue
            for n, line in enumerate(lines, 1):
                code = COMMENT.sub("", line)
                for pattern, what in PATTERNS:
                    if pattern.search(code):
                        found.append("%s:%d: %s outside src/joints: %s" % (rel, n, what, line.strip()))
    return sorted(found)


def main():
    return check_main(offences, "joint type", "src/joints")


if __name__ == "__main__":
    sys.exit(main())
