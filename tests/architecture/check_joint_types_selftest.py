#!/usr/bin/env python3
"""check_joint_types.py can fail: on a small tree with a planted enumerator, a switch
on a joint's type and a name comparison outside src/joints — and the same inside
src/joints, in comments and with "distance", which are allowed — it names exactly
the three offences by file:line and exits 1."""
from planted import expect_offences

FILES = {
    "src/joints/registry.cpp": "if (t == JointType::Revolute) {}\nswitch (j.type) {}\n",
    "src/joints/revolute.cpp": 'd.name = "revolute";\nif (name == "revolute") {}\n',
    "src/mobility/mobility.cpp": "int a;\n  if (j.type == JointType::Screw) return;\n",
    "src/io/convert.cpp": "// switch (jm.type) in a comment\n  switch (jm->type) {\n",
    "src/model/compile.cpp": 'if (*spec.type == "screw") {}\nif (type == "distance") {}\nswitch (d.kind) {}\n',
}
EXPECTED = [
    "src/io/convert.cpp:2: switches on a joint's type outside src/joints: switch (jm->type) {",
    "src/mobility/mobility.cpp:2: names a joint type enumerator outside src/joints: "
    "if (j.type == JointType::Screw) return;",
    "src/model/compile.cpp:1: compares with a joint type's name outside src/joints: "
    'if (*spec.type == "screw") {}',
]
expect_offences('check_joint_types.py', FILES, EXPECTED, "check_joint_types.py names the three offences and exits 1")
