"""whirl explore: a live page where the rotation rate of a chain is turned and the chain answers.

    python3 -m whirl.explore [--port P] [--no-browser]

serves one page on 127.0.0.1 (the first free port from P, default 8470; printed on start) and
opens it in the browser. The page sends the chain (length, mass, tip mass, links or the
continuum), the rate (Hz, rpm or rad/s) and the mode; this server answers with numbers computed
by libwhirl through the package (no physics in the page): the steady shape, its node count and
tip radius, the branches of every mode against the rate with the stability windows of the chosen
mode, the linear verdict and growth time, and a perturbed time-domain run seeded with the shape.

Units: the page works in SI (m, kg, s); the library in units of the chain (length L, mass M,
time sqrt(L/g), g = 9.80665 m/s^2): rates scale by sqrt(g/L), lengths by L, growth rates by
sqrt(g/L). Air drag: the quadratic drag of a round chain of diameter d in air,
c2 = rho C_d d / 2 per unit length (rho = 1.204 kg/m^3, C_d = 1.2 for a cylinder across the
flow), in the library's units c2 L^2 / M. A chain under drag has a steady shape only while its
pivot is driven on a circle (the drag's torque must be balanced), so with drag on the pivot runs
on a circle of the given radius and the shape is the trailing one (whirl driven).

Only requests from this machine are answered: the socket is bound to 127.0.0.1, and a request
from another address or whose Host header names another host (DNS rebinding) is refused (403).
Ctrl-C stops the server and any run in progress."""
import argparse
import http.server
import json
import math
import os
import signal
import sys
import threading
import urllib.parse
import webbrowser

import numpy as np

from . import _lib
from .steady import Chain, shape as _shape, sweep as _sweep, critical as _critical
from .stability import stability as _stability, stability_windows as _stability_windows
from .dynamics import Simulation
from .driven import driven as _driven

G = 9.80665
AIR_DENSITY = 1.204  # kg/m^3 at 20 C
CYLINDER_DRAG = 1.2  # C_d of a cylinder across the flow at the Reynolds numbers of a swung chain
VERDICT_LINKS = 30   # the N-link chain whose linearisation gives the continuum's verdict
MAX_LINKS = 400      # the live page's bound: a shape and its verdict within ~0.1 s
MAX_MODE = 12
RUN_PERIODS = 40     # length of a perturbed run, in rotation periods
RUN_FRAMES = 400     # frames sent for one run
BRANCH_RATES = 120   # rates of the branch diagram
PAGE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "explore.html")


class InputError(ValueError):
    """A request's parameter out of range: answered with 400 and the message."""


def _number(q, name, lo, hi, default=None, integer=False):
    raw = q.get(name, [None])[0]
    if raw is None or raw == "":
        if default is None:
            raise InputError("%s: missing" % name)
        return default
    try:
        v = int(raw) if integer else float(raw)
    except ValueError:
        raise InputError("%s: not a number: %.40s" % (name, raw)) from None
    if not (math.isfinite(v) and lo <= v <= hi):
        raise InputError("%s must be in [%g, %g], got %s" % (name, lo, hi, raw[:40]))
    return v


