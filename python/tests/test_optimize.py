"""Design by objective through the Python package (issue 29): Model.optimize on the
worked Freudenstein example recovers the closed-form three-point solution (the linear
system in K1, K2, K3), returns the optimised Model, and Model.objective/gradient give a
user's own optimiser the reduction and its exact gradient (checked against central
differences; python3-scipy is not installed in this Debian, so no scipy here)."""
import math
import os

import numpy as np
import pytest

import mechkin

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FILE = os.path.join(ROOT, "mechanisms", "synthesis", "freudenstein-three-points.json")


def closed_form():
    """a, b, c (d = 1) through (theta2, theta4) = (60, 100), (90, 110), (120, 125) deg."""
    t2 = np.radians([60.0, 90.0, 120.0])
    t4 = np.radians([100.0, 110.0, 125.0])
    k = np.linalg.solve(np.column_stack([np.cos(t4), -np.cos(t2), np.ones(3)]), np.cos(t2 - t4))
    a, c = 1 / k[0], 1 / k[1]
    return a, math.sqrt(a * a + c * c + 1 - 2 * a * c * k[2]), c


def test_optimize_recovers_the_three_point_solution():
    model = mechkin.load(FILE)
    result = model.optimize(vary=["a", "b", "c"], minimize="fit")
    assert isinstance(result, mechkin.OptimizeResult)
    assert result.converged
    assert result.objective_after < 1e-18 < 1 < result.objective_before
    for name, exact in zip("abc", closed_form()):
        assert math.isclose(result.values[name], exact, rel_tol=1e-8)
        assert math.isclose(result.model.parameters[name], exact, rel_tol=1e-8)
    assert [p["name"] for p in result.parameters] == ["a", "b", "c"]
    assert "converged" in repr(result) and "fit" in str(result)
    # the new model runs, its fit reduction ~ 0
    motion = result.model.run(order=3, bodies=[])
    assert motion.reductions["fit"]["value"] < 1e-16


def test_objective_and_gradient_against_central_differences():
    model = mechkin.load(FILE)
    x = {"a": 0.6, "b": 0.7, "c": 1.1}
    f = model.objective("fit", x, tol=1e-13)
    g = model.gradient("fit", x, tol=1e-13)
    assert f > 0 and g.shape == (3,)
    for k, name in enumerate(x):
        h = 1e-5 * x[name]
        up, down = dict(x), dict(x)
        up[name] += h
        down[name] -= h
        fd = (model.objective("fit", up, tol=1e-13) - model.objective("fit", down, tol=1e-13)) / (2 * h)
        assert math.isclose(g[k], fd, rel_tol=1e-6), (name, g[k], fd)
    # an array in the order of vary gives the same
    assert model.objective("fit", [0.6, 0.7, 1.1], vary=["a", "b", "c"], tol=1e-13) == f


def test_a_users_own_bfgs_with_the_gradient():
    """A plain BFGS (numpy, a backtracking line search) on Model.objective and
    Model.gradient: what scipy.optimize.minimize(jac=...) would do, from the same two
    calls; a variant that does not assemble (ValueError) shortens the step."""
    model = mechkin.load(FILE)
    vary = ["a", "b", "c"]
    x = np.array([0.6, 0.7, 1.1])
    f0 = f = model.objective("fit", x, vary=vary)
    g = model.gradient("fit", x, vary=vary)
    h = np.eye(3) * 1e-3
    for _ in range(60):
        p = -h @ g
        step = 1.0
        while step > 1e-12:
            try:
                trial = model.objective("fit", x + step * p, vary=vary)
            except ValueError:
                trial = math.inf
            if trial <= f + 1e-4 * step * g @ p:
                break
            step /= 2
        s_ = step * p
        x, f = x + s_, trial
        g_new = model.gradient("fit", x, vary=vary)
        y = g_new - g
        g = g_new
        if y @ s_ > 0:
            rho = 1 / (y @ s_)
            i3 = np.eye(3)
            h = (i3 - rho * np.outer(s_, y)) @ h @ (i3 - rho * np.outer(y, s_)) + rho * np.outer(s_, s_)
        if f < 1e-20:
            break
    assert f < 1e-12 * f0
    for name, exact, got in zip(vary, closed_form(), x):
        assert math.isclose(got, exact, rel_tol=1e-5), name


def test_bad_requests_raise_value_error_with_why():
    model = mechkin.load(FILE)
    with pytest.raises(ValueError, match="no parameter 'zz'"):
        model.optimize(vary=["zz"], minimize="fit")
    with pytest.raises(ValueError, match="'nope' is not a reduction"):
        model.objective("nope", {"a": 0.6})
    with pytest.raises(ValueError, match="REDUCTION >= NUMBER"):
        model.optimize(vary=["a"], minimize="fit", subject_to=["fit = 1"])
    with pytest.raises(ValueError, match="cannot be evaluated there"):
        model.objective("fit", {"b": 0.01})  # too short a coupler: it does not assemble
