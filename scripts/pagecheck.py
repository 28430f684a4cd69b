"""Opens HTML pages in headless Chromium and checks what a reader would see.

For any page the project writes: the report, a check's, compare's and the
pytest plugin's session page, the documentation site. Standard library only.

Command line::

    python3 scripts/pagecheck.py [--width 1280] [--height 900] [--screenshots DIR] PAGE...

opens each PAGE (a file path or a URL), prints one JSON object per page
(the fields of ``check`` below, less ``text``) and exits 1 when a page has a
problem, 2 when Chromium cannot be started.

From Python (``sys.path.insert(0, "scripts")``; ``import pagecheck``)::

    with pagecheck.Browser() as b:
        r = b.check("target/report/index.html", screenshot="out/report.png", width=1280)
        assert r["ok"], r["problems"]
        b.evaluate("document.title")         # any expression, on the page last opened

``Browser.check(page, screenshot=None, width=1280, height=900)`` returns a
dict: ``url``; ``title``; ``scroll_width`` (the document's, in CSS pixels);
``images`` (each ``<img>``: ``src``, ``natural_width`` after decoding);
``linked_svgs`` (each ``<a href="....svg">`` loaded as an image: ``src``,
``natural_width``); ``inline_svgs`` (each top-level ``<svg>``'s drawn
``width``, ``height``); ``text`` (the body's ``innerText``); ``problems``
(one sentence each: an image that does not decode, an inline SVG drawn
empty, a page wider than ``width``) and ``ok`` (no problem). With
``screenshot`` a full-page PNG is written there.

Chromium: ``$CHROMIUM``, else ``chromium`` or ``chromium-browser`` on PATH
(Debian's package; ``scripts/chromium.sh`` installs it). It runs with
``--headless --no-sandbox --disable-gpu --no-first-run
--disable-background-networking --disable-component-update --disable-sync``
and a fresh ``--user-data-dir``, and is driven with the DevTools protocol
over ``--remote-debugging-pipe`` (NUL-separated JSON on file descriptors 3
and 4: no websocket library, no browser download). ``BrowserError`` when it
cannot start or does not answer within ``timeout`` seconds.
"""

from __future__ import annotations

import argparse
import base64
import fcntl
import json
import os
import pathlib
import select
import shutil
import signal
import sys
import tempfile
import time

FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--remote-debugging-pipe",
]

# Runs in the page: every <img> decoded, every linked .svg loaded as an
# image, the size of every top-level inline <svg>, the document's width.
PROBE = """(async () => {
  const load = (src) => new Promise((done) => {
    const im = new Image();
    im.onload = () => done({src, natural_width: im.naturalWidth});
    im.onerror = () => done({src, natural_width: 0});
    im.src = src;
  });
  const images = await Promise.all([...document.images].map(async (im) => {
    try { await im.decode(); } catch (e) {}
    return {src: im.currentSrc || im.src, natural_width: im.naturalWidth};
  }));
  const hrefs = [...new Set([...document.querySelectorAll('a[href]')]
    .map((a) => a.href).filter((h) => /\\.svg$/i.test(h.split(/[?#]/)[0])))];
  const linked_svgs = await Promise.all(hrefs.map(load));
  const inline_svgs = [...document.querySelectorAll('svg')]
    .filter((s) => !s.parentElement.closest('svg'))
    .map((s) => { const r = s.getBoundingClientRect(); return {width: r.width, height: r.height}; });
  return {title: document.title, scroll_width: document.documentElement.scrollWidth,
          images, linked_svgs, inline_svgs, text: document.body ? document.body.innerText : ''};
})()"""


class BrowserError(RuntimeError):
    """Chromium could not be started, or did not answer in time."""


def find_chromium():
    """The Chromium executable: ``$CHROMIUM``, else one on PATH, else None."""
    for name in (os.environ.get("CHROMIUM"), "chromium", "chromium-browser"):
        path = name and shutil.which(name)
        if path:
            return path
    return None


