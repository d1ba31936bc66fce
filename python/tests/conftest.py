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
