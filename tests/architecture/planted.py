"""Shared by the architecture checks and their self-tests: the checks' command line
(root argument, offence lines, summary, exit status) and a self-test's planted
tree (write the files, run the check on it, compare the offences it names)."""
import os
import subprocess
import sys
import tempfile


def check_main(offences, what, needed="src"):
    """The checks' main: ROOT (default: the repository) → offence lines, summary, 1 if any."""
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    if not os.path.isdir(os.path.join(root, needed)):
        print("no %s/ folder under %s" % (needed, root))
        return 2
    found = offences(root)
    for line in found:
        print(line)
    print("%d %s offence(s) in %s/src" % (len(found), what, root))
    return 1 if found else 0


def expect_offences(check, files, expected, success):
    """Runs `check` (a script next to this file) on a tree of `files`; exits 1 unless
    it exits 1 naming exactly `expected` (before its summary line), else prints `success`."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), check)
    with tempfile.TemporaryDirectory() as root:
        for rel, text in files.items():
            os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
            open(os.path.join(root, rel), "w").write(text)
        run = subprocess.run([sys.executable, script, root], capture_output=True, text=True)
    lines = run.stdout.strip().split("\n")
    problems = []
    if run.returncode != 1:
        problems.append("exit status %d, expected 1" % run.returncode)
    if sorted(lines[:-1]) != sorted(expected):
        problems.append("reported:\n  " + "\n  ".join(lines))
    if problems:
        print("\n".join(problems))
        sys.exit(1)
    print(success)
