"""splinelab against scipy.ndimage (degrees <= 5) and against check's MPFR
reference (higher degrees). scipy 1.17.1 is the peer (scripts/python.sh)."""

import numpy as np
import pytest
from scipy import ndimage

import splinelab

EPS = np.finfo(np.float64).eps
MODES = ["mirror", "reflect", "grid-wrap", "nearest", "grid-constant"]
# Every mode name scipy 1.17's spline filters and map_coordinates take.
FILTER_MODES = MODES + ["constant", "wrap", "grid-mirror"]
MAP_MODES = FILTER_MODES
# exact_edges=True has no scipy function: pad by 80 samples (rho^160 < 1e-58
# for quintics) the way the mode extends and filter as mirror, then crop: the
# exact spline of the extended signal (the recipe of
# verify/fixtures/scipy/make_fixtures.py).
PAD = 80


def rng(seed=7):
    return np.random.default_rng(seed)


def scipy_filter1d(x, d, axis, mode, exact_edges=False):
    if not (exact_edges and mode in ("nearest", "grid-constant")):
        return ndimage.spline_filter1d(x, d, axis=axis, mode=mode)
    axis %= x.ndim
    pad = [(PAD, PAD) if a == axis else (0, 0) for a in range(x.ndim)]
    q = np.pad(x, pad, mode="edge" if mode == "nearest" else "constant")
    c = ndimage.spline_filter1d(q, d, axis=axis, mode="mirror")
    return c[tuple(slice(PAD, -PAD) if a == axis else slice(None) for a in range(x.ndim))]


def scipy_filter(x, d, mode, exact_edges=False):
    for axis in range(x.ndim):
        x = scipy_filter1d(x, d, axis, mode, exact_edges)
    return x


def ulps_of_max(ours, ref):
    return np.abs(ours - ref).max() / (EPS * np.abs(ref).max())


@pytest.mark.parametrize("exact_edges", [False, True])
@pytest.mark.parametrize("mode", FILTER_MODES)
@pytest.mark.parametrize("d", [2, 3, 4, 5])
def test_filter1d_equals_scipy(d, mode, exact_edges):
    # Lines of >= 24 samples: scipy's reflect is wrong on shorter lines
    # (relative error ~ rho^(2 n), notes of issue 14); checked below by check.
    for shape, axis in [((37,), 0), ((24, 41), 0), ((24, 41), 1), ((30, 5, 26), -1)]:
        x = rng().uniform(-1, 1, shape)
        ours = splinelab.spline_filter1d(x, order=d, axis=axis, mode=mode, exact_edges=exact_edges)
        assert ulps_of_max(ours, scipy_filter1d(x, d, axis, mode, exact_edges)) <= 8, (shape, axis)


def test_filter_modes_are_scipys_rules_not_the_exact_extension():
    # scipy filters nearest with the reflect rule and grid-constant / wrap
    # with the mirror rule; the exact extensions differ at the ends by O(1).
    x = rng(2).uniform(-1, 1, 40)
    for mode, rule in [("nearest", "reflect"), ("grid-constant", "mirror"), ("wrap", "mirror"), ("constant", "mirror")]:
        np.testing.assert_array_equal(splinelab.spline_filter1d(x, 3, mode=mode), splinelab.spline_filter1d(x, 3, mode=rule))
    for mode in ("nearest", "grid-constant"):
        gap = np.abs(splinelab.spline_filter1d(x, 3, mode=mode, exact_edges=True) - ndimage.spline_filter1d(x, 3, mode=mode))
        assert gap.max() > 1e-3


@pytest.mark.parametrize("mode", FILTER_MODES)
@pytest.mark.parametrize("d", [2, 3, 5])
def test_spline_filter_equals_scipy(d, mode):
    for shape in [(33, 28), (25, 24, 26)]:
        x = rng(3).uniform(-1, 1, shape)
        for exact_edges in (False, True):
            ours = splinelab.spline_filter(x, order=d, mode=mode, exact_edges=exact_edges)
            assert ulps_of_max(ours, scipy_filter(x, d, mode, exact_edges)) <= 8 * len(shape), shape


@pytest.mark.parametrize("mode", ["mirror", "grid-wrap", "grid-constant", "nearest"])
def test_short_lines_equal_scipy(mode):
    # nearest is scipy's reflect rule, wrong on short lines: its exact
    # extension is compared (against the padded recipe) instead.
    for n in [1, 2, 3, 5, 9]:
        x = rng(n).uniform(-1, 1, n)
        exact = mode == "nearest"
        ours = splinelab.spline_filter1d(x, order=3, mode=mode, exact_edges=exact)
        assert ulps_of_max(ours, scipy_filter1d(x, 3, 0, mode, exact)) <= 8, n