class Scene:
    """One request's chain and rate, with the conversions to the library's units."""

    UNITS = {"hz": 2 * math.pi, "rpm": 2 * math.pi / 60, "rad/s": 1.0}

    def __init__(self, q, need_rate=True):
        self.length = _number(q, "length", 0.01, 100.0)
        self.mass = _number(q, "mass", 1e-4, 1e4)
        self.tip = _number(q, "tip", 0.0, 1e4, default=0.0)
        self.links = _number(q, "links", 0, MAX_LINKS, default=0, integer=True)
        if self.links == 1:
            raise InputError("links: 0 (the continuum) or 2..%d" % MAX_LINKS)
        self.drag = _number(q, "drag", 0, 1, default=0, integer=True) == 1
        self.diameter = _number(q, "diameter", 1e-4, 0.1, default=0.004)
        self.eps = _number(q, "eps", 1e-4, 0.5, default=0.01) if self.drag else 0.0
        self.unit = q.get("unit", ["hz"])[0].lower()
        if self.unit not in self.UNITS:
            raise InputError("unit must be hz, rpm or rad/s, got %.20s" % self.unit)
        self.time = math.sqrt(self.length / G)  # the library's unit of time [s]
        if need_rate:
            rate = _number(q, "rate", 1e-3, 1e5)
            self.omega = rate * self.UNITS[self.unit]  # rad/s
            self.w = self.omega * self.time              # dimensionless
            self.mode = _number(q, "mode", 1, MAX_MODE, integer=True)
            if self.links and self.mode > self.links:
                raise InputError("mode %d needs at least %d links" % (self.mode, self.mode))
            if self.w > 200:
                raise InputError("rate above %s: beyond what the page computes live"
                                 % self.rate_text(200 / self.time))

    @property
    def m_tip(self):
        return self.tip / self.mass

    @property
    def c2(self):
        """The quadratic drag per unit length in the library's units (0 without drag)."""
        if not self.drag:
            return 0.0
        return 0.5 * AIR_DENSITY * CYLINDER_DRAG * self.diameter * self.length ** 2 / self.mass

    def rate_of(self, w):
        """A dimensionless rate in the user's unit."""
        return w / self.time / self.UNITS[self.unit]

    def rate_text(self, omega):
        v = omega / self.UNITS[self.unit]
        return "%.4g %s" % (v, {"hz": "Hz", "rpm": "rpm", "rad/s": "rad/s"}[self.unit])

    def key(self):
        return (self.length, self.mass, self.tip, self.links, self.drag, self.diameter, self.eps,
                self.unit)


def _chain_of(sc, links):
    return Chain(links, tip_mass=sc.m_tip)


def _verdict(sc, links):
    """The linear verdict of the shape of sc.mode at sc.w on the chain of `links` links, and
    its growth rate [1/s]."""
    res = _stability(sc.w, sc.mode, _chain_of(sc, links), linear=True,
                     air_drag_quadratic=sc.c2, drive_radius=sc.eps / sc.length)
    return res.verdict, float(res.eig_growth) / sc.time


def _missing_mode(sc, links, err):
    crit = _critical(sc.mode, links=links, tip_mass=0.0 if links else sc.m_tip)[-1]
    if sc.w < crit:
        return InputError("mode %d exists only above %s for this chain"
                          % (sc.mode, sc.rate_text(crit / sc.time)))
    return InputError(str(err).splitlines()[0])


def shape_answer(sc):
    """The steady shape at the scene's rate (with drag: the trailing shape of the pivot driven
    on its circle), in m and N, with its node count, tip radius and linear verdict."""
    links = _chain_of(sc, sc.links) if sc.links else None
    L = sc.length
    out = {"rate": sc.rate_of(sc.w), "unit": sc.unit, "omega": sc.omega,
           "period": 2 * math.pi / sc.omega, "mode": sc.mode, "drag": sc.drag}
    try:
        if sc.drag:
            d = _driven(sc.w, sc.mode, sc.eps / L, air_drag_quadratic=sc.c2, links=links,
                        tip_mass=0.0 if links else sc.m_tip)
            x, y, z, t = d.x, d.y, d.z, d.tension
            node_count, tip_r = int(d.node_count), float(d.tip_r)
        else:
            s = _shape(sc.w, sc.mode, links=links, tip_mass=0.0 if links else sc.m_tip)
            x, y, z, t = s.r, np.zeros_like(s.r), s.z, s.tension
            node_count, tip_r = int(s.node_count), float(s.tip_r)
    except _lib.Error as e:
        raise _missing_mode(sc, links, e) from None
    out.update(x=(x * L).tolist(), y=(y * L).tolist(), z=(z * L).tolist(),
               tension=(t * sc.mass * G).tolist(), tip_r=abs(tip_r) * L, node_count=node_count)
    out["born"] = sc.rate_of(_critical(sc.mode, links=links, tip_mass=0.0 if links else sc.m_tip)[-1])
    vl = sc.links or VERDICT_LINKS
    out["verdict"], growth = _verdict(sc, vl)
    out["verdict_links"] = vl
    out["growth"] = growth
    out["growth_time"] = (1.0 / growth) if growth > 0 else None
    return out


