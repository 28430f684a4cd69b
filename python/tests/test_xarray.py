"""The splinelab accessor (``import splinelab.xarray``, issue 51) against
xarray's own ``interp`` and against the exact not-a-knot spline.

References: xarray 2026.9.0's ``interp`` at run time (it calls scipy:
``interp1d``/``PchipInterpolator`` along one dimension, ``interpn`` along
several) for the coordinates, dimensions, attributes, exceptions and, where
scipy's numbers are exact, the numbers; for "cubic" and "quintic" along
several dimensions, where xarray's ``interpn`` solves iteratively
(``gcrotmk``, ``atol=1e-6``), the exact spline computed independently
(``make_interp_spline`` along each axis in turn, then ``NdBSpline``:
test_rgi.exact_spline). Dask: the lazy result against the in-memory one,
and the input chunks a computation reads, counted by the array itself.

``python python/tests/test_xarray.py`` prints the agreement figures.
"""

import subprocess
import sys
import threading

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

xr = pytest.importorskip("xarray", reason="pip install splinelab[xarray]")
da_mod = pytest.importorskip("dask.array")

import splinelab.xarray  # noqa: E402,F401  (registers the accessor)
from test_rgi import exact_spline  # noqa: E402

METHODS = ["linear", "nearest", "slinear", "cubic", "quintic", "pchip"]
DEGREE = {"cubic": 3, "quintic": 5}

def jittered(lo, hi, n, rng):
    """n nodes from lo to hi, each interior one moved by up to 0.35 of the spacing."""
    x = np.linspace(lo, hi, n)
    x[1:-1] += rng.uniform(-0.35, 0.35, n - 2) * (hi - lo) / (n - 1)
    return x


def cube(uniform, shape=(13, 11, 3), rng=None):
    """A labelled cube: x, y interpolated, t carried; a string coordinate
    along x, a 2-D coordinate, attributes. The same for the same arguments."""
    rng = np.random.default_rng(51 + shape[0]) if rng is None else rng
    if uniform:
        x, y = np.linspace(0.0, 6.0, shape[0]), np.linspace(-2.0, 3.0, shape[1])
    else:
        x, y = jittered(0.0, 6.0, shape[0], rng), jittered(-2.0, 3.0, shape[1], rng)
    X, Y = np.meshgrid(x, y, indexing="ij")
    v = np.sin(X)[..., None] * np.cos(1.3 * Y)[..., None] + rng.normal(scale=0.1, size=shape)
    return xr.DataArray(
        v, dims=("x", "y", "t"), name="temp", attrs={"units": "K"},
        coords={"x": ("x", x, {"units": "km"}), "y": y, "t": np.arange(shape[2]),
                "lab": ("x", [f"s{i}" for i in range(shape[0])]), "area": (("x", "y"), X * Y)})


def same_labels(ours, theirs, coord_tol=1e-12):
    """Coordinates (each variable identical; an interpolated one within
    ``coord_tol``), dims, attrs and name as xarray's. One difference by
    design: xarray keeps a non-numeric coordinate along a dimension that
    pointwise interpolation removed (a coordinate on a dimension the array
    no longer has); the accessor drops it."""
    assert ours.dims == theirs.dims
    assert ours.attrs == theirs.attrs and ours.name == theirs.name
    expected = {k for k, c in theirs.coords.items() if set(c.dims) <= set(theirs.dims)}
    assert set(ours.coords) == expected, (list(ours.coords), list(theirs.coords))
    for k in expected:
        a, b = ours.coords[k].variable, theirs.coords[k].variable
        if b.dtype.kind == "f" and k not in theirs.dims:   # an interpolated coordinate: computed numbers
            assert a.dims == b.dims and a.attrs == b.attrs and a.dtype == b.dtype
            assert coord_tol is None or rel(a.values, b.values) <= coord_tol
        else:
            xr.testing.assert_identical(a, b)


def rel(a, b):
    a, b = np.asarray(a), np.asarray(b)
    assert (np.isnan(a) == np.isnan(b)).all()
    ok = ~np.isnan(b)
    if not ok.any():
        return 0.0
    scale = np.abs(b[ok]).max() or 1.0   # all zero: absolute
    return float(np.abs(a[ok] - b[ok]).max() / scale)


