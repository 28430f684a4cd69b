"""The downstream tests that fail with splinelab swapped in, each with its
reason (README.md in this folder). splinelab_swap marks them
xfail(strict=True) when swapped, and run.py requires each to pass on scipy:
a fixed one shows as a strict XPASS failure, and its entry goes.

Two kinds:

- :data:`FLOAT32` (by design): splinelab computes float32 input in float32
  (README: "float32 and complex64 results are computed in float32"), scipy
  in float64 rounded once to float32. reproject checks that two routes to
  the same values (edge-padded vs clipped coordinates; dask-image's chunked
  prefilter vs the whole-array one) agree to ``rtol=1e-7`` on float32 data;
  on splinelab they agree to 1-3 float32 ulps of max|value| (measured:
  at most 3.5e-7 absolute on data in [0, 1), 1.2e-7 for order 1), which
  ``rtol=1e-7`` refuses where a value is small.
- :data:`NAN` (issue 37's ``nan_policy``): scipy computes where splinelab
  refuses a non-finite sample or coordinate (``ValueError: coordinate 0 is
  not finite``); applied only while splinelab has no ``nan_policy``: with
  it (``"propagate"``, scipy's NaN behaviour, the default) they must pass.
"""

FLOAT32_REASON = ("float32 input is computed in float32 (scipy: float64, rounded once): two routes agree to "
                  "1-3 float32 ulps, not to the rtol=1e-7 the test asks")
NAN_REASON = "NaN coordinates: splinelab refuses them (ValueError) where scipy computes (issue 37, nan_policy)"

FLOAT32 = {
    # result1 (edge-padded) vs result2 (dask-image prefilter) vs the
    # reference, float32 data of either byte order.
    **{f"reproject/tests/test_array_utils.py::test_custom_map_coordinates[{dtype}-{order}-shape{s}-{cval}]":
       FLOAT32_REASON
       for dtype in ("<f4", ">f4") for order in (1, 2, 3) for s in (0, 1, 2) for cval in ("3", "nan")},
    # block_size=(10, 10) dask route vs whole array, float32 FITS data.
    "reproject/interpolation/tests/test_core.py::test_reproject_order_method[bilinear]": FLOAT32_REASON,
}

NAN = {
    # The round trip's output pixels off the solar disk have NaN world
    # coordinates, hence NaN pixel coordinates into map_coordinates.
    "reproject/interpolation/tests/test_core.py::test_reproject_roundtrip_kwarg[fits]": NAN_REASON,
}



def _refuses_nan():
    """Whether this splinelab refuses non-finite input (no ``nan_policy``
    yet): NAN applies only then, so the harness is right before and after
    the nan branch lands (after it, those tests must pass as on scipy)."""
    import inspect

    import splinelab

    return "nan_policy" not in inspect.signature(splinelab.map_coordinates).parameters


KNOWN: dict[str, str] = {**FLOAT32, **(NAN if _refuses_nan() else {})}
