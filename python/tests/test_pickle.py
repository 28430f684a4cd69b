"""Every object splinelab hands to users survives ``pickle`` and
``copy.deepcopy`` with the same bits, and crosses into another process
(``concurrent.futures`` with the spawn start method, a dask.distributed
process worker) with the same bits.

References: the object itself before the round trip (its values, attributes
and messages computed before pickling), compared bit for bit (the bytes of
each array, the bits of each float, NaN included). The objects:
:class:`splinelab.RegularGridInterpolator` for every method (its spline
rebuilt from its samples on unpickling), :class:`splinelab.Interpolant`
(updated samples included), every exception class splinelab defines or
raises (:mod:`splinelab.errors` and the extension's), and the results of
the public functions that return something other than an array
(``check``, ``truncation_width``, ``filter_bound``, ``coefficients``, the
lazy arrays of :mod:`splinelab.dask`).
"""

import concurrent.futures
import copy
import inspect
import multiprocessing
import operator
import os
import pickle
import struct

import numpy as np
import pytest

import splinelab
from splinelab import _splinelab as _ext
from splinelab import errors

RGI_METHODS = ["linear", "nearest", "slinear", "cubic", "quintic", "pchip", "slinear_legacy", "cubic_legacy",
               "quintic_legacy"]
SPLINE_METHODS = {"slinear", "cubic", "quintic"}


def _pickled(obj):
    return pickle.loads(pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL))


def _pickled_protocol_2(obj):
    return pickle.loads(pickle.dumps(obj, protocol=2))


ROUND_TRIPS = {"pickle": _pickled, "pickle-protocol-2": _pickled_protocol_2, "deepcopy": copy.deepcopy}


def assert_same_bits(got, want, where="value"):
    """``got`` is ``want`` bit for bit: arrays by dtype, shape and bytes,
    floats by their IEEE bits (NaN equals NaN of the same payload),
    containers element by element; the message names the first difference."""
    assert type(got) is type(want), f"{where}: type {type(got).__name__} != {type(want).__name__}"
    if isinstance(want, np.ndarray):
        assert got.dtype == want.dtype, f"{where}: dtype {got.dtype} != {want.dtype}"
        assert got.shape == want.shape, f"{where}: shape {got.shape} != {want.shape}"
        if got.tobytes() != want.tobytes():
            diff = np.flatnonzero(got.view(np.uint8).ravel() != want.view(np.uint8).ravel())
            raise AssertionError(f"{where}: bytes differ from byte {diff[0]}:\n got {got!r}\nwant {want!r}")
    elif isinstance(want, float):
        assert struct.pack("<d", got) == struct.pack("<d", want), f"{where}: {got!r} != {want!r}"
    elif isinstance(want, dict):
        assert list(got) == list(want), f"{where}: keys {list(got)} != {list(want)}"
        for k in want:
            assert_same_bits(got[k], want[k], f"{where}[{k!r}]")
    elif isinstance(want, (list, tuple)):
        assert len(got) == len(want), f"{where}: length {len(got)} != {len(want)}"
        for i, (g, w) in enumerate(zip(got, want)):
            assert_same_bits(g, w, f"{where}[{i}]")
    else:
        assert got == want, f"{where}: {got!r} != {want!r}"


# ---------------------------------------------------------------- RegularGridInterpolator


def _grid_case(dtype=np.float64, trailing=(), descending=False):
    """A 7 x 6 grid with uneven spacing, samples of a smooth function plus
    noise (so no method is exact on them), and points inside, outside,
    on a node, and NaN."""
    rng = np.random.default_rng(59)
    x = np.cumsum(rng.uniform(0.5, 1.5, 7))
    y = np.cumsum(rng.uniform(0.5, 1.5, 6))
    v = np.sin(x[:, None]) * np.cos(y[None, :]) + 0.1 * rng.standard_normal((7, 6))
    for m in trailing:
        v = np.stack([v * (j + 1) for j in range(m)], axis=-1)
    if np.dtype(dtype).kind == "c":
        v = v + 1j * np.cos(v)
    v = v.astype(dtype)
    if descending:
        x, v = x[::-1], v[::-1]
    xi = np.array([[x.min() + 0.3, y[0] + 0.7], [np.median(x), np.median(y)], [x[2], y[3]],
                   [x.max() + 0.4, y[1]], [x.min() - 1.0, y.max() + 2.0], [np.nan, y[2]]])
    return (x, y), v, xi


