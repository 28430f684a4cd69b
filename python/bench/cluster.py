"""splinelab on a dask.distributed cluster: issue 51's two cluster figures.

Both cases run on a ``LocalCluster`` of 2 process workers, 1 thread each,
``memory_limit="1.5GB"`` (the issue's), no dashboard, loopback only. Each
row records the wall time (graph building included), the number of tasks,
the peak resident size of each worker (VmHWM, reset in every worker before
the call), whether a worker was restarted (the workers' process ids before
and after), and the accuracy against an independent in-memory reference.

    .venv/bin/python python/bench/cluster.py affine            # 8000² cubic rotation, zarr to zarr
    .venv/bin/python python/bench/cluster.py timeaxis          # xarray #10130's case
    .venv/bin/python python/bench/cluster.py affine --quick    # small sizes (a minute)
    .venv/bin/python python/bench/cluster.py affine --malloc-trim 1073741824   # workers' glibc trim raised

Cases:

- ``affine``: an 8000² float32 zarr array (standard normal, 1000² chunks,
  written once under /tmp), cubic, rotation by 0.1 rad about the centre,
  mode 'constant', read with ``dask.array.from_zarr`` and written back to
  zarr in the same chunks: ``splinelab.dask.affine_transform`` (float32 out,
  the input's dtype, and float64 out for the accuracy), dask-image's
  ``affine_transform`` (its defaults: no prefilter), and scipy in memory on
  one core (``output=float64``: the reference, and its time). Accuracy: max
  |ours - scipy| / max|scipy| over the whole output.
- ``timeaxis`` (xarray #10130): 8760 hourly steps x 200 x 200 float32 in
  24-step chunks (made lazily by ``dask.array.random.default_rng(10130)``:
  1.4 GB would not fit beside the cluster), cubic onto 3-hourly times,
  written to zarr: the accessor ``da.splinelab.interp(time=...,
  method="cubic")``, then xarray's own ``da.interp`` on the same cluster
  (under a timeout; restarts recorded). Accuracy: 16 (lat, lon) columns
  against scipy's not-a-knot ``make_interp_spline`` of the same column.

Workers' allocator: distributed's nanny starts each worker with glibc's
``MALLOC_TRIM_THRESHOLD_=65536``, under which every large array is a fresh
``mmap`` whose pages the kernel faults in and zeroes, and unmaps on free.
splinelab's output tasks keep their scratch arrays per worker thread (not
subject to it); ``--malloc-trim BYTES`` raises the threshold for this
benchmark's cluster only (dask config ``distributed.nanny.pre-spawn-environ``,
set around the cluster's start) to measure what the remaining allocations
(zarr's chunks, the results, the transfers) cost.

Results: one JSON file per case under python/bench/cluster/ (``--out``).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TMP = "/tmp/splinelab_bench_cluster"
MEMORY_LIMIT = "1.5GB"


# ----------------------------------------------------------------- the cluster


#: The workers' ``MALLOC_TRIM_THRESHOLD_`` (``--malloc-trim``), or None:
#: distributed's default (65536, its nanny's ``pre-spawn-environ``).
MALLOC_TRIM = None


def _cluster():
    import dask
    import distributed
    environ = {} if MALLOC_TRIM is None else {"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": MALLOC_TRIM}
    with dask.config.set(environ):
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                           memory_limit=MEMORY_LIMIT, host="127.0.0.1", dashboard_address=None)
    client = distributed.Client(cluster)
    return cluster, client


def _worker_trim():
    return os.environ.get("MALLOC_TRIM_THRESHOLD_")


def _worker_reset():
    """In a worker: VmHWM reset to the resident size; the size in KiB."""
    with open("/proc/self/clear_refs", "w") as fh:
        fh.write("5")
    return _worker_kib("VmRSS")


def _worker_kib(field="VmHWM"):
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return -1


def _pids(client):
    return sorted(client.run(os.getpid).values())


def measured(client, label, call, timeout=None):
    """``call()`` (builds and runs the graph on the cluster) timed, with the
    peak of each worker above its resident size before, and restarts."""
    before = _pids(client)
    base = client.run(_worker_reset)
    t0 = time.perf_counter()
    row = {"case": label}
    try:
        extra = call(timeout) if timeout else call()
        row["status"] = "ok"
        row.update(extra or {})
    except Exception as e:  # noqa: BLE001 - a library that fails is a result here
        row["status"] = f"failed: {type(e).__name__}: {str(e)[:300]}"
    row["seconds"] = round(time.perf_counter() - t0, 3)
    try:
        client.wait_for_workers(2, timeout=60)
    except Exception:  # noqa: BLE001
        pass
    peaks = client.run(_worker_kib)
    after = _pids(client)
    row["peak_mb_per_worker"] = [round(peaks[w] / 1024, 1) for w in sorted(peaks)]
    row["rss_before_mb"] = [round(base[w] / 1024, 1) for w in sorted(base) if w in base]
    row["workers_restarted"] = len(set(before) - set(after))
    print(json.dumps(row), flush=True)
    return row


def _machine():
    with open("/proc/loadavg") as fh:
        load = fh.read().split()[:3]
    return {"cores": os.cpu_count(), "load_before": load,
            "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
            "commit": subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                                     cwd=HERE).stdout.strip()}


def _versions():
    import dask
    import distributed
    import scipy
    import splinelab
    import zarr
    return {"splinelab": splinelab.__version__, "scipy": scipy.__version__, "dask": dask.__version__,
            "distributed": distributed.__version__, "zarr": zarr.__version__}


def _n_tasks(lazy):
    return len(lazy.__dask_graph__())


# ----------------------------------------------------------------- affine


def _affine_store(n, chunk):
    """The n² float32 input store, written once, a band of chunks at a time."""
    import zarr
    path = f"{TMP}/affine_{n}_{chunk}.zarr"
    if os.path.exists(path + ".done"):
        return path
    shutil.rmtree(path, ignore_errors=True)
    z = zarr.create_array(path, shape=(n, n), chunks=(chunk, chunk), dtype="float32")
    rng = np.random.default_rng(51)
    for r in range(0, n, chunk):
        z[r:r + chunk] = rng.standard_normal((min(chunk, n - r), n), dtype=np.float32)
    open(path + ".done", "w").close()
    return path


def _rotation(n):
    c, s = np.cos(0.1), np.sin(0.1)
    m = np.array([[c, -s], [s, c]])
    centre = np.array([(n - 1) / 2, (n - 1) / 2])
    return m, centre - m @ centre


def _warm_up(client, m):
    """Both libraries imported in the workers (a 64² call each), so the
    timed calls measure the work, not the first import."""
    import dask.array as da
    import dask_image.ndinterp as ndinterp

    import splinelab.dask as sld
    x = da.ones((64, 64), chunks=32, dtype=np.float32)
    client.compute([sld.affine_transform(x, m, order=3), ndinterp.affine_transform(x, m, order=3)], sync=True)


def case_affine(quick):
    """Rounds of (scipy, splinelab, dask-image), interleaved so that the load
    of a shared machine falls on all three alike; then one float64 run of
    splinelab for the accuracy. The summary: min and median per case."""
    import zarr

    n, chunk = (2000, 500) if quick else (8000, 1000)
    src = _affine_store(n, chunk)
    m, off = _rotation(n)
    img = zarr.open_array(src, mode="r")[...]
    ref = None
    rows = []
    cluster, client = _cluster()
    try:
        print("workers' MALLOC_TRIM_THRESHOLD_:", sorted(set(client.run(_worker_trim).values())), flush=True)
        _warm_up(client, m)
        for _ in range(1 if quick else 3):
            ref, row = _scipy_affine(img, m, off)
            rows.append(row)
            for lib in ("splinelab", "dask-image"):
                rows.append(_accuracy(measured(client, f"{lib} on the cluster, output float32",
                                               _affine_call(lib, src, m, off, chunk, np.float32)), ref))
        rows.append(_accuracy(measured(client, "splinelab on the cluster, output float64",
                                       _affine_call("splinelab", src, m, off, chunk, np.float64)), ref))
    finally:
        client.close()
        cluster.close()
    return {"shape": [n, n], "chunks": [chunk, chunk], "rows": rows, "summary": _summary(rows)}


def _scipy_affine(img, m, off):
    """scipy in memory on one core (float64 out: the reference)."""
    import scipy.ndimage as ndi
    t0 = time.perf_counter()
    ref = ndi.affine_transform(img, m, off, order=3, output=np.float64)
    row = {"case": "scipy in memory, 1 core", "seconds": round(time.perf_counter() - t0, 3), "output": "float64"}
    print(json.dumps(row), flush=True)
    return ref, row


def _affine_call(lib, src, m, off, chunk, dtype):
    """The call ``measured`` times: zarr in, the transform, zarr out."""
    def call():
        import dask.array as da
        out_path = f"{TMP}/affine_out_{lib}.zarr"
        shutil.rmtree(out_path, ignore_errors=True)
        darr = da.from_zarr(src)
        if lib == "splinelab":
            import splinelab.dask as sld
            lazy = sld.affine_transform(darr, m, off, order=3, output=dtype, output_chunks=(chunk, chunk))
        else:  # dask-image's defaults (no prefilter), float32 out as the input
            import dask_image.ndinterp as ndinterp
            lazy = ndinterp.affine_transform(darr, m, off, order=3, output_chunks=(chunk, chunk))
        tasks = _n_tasks(lazy)
        lazy.to_zarr(out_path)
        return {"tasks": tasks, "out": out_path}
    return call


def _accuracy(row, ref):
    """max |result - scipy's float64| / max|scipy's|; for float32 results
    also the count differing from scipy's value rounded to float32."""
    import zarr
    if "out" not in row:
        return row
    got = zarr.open_array(row.pop("out"), mode="r")[...]
    row["max_rel_vs_scipy"] = float(np.abs(got.astype(np.float64) - ref).max() / np.abs(ref).max())
    if got.dtype == np.float32:
        row["float32_outputs_differing_from_scipys_rounding"] = int((got != ref.astype(np.float32)).sum())
    print(json.dumps({k: row[k] for k in row if "vs" in k or "differing" in k}), flush=True)
    return row


