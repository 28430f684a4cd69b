"""Derivatives of the interpolant (map_coordinates(derivative=...),
spline_gradient) against 5-point central differences of scipy 1.17.1's
own map_coordinates values (an independent evaluation), at points whose
stencil stays inside one polynomial piece, so the difference formula is
exact for cubics and within h^4 f^(5) / 30 for quintics."""

import numpy as np
import pytest
from scipy import ndimage

import splinelab

H = 1e-3


def rng(seed=7):
    return np.random.default_rng(seed)


def points_in_cells(count, lo, hi, d, seed):
    # The spline's pieces end at integers (odd degrees) or half-integers
    # (even ones): keep the stencil x +- 2h inside one piece.
    x = rng(seed).uniform(lo, hi, count)
    knot = np.floor(x) if d % 2 else np.floor(x + 0.5) - 0.5
    return knot + 0.1 + 0.8 * (x - np.floor(x))


def central_difference(values_at, x, axis):
    def at(t):
        y = x.copy()
        y[axis] += t
        return values_at(y)

    return (at(-2 * H) - 8 * at(-H) + 8 * at(H) - at(2 * H)) / (12 * H)


@pytest.mark.parametrize("mode", ["mirror", "reflect", "grid-wrap", "wrap", "nearest", "constant"])
@pytest.mark.parametrize("d", [2, 3, 5])
def test_first_partials_equal_central_differences_of_scipy(d, mode):
    x = rng(d).uniform(-1, 1, (30, 32))
    lo, hi = (0.5, 28.5) if mode == "constant" else (-6, 36)
    at = np.stack([points_in_cells(300, lo, hi, d, 1), points_in_cells(300, lo, hi, d, 2)])

    def scipy_values(y):
        return ndimage.map_coordinates(x, y, order=d, mode=mode)

    g = splinelab.spline_gradient(x, at, order=d, mode=mode)
    assert g.shape == (2, 300)
    for axis in range(2):
        fd = central_difference(scipy_values, at, axis)
        # Rounding: ~ 3 u max|f| / h; truncation (quintics): h^4 |f^(5)| / 30.
        assert np.abs(g[axis] - fd).max() <= 1e-9 * np.abs(fd).max() + (1e-9 if d == 5 else 0), axis
        ours = splinelab.map_coordinates(x, at, order=d, mode=mode, derivative=[int(axis == 0), int(axis == 1)])
        np.testing.assert_array_equal(ours, g[axis])


def test_second_and_mixed_partials():
    # A cubic's second derivative is piecewise linear, the mixed one too:
    # central differences of our first derivatives agree to rounding.
    x = rng(3).uniform(-1, 1, (25, 26))
    at = np.stack([points_in_cells(200, 2, 22, 3, 4), points_in_cells(200, 2, 22, 3, 5)])

    def d0(y):
        return splinelab.map_coordinates(x, y, order=3, mode="mirror", derivative=(1, 0))

    for deriv, axis in [((2, 0), 0), ((1, 1), 1)]:
        ours = splinelab.map_coordinates(x, at, order=3, mode="mirror", derivative=deriv)
        assert np.abs(ours - central_difference(d0, at, axis)).max() <= 1e-8


def test_derivative_refusals():
    x = np.ones((5, 5))
    with pytest.raises(ValueError, match="one non-negative order per axis"):
        splinelab.map_coordinates(x, [[1.0], [1.0]], derivative=(1,))
    with pytest.raises(ValueError, match="degree"):
        splinelab.map_coordinates(x, [[1.0], [1.0]], order=3, derivative=(4, 0))
