"""The N-link chain in time from Python: conservation laws and the order of the integrator."""
import numpy as np
import pytest

import whirl


def _swinging(n=12, method="gauss2", frame="inertial", omega=0.0):
    """A 3D chain started from the mode-1 shape at 2.385 spun at 0.8 of its rate: not a steady
    state, so it swings and twists."""
    sim = whirl.Simulation(n, omega=omega, frame=frame, method=method)
    s = whirl.shape(2.385, 1, links=n)
    x = np.zeros((n, 3))
    x[:, 0], x[:, 2] = s.r[1:], s.z[1:]
    v = np.zeros((n, 3))
    v[:, 1] = (0.8 * 2.385 - (omega if frame == "rotating" else 0)) * x[:, 0]
    sim.set_state(x, v)
    return sim


def test_energy_conserved_and_gauss2_is_fourth_order():
    errors = []
    for dt in (0.01, 0.005):
        sim = _swinging()
        tr = sim.run(4.0, dt, every=0.5)
        assert tr.constraint.max() < 1e-12
        # no torque about z: L_z conserved (up to the stage solve and the projection)
        assert np.ptp(tr.lz) < 1e-9
        errors.append(np.max(np.abs(tr.energy - tr.energy[0])))
    assert errors[0] < 1e-6
    order = np.log2(errors[0] / errors[1])
    assert 3.5 < order < 4.5, (errors, order)


def test_jacobi_conserved_in_the_rotating_frame():
    sim = _swinging(frame="rotating", omega=2.385, method="gauss3")
    tr = sim.run(3.0, 0.005, every=0.25)
    assert np.max(np.abs(tr.jacobi - tr.jacobi[0])) < 1e-9
    assert tr.deviation[0] == 0 and tr.deviation[-1] > 1e-3


def test_steady_start_stays_steady():
    sim = whirl.Simulation(30, omega=3.5, frame="rotating", method="rk4")
    sim.set_steady(2)
    tr = sim.run(2.0, 0.002, every=1.0, positions=False)
    assert tr.x is None
    assert tr.deviation.max() < 1e-12
    assert tr.stats["steps"] == 1000 and tr.stats["rhs_evals"] == 4000


def test_inertial_positions_rotate_rigidly():
    w = 2.9
    sim = whirl.Simulation(16, omega=w, method="gauss2")
    sim.set_steady(1)
    tr = sim.run(1.0, 0.001, every=0.5)
    x0, x1 = tr.x[0], tr.x[-1]
    c, s = np.cos(w * 1.0), np.sin(w * 1.0)
    rotated = x0 @ np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]])
    np.testing.assert_allclose(x1, rotated, atol=1e-9)


def test_adaptive_run_and_stats():
    sim = _swinging(method="rk8")
    tr = sim.run(2.0, 0.01, every=0.5, tol=1e-10)
    assert tr.stats["steps"] > 0 and tr.stats["rhs_evals"] >= 13 * tr.stats["steps"]
    assert np.max(np.abs(tr.energy - tr.energy[0])) < 1e-8
    np.testing.assert_allclose(tr.t, [0, 0.5, 1.0, 1.5, 2.0])


def test_seed_formulation_agrees_with_default():
    out = []
    for f in ("default", "seed"):
        sim = whirl.Simulation(4, dim=2, method="gauss3", formulation=f)
        x = np.zeros((4, 3))
        th = np.array([0.9, 0.5, -0.3, 0.2])
        x[:, 0], x[:, 2] = np.cumsum(0.25 * np.sin(th)), -np.cumsum(0.25 * np.cos(th))
        sim.set_state(x, np.zeros((4, 3)))
        out.append(sim.run(2.0, 0.001, every=2.0).x[-1])
    np.testing.assert_allclose(out[0], out[1], atol=1e-9)


def test_two_threads_give_the_same_run():
    runs = []
    for threads in (1, 2):
        sim = whirl.Simulation(5000, omega=3.0, method="rk4", threads=threads)
        sim.set_steady(2, perturb=0.01)
        runs.append(sim.run(1e-4, 2e-5, every=5e-5))
    np.testing.assert_array_equal(runs[0].x, runs[1].x)
    np.testing.assert_array_equal(runs[0].energy, runs[1].energy)
    with pytest.raises(whirl.Error, match="threads must be"):
        whirl.Simulation(10, threads=1000)
