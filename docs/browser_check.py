#!/usr/bin/env python3
"""Opens the built documentation site and the report in headless Chromium.

Interface (small on purpose; scripts/chromium.sh installs the browser):

- ``Browser()`` (a context manager): headless Chromium through Debian's
  chromedriver (``CHROMIUM``/``CHROMEDRIVER`` override the paths), 1280 × 900.
- ``Browser.open(url) -> Page``: loads ``url`` and returns ``Page(url,
  console_errors, broken_images, scroll_width, client_width)``: the console
  messages of level SEVERE (JavaScript errors, failed loads), the ``src`` of
  every ``<img>`` whose ``naturalWidth`` is 0 once loading settled (lazy images
  are made eager first), and the document's ``scrollWidth`` and
  ``clientWidth`` (a page wider than the window scrolls sideways).
- ``Browser.screenshot(url, path)``: a PNG of the page as a reader sees it.
- ``Browser.search(site_url, name) -> list[str]``: the links Sphinx's own
  search page lists for ``name``.
- ``serve(folder)``: a context manager serving ``folder`` over HTTP on
  127.0.0.1 (a free port) and giving its base URL, so pages load as from a
  web server (no file:// restrictions).

Command line: ``browser_check.py --site DIR [--shots DIR]`` opens every page
of the Sphinx site under DIR (not each of the rustdoc's thousands: the crate
roots stand for them), the report at ``DIR/report/index.html``, and fails
(exit 1, every problem printed) on a console error, an image that does not
decode, a page that scrolls sideways, or a public function of ``splinelab``,
``splinelab.dask`` or ``splinelab.testing`` that the search does not find;
screenshots of the landing page, the gallery and the ``map_coordinates`` API
page go to ``--shots``.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import functools
import http.server
import os
import pathlib
import sys
import threading
import time
import urllib.parse


@dataclasses.dataclass
class Page:
    """What one page load showed."""

    url: str
    console_errors: list[str]
    broken_images: list[str]
    scroll_width: int
    client_width: int


@contextlib.contextmanager
def serve(folder):
    """Serves ``folder`` on 127.0.0.1 (a free port); yields the base URL."""

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    handler = functools.partial(Quiet, directory=str(folder))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()


_IMAGES_SETTLED = """
const done = arguments[arguments.length - 1];
const images = [...document.images];
images.forEach(i => { i.loading = 'eager'; });
const start = Date.now();
(function wait() {
  if (images.every(i => i.complete) || Date.now() - start > 8000) {
    done(images.filter(i => !i.complete || i.naturalWidth === 0).map(i => i.currentSrc || i.src));
  } else { setTimeout(wait, 50); }
})();
"""


class Browser:
    """Headless Chromium driven through chromedriver (selenium)."""

    def __init__(self, width=1280, height=900):
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service

        options = webdriver.ChromeOptions()
        options.binary_location = os.environ.get("CHROMIUM", "/usr/bin/chromium")
        for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     f"--window-size={width},{height}", "--hide-scrollbars"):
            options.add_argument(flag)
        options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
        service = Service(executable_path=os.environ.get("CHROMEDRIVER", "/usr/bin/chromedriver"))
        self.driver = webdriver.Chrome(service=service, options=options)
        self.driver.set_script_timeout(15)
        self.driver.set_page_load_timeout(30)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.driver.quit()

    def open(self, url) -> Page:
        d = self.driver
        d.get_log("browser")  # drop what an earlier page left
        d.get(url)
        broken = d.execute_async_script(_IMAGES_SETTLED)
        widths = d.execute_script(
            "return [document.documentElement.scrollWidth, document.documentElement.clientWidth]"
        )
        errors = [e["message"] for e in d.get_log("browser") if e["level"] == "SEVERE"]
        return Page(url, errors, broken, widths[0], widths[1])

    def screenshot(self, url, path):
        self.driver.get(url)
        self.driver.execute_async_script(_IMAGES_SETTLED)
        pathlib.Path(path).parent.mkdir(parents=True, exist_ok=True)
        self.driver.save_screenshot(str(path))

    def search(self, site_url, name, timeout=15.0) -> list[str]:
        """The result links of Sphinx's search page for ``name``."""
        d = self.driver
        d.get(urllib.parse.urljoin(site_url, "search.html") + "?q=" + urllib.parse.quote(name))
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            # Sphinx's searchtools.js writes its status line when it is done.
            finished = d.execute_script(
                "return typeof Search !== 'undefined' && Search.status !== undefined && Search.status !== null"
                " && /Search finished|did not match/.test(Search.status.innerText);"
            )
            if finished:
                break
            time.sleep(0.1)
        return d.execute_script(
            "return [...document.querySelectorAll('#search-results a')].map(a => a.getAttribute('href'))"
        )


def public_functions():
    """Every public function of the three modules, as ``(qualified name, page)``."""
    import splinelab
    import splinelab.dask
    import splinelab.testing

    names = []
    for module in (splinelab, splinelab.dask, splinelab.testing):
        for name in module.__all__:
            if callable(getattr(module, name)):
                names.append((f"{module.__name__}.{name}", name))
    return names


def site_pages(site: pathlib.Path):
    """The Sphinx pages (not _static's templates, the rustdoc or the report)."""
    skip = ("_static", "_sources", "_images", "rust", "report", "man", "_screenshots", "_downloads")
    pages = [p for p in sorted(site.rglob("*.html")) if p.relative_to(site).parts[0] not in skip]
    roots = sorted((site / "rust").glob("*/index.html"))
    return pages + roots + [site / "report" / "index.html"]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--site", required=True, type=pathlib.Path)
    ap.add_argument("--shots", type=pathlib.Path)
    a = ap.parse_args(argv)
    site = a.site.resolve()
    problems = []
    started = time.monotonic()
    with serve(site) as base, Browser() as browser:
        pages = site_pages(site)
        for path in pages:
            rel = path.relative_to(site).as_posix()
            page = browser.open(base + rel)
            problems += [f"{rel}: console: {m}" for m in page.console_errors]
            problems += [f"{rel}: image does not decode: {s}" for s in page.broken_images]
            if page.scroll_width > page.client_width + 1:
                problems.append(f"{rel}: scrolls sideways ({page.scroll_width} > {page.client_width} px)")
        functions = public_functions()
        for qualified, name in functions:
            links = browser.search(base, name)
            if not any(f"generated/{qualified}.html" in (link or "") for link in links):
                problems.append(f"search for {name!r} does not list {qualified} ({len(links)} results)")
        if a.shots:
            for rel, shot in (("index.html", "landing.png"), ("auto_examples/index.html", "gallery.png"),
                              ("api/generated/splinelab.map_coordinates.html", "api_map_coordinates.png")):
                browser.screenshot(base + rel, a.shots / shot)
    for p in problems:
        print(f"browser check: {p}")
    print(f"browser check: {len(pages)} pages, {len(functions)} functions searched, {len(problems)} problems "
          f"({time.monotonic() - started:.0f} s, {Browser.__module__} on Chromium)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