def page_url(page):
    """A URL for a file path (made absolute) or a URL (unchanged)."""
    if "://" in str(page) or str(page).startswith(("about:", "data:")):
        return str(page)
    return pathlib.Path(page).resolve().as_uri()


def _high_fd(fd):
    """``fd`` moved to a number >= 10, close-on-exec (so that the child's
    dup2 onto 3 and 4 never meets one of them)."""
    new = fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 10)
    os.close(fd)
    return new


def problems_of(r, width):
    """The sentences ``check`` reports for the probe's result ``r``."""
    out = [f"image does not decode: {i['src']}" for i in r["images"] if i["natural_width"] <= 0]
    out += [f"linked SVG does not decode: {i['src']}" for i in r["linked_svgs"] if i["natural_width"] <= 0]
    out += [f"inline SVG #{k} drawn empty" for k, s in enumerate(r["inline_svgs"]) if s["width"] <= 0]
    if r["scroll_width"] > width:
        out.append(f"page is {r['scroll_width']} px wide in a {width} px window")
    return out


class Browser:
    """One headless Chromium, driven over the DevTools pipe (a context manager)."""

    def __init__(self, executable=None, timeout=60.0):
        self.executable = executable or find_chromium()
        if not self.executable:
            raise BrowserError("no Chromium: run scripts/chromium.sh, or set CHROMIUM=/path/to/chromium")
        self.timeout = timeout
        self.pid = None
        self.session = None
        self._next = 0
        self._buf = b""
        self._events = []

    def __enter__(self):
        self.start()
        return self

    def __exit__(self, *exc):
        self.close()

    def start(self):
        self.profile = tempfile.mkdtemp(prefix="pagecheck-profile-")
        self.log = os.path.join(self.profile, "chromium.log")
        to_child, self._out = (_high_fd(fd) for fd in os.pipe())  # we write, Chromium reads fd 3
        self._in, from_child = (_high_fd(fd) for fd in os.pipe())  # Chromium writes fd 4, we read
        argv = [self.executable, *FLAGS, f"--user-data-dir={self.profile}", "about:blank"]
        actions = [
            (os.POSIX_SPAWN_DUP2, to_child, 3),
            (os.POSIX_SPAWN_DUP2, from_child, 4),
            (os.POSIX_SPAWN_OPEN, 0, os.devnull, os.O_RDONLY, 0),
            (os.POSIX_SPAWN_OPEN, 1, self.log, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644),
            (os.POSIX_SPAWN_DUP2, 1, 2),
        ]
        try:
            self.pid = os.posix_spawn(self.executable, argv, os.environ, file_actions=actions, setsid=True)
        finally:
            os.close(to_child)
            os.close(from_child)
        target = self.call("Target.createTarget", url="about:blank")["targetId"]
        self.session = self.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        self.call("Page.enable")
        self.call("Runtime.enable")

    def close(self):
        """Closes the browser (killing its process group if it does not
        exit within 10 s) and removes its profile."""
        if self.pid is None:
            return
        try:
            self._send("Browser.close", {}, None)
        except OSError:
            pass
        deadline = time.monotonic() + 10
        exited = False
        while not exited and time.monotonic() < deadline:
            exited = os.waitpid(self.pid, os.WNOHANG) != (0, 0)
            time.sleep(0 if exited else 0.05)
        if not exited:
            os.killpg(self.pid, signal.SIGKILL)
            os.waitpid(self.pid, 0)
        for fd in (self._in, self._out):
            os.close(fd)
        self.pid = None
        shutil.rmtree(self.profile, ignore_errors=True)

    def _send(self, method, params, session):
        self._next += 1
        msg = {"id": self._next, "method": method, "params": params}
        if session:
            msg["sessionId"] = session
        os.write(self._out, json.dumps(msg).encode() + b"\0")
        return self._next

    def _read(self, deadline):
        """The next message from Chromium (a response or an event)."""
        while b"\0" not in self._buf:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self._in], [], [], left)[0]:
                raise BrowserError(f"Chromium did not answer within {self.timeout} s (log: {self.log})")
            chunk = os.read(self._in, 1 << 20)
            if not chunk:
                raise BrowserError(f"Chromium closed the pipe (log: {self.log})")
            self._buf += chunk
        raw, self._buf = self._buf.split(b"\0", 1)
        return json.loads(raw)

    def call(self, method, **params):
        """Sends a DevTools command (to the page once attached) and returns its result."""
        session = self.session if not method.startswith(("Target.", "Browser.")) else None
        want = self._send(method, params, session)
        deadline = time.monotonic() + self.timeout
        while True:
            m = self._read(deadline)
            if m.get("id") == want:
                if "error" in m:
                    raise BrowserError(f"{method}: {m['error'].get('message')}")
                return m.get("result", {})
            if "method" in m:
                self._events.append(m)

    def _wait_event(self, name):
        deadline = time.monotonic() + self.timeout
        while True:
            for k, m in enumerate(self._events):
                if m["method"] == name:
                    return self._events.pop(k)
            self._events.append(self._read(deadline))

    def open(self, page, width=1280, height=900):
        """Loads ``page`` (a path or URL) in a ``width`` × ``height`` window."""
        self.call("Emulation.setDeviceMetricsOverride", width=width, height=height,
                  deviceScaleFactor=1, mobile=False)
        self._events = [m for m in self._events if m["method"] != "Page.loadEventFired"]
        r = self.call("Page.navigate", url=page_url(page))
        if r.get("errorText"):
            raise BrowserError(f"cannot open {page}: {r['errorText']}")
        self._wait_event("Page.loadEventFired")

    def evaluate(self, expression):
        """The value of a JavaScript expression (promises awaited) on the open page."""
        r = self.call("Runtime.evaluate", expression=expression, awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in r:
            raise BrowserError(f"script failed: {r['exceptionDetails'].get('text')}")
        return r["result"].get("value")

    def screenshot(self, path):
        """Writes a PNG of the whole open page (at most 16,000 px tall) to ``path``."""
        size = self.call("Page.getLayoutMetrics")["cssContentSize"]
        clip = {"x": 0, "y": 0, "width": size["width"], "height": min(size["height"], 16000), "scale": 1}
        data = self.call("Page.captureScreenshot", format="png", captureBeyondViewport=True, clip=clip)["data"]
        path = pathlib.Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(base64.b64decode(data))

    def check(self, page, screenshot=None, width=1280, height=900):
        """Opens ``page`` and reports what a reader sees (see the module doc)."""
        self.open(page, width, height)
        r = self.evaluate(PROBE)
        r["url"] = page_url(page)
        r["problems"] = problems_of(r, width)
        r["ok"] = not r["problems"]
        if screenshot is not None:
            self.screenshot(screenshot)
            r["screenshot"] = str(screenshot)
        return r


def main(argv=None):
    p = argparse.ArgumentParser(description="Open pages in headless Chromium and check them.")
    p.add_argument("pages", nargs="+", help="file paths or URLs")
    p.add_argument("--width", type=int, default=1280)
    p.add_argument("--height", type=int, default=900)
    p.add_argument("--screenshots", metavar="DIR", help="write a full-page PNG of each page here")
    a = p.parse_args(argv)
    bad = 0
    try:
        with Browser() as b:
            for k, page in enumerate(a.pages):
                shot = None
                if a.screenshots:
                    shot = pathlib.Path(a.screenshots) / f"{k:02d}-{pathlib.Path(str(page)).stem}.png"
                r = b.check(page, shot, a.width, a.height)
                r.pop("text")
                print(json.dumps(r))
                bad += not r["ok"]
    except BrowserError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
