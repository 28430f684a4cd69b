"""check(kind, ...) returns the command line's --json object."""

import decimal
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import splinelab

ROOT = pathlib.Path(__file__).resolve().parents[2]
FIX = ROOT / "verify" / "fixtures" / "scipy"


def cli():
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    exe = target / "release" / "splinelab"
    if not exe.exists():
        pytest.skip(f"{exe} not built")
    return exe


def run_cli(*args):
    r = subprocess.run([str(cli()), "check", *args, "--json"], capture_output=True, text=True, cwd=FIX)
    assert r.returncode in (0, 1), r.stderr
    return json.loads(r.stdout)


@pytest.mark.parametrize("name, d, mode", [("d3_mirror", 3, "mirror"), ("d5_reflect", 5, "reflect")])
def test_prefilter_json_equals_cli(name, d, mode):
    path = FIX / "prefilter" / f"{name}.npy"
    if not path.exists():
        pytest.skip(f"no fixture {path.name}")
    s = np.load(FIX / "prefilter" / "samples.npy")
    ours = splinelab.check("prefilter", samples=s, coeffs=np.load(path), degree=d, mode=mode, max_ulps=4)
    theirs = run_cli("prefilter", "--samples", "prefilter/samples.npy", "--coeffs", f"prefilter/{name}.npy",
                     "--degree", str(d), "--mode", mode, "--max-ulps", "4")
    assert ours == theirs


def test_knot_insertion_json_equals_cli_and_finds_scipys_defect():
    case = json.loads((FIX / "knot_insertion.json").read_text())["cases"]["right_end_3"]
    spline = lambda s: (s["t"], s["c"], s["k"])  # noqa: E731
    ours = splinelab.check("knot-insertion", before=spline(case["before"]), after=spline(case["after"]))
    assert ours == run_cli("knot-insertion", "--input", "knot_insertion.json", "--case", "right_end_3")
    assert ours["verdict"] == "fail" and ours["max_deviation"] > 0.4


def closed_form_cubic(count):
    """c_i = sqrt(3) (sqrt(3) - 2)^i in 60-digit decimal, rounded to float64."""
    decimal.getcontext().prec = 60
    r3 = decimal.Decimal(3).sqrt()
    return np.array([float(r3 * (r3 - 2) ** i) for i in range(count)])


def test_coeffs_against_closed_form():
    user = closed_form_cubic(12)
    r = splinelab.check("coeffs", values=user, degree=3)
    assert r["kind"] == "coeffs" and r["n"] == 12 and r["worst"]["ulps"] <= 0.5
    # The production table is correctly rounded: equal to the closed form.
    np.testing.assert_array_equal(splinelab.coefficients(degree=3, count=12), user)


def test_f32_values_are_judged_in_f32_ulps():
    s = np.random.default_rng(2).uniform(-1, 1, 50)
    c32 = splinelab.spline_filter1d(s.astype(np.float32), output=np.float32)
    r = splinelab.check("prefilter", samples=s.astype(np.float32), coeffs=c32, max_ulps=16)
    assert r["format"] == "f32" and r["verdict"] == "pass"
    r64 = splinelab.check("prefilter", samples=s.astype(np.float32), coeffs=c32, format="f64")
    assert r64["worst"]["ulps"] > 1e6  # the same numbers in f64 ulps


def test_bezier_and_bspline_eval():
    b = np.array([1.0, -2.0, 3.0, 0.5])
    t = np.linspace(0, 1, 9)
    bern = lambda t: sum(b[i] * [1, 3, 3, 1][i] * t**i * (1 - t) ** (3 - i) for i in range(4))  # noqa: E731
    assert splinelab.check("bezier-eval", coeffs=b, t=t, values=bern(t), max_ulps=8)["verdict"] == "pass"
    knots = np.array([0, 0, 0, 0, 1, 2, 3, 3, 3, 3], float)
    # Coefficients at the Greville abscissae reproduce f(x) = x (closed form).
    c = np.array([knots[j + 1 : j + 4].sum() / 3 for j in range(6)])
    x = np.linspace(0, 3, 7)
    r = splinelab.check("bspline-eval", knots=knots, coeffs=c, degree=3, x=x, values=x, max_ulps=64)
    assert r["kind"] == "bspline-eval" and r["n"] == 7 and r["verdict"] == "pass"


def test_truncation_width_matches_closed_form():
    # Cubic: uniform tail bound 2 sqrt(3) rho^(n+1) / (1 - rho), rho = 2 - sqrt(3)
    # (60-digit decimal); the bound is it rounded up.
    w = splinelab.truncation_width(degree=3, tol=1e-10)
    decimal.getcontext().prec = 60
    r3 = decimal.Decimal(3).sqrt()
    rho = 2 - r3
    tail = lambda n: 2 * r3 * rho ** (n + 1) / (1 - rho)  # noqa: E731
    assert tail(w["n"]) < decimal.Decimal("1e-10") <= tail(w["n"] - 1)
    assert tail(w["n"]) <= decimal.Decimal(w["bound"]) <= tail(w["n"]) * (1 + decimal.Decimal(2.3e-16))
    assert w["order"] == 4 and w["criterion"] == "uniform"
    assert splinelab.truncation_width(order=4, tol=1e-10) == w


