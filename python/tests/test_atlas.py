"""whirl.atlas against ``whirl windows --atlas``: the same file byte for byte, each resuming the
other's interrupted file, Ctrl-C keeping the chunks finished, the lock and the header checked.
A small atlas: modes 2 and 3 to omega 6 (four chunks, three windows' worth of work)."""
import fcntl
import os
import shutil
import signal
import re
import subprocess
import threading
import time

import numpy as np
import pytest

import whirl

ARGS = ["windows", "--atlas", "--modes", "2,3", "--omega-max", "6"]
KW = dict(modes=[2, 3], omega_max=6)


@pytest.fixture(autouse=True)
def python_sigint():
    """Python's own SIGINT handler (the suite may run with SIGINT ignored, in the
    background): a call is interruptible only then."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, old)


@pytest.fixture(scope="module")
def cli_atlas(whirl_program, tmp_path_factory):
    """The command line's atlas file (its text)."""
    path = tmp_path_factory.mktemp("atlas") / "cli.csv"
    subprocess.run([whirl_program] + ARGS + ["-o", str(path)], check=True)
    return path.read_text()


def _cli_rows(text):
    return [line.split(",") for line in text.splitlines()
            if line and not line.startswith("#") and not line.startswith("mode,")]


def test_atlas_is_the_command_lines_file(cli_atlas, tmp_path):
    out = tmp_path / "py.csv"
    calls = []
    rows = whirl.atlas(output=out, progress=lambda d, t: calls.append((d, t)), **KW)
    assert out.read_text() == cli_atlas
    # the rows returned are the file's, to the last bit
    cli = _cli_rows(cli_atlas)
    assert len(rows) == len(cli) >= 2
    for r, c in zip(rows, cli):
        assert r["mode"] == int(c[0])
        for name, text in zip(("from", "to", "freq_from", "freq_to"), c[1:3] + c[5:7]):
            assert r[name] == float(text)
        assert (r["sig_from"], r["sig_to"]) == (int(c[7]), int(c[8]))
        assert r["max_growth"] == float(c[9]) and r["err_to"] == float(c[12])
    # chunks: 2 modes x (0..5, 5..6), one call each, in order, the last the total
    assert calls == [(0, 4), (1, 4), (2, 4), (3, 4), (4, 4)]
    # in memory only (mode 2's first chunk): the same rows
    again = whirl.atlas(modes=2, omega_max=5)
    assert np.array_equal(again, rows[rows["mode"] == 2])


def test_resume_a_command_line_file(cli_atlas, tmp_path):
    """A file of the command line with its last chunk not done (its "# done" line and its
    window removed): Python computes that chunk and writes the whole file."""
    lines = cli_atlas.splitlines(keepends=True)
    last = [line for line in lines if line.startswith("# done mode 3 omega 5 6")]
    row = [line for line in lines if line.startswith("3,5.")]
    assert len(last) == 1 and len(row) == 1
    partial = "".join(line for line in lines if line not in last + row)
    out = tmp_path / "partial.csv"
    out.write_text(partial)
    calls = []
    whirl.atlas(output=out, resume=True, progress=lambda d, t: calls.append(d), **KW)
    assert out.read_text() == cli_atlas
    assert calls == [3, 4]  # three chunks kept, one computed


def test_ctrl_c_keeps_the_chunks_and_the_command_line_resumes(cli_atlas, whirl_program,
                                                              tmp_path):
    out = tmp_path / "stopped.csv"

    def ctrl_c_after_two(done, total):
        if done == 2:
            signal.raise_signal(signal.SIGINT)
    with pytest.raises(KeyboardInterrupt, match=r"whirl: atlas interrupted: 2 of 4 chunks in "
                       r"'.*stopped.csv' \(continue with resume=True\)") as e:
        whirl.atlas(output=out, progress=ctrl_c_after_two, **KW)
    assert not whirl.stop_requested()
    assert set(e.value.partial["mode"]) == {2}  # mode 2's chunks, finished
    text = out.read_text()
    assert "# done mode 2 omega 5 6" in text and "# done mode 3" not in text
    copy = tmp_path / "copy.csv"
    shutil.copy(out, copy)
    # the command line resumes Python's file ...
    subprocess.run([whirl_program] + ARGS + ["-o", str(out), "--resume"], check=True)
    assert out.read_text() == cli_atlas
    # ... and Python its own
    whirl.atlas(output=copy, resume=True, **KW)
    assert copy.read_text() == cli_atlas


def test_resume_refuses_other_options_and_bad_rows(cli_atlas, tmp_path):
    out = tmp_path / "a.csv"
    out.write_text(cli_atlas)
    with pytest.raises(whirl.InvalidInput, match="line 2 has 'tol=1e-09 scan_step=0.25' where "
                       "these options write 'tol=1e-09 scan_step=0.5'"):
        whirl.atlas(output=out, resume=True, scan_step=0.5, **KW)
    out.write_text(cli_atlas.replace("\n2,4.4", "\n7,4.4"))
    with pytest.raises(whirl.InvalidInput, match=r"a\.csv:9: mode 7 was not asked for"):
        whirl.atlas(output=out, resume=True, **KW)
    out.write_text(cli_atlas.replace("# done mode 3 omega 5 6", "# done mode 3 omega 5 7"))
    with pytest.raises(whirl.InvalidInput, match="omega 5 7 is no chunk of this atlas"):
        whirl.atlas(output=out, resume=True, **KW)
    assert out.read_text() != cli_atlas  # refused files are left as they are
    with pytest.raises(ValueError, match="no such regular file"):
        whirl.atlas(output=tmp_path / "none.csv", resume=True, **KW)
    with pytest.raises(ValueError, match="resume=True needs output"):
        whirl.atlas(resume=True, **KW)


