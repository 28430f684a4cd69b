"""The splinelab accessor on cftime time axes (non-standard calendars,
issue 51) against xarray's own ``interp`` and independent references.

xarray interpolates a cftime axis as float nanoseconds after the axis'
minimum (``missing._floatize_x``: the differences' ``total_seconds``).
References: xarray 2026.9.0's ``interp`` at run time (labels, exceptions,
and numbers where scipy's are exact), and scipy on the axis as cftime
encodes it (``cftime.num2date`` of whole seconds: the seconds are the
exact float axis, found without the accessor's or xarray's arithmetic);
"cubic" and "quintic" along two dimensions against the exact spline
(test_rgi.exact_spline), where xarray's ``interpn`` solves iteratively.
cftime is a test extra: without it these tests fail saying how to install it.
"""

import subprocess
import sys

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator, interp1d, make_interp_spline
from test_local_route import _extra
from test_rgi import exact_spline
from test_xarray import DEGREE, METHODS, da_mod, jittered, raises_as_xarray, rel, same_labels, xr

CALENDARS = ["noleap", "360_day", "all_leap", "julian", "proleptic_gregorian", "standard"]
UNITS = "seconds since 2000-01-01 00:00:00"


@pytest.fixture
def cftime():
    return _extra("cftime")


def dates(cftime, seconds, calendar):
    """Whole seconds after 2000-01-01 as cftime dates of ``calendar``."""
    return cftime.num2date(np.asarray(seconds, dtype=np.int64), UNITS, calendar=calendar)


def series(cftime, calendar, n=40, seed=0, uniform=False):
    """(time, lat) data on a cftime axis over ~14 months (across February
    and, in all_leap/julian/gregorian, 2000-02-29), its axis in seconds."""
    rng = np.random.default_rng(seed)
    days = np.linspace(0.0, 420.0, n) if uniform else jittered(0.0, 420.0, n, rng)
    secs = np.round(days * 86400.0)   # whole seconds: exact as floats and as dates
    lat = np.linspace(-30.0, 30.0, 7)
    v = np.sin(secs / 3e6)[:, None] * np.cos(np.deg2rad(lat))[None, :] + rng.normal(scale=0.1, size=(n, 7))
    da = xr.DataArray(v, dims=("time", "lat"), name="tas", attrs={"units": "K"},
                      coords={"time": ("time", dates(cftime, secs, calendar), {"axis": "T"}), "lat": lat})
    return da, secs


def new_seconds(secs, k=9, seed=1):
    """Whole seconds inside the axis, both ends included."""
    rng = np.random.default_rng(seed)
    return np.r_[secs[0], np.round(rng.uniform(secs[0], secs[-1], k - 2)), secs[-1]]


def scipy_1d(method, x, y, q):
    """scipy's own interpolator of each method on the float axis (xarray's along one dimension)."""
    if method == "pchip":
        return PchipInterpolator(x, y, axis=0, extrapolate=False)(q)
    if method == "nearest":
        return interp1d(x, y, kind="nearest", axis=0)(q)
    return make_interp_spline(x, y, k={"linear": 1, "slinear": 1, **DEGREE}[method], axis=0)(q)


# ---------------------------------------------------------------- numbers


@pytest.mark.parametrize("calendar", CALENDARS)
def test_axis_floats_are_xarrays_to_the_bit(cftime, calendar):
    """The float axis and new coordinates (microseconds too) are xarray's
    own conversion (``Variable._to_numeric`` with the axis' minimum), bit
    for bit, and the calendar's elapsed seconds (cftime's encoding) times 1e9."""
    from datetime import timedelta

    from splinelab.xarray import _float_axes
    da, secs = series(cftime, calendar)
    qs = new_seconds(secs)
    q = dates(cftime, qs, calendar) + np.array([timedelta(microseconds=m) for m in range(0, 9 * 123457, 123457)])
    (x,), (new,) = _float_axes([da.time.values], [q])
    t0 = da.time.values.min()
    assert np.array_equal(x, da.time.variable._to_numeric(offset=t0, dtype=np.float64).values)
    assert np.array_equal(new, xr.Variable("t", q)._to_numeric(offset=t0, dtype=np.float64).values)
    assert np.array_equal(x, (secs - secs[0]) * 1e9)
    assert np.abs(new - ((qs - secs[0]) * 1e9 + np.arange(9) * 123457e3)).max() <= 1e-16 * new.max()