def test_coefficients_decimal_strings():
    c = splinelab.coefficients(degree=3, count=3, bits=200)
    # sqrt(3) to 80 digits (closed form, decimal module).
    decimal.getcontext().prec = 80
    r3 = decimal.Decimal(3).sqrt()
    assert abs(decimal.Decimal(c[0]) - r3) < decimal.Decimal("1e-59")
    assert abs(decimal.Decimal(c[2]) - r3 * (r3 - 2) ** 2) < decimal.Decimal("1e-59")


@pytest.mark.parametrize("dims, d, mode", [(1, 5, "reflect"), (2, 3, "grid-wrap")])
def test_interp_json_equals_cli(dims, d, mode):
    s = np.load(FIX / "interp" / f"samples{dims}.npy")
    c = np.load(FIX / "interp" / f"coords{dims}.npy")
    v = np.load(FIX / "interp" / f"v{dims}_d{d}_{mode}.npy")
    ours = splinelab.check("interp", samples=s, coordinates=c, values=v, degree=d, mode=mode, max_ulps=64)
    theirs = run_cli("interp", "--samples", f"interp/samples{dims}.npy", "--coords", f"interp/coords{dims}.npy",
                     "--values", f"interp/v{dims}_d{d}_{mode}.npy", "--degree", str(d), "--mode", mode,
                     "--max-ulps", "64")
    assert ours == theirs
    assert ours["kind"] == "interp" and ours["n"] == len(v)


def test_cond_against_closed_forms():
    # Bernstein on {0, ½, 1}: A = [[1,0,0],[¼,½,¼],[0,0,1]], cond_∞ = ‖A‖_∞‖A⁻¹‖_∞ = 1·3 exactly.
    r = splinelab.check("cond", nodes=[0.0, 0.5, 1.0], values=[3.0], basis="bernstein", norm="inf", max_ulps=0.5)
    assert r["verdict"] == "pass" and r["worst"]["ulps"] == 0.0
    # Monomial on {0, 1}: [[1,0],[1,1]], cond_∞ = 2·2 = 4; on {0, ½, 1}: ‖A‖_∞ = 3 and
    # A⁻¹ = [[1,0,0],[−3,4,−1],[2,−4,2]] (Lagrange), ‖A⁻¹‖_∞ = 8, so 24. A value 3 ulps off is found.
    off = np.nextafter(np.nextafter(np.nextafter(4.0, 5.0), 5.0), 5.0)
    r = splinelab.check("cond", nodes=[[0.0, 1.0], [0.0, 0.5, 1.0]], values=[off, 24.0],
                        basis="monomial", norm="inf", max_ulps=1)
    assert r["verdict"] == "fail" and r["worst"]["index"] == 0 and abs(r["worst"]["ulps"] - 3.0) < 1e-9


def test_interp_takes_cval_for_grid_constant():
    # scipy 1.17.1's map_coordinates with cval = 0.75 (committed fixture):
    # checked with that cval it passes; with scipy's default 0 it is far off.
    s = np.load(FIX / "interp" / "samples1.npy")
    c = np.load(FIX / "interp" / "coords1.npy")
    v = np.load(FIX / "interp" / "v1_d3_grid-constant_cval.npy")
    args = dict(samples=s, coordinates=c, values=v, degree=3, mode="grid-constant")
    right = splinelab.check("interp", cval=0.75, **args)
    # scipy's own error (its f64 x + 12): 4.6e-14 at worst.
    assert right["verdict"] == "pass" and right["worst"]["abs"] < 1e-12
    assert splinelab.check("interp", **args)["worst"]["abs"] > 1e-3


@pytest.mark.parametrize("n,d", [(5, 5), (8, 3), (12, 4)])
def test_default_verdict_judges_scipys_short_reflect_lines(n, d):
    # scipy's half-sample initialisation on short lines, computed live: up
    # to 1.17 it is wrong there (scipy gh-24550): fail without max_ulps, at
    # index 0; 1.18 fixed it: pass. The mirror rule on the same line passes.
    import scipy
    from scipy.ndimage import spline_filter1d

    s = np.random.default_rng(n).uniform(-1, 1, n)
    r = splinelab.check("prefilter", samples=s, coeffs=spline_filter1d(s, order=d, mode="reflect"), degree=d,
                        mode="reflect")
    if _scipy_before(scipy.__version__, (1, 18)):
        assert r["verdict"] == "fail" and r["verdict_basis"] == "stable-bound"
        assert r["worst_excess"]["index"] == 0 and r["digits_lost"] > 1.5
        assert r["over_bound"] >= 1 and r["bound_factor"] == 8.0
    else:
        assert r["verdict"] == "pass" and r["worst_excess"]["excess"] < 1.0
    ok = splinelab.check("prefilter", samples=s, coeffs=spline_filter1d(s, order=d, mode="mirror"), degree=d)
    assert ok["verdict"] == "pass" and ok["worst_excess"]["excess"] < 1.0


