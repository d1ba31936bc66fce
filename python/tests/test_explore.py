"""whirl explore (python/whirl/explore.py) in headless Chromium, driven through the DevTools
protocol: the page loads, the rate turns from 2 Hz to 6 Hz, and the node count, the tip radius
and the verdict it shows agree with the command line (`whirl shape`, `whirl stability`); no
console errors; bad input gets a message next to its field and sends nothing; requests naming
another host are refused; a second server on a busy port takes another."""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, os.pardir, os.pardir)
WHIRL = os.environ.get("WHIRL", os.path.join(ROOT, "build", "whirl"))
CHROMIUM = shutil.which("chromium")

import websocket  # python3-websocket


def _server(port):
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    p = subprocess.Popen([sys.executable, "-m", "whirl.explore", "--no-browser", "--port",
                          str(port)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                         text=True)
    line = p.stdout.readline()
    assert line.startswith("whirl explore: http://127.0.0.1:"), line + p.stdout.read()
    return p, line.split()[2]


class Page:
    """A headless Chromium tab over the DevTools protocol."""

    def __init__(self, tmp):
        self.proc = subprocess.Popen(
            [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
             "--no-first-run", "--disable-background-networking", "--disable-component-update",
             "--disable-sync", "--user-data-dir=" + tmp, "--remote-debugging-port=0",
             "--window-size=1400,1000", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            env={k: v for k, v in os.environ.items() if k != "LD_PRELOAD"})
        port_file = os.path.join(tmp, "DevToolsActivePort")
        for _ in range(300):
            if os.path.exists(port_file) and open(port_file).read().strip():
                break
            time.sleep(0.05)
        port = open(port_file).read().split()[0]
        tabs = json.load(urllib.request.urlopen("http://127.0.0.1:%s/json" % port))
        ws = [t for t in tabs if t["type"] == "page"][0]["webSocketDebuggerUrl"]
        self.ws = websocket.create_connection(ws, timeout=60)
        self.n = 0
        self.console_errors = []
        self.call("Runtime.enable")
        self.call("Log.enable")
        self.call("Page.enable")

    def call(self, method, **params):
        self.n += 1
        self.ws.send(json.dumps({"id": self.n, "method": method, "params": params}))
        while True:
            m = json.loads(self.ws.recv())
            if m.get("method") == "Runtime.exceptionThrown":
                self.console_errors.append(m["params"]["exceptionDetails"].get("text"))
            elif m.get("method") == "Runtime.consoleAPICalled" and m["params"]["type"] == "error":
                self.console_errors.append(str(m["params"]["args"]))
            elif m.get("method") == "Log.entryAdded" and m["params"]["entry"]["level"] == "error":
                self.console_errors.append(m["params"]["entry"]["text"])
            if m.get("id") == self.n:
                assert "error" not in m, m
                return m["result"]

    def eval(self, expr):
        r = self.call("Runtime.evaluate", expression=expr, awaitPromise=True,
                      returnByValue=True)
        assert "exceptionDetails" not in r, r
        return r["result"].get("value")

    def wait(self, expr, seconds=60):
        end = time.time() + seconds
        while time.time() < end:
            if self.eval(expr):
                return
            time.sleep(0.05)
        raise AssertionError("timed out waiting for " + expr)

    def close(self):
        self.ws.close()
        self.proc.kill()
        self.proc.wait()


def _cli_summary(*args):
    """The key=value pairs of the first comment line of a whirl command's CSV."""
    out = subprocess.run([WHIRL, *args], capture_output=True, text=True, check=True).stdout
    first = out.splitlines()[0].lstrip("# ")
    return dict(kv.split("=", 1) for kv in first.split() if "=" in kv)


def test_page_in_chromium(tmp_path):
    assert CHROMIUM, "chromium is not installed (scripts/deps.sh installs it)"
    assert os.path.exists(WHIRL), "build the program first: make"
    server, url = _server(0)
    page = Page(str(tmp_path / "profile"))
    try:
        t0 = time.time()
        page.call("Page.navigate", url=url)
        page.wait("window.whirlState && window.whirlState.shape !== null")
        load = time.time() - t0
        page.wait("window.whirlState.branch !== null")
        # 2 Hz, then 6 Hz: the page's numbers against the command line's
        results = {}
        for hz in (2, 6):
            page.eval("whirlSetRate(%d)" % hz)
            page.wait("window.whirlState.shape && window.whirlState.shape.rate === %d" % hz)
            results[hz] = page.eval("JSON.stringify({nodes: document.getElementById('nodes')"
                                    ".textContent, tipr: window.whirlState.shape.tip_r, "
                                    "verdict: window.whirlState.shape.verdict, "
                                    "ms: window.whirlState.latencyMs})")
            results[hz] = json.loads(results[hz])
            summary = _cli_summary("shape", "--omega", "%dHz" % hz, "--mode", "2",
                                   "--length", "0.6", "--mass", "0.05", "--points", "3")
            r_tip = abs(float(summary["tip_r"]))
            assert abs(results[hz]["tipr"] - r_tip) <= 1e-9 * r_tip, (hz, results, summary)
            assert results[hz]["nodes"] == summary["node_count"] == "2"
            stab = subprocess.run([WHIRL, "stability", "--omega", "%dHz" % hz, "--mode", "2",
                                   "--links", "30", "--length", "0.6", "--mass", "0.05",
                                   "--linear"], capture_output=True, text=True, check=True)
            lines = [l for l in stab.stdout.strip().splitlines() if not l.startswith("#")]
            row = dict(zip(lines[0].split(","), lines[-1].split(",")))
            assert results[hz]["verdict"] == row["verdict"]
        assert results[2]["verdict"].startswith("stable") or "neutral" in results[2]["verdict"]
        assert results[6]["verdict"].startswith("unstable")
        # bad input: a message next to the field, nothing sent
        before = page.eval("window.whirlState.requests")
        page.eval("document.getElementById('length').value = 'abc'; "
                  "document.getElementById('length').dispatchEvent(new Event('change'))")
        assert page.eval("document.getElementById('length-msg').textContent") == "not a number"
        assert page.eval("window.whirlState.requests") == before
        page.eval("document.getElementById('length').value = '0.6'; "
                  "document.getElementById('length').dispatchEvent(new Event('change'))")
        # a perturbed run: frames arrive, the shape still answers while it runs, and it can
        # be cancelled
        page.eval("document.getElementById('run').click()")
        page.wait("window.whirlState.run && window.whirlState.run.frames.length > 5")
        page.eval("whirlSetRate(4)")
        page.wait("window.whirlState.shape && window.whirlState.shape.rate === 4")
        busy_ms = page.eval("window.whirlState.latencyMs")
        assert not page.eval("window.whirlState.run.done"), "the run ended before the check"
        page.eval("document.getElementById('cancel').click()")
        page.wait("window.whirlState.run.done")
        page.call("Performance.enable")
        metrics = {m["name"]: m["value"] for m in page.call("Performance.getMetrics")["metrics"]}
        with open("/proc/%d/status" % server.pid) as f:
            rss = [l.split()[1] for l in f if l.startswith("VmRSS")][0]
        shot = os.environ.get("WHIRL_EXPLORE_SCREENSHOT")
        if shot:
            import base64
            png = page.call("Page.captureScreenshot", format="png")["data"]
            with open(shot, "wb") as f:
                f.write(base64.b64decode(png))
        assert page.eval("window.whirlState.errors.length") == 0
        assert page.console_errors == [], page.console_errors
        print("explore: load %.2f s, update 2 Hz %.0f ms, 6 Hz %.0f ms, 4 Hz during a run "
              "%.0f ms; page JS heap %.1f MB, server RSS %.0f MB"
              % (load, results[2]["ms"], results[6]["ms"], busy_ms,
                 metrics["JSHeapUsedSize"] / 2**20, int(rss) / 1024))
    finally:
        page.close()
        server.terminate()
        server.wait(timeout=10)


def test_refuses_other_hosts_and_takes_a_free_port():
    a, url = _server(0)
    try:
        port = int(url.rsplit(":", 1)[1].strip("/"))
        req = urllib.request.Request(url, headers={"Host": "example.com"})
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(req)
        assert e.value.code == 403
        b, url_b = _server(port)
        try:
            assert url_b != url
        finally:
            b.terminate()
            b.wait(timeout=10)
        page = urllib.request.urlopen(url).read().decode()
        token = re.search(r'name="whirl-token" content="([^"]+)"', page).group(1)
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(urllib.request.Request(
                url + "api/shape?length=-1&mass=1&rate=1&mode=1",
                headers={"X-Whirl-Token": token}))
        assert e.value.code == 400
        assert "length must be in" in json.loads(e.value.read())["error"]
    finally:
        a.terminate()
        assert a.wait(timeout=10) is not None


def test_ctrl_c_stops_the_server():
    p, url = _server(0)
    urllib.request.urlopen(url).read()
    t0 = time.time()
    p.send_signal(signal.SIGINT)
    rc = p.wait(timeout=10)
    assert rc == 0 and time.time() - t0 < 2, (rc, time.time() - t0)
    assert "stopped" in p.stdout.read()