def _summary(rows):
    by = {}
    for r in rows:
        if r.get("status", "ok") == "ok":
            by.setdefault(r["case"], []).append(r["seconds"])
    return {case: {"runs": len(t), "min_s": min(t), "median_s": float(np.median(t))} for case, t in by.items()}


# ----------------------------------------------------------------- time axis


def _time_cube(quick):
    import dask.array as da
    import xarray as xr
    nt, ny = (744, 50) if quick else (8760, 200)
    data = da.random.default_rng(10130).standard_normal((nt, ny, ny), chunks=(24, ny, ny), dtype=np.float32)
    time_ = np.datetime64("2021-01-01T00") + np.arange(nt).astype("timedelta64[h]")
    cube = xr.DataArray(data, dims=("time", "lat", "lon"),
                        coords={"time": time_, "lat": np.linspace(-60.0, 60.0, ny), "lon": np.linspace(0.0, 359.0, ny)},
                        name="t2m")
    new_times = time_[0] + np.arange(0, nt, 3).astype("timedelta64[h]")
    return cube, new_times


def _columns_reference(cube, new_times, result_path, picks):
    """Max |accessor - scipy's not-a-knot spline| / max|column| over the
    picked (lat, lon) rows x columns, read from the store directly (not
    through the cluster)."""
    import zarr
    from scipy.interpolate import make_interp_spline
    got = zarr.open_array(f"{result_path}/t2m", mode="r")
    hours = np.timedelta64(1, "h")
    t = ((cube["time"].values - cube["time"].values[0]) / hours).astype(np.float64)
    tn = ((new_times - cube["time"].values[0]) / hours).astype(np.float64)
    rows, cols = sorted({i for i, _ in picks}), sorted({j for _, j in picks})
    ours = got.get_orthogonal_selection((slice(None), rows, cols))  # each stored chunk read once
    ys = cube.data[:, rows][:, :, cols].compute().astype(np.float64)
    worst = 0.0
    for a in range(len(rows)):
        for b in range(len(cols)):
            exact = make_interp_spline(t, ys[:, a, b], k=3)(tn)
            worst = max(worst, float(np.abs(ours[:, a, b] - exact).max() / np.abs(ys[:, a, b]).max()))
    return worst


