"""The single-file page of make web in headless Firefox (a manual check, outside make check:
Firefox is no dependency of whirl), over WebDriver BiDi, opened from file://:

    web_firefox.py PAGE WHIRL [PNG]

its first shape's tip radius, node count and verdict against whirl shape and whirl stability of
the native build WHIRL (1e-12 relative, verdicts identical), a rate change, a perturbed run to
its end, no console error; PNG: a screenshot of the page then. Prints "PASS name" / "FAIL name
(why)" lines and "INFO" lines with the page's times (page clock), exits 1 on a failure. Needs
firefox-esr (apt-get install --no-install-recommends firefox-esr) and python3-websocket."""
import base64
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import websocket  # python3-websocket

FIREFOX = shutil.which("firefox-esr") or shutil.which("firefox") or "/usr/bin/firefox-esr"
QUERY = "?length=60cm&mass=50g&rate=4Hz&mode=2"


class Firefox:
    """A headless Firefox with a fresh profile, driven over WebDriver BiDi."""

    def __init__(self):
        self.tmp = tempfile.mkdtemp(prefix="whirl-firefox-")
        self.proc = subprocess.Popen(
            [FIREFOX, "--headless", "--no-remote", "--profile", self.tmp,
             "--remote-debugging-port", "0", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
            env={k: v for k, v in os.environ.items() if k != "LD_PRELOAD"})
        url = None
        for line in self.proc.stderr:  # "WebDriver BiDi listening on ws://127.0.0.1:PORT"
            m = re.search(r"listening on (ws://\S+)", line)
            if m:
                url = m.group(1)
                break
        if url is None:
            raise RuntimeError("Firefox did not start its WebDriver BiDi server")
        # (no Origin header: Firefox refuses a WebSocket that names one it was not told of)
        self.ws = websocket.create_connection(url + "/session", timeout=300, suppress_origin=True)
        self.n = 0
        self.errors = []
        self.call("session.new", capabilities={})
        self.call("session.subscribe", events=["log.entryAdded"])
        self.ctx = self.call("browsingContext.getTree")["contexts"][0]["context"]
        self.call("browsingContext.setViewport", context=self.ctx,
                  viewport={"width": 1400, "height": 1000})

    def call(self, method, **params):
        self.n += 1
        self.ws.send(json.dumps({"id": self.n, "method": method, "params": params}))
        while True:
            m = json.loads(self.ws.recv())
            if m.get("id") == self.n:
                if m.get("type") == "error":
                    raise RuntimeError("%s: %s" % (method, m.get("message", m)))
                return m["result"]
            if m.get("method") == "log.entryAdded" and m["params"].get("level") == "error":
                self.errors.append(m["params"].get("text"))

    def eval(self, expr):
        r = self.call("script.evaluate", expression=expr, target={"context": self.ctx},
                      awaitPromise=True, resultOwnership="none")
        if r.get("type") == "exception":
            raise RuntimeError("%s: %s" % (expr, r.get("exceptionDetails", {}).get("text")))
        return r["result"].get("value")

    def wait(self, expr, seconds=120):
        end = time.time() + seconds
        while time.time() < end:
            if self.eval("!!(%s)" % expr):
                return
            time.sleep(0.05)
        raise RuntimeError("timed out waiting for " + expr)

    def close(self):
        try:
            self.call("session.end")
        except Exception:  # the browser's end is what matters
            pass
        self.ws.close()
        self.proc.terminate()
        try:
            self.proc.wait(20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        shutil.rmtree(self.tmp, ignore_errors=True)


def main():
    page, whirl = os.path.abspath(sys.argv[1]), sys.argv[2]
    png = sys.argv[3] if len(sys.argv) > 3 else None
    results = []

    def check(name, ok, why=""):
        results.append(ok)
        print(("PASS %s" % name) if ok else ("FAIL %s (%s)" % (name, why)), flush=True)

    f = Firefox()
    try:
        f.call("browsingContext.navigate", context=f.ctx, url="file://" + page + QUERY,
               wait="complete")
        f.wait("window.whirlState && window.whirlState.firstMs !== undefined")
        print("INFO %s: the engine ready %.0f ms and the first shape drawn %.0f ms after the "
              "navigation (page clock)" % (f.eval("navigator.userAgent"),
                                           f.eval("window.whirlState.readyMs"),
                                           f.eval("window.whirlState.firstMs")))
        a = f.eval("JSON.stringify(window.whirlState.shape)")
        a = json.loads(a) if a else {}
        out = subprocess.run([whirl, "shape", "--length", "60cm", "--mass", "50g", "--omega",
                              "4Hz", "--mode", "2"], capture_output=True, text=True,
                             check=True).stdout.splitlines()[0]
        head = dict(kv.split("=", 1) for kv in out.lstrip("# ").split() if "=" in kv)
        tip = abs(float(head["tip_r"]))
        check("tip radius equals whirl shape's to 1e-12 (%r)" % a.get("tip_r"),
              abs(a.get("tip_r", 0) - tip) <= 1e-12 * tip, "whirl shape: %r" % tip)
        check("node count equals whirl shape's", a.get("node_count") == int(head["node_count"]))
        out = subprocess.run([whirl, "stability", "--linear", "--links", "30", "--length", "60cm",
                              "--mass", "50g", "--omega", "4Hz", "--mode", "2"],
                             capture_output=True, text=True, check=True).stdout.splitlines()
        rows = [l.split(",") for l in out if not l.startswith("#")]
        verdict = dict(zip(rows[0], rows[1]))["verdict"]
        check("verdict equals whirl stability's (%s)" % verdict, a.get("verdict") == verdict,
              a.get("verdict"))
        f.wait("window.whirlState.branch && window.whirlState.windows")
        lat = sorted(f.eval("window.whirlSetRate('%.3gHz')" % (2 + 4 * i / 20)) for i in range(20))
        print("INFO 20 rate changes: median %.0f ms, largest %.0f ms" % (lat[10], lat[-1]))
        f.eval("window.whirlSetRate('4Hz')")
        f.eval("document.getElementById('run').click()")
        f.wait("window.whirlState.run && window.whirlState.run.done", 600)
        r = json.loads(f.eval("JSON.stringify((r => ({s: (r.last - r.asked) / 1000, "
                              "tEnd: r.tEnd, frames: r.frames.length, error: r.error}))"
                              "(window.whirlState.run))"))
        check("a perturbed run to its end: %d frames" % r["frames"],
              r["frames"] == 401 and not r["error"], r["error"])
        print("INFO the run: %.3g s of motion computed in %.3g s (%.3g times real time)"
              % (r["tEnd"], r["s"], r["tEnd"] / r["s"]))
        if png:
            time.sleep(0.5)
            data = f.call("browsingContext.captureScreenshot", context=f.ctx)["data"]
            with open(png, "wb") as out:
                out.write(base64.b64decode(data))
        page_errors = f.eval("JSON.stringify(window.whirlState.errors)")
        check("no console errors", not f.errors and page_errors == "[]",
              "%s %s" % (f.errors[:3], page_errors))
    except Exception as e:  # the driver's own failure is a failed check
        check("the Firefox driver ran to the end", False, repr(e)[:300])
    finally:
        f.close()
    sys.exit(0 if all(results) else 1)


if __name__ == "__main__":
    main()
