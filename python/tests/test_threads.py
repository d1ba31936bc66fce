"""Python objects across threads and forks: a Simulation used from a second thread while a first
runs it is refused (whirl.InUse), not corrupted; separate Simulations run in parallel threads and
agree with a serial run; a child forked by multiprocessing (the default start method on Linux)
after the parent ran the library's OpenMP loops computes instead of hanging in libgomp."""
import os
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import whirl
from whirl import _lib

HERE = os.path.dirname(os.path.abspath(__file__))


def _steady_sim(n=30):
    sim = whirl.Simulation(n, omega=4.0)
    sim.set_steady(2, perturb=1e-3)
    return sim


def test_a_second_thread_is_refused_while_a_run_is_in_progress():
    sim = _steady_sim()
    before = {}
    failure = []

    def long_run():
        try:
            sim.run(1e5, 0.01, every=1e5, positions=False)
        except KeyboardInterrupt:
            pass  # stopped below
        except Exception as e:  # reported to the main thread
            failure.append(e)

    a = threading.Thread(target=long_run)
    a.start()
    try:
        end = time.monotonic() + 60
        while sim.t == 0 and time.monotonic() < end and a.is_alive():
            time.sleep(0.01)
        assert sim.t > 0, "the first run did not start"
        before["t"] = sim.t
        # (RuntimeError: whirl.InUse is one)
        with pytest.raises(RuntimeError, match="in use by another thread .*Simulation.run"):
            sim.run(sim.t + 0.5, 0.01)
        with pytest.raises(RuntimeError, match="in use by another thread"):
            sim.set_steady(2)
        with pytest.raises(RuntimeError, match="in use by another thread"):
            sim.positions()
    finally:
        _lib.lib.whirl_stop_request()  # ends the first run (it is not in the main thread)
        a.join(timeout=60)
        _lib.lib.whirl_stop_clear()
    assert not a.is_alive() and failure == []
    # the object is usable again, from any thread, once the first call has returned
    sim.set_steady(2)
    assert sim.run(0.5, 0.01).t[-1] == 0.5


def test_separate_simulations_run_in_parallel_threads_as_in_series():
    serial = _steady_sim().run(5.0, 0.01, every=0.5)
    out = [None, None]

    def go(k):
        out[k] = _steady_sim().run(5.0, 0.01, every=0.5)

    threads = [threading.Thread(target=go, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)
    for tr in out:
        assert tr is not None
        assert np.array_equal(tr.x, serial.x) and np.array_equal(tr.energy, serial.energy)


def test_same_thread_calls_nest():
    sim = whirl.Simulation(4)
    sim.set_hanging()  # calls set_state inside: the same thread
    assert sim.positions().shape == (4, 3)


def test_max_threads_setting():
    n = whirl.max_threads()
    assert n >= 1
    try:
        whirl.set_max_threads(1)
        assert whirl.max_threads() == 1
        a = whirl.sweep([2], np.linspace(3, 8, 200))[2]["tip_r"]
        whirl.set_max_threads(0)
        assert whirl.max_threads() == n
        b = whirl.sweep([2], np.linspace(3, 8, 200))[2]["tip_r"]
        assert np.array_equal(a, b)  # the same bits on any number of threads
        with pytest.raises(ValueError, match="threads must be >= 0"):
            whirl.set_max_threads(-1)
        with pytest.raises(TypeError):
            whirl.set_max_threads(1.5)
    finally:
        whirl.set_max_threads(0)


SWEEP = textwrap.dedent("""
    import sys
    import numpy as np
    import whirl

    out = whirl.sweep([1, 2, 3], np.linspace(1.0, 12.0, 200))
    out.update({-k: a for k, a in whirl.sweep([1, 2], np.linspace(12.0, 2.0, 150),
                                              tip_mass=0.3).items()})
    np.savez(sys.argv[1], **{str(k): a for k, a in out.items()})
""")


def _sweep_on(threads, tmp_path):
    script = tmp_path / "sweep.py"
    script.write_text(SWEEP)
    path = tmp_path / ("sweep%d.npz" % threads)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads),
               PYTHONPATH=os.path.join(HERE, os.pardir) + os.pathsep
               + os.environ.get("PYTHONPATH", ""))
    p = subprocess.run([sys.executable, str(script), str(path)], env=env, capture_output=True,
                       text=True, timeout=240)
    assert p.returncode == 0, p.stdout + p.stderr
    with np.load(str(path)) as f:
        return {k: f[k] for k in f.files}


def test_a_sweep_is_bitwise_the_same_on_any_number_of_threads(tmp_path):
    one = _sweep_on(1, tmp_path)
    assert all(a.size > 50 for a in one.values())
    for threads in (2, 3):
        other = _sweep_on(threads, tmp_path)
        assert sorted(other) == sorted(one)
        for k in one:
            assert np.array_equal(one[k], other[k]), (threads, k)


def test_the_sweep_command_writes_the_same_bytes_on_any_number_of_threads(whirl_program):
    def run(threads):
        env = dict(os.environ, OMP_NUM_THREADS=str(threads))
        p = subprocess.run([whirl_program, "sweep", "--modes", "1,2,3", "--omega-min", "1",
                            "--omega-max", "12", "--omega-count", "300"], env=env,
                           capture_output=True, timeout=240)
        assert p.returncode == 0, p.stderr
        return p.stdout

    one = run(1)
    assert one.count(b"\n") > 300
    assert run(2) == one and run(3) == one


CHILD = textwrap.dedent("""
    import multiprocessing, sys
    import numpy as np
    import whirl

    def sweep(_):
        return whirl.sweep([2], np.linspace(3, 8, 400))[2]["tip_r"]

    def smap(_):
        return whirl.stability_map(np.linspace(3, 8, 16), 2, links=12)["growth"]

    def threads(_):
        try:
            whirl.set_max_threads(2)
            refused = ""
        except whirl.InvalidInput as e:
            refused = str(e)
        return whirl.max_threads(), refused

    if __name__ == "__main__":
        assert multiprocessing.get_start_method() == "fork"
        # the parent's OpenMP threads (OMP_NUM_THREADS=4) exist from here on
        parent = sweep(0), smap(0)
        with multiprocessing.Pool(2) as pool:
            child = (pool.apply_async(sweep, (0,)).get(timeout=60),
                     pool.apply_async(smap, (0,)).get(timeout=60))
            assert whirl.max_threads() == 4, whirl.max_threads()
            n, refused = pool.apply_async(threads, (0,)).get(timeout=60)
        for a, b in zip(parent, child):
            np.testing.assert_allclose(a, b, rtol=1e-10)
        assert n == 1 and "child of fork()" in refused, (n, refused)
        assert isinstance(whirl.InUse("x"), RuntimeError)
        print("forked children computed")
""")


def test_a_forked_child_computes_after_the_parent_used_its_threads(tmp_path):
    script = tmp_path / "child.py"
    script.write_text(CHILD)
    env = dict(os.environ, OMP_NUM_THREADS="4",
               PYTHONPATH=os.path.join(HERE, os.pardir) + os.pathsep
               + os.environ.get("PYTHONPATH", ""))
    try:
        p = subprocess.run([sys.executable, str(script)], env=env, capture_output=True,
                           text=True, timeout=240)
    except subprocess.TimeoutExpired as e:
        pytest.fail("the forked child hung: %s" % e)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "forked children computed" in p.stdout
