"""Stability from Python: the linear growth against the perturbed run, and verdicts."""
import numpy as np
import pytest

import whirl


def test_mode2_unstable_run_grows_at_the_eigenvalue_rate():
    r = whirl.stability(4.45, 2, 20)
    assert r.verdict == "unstable"
    assert r.eig_growth > 0.01
    assert r.eig_growth == pytest.approx(np.max(r.eigenvalues.real), rel=1e-12)
    # the perturbed nonlinear run and the linearisation are two independent routes
    assert r.sim_growth == pytest.approx(r.eig_growth, rel=0.02)


def test_mode1_is_stable_and_damping_makes_it_converge():
    r = whirl.stability(2.385, 1, 10, periods=30)
    assert r.verdict == "stable (minimum)" and r.eig_growth == 0 and r.index == 0
    # conservative: eigenvalues on the imaginary axis, in conjugate pairs
    assert np.max(np.abs(r.eigenvalues.real)) < 1e-8
    d = whirl.stability(2.385, 1, 10, damping=0.01, linear=True)
    assert d.eig_growth < 0 and d.verdict == "converging"


def test_stability_map_matches_single_points():
    omega = np.linspace(4.0, 5.0, 11)
    m = whirl.stability_map(omega, 2, 20)
    np.testing.assert_array_equal(m["omega"], omega)
    for row in m[::5]:
        r = whirl.stability(row["omega"], 2, 20, linear=True)
        assert row["growth"] == pytest.approx(r.eig_growth, rel=1e-8, abs=1e-12)
    assert np.any(m["growth"] > 0) and np.any(m["growth"] == 0)


def test_high_rate_shapes_come_from_the_branch():
    # N = 15, mode 7 at omega 150: the tip radius (2.6e-5) does not fix the shape; the shape,
    # the map and the single point all use the branch's nodes (pivot on the axis, balanced)
    s = whirl.shape(150, 7, links=15)
    assert s.r[0] == 0
    # the force across each link from the loads m (omega^2 r, -g) below it, over M (g + w^2 L)
    fr = np.cumsum((150.0**2 * s.r[1:] / 15)[::-1])[::-1]
    fz = -np.arange(15, 0, -1) / 15
    ur, uz = np.diff(s.r), np.diff(s.z)
    across = np.abs(fr * uz - fz * ur) / np.hypot(ur, uz)
    assert np.max(across) < 1e-13 * (1 + 150.0**2)
    m = whirl.stability_map(np.array([100.0, 150.0]), 7, 15)
    r = whirl.stability(150, 7, 15, linear=True)
    assert r.eig_growth > 30
    assert m["growth"][-1] == pytest.approx(r.eig_growth, rel=1e-12)


def test_driven_shape_trails_and_counts_its_node():
    d = whirl.driven(3.0, 1, 0.05, air_drag=0.1)
    assert d.node_count == 1 and d.residual < 1e-9
    assert d.tip[1] < 0  # the drag makes the tip trail behind the pivot
    assert d.x[0] == pytest.approx(0.05) and d.z[-1] < 0
    free = whirl.driven(3.0, 1, 0.0)
    assert free.tip_r == pytest.approx(whirl.shape(3.0, 1).tip_r, rel=1e-9)


def test_windows_edges_agree_with_the_full_linearisation():
    windows, stats = whirl.stability_windows(2, 20, 3.0, 6.0)
    assert len(windows) >= 1 and stats["shapes"] > 0
    for w in windows:
        # the reduced (lambda^2) eigenproblem's edges against the full first-order one
        inside = whirl.stability(0.5 * (w["from"] + w["to"]), 2, 20, linear=True)
        assert inside.eig_growth > 0
        best = whirl.stability(w["at"], 2, 20, linear=True)
        assert best.eig_growth == pytest.approx(w["max_growth"], rel=1e-6)
        for edge, outside in ((w["from"], w["from"] - 1e-4), (w["to"], w["to"] + 1e-4)):
            assert whirl.stability(outside, 2, 20, linear=True).eig_growth == 0
    with pytest.raises(whirl.Error):
        whirl.stability_windows(3, 20, 1.0, 2.0)  # mode 3 is born at 4.3


def test_mode2_is_a_saddle_held_by_the_coriolis_coupling():
    # mode 2 outside its windows: linearly neutral, yet two negative directions of the amended
    # potential; with damping it grows (Kelvin-Tait-Chetaev), mode 1 (a minimum) converges
    r = whirl.stability(4.5, 2, 12, linear=True)
    assert r.eig_growth == 0 and r.index == 2 and r.verdict == "neutral (gyroscopic)"
    d = whirl.stability(4.5, 2, 12, damping=0.001, linear=True)
    assert d.eig_growth > 0 and d.index == 2 and d.verdict == "unstable"