RGI_CASES = {
    "float64": {},
    "float32": {"dtype": np.float32},
    "complex": {"dtype": np.complex128},
    "trailing": {"trailing": (2,)},
    "descending": {"descending": True},
}


def _rgi_and_values(method, case, fill_value):
    points, v, xi = _grid_case(**RGI_CASES[case])
    r = splinelab.RegularGridInterpolator(points, v, method=method, bounds_error=False, fill_value=fill_value)
    return r, xi


# scipy refuses complex values for "pchip" (tested in test_rgi.py): that pair is left out.
RGI_PAIRS = [(m, c) for m in RGI_METHODS for c in RGI_CASES if not (m == "pchip" and c == "complex")]


def _rgi_state(r, xi):
    """What a user reads from an interpolator: its results (the method of
    construction, another method for one call, a derivative), and its
    attributes."""
    state = {"values_at_xi": r(xi), "linear_at_xi": r(xi, method="linear"),
             "grid": r.grid, "values": np.asarray(r.values), "method": r.method, "bounds_error": r.bounds_error,
             "condition": r.condition, "error_bound": r.error_bound}
    if r.method in SPLINE_METHODS:
        state["derivative_at_xi"] = r(xi, nu=(1, 0))
    return state


@pytest.mark.parametrize("trip", list(ROUND_TRIPS))
@pytest.mark.parametrize("method, case", RGI_PAIRS)
def test_regular_grid_interpolator_round_trip_keeps_every_bit(method, case, trip):
    r, xi = _rgi_and_values(method, case, fill_value=None)
    before = _rgi_state(r, xi)
    copied = ROUND_TRIPS[trip](r)
    assert type(copied) is splinelab.RegularGridInterpolator
    assert_same_bits(_rgi_state(copied, xi), before, f"{method}/{case}/{trip}")
    assert_same_bits(_rgi_state(r, xi), before, "the original after the round trip")


@pytest.mark.parametrize("fill_value", [np.nan, 2.5, np.float32(-1.0)])
@pytest.mark.parametrize("method", ["linear", "cubic", "pchip"])
def test_regular_grid_interpolator_fill_value_survives(method, fill_value):
    r, xi = _rgi_and_values(method, "float64", fill_value=fill_value)
    before = r(xi)
    copied = _pickled(r)
    assert_same_bits(copied.fill_value, r.fill_value, "fill_value")
    assert_same_bits(copied(xi), before)


def test_regular_grid_interpolator_bounds_error_survives():
    """A copy refuses a point outside the grid as the original does."""
    points, v, xi = _grid_case()
    r = splinelab.RegularGridInterpolator(points, v, method="cubic")
    copied = _pickled(r)
    for obj in (r, copied):
        with pytest.raises(ValueError, match="out of bounds in dimension 0"):
            obj(xi[3:4])


def test_regular_grid_interpolator_copy_of_a_copy():
    """Twice through pickle (a copy sent on by the process that received
    it) and once through deepcopy: the same bits."""
    r, xi = _rgi_and_values("quintic", "trailing", fill_value=None)
    before = _rgi_state(r, xi)
    assert_same_bits(_rgi_state(copy.deepcopy(_pickled(_pickled(r))), xi), before)


# ---------------------------------------------------------------- Interpolant


def _interpolant_input(dtype=np.float64):
    rng = np.random.default_rng(60)
    return rng.uniform(-1, 1, (20, 17)).astype(dtype)


COORDS = np.array([[0.0, 3.25, 10.5, 19.0, 7.75, 12.125], [0.0, 16.0, 8.5, 2.25, 0.5, 9.0]])

INTERPOLANT_CASES = {
    "cubic-mirror": ({}, {"order": 3, "mode": "mirror"}),
    "linear-nearest": ({}, {"order": 1, "mode": "nearest"}),
    "quintic-tol": ({}, {"order": 5, "mode": "reflect", "tol": 1e-10}),
    "degree-9-constant": ({}, {"order": 9, "mode": "grid-constant", "cval": 0.5}),
    "float32": ({"dtype": np.float32}, {"order": 3}),
}


