#!/usr/bin/python3
"""How the error bounds compare with the actual error on the piston-driven
slider-crank toward its dead centre (python/tests/test_error_bounds.py's `piston`,
its geometry stored exactly, closed form θ0·(cos(πt/2) − 1)), per order, for both
`error_bounds` modes at --tol 1e-10 and 1e-13: the worst error/bound (≤ 1: the bounds
hold) and the rows where the actual error exceeds 1e-12 and the bound is more than
100× it (issue 23's tightness criterion).

    PYTHONPATH=build/python /usr/bin/python3 tools/error_bound_check.py
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python", "tests"))
import test_error_bounds as cases  # noqa: E402


def main():
    for mode in ("auto", "measured"):
        for tol in (1e-10, 1e-13):
            m, err = cases.piston(tol, error_bounds=mode)
            bound = cases.bounds_of(m)
            for k in range(4):
                big = err[:, k] > 1e-12
                loose = int((big & (bound[:, k] > 100 * err[:, k])).sum())
                print("%-8s tol %-6g order %d: worst error/bound %.3g; rows with error > 1e-12: %3d, "
                      "of them bound > 100x error: %d" % (mode, tol, k, (err[:, k] / bound[:, k]).max(),
                                                          int(big.sum()), loose))


if __name__ == "__main__":
    main()
