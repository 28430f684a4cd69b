"""``splinelab.dask`` takes dask-image's keywords (issue 51): ``output_chunks``
for ``chunks``, ``prefilter``, ``image``/``input_arr`` for the input,
``depth`` for the filter's overlap, each with dask-image's meaning, and
splinelab's defaults kept (the prefilter on: exact splines).

References: dask-image's ``dask_image.ndinterp`` at run time where it
computes the same thing (``prefilter=False``: both evaluate the given
samples as coefficients; ``order=1`` with ``prefilter=True``), scipy's
``ndimage`` in memory, and splinelab's own ``chunks=`` spelling.
"""

import numpy as np
import pytest
import scipy.ndimage as ndi

import splinelab
import splinelab.dask as sld

da = pytest.importorskip("dask.array")

EPS = np.finfo(np.float64).eps
ROT = np.array([[np.cos(0.1), -np.sin(0.1)], [np.sin(0.1), np.cos(0.1)]])
OFFSET = np.array([3.0, -2.0])


@pytest.fixture(scope="module")
def x():
    return np.random.default_rng(51).uniform(-1, 1, (60, 50))


@pytest.fixture(scope="module")
def darr(x):
    return da.from_array(x, chunks=(20, 25))


def rounding(ref):
    return 64 * EPS * max(1.0, np.abs(ref).max())


def test_output_chunks_is_chunks(darr):
    for name, call in [("affine_transform", lambda **k: sld.affine_transform(darr, ROT, OFFSET, **k)),
                       ("rotate", lambda **k: sld.rotate(darr, 10.0, **k)),
                       ("zoom", lambda **k: sld.zoom(darr, 1.5, **k)),
                       ("shift", lambda **k: sld.shift(darr, (0.5, -1.25), **k))]:
        theirs, ours = call(output_chunks=(30, 25)), call(chunks=(30, 25))
        assert theirs.chunks == ours.chunks and theirs.chunks[0][0] == 30, name
        np.testing.assert_array_equal(theirs.compute(), ours.compute())


def test_both_names_is_a_type_error_naming_both(darr):
    calls = [lambda: sld.affine_transform(darr, ROT, chunks=10, output_chunks=10),
             lambda: sld.rotate(darr, 10.0, chunks=10, output_chunks=10),
             lambda: sld.zoom(darr, 2.0, chunks=10, output_chunks=10),
             lambda: sld.shift(darr, 1.0, chunks=10, output_chunks=10)]
    for call in calls:
        with pytest.raises(TypeError, match=r"chunks=.*output_chunks="):
            call()
    with pytest.raises(TypeError, match=r"input=.*image="):
        sld.affine_transform(darr, ROT, image=darr)
    with pytest.raises(TypeError, match=r"input=.*input_arr="):
        sld.rotate(darr, 10.0, input_arr=darr)
    with pytest.raises(TypeError, match=r"darr=.*image="):
        sld.spline_filter(darr, image=darr)
    with pytest.raises(TypeError, match=r"darr=.*image="):
        sld.spline_filter1d(darr=darr, image=darr)


def test_input_under_dask_images_names(darr):
    np.testing.assert_array_equal(sld.affine_transform(image=darr, matrix=ROT, offset=OFFSET).compute(),
                                  sld.affine_transform(darr, ROT, OFFSET).compute())
    np.testing.assert_array_equal(sld.rotate(input_arr=darr, angle=10.0).compute(), sld.rotate(darr, 10.0).compute())
    np.testing.assert_array_equal(sld.spline_filter(image=darr).compute(), sld.spline_filter(darr).compute())
    np.testing.assert_array_equal(sld.spline_filter1d(image=darr, axis=0).compute(),
                                  sld.spline_filter1d(darr, axis=0).compute())


@pytest.mark.parametrize("mode", ["constant", "nearest", "grid-constant"])
@pytest.mark.parametrize("order", [0, 1, 2, 3, 5])
def test_prefilter_false_is_dask_images_default(x, darr, order, mode):
    """dask-image's defaults (no prefilter): the same coefficients evaluated,
    so the same numbers within rounding (dask-image shifts the offset per
    chunk, one more rounding), and scipy's ``prefilter=False`` in memory."""
    ndinterp = pytest.importorskip("dask_image.ndinterp")
    theirs = ndinterp.affine_transform(darr, ROT, OFFSET, order=order, mode=mode, output_chunks=(30, 25)).compute()
    ours = sld.affine_transform(darr, ROT, OFFSET, order=order, mode=mode, prefilter=False, output_chunks=(30, 25))
    ours = ours.compute()
    scipy = ndi.affine_transform(x, ROT, OFFSET, order=order, mode=mode, prefilter=False)
    assert np.abs(ours - scipy).max() <= rounding(scipy)
    if order > 0:  # degree 0: the same on every point not on a half-integer; dask-image's offset rounding moves some
        assert np.abs(ours - theirs).max() <= 1e-13


