# Type stubs of splinelab (order = spline degree everywhere, as in scipy).
from typing import Any, Callable, Literal, Sequence
import numpy as np
import numpy.typing as npt

from . import errors as errors

__version__: str
MAX_DEGREE: int

# scipy's names, computed as scipy 1.17 computes them ('wrap': period n - 1, the mirror filter rule).
Mode = Literal["mirror", "reflect", "grid-mirror", "grid-wrap", "wrap", "nearest", "grid-constant", "constant"]
# Any numeric dtype scipy takes (a type, a dtype or its name), or an array of any dtype, byte order and strides.
# What NaN / ±inf samples do (see splinelab.map_coordinates).
NanPolicy = Literal["propagate", "raise", "local"]
# The arithmetic: float64 (scipy's, the default) or the opt-in float32.
Compute = Literal["float64", "float32"]
Output = type[np.generic] | type[bool] | type[int] | type[float] | type[complex] | np.dtype[Any] | str | npt.NDArray[Any]

def spline_filter1d(
    input: npt.ArrayLike,
    order: int = 3,
    axis: int = -1,
    output: Output = ...,
    mode: Mode = "mirror",
    *,
    tol: float | None = ...,
    threads: int | None = None,
    exact_edges: bool = False,
    nan_policy: NanPolicy = "propagate",
    compute: Compute = "float64",
) -> npt.NDArray[Any]: ...
def spline_filter(
    input: npt.ArrayLike,
    order: int = 3,
    output: Output = ...,
    mode: Mode = "mirror",
    *,
    tol: float | None = ...,
    threads: int | None = None,
    exact_edges: bool = False,
    nan_policy: NanPolicy = "propagate",
    compute: Compute = "float64",
) -> npt.NDArray[Any]: ...
def map_coordinates(
    input: npt.ArrayLike,
    coordinates: npt.ArrayLike,
    output: Output | None = None,
    order: int = 3,
    mode: Mode = "constant",
    cval: float | complex = 0.0,
    prefilter: bool = True,
    *,
    tol: float | None = ...,
    threads: int | None = None,
    exact_edges: bool = False,
    nan_policy: NanPolicy = "propagate",
    compute: Compute = "float64",
    derivative: Sequence[int] | None = None,
) -> npt.NDArray[Any]: ...
def spline_gradient(
    input: npt.ArrayLike,
    coordinates: npt.ArrayLike,
    order: int = 3,
    mode: Mode = "constant",
    cval: float | complex = 0.0,
    prefilter: bool = True,
    *,
    tol: float | None = ...,
    threads: int | None = None,
    exact_edges: bool = False,
    nan_policy: NanPolicy = "propagate",
    compute: Compute = "float64",
) -> npt.NDArray[Any]: ...
def zoom(
    input: npt.ArrayLike,
    zoom: float | Sequence[float],
    output: Output | None = None,
    order: int = 3,
    mode: Mode = "constant",
    cval: float | complex = 0.0,
    prefilter: bool = True,
    *,
    grid_mode: bool = False,
    tol: float | None = ...,
    threads: int | None = None,
    exact_edges: bool = False,
    nan_policy: NanPolicy = "propagate",
    compute: Compute = "float64",
) -> npt.NDArray[Any]: ...
def shift(
    input: npt.ArrayLike,
    shift: float | Sequence[float],
    output: Output | None = None,
    order: int = 3,
    mode: Mode = "constant",
    cval: float | complex = 0.0,
    prefilter: bool = True,
    *,
    tol: float | None = ...,
    threads: int | None = None,
    exact_edges: bool = False,
    nan_policy: NanPolicy = "propagate",
    compute: Compute = "float64",
) -> npt.NDArray[Any]: ...
def rotate(
    input: npt.ArrayLike,
    angle: float,
    axes: Sequence[int] = (1, 0),
    reshape: bool = True,
    output: Output | None = None,
    order: int = 3,
    mode: Mode = "constant",
    cval: float | complex = 0.0,
    prefilter: bool = True,
    *,
    tol: float | None = ...,
    threads: int | None = None,
    exact_edges: bool = False,
    nan_policy: NanPolicy = "propagate",
    compute: Compute = "float64",
) -> npt.NDArray[Any]: ...
def affine_transform(
    input: npt.ArrayLike,
    matrix: npt.ArrayLike,
    offset: float | Sequence[float] = 0.0,
    output_shape: Sequence[int] | None = None,
    output: Output | None = None,
    order: int = 3,
    mode: Mode = "constant",
    cval: float | complex = 0.0,
    prefilter: bool = True,
    *,
    tol: float | None = ...,
    threads: int | None = None,
    exact_edges: bool = False,
    nan_policy: NanPolicy = "propagate",
    compute: Compute = "float64",
) -> npt.NDArray[Any]: ...
# scipy.interpolate's gridded interpolation (issue 49): exact not-a-knot splines.
GridMethod = Literal["linear", "nearest", "slinear", "cubic", "quintic", "pchip", "slinear_legacy", "cubic_legacy", "quintic_legacy"]

