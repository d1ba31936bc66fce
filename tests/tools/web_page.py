"""Drives the single-file page of make web (build/web/whirl-explore.html) in headless Chromium
over the DevTools protocol, opened from file://.

    web_page.py parity PAGE WHIRL     the page's numbers against the native command line:
                                      lines "PASS name" / "FAIL name (why)" for
                                      tests/cli/test_web.sh, "INFO what" for its log
    web_page.py bench PAGE [N]        load time (the driver's, and the page's own clock to the
                                      engine ready and the first shape), rate-change latency
                                      (median, p95 of N changes), the branch diagram's time,
                                      the perturbed run's speed against real time, the page's
                                      memory: one JSON line
    web_page.py shot PAGE QUERY PNG   a screenshot of the page at the state QUERY

The page's own state is read from window.whirlState (what it drew); nothing is computed here but
the comparisons."""
import json
import math
import os
import re
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
            d = p["exceptionDetails"]  # "Uncaught" and what: the exception's description
            self.console_errors.append("%s %s (%s:%s)" % (
                d.get("text"), d.get("exception", {}).get("description", ""), d.get("url", ""),
                d.get("lineNumber", "")))
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
# the address of the download link %s as a user reaches it: the page makes the file when the link
# is focused, pressed or clicked
LINK = ("((l) => (l.dispatchEvent(new Event('focus')), l.href))"
        "(document.getElementById('%s'))")


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


def svg_check(p, a, check):
    """shape.svg and branches.svg: SVG documents of the figures drawn; the shape's curve is the
    shape shown, point for point (each to the 0.01 px the SVG writes: the points' order and count
    are checked, their place only to that)."""
    fetch = "fetch(" + LINK + ").then(r => r.text())"
    svg = p.eval(fetch % "svg-shape")
    paths = re.findall(r'<path d="([^"]*)"', svg)
    curve = max(paths, key=len) if paths else ""
    points = re.findall(r"[ML](-?[\d.]+) (-?[\d.]+)", curve)
    xs = [float(u) for u, _ in points]
    # the curve's x in pixels against the shape's x in metres: one affine map for all points
    k = (xs[-1] - xs[0]) / (a["x"][-1] - a["x"][0]) if len(xs) == len(a["x"]) else 0
    off = max((abs(xs[0] + k * (x - a["x"][0]) - u) for x, u in zip(a["x"], xs)), default=1)
    check("shape.svg is an SVG of the figure: the shape's %d points (largest misplacement "
          "%.3g px)" % (len(a["x"]), off),
          svg.startswith("<?xml") and "<svg xmlns=" in svg and svg.rstrip().endswith("</svg>")
          and len(xs) == len(a["x"]) and k > 0 and off <= 0.02, svg[:300])
    svg = p.eval(fetch % "svg-branch")
    b = p.eval("window.whirlState.branch")
    curves = [d for d in re.findall(r'<path d="([^"]*)" fill="none"', svg) if d.count("L") > 20]
    check("branches.svg is an SVG of the figure: a curve for each of the %d modes drawn "
          "(those of more than 21 points: the ticks are paths too)"
          % len(b["modes"]), svg.startswith("<?xml") and
          sorted(d.count("L") + 1 for d in curves) ==
          sorted(len(m["rate"]) for m in b["modes"] if len(m["rate"]) > 21),
          "%d curves" % len(curves))


