#!/usr/bin/env python3
"""tools/long_functions.py sees every function: on a synthetic file it reports a
method defined inside a class body (inside a namespace), a constructor with an
initializer list, an operator and a free function over the limit, with their
lengths; it skips the short ones, lambdas and control blocks; --check exits 1."""
import os
import subprocess
import sys
import tempfile

tool = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "tools", "long_functions.py")


def body(n):
    return "".join("    x += %d;  // }{ \"}\" '{'\n" % k for k in range(n))


source = (
    "#include <vector>\n"                                   # 1
    "namespace a {\n"                                       # 2
    "struct S {\n"                                          # 3
    "  int Method() const {\n"                              # lines 4..89
    "    int x = 0;\n" + body(82) + "    return x;\n  }\n"
    "  S(int v) : v_(v), w_{v} {\n"                          # lines 90..180
    "    int x = 0;\n" + body(88) + "  }\n"
    "  bool operator<(const S& o) const { return v_ < o.v_; }\n"   # short
    "  int v_, w_;\n"
    "};\n"
    "}  // namespace a\n"
    "template <typename T>\n"
    "T Free(T t) {\n"                                       # 82 lines, the template line not counted
    "  auto f = [&](int k) {\n    return k;\n  };\n" + body(76) + "  return t;\n}\n"
    "int Short() {\n  if (true) {\n    return 1;\n  }\n  return 0;\n}\n"
)
with tempfile.TemporaryDirectory() as root:
    path = os.path.join(root, "sample.hpp")
    open(path, "w").write(source)
    run = subprocess.run([sys.executable, tool, "--check", root], capture_output=True, text=True)
    got = [line.split(": ", 1)[1] for line in run.stdout.strip().split("\n")[:-1]]
    expected = ["86 lines: Method", "91 lines: S", "82 lines: Free"]
    if got != expected or run.returncode != 1:
        print("expected %s with exit 1, got %s with exit %d:\n%s" % (expected, got, run.returncode, run.stdout))
        sys.exit(1)
    allow = os.path.join(root, "allow.txt")
    open(allow, "w").write("%s:Method\n%s:S  # comment\n%s:Free\n" % (path, path, path))
    run = subprocess.run([sys.executable, tool, "--check", "--allow", allow, root], capture_output=True, text=True)
    if run.returncode != 0:
        print("the allow-list did not allow:\n" + run.stdout)
        sys.exit(1)
print("long_functions.py reports the in-class method, the constructor and the free function")
