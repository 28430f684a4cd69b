"""Chunked prefiltering on dask: a 2-D array in 4 x 4 chunks, degrees 3, 5, 9,
threaded scheduler and a 2-worker LocalCluster (loopback): the largest
difference to the unchunked exact result stays within the certified bound.
dask-image's seam error at its default depth (degrees 3, 5) is printed
beside ours (run pytest -s to see it)."""

import dask
import dask.array as da
import numpy as np
import pytest

import splinelab
import splinelab.dask as sld

EPS = np.finfo(np.float64).eps
N = 320  # 4 x 4 chunks of 80: at least the depth of degree 9 at 1e-12 (68)


@pytest.fixture(scope="module")
def data():
    return np.random.default_rng(18).uniform(-1, 1, (N, N))


def allowed(order, tol, x, exact, route="truncated"):
    b = sld.bound(order, tol, ndim=2, route=route)
    return b * np.abs(x).max() + 64 * EPS * np.abs(exact).max()


def seam_errors(x, exact, order, tol, scheduler):
    ours = sld.spline_filter(da.from_array(x, chunks=N // 4), order=order, tol=tol).compute(scheduler=scheduler)
    return np.abs(ours - exact).max()


@pytest.mark.parametrize("route", sld.ROUTES)
@pytest.mark.parametrize("mode", ["mirror", "grid-wrap", "nearest"])
@pytest.mark.parametrize("order", [3, 5, 9])
def test_threaded_within_certified_bound(data, order, mode, route):
    tol = 1e-12
    assert sld.depth(order, tol, route) <= N // 4
    exact = splinelab.spline_filter(data, order=order, mode=mode)
    darr = da.from_array(data, chunks=N // 4)
    assert darr.numblocks == (4, 4)
    ours = sld.spline_filter(darr, order=order, mode=mode, tol=tol, route=route).compute(scheduler="threads")
    assert np.abs(ours - exact).max() <= allowed(order, tol, data, exact, route)


@pytest.mark.parametrize("route", sld.ROUTES)
def test_filter1d_and_loose_tolerance(data, route):
    # A loose tol: the error is real (not rounding) and still within the bound.
    tol = 1e-4
    exact = splinelab.spline_filter1d(data, order=3, axis=0)
    darr = da.from_array(data, chunks=N // 4)
    ours = sld.spline_filter1d(darr, order=3, axis=0, tol=tol, route=route).compute()
    err = np.abs(ours - exact).max()
    assert 1e3 * EPS < err <= sld.bound(3, tol, 1, route) * np.abs(data).max() + 64 * EPS * np.abs(exact).max()
    assert sld.bound(3, tol, 1, route) < tol


def test_recursive_bound_is_twice_the_tail_of_the_half_tolerance_width():
    f = splinelab.filter_bound(5, 5e-9)
    assert sld.depth(5, 1e-8, "recursive") == f["half_width"] + 3
    # (A + 2b) - A: the subtraction loses log2(A / 2b) ~ 30 bits.
    np.testing.assert_allclose(sld.bound(5, 1e-8, 1, "recursive"), 2 * f["bound"], rtol=1e-6)
    with pytest.raises(ValueError, match="route"):
        sld.depth(3, 1e-8, "fast")


def test_local_cluster_within_certified_bound(data):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        for order, route in [(3, "truncated"), (5, "truncated"), (9, "truncated"), (3, "recursive"), (9, "recursive")]:
            exact = splinelab.spline_filter(data, order=order)
            darr = da.from_array(data, chunks=N // 4)
            ours = client.compute(sld.spline_filter(darr, order=order, tol=1e-12, route=route)).result()
            assert np.abs(ours - exact).max() <= allowed(order, 1e-12, data, exact, route), (order, route)


@pytest.mark.parametrize("order", [3, 5])
def test_dask_image_seam_error_reported(data, order):
    ndinterp = pytest.importorskip("dask_image.ndinterp")
    exact = splinelab.spline_filter(data, order=order)
    theirs = ndinterp.spline_filter(da.from_array(data, chunks=N // 4), order=order).compute(scheduler="threads")
    with dask.config.set(scheduler="threads"):
        ours = seam_errors(data, exact, order, sld.DEFAULT_TOL, "threads")
    err = np.abs(theirs - exact).max()
    print(f"\ndegree {order}: seam error dask-image {err:.3e} (default depth), splinelab.dask {ours:.3e} "
          f"(tol {sld.DEFAULT_TOL:g}, bound {allowed(order, sld.DEFAULT_TOL, data, exact):.3e})")
    assert np.isfinite(err)


@pytest.mark.parametrize("mode", ["mirror", "reflect", "nearest", "grid-wrap", "constant", "grid-constant", "wrap", "grid-mirror"])
@pytest.mark.parametrize(("shape", "chunks"), [((60, 50), 7), ((40, 33, 21), (5, 11, 21)), ((200,), 3)])
def test_zero_continuation_blocks_within_bound_whatever_the_chunks(mode, shape, chunks):
    """The default route (exact recursion per padded block, zeros beyond it,
    the mode's extension padded at the array's edges): chunks of 3 to 11
    samples (far below the overlap), an axis left whole, every mode; the
    difference to the unchunked exact filter stays within the per-axis
    truncation bound and is not zero (the blocks really are truncated)."""
    x = np.random.default_rng(7).uniform(-1, 1, shape)
    for order, tol in [(2, 1e-12), (3, 1e-6), (5, 1e-12)]:
        exact = splinelab.spline_filter(x, order=order, mode=mode)
        ours = sld.spline_filter(da.from_array(x, chunks=chunks), order=order, mode=mode, tol=tol).compute()
        err = np.abs(ours - exact).max()
        assert err <= sld.bound(order, tol, x.ndim) * np.abs(x).max() + 64 * EPS * np.abs(exact).max(), (order, err)
        if tol == 1e-6:
            assert err > 1e3 * EPS, err


@pytest.mark.parametrize("call", [
    lambda d: sld.spline_filter(d, order=3, mode="mirror"),
    lambda d: sld.spline_filter(d, order=3, mode="grid-wrap"),  # the convolution's blocks
    lambda d: sld.spline_filter1d(d, order=5, axis=0, route="recursive"),
    lambda d: sld.zoom(d, 1.25, order=3, mode="reflect"),  # the fused route's tasks
])
def test_filter_settings_are_made_once_a_call(data, monkeypatch, call):
    # The filters' settings are checked when the graph is built: the same
    # number of times for 4 blocks as for 64, none in the tasks; the values
    # those of the unchunked call within the certified bound.
    from splinelab._settings import Settings

    made = []
    real = Settings.for_filter.__func__

    def counted(cls, *args, **kwargs):
        made.append(args)
        return real(cls, *args, **kwargs)

    monkeypatch.setattr(Settings, "for_filter", classmethod(counted))
    counts = []
    for chunks in (N // 2, N // 8):
        made.clear()
        lazy = call(da.from_array(data, chunks=chunks))
        counts.append(len(made))
        made.clear()
        got = lazy.compute(scheduler="sync")
        assert made == [], len(made)
        np.testing.assert_allclose(got, call(da.from_array(data, chunks=N)).compute(scheduler="sync"), rtol=0,
                                   atol=sld.bound(5, sld.DEFAULT_TOL, ndim=2) * 8 + 1e-12)
    assert counts[0] == counts[1] <= 4, counts


@pytest.mark.parametrize("mode", ["constant", "nearest", "mirror", "reflect", "wrap", "grid-mirror", "grid-constant",
                                  "grid-wrap"])
def test_region_spans_by_the_arithmetic_they_stand_for(mode):
    # _Rules.spans and _Fused.widened (what the output tasks and the
    # accessor's mode= windows read) against the windows' arithmetic written
    # out point by point: `d + 1` coefficients around the point with the
    # engine's margin of 2 below and 3 above, clamped to the axis (the whole
    # axis for degree 0 under folding and for grid-wrap over an end), then
    # the certified overlap `depth` each side, clamped again.
    rng = np.random.default_rng(19)
    for d in range(6):
        for n in (1, 2, 7, 40):
            rules = sld._Rules(d, mode, 0.0, "float64", (n,), (n,), True)
            x = np.concatenate([rng.uniform(-5, n + 5, 100), rng.uniform(-1e15, 1e15, 10),
                                [-0.5, 0.0, n - 1.0, n - 0.5, 2.0**52, -2.0**52]])
            for depth in (0, 7):
                lo, hi = sld._Fused(max(d, 2), mode, depth, 1, (n,)).widened(0, *rules.spans(0, x, x))
                for v, a, b in zip(x, lo, hi):
                    low, high = int(np.floor(v)) - (d + 1) // 2 - 2, int(np.ceil(v)) + (d + 1) // 2 + 3
                    whole = ((d == 0 and rules.engine_mode in sld._FOLDING)
                             or (rules.engine_mode == "grid-wrap" and (low < 0 or high > n)))
                    low, high = (0, n) if whole else (max(low, 0), min(high, n))
                    assert (a, b) == (max(low - depth, 0), min(high + depth, n)), (d, n, v)
                    assert rules._span(0, v, v) == (low, high)