def branch_answer(sc, rate_max):
    """Tip radius against the rate, up to rate_max [the user's unit], of the modes born below
    it (at most 6)."""
    links = _chain_of(sc, sc.links) if sc.links else None
    m_tip = 0.0 if links else sc.m_tip
    w_max = rate_max * sc.UNITS[sc.unit] * sc.time
    crit = _critical(MAX_MODE if links is None else min(MAX_MODE, sc.links), links=links,
                     tip_mass=m_tip)
    modes = [k + 1 for k, c in enumerate(crit) if c < w_max][:6]
    grid = np.linspace(w_max / BRANCH_RATES, w_max, BRANCH_RATES)
    branches = _sweep(modes, grid, links=links, tip_mass=m_tip) if modes else {}
    out = {"unit": sc.unit, "rate_max": rate_max, "modes": []}
    for k in modes:
        b = branches[k]
        # each branch from its birth on the hanging chain (tip radius 0)
        out["modes"].append({"mode": k, "born": sc.rate_of(crit[k - 1]),
                             "rate": [sc.rate_of(crit[k - 1])] + [sc.rate_of(w)
                                                                  for w in b["omega"]],
                             "tip_r": [0.0] + (np.abs(b["tip_r"]) * sc.length).tolist()})
    return out


def windows_answer(sc, mode, rate_max):
    """The stability windows of `mode` up to rate_max: [from, to, largest growth [1/s]] in the
    user's rate unit, of the N-link chain (the continuum's from VERDICT_LINKS links). Without
    dissipation only; mode 1 has none (a minimum of the amended potential)."""
    vl = sc.links or VERDICT_LINKS
    out = {"mode": mode, "links": vl, "windows": []}
    if mode < 2 or mode > vl or sc.drag:
        return out
    chain = _chain_of(sc, vl)
    w_max = rate_max * sc.UNITS[sc.unit] * sc.time
    lo = _critical(mode, links=chain)[-1] * (1 + 1e-4)
    if lo < w_max:
        win, _ = _stability_windows(mode, links=chain, omega_min=lo, omega_max=w_max)
        out["windows"] = [[sc.rate_of(a["from"]), sc.rate_of(a["to"]),
                           float(a["max_growth"]) / sc.time] for a in win]
    return out


class Run:
    """A perturbed run seeded with the shape, in a thread of its own; frames are read while it
    runs and it stops at the next chunk once cancelled."""

    def __init__(self, sc, frame):
        self.sc = sc
        self.frame = frame
        self.frames = []     # (t [s], deviation [m], positions [(N, 3) in m])
        self.error = None
        self.done = False
        self.cancelled = threading.Event()
        self.thread = threading.Thread(target=self._go, daemon=True)
        self.thread.start()

    def _go(self):
        sc = self.sc
        try:
            sim = Simulation(_chain_of(sc, sc.links or VERDICT_LINKS), dim=3, frame=self.frame, omega=sc.w,
                             drive_radius=sc.eps / sc.length, air_drag_quadratic=sc.c2,
                             method="gauss2")
            sim.set_steady(sc.mode, perturb=1e-3)
            period = 2 * math.pi / sc.w
            t_end = RUN_PERIODS * period
            every = t_end / RUN_FRAMES
            dt = min(period / 200, every)
            t = 0.0
            while t < t_end * (1 - 1e-12) and not self.cancelled.is_set():
                t1 = min(t + every, t_end)
                tr = sim.run(t1, dt, every=t1 - t)
                x = tr.x[-1] * sc.length
                self.frames.append((float(tr.t[-1]) * sc.time,
                                    float(tr.deviation[-1]) * sc.length, x.tolist()))
                t = t1
        except Exception as e:  # reported to the page, never a trace
            self.error = str(e) or e.__class__.__name__
        finally:
            self.done = True


