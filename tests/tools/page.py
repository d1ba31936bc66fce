"""One headless Chromium for a test's pages, driven through the DevTools protocol, instead of a new
browser for every screenshot or DOM dump (each start costs about a second).

    page.py start DIR             starts Chromium (profile in DIR), prints "PORT PID" and returns
    page.py shot PORT URL PNG LOG an 800 x 600 screenshot of URL into PNG
    page.py dom PORT URL LOG      prints URL's <body ...> tag after its script ran

Each page opens in a tab of its own, 800 x 600 CSS pixels at scale 1, scroll bars hidden, and is
read once its load event fired and two animation frames passed. Every console message of the page
(console.* calls of any level, uncaught exceptions, the browser's own entries such as a resource
that failed to load) goes to LOG, one line each: the tests want it empty."""
import json
import os
import subprocess
import sys
import time
import urllib.request

import websocket  # python3-websocket

WIDTH, HEIGHT = 800, 600


def start(profile):
    os.makedirs(profile, exist_ok=True)
    port_file = os.path.join(profile, "DevToolsActivePort")
    if os.path.exists(port_file):
        os.remove(port_file)
    proc = subprocess.Popen(
        ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
         "--no-first-run", "--disable-background-networking", "--disable-component-update",
         "--disable-sync", "--hide-scrollbars", "--user-data-dir=" + profile,
         "--remote-debugging-port=0", "--window-size=%d,%d" % (WIDTH, HEIGHT), "about:blank"],
        stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        env={k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}, start_new_session=True)
    # the port Chromium chose, in DevToolsActivePort once it listens (up to 60 s on a busy machine)
    for _ in range(1200):
        if proc.poll() is not None:
            sys.exit("page.py: chromium exited with status %d" % proc.returncode)
        if os.path.exists(port_file) and open(port_file).read().strip():
            break
        time.sleep(0.05)
    else:
        proc.kill()
        sys.exit("page.py: chromium did not start within 60 s")
    print(open(port_file).read().split()[0], proc.pid)


class Tab:
    """A new tab of the browser at PORT; its console messages collect in self.console."""

    def __init__(self, port):
        self.base = "http://127.0.0.1:%s" % port
        req = urllib.request.Request(self.base + "/json/new?about:blank", method="PUT")
        target = json.load(urllib.request.urlopen(req, timeout=60))
        self.id = target["id"]
        self.ws = websocket.create_connection(target["webSocketDebuggerUrl"], timeout=120)
        self.n = 0
        self.console = []
        self.loaded = False
        for method in ("Runtime.enable", "Log.enable", "Page.enable"):
            self.call(method)
        self.call("Emulation.setDeviceMetricsOverride", width=WIDTH, height=HEIGHT,
                  deviceScaleFactor=1, mobile=False)
        self.call("Emulation.setScrollbarsHidden", hidden=True)

    def _event(self, m):
        method, p = m.get("method"), m.get("params", {})
        if method == "Runtime.consoleAPICalled":
            self.console.append("console.%s: %s" % (p["type"], " ".join(
                str(a.get("value", a.get("description", ""))) for a in p.get("args", []))))
        elif method == "Runtime.exceptionThrown":
            d = p["exceptionDetails"]
            self.console.append("exception: %s %s" % (
                d.get("text", ""), d.get("exception", {}).get("description", "")))
        elif method == "Log.entryAdded" and p["entry"]["level"] != "verbose":
            e = p["entry"]
            self.console.append("%s %s: %s" % (e["source"], e["level"], e["text"]))
        elif method == "Page.loadEventFired":
            self.loaded = True

    def call(self, method, **params):
        self.n += 1
        self.ws.send(json.dumps({"id": self.n, "method": method, "params": params}))
        while True:
            m = json.loads(self.ws.recv())
            self._event(m)
            if m.get("id") == self.n:
                if "error" in m:
                    sys.exit("page.py: %s: %s" % (method, m["error"]))
                return m["result"]

    def open(self, url):
        self.call("Page.navigate", url=url)
        while not self.loaded:
            self._event(json.loads(self.ws.recv()))
        # two animation frames, for what the page draws after its load event
        self.eval("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")

    def eval(self, expr):
        r = self.call("Runtime.evaluate", expression=expr, awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in r:
            sys.exit("page.py: %s: %s" % (expr, r["exceptionDetails"]))
        return r["result"].get("value")

    def close(self, log):
        with open(log, "w") as f:
            f.writelines(line + "\n" for line in self.console)
        self.ws.close()
        urllib.request.urlopen(self.base + "/json/close/" + self.id, timeout=60).read()


def main(argv):
    if len(argv) == 2 and argv[0] == "start":
        start(argv[1])
    elif len(argv) == 5 and argv[0] == "shot":
        import base64
        tab = Tab(argv[1])
        tab.open(argv[2])
        png = tab.call("Page.captureScreenshot", format="png")["data"]
        with open(argv[3], "wb") as f:
            f.write(base64.b64decode(png))
        tab.close(argv[4])
    elif len(argv) == 4 and argv[0] == "dom":
        tab = Tab(argv[1])
        tab.open(argv[2])
        body = tab.eval("document.body.outerHTML.match(/^<body[^>]*>/)[0]")
        tab.close(argv[3])
        print(body)
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
