"""progress= on the long calls: a callable gets (done, total) never decreasing, ending at
(total, total) on completion; an exception it raises (also from a thread of the library's) is
the call's; progress=True draws a tqdm bar or a line on standard error; Ctrl-C still stops a
call that reports progress, naming the call."""
import os
import signal
import sys
import threading
import time
import types

import numpy as np
import pytest

import whirl


@pytest.fixture(autouse=True)
def python_sigint():
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, old)


class Calls(list):
    def __call__(self, done, total):
        self.append((done, total))

    def check(self, total=None):
        """Never decreasing, never past the total, one total throughout, ending there."""
        assert self, "never called"
        dones = [d for d, t in self]
        totals = {t for d, t in self}
        assert len(totals) == 1, totals
        (t,) = totals
        assert all(b > a for a, b in zip(dones, dones[1:])), dones
        assert 0 <= dones[0] and dones[-1] == t
        if total is not None:
            assert t == pytest.approx(total, rel=1e-15)
        return t


def test_stability_map_reports_each_point_from_the_librarys_threads():
    calls = Calls()
    out = whirl.stability_map(np.linspace(3, 6, 24), 2, 12, progress=calls)
    assert calls.check(len(out)) == 24
    assert len(calls) == 24
    # the same numbers as without progress
    assert np.array_equal(out, whirl.stability_map(np.linspace(3, 6, 24), 2, 12))


def test_sweep_windows_run_and_spin_up_report_their_progress():
    calls = Calls()
    whirl.sweep([1, 2, 3], np.linspace(1, 5, 40), progress=calls)
    assert calls == [(1, 3), (2, 3), (3, 3)]
    calls = Calls()
    whirl.stability_windows(2, omega_min=3, omega_max=5, progress=calls)
    calls.check(2.0)
    assert len(calls) > 3  # the rates of the scan
    calls = Calls()
    whirl.stability_windows(2, 8, omega_min=3, omega_max=5, progress=calls)
    assert calls == [(2.0, 2.0)]  # the N-link search reports its end only
    calls = Calls()
    sim = whirl.Simulation(5, omega=3.0, method="rk4")
    sim.set_steady(2)
    tr = sim.run(2.0, 1e-3, every=0.5, progress=calls)
    calls.check(2.0)
    assert len(calls) >= 8 and tr.t[-1] == 2.0  # 2000 steps: calls of 256 steps at most
    calls = Calls()
    r = whirl.stability(3.0, 2, 5, periods=5, progress=calls)
    calls.check(5 * 2 * np.pi / 3.0)
    assert r.duration == pytest.approx(calls[-1][1], rel=1e-12)
    calls = Calls()
    whirl.spin_up(3.0, 0.05, 5, air_drag=0.1, t_max=60, progress=calls)
    assert len(calls) > 10
    calls.check(60 + 60 * 2 * np.pi / 3.0)  # t_max and the Lyapunov window
    calls = Calls()
    whirl.dissipative_windows(2, 8, damping=0.01, omega_min=3, omega_max=4, progress=calls)
    assert calls == [(1, 1)]


def test_fit_and_scene_report_their_progress(tmp_path):
    shape = whirl.shape(6.0, 2, points=60)
    calls = Calls()
    res = whirl.fit(shape.r, shape.z, omega_max=8.0, progress=calls)
    t = calls.check()
    assert res.mode == 2 and t >= 2 and len(calls) == t + 1  # 0 .. the modes tried
    scene = tmp_path / "s.ini"
    scene.write_text("[chain]\ndim = 3\nlinks = 5\n[start]\nomega = 3\nmode = 2\n"
                     "[run]\ndt = 0.01\nt_end = 1\n[output]\nevery = 0.5\n")
    calls = Calls()
    whirl.run_scene(scene, progress=calls)
    calls.check(1.0)
    assert len(calls) >= 100  # every fixed step


def test_si_units_report_seconds():
    calls = Calls()
    sim = whirl.Simulation(5, omega="3Hz", method="rk4", length=0.6, mass=0.05)
    sim.set_steady(2)
    sim.run("0.2s", "1ms", every="0.1s", progress=calls)
    calls.check(0.2)


def test_an_exception_of_the_callback_is_the_calls():
    class Stop(Exception):
        pass

    def stop_at_5(done, total):
        if done >= 5:
            raise Stop("enough")
    with pytest.raises(Stop, match="enough"):  # raised in a thread of the library's
        whirl.stability_map(np.linspace(3, 6, 24), 2, 12, progress=stop_at_5)
    assert not whirl.stop_requested()
    sim = whirl.Simulation(5, omega=3.0, method="rk4")
    sim.set_steady(2)
    with pytest.raises(Stop):
        sim.run(2.0, 1e-3, progress=lambda d, t: stop_at_5(d * 10, t))
    with pytest.raises(Stop):
        whirl.stability(3.0, 2, 5, periods=5, progress=lambda d, t: stop_at_5(d, t))
    assert not whirl.stop_requested()
    # the library works on as before
    assert len(whirl.stability_map(np.linspace(3, 6, 4), 2, 12)) == 4
    with pytest.raises(TypeError, match="progress must be"):
        whirl.sweep(1, [2.0], progress="yes")


def test_true_without_tqdm_writes_a_line_on_stderr(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "tqdm", None)  # not importable
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    whirl.sweep([1, 2], np.linspace(1, 5, 10), progress=True)
    err = capsys.readouterr().err
    assert err.endswith("whirl: sweep: 2/2 modes (100%)\n")
    assert "\r" in err


