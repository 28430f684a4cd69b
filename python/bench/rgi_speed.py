"""RegularGridInterpolator and interpn: splinelab against scipy.interpolate,
every method, what a user times (not run by CI):

    .venv/bin/python python/bench/rgi_speed.py [--quick] [--rounds 5] [--threads both|default|1]
        [--budget 20] [--cap 60] [--calls interpn,rgi,eval] [--only REGEX] [--json PATH]

Every method ("linear", "nearest", "slinear", "cubic", "quintic", "pchip")
on grids 8², 200², 2000², 32³ and 128²×64 (jittered spacing, each step
uniform in [0.5, 1.5], standard normal float64 values, as rgi.py), at 1,
10², 10⁴ and 10⁶ points uniform inside the grid. Three calls per case:
``interpn`` (``interpn(points, values, xi, method)``), ``rgi``
(``RegularGridInterpolator(points, values, method)(xi)``): construction
plus evaluation, what a user times; ``eval``: ``ip(xi)`` on an interpolator
constructed beforehand. The figure is the ratio splinelab / scipy.

One process; each case times scipy and splinelab alternately (which goes
first rotates), each a batch of calls lasting about 2 ms, and keeps the
minimum per call over ``--rounds`` rounds. splinelab runs with its default
threads and with ``threads=1`` (``--threads``); with both, the two settings
share one scipy measurement, the three alternated. scipy has one thread.

Every case has a time budget (``--budget`` seconds, counted over both
libraries' calls) that bounds scipy's repeats: one call of each is timed first (the warm-up,
which counts as a round for calls longer than a batch); a scipy call over
the budget is recorded "over budget" with that one time (a lower bound; the
ratio is then an upper bound) and not repeated, and a scipy call still
running after ``--cap`` seconds is interrupted (SIGALRM) and recorded the
same way with the time it had run. scipy takes part in the rounds while
the next one fits in what is left of the budget; splinelab runs all
``--rounds`` (its slowest call, 10⁶ quintic points in 3-D, is a second or
two). Without running a call, scipy is recorded:

* skipped, for its spline methods ("slinear", "cubic", "quintic") on grids
  of more than 10⁶ nodes (2000², 128²×64): it builds them by gcrotmk on the
  whole grid (the case where rgi.py measures memory, not speed);
* skipped, for "pchip" where its first pass would hold more than 4 GiB
  (``points × nodes / last axis`` float64 values: 10⁶ points on 2000² or
  128²×64);
* over budget, for ``interpn`` and ``rgi`` where its construction of the
  grid and method (timed once per grid and method, for ``eval``) was, and
  for ``eval`` where that construction was interrupted; for a call over
  budget at fewer points;
* over budget (predicted), where the straight line through the two
  smaller point counts' times (the cost is a construction plus a cost per
  point) predicts more than twice ``--cap``; scipy's "pchip" loops in
  Python over the points.

splinelab is measured in every case. Printed: one line per case and
threads setting (scipy, splinelab, ratio; the scipy status where it is
not measured), then the largest ratio per method and grid, the count of
cases above 1.0 and 1.05. When pyinterp is importable: "linear" against
pyinterp's bilinear (``pyinterp.Grid2D`` and ``pyinterp.bivariate``, x the
grid's first axis) at 10⁶ points on 200² and 2000², after a check that its
values agree with scipy's to 1e-12 (printed); splinelab's threads settings
against pyinterp's ``num_threads`` 0 (every core) and 1.

``--quick``: 8² and 200², 1 and 10⁴ points, 3 rounds, a budget of 3 s
(under a minute); pyinterp at 10⁴ points on 200². ``--json PATH`` writes
every case as a record with the machine (cores, load average at the start
and the end), the versions and the commit.

A full run: 360 cases (720 records with both threads settings), most of
them milliseconds; its time is bounded by the budget: scipy's "pchip" at
10⁴ points and its spline constructions on 200² and 32³ reach it (about
20 s a case), the 10⁶-point cases take seconds each. About half an hour
on a 2-core machine (25 to 40 minutes).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import re
import signal
import sys
import time

import numpy as np
import scipy
import scipy.interpolate as si

import splinelab
from small_calls import BATCH, _batch, provenance

GRIDS = [(8, 8), (200, 200), (2000, 2000), (32, 32, 32), (128, 128, 64)]
QUICK_GRIDS = [(8, 8), (200, 200)]
POINTS = [1, 100, 10_000, 1_000_000]
QUICK_POINTS = [1, 10_000]
METHODS = ["linear", "nearest", "slinear", "cubic", "quintic", "pchip"]
CALLS = ["interpn", "rgi", "eval"]
#: scipy's spline methods solve for the coefficients with gcrotmk on the
#: whole grid: not run beyond this many nodes.
SCIPY_SPLINES = ("slinear", "cubic", "quintic")
SCIPY_SPLINE_MAX_NODES = 1_000_000
#: scipy's "pchip" evaluates the last axis for every point at once, an array
#: of ``points * nodes / last axis`` values: not run beyond this many bytes.
SCIPY_PCHIP_MAX_BYTES = 4 * 2**30
#: pyinterp's bilinear against scipy's linear: the largest difference allowed.
PYINTERP_TOL = 1e-12


def _shape(shape):
    return "x".join(map(str, shape))


def _count(m):
    return str(m) if m < 100 else f"1e{round(math.log10(m))}"


def _time(s):
    if s is None:
        return f"{'-':>10}"
    if s < 1e-3:
        return f"{s * 1e6:7.1f} us"
    if s < 1.0:
        return f"{s * 1e3:7.2f} ms"
    return f"{s:7.2f} s "


def data(shape, points):
    """Jittered axes, standard normal values, ``max(points)`` points
    uniform inside the grid (the first ``m`` rows are the case of ``m``)."""
    rng = np.random.default_rng([7, *shape])
    grid = tuple(np.cumsum(rng.uniform(0.5, 1.5, n)) for n in shape)
    values = rng.standard_normal(shape)
    xi = np.column_stack([rng.uniform(g[0], g[-1], max(points)) for g in grid])
    return grid, values, xi


# ---------------------------------------------------------------- timing


class _Interrupted(Exception):
    pass


def _once(call, cap=None):
    """Seconds of one call and whether it was interrupted after ``cap``
    seconds (None: never)."""
    armed = [cap is not None]

    def alarm(signum, frame):
        if armed[0]:
            raise _Interrupted

    old = signal.signal(signal.SIGALRM, alarm) if cap is not None else None
    if cap is not None:
        signal.setitimer(signal.ITIMER_REAL, cap)
    t = time.perf_counter()
    interrupted = False
    try:
        call()
        armed[0] = False
    except _Interrupted:
        interrupted = True
    finally:
        armed[0] = False
        elapsed = time.perf_counter() - t
        if cap is not None:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, old)
    return elapsed, interrupted


def measure(calls, rounds, budget, cap, capped=("scipy",)):
    """``calls``: name -> callable. Each is called once (the ``capped`` ones
    interrupted after ``cap`` s); a ``capped`` one over ``budget`` s is
    recorded with that time. Then up to ``rounds`` rounds of batches (about
    :data:`BATCH` s each, the first caller rotating); a ``capped`` call
    leaves the rounds when the next would take the case past ``budget``,
    the others run them all. Returns name -> dict(s, status, rounds)."""
    out, active, spent = {}, [], 0.0
    for name, call in calls.items():
        t, interrupted = _once(call, cap if name in capped else None)
        if interrupted or (name in capped and t > budget):
            out[name] = dict(s=t, status="interrupted" if interrupted else "over budget", rounds=1)
            continue
        out[name] = dict(s=t, status="measured", rounds=1)
        active.append(name)
        spent += t
    reps, cost = {}, {}
    for name in active:
        t = out[name]["s"]
        if t < BATCH:  # the warm-up's time is inflated: once more, then batches only
            t = min(t, _batch(calls[name], 1))
            spent += t
        reps[name] = max(1, min(10_000, int(BATCH / max(t, 1e-7))))
        cost[name] = reps[name] * t
        if reps[name] > 1:
            out[name]["s"], out[name]["rounds"] = math.inf, 0
    for r in range(rounds):
        active = [n for n in active if n not in capped or spent + sum(cost[m] for m in active) <= budget]
        if not active:
            break
        k = r % len(active)
        for name in active[k:] + active[:k]:
            t = _batch(calls[name], reps[name])
            out[name]["s"] = min(out[name]["s"], t)
            out[name]["rounds"] += 1
            spent += t * reps[name]
    for name, o in out.items():
        if o["rounds"] == 0:  # no round fitted the budget: one batch alone
            o["s"], o["rounds"] = _batch(calls[name], reps[name]), 1
    return out


# ---------------------------------------------------------------- cases


def scipy_skip(method, shape, m):
    """Why scipy is not run on this case (None: it is)."""
    nodes = math.prod(shape)
    if method in SCIPY_SPLINES and nodes > SCIPY_SPLINE_MAX_NODES:
        return f"its {method} builds by gcrotmk on the whole grid ({nodes:,} nodes > {SCIPY_SPLINE_MAX_NODES:,})"
    held = m * nodes // shape[-1] * 8
    if method == "pchip" and held > SCIPY_PCHIP_MAX_BYTES:
        return f"its pchip would hold {held / 2**30:.0f} GiB (points x nodes / last axis)"
    return None


def predicted(history, m):
    """scipy's seconds at ``m`` points from the straight line through the
    two largest smaller point counts measured (None with fewer than two)."""
    if len(history) < 2:
        return None
    (m1, t1), (m2, t2) = history[-2:]
    slope = max(0.0, (t2 - t1) / (m2 - m1))
    return t2 + slope * (m - m2)


def user_calls(kind, grid, values, xi, method, threads, scipy_ip, ours_ip):
    """scipy's call and splinelab's per threads setting, for ``kind``."""
    def kw(t):
        return {} if t is None else {"threads": t}
    if kind == "interpn":
        theirs = lambda: si.interpn(grid, values, xi, method=method)  # noqa: E731
        ours = {t: (lambda t=t: splinelab.interpn(grid, values, xi, method=method, **kw(t))) for t in threads}
    elif kind == "rgi":
        theirs = lambda: si.RegularGridInterpolator(grid, values, method=method)(xi)  # noqa: E731
        ours = {t: (lambda t=t: splinelab.RegularGridInterpolator(grid, values, method=method, **kw(t))(xi))
                for t in threads}
    else:
        theirs = None if scipy_ip is None else (lambda: scipy_ip(xi))
        ours = {t: (lambda t=t: ours_ip[t](xi)) for t in threads}
    return theirs, ours


def _tname(t):
    return "default" if t is None else str(t)


def _print_case(label, rec):
    status = rec["scipy_status"]
    ratio = rec["ratio"]
    if ratio is None:
        r = f"{'-':>7}"
    else:
        r = f"{'<=' if status != 'measured' else '  '}{ratio:5.2f}"
    note = "" if status == "measured" else f"  scipy {status}" + (f" ({rec['scipy_note']})" if rec["scipy_note"]
                                                                   else "")
    print(f"{label:<34} threads {rec['threads']:<7} scipy {_time(rec['scipy_s'])}  splinelab "
          f"{_time(rec['splinelab_s'])}  ratio {r}  [{rec['scipy_rounds']}/{rec['rounds']}]{note}", flush=True)


def scipy_plan(kind, method, shape, m, build, history, over, budget, cap):
    """Whether scipy runs on this case: ``(status, note, lower_bound_s,
    predicted_s)``, status "measured" where it runs. ``build``: its timed
    construction for the grid and method (None where skipped);
    ``history``: the call's (points, seconds) measured so far; ``over``:
    (points, seconds) of a smaller count over budget, or None."""
    skip = scipy_skip(method, shape, m)
    if skip is not None:
        return "skipped", skip, None, None
    if kind == "eval" and build["interrupted"]:
        return "over budget", f"its construction was interrupted at {build['s']:.1f} s: nothing to evaluate", \
            None, None
    if kind != "eval" and (build["interrupted"] or build["s"] > budget):
        return ("over budget", f"its construction alone took {build['s']:.1f} s"
                + (", interrupted" if build["interrupted"] else "") + "; not run", build["s"], None)
    if over is not None:
        return "over budget", f"over budget at {_count(over[0])} points; not run", over[1], None
    pred = predicted(history, m)
    if pred is not None and pred > 2 * cap:
        return ("over budget (predicted)", f"{pred:.0f} s predicted from {_count(history[-2][0])} and "
                f"{_count(history[-1][0])} points; not run", None, pred)
    return "measured", None, None, None


def run(grids, points, calls, thread_settings, rounds, budget, cap, only):
    records = []
    for shape in grids:
        grid, values, xi_all = data(shape, points)
        for method in METHODS:
            labels = [(kind, m, f"{kind} {method} {_shape(shape)} {_count(m)}") for m in points for kind in calls]
            labels = [x for x in labels if not only or re.search(only, x[2])]
            if not labels:
                continue
            # once per grid and method: scipy's construction (timed: the rule
            # for interpn and rgi), splinelab's per threads setting
            scipy_ip, build = None, None
            if scipy_skip(method, shape, 1) is None:
                holder = {}
                t, interrupted = _once(lambda: holder.setdefault(
                    "ip", si.RegularGridInterpolator(grid, values, method=method)), cap)
                build, scipy_ip = dict(s=t, interrupted=interrupted), holder.get("ip")
            ours_ip = {t: splinelab.RegularGridInterpolator(grid, values, method=method,
                                                            **({} if t is None else {"threads": t}))
                       for t in thread_settings}
            history, over = {kind: [] for kind in calls}, {kind: None for kind in calls}
            for kind, m, label in labels:
                theirs, ours = user_calls(kind, grid, values, xi_all[:m], method, thread_settings, scipy_ip, ours_ip)
                status, note, scipy_s, pred = scipy_plan(kind, method, shape, m, build, history[kind], over[kind],
                                                         budget, cap)
                named = ({"scipy": theirs} if status == "measured" else {}) | {_tname(t): f for t, f in ours.items()}
                res = measure(named, rounds, budget, cap)
                if "scipy" in res:
                    scipy_s = res["scipy"]["s"]
                    if res["scipy"]["status"] == "measured":
                        history[kind].append((m, scipy_s))
                    else:
                        over[kind] = (m, scipy_s)
                        status = "over budget"
                        note = "one call" + (f", interrupted at {cap:g} s" if res["scipy"]["status"] == "interrupted"
                                             else "")
                for t in thread_settings:
                    ours_s = res[_tname(t)]["s"]
                    rec = dict(call=kind, method=method, grid=list(shape), nodes=math.prod(shape), points=m,
                               threads=_tname(t), scipy_s=scipy_s, scipy_status=status, scipy_note=note,
                               scipy_predicted_s=pred, splinelab_s=ours_s,
                               ratio=None if scipy_s is None else ours_s / scipy_s, rounds=res[_tname(t)]["rounds"],
                               scipy_rounds=res["scipy"]["rounds"] if "scipy" in res else 0)
                    records.append(rec)
                    _print_case(label, rec)
            del scipy_ip, ours_ip
    return records


def summary(records):
    measured = [r for r in records if r["scipy_status"] == "measured"]
    bounded = [r for r in records if r["scipy_status"] == "over budget" and r["ratio"] is not None]
    if measured:
        print("\nlargest ratio (splinelab / scipy) per method and grid, over calls, points and threads "
              "(measured cases):")
        shapes = sorted({tuple(r["grid"]) for r in measured}, key=lambda s: (len(s), s))
        print(f"{'':<10}" + "".join(f"{_shape(s):>12}" for s in shapes) + f"{'all':>12}")
        for method in METHODS:
            rows = [r for r in measured if r["method"] == method]
            if not rows:
                continue
            cells = []
            for s in shapes:
                rs = [r["ratio"] for r in rows if tuple(r["grid"]) == s]
                cells.append(f"{max(rs):12.2f}" if rs else f"{'':>12}")
            print(f"{method:<10}" + "".join(cells) + f"{max(r['ratio'] for r in rows):12.2f}")
        ratios = [r["ratio"] for r in measured]
        print(f"\n{len(measured)} measured cases: {sum(x > 1.0 for x in ratios)} above 1.0, "
              f"{sum(x > 1.05 for x in ratios)} above 1.05; median ratio {np.median(ratios):.2f}, "
              f"max {max(ratios):.2f}")
    if bounded:
        print(f"{len(bounded)} cases with scipy over budget (ratio an upper bound): largest bound "
              f"{max(r['ratio'] for r in bounded):.3f}")
    others = [r for r in records if r["scipy_status"] != "measured" and r["ratio"] is None]
    for status in sorted({r["scipy_status"] for r in others}):
        print(f"{sum(r['scipy_status'] == status for r in others)} cases with scipy {status} "
              f"(splinelab timed alone)")


# ---------------------------------------------------------------- pyinterp


def pyinterp_rows(grids, m, thread_settings, rounds, budget, cap):
    """"linear" against pyinterp's bilinear on the 2-D ``grids`` at ``m``
    points: a check of its values against scipy's, then construction plus
    evaluation and evaluation alone."""
    try:
        import pyinterp
    except ImportError:
        print("\npyinterp is missing (pip install pyinterp): no comparison with its bilinear")
        return dict(available=False)
    print(f"\npyinterp {pyinterp.__version__}: linear against its bilinear (Grid2D, bivariate), {_count(m)} points")
    out = dict(available=True, version=pyinterp.__version__, checks=[], cases=[])
    nt = {None: 0, 1: 1}  # pyinterp's num_threads: 0 is every core

    def build(grid, values):
        x, y = (pyinterp.Axis(np.asarray(g, dtype=np.float64), is_circle=False) for g in grid)
        return pyinterp.Grid2D(x, y, values)  # array[i, j] at (x[i], y[j]): the grid's first axis is x

    def bilinear(g2, xi, t):
        return pyinterp.bivariate(g2, xi[:, 0], xi[:, 1], interpolator="bilinear", bounds_error=False,
                                  num_threads=nt[t])

    for shape in grids:
        grid, values, xi_all = data(shape, [m])
        xi = xi_all[:m]
        try:
            g2 = build(grid, values)
            diff = float(np.abs(bilinear(g2, xi, None) - si.RegularGridInterpolator(grid, values)(xi)).max())
        except Exception as exc:  # an API that changed: say so, keep the rest of the run
            print(f"  {_shape(shape)}: pyinterp failed: {type(exc).__name__}: {exc}")
            out["checks"].append(dict(grid=list(shape), points=m, error=f"{type(exc).__name__}: {exc}"))
            continue
        ok = bool(diff <= PYINTERP_TOL)
        print(f"  check {_shape(shape)}: max |pyinterp bilinear - scipy linear| at the {_count(m)} points = "
              f"{diff:.2e} ({'agrees' if ok else 'DISAGREES'}, tolerance {PYINTERP_TOL:g})")
        out["checks"].append(dict(grid=list(shape), points=m, max_abs_diff=diff, tol=PYINTERP_TOL, agrees=ok))
        if not ok:
            print("  not timed: its values are not scipy's")
            continue
        ips = {t: splinelab.RegularGridInterpolator(grid, values, **({} if t is None else {"threads": t}))
               for t in thread_settings}
        scipy_ip = si.RegularGridInterpolator(grid, values)
        kinds = {
            "rgi": (lambda: si.RegularGridInterpolator(grid, values)(xi),
                    {t: (lambda t=t: splinelab.RegularGridInterpolator(
                        grid, values, **({} if t is None else {"threads": t}))(xi)) for t in thread_settings},
                    {t: (lambda t=t: bilinear(build(grid, values), xi, t)) for t in thread_settings}),
            "eval": (lambda: scipy_ip(xi), {t: (lambda t=t: ips[t](xi)) for t in thread_settings},
                     {t: (lambda t=t: bilinear(g2, xi, t)) for t in thread_settings}),
        }
        for kind, (theirs, ours, pyi) in kinds.items():
            named = {"scipy": theirs} | {f"splinelab {_tname(t)}": f for t, f in ours.items()} \
                | {f"pyinterp {_tname(t)}": f for t, f in pyi.items()}
            res = measure(named, rounds, budget, cap)
            for t in thread_settings:
                o, p, s = (res[f"splinelab {_tname(t)}"], res[f"pyinterp {_tname(t)}"], res["scipy"])
                rec = dict(call=kind, method="linear", grid=list(shape), points=m, threads=_tname(t),
                           scipy_s=s["s"], pyinterp_s=p["s"], splinelab_s=o["s"], ratio_pyinterp=o["s"] / p["s"],
                           ratio_scipy=o["s"] / s["s"], rounds=o["rounds"])
                out["cases"].append(rec)
                print(f"  {kind:<5} {_shape(shape):<10} threads {rec['threads']:<7} scipy {_time(s['s'])}  "
                      f"pyinterp {_time(p['s'])}  splinelab {_time(o['s'])}  "
                      f"splinelab/pyinterp {rec['ratio_pyinterp']:5.2f}  [{rec['rounds']}]", flush=True)
    return out


# ---------------------------------------------------------------- main


def machine():
    model = ""
    try:
        with open("/proc/cpuinfo") as fh:
            model = next((ln.split(":", 1)[1].strip() for ln in fh if ln.startswith("model name")), "")
    except OSError:
        pass
    return dict(cpu_count=os.cpu_count(), cpu_affinity=len(os.sched_getaffinity(0)), cpu_model=model,
                python=platform.python_version(), numpy=np.__version__, scipy=scipy.__version__,
                splinelab=splinelab.__version__,
                # scipy's gcrotmk runs on OpenBLAS, whose threads swing its time on a loaded machine
                thread_env={k: os.environ[k] for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS",
                                                       "RAYON_NUM_THREADS") if k in os.environ})


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="8², 200²; 1 and 1e4 points; 3 rounds; budget 3 s")
    ap.add_argument("--rounds", type=int, help="rounds per case (default 5, --quick 3); fewer where the "
                                                "budget ends first")
    ap.add_argument("--threads", choices=("both", "default", "1"), default="both")
    ap.add_argument("--budget", type=float, help="seconds per case, both libraries (default 20, --quick 3)")
    ap.add_argument("--cap", type=float, help="seconds after which one scipy call is interrupted "
                                              "(default 3 x budget)")
    ap.add_argument("--calls", default=",".join(CALLS), help="which of interpn,rgi,eval")
    ap.add_argument("--only", help="a regular expression the case's label must match ('eval cubic 200x200 1e4'; "
                                   "'pyinterp': its rows alone)")
    ap.add_argument("--json", help="write every case to this file")
    args = ap.parse_args(argv)
    argv = sys.argv[1:] if argv is None else list(argv)
    load_before, start = os.getloadavg(), time.perf_counter()
    rounds = args.rounds or (3 if args.quick else 5)
    budget = args.budget or (3.0 if args.quick else 20.0)
    cap = args.cap or 3 * budget
    calls = [c for c in args.calls.split(",") if c]
    if not set(calls) <= set(CALLS):
        ap.error(f"--calls: one or more of {','.join(CALLS)}")
    threads = {"both": [None, 1], "default": [None], "1": [1]}[args.threads]
    grids, points = (QUICK_GRIDS, QUICK_POINTS) if args.quick else (GRIDS, POINTS)
    info = machine()
    print(f"splinelab {info['splinelab']}, scipy {info['scipy']}, numpy {info['numpy']}, python {info['python']}; "
          f"{info['cpu_count']} cores ({info['cpu_model']}), load {' '.join(f'{x:.2f}' for x in load_before)}; "
          f"{rounds} rounds, budget {budget:g} s a case, cap {cap:g} s a scipy call\n"
          f"[scipy/splinelab]: the samples each minimum is over (the warm-up counts for calls longer than a batch)")
    records = run(grids, points, calls, threads, rounds, budget, cap, args.only)
    if records:
        summary(records)
    pyi = dict(available=None)
    if not args.only or re.search(args.only, "pyinterp"):
        pyi = pyinterp_rows([g for g in ((200, 200), (2000, 2000)) if g in grids],
                            10_000 if args.quick else 1_000_000, threads, rounds, budget, cap)
    elapsed = time.perf_counter() - start
    print(f"\n{elapsed:.0f} s in all; load {' '.join(f'{x:.2f}' for x in os.getloadavg())} at the end")
    if args.json:
        prov = provenance(argv, load_before)  # before the file is opened: a tracked one would read as a change
        prov["command"] = " ".join([".venv/bin/python", "python/bench/rgi_speed.py", *argv])
        info["pyinterp"] = pyi.get("version")
        with open(args.json, "w") as fh:
            json.dump(dict(argv=argv, provenance=prov, machine=info, rounds=rounds, budget_s=budget, cap_s=cap,
                           batch_s=BATCH, grids=[list(g) for g in grids], points=points, calls=calls,
                           elapsed_s=elapsed, cases=records, pyinterp=pyi), fh, indent=1)


if __name__ == "__main__":
    main()