def run_check(p, page_file, whirl, check):
    """Perturb and run: the page's 401 frames (60 cm, 50 g, mode 2 at 4 Hz, the 30-link chain,
    inertial view) against whirl simulate of the same run (the classroom scene, the page's step;
    the start state is built by another route, the same to about 1e-13): the deviation to 1e-9
    relative, the tip's position to 1e-6 m (the page sends 7 digits); and the run computed at
    least as fast as real time (the speed is reported, not asserted: a test is not a timing)."""
    p.open(page_file, "?length=60cm&mass=50g&rate=4Hz&mode=2")
    p.eval("document.getElementById('frame').value = 'inertial'")
    p.eval("document.getElementById('run').click()")
    p.wait("window.whirlState.run && window.whirlState.run.done", 300)
    r = p.eval("(() => { const r = window.whirlState.run; return { frames: r.frames, dt: r.dt, "
               "error: r.error, asked: r.asked, last: r.last, first: r.first, lag: r.lagMs, "
               "links: r.links, tEnd: r.tEnd }; })()")
    if r["error"] or not r["frames"]:
        check("perturb and run", False, r["error"])
        return
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir)
    every = r["tEnd"] / 400
    out = subprocess.run(
        [whirl, "simulate", os.path.join(root, "data", "scenes", "classroom.ini"),
         "--set", "run.t_end=%r" % r["tEnd"], "--set", "run.dt=%r" % r["dt"],
         "--set", "output.every=%r" % every, "--set", "start.seed=1", "--set",
         "run.frame=rotating", "--set", "run.method=gauss2", "--set",
         "output.columns=t,deviation,tip_x,tip_y,tip_z"],
        capture_output=True, text=True, check=True).stdout
    rows = [[float(v) for v in l.split(",")] for l in out.splitlines()
            if l and not l.startswith(("#", "t,"))]
    frames = r["frames"]
    dev = max((abs(f[1] - c[1]) / c[1] for f, c in zip(frames, rows)), default=1)
    tip = max((max(abs(f[-3 + i] - c[2 + i]) for i in range(3)) for f, c in zip(frames, rows)),
              default=1)
    times = all(abs(f[0] - c[0]) <= 1e-12 * r["tEnd"] for f, c in zip(frames, rows))
    check("perturb and run: %d frames of %d links equal whirl simulate's (deviation to %.2g "
          "relative, tip to %.2g m)" % (len(frames), r["links"], dev, tip),
          len(frames) == len(rows) == 401 and times and dev <= 1e-9 and tip <= 1e-6,
          "%d frames against %d rows" % (len(frames), len(rows)))
    # Cancel in a run of 100 links (several seconds of work): the Worker ended, the run said
    # cancelled, and a new run computes
    p.open(page_file, "?length=60cm&mass=50g&rate=4Hz&mode=2&links=100")
    p.wait("window.whirlState.branch && window.whirlState.windows", 300)
    p.eval("document.getElementById('run').click()")
    p.wait("window.whirlState.run.frames.length > 0", 120)
    p.eval("document.getElementById('cancel').click()")
    said = p.eval("document.getElementById('run-status').textContent")
    p.wait("window.whirlState.ready", 60)
    p.eval("document.getElementById('model').value = '0'")
    p.eval("document.getElementById('run').click()")
    p.wait("window.whirlState.run.frames.length > 0", 120)
    check("Cancel in a run of 100 links ends it (%s); a new run computes" % said,
          "cancelled" in said and p.eval("window.whirlState.run.links") == 30)
    speed = r["tEnd"] / ((r["last"] - r["asked"]) / 1000)
    print("INFO perturb and run: 40 turns (%.3g s of motion) computed in %.3g s: %.3g times real "
          "time; the playing (from 0.5 s of motion in) waited for frames %.0f ms in all" % (
              r["tEnd"], (r["last"] - r["asked"]) / 1000, speed, r["lag"]))


def shaken_run(p, fields):
    """Sets the page's fields (id: value), presses Shake and run, and returns the run when done."""
    for k, v in fields.items():
        p.eval("document.getElementById(%s).value = %s" % (json.dumps(k), json.dumps(v)))
    p.eval("document.getElementById('shake-run').click()")
    p.wait("window.whirlState.run && window.whirlState.run.done", 120)
    return p.eval("(() => { const r = window.whirlState.run; return { frames: r.frames, "
                  "error: r.error, links: r.links, period: r.period }; })()")


