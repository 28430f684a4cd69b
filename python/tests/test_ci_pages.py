"""The pages a CI run leaves, opened in headless Chromium (scripts/pagecheck.py):
the pytest plugin's session page, a passing and a failing check's page and
the compare page of a regression.

Each must: carry the report's stylesheet (the extension's REPORT_CSS, the
one the report inlines); show every image (each <img> and each linked .svg
decodes, naturalWidth > 0; each inline chart is drawn); fit a 1,280-pixel
window (scrollWidth <= 1280); print figures with their meaningful digits
(no decimal with 7 or more fractional digits in the text); colour its
verdicts; link its machine-readable files (which exist). The session page
leads with its chart, the failed check marked; the compare page with the
figures that moved. A full-page screenshot of each goes to
target/test-output/pages/.

Chromium is Debian's package (scripts/chromium.sh); without it these tests
skip, unless SPLINELAB_REQUIRE_CHROMIUM=1 (scripts/test.sh sets it), where
they fail.
"""

import json
import os
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest

import splinelab
from splinelab import _splinelab

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHOTS = ROOT / "target" / "test-output" / "pages"
sys.path.insert(0, str(ROOT / "scripts"))
import pagecheck  # noqa: E402

SAMPLES = np.array([1.0, 2.0, 0.5, 3.0, 1.0, 0.0, 2.0, 1.0, 4.0, 2.5, -1.0, 0.25])
K = 8
FAIL_BG, PASS_BG = "rgb(248, 207, 207)", "rgb(215, 240, 215)"

TESTS = """
import numpy as np
from splinelab.testing import assert_check

def test_filter():
    assert_check("prefilter", samples=np.load("s.npy"), coeffs=np.load("c.npy"), degree=3)

def test_second():
    assert_check("prefilter", samples=np.load("s.npy"), coeffs=np.load("ref.npy"), degree=3)

def test_big():
    x = np.linspace(-1.0, 1.0, 400) ** 3
    assert_check("prefilter", samples=x, coeffs=np.load("big.npy"), degree=5)
"""


@pytest.fixture(scope="module")
def browser():
    if pagecheck.find_chromium() is None:
        if os.environ.get("SPLINELAB_REQUIRE_CHROMIUM") == "1":
            pytest.fail("no Chromium: run scripts/chromium.sh")
        pytest.skip("no Chromium (scripts/chromium.sh installs Debian's)")
    with pagecheck.Browser() as b:
        yield b


def session(folder, coeffs, out):
    """A pytest session of three checks (the first on `coeffs`) recorded into `out`."""
    folder.mkdir(parents=True, exist_ok=True)
    np.save(folder / "s.npy", SAMPLES)
    np.save(folder / "c.npy", coeffs)
    np.save(folder / "ref.npy", splinelab.spline_filter1d(SAMPLES, order=3, mode="mirror"))
    np.save(folder / "big.npy", splinelab.spline_filter1d(np.linspace(-1.0, 1.0, 400) ** 3, order=5, mode="mirror"))
    (folder / "test_pages.py").write_text(TESTS)
    subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "test_pages.py",
                    "--splinelab-report", str(out)], cwd=folder, capture_output=True, text=True)
    return out


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    """The session page of a run with one failed check, a passing and a
    failing check's page, and the compare page against a clean run."""
    tmp = tmp_path_factory.mktemp("pages")
    good = splinelab.spline_filter1d(SAMPLES, order=3, mode="mirror")
    splinelab.check("prefilter", samples=SAMPLES, coeffs=good, degree=3, out=tmp / "ref")
    ref, bound = np.load(tmp / "ref" / "reference.npy"), np.load(tmp / "ref" / "bound.npy")
    bad = ref.copy()
    bad[5] = ref[5] + 2 * K * bound[5]
    clean = session(tmp / "a", good, tmp / "clean")
    failing = session(tmp / "b", bad, tmp / "failing")
    subprocess.run([sys.executable, "-m", "splinelab", "compare", "--baseline", str(clean / "summary.json"),
                    "--current", str(failing / "summary.json"), "--out", str(tmp / "compare")],
                   capture_output=True, text=True)
    return {
        "session": failing / "index.html",
        "check_pass": failing / "checks" / "test_pages_py_test_second" / "index.html",
        "check_fail": failing / "checks" / "test_pages_py_test_filter" / "index.html",
        "compare": tmp / "compare" / "index.html",
    }


def opened(browser, pages, name):
    SHOTS.mkdir(parents=True, exist_ok=True)
    shot = SHOTS / f"{name}.png"
    shot.unlink(missing_ok=True)
    r = browser.check(pages[name], screenshot=shot, width=1280)
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and shot.stat().st_size > 10_000
    r["links"] = browser.evaluate("[...document.querySelectorAll('a[href]')].map((a) => a.getAttribute('href'))")
    r["html"] = pages[name].read_text(encoding="utf-8")
    return r


def background(browser, selector):
    return browser.evaluate(f"getComputedStyle(document.querySelector({json.dumps(selector)})).backgroundColor")


@pytest.mark.parametrize("name", ["session", "check_pass", "check_fail", "compare"])
def test_every_page_shows_its_images_fits_the_window_and_shares_the_style(browser, pages, name):
    r = opened(browser, pages, name)
    assert r["ok"], r["problems"]
    assert r["inline_svgs"], "a chart on every page"
    assert all(i["natural_width"] > 0 for i in r["images"] + r["linked_svgs"])
    assert r["scroll_width"] <= 1280
    assert f"<style>{_splinelab.REPORT_CSS}</style>" in r["html"]
    assert "Provenance" in r["text"] and "git commit" in r["text"]
    long = re.findall(r"\b\d+\.\d{7,}\b", r["text"])
    assert long == [], f"figures printed with more digits than they mean: {long}"
    for href in r["links"]:
        if not href.startswith(("#", "http")):
            assert (pages[name].parent / href).is_file(), href


def test_the_session_page_leads_with_the_chart_and_marks_the_failure(browser, pages):
    r = opened(browser, pages, "session")
    html = r["html"]
    assert html.index("<figure>") < html.index("<table"), "the chart comes before the table"
    assert "FAILED #2 test_pages_py_test_filter" in html  # the failed check's own legend entry
    assert background(browser, "p.fail") == FAIL_BG and "3 checks, 1 failed" in r["text"]
    assert background(browser, "span.verdict.pass") == PASS_BG
    assert "summary.json" in r["links"]
    assert "checks/test_pages_py_test_big/summary.json" in r["links"]
    assert "checks/test_pages_py_test_filter/index.html" in r["links"]


def test_check_pages_colour_their_verdict_and_link_their_data(browser, pages):
    r = opened(browser, pages, "check_fail")
    assert background(browser, "p.fail") == FAIL_BG and "check prefilter: fail" in r["text"]
    assert {"summary.json", "reference.npy", "error.npy", "bound.npy"} <= set(r["links"])
    r = opened(browser, pages, "check_pass")
    assert background(browser, "p.pass") == PASS_BG and "check prefilter: pass" in r["text"]


def test_the_compare_page_leads_with_the_figures_that_moved(browser, pages):
    r = opened(browser, pages, "compare")
    html = r["html"]
    moved = html.index("Figures that moved")
    assert moved < html.index("<figure>") and moved < html.index("Every figure")
    first_table = html[moved:html.index("</table>", moved)]
    assert "test_pages_py_test_filter.check.prefilter.worst_excess" in first_table
    assert "test_pages_py_test_second" not in first_table, "only the figures that moved"
    assert background(browser, "span.verdict.fail") == FAIL_BG
    assert "compare.json" in r["links"]