@pytest.mark.parametrize("mode", MAP_MODES)
@pytest.mark.parametrize("d", [0, 1, 2, 3, 4, 5])
def test_map_coordinates_equals_scipy(d, mode):
    # scipy's own output (default exact_edges=False: scipy's 12-sample
    # padding for nearest / grid-constant), points inside, outside, on
    # half-integers and at the ends (where 'constant' switches to cval).
    x = rng(11).uniform(-1, 1, (26, 31))
    ends = np.array([[-1e-12, 0.0, 25.0, 25.0 + 1e-12, -0.5, 25.5], [0.0, -1e-12, 30.0, 30.0 + 1e-12, 30.5, -0.5]])
    pts = np.concatenate(
        [np.stack([rng(12).uniform(-3, 28, 400), rng(13).uniform(-3, 33, 400)]),
         np.round(np.stack([rng(14).uniform(-3, 28, 60), rng(15).uniform(-3, 33, 60)]) * 2) / 2, ends], axis=1)
    ours = splinelab.map_coordinates(x, pts, order=d, mode=mode, cval=0.375)
    ref = ndimage.map_coordinates(x, pts, order=d, mode=mode, cval=0.375)
    # 32 ulps of max|value|: both round sums of (d + 1)^2 terms (worst seen 25).
    assert ulps_of_max(ours, ref) <= 32
    assert ours.shape == (pts.shape[1],)
    if d > 1:
        c = ndimage.spline_filter(x, d, mode=mode)
        ours = splinelab.map_coordinates(c, pts, order=d, mode=mode, cval=0.375, prefilter=False)
        ref = ndimage.map_coordinates(c, pts, order=d, mode=mode, cval=0.375, prefilter=False)
        assert ulps_of_max(ours, ref) <= 32


@pytest.mark.parametrize("mode", ["nearest", "grid-constant"])
@pytest.mark.parametrize("d", [2, 3, 5])
def test_map_coordinates_exact_edges(d, mode):
    # exact_edges=True: the spline of the extended signal, against scipy on
    # the input padded by 80 (scipy's 12 leaves rho^(24 - k) of the data).
    x = rng(11).uniform(-1, 1, (26, 31))
    pts = np.stack([rng(12).uniform(-3, 28, 400), rng(13).uniform(-3, 33, 400)])
    ours = splinelab.map_coordinates(x, pts, order=d, mode=mode, cval=0.375, exact_edges=True)
    q = np.pad(x, PAD, mode="edge") if mode == "nearest" else np.pad(x, PAD, constant_values=0.375)
    ref = ndimage.map_coordinates(q, pts + PAD, order=d, mode="mirror")
    assert ulps_of_max(ours, ref) <= 128


def test_map_coordinates_default_mode_is_scipys_constant():
    x = rng(4).uniform(-1, 1, 20)
    pts = [[-0.5, 3.25, 19.5]]
    np.testing.assert_allclose(splinelab.map_coordinates(x, pts), ndimage.map_coordinates(x, pts), rtol=0, atol=8 * EPS)
    assert splinelab.map_coordinates(x, pts)[0] == 0.0


def test_scipy_wrap_is_period_n_minus_1_in_map_coordinates():
    # scipy's 'wrap': the mirror spline at the point moved by whole periods
    # n - 1, far outside too (n = 1, 2: every point reads sample 0 / folds).
    from splinelab._ndimage import _wrap_coordinates

    for n in (1, 2, 7, 30):
        x = rng(n).uniform(-1, 1, n)
        pts = np.concatenate([rng(n + 1).uniform(-3 * n - 5, 4 * n + 5, (1, 300)), [[-(n - 1.0), 2.0 * (n - 1), 0.0]]], axis=1)
        for d in (0, 1, 3, 5):
            ours = splinelab.map_coordinates(x, pts, order=d, mode="wrap")
            ref = ndimage.map_coordinates(x, pts, order=d, mode="wrap")
            if n == 7 and d == 5:
                # scipy's mirror filter is off on short lines (79 ulps of
                # max|value| here): both against check's MPFR reference at
                # the folded points (the folding is scipy's, compared above).
                at = _wrap_coordinates(pts, x.shape)[0]
                judge = [splinelab.check("interp", samples=x, coordinates=at, values=v, degree=5)["max_ulps_scaled"]
                         for v in (ours, ref)]
                assert judge[0] <= 16 < 64 < judge[1], judge
                continue
            assert ulps_of_max(ours, ref) <= 32, (n, d)
    with pytest.raises(ValueError, match="unknown mode"):
        splinelab.map_coordinates(np.ones(5), [[1.0]], mode="periodic")


