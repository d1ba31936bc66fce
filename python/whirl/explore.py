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
Only the page itself may use the API (403 otherwise): it carries a token made afresh by each
server (a page of another site cannot read it), and a request whose Origin or Sec-Fetch-Site
names another site is refused (cross-site request forgery); what starts or stops a run is a
POST. Each computation runs in a worker process, at most a few at once (503 beyond), and is
stopped (its process killed) once its client has gone or after COMPUTE_SECONDS; slow clients
time out. Every request is answered (400 with a message for bad input).
Ctrl-C stops the server and any run in progress."""
import argparse
import hmac
import http.server
import json
import math
import multiprocessing
import os
import secrets
import select
import signal
import socket
import sys
import threading
import time
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
# The server's bounds: one computation stops after COMPUTE_SECONDS (a shape takes ~0.1 s, the
# windows of 400 links up to mode 12 would take minutes); at most MAX_COMPUTATIONS run at once
# (a page asks for a shape, the branches and the windows together), a request waiting at most
# QUEUE_SECONDS for its turn (503 after); a client slower than CLIENT_SECONDS to send its
# request or read its answer is dropped; at most MAX_CONNECTIONS connections are served at once
# (503 beyond); a run stops after RUN_SECONDS, or when the page has not polled for RUN_IDLE
# seconds (it polls every 0.2 s). A computation watches its client every POLL_SECONDS.
COMPUTE_SECONDS = 20.0
MAX_COMPUTATIONS = 3
QUEUE_SECONDS = 5.0
CLIENT_SECONDS = 10.0
MAX_CONNECTIONS = 32
RUN_SECONDS = 600.0
RUN_IDLE = 10.0
POLL_SECONDS = 0.02
MAX_FIELDS = 32      # fields of one query (the page sends at most 13)
BODY_MAX = 4096      # bytes of a POST's form
ENDPOINTS = ("/api/shape", "/api/branch", "/api/windows", "/api/csv/shape", "/api/csv/branch",
             "/api/run/start", "/api/run/poll", "/api/run/cancel")
CHANGES_STATE = ("/api/run/start", "/api/run/cancel")  # POST only
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
            arc, x, y, z, t = d.s, d.x, d.y, d.z, d.tension
            node_count, tip_r = int(d.node_count), float(d.tip_r)
        else:
            s = _shape(sc.w, sc.mode, links=links, tip_mass=0.0 if links else sc.m_tip)
            arc, x, y, z, t = s.s, s.r, np.zeros_like(s.r), s.z, s.tension
            node_count, tip_r = int(s.node_count), float(s.tip_r)
    except _lib.Error as e:
        raise _missing_mode(sc, links, e) from None
    out.update(s=(arc * L).tolist(), x=(x * L).tolist(), y=(y * L).tolist(), z=(z * L).tolist(),
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
    runs. It stops at the next chunk (a tenth of a period) once cancelled: by the page, by a new
    run, when the page has not asked for frames for RUN_IDLE seconds (it went away), or after
    RUN_SECONDS."""

    def __init__(self, sc, frame):
        self.sc = sc
        self.frame = frame
        self.frames = []     # (t [s], deviation [m], positions [(N, 3) in m])
        self.error = None
        self.done = False
        self.cancelled = threading.Event()
        self.polled = time.monotonic()
        self.thread = threading.Thread(target=self._go, daemon=True)
        self.thread.start()

    def _stop_reason(self, started):
        if self.cancelled.is_set():
            return "cancelled"
        now = time.monotonic()
        if now - self.polled > RUN_IDLE:
            return "stopped: the page stopped asking for frames"
        if now - started > RUN_SECONDS:
            return "stopped after %g s, the page's bound on one run" % RUN_SECONDS
        return None

    def _go(self):
        sc = self.sc
        started = time.monotonic()
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
            while t < t_end * (1 - 1e-12):
                reason = self._stop_reason(started)
                if reason is not None:
                    if reason != "cancelled":
                        self.error = reason
                    self.cancelled.set()
                    break
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