def test_dissipative_windows_edges_are_roots_of_the_growth():
    # the hand-swung chain with linear drag, tip opposite the pivot: converging, unstable, converging
    kw = dict(drive_radius=0.02, air_drag=0.01, side=-1)
    w, stats = whirl.dissipative_windows(2, 10, omega_min=2, omega_max=6, **kw)
    assert list(w["verdict"]) == ["converging", "unstable", "converging"]
    assert stats["scan"] > 10
    for edge in (w["to"][0], w["to"][1]):
        below = whirl.stability(edge - 1e-6, 2, 10, linear=True, **kw).eig_growth
        above = whirl.stability(edge + 1e-6, 2, 10, linear=True, **kw).eig_growth
        assert below * above < 0
    # internal damping: a saddle grows at every rate (Kelvin-Tait-Chetaev)
    d, _ = whirl.dissipative_windows(2, 10, damping=1e-3, omega_min=3, omega_max=6)
    assert list(d["verdict"]) == ["unstable"] and d["open_from"][0] and d["open_to"][0]
    with pytest.raises(whirl.Error, match="no dissipation"):
        whirl.dissipative_windows(2, 10)
    with pytest.raises(ValueError, match="side"):
        whirl.dissipative_windows(2, 10, damping=1e-3, side=0)


def test_three_driven_shapes_at_one_rate():
    # past the fold (omega 1.5, eps 0.05, 20 links) the forced chain has three shapes: mode 1 on
    # the pivot's side (a minimum), on the far side (unstable, index 1) and mode 0, the near-axis
    # one on the far side (neutral, index 2); below resonance mode 0 alone, a minimum
    near = whirl.stability(1.5, 0, 20, linear=True, drive_radius=0.05)
    assert (near.verdict, near.index, near.eig_growth) == ("neutral (gyroscopic)", 2, 0)
    big = whirl.stability(1.5, 1, 20, linear=True, drive_radius=0.05)
    assert (big.verdict, big.index) == ("stable (minimum)", 0)
    far = whirl.stability(1.5, 1, 20, linear=True, drive_radius=0.05, side=-1)
    assert (far.verdict, far.index) == ("unstable", 1) and far.eig_growth > 0.1
    assert near.tip_r < 0.25 < far.tip_r < big.tip_r
    shape = whirl.driven(1.5, 0, 0.05, links=20)
    assert shape.tip[0] < 0 and shape.tip_r == pytest.approx(near.tip_r, rel=1e-12)
    low = whirl.stability(0.8, 0, 20, linear=True, drive_radius=0.05)
    assert (low.verdict, low.index) == ("stable (minimum)", 0)
    with pytest.raises(ValueError):
        whirl.stability(1.5, 0, 20, linear=True)  # mode 0 is the hand-swung chain's


def test_modes_and_a_run_seeded_along_the_unstable_one():
    r = whirl.stability(6.3, 2, 12, linear=True, modes=True)
    count = len(r.eigenvalues)
    assert r.displacements.shape == (count, 13, 3) and r.angles.shape == (count, 24)
    assert r.krein.shape == (count,)
    # the pivot does not move; each mode's largest node displacement is 1
    assert np.all(r.displacements[:, 0, :] == 0)
    big = np.sqrt(np.max(np.sum(np.abs(r.displacements) ** 2, axis=2), axis=1))
    assert np.allclose(big, 1, rtol=0, atol=1e-12)
    # neutral modes carry a signature, the growing and decaying ones none
    neutral = np.abs(r.eigenvalues.real) <= 1e-10 * np.max(np.abs(r.eigenvalues))
    assert np.all(r.krein[neutral] != 0) and np.all(r.krein[~neutral] == 0)
    # the run seeded along the fastest-growing mode grows at its Re lambda
    top = int(np.argmax(r.eigenvalues.real))
    s = whirl.stability(6.3, 2, 12, along=top, perturb=1e-9, method="gauss2")
    assert s.verdict == "unstable"
    assert s.sim_growth == pytest.approx(r.eigenvalues[top].real, rel=1e-3)
    with pytest.raises(ValueError, match="along"):
        whirl.stability(6.3, 2, 12, along=count)


def test_modes_in_si_units_are_scaled_to_one_metre():
    d = whirl.stability(4.5, 2, 6, linear=True, modes=True)
    s = whirl.stability(4.5 * np.sqrt(9.80665 / 0.6), 2, 6, linear=True, modes=True,
                        length=0.6, mass=0.05)
    assert np.allclose(s.displacements, d.displacements, rtol=0, atol=1e-9)
    assert np.allclose(s.angles * 0.6, d.angles, rtol=0, atol=1e-9)
    assert np.array_equal(s.krein, d.krein)


def test_simulation_started_along_the_unstable_mode_grows_at_its_eigenvalue():
    r = whirl.stability(6.3, 2, 12, linear=True, modes=True)
    top = int(np.argmax(r.eigenvalues.real))
    sim = whirl.Simulation(12, omega=6.3, frame="rotating", method="gauss2")
    sim.set_steady(2, along=r.angles[top], amplitude=1e-8)
    tr = sim.run(80, 0.005, every=0.05, positions=False)
    # the slope of log(deviation) over [30, 80], past the start's decaying partner -lambda
    # (deviation 1e-4 L at the end: still linear)
    m = tr.t >= 30
    slope = np.polyfit(tr.t[m], np.log(tr.deviation[m]), 1)[0]
    assert slope == pytest.approx(r.eigenvalues[top].real, rel=1e-4)
    with pytest.raises(ValueError, match="2N = 24"):
        sim.set_steady(2, along=r.angles[top][:5])
    with pytest.raises(ValueError, match="not both"):
        sim.set_steady(2, along=r.angles[top], perturb=1e-3)
    with pytest.raises(whirl.Error, match="zero"):
        sim.set_steady(2, along=np.zeros(24))
