"""Bad input from Python: a Python exception with a message naming the problem (TypeError,
ValueError, or whirl.Error carrying the library's message), never a crash."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import whirl


@pytest.mark.parametrize("call,exc,match", [
    (lambda: whirl.critical("3"), TypeError, "modes"),
    (lambda: whirl.critical(-1), ValueError, "modes"),
    (lambda: whirl.critical(3, links=2), ValueError, "modes 1..2"),
    (lambda: whirl.critical(3, tip_mass=float("nan")), ValueError, "tip_mass"),
    (lambda: whirl.shape(float("nan"), 1), ValueError, "omega"),
    (lambda: whirl.shape(-2.0, 1), ValueError, "omega"),
    (lambda: whirl.shape(3.0, 1.5), TypeError, "mode"),
    (lambda: whirl.shape(3.0, 0), ValueError, "mode"),
    (lambda: whirl.shape(3.0, 1, points=1), ValueError, "points"),
    (lambda: whirl.shape(3.0, 1, links=-4), ValueError, "links"),
    (lambda: whirl.shape(3.0, 1, length=0), ValueError, "length"),
    (lambda: whirl.sweep([1], [[1.0, 2.0]]), ValueError, "one-dimensional"),
    (lambda: whirl.sweep([1], ["a"]), ValueError, r"omega\[0\] must be a number"),
    (lambda: whirl.sweep([1], [[1.0], "a"]), TypeError, "omega"),
    (lambda: whirl.sweep([1], [1.0, np.nan]), ValueError, "finite"),
    (lambda: whirl.sweep(["x"], [1.0]), TypeError, "mode"),
    (lambda: whirl.Chain(lengths=[0.5, 0.5], masses=[0.5]), ValueError, "shape"),
    (lambda: whirl.Chain(lengths=[0.5, -0.5], masses=[0.5, 0.5]), ValueError, "lengths"),
    (lambda: whirl.Chain(0), ValueError, "links"),
    (lambda: whirl.Simulation(3, frame="sideways"), ValueError, "frame"),
    (lambda: whirl.Simulation(3, method=5), TypeError, "method"),
    (lambda: whirl.Simulation(3).set_state(np.zeros((2, 3)), np.zeros((2, 3))), ValueError, "x"),
    (lambda: whirl.Simulation(3).run(1.0, 0.1), RuntimeError, "start"),
    (lambda: whirl.stability(3.0, 1, 10, side=0), ValueError, "side"),
    (lambda: whirl.fit([0.1, 0.2], [-0.5, -0.9]), ValueError, "3 points"),
    (lambda: whirl.fit([0.1, 0.2, 0.3], [-0.5, -0.9]), ValueError, "shape"),
    (lambda: whirl.spin_up(3.0, 0.05, 5, bogus=1), TypeError, "bogus"),
])
def test_python_side_checks(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def _library_error(call, name, match):
    with pytest.raises(whirl.Error, match=match) as e:
        call()
    assert e.value.status_name == name
    assert e.value.message == str(e.value)
    assert e.value.message and "\n" not in e.value.message


def test_mode_that_does_not_exist():
    _library_error(lambda: whirl.shape(2.0, 3), "EDOM", "omega_3=4.32686395")
    _library_error(lambda: whirl.shape(2.0, 3, links=20), "EDOM", "mode 3")
    _library_error(lambda: whirl.stability(2.0, 2, 10), "EDOM", "")


def test_library_rejects_bad_model_and_state():
    # an _alloc function returns NULL and leaves its message and its status (whirl_last_status)
    _library_error(lambda: whirl.Simulation(3, dim=2, frame="rotating"), "EINVAL", "")
    sim = whirl.Simulation(3)
    x = np.array([[0, 0, -0.3], [0, 0, -0.6], [0, 0, -0.9]])  # links of 0.3, not 1/3
    _library_error(lambda: sim.set_state(x, np.zeros((3, 3))), "EINVAL", "")


def test_integrator_errors():
    sim = whirl.Simulation(3, method="gauss2")
    sim.set_hanging()
    _library_error(lambda: sim.run(1.0, 0.1, tol=1e-8), "EINVAL", "adaptive")
    stiff = whirl.Simulation(200, method="gauss2", omega=4.0)
    stiff.set_steady(1)
    # far beyond the fixed-point iteration's convergence: the stage solve fails
    _library_error(lambda: stiff.run(1.0, 0.5), "EMAXITER", "")


def test_driven_fit_and_spin_up_errors():
    _library_error(lambda: whirl.driven(3.0, 1, 0.0, air_drag=0.1), "EDOM", "")
    _library_error(lambda: whirl.spin_up(3.0, 0.05, 5, t_ramp=0.0), "EINVAL", "t_ramp")
    r = np.linspace(0.1, 0.3, 5)
    _library_error(lambda: whirl.fit(r, -r, mode=3, omega_max=2.0), "EDOM", "")


@pytest.fixture(autouse=True)
def python_sigint():
    """Python's own SIGINT handler, as in an interactive session, also where the suite runs
    with SIGINT ignored (started in the background): a call is interruptible only then."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, old)