def test_true_with_tqdm_updates_a_bar(monkeypatch):
    bars = []

    class Bar:
        def __init__(self, total, desc, unit, leave):
            self.total, self.desc, self.n, self.closed = total, desc, 0, False
            bars.append(self)

        def update(self, k):
            assert k > 0
            self.n += k

        def close(self):
            self.closed = True
    auto = types.ModuleType("tqdm.auto")
    auto.tqdm = Bar
    monkeypatch.setitem(sys.modules, "tqdm", types.ModuleType("tqdm"))
    monkeypatch.setitem(sys.modules, "tqdm.auto", auto)
    out = whirl.stability_map(np.linspace(3, 6, 12), 2, 8, progress=True)
    (bar,) = bars
    assert bar.desc == "whirl: stability_map" and bar.total == len(out) == bar.n
    assert bar.closed


def test_ctrl_c_stops_a_call_that_reports_progress():
    calls = Calls()
    sim = whirl.Simulation(400, omega=3.0, method="rk4")
    sim.set_steady(2)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt, match="Simulation.run at t = .* interrupted"):
        sim.run(1e3, 1e-4, every=1e3, positions=False, progress=calls)
    assert time.monotonic() - start < 5
    assert calls and not whirl.stop_requested()
    dones = [d for d, t in calls]
    assert all(b > a for a, b in zip(dones, dones[1:]))
    # the map: its callback runs on the library's threads while the signal comes
    calls = Calls()
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt, match="stability_map"):
        whirl.stability_map(np.linspace(3, 6, 400), 2, 150, progress=calls)
    assert not whirl.stop_requested()


def test_critical_equilibria_and_a_batch_of_shapes_report_their_progress():
    calls = Calls()
    rates = whirl.critical(2000, links=2000, progress=calls)
    assert calls.check(2000) == 2000 and len(calls) == 20  # blocks of 100 rates
    assert np.array_equal(rates, whirl.critical(2000, links=2000))
    calls = Calls()
    whirl.critical(3, progress=calls)
    assert calls == [(3, 3)]
    calls = Calls()
    rows, evidence = whirl.equilibria(9.0, links=5, progress=calls)
    calls.check(6)  # the N-link search's stages
    assert len(calls) > 6
    plain = whirl.equilibria(9.0, links=5)
    assert np.array_equal(rows["tip_r"], plain[0]["tip_r"]) and evidence == plain[1]
    calls = Calls()
    whirl.equilibria(8.0, progress=calls)
    calls.check(2)
    calls = Calls()
    shapes = whirl.shape(np.linspace(3, 6, 10), 2, links=20, progress=calls)
    assert calls == [(k, 10) for k in range(1, 11)] and len(shapes) == 10
    calls = Calls()
    whirl.shape(3.0, 2, links=20, progress=calls)
    assert calls == [(1, 1)]


def test_driven_branch_reports_its_continuation():
    calls = Calls()
    out = whirl.driven_branch(0.8, 2.0, 0.02, side=-1, progress=calls)
    calls.check(1.0)
    assert len(calls) > 10 and out.complete
    assert np.array_equal(out.omega, whirl.driven_branch(0.8, 2.0, 0.02, side=-1).omega)
    # with the stability of its points: the continuation, then the points
    calls = Calls()
    out = whirl.driven_branch(2.0, 3.0, 0.02, links=6, progress=calls)
    calls.check(1.0)
    dones = [d for d, t in calls]
    assert 0.5 in dones and len([d for d in dones if d > 0.5]) == len(out)


def _sigint_at(k, calls):
    """A progress callable that records its calls and sends SIGINT to this process at the
    k-th (the library's handler takes it: a stop request, seen right after)."""
    def progress(done, total):
        calls.append((done, total))
        if len(calls) == k:
            os.kill(os.getpid(), signal.SIGINT)
    return progress


def test_ctrl_c_keeps_what_the_long_calls_computed():
    calls = Calls()
    with pytest.raises(KeyboardInterrupt, match="shape interrupted: 3 of 10 shapes") as e:
        whirl.shape(np.linspace(3, 6, 10), 2, links=20, progress=_sigint_at(3, calls))
    assert len(e.value.partial) == 3 and not whirl.stop_requested()
    assert e.value.partial[2] == whirl.shape(np.linspace(3, 6, 10)[2], 2, links=20)
    full = whirl.driven_branch(0.8, 2.0, 0.02, side=-1)
    calls = Calls()
    out = whirl.driven_branch(0.8, 2.0, 0.02, side=-1, keep_interrupted=True,
                              progress=_sigint_at(5, calls))
    assert out.interrupted and not out.complete and 5 <= len(out) < len(full)
    assert np.array_equal(out.omega, full.omega[:len(out)]) and not whirl.stop_requested()
    calls = Calls()
    with pytest.raises(KeyboardInterrupt, match="driven_branch interrupted") as e:
        whirl.driven_branch(0.8, 2.0, 0.02, side=-1, progress=_sigint_at(5, calls))
    assert np.array_equal(e.value.partial.omega, out.omega)
    calls = Calls()
    with pytest.raises(KeyboardInterrupt, match="critical interrupted"):
        whirl.critical(2000, links=2000, progress=_sigint_at(2, calls))
    assert len(calls) == 2 and not whirl.stop_requested()
    calls = Calls()
    with pytest.raises(KeyboardInterrupt, match="equilibria interrupted"):
        whirl.equilibria(9.0, links=5, progress=_sigint_at(3, calls))
    assert len(calls) == 3 and not whirl.stop_requested()