@pytest.mark.parametrize("calendar", CALENDARS)
@pytest.mark.parametrize("method", METHODS)
def test_one_dimension_is_xarrays_and_scipys(cftime, method, calendar):
    """Along time, every method: xarray's numbers and labels (the time
    coordinate a CFTimeIndex of the calendar), and scipy's on the seconds."""
    da, secs = series(cftime, calendar, uniform=calendar == "noleap")
    qs = new_seconds(secs)
    q = dates(cftime, qs, calendar)
    ours, theirs = da.splinelab.interp(time=q, method=method), da.interp(time=q, method=method)
    same_labels(ours, theirs)
    assert isinstance(ours.indexes["time"], xr.CFTimeIndex) and ours.indexes["time"].calendar == calendar
    assert rel(ours, theirs) <= 1e-12
    assert rel(ours, scipy_1d(method, secs, da.values, qs)) <= 1e-12
    outside = dates(cftime, [secs[0] - 3600, secs[-1] + 3600], calendar)   # NaN, as xarray
    assert rel(da.splinelab.interp(time=outside, method=method), da.interp(time=outside, method=method)) == 0.0


@pytest.mark.parametrize("calendar", ["360_day", "julian"])
@pytest.mark.parametrize("method", ["linear", "nearest", "slinear", "pchip"])
def test_two_dimensions_are_xarrays_where_scipy_is_exact(cftime, method, calendar):
    """time and lat together, orthogonal and pointwise (xarray's interpn)."""
    da, secs = series(cftime, calendar)
    q = dates(cftime, new_seconds(secs, 5), calendar)
    lats = np.array([-30.0, -12.5, 0.3, 17.0, 30.0])
    for kw in (dict(time=q, lat=lats), dict(time=xr.DataArray(q, dims="p"), lat=xr.DataArray(lats, dims="p"))):
        ours, theirs = da.splinelab.interp(method=method, **kw), da.interp(method=method, **kw)
        same_labels(ours, theirs)
        assert rel(ours, theirs) <= 1e-12


@pytest.mark.parametrize("calendar", ["noleap", "all_leap"])
@pytest.mark.parametrize("method", ["cubic", "quintic"])
def test_two_dimensions_splines_are_the_exact_spline(cftime, method, calendar):
    """time and lat together: the exact tensor-product spline on (seconds, lat),
    orthogonal and pointwise; xarray's labels."""
    da, secs = series(cftime, calendar)
    qs = new_seconds(secs, 5)
    lats = np.array([-30.0, -12.5, 0.3, 17.0, 30.0])
    spl = exact_spline((secs, da.lat.values), da.values, DEGREE[method])
    T, L = np.meshgrid(qs, lats, indexing="ij")
    q = dates(cftime, qs, calendar)
    ortho = da.splinelab.interp(time=q, lat=lats, method=method)
    same_labels(ortho, da.interp(time=q, lat=lats, method=method), coord_tol=None)
    assert rel(ortho, spl(np.stack([T.ravel(), L.ravel()], -1)).reshape(T.shape)) <= 1e-12
    pts = da.splinelab.interp(time=xr.DataArray(q, dims="p"), lat=xr.DataArray(lats, dims="p"), method=method)
    assert pts.dims == ("p",)
    assert rel(pts, spl(np.stack([qs, lats], -1))) <= 1e-12


@pytest.mark.parametrize("calendar", ["360_day", "noleap", "julian"])
def test_date_strings_parse_into_the_calendar(cftime, calendar):
    """Strings on a cftime axis are dates of the index's type, partial ones
    ("2000-03") their start, as xarray; "2000-02-30" exists in 360_day only."""
    da, secs = series(cftime, calendar)
    strings = ["2000-01-20", "2000-03", "2000-06-15T12:30"]
    ours, theirs = da.splinelab.interp(time=strings), da.interp(time=strings, method="cubic")
    same_labels(ours, theirs)
    assert rel(ours, theirs) <= 1e-12
    date = type(da.time.values[0])
    exact = [date(2000, 1, 20), date(2000, 3, 1), date(2000, 6, 15, 12, 30)]
    assert list(ours.time.values) == exact
    qs = cftime.date2num(exact, UNITS, calendar=calendar)
    assert rel(ours, make_interp_spline(secs, da.values, k=3)(qs)) <= 1e-12
    one = da.splinelab.interp(time="2000-02-28", method="linear")
    same_labels(one, da.interp(time="2000-02-28"))
    assert one.time.values == date(2000, 2, 28)
    if calendar == "360_day":
        feb30 = da.splinelab.interp(time=["2000-02-30"], method="linear")
        assert rel(feb30, da.interp(time=["2000-02-30"])) <= 1e-12


