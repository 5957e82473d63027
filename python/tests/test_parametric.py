"""Parameters, sensitivities and sweeps from Python (issue "Parametric designs")."""
import math
import os
import pickle

import pytest

import mechkin

HERE = os.path.dirname(os.path.abspath(__file__))
SLIDER = os.path.join(HERE, "..", "..", "mechanisms", "parametric-slider-crank.json")
FOUR_BAR = os.path.join(HERE, "..", "..", "mechanisms", "parametric-four-bar.json")


def test_with_parameters_recompiles_and_pickles():
    m = mechkin.load(SLIDER)
    assert m.parameters["crank"] == 40
    assert m.parameter_info["rod"]["tolerance"] == 0.05
    m2 = m.with_parameters(crank=45)
    assert m2.parameters["crank"] == 45
    assert m2.parameters["pin_x"] == pytest.approx(45 * math.cos(math.pi / 6), abs=1e-12)
    again = pickle.loads(pickle.dumps(m2))
    assert again.parameters["crank"] == 45
    with pytest.raises(mechkin.FormatError) as e:
        m.with_parameters(rod=5)
    assert "/parameters/slider_x" in str(e.value)


def test_sensitivity_columns_match_closed_form():
    m = mechkin.load(SLIDER)
    motion = m.run(order=1, sensitivity=["rod"], outputs="piston", bodies=[])
    c, L, e = 40.0, 120.0, 10.0
    for t, d in zip(motion.t, motion.sensitivity("piston.x", "rod")):
        th = math.radians(30 + 360 * t)
        assert d == pytest.approx(L / math.sqrt(L * L - (e - c * math.sin(th)) ** 2), abs=1e-9)
    back = pickle.loads(pickle.dumps(motion))
    assert back.sensitivity("piston.x", "rod")[5] == motion.sensitivity("piston.x", "rod")[5]


def _same(a, b):
    if isinstance(a, float) and math.isnan(a):
        return isinstance(b, float) and math.isnan(b)
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    return a == b


def _variants():
    # b = 5: b + c < |BD| at the start, no assembly; others: cranks, limits, change points
    return [{"a": a, "b": b} for a in (30.0, 45.0, 60.0) for b in (5.0, 120.0, 160.0)]


def test_local_sweep_reports_every_kind_of_variant():
    m = mechkin.load(FOUR_BAR)
    out = mechkin.sweep(m, _variants(), threads=2)
    assert len(out) == 9
    statuses = set(out["status"])
    assert "complete" in statuses and "invalid" in statuses
    nominal_like = out.iloc[3 * 0 + 1]  # a = 30, b = 120: a Grashof crank-rocker
    assert nominal_like["status"] == "complete" and nominal_like["rows"] == 73
    invalid = out[out["status"] == "invalid"].iloc[0]
    assert "acos" in invalid["message"]


def test_sweep_on_a_dask_local_cluster_matches_local_threads():
    distributed = pytest.importorskip("distributed")
    import pandas
    m = mechkin.load(FOUR_BAR)
    local = mechkin.sweep(m, _variants(), threads=2)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = mechkin.sweep(m, _variants(), client=client)
    pandas.testing.assert_frame_equal(local, remote)
    assert local.attrs == remote.attrs