def test_degrees_0_and_1_return_the_input_as_scipy():
    x = rng().uniform(-1, 1, (5, 6))
    for d in (0, 1):
        np.testing.assert_array_equal(splinelab.spline_filter1d(x, order=d), ndimage.spline_filter1d(x, d))
        # scipy's spline_filter refuses them; ours returns the input too.
        np.testing.assert_array_equal(splinelab.spline_filter(x, order=d), x)


@pytest.mark.parametrize("mode", ["mirror", "reflect", "grid-wrap"])
@pytest.mark.parametrize("d", [7, 9, 15])
def test_high_degrees_against_check_mpfr_reference(d, mode):
    s = rng(d).uniform(-1, 1, 60)
    c = splinelab.spline_filter1d(s, order=d, mode=mode)
    r = splinelab.check("prefilter", samples=s, coeffs=c, degree=d, mode=mode)
    # The largest error in ulps of max|D| (small coefficients carry an
    # absolute error, so per-element ulps are not the measure): measured
    # <= 6.5 for these cases.
    assert r["max_ulps_scaled"] <= 16, r["worst"]
    assert r["reference_bits"] >= 128 and r["n"] == 60


def test_reflect_short_lines_pass_check_where_scipy_117_fails():
    # scipy up to 1.17 initialises short reflect lines wrongly (gh-24550,
    # fixed in 1.18): splinelab has the corrected values with either.
    import scipy

    s = rng(1).uniform(-1, 1, 9)
    ours = check_ulps(s, splinelab.spline_filter1d(s, order=5, mode="reflect"))
    theirs = check_ulps(s, ndimage.spline_filter1d(s, 5, mode="reflect"))
    assert ours <= 16
    if tuple(int(p) for p in scipy.__version__.split(".")[:2]) < (1, 18):
        assert 1e3 < theirs
    else:
        assert theirs <= 16


def check_ulps(s, c):
    return splinelab.check("prefilter", samples=s, coeffs=c, degree=5, mode="reflect")["worst"]["ulps"]


def test_truncated_route_within_certified_bound():
    x = rng(5).uniform(-1, 1, (40, 50))
    exact = splinelab.spline_filter(x, order=5)
    for tol in (1e-4, 1e-8, 1e-12):
        b = splinelab.filter_bound(5, tol, ndim=2)
        err = np.abs(splinelab.spline_filter(x, order=5, tol=tol) - exact).max()
        assert err <= b["total"] * np.abs(x).max() + 64 * EPS, tol
        assert b["bound"] < tol


def test_float32_computed_in_float32():
    x = rng().uniform(-1, 1, (20, 30)).astype(np.float32)
    ours = splinelab.spline_filter(x, order=3, output=np.float32)
    assert ours.dtype == np.float32
    ref = ndimage.spline_filter(x.astype(np.float64), 3)
    assert np.abs(ours - ref).max() <= 16 * np.finfo(np.float32).eps * np.abs(ref).max()
    # float32 input, default output: float64 as scipy.
    np.testing.assert_allclose(splinelab.spline_filter(x, order=3), ref, rtol=0, atol=16 * EPS)


def test_any_strides_give_the_contiguous_result():
    x = rng().uniform(-1, 1, (30, 40))
    for view in [x[::2, ::-1], x.T, np.asfortranarray(x), x[3:27:3, 1::5]]:
        np.testing.assert_array_equal(
            splinelab.spline_filter(view, order=3), splinelab.spline_filter(np.ascontiguousarray(view), order=3)
        )
    assert splinelab.spline_filter(x[::2], order=3).flags.c_contiguous


def test_output_array_and_threads():
    x = rng().uniform(-1, 1, (64, 64))
    out = np.empty_like(x)
    r = splinelab.spline_filter1d(x, 3, 0, out, threads=2)
    assert r is out
    np.testing.assert_array_equal(out, splinelab.spline_filter1d(x, 3, 0, threads=1))


def test_output_written_directly_in_place_or_through_a_copy():
    x = rng().uniform(-1, 1, (30, 40))
    want = splinelab.spline_filter(x, order=3)
    # C-ordered output: written directly; output=input: in place.
    out = np.empty_like(x)
    assert splinelab.spline_filter(x, order=3, output=out) is out
    np.testing.assert_array_equal(out, want)
    y = x.copy()
    assert splinelab.spline_filter(y, order=3, output=y) is y
    np.testing.assert_array_equal(y, want)
    # Fortran-ordered output: through a temporary, same numbers.
    out = np.empty_like(x, order="F")
    assert splinelab.spline_filter(x, order=3, output=out) is out
    np.testing.assert_array_equal(out, want)
    # Output overlapping the input at another offset: the input is read first.
    line = rng(3).uniform(-1, 1, 1000)
    z = np.zeros(1010)
    z[:1000] = line
    r = splinelab.spline_filter1d(z[:1000], 5, output=z[10:])
    np.testing.assert_array_equal(r, splinelab.spline_filter1d(line, 5))


