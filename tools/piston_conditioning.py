#!/usr/bin/env python3
"""How much one unit in the last place of the piston position moves the exact crank
derivatives of the piston-driven slider-crank (tests/data/piston-driven-slider-crank.json:
crank 20 mm, rod 50 mm, crank angle 60° cos(πt/2)) at t = 0.998, near its dead centre.

    /usr/bin/python3 tools/piston_conditioning.py

The crank angle follows from the piston position x through x = a cos θ + √(b² − a² sin² θ);
its rates from x', x'', x''' by θ' = x'/X₁, θ'' = (x'' − X₂θ'²)/X₁, θ''' = (x''' − X₃θ'³ − 3X₂θ'θ'')/X₁
(X_k = dᵏx/dθᵏ). Moving x by one double-precision spacing moves θ by ulp/|X₁| and the
rates by what this prints (long double arithmetic, relative to θ₀ω^k)."""
import numpy as np

L = np.longdouble
a, b = L(0.020), L(0.050)


def X(th):
    return a * np.cos(th) + np.sqrt(b * b - (a * np.sin(th)) ** 2)


def derivative(f, th, k, h=L(1e-3)):
    if k == 1:
        return (f(th - 2 * h) - 8 * f(th - h) + 8 * f(th + h) - f(th + 2 * h)) / (12 * h)
    if k == 2:
        return (-f(th - 2 * h) + 16 * f(th - h) - 30 * f(th) + 16 * f(th + h) - f(th + 2 * h)) / (12 * h * h)
    return (-f(th - 3 * h) + 8 * f(th - 2 * h) - 13 * f(th - h) + 13 * f(th + h) - 8 * f(th + 2 * h) + f(th + 3 * h)) / (8 * h ** 3)


def main(t=L(0.998)):
    th0, w = L(np.pi) / 3, L(np.pi) / 2
    th = th0 * np.cos(w * t)
    rates = [-th0 * w * np.sin(w * t), -th0 * w * w * np.cos(w * t), th0 * w ** 3 * np.sin(w * t)]
    X1, X2, X3 = (derivative(X, th, k) for k in (1, 2, 3))
    x1 = X1 * rates[0]
    x2 = X2 * rates[0] ** 2 + X1 * rates[1]
    x3 = X3 * rates[0] ** 3 + 3 * X2 * rates[0] * rates[1] + X1 * rates[2]

    def crank_rates(theta):
        Y1, Y2, Y3 = (derivative(X, theta, k) for k in (1, 2, 3))
        t1 = x1 / Y1
        t2 = (x2 - Y2 * t1 ** 2) / Y1
        return t1, t2, (x3 - Y3 * t1 ** 3 - 3 * Y2 * t1 * t2) / Y1

    ulp = np.spacing(np.float64(X(th)))
    dth = L(ulp) / abs(X1)
    print("t = %.3f s: x = %.6g m (spacing %.3g m), dx/dθ = %.3g m/rad: one spacing of x moves θ by %.3g rad"
          % (float(t), float(X(th)), ulp, float(X1), float(dth)))
    for k, (p, q) in enumerate(zip(crank_rates(th), crank_rates(th + dth))):
        print("  crank %s moves by %.2g of its scale" % (("velocity", "acceleration", "jerk")[k],
                                                        float(abs(q - p)) / float(th0 * w ** (k + 1))))


if __name__ == "__main__":
    main()