def shake_check(p, check):
    """Shake the pivot: the preset of Kapitza's pendulum (3 links of 20 cm standing up, shaken
    1 cm at 55 Hz; its multipliers on the unit circle by whirl periodic) keeps the tip above the
    pivot over the run's 100 periods while the pivot moves (in the frames and as drawn); a free
    swing of 20 degrees dies away with air drag and not without; a bad amplitude or frequency is
    said next to its field and nothing is drawn. (The same runs through the C interface against
    the library: build/tests/test_whirl_web.)"""
    # (the page as run_check left it, a run under way: the preset replaces it)
    p.eval("document.getElementById('kapitza').click()")
    p.wait("window.whirlState.run && window.whirlState.run.done", 120)
    r = p.eval("(() => { const r = window.whirlState.run; return { frames: r.frames, "
               "error: r.error, links: r.links, period: r.period }; })()")
    frames = r["frames"] or [[0, 0, 0, 0, 0]]
    pz = [f[4] for f in frames]
    low = min(f[1] for f in frames)
    periods = frames[-1][0] / r["period"] if r["period"] else 0
    drawn = set()
    for _ in range(50):  # the animation's pivot, as drawn
        d = p.eval("window.whirlState.run.drawn")
        if d:
            drawn.add(round(d["pivot"][2], 6))
        if len(drawn) > 2:
            break
        time.sleep(0.02)
    check("Kapitza's preset: the 3-link chain standing on a pivot shaken 1 cm at 55 Hz stays up "
          "over %.0f periods (the tip at least %.3g m above the pivot); the pivot moves %.3g m "
          "and is drawn moving" % (periods, low, max(pz) - min(pz)),
          not r["error"] and r["links"] == 3 and len(frames) == 801 and periods >= 99 and
          low > 0.5 and 0.019 < max(pz) - min(pz) <= 0.02 and len(drawn) > 2,
          "error %r, %d frames, %d drawn positions" % (r["error"], len(frames), len(drawn)))
    swing = {"pivot": "none", "start": "hanging", "tilt": "20", "drag2": "0"}  # the 3 links
    tips = []
    for drag in ("0", "0.05"):
        r = shaken_run(p, dict(swing, drag=drag))
        tips.append(max(abs(f[-3]) for f in r["frames"][-100:]) if r["frames"] else 0)
    check("air drag: a free swing of 20 degrees keeps %.3g m of tip excursion at its end without "
          "drag and %.3g m with 0.05 kg/(m s)" % tuple(tips), tips[1] < 0.5 * tips[0], tips)
    for field, value in (("amp", "1xx"), ("shake", "0Hz"), ("drag", "-1")):
        r = shaken_run(p, dict({"pivot": "vertical", "amp": "1cm", "shake": "55Hz", "drag": "0"},
                               **{field: value}))
        msg = p.eval("document.getElementById('%s-msg').textContent" % field)
        check("bad %s %s: a message next to the field (%s), nothing drawn" % (field, value, msg),
              r["error"] and msg and not r["frames"], "error %r" % r["error"])


