"""The live page's server (whirl.explore) as an adversary meets it, over loopback: only the page
itself may use the API (a per-server token; Origin and Sec-Fetch-Site of another site refused);
what starts or stops a run is a POST; a computation is bounded in time and stopped once its
client has gone; at most a few computations run at once; slow clients time out and hold a bounded
number of threads; every query is answered (400 with a message), the CSV links included."""
import http.client
import json
import random
import re
import socket
import threading
import time
import urllib.parse

import pytest

from whirl import explore

SHAPE = "length=0.6&mass=0.05&rate=3&mode=2&unit=hz"
CHAIN = "length=0.6&mass=0.05&unit=hz"
# within the page's own bounds, but minutes of work: the windows of mode 12 of 400 links
HEAVY = "/api/windows?length=0.6&mass=0.05&links=400&unit=hz&rate_max=50&mode=12"


class Live:
    """A server on a free loopback port, in this process."""

    def __init__(self, **bounds):
        self.server = explore.Server(0, **bounds)
        self.port = self.server.server_address[1]
        self.thread = threading.Thread(target=self.server.serve_forever,
                                       kwargs={"poll_interval": 0.05}, daemon=True)
        self.thread.start()
        page = self.request("GET", "/", token=False)[2].decode()
        m = re.search(r'name="whirl-token" content="([^"]+)"', page)
        self.token = m.group(1)
        assert self.token == self.server.token and "{{" not in self.token

    def request(self, method, path, body=None, headers=None, token=True, timeout=60):
        c = http.client.HTTPConnection("127.0.0.1", self.port, timeout=timeout)
        h = {"X-Whirl-Token": self.token} if token else {}
        if body is not None:
            h["Content-Type"] = "application/x-www-form-urlencoded"
        h.update(headers or {})
        c.request(method, path, body=body, headers=h)
        r = c.getresponse()
        out = r.status, dict(r.getheaders()), r.read()
        c.close()
        return out

    def json(self, method, path, **kw):
        code, _, body = self.request(method, path, **kw)
        return code, json.loads(body)

    def close(self):
        self.server.shutdown()
        self.server.server_close()
        self.thread.join(10)


@pytest.fixture
def live():
    s = Live(seconds=3.0)
    yield s
    s.close()


def _busy(live):
    """Computations running now."""
    w = live.server.workers
    return w.size - w.slots._value


def test_shape_csv_answers(live):
    code, headers, body = live.request("GET", "/api/csv/shape?%s&links=30&token=%s"
                                       % (SHAPE, live.token), token=False)
    assert code == 200, body
    lines = body.decode().splitlines()
    assert lines[2] == "s,x,y,z,tension" and len(lines) == 3 + 31
    s, x, y, z, t = (float(v) for v in lines[-1].split(","))
    assert abs(s - 0.6) < 1e-9 and y == 0 and z < 0 and t > 0  # the free end, 0.6 m down the chain
    code, _, body = live.request("GET", "/api/csv/branch?%s&rate_max=6&token=%s"
                                 % (CHAIN, live.token), token=False)
    assert code == 200 and body.decode().splitlines()[2] == "mode,rate,tip_r"


def test_other_sites_are_refused(live):
    ok = live.json("GET", "/api/shape?" + SHAPE)
    assert ok[0] == 200 and ok[1]["node_count"] == 2
    refused = [
        live.json("GET", "/api/shape?" + SHAPE, token=False),  # a page elsewhere: no token
        live.json("GET", "/api/shape?%s&token=%s" % (SHAPE, "x" * 43), token=False),
        live.json("GET", "/api/shape?" + SHAPE, headers={"Origin": "http://evil.example"}),
        live.json("GET", "/api/shape?" + SHAPE, headers={"Origin": "null"}),
        live.json("GET", "/api/shape?" + SHAPE, headers={"Sec-Fetch-Site": "cross-site"}),
        live.json("GET", "/api/shape?" + SHAPE, headers={"Sec-Fetch-Site": "same-site"}),
        live.json("POST", "/api/run/start", body=SHAPE + "&links=10", token=False,
                  headers={"Origin": "http://evil.example", "Sec-Fetch-Site": "cross-site"}),
        live.json("POST", "/api/run/cancel", body="id=1", token=False),
    ]
    for code, answer in refused:
        assert code == 403 and "refused" in answer["error"] or "token" in answer["error"], \
            (code, answer)
    assert live.server.next_run == 1  # no run was started
    # the page's own origin passes
    code, _ = live.json("GET", "/api/shape?" + SHAPE, headers={
        "Origin": "http://127.0.0.1:%d" % live.port, "Sec-Fetch-Site": "same-origin"})
    assert code == 200
    # the page itself cannot be framed by another site
    _, headers, _ = live.request("GET", "/", token=False)
    assert headers["X-Frame-Options"] == "DENY"


