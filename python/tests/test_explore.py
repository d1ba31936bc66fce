"""whirl.explore: finds the page of `make web` (the named file, WHIRL_EXPLORE_PAGE, the package's
copy, the source tree's build/web) or says in one line to run `make web`; opens it as a file;
with --serve, a server on 127.0.0.1 that answers GET and HEAD of the page alone: any other path
404, any other method 405, a Host naming another host 403. A stand-in page is used: the page
itself is tested in headless Chromium by tests/cli/test_web.sh."""
import http.client
import os
import subprocess
import sys

import pytest

from whirl import explore

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, os.pardir, "whirl", "explore.py")
PAGE = b"<!DOCTYPE html><title>stand-in</title><p>the page\n"


@pytest.fixture
def page(tmp_path):
    p = tmp_path / "whirl-explore.html"
    p.write_bytes(PAGE)
    return str(p)


def _run(*args, env=None):
    """explore.py as `make explore` runs it: a script, without the package."""
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True,
                          timeout=60, env=dict(os.environ, **(env or {})))


def test_named_page_opens_as_a_file(page):
    r = _run(page, "--no-browser")
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "whirl explore: file://" + page


def test_environment_names_the_page(page):
    r = _run("--no-browser", env={"WHIRL_EXPLORE_PAGE": page})
    assert r.returncode == 0 and r.stdout.strip().endswith(page), r.stdout + r.stderr


def test_missing_page_says_make_web(tmp_path):
    missing = str(tmp_path / "none.html")
    for args, env in (([missing, "--no-browser"], None),
                      (["--no-browser"], {"WHIRL_EXPLORE_PAGE": missing})):
        r = _run(*args, env=env)
        lines = r.stderr.strip().splitlines()
        assert r.returncode == 1 and len(lines) == 1, r.stderr
        assert "make web" in lines[0] and missing in lines[0] and not r.stdout


def test_package_copy_then_source_tree(tmp_path, monkeypatch):
    monkeypatch.delenv("WHIRL_EXPLORE_PAGE", raising=False)
    found = explore.candidates()
    assert found[0] == os.path.join(os.path.dirname(explore.__file__), "whirl-explore.html")
    assert found[1].endswith(os.path.join("build", "web", "whirl-explore.html"))
    monkeypatch.setenv("WHIRL_EXPLORE_PAGE", str(tmp_path / "x.html"))
    assert explore.candidates() == [str(tmp_path / "x.html")]  # that file or none


def _request(port, method, path, host=None):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    c.putrequest(method, path, skip_host=True)
    c.putheader("Host", "127.0.0.1:%d" % port if host is None else host)
    c.endheaders()
    r = c.getresponse()
    out = r.status, dict(r.getheaders()), r.read()
    c.close()
    return out


def test_server_serves_the_page_alone(page):
    p = subprocess.Popen([sys.executable, SCRIPT, page, "--serve", "--port", "0", "--no-browser"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        line = p.stdout.readline()
        assert line.startswith("whirl explore: http://127.0.0.1:"), line + p.stderr.read()
        port = int(line.split("http://127.0.0.1:")[1].split("/")[0])
        for path in ("/", "/whirl-explore.html", "/?length=60cm&rate=4Hz"):
            code, headers, body = _request(port, "GET", path)
            assert code == 200 and body == PAGE, (path, code)
            assert headers["Content-Type"].startswith("text/html")
        code, _, body = _request(port, "HEAD", "/")
        assert code == 200 and body == b""
        code, _, body = _request(port, "GET", "/", host="localhost:%d" % port)
        assert code == 200 and body == PAGE
        # nothing else: another file, another method, another host
        for path in ("/etc/passwd", "/../whirl-explore.html", "/api/shape?length=1", "//x"):
            assert _request(port, "GET", path)[0] == 404, path
        for method in ("POST", "PUT", "DELETE", "OPTIONS"):
            code, headers, _ = _request(port, method, "/")
            assert code == 405 and headers["Allow"] == "GET, HEAD", method
        for host in ("evil.example:%d" % port, "evil.example", "127.0.0.1.evil.example", ""):
            assert _request(port, "GET", "/", host=host)[0] == 403, host
    finally:
        p.terminate()
        p.wait(10)


def test_busy_port_takes_the_next(page):
    first = explore.serve(page, 0)
    try:
        busy = first.server_address[1]
        second = explore.serve(page, busy)
        try:
            assert second.server_address[1] != busy
            assert second.server_address[0] == "127.0.0.1"
        finally:
            second.server_close()
    finally:
        first.server_close()