@pytest.mark.parametrize("method", ["linear", "cubic"])
def test_vectorised_times_and_cftime_coordinates_as_xarray(cftime, method):
    """A time per latitude (xarray's vectorised form); cftime-valued
    coordinates along time (a date and its bounds) reindexed as xarray."""
    da, secs = series(cftime, "noleap")
    q = dates(cftime, np.round(np.random.default_rng(3).uniform(secs[0], secs[-1], 7)), "noleap")
    per_lat = xr.DataArray(q, dims="lat", coords={"lat": da.lat.values})
    ours, theirs = da.splinelab.interp(time=per_lat, method=method), da.interp(time=per_lat, method=method)
    same_labels(ours, theirs)
    assert rel(ours, theirs) <= 1e-12
    when = da.time.values
    ds = da.to_dataset().assign_coords(aux=("time", when), bnds=(("time", "nv"), np.stack([when, when], -1)))
    ours, theirs = ds.splinelab.interp(time=q, method=method), ds.interp(time=q, method=method)
    for name in ("time", "aux", "bnds"):
        xr.testing.assert_identical(ours[name].variable, theirs[name].variable)


def test_unsorted_axis_is_sorted_first_as_xarray(cftime):
    """A descending cftime axis is sorted first (xarray's ``sortby``)."""
    da, secs = series(cftime, "julian")
    q = dates(cftime, new_seconds(secs), "julian")
    flipped = da.isel(time=slice(None, None, -1))
    for method in ("linear", "cubic"):
        ours = flipped.splinelab.interp(time=q, method=method)
        same_labels(ours, flipped.interp(time=q, method=method))
        assert rel(ours, da.splinelab.interp(time=q, method=method)) == 0.0


def test_mode_on_a_uniform_cftime_axis_is_ndimages(cftime):
    """``mode=`` on a daily noleap axis: scipy.ndimage on the index coordinates (days)."""
    from scipy import ndimage
    days = np.arange(60)
    da = xr.DataArray(np.sin(days / 5.0), dims="time", coords={"time": dates(cftime, days * 86400, "noleap")})
    qd = np.array([-1.25, 0.5, 27.75, 58.5, 60.5])
    ours = da.splinelab.interp(time=dates(cftime, np.round(qd * 86400), "noleap"), mode="mirror")
    assert rel(ours, ndimage.map_coordinates(da.values, [qd], order=3, mode="mirror")) <= 1e-12


# ---------------------------------------------------------------- dask


@pytest.mark.parametrize("calendar", ["noleap", "360_day"])
@pytest.mark.parametrize("method", METHODS)
def test_dask_chunked_along_time_equals_the_in_memory_result(cftime, method, calendar):
    """Chunked along the cftime axis: lazy, the in-memory numbers bit for
    bit, for orthogonal and pointwise indexers and strings."""
    da, secs = series(cftime, calendar)
    chunked = da.chunk(time=6, lat=4)
    q = dates(cftime, new_seconds(secs), calendar)
    lats = np.linspace(-29.0, 29.0, len(q))
    for kw in (dict(time=q), dict(time=q, lat=lats[:3]), dict(time=xr.DataArray(q, dims="p"),
                                                              lat=xr.DataArray(lats, dims="p")),
               dict(time=["2000-02-01", "2000-09-15"])):
        lazy, ref = chunked.splinelab.interp(method=method, **kw), da.splinelab.interp(method=method, **kw)
        assert isinstance(lazy.data, da_mod.Array)
        same_labels(lazy, ref)
        assert lazy.values.tobytes() == ref.values.tobytes()


def test_dask_dataset_with_cftime_values_equals_xarrays(cftime):
    """A chunked Dataset with a numeric and a cftime-valued variable along time."""
    da, secs = series(cftime, "noleap")
    ds = xr.Dataset({"tas": da, "when": ("time", da.time.values)}).chunk(time=8)
    q = dates(cftime, new_seconds(secs), "noleap")
    ours, theirs = ds.splinelab.interp(time=q, method="linear"), ds.interp(time=q, method="linear")
    assert isinstance(ours.tas.data, da_mod.Array)
    xr.testing.assert_allclose(ours.compute(), theirs.compute(), rtol=1e-12)
    xr.testing.assert_identical(ours.when.compute(), theirs.when.compute())


# ---------------------------------------------------------------- cftime values


