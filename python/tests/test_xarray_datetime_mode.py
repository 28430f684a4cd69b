"""datetime64- and timedelta64-valued variables under the accessor's
``mode=`` (issue 51), converted as xarray's ``interp`` converts them: the
integers of the variable's own unit as float64 (NaT as NaN), interpolated,
rounded back (NaN as NaT).

References: scipy's ``ndimage.map_coordinates`` on those float64 integers at
the index coordinates, in the same mode with cval NaN (the accessor's
``mode=`` is ndimage's spline on a uniform axis), rounded back as xarray
rounds; and xarray's own ``interp`` where the two agree by construction
(degree 0 and 1 inside the grid, where no boundary mode applies, and NaT
outside for 'constant'). Dask: lazy, and the chunked result against the
in-memory one within the certified bound.

Float64 holds the integers of a 'ns' datetime of 2020 (about 1.6e18) to 256
ns (xarray's conversion), so 'ns' values are compared within 4e-15 of the
largest integer (6400 ns); 's' values (about 1.6e9) exactly.
"""

import numpy as np
import pytest

xr = pytest.importorskip("xarray", reason="pip install splinelab[xarray]")
dask_array = pytest.importorskip("dask.array")
ndi = pytest.importorskip("scipy.ndimage")

import splinelab.xarray  # noqa: E402,F401  (registers the accessor)

MODES = ["mirror", "reflect", "nearest", "wrap", "grid-wrap", "grid-mirror", "constant", "grid-constant"]
ORDER = {"nearest": 0, "linear": 1, "cubic": 3, "quintic": 5}
NAT = np.iinfo(np.int64).min


