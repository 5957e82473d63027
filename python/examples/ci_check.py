#!/usr/bin/env python3
"""A CI gate for a folder of mechanism files: every file must be valid, hold its
`expect` assertions, run completely, and keep its peak output accelerations
under a limit. Exit status 0 when all pass, 1 otherwise (for any CI system).

    /usr/bin/python3 python/examples/ci_check.py mechanisms/*.json [--max-accel 1e4]
"""
import argparse
import sys

import numpy as np

import mechkin


def check_file(path, max_accel):
    try:
        model = mechkin.load(path)
    except mechkin.FormatError as e:
        return ["invalid: " + str(d) for d in e.diagnostics]
    problems = []
    report = model.check()
    for e in report.expect:
        if not e["held"]:
            problems.append("expect %s = %s failed (actual %s)" % (e["key"], e["expected"], e["actual"]))
    if report.mobility.get("driven") != "full" or report.mobility.get("idle"):
        print("  note: %s is not fully driven or has idle freedoms: checked, not run" % path)
        return problems
    motion = model.run(order=2)
    if not motion.complete:
        problems.append("run stopped: %s" % motion.stop.message.splitlines()[0])
    for c in motion.columns:
        if c["quantity"] in ("point", "body_position") and c["order"] == 2:
            peak = float(np.abs(motion[c["name"]]).max()) if len(motion) else 0.0
            if peak > max_accel:
                problems.append("%s peaks at %.4g %s (limit %.4g)" % (c["name"], peak, c["unit"], max_accel))
    return problems


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("files", nargs="+")
    ap.add_argument("--max-accel", type=float, default=float("inf"))
    args = ap.parse_args()
    failed = 0
    for path in args.files:
        problems = check_file(path, args.max_accel)
        print("%s: %s" % (path, "ok" if not problems else "FAILED"))
        for p in problems:
            print("  - " + p)
        failed += bool(problems)
    print("%d passed, %d failed" % (len(args.files) - failed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
