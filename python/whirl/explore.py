"""whirl explore: opens the live page, build/web/whirl-explore.html of `make web`, in the browser.

    python3 -m whirl.explore [PAGE] [--serve] [--port P] [--no-browser]

The page is one self-contained file: libwhirl compiled to WebAssembly runs inside it, in a
Worker, so every number on it is the library's and nothing is computed here. By default the
file itself is opened (file://: no server at all). --serve serves it instead on this machine
only, for a browser that cannot read local files (a confined one): a static server on
127.0.0.1 (the first free port from P, default 8470; printed on start) that answers GET and
HEAD of the page alone and obeys nothing else: no other path, no other method, and no request
whose Host names another host (DNS rebinding). Ctrl-C stops it.

The page is looked for, in this order:
  1. PAGE, or the file named by the environment variable WHIRL_EXPLORE_PAGE (either: that file
     or none);
  2. whirl-explore.html inside the package (a wheel or `make python` after `make web` carries
     it);
  3. build/web/whirl-explore.html of the source tree the package sits in (python/whirl ->
     ../../build/web), the page `make web` just wrote.
Without one, a line says to run `make web` and the exit status is 1.

This file uses the standard library only: `make explore` runs it as a script, without the
package (and so without libwhirl or numpy)."""
import argparse
import http.server
import os
import sys
import webbrowser
from typing import Any, List, Optional

PAGE_NAME = "whirl-explore.html"
HERE = os.path.dirname(os.path.abspath(__file__))
PORT = 8470
PORTS_TRIED = 50     # --serve takes the first free port of P .. P + PORTS_TRIED - 1
CLIENT_SECONDS = 10  # a client slower than this to send its request is dropped
PAGE_BYTES_MAX = 64 << 20  # a file larger than this is not the page


def candidates() -> List[str]:
    """The places the page is looked for (the rule above), first to last."""
    env = os.environ.get("WHIRL_EXPLORE_PAGE")
    if env:  # that file or nothing, as WHIRL_LIBRARY for the library
        return [env]
    return [
        os.path.join(HERE, PAGE_NAME),
        os.path.normpath(os.path.join(HERE, os.pardir, os.pardir, "build", "web", PAGE_NAME))]


def find_page(page: Optional[str] = None) -> str:
    """The path of the page to open; SystemExit with one line when there is none."""
    tried = [page] if page else candidates()
    for path in tried:
        if os.path.isfile(path):
            return os.path.abspath(path)
    raise SystemExit("whirl explore: no page (%s missing): run `make web` in the source tree, "
                     "which writes build/web/%s, or name the file" % (", ".join(tried), PAGE_NAME))


class PageServer(http.server.ThreadingHTTPServer):
    """Serves one file, read once, on 127.0.0.1."""

    daemon_threads = True
    allow_reuse_address = False  # a port another server holds is busy, not shared

    def __init__(self, port: int, body: bytes) -> None:
        self.body = body
        super().__init__(("127.0.0.1", port), PageHandler)


class PageHandler(http.server.BaseHTTPRequestHandler):
    server_version = "whirl-explore"
    timeout = CLIENT_SECONDS

    def log_message(self, fmt: str, *args: Any) -> None:  # quiet: the terminal shows the address
        pass

    def _answer(self, code: int, body: bytes, ctype: str = "text/plain; charset=utf-8",
                send_body: bool = True) -> None:
        self.send_response(code)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.send_header("X-Content-Type-Options", "nosniff")
        self.send_header("Referrer-Policy", "no-referrer")
        if code == 405:
            self.send_header("Allow", "GET, HEAD")
        self.end_headers()
        if send_body:
            self.wfile.write(body)

    def _host_ok(self) -> bool:
        host = (self.headers.get("Host") or "").strip().lower()
        name = host.rsplit(":", 1)[0] if not host.startswith("[") else host.split("]")[0] + "]"
        return name in ("127.0.0.1", "localhost")

    def _get(self, send_body: bool) -> None:
        if not self._host_ok():
            self._answer(403, b"only this machine's page is served here\n",
                         send_body=send_body)
            return
        path = self.path.split("?", 1)[0].split("#", 1)[0]
        if path not in ("/", "/" + PAGE_NAME):
            self._answer(404, b"this server serves the page alone: /\n",
                         send_body=send_body)
            return
        assert isinstance(self.server, PageServer)
        self._answer(200, self.server.body, "text/html; charset=utf-8", send_body)

    def do_GET(self) -> None:
        self._get(True)

    def do_HEAD(self) -> None:
        self._get(False)

    def _refuse(self) -> None:
        self._answer(405, b"the page is read, never written: GET or HEAD only\n")

    do_POST = do_PUT = do_DELETE = do_PATCH = do_OPTIONS = _refuse


def serve(page: str, port: int) -> PageServer:
    """A PageServer of the page on the first free port from port (0: any)."""
    size = os.path.getsize(page)
    if size > PAGE_BYTES_MAX:
        raise SystemExit("whirl explore: %s is %d bytes, not the page" % (page, size))
    with open(page, "rb") as f:
        body = f.read()
    last = None
    for p in ([0] if port == 0 else range(port, min(port + PORTS_TRIED, 65536))):
        try:
            return PageServer(p, body)
        except OSError as e:  # busy: the next one
            last = e
    raise SystemExit("whirl explore: no free port in %d..%d on 127.0.0.1 (%s)"
                     % (port, port + PORTS_TRIED - 1, last))


def main(argv: Optional[List[str]] = None) -> int:
    ap = argparse.ArgumentParser(prog="whirl explore", description=__doc__.split("\n\n")[0])
    ap.add_argument("page", nargs="?", help="the page (default: the rule in the module's help)")
    ap.add_argument("--serve", action="store_true",
                    help="serve the page on 127.0.0.1 instead of opening the file")
    ap.add_argument("--port", type=int, default=PORT,
                    help="with --serve: the first port tried (default %d; 0: any)" % PORT)
    ap.add_argument("--no-browser", action="store_true",
                    help="print the address without opening a browser")
    a = ap.parse_args(argv)
    if not 0 <= a.port <= 65535:
        ap.error("--port must be in 0..65535, got %d" % a.port)
    page = find_page(a.page)
    if not a.serve:
        url = "file://" + page
        print("whirl explore: %s" % url, flush=True)
        if not a.no_browser and not webbrowser.open(url):
            print("whirl explore: no browser found: open the address above", file=sys.stderr)
        return 0
    server = serve(page, a.port)
    url = "http://127.0.0.1:%d/" % server.server_address[1]
    print("whirl explore: %s (Ctrl-C stops it)" % url, flush=True)
    if not a.no_browser and not webbrowser.open(url):
        print("whirl explore: no browser found: open the address above", file=sys.stderr)
    try:
        server.serve_forever(poll_interval=0.2)
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