def targets(da, seed=0):
    rng = np.random.default_rng(seed)
    x, y = da.x.values, da.y.values
    inside_x = np.r_[x[0], rng.uniform(x[0], x[-1], 7), x[-1]]
    inside_y = np.r_[y[0], rng.uniform(y[0], y[-1], 5), y[-1]]
    return inside_x, inside_y


# ---------------------------------------------------------------- numbers


@pytest.mark.parametrize("uniform", [True, False])
@pytest.mark.parametrize("method", METHODS)
def test_one_dimension_is_xarrays_interp1d(method, uniform):
    """Along one dimension xarray calls interp1d / make_interp_spline /
    PchipInterpolator, all exact: ours within 1e-12 relative."""
    da = cube(uniform)
    xs, _ = targets(da)
    xs = np.r_[xs, da.x.values[0] - 1.0, da.x.values[-1] + 1.0]   # out of range: NaN, as xarray
    ours, theirs = da.splinelab.interp(x=xs, method=method), da.interp(x=xs, method=method)
    same_labels(ours, theirs)
    assert ours.dtype == theirs.dtype
    assert rel(ours, theirs) <= 1e-12


@pytest.mark.parametrize("uniform", [True, False])
@pytest.mark.parametrize("method", ["linear", "nearest", "slinear", "pchip"])
def test_several_dimensions_are_xarrays_where_scipy_is_exact(method, uniform):
    da = cube(uniform)
    xs, ys = targets(da)
    for kw in (dict(x=xs, y=ys), dict(x=xr.DataArray(xs[:5], dims="p"), y=xr.DataArray(ys[:5], dims="p"))):
        ours, theirs = da.splinelab.interp(method=method, **kw), da.interp(method=method, **kw)
        same_labels(ours, theirs)
        assert rel(ours, theirs) <= 1e-12


@pytest.mark.parametrize("dtype", ["float32", "int64", "complex128"])
@pytest.mark.parametrize("method", METHODS)
def test_result_dtypes_are_xarrays(method, dtype):
    """xarray in memory: float64 for linear and the splines, the values' float
    dtype for nearest and for pchip along several dimensions. float32 input:
    scipy's interp1d computes "linear" in float32, here in float64 (the two
    differ by float32 rounding)."""
    da = cube(True)
    if dtype == "complex128" and method == "pchip":
        return
    da = (da * 10).astype(dtype) if dtype != "complex128" else da + 0.5j * da
    for kw in (dict(x=[1.5, 2.5]), dict(x=[1.5, 2.5], y=[0.5])):
        ours, theirs = da.splinelab.interp(method=method, **kw), da.interp(method=method, **kw)
        assert ours.dtype == theirs.dtype, (kw, ours.dtype, theirs.dtype)
        if method in ("cubic", "quintic") and len(kw) > 1:
            continue
        tol = 1e-6 if dtype == "float32" else 1e-12
        assert np.abs(ours.values - theirs.values).max() <= tol * np.abs(theirs.values).max()


def spline_distances(method, uniform):
    """Ours and xarray's distance from the exact spline, relative to max|data|."""
    da = cube(uniform)
    xs, ys = targets(da)
    ours = da.splinelab.interp(x=xs, y=ys, method=method)
    theirs = da.interp(x=xs, y=ys, method=method)
    same_labels(ours, theirs, coord_tol=None)   # "area", interpolated by xarray's gcrotmk too:
    X, Y = np.meshgrid(xs, ys, indexing="ij")     # it is x*y, which the exact spline reproduces
    assert rel(ours.area.values, X * Y) <= 1e-12
    spl = exact_spline((da.x.values, da.y.values), da.values, DEGREE[method])
    exact = spl(np.stack([X.ravel(), Y.ravel()], axis=-1)).reshape(X.shape + (da.sizes["t"],))
    scale = np.abs(da.values).max()
    return (float(np.abs(ours.values - exact).max() / scale), float(np.abs(theirs.values - exact).max() / scale))


@pytest.mark.parametrize("uniform", [True, False])
@pytest.mark.parametrize("method", ["cubic", "quintic"])
def test_several_dimensions_splines_are_exact_where_xarrays_are_not(method, uniform):
    """Along several dimensions xarray's cubic/quintic is scipy's gcrotmk
    (atol=1e-6): ours is the exact spline, xarray's is not."""
    ours, theirs = spline_distances(method, uniform)
    assert ours <= 1e-12
    assert theirs > 1e-9, "xarray's iterative solve is no longer approximate: compare directly"


