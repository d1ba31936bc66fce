"""Stiff runs: damping or drag whose decay is too fast for the fixed step. A Simulation whose
method was not named takes the implicit method then (with a StiffWarning saying why); a method
named is kept and its failure says why."""
import warnings

import numpy as np
import pytest

import whirl

# 30 links, D = 1e-3: the fastest decay 16 D N^3 = 432, so dt = 0.01 is 4.3 times the rate
# (past the Gauss fixed point's 3.46 and rk4's 2.785), dt = 2e-4 is 0.086
D = 1e-3


def _sim(method=None, **model):
    sim = whirl.Simulation(30, omega=3.0, method=method, **model)
    sim.set_steady(1, perturb=1e-3, seed=1)
    return sim


def test_stiff_rate_is_the_damping_bound():
    assert _sim(internal_damping=D).stiff_rate == pytest.approx(16 * D * 30 ** 3, rel=1e-12)
    assert _sim().stiff_rate == 0
    u = whirl.Units(length=0.6, mass=0.05)
    sim = whirl.Simulation(30, omega="3Hz", internal_damping=D * u.damping, units=u)
    assert sim.stiff_rate == pytest.approx(16 * D * 30 ** 3 * u.rate, rel=1e-12)


# m l^2 = 0.006, 0.025, 0.048 (the least is not min m min l^2 = 0.001); l / m = 1/6, 5, 4/3
_LENGTHS, _MASSES = [0.1, 0.5, 0.4], [0.6, 0.1, 0.3]


@pytest.mark.parametrize("model", [
    dict(internal_damping=0.03), dict(air_drag=7.0),
    dict(air_drag_quadratic=4.0, drive_radius=0.2),
    dict(internal_damping=0.01, air_drag=1.5, air_drag_quadratic=4.0, drive_radius=0.2)])
def test_stiff_rate_of_a_non_uniform_chain_is_the_formula(model):
    # whirl_model_stiff_rate's formula (whirl/dynamics.h): 16 D / min(m l^2) + max(l / m)
    # (c + 2 c2 |omega| (L + eps))
    chain = whirl.Chain(lengths=_LENGTHS, masses=_MASSES)
    sim = whirl.Simulation(chain, omega=-2.5, **model)
    lengths, masses = np.array(_LENGTHS), np.array(_MASSES)
    speed = 2.5 * (lengths.sum() + model.get("drive_radius", 0.0))
    want = (16 * model.get("internal_damping", 0.0) / (masses * lengths ** 2).min()
            + (lengths / masses).max() * (model.get("air_drag", 0.0)
                                          + 2 * model.get("air_drag_quadratic", 0.0) * speed))
    assert sim.stiff_rate == pytest.approx(want, rel=1e-14)


def test_both_sources_are_named():
    sim = _sim(internal_damping=D, air_drag=500.0)  # 432 and 500
    assert sim.stiff_rate == pytest.approx(932.0, rel=1e-12)
    with pytest.warns(whirl.StiffWarning, match="the internal damping and the air drag make "
                      "the chain stiff"):
        assert sim.run(0.05, 0.01).method == "gsl-msbdf"


def test_default_method_falls_back_to_the_implicit_one_and_says_why():
    with pytest.warns(whirl.StiffWarning, match=r"the internal damping makes the chain stiff "
                      r"\(decay rates up to about 4.3e\+02 sqrt\(g/L\), dt x rate = 4.3\).*"
                      r"this run takes gsl-msbdf"):
        run = _sim(internal_damping=D).run(1.0, 0.01, every=0.1)
    assert run.method == "gsl-msbdf" and run.stats["steps"] > 0
    assert issubclass(whirl.StiffWarning, RuntimeWarning)
    # against the default method itself at a step 50 times smaller, inside its stable range
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ref = _sim(internal_damping=D).run(1.0, 2e-4, every=0.1)
    assert ref.method == "gauss2"
    assert np.abs(run.x - ref.x).max() < 1e-6
    assert np.abs(run.deviation - ref.deviation).max() < 1e-6 * ref.deviation.max() + 1e-9


@pytest.mark.parametrize("method,failure", [("gauss2", "Gauss stage iteration diverges"),
                                            ("rk4", "not finite")])
def test_named_method_is_kept_and_its_failure_says_why(method, failure):
    sim = _sim(method, internal_damping=D)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(whirl.Error, match=failure + r".*; the internal damping makes the "
                           r"chain stiff .*fixed steps of %s need dt below about 0.0046, or "
                           r"method='gsl-msbdf' with tol" % method):
            sim.run(1.0, 0.01)


def test_not_stiff_and_named_implicit_runs_take_no_fallback():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _sim(internal_damping=1e-4).run(0.2, 0.01).method == "gauss2"  # h rate 0.43
        run = _sim("gsl-msbdf", internal_damping=D).run(0.2, 0.01, tol=1e-8)
    assert run.method == "gsl-msbdf"


def test_air_drag_makes_the_chain_stiff_too():
    # linear drag c per length on links of l = m = 1/30: decay rate c l / m = c
    sim = _sim(air_drag=500.0)
    assert sim.stiff_rate == pytest.approx(500.0, rel=1e-12)
    with pytest.warns(whirl.StiffWarning, match="the air drag makes the chain stiff"):
        assert sim.run(0.2, 0.01).method == "gsl-msbdf"