def case_timeaxis(quick, xarray_timeout):
    import splinelab.xarray  # noqa: F401  (registers the accessor)
    cube, new_times = _time_cube(quick)
    rows = []
    cluster, client = _cluster()
    try:
        def written(lib, lazy_of, sink, timeout=None):
            """The result written to zarr (or summed) on the cluster (``timeout``: then cancelled)."""
            import distributed

            def call(*_):
                path = f"{TMP}/timeaxis_{lib}.zarr"
                shutil.rmtree(path, ignore_errors=True)
                lazy = lazy_of()
                tasks = _n_tasks(lazy.data)
                if sink == "zarr":
                    future = client.compute(lazy.to_dataset().to_zarr(path, mode="w", compute=False))
                else:  # xarray's output chunks are not zarr's (lat, lon split unevenly): the sum, gathered
                    future = client.compute(lazy.data.sum())
                try:
                    future.result(timeout=timeout)
                except distributed.TimeoutError:
                    future.cancel()
                    return {"tasks": tasks, "sink": sink, "status": f"timed out after {timeout} s (cancelled)"}
                return {"tasks": tasks, "sink": sink, **({"out": path} if sink == "zarr" else {})}
            return call

        ny = cube.shape[1]
        picks = [(i, j) for i in (0, ny // 3, 2 * ny // 3, ny - 1) for j in (0, ny // 4, ny // 2, ny - 1)]
        cases = [("splinelab accessor, cubic", "splinelab",
                  lambda: cube.splinelab.interp(time=new_times, method="cubic"), "zarr", None),
                 ("xarray interp, cubic", "xarray", lambda: cube.interp(time=new_times, method="cubic"), "sum",
                  xarray_timeout)]
        for label, lib, lazy_of, sink, timeout in cases:
            row = measured(client, label, written(lib, lazy_of, sink, timeout), timeout=timeout)
            if "out" in row:
                row["max_rel_vs_scipy_columns"] = _columns_reference(cube, new_times, row.pop("out"), picks)
                print(json.dumps({"case": label, "max_rel_vs_scipy_columns": row["max_rel_vs_scipy_columns"]}))
            rows.append(row)
    finally:
        client.close()
        cluster.close()
    return {"shape": list(cube.shape), "chunks": [24, cube.shape[1], cube.shape[2]], "new_times": len(new_times),
            "data": "dask.array.random.default_rng(10130).standard_normal, float32, made lazily", "rows": rows}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case", choices=["affine", "timeaxis"])
    ap.add_argument("--quick", action="store_true", help="small sizes")
    ap.add_argument("--xarray-timeout", type=float, default=300.0, help="seconds for xarray's interp (timeaxis)")
    ap.add_argument("--out", default=os.path.join(HERE, "cluster"), help="directory of the JSON results")
    ap.add_argument("--malloc-trim", type=int, default=None,
                    help="the workers' MALLOC_TRIM_THRESHOLD_ in bytes, set for this cluster through dask's config "
                         "distributed.nanny.pre-spawn-environ (default: distributed's, 65536); the JSON is then "
                         "<case>_malloc_trim.json")
    args = ap.parse_args()
    global MALLOC_TRIM
    MALLOC_TRIM = args.malloc_trim
    os.makedirs(TMP, exist_ok=True)
    trim = MALLOC_TRIM if MALLOC_TRIM is not None else "distributed's default (65536)"
    info = {"machine": _machine(), "versions": _versions(), "memory_limit": MEMORY_LIMIT, "quick": args.quick,
            "workers_malloc_trim_threshold": trim}
    result = case_affine(args.quick) if args.case == "affine" else case_timeaxis(args.quick, args.xarray_timeout)
    with open("/proc/loadavg") as fh:
        info["machine"]["load_after"] = fh.read().split()[:3]
    os.makedirs(args.out, exist_ok=True)
    name = f"{args.case}{'_quick' if args.quick else ''}{'_malloc_trim' if MALLOC_TRIM is not None else ''}.json"
    with open(os.path.join(args.out, name), "w") as fh:
        json.dump({**info, **result}, fh, indent=1)
    print("wrote", os.path.join(args.out, name))


if __name__ == "__main__":
    sys.exit(main())
