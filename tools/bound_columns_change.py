#!/usr/bin/python3
"""What a change to the error bounds did to the bundled tables: runs two `mechkin`
builds on every mechanisms/*.json (`run FILE -o T.csv`, default options) and prints,
per file, whether the exit codes and stderr are the same, how many cells differ in the
columns other than error_bound* (0: byte-identical there), and how many error_bound
cells changed, with the range of new/old. Exits 1 if anything but error_bound cells
differs.

    /usr/bin/python3 tools/bound_columns_change.py NEW_MECHKIN OLD_MECHKIN
"""
import csv
import glob
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(binary, path, out):
    proc = subprocess.run([binary, "run", path, "-o", out], capture_output=True, text=True)
    return proc.returncode, proc.stderr


def compare(new_csv, old_csv):
    """(other cells differing, error_bound cells changed, lowest new/old, highest new/old)."""
    with open(new_csv) as a, open(old_csv) as b:
        new, old = list(csv.reader(a)), list(csv.reader(b))
    if new[0] != old[0] or len(new) != len(old):
        return None
    bound_columns = {i for i, h in enumerate(new[0]) if h.startswith("error_bound")}
    other, changed, low, high = 0, 0, 1.0, 1.0
    for row_new, row_old in zip(new[1:], old[1:]):
        for i, (x, y) in enumerate(zip(row_new, row_old)):
            if x == y:
                continue
            if i not in bound_columns:
                other += 1
                continue
            changed += 1
            ratio = float(x) / float(y) if float(y) else float("inf")
            low, high = min(low, ratio), max(high, ratio)
    return other, changed, low, high


def main():
    new_bin, old_bin = sys.argv[1], sys.argv[2]
    failed, changed_files = False, 0
    with tempfile.TemporaryDirectory() as tmp:
        for path in sorted(glob.glob(os.path.join(ROOT, "mechanisms", "*.json"))):
            name = os.path.basename(path)
            new_csv, old_csv = os.path.join(tmp, "new.csv"), os.path.join(tmp, "old.csv")
            new_res, old_res = run(new_bin, path, new_csv), run(old_bin, path, old_csv)
            if new_res != old_res:
                print("%-36s exit code or stderr differ" % name)
                failed = True
            elif new_res[0] != 0:
                print("%-36s refused by both (exit %d, same stderr)" % (name, new_res[0]))
            else:
                result = compare(new_csv, old_csv)
                if result is None:
                    print("%-36s header or row count differ" % name)
                    failed = True
                    continue
                other, changed, low, high = result
                failed |= other > 0
                changed_files += changed > 0
                print("%-36s other columns: %d cells differ; error_bound: %d cells changed (new/old %.3g to %.3g)"
                      % (name, other, changed, low, high))
    print("tables whose error_bound columns changed: %d" % changed_files)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