def test_runs_start_and_stop_only_by_post(live):
    code, answer = live.json("GET", "/api/run/start?%s&links=10" % SHAPE)
    assert code == 405 and "POST" in answer["error"]
    code, answer = live.json("POST", "/api/run/start", body=SHAPE + "&links=10")
    assert code == 200, answer
    rid = answer["id"]
    code, answer = live.json("GET", "/api/run/cancel?id=%d" % rid)
    assert code == 405
    code, answer = live.json("POST", "/api/run/cancel", body="id=%d" % rid)
    assert code == 200 and answer["cancelled"]
    end = time.monotonic() + 30
    while time.monotonic() < end:
        code, answer = live.json("GET", "/api/run/poll?id=%d" % rid)
        if answer["done"]:
            break
        time.sleep(0.05)
    assert answer["done"] and answer["cancelled"]


def test_a_long_computation_is_bounded_in_time(live):
    t0 = time.monotonic()
    code, answer = live.json("GET", HEAVY)
    took = time.monotonic() - t0
    assert code == 503 and "stopped after 3 s" in answer["error"], answer
    assert took < 30, took
    assert _busy(live) == 0 and not live.server.workers.all - set(live.server.workers.idle)


def _leave_while_computing(live, path):
    """Sends the request, waits until its computation runs, closes the connection; the seconds
    until the server has stopped the computation (its worker killed)."""
    sock = socket.create_connection(("127.0.0.1", live.port), timeout=30)
    sock.sendall(("GET %s HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Whirl-Token: %s\r\n\r\n"
                  % (path, live.token)).encode())
    end = time.monotonic() + 30
    while _busy(live) == 0 and time.monotonic() < end:
        time.sleep(0.005)
    assert _busy(live) == 1
    workers = list(live.server.workers.all)
    sock.close()
    t0 = time.monotonic()
    while _busy(live) and time.monotonic() < end:
        time.sleep(0.002)
    took = time.monotonic() - t0
    assert _busy(live) == 0
    for p, _ in workers:
        p.join(10)
        assert not p.is_alive()
    return took


def test_a_computation_stops_when_its_client_leaves():
    live = Live(seconds=60.0)
    try:
        took = [_leave_while_computing(live, HEAVY) for _ in range(3)]
        # each change of mode on the page drops the request before: none keeps running
        for mode in (10, 11, 12):
            _leave_while_computing(live, HEAVY.replace("mode=12", "mode=%d" % mode))
        print("explore: a computation stopped %.3f s (median of 3) after its client left"
              % sorted(took)[1])
    finally:
        live.close()


def test_at_most_a_few_computations_at_once(monkeypatch):
    monkeypatch.setattr(explore, "QUEUE_SECONDS", 0.5)
    live = Live(seconds=5.0, computations=2)
    try:
        out = []

        def heavy():
            out.append(live.json("GET", HEAVY)[0])

        threads = [threading.Thread(target=heavy) for _ in range(2)]
        for t in threads:
            t.start()
        end = time.monotonic() + 30
        while _busy(live) < 2 and time.monotonic() < end:
            time.sleep(0.01)
        code, answer = live.json("GET", HEAVY.replace("mode=12", "mode=11"))
        assert code == 503 and "busy" in answer["error"], answer
        for t in threads:
            t.join(60)
        assert out == [503, 503]  # both stopped at the bound
    finally:
        live.close()


