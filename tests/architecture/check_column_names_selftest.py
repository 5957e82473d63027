#!/usr/bin/env python3
"""check_column_names.py must fail on a planted composition (C++ and Python) and
pass comments, docstrings, messages and the layout itself."""
import os
import subprocess
import sys
import tempfile

CHECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_column_names.py")


def run(files):
    with tempfile.TemporaryDirectory() as root:
        for rel, text in files.items():
            os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
            open(os.path.join(root, rel), "w").write(text)
        return subprocess.run([sys.executable, CHECK, root], capture_output=True, text=True)


clean = {
    "src/analysis/motion.cpp": 'std::string n = b + "/d(" + p + ")"; const char* s = "_t";\n',
    "src/io/a.cpp": '// a comment naming "_t" and "/d(" is fine\nstd::string m = "adds d(column)/d(parameter)";\n',
    "python/mechkin/a.py": 'def f():\n    """d(column)/d(parameter) and ".effort" in a docstring"""\n    return 1\n',
}
r = run(clean)
assert r.returncode == 0, r.stdout
for rel, text in {"src/analysis/tolerance.cpp": 'Find(name + "/d(" + p + ")");\n',
                  "src/io/gltf.cpp": 'int k = Find(body + ".x" + "_tt");  // a comment\n',
                  "python/mechkin/b.py": 'def g(m, d):\n    return m[d + ".effort"]\n',
                  "python/mechkin/c.py": 'def h(m, c, p):\n    return m["%s/d(%s)" % (c, p)]\n'}.items():
    r = run(dict(clean, **{rel: text}))
    assert r.returncode == 1 and rel in r.stdout, (rel, r.stdout)
print("ok")