@pytest.mark.parametrize("chunked", [False, True])
def test_xarrays_quintic_nd_case_is_scipys_iterative_error(chunked):
    """The known difference of xarray's own test_interpolate_nd[quintic]
    (python/tests/downstream/known.py): on its 100x30x10 cube, the
    accessor's quintic is the exact spline (within 1e-14 of max|data|),
    xarray's (scipy's interpn, gcrotmk) is 2.5e-6 from it, and the two
    differ by more than the test's rtol=1e-5, atol=1e-8."""
    x, y, z = np.linspace(0, 1, 100), np.linspace(0, 0.1, 30), np.linspace(0.1, 0.2, 10)
    values = np.sin(x[:, None, None]) * np.cos(y[:, None]) * z
    data = xr.DataArray(values, dims=["x", "y", "z"], coords={"x": x, "y": y, "z": z})
    new = dict(x=np.linspace(0.1, 1.0, 11), y=np.linspace(0.0, 0.1, 10), z=z)   # inside: no NaN fill
    src = data.chunk(z=5) if chunked else data
    ours = src.splinelab.interp(method="quintic", **new).values
    theirs = data.interp(method="quintic", **new).values
    exact = exact_spline((x, y, z), values, 5)(np.stack(np.meshgrid(*new.values(), indexing="ij"), -1))
    scale = np.abs(values).max()
    assert np.abs(ours - exact).max() <= 1e-14 * scale
    assert np.abs(theirs - exact).max() >= 1e-6 * scale
    assert not np.allclose(ours, theirs, rtol=1e-5, atol=1e-8)


@pytest.mark.parametrize("method", ["linear", "cubic", "pchip", "nearest"])
def test_datetime_coordinates_as_xarray_converts_them(method):
    rng = np.random.default_rng(1)
    t = np.datetime64("2020-01-01") + np.cumsum(rng.integers(1, 5, 12)).astype("timedelta64[D]")
    da = xr.DataArray(rng.normal(size=(12, 4)), dims=("time", "z"), coords={"time": t})
    new = t[0] + np.array([1, 7, 20, 31], dtype="timedelta64[h]") * 5
    ours, theirs = da.splinelab.interp(time=new, method=method), da.interp(time=new, method=method)
    same_labels(ours, theirs)
    assert rel(ours, theirs) <= 1e-12
    s = da.splinelab.interp(time="2020-01-05", method=method)   # a date string, as xarray
    same_labels(s, da.interp(time="2020-01-05", method=method))


def test_datetime_values_round_as_xarray():
    ds = xr.Dataset({"when": ("x", np.datetime64("2021-03-01") + np.arange(6) * np.timedelta64(7, "h"))},
                    coords={"x": np.arange(6.0)})
    ours, theirs = ds.splinelab.interp(x=[0.5, 2.25], method="linear"), ds.interp(x=[0.5, 2.25], method="linear")
    xr.testing.assert_identical(ours, theirs)


@pytest.mark.parametrize("kwargs", [{"fill_value": 3.5}, {"fill_value": "extrapolate"}, {"fill_value": (-1.0, 9.0)},
                                    {"fill_value": None}])
@pytest.mark.parametrize("method", ["linear", "nearest", "cubic", "quintic", "slinear"])
def test_fill_value_one_dimension(method, kwargs):
    da = cube(False)
    xs = np.r_[-1.0, 0.5, 2.0, 7.5]
    ours, theirs = da.splinelab.interp(x=xs, method=method, kwargs=kwargs), da.interp(x=xs, method=method,
                                                                                        kwargs=kwargs)
    assert rel(ours, theirs) <= 1e-12


@pytest.mark.parametrize("kwargs", [{}, {"fill_value": 2.0}, {"fill_value": None}])
@pytest.mark.parametrize("method", ["linear", "nearest", "slinear", "pchip"])
def test_fill_value_several_dimensions(method, kwargs):
    """Pointwise (xarray's interpn): NaN, a number, or None to extrapolate."""
    da = cube(True)
    px = xr.DataArray([-0.5, 1.0, 6.5, 3.0], dims="p")
    py = xr.DataArray([0.0, 3.5, 1.0, -2.5], dims="p")
    ours = da.splinelab.interp(x=px, y=py, method=method, kwargs=kwargs)
    theirs = da.interp(x=px, y=py, method=method, kwargs=kwargs)
    assert rel(ours, theirs) <= 1e-12


