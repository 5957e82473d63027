#!/usr/bin/env python3
"""check_joint_types.py can fail: on a small tree with a planted enumerator, a switch
on a joint's type and a name comparison outside src/joints — and the same inside
src/joints, in comments and with "distance", which are allowed — it names exactly
the three offences by file:line and exits 1."""
import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
with tempfile.TemporaryDirectory() as root:
    files = {
        "src/joints/registry.cpp": "if (t == JointType::Revolute) {}\nswitch (j.type) {}\n",
        "src/joints/revolute.cpp": 'd.name = "revolute";\nif (name == "revolute") {}\n',
        "src/mobility/mobility.cpp": "int a;\n  if (j.type == JointType::Screw) return;\n",
        "src/io/convert.cpp": "// switch (jm.type) in a comment\n  switch (jm->type) {\n",
        "src/model/compile.cpp": 'if (*spec.type == "screw") {}\nif (type == "distance") {}\nswitch (d.kind) {}\n',
    }
    for rel, text in files.items():
        os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
        open(os.path.join(root, rel), "w").write(text)
    run = subprocess.run([sys.executable, os.path.join(here, "check_joint_types.py"), root],
                         capture_output=True, text=True)
    lines = run.stdout.strip().split("\n")
    expected = [
        "src/io/convert.cpp:2: switches on a joint's type outside src/joints: switch (jm->type) {",
        "src/mobility/mobility.cpp:2: names a joint type enumerator outside src/joints: "
        "if (j.type == JointType::Screw) return;",
        "src/model/compile.cpp:1: compares with a joint type's name outside src/joints: "
        'if (*spec.type == "screw") {}',
    ]
    problems = []
    if run.returncode != 1:
        problems.append("exit status %d, expected 1" % run.returncode)
    if sorted(lines[:-1]) != sorted(expected):
        problems.append("reported:\n  " + "\n  ".join(lines))
    if problems:
        print("\n".join(problems))
        sys.exit(1)
    print("check_joint_types.py names the three offences and exits 1")
