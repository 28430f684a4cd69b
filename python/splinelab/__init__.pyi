# Type stubs of splinelab (order = spline degree everywhere, as in scipy).
from typing import Any, Literal, Sequence
import numpy as np
import numpy.typing as npt

__version__: str
MAX_DEGREE: int

# scipy's names; 'wrap' is taken by the filters (scipy's mirror rule), not by map_coordinates.
Mode = Literal["mirror", "reflect", "grid-mirror", "grid-wrap", "wrap", "nearest", "grid-constant", "constant"]
Output = type[np.float64] | type[np.float32] | np.dtype[Any] | str | npt.NDArray[np.floating[Any]]

def spline_filter1d(
    input: npt.ArrayLike,
    order: int = 3,
    axis: int = -1,
    output: Output = ...,
    mode: Mode = "mirror",
    *,
    tol: float | None = None,
    threads: int | None = None,
    exact_edges: bool = False,
) -> npt.NDArray[np.floating[Any]]: ...
def spline_filter(
    input: npt.ArrayLike,
    order: int = 3,
    output: Output = ...,
    mode: Mode = "mirror",
    *,
    tol: float | None = None,
    threads: int | None = None,
    exact_edges: bool = False,
) -> npt.NDArray[np.floating[Any]]: ...
def map_coordinates(
    input: npt.ArrayLike,
    coordinates: npt.ArrayLike,
    output: Output | None = None,
    order: int = 3,
    mode: Mode = "constant",
    cval: float = 0.0,
    prefilter: bool = True,
    *,
    tol: float | None = None,
    threads: int | None = None,
    exact_edges: bool = False,
) -> npt.NDArray[np.floating[Any]]: ...
def truncation_width(
    degree: int | None = None,
    order: int | None = None,
    tension: str | float | None = None,
    *,
    tol: float,
    criterion: Literal["uniform", "coeff", "knot"] = "uniform",
) -> dict[str, Any]: ...
def coefficients(
    degree: int | None = None,
    order: int | None = None,
    tension: str | float | None = None,
    *,
    count: int = 10,
    bits: int | None = None,
) -> npt.NDArray[np.float64] | list[str]: ...
def filter_bound(order: int, tol: float | None = None, ndim: int = 1) -> dict[str, Any]: ...
def check(
    kind: Literal["prefilter", "coeffs", "bspline-eval", "bezier-eval", "knot-insertion"],
    **kwargs: Any,
) -> dict[str, Any]: ...