def test_pchip_extrapolate_keyword_one_dimension():
    da = cube(False)
    kw = {"extrapolate": True}
    xs = [-0.5, 3.0, 6.5]
    assert rel(da.splinelab.interp(x=xs, method="pchip", kwargs=kw), da.interp(x=xs, method="pchip", kwargs=kw)) \
        <= 1e-12


def test_mode_is_map_coordinates_on_the_index_coordinates():
    """mode=: ndimage's boundary modes on uniform axes, scipy.ndimage's numbers."""
    from scipy import ndimage
    da = cube(True)
    xs, ys = np.array([-0.3, 1.1, 5.9, 6.4]), np.array([-2.2, 0.4, 3.1, 1.0])
    ours = da.splinelab.interp(x=xr.DataArray(xs, dims="p"), y=xr.DataArray(ys, dims="p"), mode="mirror")
    ix = (xs - 0.0) / (6.0 / 12)
    iy = (ys + 2.0) / (5.0 / 10)
    ref = np.stack([ndimage.map_coordinates(da.values[..., k], [ix, iy], order=3, mode="mirror")
                    for k in range(da.sizes["t"])], axis=-1)
    assert rel(ours, ref) <= 1e-12
    tight = da.splinelab.interp(x=xs, mode="reflect", tol=1e-9)
    assert tight.dims == ("x", "y", "t")
    with pytest.raises(ValueError, match="'x'"):
        cube(False).splinelab.interp(x=[1.0], mode="mirror")


# ---------------------------------------------------------------- labels


FORMS = ["scalar", "array", "pointwise", "own_dim", "skip"]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(fx=st.sampled_from(FORMS), fy=st.sampled_from(FORMS), ft=st.sampled_from(["skip", "scalar", "array"]),
       method=st.sampled_from(["linear", "nearest", "cubic", "pchip"]), seed=st.integers(0, 2**16))
def test_labels_equal_xarrays_for_every_indexing_form(fx, fy, ft, method, seed):
    """Property: for any mix of indexing forms the result's coordinates,
    dims, attrs and name are xarray's (values too, where scipy is exact)."""
    rng = np.random.default_rng(seed)
    da = cube(bool(seed % 2), shape=(9, 8, 6), rng=rng)
    coords = {}
    for dim, form in (("x", fx), ("y", fy), ("t", ft)):
        lo, hi = float(da[dim].min()), float(da[dim].max())
        pick = rng.uniform(lo, hi, 3)
        if form == "scalar":
            coords[dim] = float(pick[0])
        elif form == "array":
            coords[dim] = np.sort(pick)
        elif form == "pointwise":
            coords[dim] = xr.DataArray(pick, dims="p", coords={"p": [10, 20, 30]}, attrs={"from": dim})
        elif form == "own_dim":
            coords[dim] = xr.DataArray(pick, dims=f"new_{dim}")
    if not coords:
        return
    try:
        theirs = da.interp(coords, method=method)
    except Exception as e:   # xarray refuses it (e.g. a scalar x beside a pointwise y): so do we
        with pytest.raises(type(e)):
            da.splinelab.interp(coords, method=method)
        return
    ours = da.splinelab.interp(coords, method=method)
    several = len(coords) > 1
    same_labels(ours, theirs, coord_tol=None if several and method == "cubic" else 1e-12)
    if not (several and method == "cubic"):
        assert rel(ours, theirs) <= 1e-12


def test_dataset_interpolates_every_variable_with_the_dims_and_keeps_the_others():
    da = cube(False)
    ds = xr.Dataset({"temp": da, "ints": ("x", np.arange(13)), "flat": ("t", [1.0, 2.0, 3.0]),
                     "name": ("x", [f"n{i}" for i in range(13)]), "when": ("y", np.datetime64("2020-01-01")
                                                                         + np.arange(11) * np.timedelta64(1, "D"))},
                    attrs={"title": "cube"})
    kw = dict(x=[0.5, 2.0, 4.5], y=1.0)
    ours, theirs = ds.splinelab.interp(method="linear", **kw), ds.interp(method="linear", **kw)
    assert set(ours.data_vars) == set(theirs.data_vars) and ours.attrs == theirs.attrs
    for name in theirs.variables:
        xr.testing.assert_allclose(ours[name].variable, theirs[name].variable, rtol=1e-12)
        assert ours[name].attrs == theirs[name].attrs