def floquet_check(p, whirl, check):
    """The Floquet multipliers of the shaken settings: the 5-link chain of 60 cm hanging from a
    pivot on a circle of 1 cm at 4 Hz, asked by the button: the largest |mu| shown equals whirl
    periodic's |mu|max to the digits shown (to its error estimate's first digit; the whole value
    to REL: the WebAssembly engine has no LAPACK and another libm) and so does the verdict; then a change of the amplitude and
    rate (10 cm at 1 Hz, 3 links: Newton's method does not converge) solves again by itself and
    shows the library's one line and no multiplier; Stop ends a long solve (30 links on 1 cm at
    3 Hz, 15 s natively) and the page says so. (The multipliers against whirl periodic bit for
    bit through the C interface: build/tests/test_whirl_web.)"""
    fields = {"model": "n", "links": "5", "length": "60cm", "mass": "50g", "tip": "0g",
              "pivot": "circle", "amp": "1cm", "shake": "4Hz", "start": "hanging", "drag": "0",
              "drag2": "0"}
    for k, v in fields.items():
        p.eval("document.getElementById(%s).value = %s" % (json.dumps(k), json.dumps(v)))
    p.eval("window.whirlState.floquet = null; document.getElementById('floquet-go').click()")
    p.wait("window.whirlState.floquet", 120)
    shown = p.eval("(() => { const e = document.getElementById('floquet-mu'); "
                   "return e ? e.textContent : ''; })()")
    verdict = p.eval("(() => { const e = document.getElementById('floquet-verdict'); "
                     "return e ? e.textContent : ''; })()")
    out = subprocess.run([whirl, "periodic", "--pivot", "circle:1cm", "--omega", "4Hz", "--links",
                          "5", "--length", "60cm", "--mass", "50g"], capture_output=True,
                         text=True, check=True).stdout
    mu, err = re.search(r"\|mu\|max=(\S+) \+- (\S+?);", out).groups()
    cli_verdict = re.search(r"verdict=(\w+)", out).group(1)
    # the page shows |mu| to the decimal of its error's first digit (at most 15 digits): the
    # command line's value so rounded; the whole value to the page's parity, REL
    mu, err = float(mu), float(err)
    decimals = max(0, min(14 - math.floor(math.log10(abs(mu) or 1)),
                          -math.floor(math.log10(err)) if err > 0 else 99))
    full = p.eval("window.whirlState.floquet.max_modulus")
    check("Floquet multipliers: the largest |mu| shown (%s, %s) equals whirl periodic's %s "
          "(%.15g +- %.2g, %s) to its digits; the whole values differ by %.2g relative"
          % (shown, verdict, "%.*f" % (decimals, mu), mu, err, cli_verdict,
             abs(full - mu) / mu if full else float("nan")),
          shown == "%.*f" % (decimals, mu) and verdict == cli_verdict and close(full, mu, REL),
          p.eval("document.getElementById('floquet').textContent")[:200])
    p.eval("window.whirlState.floquet = null")
    for k, v in (("links", "3"), ("shake", "1Hz"), ("amp", "10cm")):
        p.eval("document.getElementById(%s).value = %s" % (json.dumps(k), json.dumps(v)))
    p.eval("document.getElementById('amp').dispatchEvent(new Event('change'))")
    p.wait("window.whirlState.floquet", 120)
    text = p.eval("document.getElementById('floquet').textContent")
    check("Floquet multipliers: a change solves again; Newton's method that does not converge "
          "shows one line and no multiplier (%s)" % text,
          text.startswith("no periodic motion: ") and "did not converge" in text and
          "\n" not in text and not p.eval("document.getElementById('floquet-mu')"), text)
    for k, v in (("links", "30"), ("shake", "3Hz"), ("amp", "1cm")):
        p.eval("document.getElementById(%s).value = %s" % (json.dumps(k), json.dumps(v)))
    p.eval("document.getElementById('amp').dispatchEvent(new Event('change'))")
    time.sleep(1)  # under way, not refused (a refusal answers in milliseconds)
    busy = p.eval("!document.getElementById('floquet-stop').disabled && !window.whirlState.floquet")
    p.eval("document.getElementById('floquet-stop').click()")
    time.sleep(0.5)
    text = p.eval("document.getElementById('floquet').textContent")
    check("Floquet multipliers: Stop ends a solve under way (%s)" % text,
          busy and text.startswith("stopped") and not p.eval("window.whirlState.floquet") and
          p.eval("document.getElementById('floquet-stop').disabled"), text)


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
                csv = p.eval(("fetch(" + LINK + ").then(r => r.text())") % "csv-shape")
                rows = [l.split(",") for l in csv.splitlines() if not l.startswith("#")]
                check("shape.csv holds what is shown (%d rows)" % (len(rows) - 1),
                      rows[0] == ["x", "z", "tension"] and len(rows) - 1 == len(a["x"]) and
                      all(float(r[0]) == x and float(r[1]) == z
                          for r, x, z in zip(rows[1:], a["x"], a["z"])), csv[:200])
                png = p.eval((LINK + ".slice(0, 22)") % "png-shape")
                check("shape.png is the figure", png == "data:image/png;base64,", png)
                svg_check(p, a, check)
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
        # bad input in the address: a message next to the field and a line at the top naming
        # the parameter, nothing drawn
        for bad, field in (("mass=5x", "mass"), ("rate=400Hz", "rate"), ("links=1", "links"),
                           ("mode=13", "mode"), ("length=-1", "length"), ("tip=1kg2", "tip")):
            query = "length=60cm&mass=50g&rate=4Hz&mode=2".split("&")
            query = [q for q in query if not q.startswith(field + "=")] + [bad]
            p.open(page_file, "?" + "&".join(query))
            msg = p.eval("document.getElementById('%s-msg').textContent" % field)
            top = p.eval("document.getElementById('address-msg').textContent")
            check("bad %s in the address: a message next to the field (%s) and at the top"
                  % (bad, msg), field in msg and top.startswith("in the address: " + field) and
                  p.eval("window.whirlState.shape") is None, "top line %r" % top)
        # where WebAssembly is unavailable: one line says so, and nothing starts
        script = p.call("Page.addScriptToEvaluateOnNewDocument",
                        source="delete globalThis.WebAssembly;")["identifier"]
        p.open(page_file, "?length=60cm&mass=50g&rate=4Hz&mode=2", wait=False)
        try:
            p.wait("document.readyState === 'complete' && "
                   "!document.getElementById('nowasm').hidden", 20)
        except RuntimeError:
            pass  # the check below fails, with what the page shows
        line = p.eval("document.getElementById('nowasm').hidden ? '' : "
                      "document.getElementById('nowasm').textContent")
        check("without WebAssembly: one line says so (%s)" % line,
              "WebAssembly" in line and not p.eval("window.whirlState.ready"))
        p.call("Page.removeScriptToEvaluateOnNewDocument", identifier=script)
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
        run_check(p, page_file, whirl, check)
        t0 = time.time()
        shake_check(p, check)
        print("INFO shake the pivot: the preset's run, two free swings and three bad fields in "
              "%.1f s" % (time.time() - t0))
        t0 = time.time()
        floquet_check(p, whirl, check)
        print("INFO Floquet multipliers: two solves and a stop in %.1f s" % (time.time() - t0))
        external = [u for u in p.requests if not u.startswith(("file:", "blob:", "data:"))]
        check("no request leaves the machine", not external, "%s" % external[:3])
        check("no console errors", not p.console_errors, "%s" % p.console_errors[:3])