class Server(http.server.ThreadingHTTPServer):
    daemon_threads = True

    def __init__(self, port):
        super().__init__(("127.0.0.1", port), Handler)
        self.runs = {}
        self.next_run = 1
        self.cache = {}
        self.lock = threading.Lock()

    def cached(self, key, make):
        """make()'s answer, kept for the same key (the branch diagram and the windows depend on
        the chain only, not on the rate turned)."""
        with self.lock:
            hit = self.cache.get(key)
        if hit is None:
            hit = make()
            with self.lock:
                if len(self.cache) > 64:
                    self.cache.clear()
                self.cache[key] = hit
        return hit


class Handler(http.server.BaseHTTPRequestHandler):
    server_version = "whirl-explore"

    def log_message(self, fmt, *args):  # quiet: the terminal shows the address and errors
        pass

    def _send(self, code, body, ctype="application/json", extra=None):
        data = body if isinstance(body, bytes) else body.encode()
        self.send_response(code)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(data)))
        self.send_header("Cache-Control", "no-store")
        for k, v in (extra or {}).items():
            self.send_header(k, v)
        self.end_headers()
        self.wfile.write(data)

    def _json(self, obj, code=200):
        self._send(code, json.dumps(obj, allow_nan=False))

    def _allowed(self):
        host = (self.headers.get("Host") or "").rsplit(":", 1)[0].strip("[]")
        client = self.client_address[0]
        return client in ("127.0.0.1", "::1") and host in ("127.0.0.1", "localhost")

    def do_GET(self):
        if not self._allowed():
            return self._send(403, "only this machine may use this page\n", "text/plain")
        url = urllib.parse.urlsplit(self.path)
        q = urllib.parse.parse_qs(url.query, max_num_fields=32)
        try:
            if url.path in ("/", "/index.html"):
                with open(PAGE, "rb") as f:
                    return self._send(200, f.read(), "text/html; charset=utf-8")
            if url.path == "/api/shape":
                return self._json(shape_answer(Scene(q)))
            if url.path in ("/api/branch", "/api/windows"):
                sc = Scene(q, need_rate=False)
                rate_max = _number(q, "rate_max", 1e-3, 1e5)
                if rate_max * sc.UNITS[sc.unit] * sc.time > 200:
                    raise InputError("rate_max above %s: beyond what the page computes live"
                                     % sc.rate_text(200 / sc.time))
                if url.path == "/api/branch":
                    key, make = ("branch",), (lambda: branch_answer(sc, rate_max))
                else:
                    mode = _number(q, "mode", 1, MAX_MODE, integer=True)
                    key, make = ("windows", mode), (lambda: windows_answer(sc, mode, rate_max))
                return self._json(self.server.cached(key + sc.key() + (rate_max,), make))
            if url.path == "/api/run/start":
                sc = Scene(q)
                frame = q.get("frame", ["rotating"])[0]
                if frame not in ("rotating", "inertial"):
                    raise InputError("frame must be rotating or inertial")
                shape_answer(sc)  # refuses a mode that does not exist at the rate
                with self.server.lock:
                    for r in self.server.runs.values():
                        r.cancelled.set()
                    rid = self.server.next_run
                    self.server.next_run += 1
                    self.server.runs = {rid: Run(sc, frame)}
                return self._json({"id": rid})
            if url.path in ("/api/run/poll", "/api/run/cancel"):
                rid = _number(q, "id", 1, 1e9, integer=True)
                run = self.server.runs.get(rid)
                if run is None:
                    raise InputError("no run %d" % rid)
                if url.path.endswith("cancel"):
                    run.cancelled.set()
                    return self._json({"cancelled": True})
                start = _number(q, "from", 0, 1e9, default=0, integer=True)
                frames = run.frames[start:]
                return self._json({"frames": frames, "done": run.done,
                                   "cancelled": run.cancelled.is_set(), "error": run.error,
                                   "total": RUN_FRAMES})
            if url.path in ("/api/csv/shape", "/api/csv/branch"):
                return self._csv(url.path, q)
            return self._send(404, "not found\n", "text/plain")
        except (InputError, ValueError, TypeError, _lib.Error) as e:
            return self._json({"error": str(e).splitlines()[0] if str(e) else "bad request"},
                              400)
        except (BrokenPipeError, ConnectionResetError):
            return None

    def _csv(self, path, q):
        if path.endswith("shape"):
            sc = Scene(q)
            a = shape_answer(sc)
            lines = ["# whirl explore: steady shape, mode %d at %s; chain %g m, %g kg, tip %g kg, %s"
                     % (sc.mode, sc.rate_text(sc.omega), sc.length, sc.mass, sc.tip,
                        "%d links" % sc.links if sc.links else "continuum"),
                     "# units: s [m], r [m], z [m], tension [N]", "s,r,z,tension"]
            lines += ["%.10g,%.10g,%.10g,%.10g" % row
                      for row in zip(a["s"], a["r"], a["z"], a["tension"])]
            name = "shape.csv"
        else:
            sc = Scene(q, need_rate=False)
            a = self.server.cached(("branch",) + sc.key() + (_number(q, "rate_max", 1e-3, 1e5),),
                                   lambda: branch_answer(sc, _number(q, "rate_max", 1e-3, 1e5)))
            unit = {"hz": "Hz", "rpm": "rpm", "rad/s": "rad/s"}[sc.unit]
            lines = ["# whirl explore: branches; chain %g m, %g kg, tip %g kg, %s"
                     % (sc.length, sc.mass, sc.tip,
                        "%d links" % sc.links if sc.links else "continuum"),
                     "# units: rate [%s], tip_r [m]" % unit, "mode,rate,tip_r"]
            for m in a["modes"]:
                lines += ["%d,%.10g,%.10g" % (m["mode"], f, r)
                          for f, r in zip(m["rate"], m["tip_r"])]
            name = "branches.csv"
        self._send(200, "\n".join(lines) + "\n", "text/csv",
                   {"Content-Disposition": 'attachment; filename="%s"' % name})


