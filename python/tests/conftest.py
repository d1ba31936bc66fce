"""pytest set-up: the package from this source tree, the repository's build directory, and (with
WHIRL_TAP=1) one TAP line per test, for tests/run.sh's count."""
import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, os.pardir, os.pardir))
sys.path.insert(0, os.path.join(REPO, "python"))
BUILD = os.path.abspath(os.environ.get("WHIRL_BUILD", os.path.join(REPO, "build")))
# absolute, for the notebooks' kernels, which run in python/examples
os.environ["WHIRL_LIBRARY"] = os.path.abspath(
    os.environ.get("WHIRL_LIBRARY", os.path.join(BUILD, "libwhirl.so")))


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def whirl_program():
    path = os.path.join(BUILD, "whirl")
    if not os.access(path, os.X_OK):
        pytest.fail("the whirl program is not built: %s" % path)
    return path


def pytest_runtest_logreport(report):
    if os.environ.get("WHIRL_TAP") != "1":
        return
    if report.when == "call" or (report.when == "setup" and not report.passed):
        ok = report.passed or report.skipped
        print("\n%s - python: %s%s" % ("ok" if ok else "not ok", report.nodeid,
                                        " # SKIP" if report.skipped else ""), flush=True)


# The slow tests (processor time measured in docs/performance.md, "How long make check takes"):
# marked `slow`, they run once, in the plain half of make check; the sanitizer half and
# make check-quick leave them out (tests/cli/test_python.sh passes -m "not slow"). Each entry: the
# start of "FILE::TEST[PARAMS]", and why the test is slow rather than a test of memory.
SLOW = {
    "test_install.py::": "venvs and pip builds of the package: packaging, not memory",
    "test_notebooks.py::test_notebook_runs": "a Jupyter kernel per notebook; the calls "
    "they make are the ones the other tests make",
    "test_notebooks.py::test_notebooks_import": "two Jupyter kernels; nothing computed",
    # the atlas's chunks computed again and again (mode 3 to omega 6: a minute and a half under
    # the sanitizers): under them the library's atlas, its stop and its resume run in
    # test_atlas.c and tests/cli/test_stability_stops.sh, Python's side of a stop in
    # test_ctrl_c_inside_a_chunk and of a resume in test_resume_refuses_other_options_and_bad_rows
    "test_atlas.py::test_ctrl_c_keeps_the_chunks_and_the_command_line_resumes":
    "four atlas chunks computed twice over",
    "test_atlas.py::test_resume_a_command_line_file": "a chunk of mode 3 computed",
    # mode 8's continuum window at 731 collocation points; the same bound and the same computation
    # run under the sanitizers in tests/cli/test_stability.sh, the refusal in
    # test_continuum_windows_memory_refused
    "test_equilibria.py::test_continuum_windows_memory_bound": "mode 8's window of the continuum",
}


# The tests that the sanitizer half leaves out besides the slow ones, marked `plain_only`: those
# of sanitize-except.txt, written by tests/tools/python_sanitize_list.py so that the tests the
# sanitizers run still call every library function with every outcome (and run every command of
# the program) that the whole suite does (docs/performance.md).
with open(os.path.join(HERE, "sanitize-except.txt")) as _f:
    PLAIN_ONLY = {line.strip() for line in _f if line.strip() and not line.startswith("#")}


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: run once, in the plain half of make check")
    config.addinivalue_line("markers", "plain_only: left out of the sanitizer half "
                            "(sanitize-except.txt)")


def pytest_collection_modifyitems(config, items):
    for item in items:
        name = "%s::%s" % (os.path.basename(str(item.fspath)), item.name)
        if any(name.startswith(prefix) for prefix in SLOW):
            item.add_marker(pytest.mark.slow)
        if name in PLAIN_ONLY:
            item.add_marker(pytest.mark.plain_only)
