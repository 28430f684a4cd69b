"""``RegularGridInterpolator``'s "linear" and "nearest" give scipy 1.17's
bits: the same cells, normalised distances, weights and summation order
(core/src/gridded/multilinear.rs), so the value at a node is the sample
itself on any spacing and the values between nodes are scipy's to the last
bit. The reference is scipy itself at run time (a peer).

``python python/tests/test_rgi_bits.py`` prints the figure: how many node
values and values between nodes differ from scipy's on 200 random 7-node
grids in 1-D and 2-D.
"""

import numpy as np
import pytest
import scipy.interpolate as si
from hypothesis import given, settings
from hypothesis import strategies as st

import splinelab

DTYPES = [np.float64, np.float32, np.complex128, np.complex64, np.float16, np.int32]


def same_bits(a, b):
    """Equal dtype, shape and bytes (NaN payloads included), or the same
    exception class."""
    if isinstance(a, type) or isinstance(b, type):
        return a is b
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def both(grid, values, xi, method, **kw):
    """Our result and scipy's, or the class of the exception each raised."""
    def outcome(module):
        try:
            return module.RegularGridInterpolator(grid, values, method=method, **kw)(xi)
        except Exception as e:  # scipy's refusal is the reference
            return type(e)
    return outcome(splinelab), outcome(si)


def random_values(rng, shape, dtype):
    v = rng.uniform(-1, 1, shape)
    if np.dtype(dtype).kind == "c":
        v = v + 1j * rng.uniform(-1, 1, shape)
    return (v * (50 if np.dtype(dtype).kind == "i" else 1)).astype(dtype)


def differing(trials=200, seed=0):
    """(node values differing, node values, between differing, between) on
    random 7-node grids in 1-D and 2-D, "linear" and "nearest"."""
    rng = np.random.default_rng(seed)
    counts = np.zeros(4, dtype=int)
    for _ in range(trials):
        for ndim in (1, 2):
            grid = tuple(np.sort(rng.uniform(-5, 5, 7)) for _ in range(ndim))
            values = rng.uniform(-1, 1, (7,) * ndim)
            nodes = np.stack(np.meshgrid(*grid, indexing="ij"), -1).reshape(-1, ndim)
            between = np.stack([rng.uniform(g[0], g[-1], 50) for g in grid], -1)
            for method in ("linear", "nearest"):
                for j, xi in ((0, nodes), (2, between)):
                    ours, theirs = both(grid, values, xi, method)
                    counts[j] += int(np.sum(ours.view(np.int64) != theirs.view(np.int64)))
                    counts[j + 1] += ours.size
    return counts


def test_astropys_node_value_is_the_sample():
    x = np.array([1.5, 3.4, 6.7, 7.0, 32.0])
    assert splinelab.interpn((x,), np.arange(5.0), [[3.4]])[0] == 1.0
    assert splinelab.interpn((x,), np.arange(5.0), [[3.4]], method="nearest")[0] == 1.0


def test_random_non_uniform_grids_nodes_and_between_are_scipys_bits():
    counts = differing(trials=40)
    assert counts[0] == 0 and counts[2] == 0, counts


@pytest.mark.parametrize("ndim", [1, 2, 3])
@pytest.mark.parametrize("dtype", DTYPES)
@pytest.mark.parametrize("layout", ["plain", "trailing", "readonly", "descending", "fortran"])
def test_every_dtype_and_layout_is_scipys_bits(ndim, dtype, layout):
    # The 2-D float64/complex128 writeable case is scipy's Cython kernel,
    # every other its general route: each is followed.
    rng = np.random.default_rng(ndim * 100 + DTYPES.index(dtype))
    grid = tuple(np.sort(rng.uniform(-5, 5, 6)) for _ in range(ndim))
    values = random_values(rng, (6,) * ndim + ((3,) if layout == "trailing" else ()), dtype)
    if layout == "readonly":
        values.flags.writeable = False
    elif layout == "descending":
        grid = tuple(g[::-1] for g in grid)
    elif layout == "fortran":
        values = np.asfortranarray(values)
    xi = np.concatenate([np.stack([rng.uniform(g.min() - 1, g.max() + 1, 100) for g in grid], -1),
                         np.full((1, ndim), np.nan)])
    for method in ("linear", "nearest"):
        ours, theirs = both(grid, values, xi, method, bounds_error=False, fill_value=None)
        assert same_bits(ours, theirs), (method, ours.dtype, theirs.dtype)


def test_length_one_axes_and_broadcast_values_are_scipys_bits():
    rng = np.random.default_rng(3)
    one, y = np.array([1.0]), np.linspace(0, 3, 5)
    v = rng.uniform(-1, 1, (1, 5))
    xi = np.array([[1.0, 1.3], [1.0, 2.0], [0.5, 1.0], [np.nan, 1.0], [4.0, -2.0]])
    grid = np.array([0.0, 1.0, 2.5, 4.0])
    for method in ("linear", "nearest"):
        kw = dict(bounds_error=False, fill_value=None)
        assert same_bits(*both((one, y), v, xi, method, **kw))
        assert same_bits(*both((y, one), v.T.copy(), xi[:, ::-1], method, **kw))
        assert same_bits(*both((grid, grid), np.broadcast_to(np.float64(2.5), (4, 4)), [[0.5, 1.0], [3.0, 2.0]],
                               method))


def test_extrapolation_far_outside_is_scipys_finite_values():
    # scipy extrapolates at +-1e300 with finite values; the B-spline form
    # of the weights made NaN there.
    g = np.array([0.0, 1.0, 2.5, 4.0])
    v = np.array([1.0, -2.0, 3.0, 0.5])
    kw = dict(bounds_error=False, fill_value=None)
    ours, theirs = both((g,), v, [[1e300], [-1e300], [4e307]], "linear", **kw)
    assert same_bits(ours, theirs) and np.all(np.isfinite(theirs[:2]))
    ours, theirs = both((g, g), np.outer(v, v), [[1e300, 1.0], [-1e300, 2.0], [1e300, 1e300]], "linear", **kw)
    assert same_bits(ours, theirs)


@settings(max_examples=60, deadline=None)
@given(st.integers(2, 9), st.integers(1, 3), st.floats(1e-9, 1e9), st.integers(0, 2**32 - 1))
def test_any_spacing_is_scipys_bits(n, ndim, scale, seed):
    # Near-degenerate spacings included: cells from 1e-9 to 1e9 wide, and
    # points on, between and just beside the nodes.
    rng = np.random.default_rng(seed)
    grid = tuple(np.cumsum(rng.uniform(0.01, 1, n)) * scale for _ in range(ndim))
    values = rng.uniform(-1, 1, (n,) * ndim)
    on = np.stack([rng.choice(g, 20) for g in grid], -1)
    beside = np.nextafter(on, np.where(rng.random(on.shape) < 0.5, -np.inf, np.inf))
    inside = np.stack([rng.uniform(g[0], g[-1], 20) for g in grid], -1)
    xi = np.concatenate([on, beside, inside])
    for method in ("linear", "nearest"):
        assert same_bits(*both(grid, values, xi, method, bounds_error=False, fill_value=None)), method


if __name__ == "__main__":
    n_bad, n, b_bad, b = differing()
    print(f"linear and nearest on 200 random 7-node grids (1-D and 2-D): {n_bad} of {n} node values and "
          f"{b_bad} of {b} values between nodes differ from scipy's bits")