def test_map_coordinates_prefilter_false_matches_dask_image(x, darr):
    ndinterp = pytest.importorskip("dask_image.ndinterp")
    # 3 x 3 blocks: dask-image 2025's map_coordinates numbers the blocks of
    # a non-square block grid wrongly (an IndexError on 3 x 2).
    square = da.from_array(x, chunks=(20, 17))
    pts = np.random.default_rng(5).uniform(-1, 60, (2, 300))
    at = da.from_array(pts, chunks=(2, 100))
    for order in (1, 3):
        theirs = ndinterp.map_coordinates(square, at, order=order, mode="nearest").compute()
        ours = sld.map_coordinates(darr, at, order=order, mode="nearest", prefilter=False).compute()
        scipy = ndi.map_coordinates(x, pts, order=order, mode="nearest", prefilter=False)
        assert np.abs(ours - theirs).max() <= 1e-13 and np.abs(ours - scipy).max() <= rounding(scipy)


def test_prefilter_stays_on_by_default(x, darr):
    """splinelab's default is scipy's (the prefilter on): within the
    certified bound of scipy's exact interpolation, where dask-image's
    default (off) is an approximating spline far from it."""
    ndinterp = pytest.importorskip("dask_image.ndinterp")
    scipy = ndi.affine_transform(x, ROT, OFFSET, order=3)
    ours = sld.affine_transform(darr, ROT, OFFSET, order=3, output_chunks=(30, 25)).compute()
    theirs = ndinterp.affine_transform(darr, ROT, OFFSET, order=3, output_chunks=(30, 25)).compute()
    assert np.abs(ours - scipy).max() <= sld.bound(3, sld.DEFAULT_TOL, 2) * np.abs(x).max() + rounding(scipy)
    assert np.abs(theirs - scipy).max() > 0.1
    # The same with the prefilter asked for by name, and dask-image's prefilter=True (its empirical depth).
    np.testing.assert_array_equal(sld.affine_transform(darr, ROT, OFFSET, prefilter=True).compute(),
                                  sld.affine_transform(darr, ROT, OFFSET).compute())
    theirs = ndinterp.affine_transform(darr, ROT, OFFSET, order=3, prefilter=True, output_chunks=(30, 25)).compute()
    assert np.abs(theirs - scipy).max() < 1e-6


def test_rotate_keywords(x, darr):
    ndinterp = pytest.importorskip("dask_image.ndinterp")
    theirs = ndinterp.rotate(darr, 20.0, order=1, output_chunks=(16, 16)).compute()
    ours = sld.rotate(darr, 20.0, order=1, output_chunks=(16, 16))
    assert ours.chunks[0][0] == 16
    ours = ours.compute()
    assert ours.shape == theirs.shape and np.abs(ours - theirs).max() <= 1e-13
    np.testing.assert_allclose(ours, ndi.rotate(x, 20.0, order=1), rtol=0, atol=rounding(x))


def test_spline_filter_output_chunks_and_depth(x, darr):
    """``output_chunks`` rechunks the result (dask-image ignores it);
    ``depth`` is an overlap never below the certified one: a small one
    still gives the certified bound, a large one reads more and stays
    within it."""
    exact = splinelab.spline_filter(x, order=3)
    allowed = sld.bound(3, sld.DEFAULT_TOL, 2) * np.abs(x).max() + rounding(exact)
    default = sld.spline_filter(darr, order=3)
    for kw in [dict(depth=2), dict(depth=12), dict(depth=40), dict(output_chunks=(30, 50))]:
        out = sld.spline_filter(darr, order=3, **kw)
        if "output_chunks" in kw:
            assert out.chunks == ((30, 30), (50,))
        elif kw["depth"] <= sld.depth(3):
            assert out.chunks == default.chunks
            np.testing.assert_array_equal(out.compute(), default.compute())
        assert np.abs(out.compute() - exact).max() <= allowed, kw
    one = sld.spline_filter1d(darr, order=5, axis=0, depth=30, output_chunks=(60, 10)).compute()
    exact1 = splinelab.spline_filter1d(x, order=5, axis=0)
    assert np.abs(one - exact1).max() <= sld.bound(5, sld.DEFAULT_TOL, 1) * np.abs(x).max() + rounding(exact1)
    for bad in (-1, 2.5, True):
        with pytest.raises(ValueError, match="depth"):
            sld.spline_filter(darr, depth=bad)