def test_vectorised_dims_as_xarray():
    """xarray #6799's comment: interpolating along q at a point that depends
    on the other (not interpolated) dims."""
    rng = np.random.default_rng(2)
    da = xr.DataArray(rng.normal(size=(3, 8, 4, 5)), dims=("time", "q", "lat", "lon"),
                      coords={"q": np.linspace(0, 7, 8)})
    q = xr.DataArray(rng.uniform(0, 7, (4, 5)), dims=("lat", "lon"))
    for method in ("linear", "cubic"):
        ours, theirs = da.splinelab.interp(q=q, method=method), da.interp(q=q, method=method)
        same_labels(ours, theirs)
        assert rel(ours, theirs) <= 1e-12


# ---------------------------------------------------------------- bad input


def raises_as_xarray(call_ours, call_theirs, word):
    with pytest.raises(Exception) as theirs:
        call_theirs()
    with pytest.raises(type(theirs.value)) as ours:
        call_ours()
    assert word in str(ours.value), (str(ours.value), str(theirs.value))


def test_unknown_dimension():
    da = cube(True)
    raises_as_xarray(lambda: da.splinelab.interp(w=1.0), lambda: da.interp(w=1.0), "'w'")


@pytest.mark.parametrize("method,n", [("cubic", 3), ("quintic", 5)])
def test_axis_too_short_for_the_method(method, n):
    da = cube(True).isel(x=slice(0, n))
    raises_as_xarray(lambda: da.splinelab.interp(x=[0.2], method=method), lambda: da.interp(x=[0.2], method=method),
                     "'x'")
    raises_as_xarray(lambda: da.splinelab.interp(x=[0.2], y=[0.0], method=method),
                     lambda: da.interp(x=[0.2], y=[0.0], method=method), "'x'")


def test_non_monotonic_and_repeated_coordinates():
    da = cube(True)
    shuffled = da.isel(x=np.r_[1, 0, 2:da.sizes["x"]])
    raises_as_xarray(lambda: shuffled.splinelab.interp(x=[1.0], method="cubic", assume_sorted=True),
                     lambda: shuffled.interp(x=[1.0], method="cubic", assume_sorted=True), "'x'")
    repeated = da.assign_coords(x=np.r_[da.x.values[:3], da.x.values[2:-1]])
    raises_as_xarray(lambda: repeated.splinelab.interp(x=[1.0], method="cubic"),
                     lambda: repeated.interp(x=[1.0], method="cubic"), "'x'")
    # unsorted is fine when not assumed sorted: sorted first, as xarray
    assert rel(shuffled.splinelab.interp(x=[1.0, 2.0]), da.splinelab.interp(x=[1.0, 2.0])) == 0.0


def test_indexers_of_mismatched_dims():
    da = cube(True)
    px, py = xr.DataArray([1.0, 2.0, 3.0], dims="p"), xr.DataArray([0.0, 1.0], dims="p")
    raises_as_xarray(lambda: da.splinelab.interp(x=px, y=py), lambda: da.interp(x=px, y=py, method="cubic"), "p")
    raises_as_xarray(lambda: da.splinelab.interp(x=np.ones((2, 2))), lambda: da.interp(x=np.ones((2, 2))), "x")


def test_datetime_axis_with_numbers_and_unknown_method():
    da = xr.DataArray(np.arange(6.0), dims="time",
                      coords={"time": np.datetime64("2020-01-01") + np.arange(6) * np.timedelta64(1, "D")})
    raises_as_xarray(lambda: da.splinelab.interp(time=[1.5]), lambda: da.interp(time=[1.5]), "datetime")
    raises_as_xarray(lambda: da.splinelab.interp(time=da.time[:2], method="spline3"),
                     lambda: da.interp(time=da.time[:2], method="spline3"), "spline3")


