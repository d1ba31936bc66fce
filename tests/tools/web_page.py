"""Drives the single-file page of make web (build/web/whirl-explore.html) in headless Chromium
over the DevTools protocol, opened from file://.

    web_page.py parity PAGE WHIRL     the page's numbers against the native command line:
                                      lines "PASS name" / "FAIL name (why)" for tests/cli/test_web.sh
    web_page.py bench PAGE [N]        load time, rate-change latency (median, p95 of N changes),
                                      the branch diagram's time, the page's memory: one JSON line
    web_page.py shot PAGE QUERY PNG   a screenshot of the page at the state QUERY

The page's own state is read from window.whirlState (what it drew); nothing is computed here but
the comparisons."""
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

import websocket  # python3-websocket

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"


class Page:
    """A headless Chromium tab over the DevTools protocol, with a fresh profile."""

    def __init__(self):
        self.tmp = tempfile.mkdtemp(prefix="whirl-web-")
        self.proc = subprocess.Popen(
            [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             "--user-data-dir=" + self.tmp, "--remote-debugging-port=0",
             "--window-size=1400,1000", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            env={k: v for k, v in os.environ.items() if k != "LD_PRELOAD"})
        port_file = os.path.join(self.tmp, "DevToolsActivePort")
        for _ in range(600):
            if os.path.exists(port_file) and open(port_file).read().strip():
                break
            time.sleep(0.05)
        port = open(port_file).read().split()[0]
        tabs = json.load(urllib.request.urlopen("http://127.0.0.1:%s/json" % port))
        url = [t for t in tabs if t["type"] == "page"][0]["webSocketDebuggerUrl"]
        self.ws = websocket.create_connection(url, timeout=120)
        self.n = 0
        self.console_errors = []
        self.requests = []
        self.call("Runtime.enable")
        self.call("Log.enable")
        self.call("Page.enable")
        self.call("Network.enable")

    def _event(self, m):
        method, p = m.get("method"), m.get("params", {})
        if method == "Runtime.exceptionThrown":
            self.console_errors.append(p["exceptionDetails"].get("text"))
        elif method == "Runtime.consoleAPICalled" and p["type"] == "error":
            self.console_errors.append(str(p["args"]))
        elif method == "Log.entryAdded" and p["entry"]["level"] == "error":
            self.console_errors.append(p["entry"]["text"])
        elif method == "Network.requestWillBeSent":
            self.requests.append(p["request"]["url"])

    def call(self, method, **params):
        self.n += 1
        self.ws.send(json.dumps({"id": self.n, "method": method, "params": params}))
        while True:
            m = json.loads(self.ws.recv())
            self._event(m)
            if m.get("id") == self.n:
                if "error" in m:
                    raise RuntimeError("%s: %s" % (method, m["error"]))
                return m["result"]

    def eval(self, expr):
        r = self.call("Runtime.evaluate", expression=expr, awaitPromise=True,
                      returnByValue=True)
        if "exceptionDetails" in r:
            raise RuntimeError("%s: %s" % (expr, r["exceptionDetails"]))
        return r["result"].get("value")

    def wait(self, expr, seconds=60):
        end = time.time() + seconds
        while time.time() < end:
            if self.eval(expr):
                return True
            time.sleep(0.01)
        raise RuntimeError("timed out waiting for " + expr)

    def open(self, page, query="", wait=True):
        """Opens the page (file://) and waits for its first answer (wait=True); returns the
        seconds from the navigation to the first shape drawn."""
        t0 = time.time()
        self.call("Page.navigate", url="file://" + os.path.abspath(page) + query)
        if wait:
            self.wait("window.whirlState && window.whirlState.answers > 0")
        return time.time() - t0

    def close(self):
        self.ws.close()
        self.proc.kill()
        self.proc.wait()
        shutil.rmtree(self.tmp, ignore_errors=True)


def cli(whirl, *args):
    """A whirl command's first comment line (key=value pairs) and its CSV rows."""
    out = subprocess.run([whirl, *args], capture_output=True, text=True, check=True).stdout
    lines = out.splitlines()
    head = dict(kv.split("=", 1) for kv in lines[0].lstrip("# ").split() if "=" in kv)
    rows = [l.split(",") for l in lines if not l.startswith("#")]
    return head, rows


def close(a, b, rel, floor=0.0):
    return abs(a - b) <= rel * max(abs(b), floor)


REL = 1e-12  # the parity asked of the page: 1e-12 relative, verdicts identical


def parity(page_file, whirl):
    p = Page()
    results = []

    def check(name, ok, why=""):
        name, why = " ".join(name.split()), " ".join(str(why).split())  # one line each
        results.append(("PASS %s" % name) if ok else ("FAIL %s (%s)" % (name, why)))

    try:
        parity_cases(p, page_file, whirl, check)
    except Exception as e:  # the driver's own failure is a failed check, with what was done
        check("the page's driver ran to the end", False, repr(e)[:300])
    finally:
        p.close()
    for r in results:
        print(r)


def windows(p, whirl, check):
    """The shaded windows of mode 2 (60 cm, 50 g, up to 12 Hz: three times the rate) against
    whirl stability --windows of the 30-link chain. Each edge is located to tol = 1e-9 in the
    chain's rate unit sqrt(g/L) (the library's default), so two locations of one edge are held
    to 2e-9 sqrt(g/L); the number of windows and the open end must agree exactly."""
    p.wait("window.whirlState.windows && window.whirlState.branch")
    a = p.eval("window.whirlState.windows")
    out = subprocess.run([whirl, "stability", "--windows", "--links", "30", "--modes", "2",
                          "--omega-min", "2Hz", "--omega-max", "12Hz", "--length", "60cm",
                          "--mass", "50g"], capture_output=True, text=True, check=True).stdout
    rows = [l.split(",") for l in out.splitlines() if not l.startswith("#")][1:]
    unit = (9.80665 / 0.6) ** 0.5 / (2 * 3.141592653589793)  # Hz per sqrt(g/L)
    cli = [(float(r[2]) / (2 * 3.141592653589793), float(r[3]) / (2 * 3.141592653589793))
           for r in rows]
    page = [(w[0], w[1]) for w in a["windows"]]
    worst = max((abs(u - v) / unit for pw, cw in zip(page, cli) for u, v in zip(pw, cw)),
                default=None)
    check("the windows of mode 2 up to 12 Hz: %d, as whirl stability --windows, edges to "
          "2e-9 sqrt(g/L) (largest difference %s)" % (len(cli), worst),
          len(page) == len(cli) and len(cli) > 0 and worst <= 2e-9, "%s against %s" % (page, cli))


def parity_cases(p, page_file, whirl, check):
    if True:
        cases = [  # (query, shape args, stability args or None)
            ("length=60cm&mass=50g&rate=4Hz&mode=2", ["--length", "60cm", "--mass", "50g",
             "--omega", "4Hz", "--mode", "2"], ["--links", "30"]),
            ("length=1.5&mass=0.2&rate=150rpm&mode=3&links=20", ["--length", "1.5", "--mass",
             "0.2", "--omega", "150rpm", "--mode", "3", "--links", "20"], ["--links", "20"]),
            ("length=60cm&mass=50g&tip=10g&rate=3Hz&mode=1", ["--length", "60cm", "--mass", "50g",
             "--tip-mass", "10g", "--omega", "3Hz", "--mode", "1"], None),
            ("length=60cm&mass=50g&rate=6.5Hz&mode=3", ["--length", "60cm", "--mass", "50g",
             "--omega", "6.5Hz", "--mode", "3"], ["--links", "30"]),
        ]
        for k, (query, shape_args, stab_args) in enumerate(cases):
            load = p.open(page_file, "?" + query)
            a = p.eval("window.whirlState.shape")
            name = "page ?%s" % query
            if not a:
                check(name + ": a shape", False, "none; errors %s, note %s" % (
                    p.console_errors, p.eval("document.body.innerText.slice(0, 300)")))
                continue
            head, rows = cli(whirl, "shape", *shape_args)
            L = float(shape_args[shape_args.index("--length") + 1].rstrip("cm")) / (
                100 if shape_args[shape_args.index("--length") + 1].endswith("cm") else 1)
            check(name + ": tip radius equals whirl shape's to 1e-12",
                  close(a["tip_r"], abs(float(head["tip_r"])), REL),
                  "%r against %r" % (a["tip_r"], head["tip_r"]))
            check(name + ": node count equals whirl shape's",
                  a["node_count"] == int(head["node_count"]),
                  "%r against %r" % (a["node_count"], head["node_count"]))
            data = rows[1:]
            xs = [float(r[1]) for r in data]
            zs = [float(r[2]) for r in data]
            worst = max(max(abs(u - v) for u, v in zip(a["x"], xs)),
                        max(abs(u - v) for u, v in zip(a["z"], zs))) if len(xs) == len(a["x"]) else None
            check(name + ": the %d points of the shape equal whirl shape's to 1e-12 L" % len(xs),
                  worst is not None and worst <= REL * L,
                  "largest difference %r m, %d against %d points" % (worst, len(a["x"]), len(xs)))
            if stab_args:
                out = subprocess.run(
                    [whirl, "stability", "--linear", "--length",
                     shape_args[shape_args.index("--length") + 1], "--mass",
                     shape_args[shape_args.index("--mass") + 1], "--omega",
                     shape_args[shape_args.index("--omega") + 1], "--mode",
                     shape_args[shape_args.index("--mode") + 1], *stab_args],
                    capture_output=True, text=True, check=True).stdout.splitlines()
                hdr = [l for l in out if not l.startswith("#")]
                row = dict(zip(hdr[0].split(","), hdr[1].split(",")))
                check(name + ": verdict equals whirl stability's (%s)" % row["verdict"],
                      a.get("verdict") == row["verdict"] and a.get("index") == int(row["index"]),
                      "%r index %r against %r index %r" % (a.get("verdict"), a.get("index"),
                                                          row["verdict"], row["index"]))
                g = float(row["eig_growth"])  # [1/s]; 0 where no eigenvalue has Re > 0
                check(name + ": growth rate %.6g 1/s equals whirl stability's to 1e-12" % g,
                      close(a.get("growth", float("nan")), g, REL, 1e-300) if g else
                      a.get("growth") == 0, "%r against %r" % (a.get("growth"), g))
            if k == 0:
                check("the page loads from file:// within 10 s (%.2f s)" % load, load < 10)
                windows(p, whirl, check)
                csv = p.eval("fetch(document.getElementById('csv-shape').href).then(r => r.text())")
                rows = [l.split(",") for l in csv.splitlines() if not l.startswith("#")]
                check("shape.csv holds what is shown (%d rows)" % (len(rows) - 1),
                      rows[0] == ["x", "z", "tension"] and len(rows) - 1 == len(a["x"]) and
                      all(float(r[0]) == x and float(r[1]) == z
                          for r, x, z in zip(rows[1:], a["x"], a["z"])), csv[:200])
                png = p.eval("document.getElementById('png-shape').href.slice(0, 22)")
                check("shape.png is the figure", png == "data:image/png;base64,", png)
        # a rate change: the slider's path (whirlSetRate), then the numbers of the new rate
        p.open(page_file, "?length=60cm&mass=50g&rate=2Hz&mode=2")
        p.eval("window.whirlSetRate('5Hz')")
        a = p.eval("window.whirlState.shape")
        head, _ = cli(whirl, "shape", "--length", "60cm", "--mass", "50g", "--omega", "5Hz",
                      "--mode", "2")
        check("a rate change to 5 Hz: the tip radius of whirl shape",
              a and close(a["tip_r"], abs(float(head["tip_r"])), REL), "%r" % (a,))
        # below the birth: the hanging chain and where the mode is born, not a blank panel
        p.open(page_file, "?length=60cm&mass=50g&rate=1Hz&mode=2")
        a = p.eval("window.whirlState.shape")
        crit, rows = cli(whirl, "critical", "--modes", "2", "--length", "60cm", "--mass", "50g")
        born = float(rows[-1][-1]) / (2 * 3.141592653589793)
        text = p.eval("document.getElementById('summary').innerText")
        check("below the birth: the hanging chain and the rate of the birth (%s)" % text.strip()[:90],
              a and a.get("hanging") and close(a["born"], born, REL) and "born" in text,
              "%r, whirl critical %r" % (a, rows[-1]))
        p.open(page_file, "?length=60cm&mass=50g&rate=3Hz&mode=2&present=1")
        check("present=1 in the address: the presentation mode",
              p.eval("document.body.classList.contains('present') && "
                     "document.getElementById('share').href.endsWith('present=1')"))
        # bad input: a message next to the field, nothing drawn
        p.open(page_file, "?length=60cm&mass=5x&rate=4Hz&mode=2")
        msg = p.eval("document.getElementById('mass-msg').textContent")
        check("bad mass in the address: a message next to the field (%s)" % msg,
              "mass" in msg and p.eval("window.whirlState.shape") is None)
        p.open(page_file, "?length=60cm&mass=50g&rate=4Hz&mode=2&colour=red")
        msg = p.eval("document.getElementById('address-msg').textContent")
        check("an unknown address parameter named at the top (%s)" % msg, "colour" in msg)
        # Cancel: the Worker ended and restarted, the page says so, and computes again
        # (400 links: the verdict's eigen-solve of 1600 rows takes long; Cancel is enabled
        # while a request is out)
        p.open(page_file, "?length=60cm&mass=50g&rate=4Hz&mode=2&links=400", wait=False)
        p.wait("window.whirlState && window.whirlState.ready && "
               "!document.getElementById('cancel').disabled")
        p.eval("document.getElementById('cancel').click()")
        status = p.eval("document.getElementById('status').textContent")
        p.wait("window.whirlState.ready")
        before = p.eval("window.whirlState.answers")
        p.eval("document.getElementById('model').value = '0'")
        p.eval("window.whirlSetRate('4.5Hz')")
        check("Cancel ends and restarts the engine (%s), which answers again" % status,
              "cancelled" in status and p.eval("window.whirlState.answers") > before and
              p.eval("window.whirlState.cancelled") == 1)
        external = [u for u in p.requests if not u.startswith(("file:", "blob:", "data:"))]
        check("no request leaves the machine", not external, "%s" % external[:3])
        check("no console errors", not p.console_errors, "%s" % p.console_errors[:3])


def bench(page_file, n=40):
    p = Page()
    try:
        loads = []
        for _ in range(3):
            loads.append(p.open(page_file, "?length=60cm&mass=50g&rate=2Hz&mode=2"))
        p.wait("window.whirlState.branch && window.whirlState.windows", 60)
        # the branch diagram of a new chain: from the change to its curves and windows
        t_branch = p.eval("""(async () => { const s = window.whirlState; s.branch = null; s.windows = null;
            const t0 = performance.now(); document.getElementById('length').value = '70cm';
            document.getElementById('length').dispatchEvent(new Event('change'));
            while (!(s.branch && s.windows)) await new Promise(r => setTimeout(r, 1));
            return performance.now() - t0; })()""")
        lat = []
        for i in range(n):
            rate = "%.3gHz" % (2 + 4 * i / n)
            lat.append(p.eval("window.whirlSetRate('%s')" % rate))
        lat.sort()
        mem = p.eval("performance.memory ? performance.memory.usedJSHeapSize : null")
        wasm = p.eval("window.whirlState.wasmBytes")
        print(json.dumps({"load_s": loads, "latency_ms_median": statistics.median(lat),
                          "latency_ms_p95": lat[int(0.95 * (len(lat) - 1))],
                          "latency_ms_max": lat[-1], "changes": n, "branch_ms": t_branch,
                          "js_heap_bytes": mem, "wasm_memory_bytes": wasm, "errors": p.console_errors}))
    finally:
        p.close()


def shot(page_file, query, png):
    import base64
    p = Page()
    try:
        p.open(page_file, query)
        p.wait("window.whirlState.branch && window.whirlState.windows", 60)
        time.sleep(0.2)
        data = p.call("Page.captureScreenshot", format="png")["data"]
        open(png, "wb").write(base64.b64decode(data))
    finally:
        p.close()


if __name__ == "__main__":
    what = sys.argv[1]
    if what == "parity":
        parity(sys.argv[2], sys.argv[3])
    elif what == "bench":
        bench(sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 40)
    elif what == "shot":
        shot(sys.argv[2], sys.argv[3], sys.argv[4])
