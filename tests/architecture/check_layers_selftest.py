#!/usr/bin/env python3
"""check_layers.py can fail: on a small tree with an upward include, a JSON include
in model and a clean downward include, it names exactly the two offences by file:line."""
import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
with tempfile.TemporaryDirectory() as root:
    files = {
        "src/kinematics/newton.cpp": '#include "constraints/system.hpp"\n#include "math/rotation.hpp"\n',
        "src/constraints/system.cpp": '// a comment\n#include "analysis/motion.hpp"\n',
        "src/model/model.cpp": "#include <vector>\n#include <nlohmann/json.hpp>\n",
        "src/io/table_writer.cpp": '#include <nlohmann/json.hpp>\n#include "analysis/motion.hpp"\n',
        "src/spec/parse.cpp": "#include <nlohmann/json.hpp>\n",  # the spec layer may read JSON
    }
    for rel, text in files.items():
        os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
        open(os.path.join(root, rel), "w").write(text)
    run = subprocess.run([sys.executable, os.path.join(here, "check_layers.py"), root], capture_output=True, text=True)
    lines = run.stdout.strip().split("\n")
    expected = [
        "src/constraints/system.cpp:2: layer 'constraints' includes \"analysis/motion.hpp\" from the higher layer 'analysis'",
        "src/model/model.cpp:2: <nlohmann/json.hpp> outside src/spec and src/io (layer 'model')",
    ]
    problems = []
    if run.returncode != 1:
        problems.append("exit status %d, expected 1" % run.returncode)
    if sorted(lines[:-1]) != sorted(expected):
        problems.append("reported:\n  " + "\n  ".join(lines))
    if problems:
        print("\n".join(problems))
        sys.exit(1)
    print("check_layers.py names both offences and exits 1")