def _interpolant_state(ip):
    return {"values": ip(COORDS), "derivative": ip(COORDS, derivative=(1, 0)), "shape": ip.shape, "ndim": ip.ndim,
            "order": ip.order, "mode": ip.mode, "truncation": ip.truncation(), "repr": repr(ip)}


@pytest.mark.parametrize("trip", list(ROUND_TRIPS))
@pytest.mark.parametrize("case", list(INTERPOLANT_CASES))
def test_interpolant_round_trip_keeps_every_bit(case, trip):
    input_kwargs, kwargs = INTERPOLANT_CASES[case]
    ip = splinelab.Interpolant(_interpolant_input(**input_kwargs), **kwargs)
    before = _interpolant_state(ip)
    assert_same_bits(_interpolant_state(ROUND_TRIPS[trip](ip)), before, f"{case}/{trip}")


@pytest.mark.parametrize("trip", list(ROUND_TRIPS))
def test_interpolant_updated_samples_survive(trip):
    """The samples changed by ``update`` travel with the copy: its values
    are those of an interpolant built on the changed array (an independent
    reference), and the copy's own updates leave the original alone."""
    a = _interpolant_input()
    ip = splinelab.Interpolant(a, order=3)
    ip.update((slice(4, 7), 9), [0.25, -3.0, 1.5])
    changed = a.copy()
    changed[4:7, 9] = [0.25, -3.0, 1.5]
    want = splinelab.Interpolant(changed, order=3)(COORDS)
    before = ip(COORDS)
    assert_same_bits(before, want, "updated original vs rebuilt")
    copied = ROUND_TRIPS[trip](ip)
    assert_same_bits(copied(COORDS), want, "updated copy vs rebuilt")
    copied.update((10, 8), 100.0)
    assert_same_bits(ip(COORDS), before, "the original after the copy's update")
    assert not np.array_equal(copied(COORDS), before)


def test_interpolant_over_a_lazy_array_round_trip():
    """An interpolant reading a dask array a box at a time (its changed
    samples kept beside it): the same bits after pickling."""
    da = pytest.importorskip("dask.array")
    a = _interpolant_input()
    ip = splinelab.Interpolant(da.from_array(a, chunks=(8, 8)), order=3)
    ip.update((3, 4), 7.0)
    before = ip(COORDS)
    assert_same_bits(_pickled(ip)(COORDS), before)
    assert_same_bits(copy.deepcopy(ip)(COORDS), before)


def test_interpolant_over_a_memory_map_round_trip(tmp_path):
    a = _interpolant_input()
    path = tmp_path / "samples.npy"
    np.save(path, a)
    ip = splinelab.Interpolant(np.load(path, mmap_mode="r"), order=3)
    before = ip(COORDS)
    assert_same_bits(_pickled(ip)(COORDS), before)


# ---------------------------------------------------------------- exceptions


def _exception_classes():
    """Every exception class of :mod:`splinelab.errors` and of the extension."""
    found = {}
    for module in (errors, _ext):
        for name, obj in vars(module).items():
            if inspect.isclass(obj) and issubclass(obj, BaseException) and not name.startswith("_"):
                found[f"{module.__name__}.{name}"] = obj
    return found


EXCEPTIONS = _exception_classes()


def test_the_exception_classes_are_found():
    """The enumeration above sees the classes it must (so the test below
    cannot pass by testing nothing)."""
    names = {c.__name__ for c in EXCEPTIONS.values()}
    assert {"OrderError", "ModeError", "DtypeError", "MappingError", "NonFiniteCoordinateError"} <= names


@pytest.mark.parametrize("trip", list(ROUND_TRIPS))
@pytest.mark.parametrize("name", list(EXCEPTIONS))
def test_exception_round_trip_keeps_class_and_message(name, trip):
    cls = EXCEPTIONS[name]
    e = cls("spline order 200 is not supported")
    e.note = "an attribute set by the raiser"
    copied = ROUND_TRIPS[trip](e)
    assert type(copied) is cls
    assert copied.args == e.args and str(copied) == str(e)
    assert copied.note == e.note
    for base in cls.__mro__:  # still caught where the original is caught
        assert isinstance(copied, base)