def serve(port=8470, browser=True, tries=50, out=sys.stdout):
    """Starts the server on the first free port from `port` (0: any) and serves until Ctrl-C."""
    server = None
    for p in ([0] if port == 0 else range(port, port + tries)):
        try:
            server = Server(p)
            break
        except OSError:
            continue
    if server is None:
        raise OSError("no free port in %d..%d" % (port, port + tries - 1))
    url = "http://127.0.0.1:%d/" % server.server_address[1]
    print("whirl explore: %s (Ctrl-C stops)" % url, file=out, flush=True)
    if browser:
        threading.Thread(target=webbrowser.open, args=(url,), daemon=True).start()
    try:
        server.serve_forever(poll_interval=0.2)
    except KeyboardInterrupt:
        print("whirl explore: stopped", file=out, flush=True)
    finally:
        for r in list(server.runs.values()):
            r.cancelled.set()
        server.server_close()
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m whirl.explore",
                                 description="A live page: turn the rate, watch the chain.")
    ap.add_argument("--port", type=int, default=8470,
                    help="first port tried (the next free one is taken; 0: any)")
    ap.add_argument("--no-browser", action="store_true", help="do not open a browser")
    a = ap.parse_args(argv)
    if not 0 <= a.port <= 65535:
        ap.error("--port must be in 0..65535")
    # Ctrl-C stops the server even when it was started where SIGINT is ignored (a shell's
    # background job), since that is the only way the page tells it to stop
    signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        return serve(a.port, not a.no_browser)
    except OSError as e:
        print("whirl explore: %s" % e, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
