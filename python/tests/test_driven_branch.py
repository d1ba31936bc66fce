"""whirl.driven_branch against ``whirl driven --omega-min A --omega-max B``: every column of the
command line's CSV, to the last bit, through the folds and with the stability of each point;
Ctrl-C keeping the points so far."""
import signal
import subprocess

import numpy as np
import pytest

import whirl


@pytest.fixture(autouse=True)
def python_sigint():
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, old)


def _cli(whirl_program, args):
    """The command line's branch: (comment lines, columns as arrays of str)."""
    out = subprocess.run([whirl_program, "driven"] + args, check=True, capture_output=True,
                         text=True).stdout.splitlines()
    comments = [line for line in out if line.startswith("#")]
    rows = [line.split(",") for line in out if not line.startswith("#")]
    header, rows = rows[0], rows[1:]
    return comments, {name: np.array([r[i] for r in rows]) for i, name in enumerate(header)}


COLUMNS = [("omega", "omega", float), ("tip_x", "tip_x", float), ("tip_y", "tip_y", float),
           ("tip_r", "tip_r", float), ("top_tension", "top_tension", float),
           ("node_count", "nodes", int), ("fold", "fold", lambda s: bool(int(s)))]
STABILITY = [("eig_growth", "eig_growth", float), ("index", "index", int),
             ("verdict", "verdict", str)]


def _same(branch, comments, cli, columns):
    for name, col, conv in columns:
        want = np.array([conv(x) for x in cli[col]])
        assert np.array_equal(getattr(branch, name), want), name
    folds = [float(c.split("=")[1]) for c in comments if c.startswith("# fold omega=")]
    assert np.array_equal(branch.folds, folds)
    assert branch.complete == any("left the interval" in c for c in comments)


def test_branch_with_stability_equals_the_command_line(whirl_program):
    args = ["--omega-min", "1", "--omega-max", "6", "--mode", "2", "--eps", "0.05",
            "--drag-quadratic", "0.015", "--links", "20", "--stability"]
    comments, cli = _cli(whirl_program, args)
    calls = []
    b = whirl.driven_branch(1, 6, 0.05, mode=2, air_drag_quadratic=0.015, links=20,
                            progress=lambda d, t: calls.append((d, t)))
    assert len(b) == len(cli["omega"]) > 100 and b.folds.size >= 1 and b.fold.sum() >= 1
    _same(b, comments, cli, COLUMNS + STABILITY)
    assert set(b.verdict) >= {"unstable"}
    # the part of the work done: the continuation's reach (the first half), then one call per
    # point analysed, the last the total
    n = len(b)
    assert all(t == 1.0 for d, t in calls)
    reach = [d for d, t in calls if d <= 0.5]
    assert len(reach) > 10 and reach[-1] == 0.5
    assert [d for d, t in calls if d > 0.5] == [0.5 + 0.5 * (j + 1) / n for j in range(n)]


def test_continuum_branch_through_its_fold_upwards_and_in_si(whirl_program):
    args = ["--omega-min", "0.6", "--omega-max", "2.2", "--eps", "0.02", "--side", "-1"]
    comments, cli = _cli(whirl_program, args)
    b = whirl.driven_branch(0.6, 2.2, 0.02, side=-1)
    assert b.eig_growth is None and b.folds.size == 1
    _same(b, comments, cli, COLUMNS)
    # from a start inside, upwards
    args = ["--omega-min", "0.6", "--omega-max", "2.2", "--omega", "1.5", "--up", "--eps",
            "0.02", "--side", "-1", "--links", "10"]
    comments, cli = _cli(whirl_program, args)
    b = whirl.driven_branch(0.6, 2.2, 0.02, side=-1, omega=1.5, up=True, links=10,
                            stability=False)
    _same(b, comments, cli, COLUMNS)
    # SI units: the command line's numbers in its units, to round-off of the scalings
    rate = np.sqrt(9.80665 / 0.6)
    args = ["--omega-min", repr(0.6 * rate), "--omega-max", repr(2.2 * rate), "--omega",
            repr(1.5 * rate), "--up", "--eps", "12mm", "--side", "-1", "--links", "10",
            "--length", "0.6", "--mass", "0.05"]
    comments, cli = _cli(whirl_program, args)
    si = whirl.driven_branch(0.6 * rate, 2.2 * rate, "12mm", side=-1, omega=1.5 * rate,
                             up=True, links=10, stability=False, length=0.6, mass=0.05)
    assert len(si) == len(cli["omega"])
    for name, col, conv in COLUMNS:
        want = np.array([conv(x) for x in cli[col]])
        assert np.allclose(getattr(si, name), want, rtol=1e-12, atol=0), name


def test_ctrl_c_keeps_the_points(capfd):
    analysed = []

    def ctrl_c(done, total):  # after the continuation (half the work), at the 10th point
        if done > 0.5:
            analysed.append(done)
            if len(analysed) == 10:
                signal.raise_signal(signal.SIGINT)
    kw = dict(mode=2, air_drag_quadratic=0.015, links=20)
    with pytest.raises(KeyboardInterrupt, match=r"whirl: driven_branch interrupted .*: 10 "
                       r"points") as e:
        whirl.driven_branch(1, 6, 0.05, progress=ctrl_c, **kw)
    assert not whirl.stop_requested()
    part = e.value.partial
    assert len(part) == 10 and part.interrupted and not part.complete
    analysed.clear()
    kept = whirl.driven_branch(1, 6, 0.05, progress=ctrl_c, keep_interrupted=True, **kw)
    assert kept == part
    full = whirl.driven_branch(1, 6, 0.05, **kw)
    assert np.array_equal(full.eig_growth[:10], part.eig_growth)
    assert "interrupted" in repr(part) and "DrivenBranch(" in repr(full)


def test_driven_branch_checks_its_arguments():
    with pytest.raises(ValueError, match="omega_min must be < omega_max"):
        whirl.driven_branch(3, 2, 0.05)
    with pytest.raises(ValueError, match="must be in \\[omega_min, omega_max\\]"):
        whirl.driven_branch(1, 2, 0.05, omega=3)
    with pytest.raises(ValueError, match="stability needs links"):
        whirl.driven_branch(1, 2, 0.05, stability=True)
    with pytest.raises(ValueError, match="arc_step must be in"):
        whirl.driven_branch(1, 2, 0.05, arc_step=2)
    with pytest.raises(whirl.InvalidInput, match="driven_branch: start at omega"):
        whirl.driven_branch(1, 2, 0.0, mode=3, air_drag=0.1)