def test_slow_clients_time_out_and_hold_few_threads(monkeypatch):
    monkeypatch.setattr(explore.Handler, "timeout", 1.0)
    live = Live(seconds=3.0, connections=16)
    socks = []
    try:
        before = threading.active_count()
        for _ in range(300):  # each sends half a request line and nothing more
            s = socket.create_connection(("127.0.0.1", live.port), timeout=10)
            s.sendall(b"GET /api/sha")
            socks.append(s)
        time.sleep(0.3)
        held = threading.active_count() - before
        assert held <= 16, held
        # once they have timed out the page is served again
        end = time.monotonic() + 30
        while time.monotonic() < end:
            try:
                code = live.request("GET", "/api/shape?" + SHAPE, timeout=5)[0]
            except (OSError, http.client.HTTPException):
                code = None
            if code == 200:
                break
            time.sleep(0.2)
        assert code == 200
        print("explore: 300 slow clients held %d threads" % held)
    finally:
        for s in socks:
            s.close()
        live.close()


def test_too_many_fields_and_odd_bodies_are_answered(live):
    q = "&".join("f%d=1" % i for i in range(40))
    code, answer = live.json("GET", "/api/shape?" + q)
    assert code == 400 and "at most 32 fields" in answer["error"]
    code, answer = live.json("POST", "/api/run/start", body="x" * 5000)
    assert code == 400 and "4096 bytes" in answer["error"]
    code, answer = live.json("POST", "/api/run/start", body="", headers={"Content-Length": "-3"})
    assert code == 400


FIELDS = ["length", "mass", "tip", "links", "drag", "diameter", "eps", "unit", "rate", "mode",
          "rate_max", "frame", "id", "from", "token"]
VALUES = ["", "0", "1", "-1", "2", "3", "30", "400", "401", "1e308", "-1e308", "nan", "inf",
          "0x10", "1_000", "9" * 5000, "abc", "hz", "rpm", "rad/s", "HZ", "rotating", "inertial",
          "\u00e9\u4e2d", "%00", "%ff%fe", "1;2", "[1]", " 2 ", "0.6", "0.05", "1e-3", "12"]
ENDPOINTS = ["/api/shape", "/api/branch", "/api/windows", "/api/csv/shape", "/api/csv/branch",
             "/api/run/poll", "/api/nothing", "/"]


def test_every_query_is_answered(live):
    rng = random.Random(38)
    seen = {}
    for _ in range(150):
        path = rng.choice(ENDPOINTS)
        fields = [(rng.choice(FIELDS), rng.choice(VALUES)) for _ in range(rng.randint(0, 14))]
        query = "&".join("%s=%s" % (k, urllib.parse.quote(v, safe="%")) for k, v in fields)
        if rng.random() < 0.1:
            query += "&&=&" + "%zz"  # malformed pieces
        try:
            code, headers, body = live.request("GET", path + "?" + query, timeout=30)
        except (OSError, http.client.HTTPException) as e:
            pytest.fail("%s?%s: no answer: %r" % (path, query[:200], e))
        assert code in (200, 400, 404, 503), (path, query[:200], code, body[:200])
        if code in (400, 503):
            assert json.loads(body)["error"], body
        seen[code] = seen.get(code, 0) + 1
    assert seen.get(400, 0) > 50 and seen.get(200, 0) > 5, seen
    # the runs' endpoints with odd forms
    for _ in range(30):
        form = "&".join("%s=%s" % (rng.choice(FIELDS), urllib.parse.quote(rng.choice(VALUES)))
                        for _ in range(rng.randint(0, 12)))
        code, _, body = live.request("POST", rng.choice(["/api/run/start", "/api/run/cancel"]),
                                     body=form)
        assert code in (200, 400), (form, code, body)


def test_refusing_a_cross_site_request_is_quick(live):
    """The time to refuse a request from another site, printed (no timed assertion)."""
    times = []
    for _ in range(100):
        t0 = time.perf_counter()
        code, _, _ = live.request("POST", "/api/run/start", body=SHAPE, token=False,
                                  headers={"Origin": "http://evil.example"})
        times.append(time.perf_counter() - t0)
        assert code == 403
    times.sort()
    print("explore: a cross-site request refused in %.2f ms (median of 100, over loopback, "
          "connection included)" % (1e3 * times[50]))


def test_a_run_stops_once_the_page_stops_asking(live, monkeypatch):
    monkeypatch.setattr(explore, "RUN_IDLE", 0.0)  # no poll since the start counts as gone
    code, answer = live.json("POST", "/api/run/start", body=SHAPE + "&links=60")
    assert code == 200, answer
    run = live.server.runs[answer["id"]]
    run.thread.join(60)  # nobody polls: the page has gone
    assert run.done and run.cancelled.is_set()
    assert run.error == "stopped: the page stopped asking for frames"
    assert run.frames == []
