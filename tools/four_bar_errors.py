#!/usr/bin/python3
"""The bundled planar four-bar (mechanisms/planar-four-bar.json) against its closed
form: the rocker angle and its first three derivatives from the crank angle (circle
intersection), in long double on truncated Taylor series, with the link lengths taken
from the stored joint points. Prints per order the largest actual error (relative to
the order's largest magnitude over the motion), the largest error bound, the worst
error/bound and the median bound/error where the error exceeds 1e-13.

    PYTHONPATH=build/python /usr/bin/python3 tools/four_bar_errors.py [--tol 1e-10]
"""
import argparse
import json
import os

import numpy as np

import mechkin

L = np.longdouble
N = 5  # Taylor coefficients 0..4: derivatives to order 3 after one integration


class Taylor:
    """c_k = f^(k)(t)/k! in long double."""

    def __init__(self, c):
        self.c = [L(v) for v in c] + [L(0)] * (N - len(c))

    def __add__(self, o):
        o = o if isinstance(o, Taylor) else Taylor([o])
        return Taylor([x + y for x, y in zip(self.c, o.c)])

    __radd__ = __add__

    def __neg__(self):
        return Taylor([-x for x in self.c])

    def __sub__(self, o):
        return self + (-(o if isinstance(o, Taylor) else Taylor([o])))

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        if not isinstance(o, Taylor):
            return Taylor([x * L(o) for x in self.c])
        return Taylor([sum(self.c[i] * o.c[k - i] for i in range(k + 1)) for k in range(N)])

    __rmul__ = __mul__

    def __truediv__(self, o):
        if not isinstance(o, Taylor):
            return Taylor([x / L(o) for x in self.c])
        q = []
        for k in range(N):
            q.append((self.c[k] - sum(o.c[i] * q[k - i] for i in range(1, k + 1))) / o.c[0])
        return Taylor(q)

    def deriv(self):
        return Taylor([(k + 1) * self.c[k + 1] for k in range(N - 1)])

    def integ(self, c0):
        return Taylor([c0] + [self.c[k - 1] / k for k in range(1, N)])

    def derivative(self, k):
        return self.c[k] * [1, 1, 2, 6, 24][k]


def sqrt(a):
    s = [np.sqrt(a.c[0])]
    for k in range(1, N):
        s.append((a.c[k] - sum(s[i] * s[k - i] for i in range(1, k))) / (2 * s[0]))
    return Taylor(s)


def sincos(u):
    s, c = [np.sin(u.c[0])], [np.cos(u.c[0])]
    for k in range(1, N):
        s.append(sum(i * u.c[i] * c[k - i] for i in range(1, k + 1)) / k)
        c.append(-sum(i * u.c[i] * s[k - i] for i in range(1, k + 1)) / k)
    return Taylor(s), Taylor(c)


def acos(x):
    return (-(x.deriv()) / sqrt(1 - x * x)).integ(np.arccos(x.c[0]))


def atan2(y, x):
    return ((x * y.deriv() - y * x.deriv()) / (x * x + y * y)).integ(np.arctan2(y.c[0], x.c[0]))


def rocker_angle(doc, t, branch):
    """The rocker's angle (Taylor series in t) with the crank at its drawn angle + 2πt."""
    o = {j["name"]: np.array([L(v) / 1000 for v in j["origin"][:2]]) for j in doc["joints"]}
    a, b, c = (np.sqrt(((o[p] - o[q]) ** 2).sum()) for p, q in (("B", "A"), ("C", "B"), ("C", "D")))
    crank = Taylor([np.arctan2(*(o["B"] - o["A"])[::-1]) + 2 * np.arccos(L(-1)) * L(t), 2 * np.arccos(L(-1))])
    s, co = sincos(crank)
    bx, by = o["A"][0] + a * co, o["A"][1] + a * s
    ex, ey = o["D"][0] - bx, o["D"][1] - by
    dist2 = ex * ex + ey * ey
    s, co = sincos(atan2(ey, ex) + branch * acos((b * b + dist2 - c * c) / (2 * b * sqrt(dist2))))
    theta = atan2(by + b * s - o["D"][1], bx + b * co - o["D"][0])
    return theta - np.arctan2(*(o["C"] - o["D"])[::-1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tol", type=float, default=1e-10)
    tol = ap.parse_args().tol
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "mechanisms", "planar-four-bar.json")
    doc = json.load(open(path))
    m = mechkin.loads(json.dumps(doc)).run(order=3, tol=tol, si=True)
    branch = min((1, -1), key=lambda g: abs(rocker_angle(doc, 0, g).c[0]))
    exact = np.array([[float(rocker_angle(doc, t, branch).derivative(k)) for k in range(4)] for t in m.t])
    suffix = ["", "_t", "_tt", "_ttt"]
    scale = np.abs(exact).max(0)
    scale[0] = 1
    for k in range(4):
        err = np.abs(np.asarray(m["rocker_angle" + suffix[k]]) - exact[:, k]) / scale[k]
        bound = np.asarray(m["error_bound" + suffix[k]])
        big = err > 1e-13
        # What a bound of 2κ^k(e_0 + 8u) (e_0 = κ·max(r, 4u)) would say on the same rows.
        kappa, u = np.asarray(m["condition"]), 2.0 ** -53
        e0 = kappa * np.maximum(np.asarray(m["residual"]), 4 * u)
        alt = e0 if k == 0 else 2 * kappa ** k * (e0 + 8 * u)
        median = lambda b: np.median(b[big] / err[big]) if big.any() else 0
        print("tol %g order %d: largest error %.3g, largest bound %.3g, worst error/bound %.3g, "
              "median bound/error (error > 1e-13) %.3g; 2κ^k(e0+8u) would be a median %.3g x" % (
                  tol, k, err.max(), bound.max(), (err / bound).max(), median(bound), median(alt)))


if __name__ == "__main__":
    main()