def bench(page_file, n=40):
    p = Page()
    try:
        loads, firsts, readys = [], [], []
        for _ in range(3):
            loads.append(p.open(page_file, "?length=60cm&mass=50g&rate=2Hz&mode=2"))
            # the page's own clock, from the navigation: the engine ready, the first shape drawn
            p.wait("window.whirlState.firstMs !== undefined")
            readys.append(p.eval("window.whirlState.readyMs"))
            firsts.append(p.eval("window.whirlState.firstMs"))
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
        # the perturbed run of the 30-link chain (the continuum's), 40 turns at 4 Hz: from the
        # click to the last frame, against the 10 s of motion; and how far the playing (real
        # time from the first frame) waited for frames
        p.open(page_file, "?length=60cm&mass=50g&rate=4Hz&mode=2")
        p.wait("window.whirlState.branch && window.whirlState.windows", 60)
        p.eval("document.getElementById('run').click()")
        p.wait("window.whirlState.run && window.whirlState.run.done", 300)
        run = p.eval("(() => { const r = window.whirlState.run; return { s: (r.last - r.asked) / 1000, "
                     "first_s: (r.first - r.asked) / 1000, t_end: r.tEnd, lag_ms: r.lagMs, "
                     "links: r.links, error: r.error }; })()")
        run["times_real_time"] = run["t_end"] / run["s"] if run["s"] > 0 else None
        mem = p.eval("performance.memory ? performance.memory.usedJSHeapSize : null")
        wasm = p.eval("window.whirlState.wasmBytes")
        print(json.dumps({"load_s": loads, "engine_ready_ms": readys, "first_shape_ms": firsts, "latency_ms_median": statistics.median(lat),
                          "latency_ms_p95": lat[int(0.95 * (len(lat) - 1))],
                          "latency_ms_max": lat[-1], "changes": n, "branch_ms": t_branch,
                          "run": run,
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