def test_one_line_any_strides_and_dtypes():
    # A single line takes the fused copy-and-check path when contiguous.
    x = rng(5).uniform(-1, 1, 30_001)
    for view in [x[::-1], x[::3], x[:, None][:, 0]]:
        np.testing.assert_array_equal(
            splinelab.spline_filter1d(view, 3), splinelab.spline_filter1d(np.ascontiguousarray(view), 3)
        )
    # One line of an N-D array (the other axes of length 1) as the same 1-D line.
    np.testing.assert_array_equal(splinelab.spline_filter1d(x[None, :, None], 3, axis=1)[0, :, 0],
                                  splinelab.spline_filter1d(x, 3))
    i = np.arange(-50, 50)
    np.testing.assert_array_equal(splinelab.spline_filter1d(i, 3, output=np.float32),
                                  splinelab.spline_filter1d(i.astype(np.float32), 3, output=np.float32))
    # The first non-finite sample is named, also beyond the first copy block.
    y = x.copy()
    y[[20_000, 25_000]] = [np.inf, np.nan]
    with pytest.raises(ValueError, match=r"sample 20000 is not finite \(inf\)"):
        splinelab.spline_filter1d(y, 3, nan_policy="raise")


def test_integer_input_is_converted():
    x = np.arange(20).reshape(4, 5)
    np.testing.assert_allclose(splinelab.spline_filter(x), ndimage.spline_filter(x), atol=8 * EPS * 20)


def test_gil_is_released_while_filtering():
    # Count this thread's loop turns between the worker's entering the call
    # and its return: with the GIL held during the call they would be ~0
    # (only the turns of one 5 ms switch interval at most).
    import threading

    x = rng().uniform(-1, 1, (1500, 1500))
    started, done = threading.Event(), threading.Event()

    def work():
        started.set()
        splinelab.spline_filter(x, order=9, threads=1)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    started.wait()
    count = 0
    while not done.is_set():
        count += 1
    t.join()
    assert count > 10_000


# scipy's prefilter=False and orders 0, 1 evaluate the given array as it is:
# no padding, so every mode compares with scipy directly, points outside the
# grid included.
@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("d", [0, 1, 2, 3, 5])
def test_given_coefficients_equal_scipy(d, mode):
    c = rng(21).uniform(-1, 1, (17, 23))
    pts = np.stack([rng(22).uniform(-4, 20, 500), rng(23).uniform(-4, 26, 500)])
    # Half-integers too: where order 0 decides between two samples.
    pts[:, :40] = np.round(pts[:, :40] * 2) / 2
    ours = splinelab.map_coordinates(c, pts, order=d, mode=mode, cval=0.25, prefilter=False)
    ref = ndimage.map_coordinates(c, pts, order=d, mode=mode, cval=0.25, prefilter=False)
    if d == 0:
        np.testing.assert_array_equal(ours, ref)
    else:
        # Both sides round a sum of (d + 1)^2 products: a few ulps of max|value|.
        assert ulps_of_max(ours, ref) <= 16


@pytest.mark.parametrize("mode", ["mirror", "reflect", "grid-wrap"])
def test_orders_0_and_1_equal_scipy_with_prefilter(mode):
    x = rng(24).uniform(-1, 1, 40)
    pts = rng(25).uniform(-3, 42, (1, 300))
    for d in (0, 1):
        ours = splinelab.map_coordinates(x, pts, order=d, mode=mode)
        ref = ndimage.map_coordinates(x, pts, order=d, mode=mode)
        assert ulps_of_max(ours, ref) <= (0 if d == 0 else 4), d


def test_prefilter_false_on_our_coefficients_is_the_interpolant():
    x = rng(26).uniform(-1, 1, (20, 19))
    pts = rng(27).uniform(0, 18, (2, 200))
    c = splinelab.spline_filter(x, order=5, mode="grid-wrap")
    a = splinelab.map_coordinates(x, pts, order=5, mode="grid-wrap")
    b = splinelab.map_coordinates(c, pts, order=5, mode="grid-wrap", prefilter=False)
    # Two roundings of the same interpolant (the interpolant pads its own
    # coefficients): each within a few ulps times the quintic's amplification.
    assert ulps_of_max(a, b) <= 16