def test_the_file_is_locked_while_a_run_writes_it(cli_atlas, whirl_program, tmp_path):
    out = tmp_path / "locked.csv"
    out.write_text(cli_atlas)
    fd = os.open(out, os.O_RDONLY)
    fcntl.flock(fd, fcntl.LOCK_EX)  # another run holds it
    try:
        with pytest.raises(whirl.Error, match="being written by another run"):
            whirl.atlas(output=out, resume=True, **KW)
    finally:
        os.close(fd)
    # while Python writes it, the command line is refused
    seen = []

    def try_cli(done, total):
        if done == 1:
            p = subprocess.run([whirl_program] + ARGS + ["-o", str(out), "--resume"],
                               capture_output=True, text=True)
            seen.append((p.returncode, p.stderr))
    new = tmp_path / "new.csv"
    out = new
    whirl.atlas(output=new, progress=try_cli, **KW)
    assert seen and seen[0][0] != 0
    assert seen[0][1] == ("whirl windows: '%s' is being written by another run (locked): "
                          "wait for it or write another file\n" % new)
    assert new.read_text() == cli_atlas


def test_python_is_refused_while_the_command_line_writes_the_file(whirl_program, tmp_path):
    # one lock, the library's (whirl_atlas_file), for both writers: a long atlas of the
    # command line's holds the file from its start; Python is refused in one line, the file
    # untouched, and the command line's run goes on to its Ctrl-C
    out = tmp_path / "cli_run.csv"
    run = subprocess.Popen([whirl_program, "stability", "--atlas", "--modes", "2",
                            "--omega-max", "400", "-o", str(out)], stderr=subprocess.PIPE,
                           text=True)
    try:
        while run.poll() is None and not (out.exists() and out.stat().st_size > 0):
            time.sleep(0.05)  # the first chunk written: the run holds the file
        assert run.poll() is None, run.stderr.read()
        before = out.read_bytes()
        with pytest.raises(whirl.Error) as e:
            whirl.atlas(2, omega_max=400, output=out, resume=True)
        assert str(e.value) == ("atlas: '%s' is being written by another run (locked): wait "
                                "for it or write another file" % out)
        assert "\n" not in str(e.value) and e.value.status_name == "EFAILED"
        assert out.read_bytes()[:len(before)] == before
    finally:
        run.send_signal(signal.SIGINT)
        run.wait()
    assert run.returncode == 130


def test_ctrl_c_inside_a_chunk(tmp_path):
    out = tmp_path / "long.csv"
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt, match=r"whirl: atlas interrupted: (\d+) of 9 "
                       r"chunks") as e:
        whirl.atlas(modes=[2, 3, 4], omega_max=15, output=out)  # about 10 s
    assert time.monotonic() - start < 5
    assert not whirl.stop_requested()
    kept = int(re.search(r"(\d+) of 9", str(e.value)).group(1))
    assert kept < 9
    # the file holds the chunks computed (as the command line's, a chunk where the mode is not
    # born yet is listed with the next one computed) and the windows the exception holds
    text = out.read_text() if out.exists() else ""
    assert text.count("# done ") <= kept
    assert len(e.value.partial) == len(_cli_rows(text))


def test_si_units(cli_atlas):
    """Rates in rad/s with length given; the defaults of tol and scan_step stay the command
    line's dimensionless ones, so the windows are the dimensionless atlas's times the rate
    unit."""
    rate = np.sqrt(9.80665 / 0.6)
    si = whirl.atlas(modes=2, omega_max=5 * rate, length=0.6)
    rows = _cli_rows(cli_atlas)
    assert len(si) == 1 and rows[0][0] == "2"
    for name, text in (("from", rows[0][1]), ("to", rows[0][2]), ("max_growth", rows[0][9])):
        assert si[name][0] == pytest.approx(float(text) * rate, rel=1e-12), name


def test_atlas_checks_its_arguments(tmp_path):
    with pytest.raises(FileNotFoundError):
        whirl.atlas(output=tmp_path / "no" / "such.csv", **KW)
    with pytest.raises(ValueError, match="omega_max must be in"):
        whirl.atlas(omega_max=6000)
    with pytest.raises(ValueError, match="tol must be smaller than scan_step"):
        whirl.atlas(tol=0.5, scan_step=0.25)
    with pytest.raises(ValueError, match="modes must not repeat"):
        whirl.atlas(modes=[2, 2])
    with pytest.raises(ValueError, match="mode must be <= 64"):
        whirl.atlas(modes=[65])
    with pytest.raises(ValueError, match="degree must be >= 6"):
        whirl.atlas(degree=4)
