#!/usr/bin/env python3
"""Every local link of a built HTML site must resolve.

Usage: check_links.py SITE_DIR

Reads every ``.html`` file under SITE_DIR and checks each ``href`` and ``src``
that is not an external address (a scheme such as ``https:``, ``mailto:``,
``data:``, ``javascript:``, or ``//``): the file it names must exist (a folder
must hold an ``index.html``), and where the link has a ``#fragment`` into one
of the site's own HTML pages, that page must have an element with that ``id``
(or a ``name``). Fragments into the Rust API (rustdoc builds some of its
anchors with JavaScript) are checked for the file only. Exit status 0 when
every link resolves, 1 otherwise (each broken link printed with the page it is
on), 2 on a bad argument.
"""

from __future__ import annotations

import html.parser
import pathlib
import sys
import urllib.parse

EXTERNAL = ("http:", "https:", "mailto:", "data:", "javascript:", "ftp:", "//", "tel:")
# Folders whose in-page anchors are made by their own scripts at load time.
FRAGMENTS_UNCHECKED = ("rust/",)


class _Page(html.parser.HTMLParser):
    """The links and the anchors (ids, names) of one page."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.links: list[str] = []
        self.anchors: set[str] = set()

    def handle_starttag(self, tag, attrs):
        for key, value in attrs:
            if value is None:
                continue
            if key in ("href", "src") and not (tag == "link" and ("rel", "preconnect") in attrs):
                self.links.append(value)
            elif key in ("id", "name"):
                self.anchors.add(value)


def parse(path: pathlib.Path) -> _Page:
    page = _Page()
    page.feed(path.read_text(encoding="utf-8", errors="replace"))
    return page


def _optional_rustdoc_script(site: pathlib.Path, target: pathlib.Path) -> bool:
    """rustdoc links every trait's and type's page to a script of the
    implementations other crates add (``trait.impl/…/trait.X.js``), loaded
    asynchronously, and writes that script only where some crate does: its
    absence means "no implementations elsewhere", not a broken page."""
    rel = target.relative_to(site).parts
    return len(rel) > 2 and rel[0] == "rust" and rel[1] in ("trait.impl", "type.impl") and target.suffix == ".js"


def broken_links(site: pathlib.Path) -> tuple[int, list[str]]:
    """(links checked, one line per broken link)."""
    site = site.resolve()
    # _static/ holds the theme's template fragments, not pages.
    pages = {p: parse(p) for p in sorted(site.rglob("*.html")) if not p.relative_to(site).parts[0] == "_static"}
    problems, checked = [], 0
    for page_path, page in pages.items():
        for link in page.links:
            if link.startswith(EXTERNAL) or link.startswith("#") and not link[1:]:
                continue
            checked += 1
            parts = urllib.parse.urlsplit(link)
            if parts.scheme:
                continue
            target = page_path if not parts.path else (page_path.parent / urllib.parse.unquote(parts.path))
            target = target.resolve()
            where = f"{page_path.relative_to(site)}: {link}"
            if not target.is_relative_to(site):
                problems.append(f"{where} (outside the site)")
                continue
            if target.is_dir():
                target = target / "index.html"
            if not target.exists():
                if _optional_rustdoc_script(site, target):
                    continue
                problems.append(f"{where} (no such file)")
                continue
            fragment = urllib.parse.unquote(parts.fragment)
            rel = str(target.relative_to(site))
            if fragment and target.suffix == ".html" and not rel.startswith(FRAGMENTS_UNCHECKED):
                anchors = pages[target].anchors if target in pages else parse(target).anchors
                if fragment not in anchors:
                    problems.append(f"{where} (no anchor #{fragment})")
    return checked, problems


def main(argv: list[str]) -> int:
    if len(argv) != 1 or not pathlib.Path(argv[0]).is_dir():
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    checked, problems = broken_links(pathlib.Path(argv[0]))
    for line in problems:
        print(f"broken link: {line}")
    print(f"check_links: {checked} local links, {len(problems)} broken")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