def test_ctrl_c_interrupts_a_long_run_and_restores_python_handler():
    handler = signal.getsignal(signal.SIGINT)
    sim = whirl.Simulation(400, omega=3.0, method="rk4")
    sim.set_steady(2)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt, match="Simulation.run at t = .* interrupted"):
        sim.run(1e3, 1e-4, every=1e3, positions=False)  # hours if not interrupted
    assert time.monotonic() - start < 5
    assert 0 < sim.t < 1e3
    assert signal.getsignal(signal.SIGINT) is handler
    assert not whirl.stop_requested()
    # Python's own handler is back: SIGINT outside a library call is Python's KeyboardInterrupt
    # (raise_signal delivers it to this thread and runs the handler before it returns; a
    # process-directed kill may land on another thread and reach Python only later)
    with pytest.raises(KeyboardInterrupt):
        signal.raise_signal(signal.SIGINT)


def test_ctrl_c_interrupts_a_spin_up():
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        whirl.spin_up(4.0, 0.05, 200, air_drag=0.05, t_max=2e4)
    assert time.monotonic() - start < 5


def test_ctrl_c_interrupts_a_scene(tmp_path):
    scene = tmp_path / "long.ini"
    scene.write_text("[chain]\ndim = 3\nlinks = 100\n[start]\nomega = 3\nmode = 2\n"
                     "[run]\ndt = 0.001\nt_end = 50000\n[output]\nevery = 1000\n")
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        whirl.run_scene(scene)  # hours if not interrupted
    assert time.monotonic() - start < 5
    assert not whirl.stop_requested()


# ---- errors in the caller's units ----
# A 60 cm, 50 g chain: the library works in L, M, g = 1 and types the quantities of its messages,
# which reach the caller in SI units (rates in rad/s, lengths in m, times in s, drags in
# kg/(m s)); no dimensionless number of the quantities given may appear.
SI = whirl.Units(length=0.6, mass=0.05)


def _message(call):
    with pytest.raises(whirl.Error) as e:
        call()
    return str(e.value)


def test_run_error_quotes_the_step_in_seconds():
    sim = whirl.Simulation(200, method="gauss2", omega="4Hz", units=SI)
    sim.set_steady(1)
    msg = _message(lambda: sim.run(1.0, "100ms"))
    assert "(step 0.1 s too large" in msg, msg
    assert "at t = 0 s" in msg, msg
    # the dimensionless step, 0.1 s / sqrt(L/g), is not quoted
    assert ("%.6g" % (0.1 / SI.time)) not in msg


def test_stability_error_quotes_dt_in_seconds():
    msg = _message(lambda: whirl.stability("4Hz", 2, 30, damping=1e-3, method="gauss2",
                                           dt="50ms", periods=5, units=SI))
    # the step asked for, and the one that failed (the run's steps end at its samples: 40
    # per period of 0.25 s)
    assert "gauss2 with dt = 0.05 s" in msg, msg
    assert "(step 0.005 s too large" in msg, msg
    msg = _message(lambda: whirl.stability("4Hz", 2, 30, dt="1e-13 s", periods=5, units=SI))
    assert "steps of 1e-13 s" in msg, msg
    assert ("%.6g" % (1e-13 / SI.time)) not in msg


def test_driven_error_quotes_eps_and_drag_in_si():
    msg = _message(lambda: whirl.driven("3Hz", 1, "1cm", air_drag=100.0, units=SI))
    assert "eps = 0.01 m, drag = 100 kg/(m s), 0 kg/m^2" in msg, msg
    assert ("%.6g" % (0.01 / SI.length)) not in msg
    msg = _message(lambda: whirl.driven("3Hz", 1, 10.0, units=SI))
    assert "smaller than the chain length 0.6 m, got 10 m" in msg, msg
    msg = _message(lambda: whirl.driven("3Hz", 1, 0.01, air_drag=1e7, units=SI))
    assert "got 10000000 kg/(m s), 0 kg/m^2" in msg, msg
    # dimensionless: the numbers as given
    msg = _message(lambda: whirl.driven(3.0, 1, 0.01, air_drag=3000.0))
    assert "eps = 0.01, drag = 3000, 0" in msg, msg


def test_set_steady_error_quotes_rates_in_rad_per_s():
    sim = whirl.Simulation(10, omega="1Hz", units=SI)
    msg = _message(lambda: sim.set_steady(3))
    assert "mode 3 does not exist at omega=6.28318530717959 rad/s" in msg, msg