def _scipy_before(version, release):
    """Whether scipy ``version`` ("1.17.1", "1.18.0rc1") is older than ``release``."""
    return tuple(int(p) for p in version.split(".")[:2]) < release


def test_new_fields_equal_the_cli():
    r = splinelab.check("prefilter", samples=np.load(FIX / "stable" / "s_n8.npy"),
                        coeffs=np.load(FIX / "stable" / "d5_reflect_n8.npy"), degree=5, mode="reflect")
    c = run_cli("prefilter", "--samples", "stable/s_n8.npy", "--coeffs", "stable/d5_reflect_n8.npy", "--degree", "5",
                "--mode", "reflect")
    for key in ["verdict", "verdict_basis", "over_bound", "worst_excess", "digits_lost", "stable_bound",
                "no_verdict_reason", "bound_factor"]:
        assert r[key] == c[key], key
    cond = splinelab.check("cond", nodes=[[0, 1], [0, 0.5, 1]], values=[1.0, 3.0], norm="inf")
    assert cond["verdict_basis"] == "finite-only" and "no stable bound" in cond["no_verdict_reason"]


@pytest.mark.parametrize("mode", ["constant", "wrap", "nearest", "mirror", "grid-wrap", "grid-constant"])
def test_interp_3d_every_mode_against_live_scipy(mode):
    from scipy.ndimage import map_coordinates

    rng = np.random.default_rng(5)
    g = rng.uniform(-1, 1, (5, 40, 33))
    shape = np.array(g.shape, dtype=np.float64)[:, None]
    c = -1.5 + rng.uniform(0, 1, (3, 30)) * (shape + 2.0)
    v = map_coordinates(g, c, order=3, mode=mode)
    r = splinelab.check("interp", samples=g, coordinates=c, values=v, degree=3, mode=mode)
    # Axis 0 has 5 samples: scipy's mirror/wrap/constant filters are exact
    # there (the mirror rule), so the verdict is pass and scipy right to 12 digits.
    assert r["verdict"] == "pass", r["worst_excess"]
    assert r["digits_min"] > 12.0 and r["mode"] == mode


def _grid_case(seed=3):
    rng = np.random.default_rng(seed)
    g = [np.sort(rng.uniform(0, 1, n)) for n in (9, 8, 7)]
    v = rng.standard_normal((9, 8, 7))
    xi = np.column_stack([rng.uniform(a[0], a[-1], 40) for a in g])
    return g, v, xi


def test_grid_spline_judges_the_exact_spline_against_mpfr():
    """The exact spline (independently: make_interp_spline along each axis,
    then NdBSpline) passes; scipy's RegularGridInterpolator, whose gcrotmk
    solve stops at atol=1e-6, fails on a grid with close nodes."""
    from scipy.interpolate import NdBSpline, RegularGridInterpolator, make_interp_spline

    g, v, xi = _grid_case()
    c, knots = v, []
    for a in range(3):
        s = make_interp_spline(g[a], c, k=3, axis=a)
        c, knots = np.moveaxis(s.c, 0, a), knots + [s.t]
    exact = NdBSpline(tuple(knots), c, 3)(xi)
    r = splinelab.check("grid-spline", grid=g, samples=v, points=xi, values=exact, degree=3)
    assert (r["kind"], r["verdict"], r["verdict_basis"]) == ("grid-spline", "pass", "stable-bound")
    ours = splinelab.RegularGridInterpolator(g, v, method="cubic")(xi)
    assert splinelab.check("grid-spline", grid=g, samples=v, points=xi, values=ours)["verdict"] == "pass"
    theirs = RegularGridInterpolator(g, v, method="cubic")(xi)
    bad = splinelab.check("grid-spline", grid=g, samples=v, points=xi, values=theirs)
    assert bad["verdict"] == "fail" and bad["worst"]["abs"] > 1e-8


def test_grid_spline_descending_axes_and_bad_input():
    g, v, xi = _grid_case(4)
    ours = splinelab.RegularGridInterpolator(g, v, method="quintic")(xi)
    flipped = [g[0][::-1], g[1], g[2][::-1]]
    fv = v[::-1, :, ::-1]
    r = splinelab.check("grid-spline", grid=flipped, samples=fv, points=xi, values=ours, degree=5)
    assert r["verdict"] == "pass"
    with pytest.raises(ValueError, match="samples of shape"):
        splinelab.check("grid-spline", grid=g, samples=v[:-1], points=xi, values=ours)
    with pytest.raises(ValueError, match="degree"):
        splinelab.check("grid-spline", grid=g, samples=v, points=xi, values=ours, degree=2)
    with pytest.raises(ValueError, match="points must have shape"):
        splinelab.check("grid-spline", grid=g, samples=v, points=xi[:, :2], values=ours)