def test_missing_xarray_says_how_to_install():
    code = ("import sys; sys.modules['xarray'] = None\n"
            "try:\n    import splinelab.xarray\nexcept ImportError as e:\n    print(e)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "pip install splinelab[xarray]" in out


# ---------------------------------------------------------------- dask


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cx=st.sampled_from([2, 4, 13]), cy=st.sampled_from([3, 5, 11]), ct=st.integers(1, 3), method=st.sampled_from(METHODS),
       pointwise=st.booleans(), both=st.booleans())
def test_dask_result_is_lazy_and_equals_the_in_memory_one(cx, cy, ct, method, pointwise, both):
    """Property: any chunking gives the in-memory numbers bit for bit,
    lazily (test_xarray_chunking.py: more chunkings, fills, NaN, lazy
    coordinates)."""
    da = cube(False)
    xs, ys = targets(da)
    if pointwise:
        kw = dict(x=xr.DataArray(xs[:5], dims="p"), y=xr.DataArray(ys[:5], dims="p"))
    else:
        kw = dict(x=xs, y=ys) if both else dict(x=xs)
    ref = da.splinelab.interp(method=method, **kw)
    lazy = da.chunk(x=cx, y=cy, t=ct).splinelab.interp(method=method, **kw)
    assert isinstance(lazy.data, da_mod.Array)
    same_labels(lazy, ref)
    assert lazy.values.tobytes() == ref.values.tobytes()


def test_dask_dataset_mode_and_whole_lines_equal_the_in_memory_ones():
    """The other dask routes: a Dataset (variables with and without the
    interpolated dims), ``mode=`` on certified windows, and ``mode=`` on
    whole lines along the chunked axes ('grid-wrap', read whole)."""
    da = cube(True)
    ds = xr.Dataset({"temp": da, "flat": ("t", [1.0, 2.0, 3.0]), "ints": ("x", np.arange(13))})
    kw = dict(x=[0.5, 2.0, 4.5], y=xr.DataArray([1.0, -1.5], dims="q"))
    lazy, ref = ds.chunk(x=4, t=2).splinelab.interp(**kw), ds.splinelab.interp(**kw)
    assert isinstance(lazy.temp.data, da_mod.Array)
    xr.testing.assert_identical(lazy.compute(), ref)
    pts = dict(x=xr.DataArray([0.3, 5.9], dims="p"), y=xr.DataArray([-1.9, 2.7], dims="p"))
    lazy = da.chunk(x=5, y=4).splinelab.interp(mode="mirror", **pts)
    assert rel(lazy.values, da.splinelab.interp(mode="mirror", **pts).values) <= 1e-13
    lazy = da.chunk(x=5, y=4).splinelab.interp(mode="grid-wrap", **pts)
    assert np.array_equal(lazy.values, da.splinelab.interp(mode="grid-wrap", **pts).values)