# ---- the computations, each in a process of its own ----
# The library's stop request is one per process, so one request's computation cannot be stopped
# in a process that runs others; a worker process can (it is killed). Workers are forked from
# multiprocessing's fork server, a process that has imported whirl and computed nothing: a
# fork of it is single-threaded and costs milliseconds, and an idle worker is kept for the next
# request.

def _compute(kind, args):
    if kind == "shape":
        return shape_answer(*args)
    if kind == "branch":
        return branch_answer(*args)
    if kind == "windows":
        return windows_answer(*args)
    raise ValueError("unknown computation %r" % kind)


def _worker_main(conn):
    """A worker: answers (kind, args) with ("ok", answer), ("bad", message) for bad input (400),
    or ("fail", message); ends when the server closes the pipe. Ctrl-C is the server's to
    handle (the terminal sends it to the whole process group)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    while True:
        try:
            kind, args = conn.recv()
        except (EOFError, OSError):
            return
        try:
            reply = ("ok", _compute(kind, args))
        except (InputError, ValueError, TypeError, _lib.Error) as e:
            reply = ("bad", str(e).splitlines()[0] if str(e) else e.__class__.__name__)
        except Exception as e:
            reply = ("fail", "%s: %s" % (e.__class__.__name__, e))
        try:
            conn.send(reply)
        except (BrokenPipeError, OSError):
            return


class Refused(Exception):
    """A request not computed: answered with ``code`` and the message."""

    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


class Workers:
    """At most `size` computations at once, each in a worker process, each bounded in time and
    cancelled (the worker killed) once its client has gone."""

    def __init__(self, size, seconds):
        self.size = size
        self.seconds = seconds
        self.slots = threading.BoundedSemaphore(size)
        self.idle = []
        self.all = set()
        self.lock = threading.Lock()
        self.ctx = multiprocessing.get_context("forkserver")
        self.ctx.set_forkserver_preload(["whirl"])  # not whirl.explore: it may be __main__

    def _take(self):
        with self.lock:
            while self.idle:
                w = self.idle.pop()
                if w[0].is_alive():
                    return w
                self._end(w)
        here, there = self.ctx.Pipe()
        p = self.ctx.Process(target=_worker_main, args=(there,), daemon=True)
        p.start()
        there.close()
        w = (p, here)
        with self.lock:
            self.all.add(w)
        return w

    def warm(self):
        """Starts the fork server and one idle worker in the background, so that the page's
        first request does not wait for them (about the time whirl takes to import)."""
        def start():
            try:
                w = self._take()
            except OSError:
                return  # the first request tries again, and reports
            with self.lock:
                self.idle.append(w)
        threading.Thread(target=start, daemon=True).start()

    def _end(self, w):
        p, conn = w
        if p.is_alive():
            p.kill()
        p.join(5)
        conn.close()
        with self.lock:
            self.all.discard(w)

    def run(self, kind, args, gone):
        """The answer of _compute(kind, args); Refused with the code and message otherwise.
        gone() is asked every POLL_SECONDS while waiting: True (the client left) kills the
        worker."""
        end = time.monotonic() + QUEUE_SECONDS
        while not self.slots.acquire(timeout=POLL_SECONDS):
            if gone():
                raise Refused(499, "the client went away")
            if time.monotonic() > end:
                raise Refused(503, "the server is busy with %d computations; try again"
                              % self.size)
        w = None
        try:
            w = self._take()
            w[1].send((kind, args))
            deadline = time.monotonic() + self.seconds
            while not w[1].poll(POLL_SECONDS):
                if gone():
                    raise Refused(499, "the client went away")
                if time.monotonic() > deadline:
                    raise Refused(503, "stopped after %g s, the page's bound on one "
                                  "computation: fewer links or a lower rate (the command "
                                  "line has no such bound)" % self.seconds)
            status, answer = w[1].recv()
            with self.lock:
                self.idle.append(w)
            w = None
        except (EOFError, OSError):
            if w is not None:
                w[0].join(1)
            raise Refused(500, "the computation's process ended (exit status %s)"
                          % (w[0].exitcode if w is not None else "?")) from None
        finally:
            if w is not None:
                self._end(w)
            self.slots.release()
        if status == "bad":
            raise InputError(answer)
        if status != "ok":
            raise Refused(500, answer)
        return answer

    def close(self):
        with self.lock:
            every = list(self.all)
        for w in every:
            self._end(w)


class Server(http.server.ThreadingHTTPServer):
    """The page's server: one thread per connection, at most MAX_CONNECTIONS of them (503
    beyond); at most MAX_COMPUTATIONS computations at once in worker processes (Workers)."""

    daemon_threads = True

    def __init__(self, port, seconds=COMPUTE_SECONDS, computations=MAX_COMPUTATIONS,
                 connections=MAX_CONNECTIONS):
        self.token = secrets.token_urlsafe(32)
        self.workers = Workers(computations, seconds)
        self.connections = threading.BoundedSemaphore(connections)
        self.runs = {}
        self.next_run = 1
        self.cache = {}
        self.lock = threading.Lock()
        super().__init__(("127.0.0.1", port), Handler)  # closes the server if it cannot bind

    def origins(self):
        port = self.server_address[1]
        return ("http://127.0.0.1:%d" % port, "http://localhost:%d" % port)

    def process_request(self, request, client_address):
        if not self.connections.acquire(blocking=False):
            body = b"busy: too many connections\n"
            try:
                request.sendall(b"HTTP/1.0 503 Service Unavailable\r\nContent-Type: text/plain\r\n"
                                b"Content-Length: %d\r\nConnection: close\r\n\r\n%s"
                                % (len(body), body))
            except OSError:
                pass
            self.shutdown_request(request)
            return
        t = threading.Thread(target=self.process_request_thread, args=(request, client_address),
                             daemon=True)
        try:
            t.start()  # the thread releases the slot (a Ctrl-C here is the server's to handle)
        except RuntimeError:  # no thread to be had
            self.connections.release()
            self.shutdown_request(request)

    def process_request_thread(self, request, client_address):
        try:
            super().process_request_thread(request, client_address)
        finally:
            self.connections.release()

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

    def server_close(self):
        with self.lock:
            for r in self.runs.values():
                r.cancelled.set()
        self.workers.close()
        super().server_close()


class Handler(http.server.BaseHTTPRequestHandler):
    server_version = "whirl-explore"
    timeout = CLIENT_SECONDS  # a client that sends its request (or reads the answer) slower

    def log_message(self, fmt, *args):  # quiet: the terminal shows the address and errors
        pass

    def _send(self, code, body, ctype="application/json", extra=None):
        data = body if isinstance(body, bytes) else body.encode()
        self.send_response(code)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(data)))
        self.send_header("Cache-Control", "no-store")
        self.send_header("X-Content-Type-Options", "nosniff")
        for k, v in (extra or {}).items():
            self.send_header(k, v)
        self.end_headers()
        self.wfile.write(data)

    def _json(self, obj, code=200):
        self._send(code, json.dumps(obj, allow_nan=False))

    def _error(self, code, message):
        self._json({"error": message}, code)

    def _allowed(self):
        host = (self.headers.get("Host") or "").rsplit(":", 1)[0].strip("[]")
        client = self.client_address[0]
        return client in ("127.0.0.1", "::1") and host in ("127.0.0.1", "localhost")

    def _same_origin(self, q):
        """None for a request of the page itself, else why not: the page's token (sent as the
        X-Whirl-Token header, or a token field in a link), and no Origin or Sec-Fetch-Site
        naming another site (browsers send them; a page elsewhere cannot read the token)."""
        origin = self.headers.get("Origin")
        if origin is not None and origin not in self.server.origins():
            return "requests from %.60s are refused: only the page itself may ask" % origin
        site = self.headers.get("Sec-Fetch-Site")
        if site is not None and site != "same-origin":
            return "%.20s requests are refused: only the page itself may ask" % site
        token = self.headers.get("X-Whirl-Token") or q.get("token", [""])[0]
        if not hmac.compare_digest(token.encode("utf-8", "replace"),
                                   self.server.token.encode()):
            return "the page's token is missing or wrong: reload the page"
        return None

    def _gone(self):
        """True once the client has closed its connection (its end readable with nothing to
        read) or reset it."""
        try:
            ready, _, _ = select.select([self.connection], [], [], 0)
            return bool(ready) and self.connection.recv(1, socket.MSG_PEEK) == b""
        except (OSError, ValueError):
            return True

    def _query(self, url):
        try:
            return urllib.parse.parse_qs(url.query, max_num_fields=MAX_FIELDS)
        except ValueError:
            raise InputError("a query has at most %d fields" % MAX_FIELDS) from None

    def _compute(self, kind, *args):
        return self.server.workers.run(kind, args, self._gone)

    def do_GET(self):
        self._handle("GET")

    def do_POST(self):
        self._handle("POST")

    def _body(self):
        """The form fields of a POST (application/x-www-form-urlencoded), at most BODY_MAX
        bytes."""
        try:
            n = int(self.headers.get("Content-Length") or 0)
        except ValueError:
            raise InputError("Content-Length: not a number") from None
        if not 0 <= n <= BODY_MAX:
            raise InputError("a request body has at most %d bytes" % BODY_MAX)
        return self.rfile.read(n).decode("utf-8", "replace") if n else ""

    def _handle(self, method):
        if not self._allowed():
            return self._send(403, "only this machine may use this page\n", "text/plain")
        try:
            url = urllib.parse.urlsplit(self.path)
            if url.path in ("/", "/index.html"):
                if method != "GET":
                    return self._send(405, "GET only\n", "text/plain", {"Allow": "GET"})
                with open(PAGE, "rb") as f:
                    page = f.read().replace(b"{{WHIRL_TOKEN}}", self.server.token.encode())
                return self._send(200, page, "text/html; charset=utf-8",
                                  {"X-Frame-Options": "DENY",
                                   "Content-Security-Policy": "frame-ancestors 'none'"})
            if url.path not in ENDPOINTS:
                return self._send(404, "not found\n", "text/plain")
            q = self._query(url)
            if method == "POST":
                form = urllib.parse.urlsplit("?" + self._body())
                for k, v in self._query(form).items():
                    q.setdefault(k, []).extend(v)
            why = self._same_origin(q)
            if why is not None:
                return self._error(403, why)
            want = "POST" if url.path in CHANGES_STATE else "GET"
            if method != want:
                return self._error(405, "%s needs %s" % (url.path, want))
            return self._api(url.path, q)
        except InputError as e:
            return self._error(400, str(e) or "bad request")
        except Refused as e:
            if e.code != 499:  # nobody is left to answer
                return self._error(e.code, str(e))
        except (BrokenPipeError, ConnectionResetError, socket.timeout):
            return None
        except Exception as e:  # a defect: answered, and shown in the terminal
            print("whirl explore: %s %s: %s: %s" % (method, self.path[:200],
                                                   e.__class__.__name__, e), file=sys.stderr)
            return self._error(500, "internal error: %s" % e.__class__.__name__)

    def _api(self, path, q):
        if path == "/api/shape":
            return self._json(self._compute("shape", Scene(q)))
        if path in ("/api/branch", "/api/windows", "/api/csv/branch"):
            sc = Scene(q, need_rate=False)
            rate_max = _number(q, "rate_max", 1e-3, 1e5)
            if rate_max * sc.UNITS[sc.unit] * sc.time > 200:
                raise InputError("rate_max above %s: beyond what the page computes live"
                                 % sc.rate_text(200 / sc.time))
            if path == "/api/windows":
                mode = _number(q, "mode", 1, MAX_MODE, integer=True)
                key, make = ("windows", mode), (lambda: self._compute("windows", sc, mode,
                                                                      rate_max))
            else:
                key, make = ("branch",), (lambda: self._compute("branch", sc, rate_max))
            answer = self.server.cached(key + sc.key() + (rate_max,), make)
            if path == "/api/csv/branch":
                return self._branch_csv(sc, answer)
            return self._json(answer)
        if path == "/api/csv/shape":
            sc = Scene(q)
            return self._shape_csv(sc, self._compute("shape", sc))
        if path == "/api/run/start":
            sc = Scene(q)
            frame = q.get("frame", ["rotating"])[0]
            if frame not in ("rotating", "inertial"):
                raise InputError("frame must be rotating or inertial")
            self._compute("shape", sc)  # refuses a mode that does not exist at the rate
            with self.server.lock:
                for r in self.server.runs.values():
                    r.cancelled.set()
                rid = self.server.next_run
                self.server.next_run += 1
                self.server.runs = {rid: Run(sc, frame)}
            return self._json({"id": rid})
        # /api/run/poll and /api/run/cancel
        rid = _number(q, "id", 1, 1e9, integer=True)
        with self.server.lock:
            run = self.server.runs.get(rid)
        if run is None:
            raise InputError("no run %d" % rid)
        if path.endswith("cancel"):
            run.cancelled.set()
            return self._json({"cancelled": True})
        run.polled = time.monotonic()
        start = _number(q, "from", 0, 1e9, default=0, integer=True)
        frames = run.frames[start:]
        return self._json({"frames": frames, "done": run.done,
                           "cancelled": run.cancelled.is_set(), "error": run.error,
                           "total": RUN_FRAMES})

    def _shape_csv(self, sc, a):
        lines = ["# whirl explore: steady shape, mode %d at %s; chain %g m, %g kg, tip %g kg, %s"
                 % (sc.mode, sc.rate_text(sc.omega), sc.length, sc.mass, sc.tip,
                    "%d links" % sc.links if sc.links else "continuum"),
                 "# units: s [m], x [m], y [m], z [m], tension [N] (x-y: the co-rotating "
                 "frame; without drag the shape lies in the x-z plane)", "s,x,y,z,tension"]
        lines += ["%.10g,%.10g,%.10g,%.10g,%.10g" % row
                  for row in zip(a["s"], a["x"], a["y"], a["z"], a["tension"])]
        self._send(200, "\n".join(lines) + "\n", "text/csv",
                   {"Content-Disposition": 'attachment; filename="shape.csv"'})

    def _branch_csv(self, sc, a):
        unit = {"hz": "Hz", "rpm": "rpm", "rad/s": "rad/s"}[sc.unit]
        lines = ["# whirl explore: branches; chain %g m, %g kg, tip %g kg, %s"
                 % (sc.length, sc.mass, sc.tip,
                    "%d links" % sc.links if sc.links else "continuum"),
                 "# units: rate [%s], tip_r [m]" % unit, "mode,rate,tip_r"]
        for m in a["modes"]:
            lines += ["%d,%.10g,%.10g" % (m["mode"], f, r)
                      for f, r in zip(m["rate"], m["tip_r"])]
        self._send(200, "\n".join(lines) + "\n", "text/csv",
                   {"Content-Disposition": 'attachment; filename="branches.csv"'})


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
    server.workers.warm()
    url = "http://127.0.0.1:%d/" % server.server_address[1]
    print("whirl explore: %s (Ctrl-C stops)" % url, file=out, flush=True)
    if browser:
        threading.Thread(target=webbrowser.open, args=(url,), daemon=True).start()
    try:
        server.serve_forever(poll_interval=0.2)
    except KeyboardInterrupt:
        print("whirl explore: stopped", file=out, flush=True)
    finally:
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
    # the module's own copy (not __main__'s), so that the worker processes find its functions
    from whirl.explore import main as _main
    sys.exit(_main())
