from typing import Any
import dask.array as da
import numpy as np

DEFAULT_TOL: float
ROUTES: tuple[str, ...]

def depth(order: int, tol: float = ..., route: str = "truncated") -> int: ...
def bound(order: int, tol: float = ..., ndim: int = 1, route: str = "truncated") -> float: ...
def spline_filter(
    darr: Any, order: int = 3, mode: str = "mirror", tol: float = ..., output: Any = ..., threads: int | None = 1,
    route: str = "truncated",
) -> da.Array: ...
def spline_filter1d(
    darr: Any, order: int = 3, axis: int = -1, mode: str = "mirror", tol: float = ..., output: Any = ...,
    threads: int | None = 1, route: str = "truncated",
) -> da.Array: ...