class CountingArray:
    """An array-like that counts the elements its ``__getitem__`` reads, by input chunk."""

    def __init__(self, values, chunks):
        self.values, self.chunks = values, chunks
        self.shape, self.dtype, self.ndim = values.shape, values.dtype, values.ndim
        self.reads = {}
        self.lock = threading.Lock()

    def __getitem__(self, key):
        out = self.values[key]
        starts = [s.start or 0 for s in key]
        stops = [s.stop if s.stop is not None else n for s, n in zip(key, self.shape)]
        chunk_ids = [tuple(range(a // c, (b - 1) // c + 1)) for a, b, c in zip(starts, stops, self.chunks)]
        with self.lock:
            for cid in np.ndindex(*[len(c) for c in chunk_ids]):
                k = tuple(ids[i] for ids, i in zip(chunk_ids, cid))
                self.reads[k] = self.reads.get(k, 0) + 1
        return out


def counted(shape, chunks, method, points, tol=None):
    values = np.random.default_rng(shape[0]).normal(size=shape)
    arr = CountingArray(values, chunks)
    lazy = xr.DataArray(da_mod.from_array(arr, chunks=chunks, lock=False, asarray=True), dims=("time", "y", "x"),
                        coords={d: np.arange(n, dtype=float) for d, n in zip(("time", "y", "x"), shape)})
    out = lazy.splinelab.interp(method=method, tol=tol, **points)
    assert not arr.reads, "the accessor read data before compute"
    got = out.values
    ref = xr.DataArray(values, dims=lazy.dims, coords=lazy.coords).splinelab.interp(method=method, **points)
    assert rel(got, ref.values) <= max(tol or 0.0, 1e-13) * np.abs(values).max() / np.abs(ref.values).max()
    return arr.reads


def test_local_methods_read_only_the_chunks_their_windows_touch():
    """A few points from a 400x40x40 array in 40x20x20 chunks (40 chunks):
    linear and pchip read only the chunks around the points, each once."""
    rng = np.random.default_rng(3)
    n = 4
    pts = dict(time=xr.DataArray(rng.uniform(50, 350, n), dims="p"), y=xr.DataArray(rng.uniform(5, 15, n), dims="p"),
               x=xr.DataArray(rng.uniform(5, 15, n), dims="p"))
    for method, halo in (("linear", 0), ("pchip", 2)):
        reads = counted((400, 40, 40), (40, 20, 20), method, pts)
        assert max(reads.values()) == 1
        near = {(int(t) // 40 + d, 0, 0) for t in pts["time"].values for d in (-1, 0, 1)
                if 0 <= (int(t) + d * (halo + 1)) // 40 * 40 < 400}
        assert set(reads) <= near and len(reads) <= 3 * n


def spline_points(rng, n=3):
    return dict(time=xr.DataArray(rng.uniform(0, 199, n), dims="p"), y=xr.DataArray(rng.uniform(0, 19, n), dims="p"),
                x=xr.DataArray(rng.uniform(0, 19, n), dims="p"))


def test_splines_read_only_their_certified_windows():
    """Cubic and quintic on a chunked time axis (200 samples in chunks of
    10) with y, x interpolated too: each point reads the chunks its
    certified window touches (a few), each once; a looser tolerance reads
    fewer."""
    pts = spline_points(np.random.default_rng(4))
    for method, most in (("cubic", 3 * 4), ("quintic", 3 * 6)):
        reads = counted((200, 20, 20), (10, 20, 20), method, pts)
        assert max(reads.values()) == 1 and len(reads) <= most, sorted(reads)
    tight = counted((200, 20, 20), (10, 20, 20), "cubic", pts)
    loose = counted((200, 20, 20), (10, 20, 20), "cubic", pts, tol=1e-4)
    assert len(loose) < len(tight)


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**16), method=st.sampled_from(["cubic", "quintic"]),
       tol=st.sampled_from([1e-14, 1e-10, 1e-6]), chunk=st.integers(5, 40))
def test_window_truncation_is_within_its_bound(seed, method, tol, chunk):
    """Property: on a jittered axis of any chunking, the windowed spline is
    within tol * max|data| of the whole-grid one (plus the rounding of
    the two computations: a few ulps of max|data|, or of the value itself
    where extrapolation makes it larger)."""
    rng = np.random.default_rng(seed)
    n = 120
    t = jittered(0.0, 50.0, n, rng)
    data = xr.DataArray(rng.normal(size=(n, 6)), dims=("t", "z"), coords={"t": t, "z": np.arange(6.0)})
    kw = dict(t=xr.DataArray(rng.uniform(-1.0, 51.0, 7), dims="p"), z=xr.DataArray(rng.uniform(0, 5, 7), dims="p"))
    whole = data.splinelab.interp(method=method, kwargs={"fill_value": None}, **kw)
    lazy = data.chunk(t=chunk).splinelab.interp(method=method, kwargs={"fill_value": None}, tol=tol, **kw)
    scale = np.abs(data.values).max()
    rounding = 1e-14 * np.maximum(scale, np.abs(whole.values))
    assert (np.abs(lazy.values - whole.values) <= tol * scale + rounding).all()


@pytest.mark.parametrize("mode", ["mirror", "reflect", "constant", "wrap"])
def test_mode_reads_certified_windows(mode):
    """``mode=`` on a chunked axis (400 samples in chunks of 20): linear
    reads only the chunks under its points' cells; cubic reads its points'
    regions with the certified overlap and, for scipy's missing-sample rule
    (a non-finite sample makes its column NaN), one streaming pass: each
    chunk once. Within ``splinelab.dask.bound`` of the whole-line result,
    a NaN column as there."""
    import splinelab.dask as sld
    values = np.random.default_rng(7).normal(size=(400, 12, 3))
    values[5, 3, 2] = np.nan
    pts = dict(time=xr.DataArray([100.3, 301.7, -4.0], dims="p"), y=xr.DataArray([2.5, 7.1, 0.4], dims="p"))
    coords = {"time": np.arange(400.0), "y": np.arange(12.0), "x": np.arange(3.0)}
    whole = xr.DataArray(values, dims=("time", "y", "x"), coords=coords)
    for method in ("linear", "cubic"):
        arr = CountingArray(values, (20, 12, 3))
        lazy = xr.DataArray(da_mod.from_array(arr, chunks=(20, 12, 3), lock=False, asarray=True),
                            dims=("time", "y", "x"), coords=coords)
        got = lazy.splinelab.interp(method=method, mode=mode, **pts).values
        ref = whole.splinelab.interp(method=method, mode=mode, **pts).values
        assert np.array_equal(np.isnan(got), np.isnan(ref)) and np.isnan(ref[:, 2]).all() == (method == "cubic")
        bound = sld.bound(3, sld.DEFAULT_TOL, 2) * np.nanmax(np.abs(values)) if method == "cubic" else 1e-15
        assert np.nanmax(np.abs(got - ref)) <= bound + 1e-14
        # each chunk read once; linear: the 1 or 2 chunks under each point's region, of 20
        assert max(arr.reads.values()) == 1
        assert len(arr.reads) == 20 if method == "cubic" else len(arr.reads) <= 6


@pytest.mark.parametrize("k", [3, 5])
def test_narrowed_windows_are_those_of_a_second_solve(k):
    """The windows cut once at a small tolerance and narrowed to a larger
    one (one solve per chunked axis) are exactly those the larger one cuts
    from its own solve: the same bounds, the same weights."""
    from splinelab._xarray_dask import _narrowed, _windows_of
    rng = np.random.default_rng(6 + k)
    x = jittered(0.0, 300.0, 301, rng)
    q = np.r_[-2.0, rng.uniform(0, 300, 40), 0.0, 300.0, 301.5]
    lo, hi, w, ltail, rtail, _ = _windows_of(x, k, q, 1e-17)
    for tol in (1e-16, 1e-13, 1e-9, 1e-3):
        lo2, hi2, w2 = _narrowed(lo, w, ltail, rtail, tol)
        lo3, hi3, w3, _, _, _ = _windows_of(x, k, q, tol)
        assert np.array_equal(lo2, lo3) and np.array_equal(hi2, hi3)
        assert all(np.array_equal(a, b) for a, b in zip(w2, w3))
    assert (hi3 - lo3).sum() < (hi - lo).sum() / 2  # narrowed, not kept


def test_cardinal_weights_are_the_spline():
    """W @ y is the not-a-knot spline at the points (scipy's make_interp_spline), for any y."""
    from scipy.interpolate import make_interp_spline

    from splinelab._xarray_dask import cardinal_weights
    rng = np.random.default_rng(5)
    x = jittered(0.0, 10.0, 40, rng)
    q = np.r_[-0.5, rng.uniform(0, 10, 9), 10.5]
    for k in (3, 5):
        W = cardinal_weights(x, k, q)
        y = rng.normal(size=(40, 3))
        ref = make_interp_spline(x, y, k=k)(q)   # up to 750 at the extrapolated ends
        assert (np.abs(W @ y - ref) <= 1e-14 * np.maximum(np.abs(y).max(), np.abs(ref))).all()


# ---------------------------------------------------------------- figures


def figures():
    print("splinelab accessor vs xarray 2026.9.0's interp (relative to max|data|)")
    for uniform in (True, False):
        for method in METHODS:
            da = cube(uniform)
            xs, _ = targets(da)
            one = rel(da.splinelab.interp(x=xs, method=method), da.interp(x=xs, method=method))
            line = f"{'uniform' if uniform else 'jittered':>8} {method:>8}  1-D vs xarray {one:8.1e}"
            if method in DEGREE:
                ours, theirs = spline_distances(method, uniform)
                line += f"  2-D: ours vs exact {ours:8.1e}, xarray vs exact {theirs:8.1e}"
            else:
                xs2, ys2 = targets(da)
                two = rel(da.splinelab.interp(x=xs2, y=ys2, method=method), da.interp(x=xs2, y=ys2, method=method))
                line += f"  2-D vs xarray {two:8.1e}"
            print(line)


if __name__ == "__main__":
    figures()