@pytest.mark.parametrize("name", list(EXCEPTIONS))
def test_exception_names_an_importable_home(name):
    """pickle finds a class by ``__module__`` and ``__qualname__``: both
    must lead back to the class itself (the extension's classes name
    ``splinelab._splinelab``, the module they live in)."""
    import importlib

    cls = EXCEPTIONS[name]
    module = importlib.import_module(cls.__module__)
    assert getattr(module, cls.__qualname__) is cls


def _raised(call):
    with pytest.raises(Exception) as info:
        call()
    return info.value


RAISED = {
    "OrderError (engine)": lambda: splinelab.map_coordinates(np.ones((5, 5)), [[1.0], [2.0]], order=200),
    "ModeError": lambda: splinelab.spline_filter1d(np.ones(5), mode="bogus"),
    "DtypeError": lambda: splinelab.spline_filter(np.array(["a", "b"])),
    "CoordinateShapeError": lambda: splinelab.Interpolant(np.ones((4, 4)))(np.ones((3, 2))),
    "SequenceLengthError": lambda: splinelab.zoom(np.ones((4, 4)), (2, 2, 2)),
    # Interpolant hands the engine's class to the user for a NaN coordinate
    "NonFiniteCoordinateError (Interpolant)": lambda: splinelab.Interpolant(np.ones((5, 5)))([[np.nan], [1.0]]),
}


@pytest.mark.parametrize("name", list(RAISED))
def test_raised_exceptions_round_trip(name):
    """Exceptions as splinelab raises them (the engine's through the
    extension included) pickle with their class and message."""
    e = _raised(RAISED[name])
    assert type(e).__name__ == name.split()[0]
    copied = _pickled(e)
    assert type(copied) is type(e) and copied.args == e.args and str(copied) == str(e)


# ---------------------------------------------------------------- the other public results


def _public_results():
    s = np.array([1.0, 2.0, 0.5, 3.0, 1.0, 0.0, 2.0, 1.0])
    x = np.array([0.0, 1.0, 2.5, 3.0, 4.5])
    g = np.add.outer(x, x ** 2)
    pts = np.array([[0.5, 1.25], [3.75, 2.0]])
    return {
        "check prefilter": lambda: splinelab.check("prefilter", samples=s, coeffs=splinelab.spline_filter1d(s)),
        "check grid-spline": lambda: splinelab.check(
            "grid-spline", grid=[x, x], samples=g, points=pts,
            values=splinelab.RegularGridInterpolator((x, x), g, method="cubic")(pts)),
        "truncation_width": lambda: splinelab.truncation_width(3, tol=1e-12),
        "filter_bound": lambda: splinelab.filter_bound(5, 1e-10, ndim=2),
        "coefficients float": lambda: splinelab.coefficients(3, count=6),
        "coefficients decimal": lambda: splinelab.coefficients(3, count=3, bits=128),
        "nan_reach": lambda: splinelab.nan_reach(3, 1e-12),
        "spline_gradient": lambda: splinelab.spline_gradient(np.outer(s, s), [[1.5, 2.0], [3.25, 0.5]]),
    }


PUBLIC = _public_results()


@pytest.mark.parametrize("trip", list(ROUND_TRIPS))
@pytest.mark.parametrize("name", list(PUBLIC))
def test_public_results_round_trip(name, trip):
    result = PUBLIC[name]()
    assert_same_bits(ROUND_TRIPS[trip](result), result, name)


def test_every_public_name_is_covered():
    """A new public callable returning an object needs a case here: the
    names of ``__all__`` are the ones above, the array functions (their
    results are numpy arrays) and the classes tested above."""
    arrays = {"spline_filter1d", "spline_filter", "map_coordinates", "spline_gradient", "zoom", "shift", "rotate",
              "affine_transform", "geometric_transform", "interpn"}
    covered = {"RegularGridInterpolator", "Interpolant", "check", "truncation_width", "filter_bound",
               "coefficients", "nan_reach", "MAX_DEGREE"}
    assert set(splinelab.__all__) == arrays | covered


