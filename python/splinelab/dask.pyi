from typing import Any, Sequence
import dask.array as da
import numpy as np

DEFAULT_TOL: float
ROUTES: tuple[str, ...]

def depth(order: int, tol: float = ..., route: str = "truncated") -> int: ...
def bound(order: int, tol: float = ..., ndim: int = 1, route: str = "truncated") -> float: ...
def spline_filter(
    darr: Any, order: int = 3, mode: str = "mirror", tol: float = ..., output: Any = ..., threads: int | None = 1,
    route: str = "truncated", nan_policy: str = "propagate", compute: str = "float64",
) -> da.Array: ...
def spline_filter1d(
    darr: Any, order: int = 3, axis: int = -1, mode: str = "mirror", tol: float = ..., output: Any = ...,
    threads: int | None = 1, route: str = "truncated", nan_policy: str = "propagate", compute: str = "float64",
) -> da.Array: ...
def map_coordinates(
    input: Any, coordinates: Any, order: int = 3, mode: str = "constant", cval: float = 0.0, tol: float = ...,
    output: Any = None, threads: int | None = 1, route: str = "truncated", nan_policy: str = "propagate", compute: str = "float64",
) -> da.Array: ...
def zoom(
    input: Any, zoom: float | Sequence[float], order: int = 3, mode: str = "constant", cval: float = 0.0, *,
    grid_mode: bool = False, tol: float = ..., output: Any = None, chunks: Any = None, threads: int | None = 1,
    route: str = "truncated", nan_policy: str = "propagate", compute: str = "float64",
) -> da.Array: ...
def shift(
    input: Any, shift: float | Sequence[float], order: int = 3, mode: str = "constant", cval: float = 0.0, *,
    tol: float = ..., output: Any = None, chunks: Any = None, threads: int | None = 1, route: str = "truncated", nan_policy: str = "propagate", compute: str = "float64",
) -> da.Array: ...
def affine_transform(
    input: Any, matrix: Any, offset: float | Sequence[float] = 0.0, output_shape: Sequence[int] | None = None,
    order: int = 3, mode: str = "constant", cval: float = 0.0, *, tol: float = ..., output: Any = None,
    chunks: Any = None, threads: int | None = 1, route: str = "truncated", nan_policy: str = "propagate", compute: str = "float64",
) -> da.Array: ...
def rotate(
    input: Any, angle: float, axes: Sequence[int] = (1, 0), reshape: bool = True, order: int = 3,
    mode: str = "constant", cval: float = 0.0, *, tol: float = ..., output: Any = None, chunks: Any = None,
    threads: int | None = 1, route: str = "truncated", nan_policy: str = "propagate", compute: str = "float64",
) -> da.Array: ...
