"""The package installs like any other, each route in a fresh venv with the system's packages
(numpy, cffi): pip install --no-build-isolation of the source, and the wheel; the installed
package loads its own copy of libwhirl (whirl.LIBRARY_PATH inside the venv), its version is the
library's, and its answers are the checkout's. A copy of python/ (WHIRL_SOURCE names the
repository) keeps the source tree free of build files. A whirl installed elsewhere (the system's
Python after `make python`, the user's site) changes nothing: pip installs into the venv even when
it sees the same version outside (--ignore-installed), the venv's own site comes first on the
path, and the user's site is left out (PYTHONNOUSERSITE)."""
import os
import shutil
import subprocess
import sys
import zipfile

import numpy as np
import pytest

import whirl

HERE = os.path.dirname(os.path.abspath(__file__))
PROBE = ("import whirl, json; print(json.dumps([whirl.__version__, whirl.LIBRARY_PATH, "
         "whirl.__file__, list(whirl.critical(3, length=0.6))]))")


@pytest.fixture
def source(tmp_path, repo):
    dst = tmp_path / "python"
    shutil.copytree(os.path.join(repo, "python"), dst,
                    ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__", "tests",
                                                  "examples", "bench", "libwhirl.so"))
    build = os.environ.get("WHIRL_BUILD", os.path.join(repo, "build"))
    # the library under test as it is (make would rebuild the sanitizer build with plain flags)
    env = dict(os.environ, WHIRL_SOURCE=repo,
               WHIRL_PREBUILT=os.path.join(build, "libwhirl.so"))
    env.pop("WHIRL_LIBRARY", None)
    env.pop("PYTHONPATH", None)
    env["PYTHONNOUSERSITE"] = "1"
    return dst, env


def _venv(tmp_path, name):
    path = tmp_path / name
    # without pip of its own (3 s of processor time each): the system's pip, seen through the
    # system's site, installs into the venv it runs in
    subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", "--without-pip",
                    str(path)], check=True)
    return path / "bin" / "python"


def _probe(python, env, venv):
    import json
    out = subprocess.run([str(python), "-c", PROBE], cwd="/", env=env, check=True,
                         capture_output=True, text=True).stdout
    version, library, module, rates = json.loads(out)
    assert version == whirl.__version__ == whirl.LIBRARY_VERSION
    assert library.startswith(str(venv)) and library.endswith("/whirl/libwhirl.so"), library
    assert module.startswith(str(venv)), module
    np.testing.assert_array_equal(rates, whirl.critical(3, length=0.6))


def test_pip_install_source(tmp_path, source):
    src, env = source
    python = _venv(tmp_path, "venv")
    subprocess.run([str(python), "-m", "pip", "install", "-q", "--ignore-installed", "--no-build-isolation",
                    "--no-deps", "--no-index", str(src)], check=True, env=env)
    _probe(python, env, tmp_path / "venv")


def test_wheel_holds_the_library(tmp_path, source):
    src, env = source
    wheels = tmp_path / "wheels"
    subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-build-isolation",
                    "--no-deps", "--no-index", "-w", str(wheels), str(src)], check=True, env=env)
    (wheel,) = wheels.iterdir()
    assert wheel.name.startswith("whirl-%s-" % whirl.__version__)
    assert not wheel.name.endswith("-none-any.whl")  # tagged for the platform
    names = zipfile.ZipFile(wheel).namelist()
    assert "whirl/libwhirl.so" in names and "whirl/py.typed" in names
    # the live page of make web goes in when the library's build has it
    page = os.path.join(os.path.dirname(os.path.realpath(env["WHIRL_PREBUILT"])), "web",
                        "whirl-explore.html")
    assert ("whirl/whirl-explore.html" in names) == os.path.isfile(page)
    python = _venv(tmp_path, "venv")
    subprocess.run([str(python), "-m", "pip", "install", "-q", "--ignore-installed", "--no-deps", "--no-index",
                    str(wheel)], check=True, env=env)
    _probe(python, env, tmp_path / "venv")
    if os.path.isfile(page):  # whirl.explore opens the package's copy
        env = {k: v for k, v in env.items() if k != "WHIRL_EXPLORE_PAGE"}
        out = subprocess.run([str(python), "-m", "whirl.explore", "--no-browser"], cwd="/",
                             env=env, check=True, capture_output=True, text=True).stdout
        assert out.startswith("whirl explore: file://" + str(tmp_path / "venv")), out
        assert out.strip().endswith("/whirl/whirl-explore.html"), out


def test_pip_runs_make(tmp_path, source, repo):
    # without WHIRL_PREBUILT setup.py runs make for build/libwhirl.so (up to date here: the
    # plain build; the sanitizer half's library is another build's)
    src, env = source
    del env["WHIRL_PREBUILT"]
    if os.environ.get("WHIRL_SANITIZE"):
        env["WHIRL_BUILD"] = os.path.join(repo, "build")
    python = _venv(tmp_path, "venv")
    subprocess.run([str(python), "-m", "pip", "install", "-q", "--ignore-installed", "--no-build-isolation",
                    "--no-deps", "--no-index", str(src)], check=True, env=env)
    out = subprocess.run([str(python), "-c", "import whirl; print(whirl.LIBRARY_PATH)"],
                         cwd="/", env=env, check=True, capture_output=True, text=True).stdout
    assert out.strip().startswith(str(tmp_path / "venv"))


def test_build_without_the_repository_fails_in_one_line(tmp_path, source):
    src, env = source
    env["WHIRL_SOURCE"] = str(tmp_path / "nowhere")
    done = subprocess.run([sys.executable, str(src / "setup.py"), "--version"], env=env,
                          capture_output=True, text=True, cwd=str(src))
    assert done.returncode != 0
    lines = [line for line in done.stderr.splitlines() if line.startswith("whirl:")]
    assert len(lines) == 1 and "version.h" in lines[0], done.stderr
