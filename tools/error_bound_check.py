#!/usr/bin/python3
"""How the error bounds compare with the actual error: on the N-four-bar and the
Bennett linkage of python/tests/test_error_bounds.py (default bounds), then on the
piston-driven slider-crank toward its dead centre (python/tests/test_error_bounds.py's `piston`,
its geometry stored exactly, closed form θ0·(cos(πt/2) − 1)), per order, for both
`error_bounds` modes at --tol 1e-10 and 1e-13: the worst error/bound (≤ 1: the bounds
hold), the largest bound/error where the actual error exceeds 1e-12, and the rows where
it is more than 100× (issue 23's tightness criterion).

    PYTHONPATH=build/python /usr/bin/python3 tools/error_bound_check.py
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python", "tests"))
import test_error_bounds as cases  # noqa: E402


def tightness(name, m, err):
    """One case's line: worst error/bound, and the (error > 1e-12, bound > 100x) rows."""
    bound = cases.bounds_of(m)
    loose = cases.loose_rows(err, bound)
    t = np.asarray(m["t"])
    worst = max((bound[i, k] / err[i, k] for i, k in loose), default=0)
    near = sorted(set("%.3f" % t[i] for i, _ in loose))
    big = err > 1e-12
    print("%-30s worst error/bound %.3g; largest bound/error where error > 1e-12: %.3g; rows over 100x: %d%s" % (
        name, (err / bound).max(), (bound[big] / err[big]).max() if big.any() else 0, len(loose),
        " (up to %.0fx, at t = %s)" % (worst, ", ".join(near)) if loose else ""))
    return len(loose)


def other_cases():
    """The N-four-bar (every case of the test) and the Bennett linkage, default bounds."""
    total = 0
    for tol in (1e-10, 1e-13):
        for n, theta0, rate in cases.CASES:
            m, err = cases.n_four_bar_errors(n, theta0, rate, tol)
            total += tightness("N=%d from %d deg at %d deg/s, tol %g" % (n, theta0, rate, tol), m, err)
        m, err = cases.bennett(tol)
        total += tightness("Bennett, tol %g" % tol, m, err)
    print("rows over 100x in these cases: %d" % total)


def main():
    other_cases()
    for mode in ("auto", "measured"):
        for tol in (1e-10, 1e-13):
            m, err = cases.piston(tol, error_bounds=mode)
            bound = cases.bounds_of(m)
            for k in range(4):
                big = err[:, k] > 1e-12
                loose = int((big & (bound[:, k] > 100 * err[:, k])).sum())
                print("%-8s tol %-6g order %d: worst error/bound %.3g; rows with error > 1e-12: %3d, "
                      "of them bound > 100x error: %d; largest bound/error there: %.3g"
                      % (mode, tol, k, (err[:, k] / bound[:, k]).max(), int(big.sum()), loose,
                         (bound[big, k] / err[big, k]).max() if big.any() else 0))


if __name__ == "__main__":
    main()
