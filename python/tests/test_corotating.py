"""A Trajectory's co-rotating positions: a run seeded on a steady shape (or on the hand-swung
chain's trailing shape) stays fixed in the frame turning at omega, where the shape solvers put
it, while its inertial positions go round."""
import numpy as np
import pytest

import whirl


def test_steady_shape_is_fixed_in_the_co_rotating_frame():
    sim = whirl.Simulation(20, omega=3.0)
    sim.set_steady(2)
    run = sim.run(4.0, 1e-3, every=0.1)  # about two turns
    s = whirl.shape(3.0, 2, links=20)  # the steady shape of the steady solver, in the x-z plane
    shape = np.stack([s.r[1:], np.zeros(20), s.z[1:]], axis=1)
    assert np.abs(run.x_rotating - shape).max() < 1e-11
    assert np.abs(run.x - shape).max() > 0.5 * s.tip_r  # the inertial positions turn
    # x_rotating is x turned by -omega t about z
    c, s_ = np.cos(3.0 * run.t)[:, None], np.sin(3.0 * run.t)[:, None]
    x, y = run.x[..., 0], run.x[..., 1]
    np.testing.assert_allclose(run.x_rotating[..., 0], c * x + s_ * y, atol=1e-14)
    np.testing.assert_allclose(run.x_rotating[..., 1], -s_ * x + c * y, atol=1e-14)
    np.testing.assert_array_equal(run.x_rotating[..., 2], run.x[..., 2])
    np.testing.assert_array_equal(run.tip_rotating, run.x_rotating[:, -1])


@pytest.mark.parametrize("frame", ["inertial", "rotating"])
def test_hand_swung_trailing_shape_is_fixed_too(frame):
    # the pivot on a circle of radius eps at omega, with drag: whirl.driven's shape (co-rotating
    # frame, pivot at (eps, 0, 0)) set at t = 0, where the frames coincide
    omega, eps, drag = 3.0, 0.05, 0.05
    d = whirl.driven(omega, 1, eps, air_drag=drag, links=20)
    x = np.stack([d.x[1:], d.y[1:], d.z[1:]], axis=1)
    v = np.zeros_like(x)
    if frame == "inertial":  # the shape's velocity omega z x x
        v[:, 0], v[:, 1] = -omega * x[:, 1], omega * x[:, 0]
    sim = whirl.Simulation(20, omega=omega, drive_radius=eps, air_drag=drag, frame=frame)
    sim.set_state(x, v)
    run = sim.run(4.0, 1e-3, every=0.1)
    assert np.abs(run.x_rotating - x).max() < 1e-11
    assert np.abs(run.x - x).max() > d.tip_r


def test_co_rotating_columns_and_planar_runs():
    u = whirl.Units(length=0.6, mass=0.05)
    sim = whirl.Simulation(6, omega="4Hz", units=u)
    sim.set_steady(1)
    run = sim.run("0.1s", "1ms", every="10ms")
    d = run.as_dict()
    np.testing.assert_array_equal(d["tip_x_rot [m]"], run.x_rotating[:, -1, 0])
    assert d["tip_y_rot [m]"].shape == run.t.shape
    assert sim.run(0.2, 1e-3, positions=False).x_rotating is None
    planar = whirl.Simulation(6, dim=2)
    planar.set_hanging()
    flat = planar.run(0.1, 1e-3)
    assert flat.x is not None and flat.x_rotating is None
    with pytest.raises(ValueError, match="planar"):
        flat.tip_rotating
