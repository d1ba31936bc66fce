#!/usr/bin/python3
"""The live page's server probed as an adversary would, over HTTP on loopback:
    /usr/bin/python3 tests/tools/explore_server_probe.py TREE
starts `python3 -m whirl.explore` of the source tree TREE (its python/ and build/libwhirl.so)
and prints what it does with the shape's CSV link, a cross-site request to start a run, a query
of 40 fields, a heavy /api/windows request whose client leaves after 2 s (the processor time of
the server and its children in the 5 s after), and 300 clients that send half a request line
(the server's threads). docs/validation/explore.md gives its output for 2.1.0 and now."""
import http.client, json, os, re, socket, subprocess, sys, time
tree = sys.argv[1]
env = dict(os.environ, PYTHONPATH=tree + "/python", WHIRL_LIBRARY=tree + "/build/libwhirl.so")
p = subprocess.Popen([sys.executable, "-m", "whirl.explore", "--no-browser", "--port", "0"],
                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, text=True)
url = p.stdout.readline().split()[2]
port = int(url.rsplit(":", 1)[1].strip("/"))
def req(method, path, headers=None, body=None, timeout=30):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=timeout)
    c.request(method, path, body=body, headers=headers or {})
    r = c.getresponse(); return r.status, r.read()
page = req("GET", "/")[1].decode()
m = re.search(r'name="whirl-token" content="([^"]+)"', page)
tok = {"X-Whirl-Token": m.group(1)} if m else {}
def cpu():
    tot = 0
    for pid in [p.pid] + [int(x) for x in subprocess.run(["pgrep", "-P", str(p.pid)], capture_output=True, text=True).stdout.split()]:
        for q in [pid] + [int(x) for x in subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True).stdout.split()]:
            try:
                f = open("/proc/%d/stat" % q).read().rsplit(")", 1)[1].split()
                tot += (int(f[11]) + int(f[12])) / os.sysconf("SC_CLK_TCK")
            except OSError: pass
    return tot
SHAPE = "length=0.6&mass=0.05&rate=3&mode=2&unit=hz&links=30"
try:
    print("csv/shape:", req("GET", "/api/csv/shape?" + SHAPE + ("&token=" + m.group(1) if m else ""))[0])
except Exception as e: print("csv/shape: no answer:", repr(e))
try:
    print("cross-site GET run/start:", req("GET", "/api/run/start?" + SHAPE, {"Origin": "http://evil.example", "Sec-Fetch-Site": "cross-site"}))
except Exception as e: print("cross-site:", repr(e))
try:
    print("40 fields:", req("GET", "/api/shape?" + "&".join("f%d=1" % i for i in range(40)), tok)[0])
except Exception as e: print("40 fields: no answer:", repr(e))
HEAVY = "/api/windows?length=0.6&mass=0.05&links=400&unit=hz&rate_max=50&mode=12"
s = socket.create_connection(("127.0.0.1", port))
s.sendall(("GET %s HTTP/1.1\r\nHost: 127.0.0.1\r\n%s\r\n" % (HEAVY, "".join("%s: %s\r\n" % kv for kv in tok.items()))).encode())
time.sleep(2); s.close(); c0 = cpu(); time.sleep(5); c1 = cpu()
print("after the client left: %.2f s of CPU in the next 5 s" % (c1 - c0))
socks = []
for _ in range(300):
    x = socket.create_connection(("127.0.0.1", port), timeout=10); x.sendall(b"GET /api/sha"); socks.append(x)
time.sleep(1)
print("threads with 300 slow clients:", [l.split()[1] for l in open("/proc/%d/status" % p.pid) if l.startswith("Threads")][0])
for x in socks: x.close()
p.kill(); p.wait()
print("stderr tail:", p.stderr.read()[-300:])