def _dask_lazies():
    """One lazy array of each public function of :mod:`splinelab.dask`,
    both routes, the local NaN policy and float32 arithmetic."""
    da = pytest.importorskip("dask.array")
    import splinelab.dask as sld

    x = _interpolant_input()
    holed = x.copy()
    holed[5, 6] = np.nan
    d, dh = da.from_array(x, chunks=(10, 9)), da.from_array(holed, chunks=(10, 9))
    matrix = np.array([[0.9, 0.1], [-0.2, 1.1]])
    return {
        "spline_filter": sld.spline_filter(d, order=3),
        "spline_filter recursive": sld.spline_filter(d, order=5, route="recursive"),
        "spline_filter1d": sld.spline_filter1d(d, order=3, axis=0, mode="grid-wrap"),
        "spline_filter local NaN": sld.spline_filter(dh, order=3, nan_policy="local"),
        "spline_filter float32": sld.spline_filter(d, order=3, compute="float32", output=np.float32),
        "zoom": sld.zoom(d, 1.5, order=3, mode="mirror"),
        "shift": sld.shift(d, (0.25, -1.5), order=3, mode="nearest"),
        "affine_transform": sld.affine_transform(d, matrix, (1.0, -0.5), order=3),
        "rotate": sld.rotate(d, 17.0, order=3, reshape=False),
        "map_coordinates": sld.map_coordinates(d, COORDS, order=3),
    }


def test_dask_lazy_arrays_round_trip():
    """The lazy arrays of :mod:`splinelab.dask` (their graphs carry
    splinelab's plans) pickle with plain ``pickle``, and compute to the
    original's bits."""
    for name, lazy in _dask_lazies().items():
        want = lazy.compute(scheduler="sync")
        assert_same_bits(_pickled(lazy).compute(scheduler="sync"), want, name)
        assert_same_bits(copy.deepcopy(lazy).compute(scheduler="sync"), want, name)


def _xarray_cases():
    """The accessor's results, eager and lazy (dask-backed): each lazy case
    takes another of the module's routes (grouped windows on chunked grid
    axes, whole grid axes with a chunked carried axis, ``mode=`` windows,
    pointwise indexers)."""
    xr = pytest.importorskip("xarray")
    pytest.importorskip("dask.array")
    import splinelab.xarray  # noqa: F401  (registers the accessor)

    x, y, t = np.linspace(0, 1, 20), np.linspace(0, 2, 24), np.arange(4.0)
    a = xr.DataArray(np.sin(np.add.outer(np.add.outer(x, y), t)), dims=("x", "y", "t"),
                     coords={"x": x, "y": y, "t": t})
    new = {"x": np.linspace(0.1, 0.9, 7), "y": np.linspace(0.2, 1.8, 5)}
    pointwise = {"x": xr.DataArray([0.1, 0.5, 0.7], dims="p"), "y": xr.DataArray([0.3, 1.1, 1.9], dims="p")}
    chunked = a.chunk({"x": 10, "y": 12, "t": 2})
    return {
        "eager cubic": lambda: a.splinelab.interp(new, method="cubic"),
        "eager mode=mirror": lambda: a.splinelab.interp(new, method="cubic", mode="mirror"),
        "lazy, grid axes chunked": lambda: chunked.splinelab.interp(new, method="cubic"),
        "lazy, carried axis chunked": lambda: a.chunk({"x": -1, "y": -1, "t": 2}).splinelab.interp(new, method="pchip"),
        "lazy, mode= windows": lambda: chunked.splinelab.interp(new, method="cubic", mode="mirror"),
        "lazy, pointwise": lambda: chunked.splinelab.interp(pointwise, method="linear"),
    }


# The dask graphs of splinelab/_xarray_dask.py call closures (`block` defined
# inside _grouped, _whole_grid, _mode_windows and the pointwise blockwise):
# cloudpickle (dask.distributed) sends them, plain pickle cannot. Module-level
# functions bound with functools.partial fix it (as splinelab.dask's _map).
@pytest.mark.parametrize("case", ["eager cubic", "eager mode=mirror", "lazy, grid axes chunked",
                                  "lazy, carried axis chunked", "lazy, mode= windows", "lazy, pointwise"])