class RegularGridInterpolator:
    method: str
    bounds_error: bool
    fill_value: Any
    def __init__(
        self,
        points: Sequence[npt.ArrayLike],
        values: npt.ArrayLike,
        method: GridMethod = "linear",
        bounds_error: bool = True,
        fill_value: Any = ...,
        *,
        solver: Callable[..., Any] | None = None,
        solver_args: dict[str, Any] | None = None,
        threads: int | None = None,
    ) -> None: ...
    def __call__(self, xi: Any, method: GridMethod | None = None, *, nu: Sequence[int] | None = None) -> npt.NDArray[Any]: ...
    @property
    def grid(self) -> tuple[npt.NDArray[np.float64], ...]: ...
    @property
    def values(self) -> Any: ...
    @property
    def condition(self) -> list[float] | None: ...
    @property
    def error_bound(self) -> float | None: ...

def interpn(
    points: Sequence[npt.ArrayLike],
    values: npt.ArrayLike,
    xi: Any,
    method: GridMethod | Literal["splinef2d"] = "linear",
    bounds_error: bool = True,
    fill_value: Any = ...,
    *,
    threads: int | None = None,
) -> npt.NDArray[Any]: ...

class Interpolant:
    shape: tuple[int, ...]
    ndim: int
    order: int
    mode: str
    def __init__(self, input: Any, order: int = 3, mode: str = "mirror", cval: float = 0.0, tol: float | None = None, nan_policy: str = "propagate", threads: int | None = None, cache_bytes: int = ...) -> None: ...
    def __call__(self, coordinates: npt.ArrayLike, derivative: Sequence[int] | None = None) -> npt.NDArray[Any]: ...
    def update(self, key: Any, values: npt.ArrayLike) -> None: ...
    def truncation(self) -> dict[str, Any]: ...
    def cache_info(self) -> dict[str, int]: ...

def geometric_transform(
    input: npt.ArrayLike,
    mapping: Callable[..., Any],
    output_shape: Sequence[int] | None = None,
    output: Output | None = None,
    order: int = 3,
    mode: Mode = "constant",
    cval: float | complex = 0.0,
    prefilter: bool = True,
    extra_arguments: Sequence[Any] = (),
    extra_keywords: dict[str, Any] | None = None,
    *,
    vectorized: bool = False,
    tol: float | None = ...,
    threads: int | None = None,
    exact_edges: bool = False,
    nan_policy: NanPolicy = "propagate",
    compute: Compute = "float64",
) -> npt.NDArray[Any]: ...
def truncation_width(
    degree: int | None = None,
    order: int | None = None,
    tension: str | float | None = None,
    *,
    tol: float,
    criterion: Literal["uniform", "coeff", "knot"] = "uniform",
    budget: float = 60.0,
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
def nan_reach(order: int, tol: float = 1e-12) -> int: ...
def check(
    kind: Literal["prefilter", "coeffs", "bspline-eval", "bezier-eval", "knot-insertion", "interp", "cond"],
    **kwargs: Any,
) -> dict[str, Any]: ...
