#!/usr/bin/python3
"""The N-four-bar's pose error in its fold direction, exactly, on the rows near the
singular positions at +-90 deg, next to the jerk's error and default error bound
(docs/constraints.md §8, "Measured"; issue 23 item 2).

At +-90 deg Φ_q loses rank in the direction of the rockers turning against the crank
(the folded branches), so the pose error that the derivatives amplify most is the rockers' turn relative to the crank
(and the couplers' turn). This prints that error computed exactly, in rational
arithmetic from the stored Euler parameters (a z-rotation: p = (cos a/2, 0, 0, sin a/2)),
next to each row's jerk error/bound. On 14 of these rows each rocker's stored
orientation is bitwise the crank's, an error of exactly 0 there; a residual of Φ in
long double resolves it only to its round-off solved through the Jacobian (about
1e-17 to 6e-17 rad on these rows), which made those bounds up to 3558x the error
before the measured bounds evaluated Φ in quadruple precision.

    PYTHONPATH=build/python /usr/bin/python3 tools/n_four_bar_fold_error.py
"""
import math
import os
import sys
from fractions import Fraction

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python", "tests"))
import test_error_bounds as cases  # noqa: E402


def relative_turn(motion, row, body, reference):
    """Turn of `body` relative to `reference` (rad), exact up to the final rounding."""
    e0, e3 = (Fraction(float(np.asarray(motion[body + c])[row])) for c in (".e0", ".e3"))
    if reference is None:
        return float(2 * e3 / e0)  # a small turn: 2 atan(e3/e0) to first order, relative error ~1e-33
    f0, f3 = (Fraction(float(np.asarray(motion[reference + c])[row])) for c in (".e0", ".e3"))
    return float(2 * (f0 * e3 - f3 * e0) / (f0 * e0 + f3 * e3))


def main():
    """Per row near +-90 deg (every case of the test, both tolerances): the jerk's
    error/bound and the fold-direction pose error; then the summary."""
    over, over_exact, rest_ratios = 0, 0, []
    for tol in (1e-10, 1e-13):
        for n, theta0, rate in cases.CASES:
            m, err = cases.n_four_bar_errors(n, theta0, rate, tol)
            bound = cases.bounds_of(m)
            t = np.asarray(m["t"])
            for row in np.nonzero(np.abs(t - 90 / 97) <= 0.021)[0]:
                rockers = [relative_turn(m, row, "rocker%d" % i, "crank") for i in range(1, n + 1)]
                couplers = [relative_turn(m, row, "coupler%d" % i, None) for i in range(1, n + 1)]
                loose = err[row, 3] > 1e-12 and bound[row, 3] > 100 * err[row, 3]
                if err[row, 3] > 1e-12:
                    over += loose
                    over_exact += loose and not any(rockers)
                    if not loose:
                        rest_ratios.append(bound[row, 3] / err[row, 3])
                print("tol %g N=%d from %4d deg at %3d deg/s, t=%.3f: jerk error %.2g, bound %.2g%s; "
                      "rockers - crank %s rad; couplers %s rad"
                      % (tol, n, theta0, rate, t[row], err[row, 3], bound[row, 3], " (over 100x)" if loose else "",
                         " ".join("%.2g" % v for v in rockers), " ".join("%.2g" % v for v in couplers)))
    print("jerk rows over 100x (error > 1e-12): %d, of them with every rocker's turn exactly the crank's: %d; "
          "the other rows with error > 1e-12: %d, bound/error %.3g to %.3g"
          % (over, over_exact, len(rest_ratios), min(rest_ratios), max(rest_ratios)))


if __name__ == "__main__":
    main()
