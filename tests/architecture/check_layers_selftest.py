#!/usr/bin/env python3
"""check_layers.py can fail: on a small tree with an upward include, a JSON include
in model and a clean downward include, it names exactly the two offences by file:line."""
from planted import expect_offences

FILES = {
    "src/kinematics/newton.cpp": '#include "constraints/system.hpp"\n#include "math/rotation.hpp"\n',
    "src/constraints/system.cpp": '// a comment\n#include "analysis/motion.hpp"\n',
    "src/model/model.cpp": "#include <vector>\n#include <nlohmann/json.hpp>\n",
    "src/io/table_writer.cpp": '#include <nlohmann/json.hpp>\n#include "analysis/motion.hpp"\n',
    "src/spec/parse.cpp": "#include <nlohmann/json.hpp>\n",  # the spec layer may read JSON
}
EXPECTED = [
    "src/constraints/system.cpp:2: layer 'constraints' includes \"analysis/motion.hpp\" from the higher layer 'analysis'",
    "src/model/model.cpp:2: <nlohmann/json.hpp> outside src/spec and src/io (layer 'model')",
]
expect_offences('check_layers.py', FILES, EXPECTED, "check_layers.py names both offences and exits 1")