def test_cftime_valued_variables_follow_xarray(cftime):
    """A cftime-valued variable is not interpolated: along its dimension
    it is reindexed (``method_non_numeric``, nearest by default), dropped
    under pointwise indexers, kept where not interpolated; as a DataArray
    it is xarray's TypeError."""
    da, secs = series(cftime, "360_day")
    when = da.time.values
    ds = xr.Dataset({"tas": da, "when": ("time", when), "stamp": ("lat", when[:7])})
    q = dates(cftime, new_seconds(secs), "360_day")
    for kw in (dict(time=q), dict(lat=[0.5, 10.0]), dict(time=q, lat=[0.5]),
               dict(time=xr.DataArray(q[:3], dims="p"), lat=xr.DataArray([0.0, 5.0, 9.0], dims="p"))):
        ours, theirs = ds.splinelab.interp(method="linear", **kw), ds.interp(method="linear", **kw)
        assert set(ours.data_vars) == set(theirs.data_vars), kw
        for name in ("when", "stamp"):
            if name in theirs:
                xr.testing.assert_identical(ours[name].variable, theirs[name].variable)
        assert rel(ours.tas, theirs.tas) <= 1e-12
    # nearest: 2000-01-02 is nearer the first sample (2000-01-01) than the second (6.5 days on or more)
    ours = ds.splinelab.interp(time=["2000-01-02"], method_non_numeric="nearest")
    assert ours.when.values[0] == when[0]
    raises_as_xarray(lambda: ds.when.splinelab.interp(time=q), lambda: ds.when.interp(time=q), "object")


# ---------------------------------------------------------------- bad input


def test_bad_new_coordinates_raise_as_xarray(cftime):
    """Numbers (xarray's TypeError, the variable named), unparseable
    strings and days the calendar lacks (ValueError), dates of another
    calendar (TypeError), numpy datetimes (numpy's UFuncTypeError)."""
    da, _ = series(cftime, "noleap")
    for bad, word in (([1.5e6], "datetime"), (xr.DataArray(["2000-01-03"], dims="p"), "datetime"),
                      (["soon"], "soon"), (["2000-02-29"], "day"),
                      ([cftime.Datetime360Day(2000, 1, 3)], "calendars"),
                      ([np.datetime64("2000-01-03")], "subtract")):
        raises_as_xarray(lambda: da.splinelab.interp(time=bad), lambda: da.interp(time=bad, method="cubic"), word)
    with pytest.raises(TypeError, match=r"(?s)datetime.*\(time: 1\)"):
        da.splinelab.interp(time=[1.5e6])


def test_without_cftime_the_accessor_works_for_the_rest():
    """cftime missing: numeric and datetime64 axes still interpolate (in a subprocess)."""
    code = (
        "import sys; sys.modules['cftime'] = None\n"
        "import numpy as np, xarray as xr, splinelab.xarray\n"
        "t = np.datetime64('2020-01-01') + np.arange(8) * np.timedelta64(1, 'D')\n"
        "da = xr.DataArray(np.arange(8.0) ** 2, dims='time', coords={'time': t})\n"
        "a = da.splinelab.interp(time=['2020-01-03T12'], method='cubic').item()\n"
        "b = xr.DataArray(da.values, dims='x', coords={'x': np.arange(8.0)}).splinelab.interp(x=2.5).item()\n"
        "print(a, b)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert [float(v) for v in out] == pytest.approx([6.25, 6.25], rel=1e-14)


# ---------------------------------------------------------------- figures


def figures():
    """The agreement per calendar and method (relative): along time against
    xarray and scipy on the seconds; on (time, lat) against xarray, or for
    the splines ours and xarray's against the exact spline; chunked
    (time 6, lat 4) against in memory. The rows agree across calendars by
    construction: each calendar's dates are the same elapsed seconds."""
    import cftime
    print("splinelab accessor on cftime axes, xarray 2026.9.0 (relative to max|result|)")
    lats = np.array([-30.0, -12.5, 0.3, 17.0, 30.0])
    for calendar in CALENDARS:
        da, secs = series(cftime, calendar)
        qs = new_seconds(secs)
        q = dates(cftime, qs, calendar)
        T, L = np.meshgrid(qs[:5], lats, indexing="ij")
        for method in METHODS:
            ours = da.splinelab.interp(time=q, method=method)
            line = (f"{calendar:>20} {method:>8}  time: vs xarray {rel(ours, da.interp(time=q, method=method)):7.1e}"
                    f", vs scipy {rel(ours, scipy_1d(method, secs, da.values, qs)):7.1e}")
            two = da.splinelab.interp(time=q[:5], lat=lats, method=method)
            theirs = da.interp(time=q[:5], lat=lats, method=method)
            if method in DEGREE:
                exact = exact_spline((secs, da.lat.values), da.values, DEGREE[method])(
                    np.stack([T.ravel(), L.ravel()], -1)).reshape(T.shape)
                line += f"  time+lat: vs exact {rel(two, exact):7.1e} (xarray {rel(theirs, exact):7.1e})"
            else:
                line += f"  time+lat: vs xarray {rel(two, theirs):7.1e}"
            lazy = da.chunk(time=6, lat=4).splinelab.interp(time=q[:5], lat=lats, method=method)
            print(line + f"  chunked vs in memory {rel(lazy.values, two.values):7.1e}")


if __name__ == "__main__":
    figures()