def test_xarray_results_round_trip(case):
    """The accessor's results pickle (a lazy one with its graph) and
    compute to the original's bits, coordinates included."""
    result = _xarray_cases()[case]()
    want = result.compute()
    got = _pickled(result).compute()
    assert_same_bits(got.values, want.values, case)
    assert got.dims == want.dims and list(got.coords) == list(want.coords)
    for name in want.coords:
        assert_same_bits(got[name].values, want[name].values, f"{case} coordinate {name}")


# ---------------------------------------------------------------- other processes


def _cross_process_objects():
    """A cubic interpolator (complex values with a trailing axis: the
    spline's column layout travels too), a pchip one and an interpolant
    with an update, and the points to evaluate them at."""
    points, v, xi = _grid_case(dtype=np.complex128, trailing=(2,))
    cubic = splinelab.RegularGridInterpolator(points, v, method="cubic", bounds_error=False, fill_value=None)
    points, v, _ = _grid_case()
    pchip = splinelab.RegularGridInterpolator(points, v, method="pchip", bounds_error=False, fill_value=None)
    ip = splinelab.Interpolant(_interpolant_input(), order=5)
    ip.update((2, 3), -4.0)
    return {"cubic": (cubic, xi), "pchip": (pchip, xi), "Interpolant": (ip, COORDS)}


def _refused_call():
    """A call splinelab refuses with one of its own classes (OrderError: a
    ValueError and a RuntimeError), raised by the engine."""
    return splinelab.map_coordinates, (np.ones((5, 5)), [[1.0], [2.0]]), {"order": 200}


def test_process_pool_workers_give_the_parents_bits():
    """Each object is called in a spawned worker process (pickled there and
    back): its values there are the parent's, bit for bit; an exception
    raised in the worker arrives with its class."""
    objects = _cross_process_objects()
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(max_workers=1, mp_context=context) as pool:
        remote = {name: pool.submit(obj, at) for name, (obj, at) in objects.items()}
        worker = pool.submit(os.getpid).result()
        func, args, kwargs = _refused_call()
        refused = pool.submit(func, *args, **kwargs)
        got = {name: f.result() for name, f in remote.items()}
        with pytest.raises(errors.OrderError, match="200"):
            refused.result()
    assert worker != os.getpid()
    for name, (obj, at) in objects.items():
        assert_same_bits(got[name], obj(at), name)


@pytest.fixture(scope="module")
def client():
    """One dask.distributed process worker (1 thread), loopback only."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, processes=True, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as c:
        assert os.getpid() not in set(c.run(os.getpid).values())
        yield c


def test_dask_distributed_worker_gives_the_parents_bits(client):
    """The same through a dask.distributed process worker. The grid
    interpolators' points travel as nested lists of floats (exact): a
    numpy array reaches a distributed worker at an unaligned address,
    which :func:`test_dask_distributed_unaligned_points` covers."""
    objects = _cross_process_objects()
    remote = {name: client.submit(obj, at.tolist() if name != "Interpolant" else at, pure=False)
              for name, (obj, at) in objects.items()}
    got = client.gather(remote)
    func, args, kwargs = _refused_call()
    with pytest.raises(errors.OrderError, match="200"):
        client.submit(func, *args, **kwargs, pure=False).result()
    for name, (obj, at) in objects.items():
        assert_same_bits(got[name], obj(at), name)


def _unaligned_in_worker(client, array):
    """A copy of ``array`` held by the worker at an address that is not a
    multiple of its itemsize (distributed places a small argument at
    whatever offset its message gives it: 1 to 7 mod 8 in most tries), and
    that it is."""
    for _ in range(32):
        held = client.scatter(array, hash=False)  # a new key each time: a released copy is not the next one
        if not client.submit(operator.attrgetter("flags.aligned"), held, pure=False).result():
            return held
    pytest.fail("distributed placed 32 copies at aligned addresses")


@pytest.mark.parametrize("name", ["cubic", "pchip"])
def test_dask_distributed_unaligned_points(client, name):
    """A grid interpolator called in a worker on the numpy points the
    worker holds (``client.submit(rgi, xi)``: the common call), at an
    unaligned address, gives the parent's bits: the points are copied to
    an aligned array before the engine reads them."""
    obj, at = _cross_process_objects()[name]
    held = _unaligned_in_worker(client, at)
    assert_same_bits(client.submit(obj, held, pure=False).result(), obj(at), name)