def dataset(unit, n=40, seed=5):
    """Datetime and timedelta variables on a uniform axis x (step 0.5)."""
    rng = np.random.default_rng(seed)
    steps = np.cumsum(rng.integers(1, 10**5, n)).astype(f"timedelta64[{unit}]")
    if unit == "ns":
        steps = steps * 10**9 + rng.integers(0, 10**9, n).astype("timedelta64[ns]")
    when = np.datetime64("2020-01-01T00", unit) + steps
    x = 3.0 + 0.5 * np.arange(n)
    return xr.Dataset({"when": ("x", when), "lag": ("x", when - when[n // 2])}, coords={"x": x},
                      attrs={"title": "t"})


def new_x(n=40):
    """Inside the axis (no half-steps: no ties for 'nearest'), and outside it."""
    x0, x1 = 3.0, 3.0 + 0.5 * (n - 1)
    inside = np.array([3.1, 4.37, 7.8, 12.01, 17.6, x1 - 0.2])
    return inside, np.concatenate([inside, [x0 - 1.3, x1 + 0.7, x1 + 6.2]])


def scipy_reference(values, xs, method, mode):
    """ndimage's spline of the float64 integers at the index coordinates of
    ``xs`` (x = 3 + 0.5 i), cval NaN, rounded back as xarray rounds."""
    ints = values.view(np.int64)
    f = np.where(ints != NAT, ints.astype(np.float64), np.nan)
    idx = ((np.asarray(xs) - 3.0) / 0.5)[None, :]
    v = ndi.map_coordinates(f, idx, order=ORDER[method], mode=mode, cval=np.nan, output=np.float64)
    back = np.where(np.isnan(v), NAT, np.round(np.nan_to_num(v)).astype(np.int64))
    return back.view(values.dtype)


def steps(a, b):
    """Per element |a - b| in the values' units (NaT only against NaT)."""
    ia, ib = np.asarray(a).view(np.int64), np.asarray(b).view(np.int64)
    assert ((ia == NAT) == (ib == NAT)).all()
    ok = ib != NAT
    return np.abs(ia[ok].astype(np.float64) - ib[ok].astype(np.float64))


def allowed(values):
    """The comparison's room: 4e-15 of the largest integer (two libraries'
    float64 splines of the same numbers; measured up to 2e-15 with
    timedeltas of 1e15 ns): below one unit for 's' values (exact there),
    6400 ns for 'ns' datetimes of 2020 (25 float64 steps of 256 ns)."""
    return 4e-15 * np.abs(values.view(np.int64)).max().astype(np.float64)


@pytest.mark.parametrize("unit", ["s", "ns"])
@pytest.mark.parametrize("method", ["nearest", "linear", "cubic", "quintic"])
@pytest.mark.parametrize("mode", MODES)
def test_mode_against_scipy(unit, method, mode):
    ds = dataset(unit)
    _, xs = new_x()
    out = ds.splinelab.interp(x=xs, method=method, mode=mode)
    for name in ("when", "lag"):
        assert out[name].dtype == ds[name].dtype
        ref = scipy_reference(ds[name].values, xs, method, mode)
        assert steps(out[name].values, ref).max(initial=0.0) <= allowed(ds[name].values)
    assert out.attrs == ds.attrs and list(out.x.values) == list(xs)


@pytest.mark.parametrize("unit", ["s", "ns"])
@pytest.mark.parametrize("method", ["nearest", "linear"])
@pytest.mark.parametrize("mode", MODES)
def test_mode_inside_equals_xarray(unit, method, mode):
    """Degrees 0 and 1 inside the grid read no boundary: xarray's interp
    (interp1d on the same float64 integers) gives the same values."""
    ds = dataset(unit)
    xs, _ = new_x()
    ours, theirs = ds.splinelab.interp(x=xs, method=method, mode=mode), ds.interp(x=xs, method=method)
    for name in ("when", "lag"):
        assert ours[name].dtype == theirs[name].dtype
        assert steps(ours[name].values, theirs[name].values).max() <= allowed(ds[name].values)


@pytest.mark.parametrize("method", ["linear", "cubic"])
def test_constant_mode_outside_is_nat_as_xarray(method):
    ds = dataset("s")
    inside, xs = new_x()
    ours, theirs = ds.splinelab.interp(x=xs, method=method, mode="constant"), ds.interp(x=xs, method=method)
    for name in ("when", "lag"):
        np.testing.assert_array_equal(np.isnat(ours[name].values), np.isnat(theirs[name].values))
        assert np.isnat(ours[name].values[len(inside):]).all()


def test_nat_in_the_data_as_scipy_spreads_nan():
    """A NaT sample: NaN in the float64 integers, spread by the prefilter as
    scipy spreads it (every value NaN, so NaT), and read only within the
    window by degrees 0 and 1."""
    ds = dataset("s")
    when = ds["when"].values.copy()
    when[11] = np.datetime64("NaT")
    ds = ds.assign(when=("x", when))
    _, xs = new_x()
    for method in ("nearest", "linear", "cubic"):
        out = ds.splinelab.interp(x=xs, method=method, mode="mirror")
        ref = scipy_reference(when, xs, method, "mirror")
        np.testing.assert_array_equal(np.isnat(out["when"].values), np.isnat(ref))
        assert steps(out["when"].values, ref).max(initial=0.0) == 0.0


@pytest.mark.parametrize("unit", ["s", "ns"])
@pytest.mark.parametrize("mode", ["mirror", "constant", "wrap", "grid-wrap", "nearest"])
@pytest.mark.parametrize("chunk", [7, 40])
def test_mode_lazy_on_dask(unit, mode, chunk):
    """On dask the datetime variables stay lazy (as xarray keeps them), and
    the chunked result is the in-memory one within the windows' certified
    bound (tol 1e-12 of max|integer|) and the conversion's rounding."""
    ds = dataset(unit)
    _, xs = new_x()
    lazy = ds.chunk({"x": chunk}).splinelab.interp(x=xs, method="cubic", mode=mode)
    assert isinstance(lazy["when"].data, dask_array.Array) and isinstance(lazy["lag"].data, dask_array.Array)
    got, mem = lazy.compute(), ds.splinelab.interp(x=xs, method="cubic", mode=mode)
    for name in ("when", "lag"):
        assert got[name].dtype == mem[name].dtype
        big = np.abs(ds[name].values.view(np.int64)).max().astype(np.float64)
        bound = 1e-12 * big + allowed(ds[name].values)
        assert steps(got[name].values, mem[name].values).max(initial=0.0) <= bound


def test_without_mode_lazy_on_dask_as_xarray():
    """Without ``mode=`` too: lazy on dask, and xarray's values (linear)."""
    ds = dataset("s").chunk({"x": 9})
    xs, _ = new_x()
    ours, theirs = ds.splinelab.interp(x=xs, method="linear"), ds.interp(x=xs, method="linear")
    assert isinstance(ours["when"].data, dask_array.Array)
    xr.testing.assert_identical(ours.compute(), theirs.compute())
