"""Throughput of independent operating points in one process: bearing_core.models.dynamics.advance_many (a thread
pool over models whose integration kernels release the GIL) against the same models advanced one after the
other, and the sweep's batch evaluator (sweep.DynamicWindow.run_batch, the points' windows advanced together)
against its one-point-at-a-time call.

    PYTHONPATH=$PWD python bench/bench_batch.py [--points 4] [--t-sim 0.02] [--workers 2] [--json]

Part 1 (advance_many): 7218B, full 16-ball model, lubricated, 'auto' integrator, n points at different loads and
speeds, each simulated for --t-sim seconds after a compiled warm-up of 2 ms. Part 2 (sweep batch): the
'dynamic' sweep model on 7008-ma2023 (lubricated, Fz 300-900 N, 3000-12,000 rpm; windows of --t-sim / 2, at most
--t-sim simulated), start (model set-up and Jones-Harris start) included. Throughput = points per wall second.

The machine may be shared: a control (a trivial nogil numba loop, alone and in --workers threads at once, before
and after the measurement) gives the number of cores the threads actually got; compare the batch gains with it.
All ratios come from this one run. Times are wall time (the headline; throughput and gains come from it) with the
process's CPU time beside it (``..._cpu_s``: time.process_time, all threads of this process, since the batch runs
in a thread pool; CPU time above the wall time means more than one core worked). The JSON output carries the
machine (bench/machine.py) under "machine"; the text output names it first.
Quickest check: ``--points 2 --t-sim 0.005``.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np  # noqa: E402
from numba import njit  # noqa: E402

from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, advance_many  # noqa: E402
from bearing_core.bearing.geometry import load_preset  # noqa: E402
from machine import Timer, machine_info, machine_line  # noqa: E402


@njit(nogil=True, cache=True)
def _spin(n):
    """A trivial compute-bound loop that releases the GIL (the control)."""
    s = 0.0
    for i in range(n):
        s += math.sin(i * 1e-6) * 1e-3
    return s


def free_cores(threads: int, n: int = 30_000_000, repeats: int = 3) -> float:
    """Cores the process got: threads x (time of one loop alone) / (time of `threads` loops at once), the
    median of `repeats` alternations."""
    import statistics
    _spin(1000)
    out = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        _spin(n)
        t1 = time.perf_counter() - t0
        ths = [threading.Thread(target=_spin, args=(n,)) for _ in range(threads)]
        t0 = time.perf_counter()
        for t in ths:
            t.start()
        for t in ths:
            t.join()
        out.append(threads * t1 / (time.perf_counter() - t0))
    return statistics.median(out)


def _models(n):
    g = load_preset("7218B")
    out = []
    for k in range(n):
        m = DynamicModel(g, DynamicsOptions(integrator="auto", reduced="full", traction="lubricated"))
        rpm = 2000.0 + 6000.0 * k / max(n - 1, 1)
        m.initialize(rpm * math.pi / 30.0, (500.0 + 250.0 * k, 0.0, 3000.0, 0.0, 0.0))
        m.advance(2e-3)          # compile / load the kernels, settle the start
        out.append(m)
    return out


def _sweep_points(n):
    from bearing_core.maps import sweep as S
    rpm = np.linspace(3000.0, 12000.0, n).tolist()
    fz = [300.0 + 600.0 * (k % 3) / 2 for k in range(n)]
    return S.SweepSpec(model="dynamic", base={"bearing": "7008-ma2023"},
                       points_list=[{"speed_rpm": r, "fz_N": f} for r, f in zip(rpm, fz)]).points()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=4)
    ap.add_argument("--t-sim", type=float, default=0.02, help="simulated time per point [s]")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="threads")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    from bearing_core.maps import sweep as S
    c0 = free_cores(a.workers)

    seq = _models(a.points)
    with Timer("process") as T:
        for m in seq:
            m.advance(m.t + a.t_sim)
    w_seq, c_seq = T.wall_s, T.cpu_s
    par = _models(a.points)
    with Timer("process") as T:
        advance_many(par, [m.t + a.t_sim for m in par], workers=a.workers)
    w_par, c_par = T.wall_s, T.cpu_s
    same = all(np.array_equal(p.y, s.y) for p, s in zip(par, seq))

    ev = S.DynamicWindow()
    pts = _sweep_points(a.points)
    opts = {"window_s": a.t_sim / 2, "max_time_s": a.t_sim, "steady_tol": 1e-8, "torque_tol": 1e-8}
    ev(pts[0], opts)                                    # warm-up (kernels loaded)
    with Timer("process") as T:
        ev_setup = [ev._start(p, opts) for p in pts]
    w_setup, c_setup = T.wall_s, T.cpu_s
    shared = {}
    with Timer("process") as T:
        ev_setup = [ev._start(p, opts, shared) for p in pts]     # as in a batch: one construction per bearing
    w_setup_shared, c_setup_shared = T.wall_s, T.cpu_s
    del ev_setup
    with Timer("process") as T:
        one = [ev(p, opts) for p in pts]
    w_one, c_one = T.wall_s, T.cpu_s
    with Timer("process") as T:
        bat = ev.run_batch(pts, opts, threads=a.workers)
    w_bat, c_bat = T.wall_s, T.cpu_s
    same_sweep = all(x == y for x, y in zip(one, bat))
    c1 = free_cores(a.workers)

    out = {"machine": machine_info(), "cpu_clock": "process (time.process_time, all threads)",
           "points": a.points, "simulated_s_per_point": a.t_sim, "workers": a.workers, "cpus": os.cpu_count(),
           "control_free_cores_before": c0, "control_free_cores_after": c1,
           "advance_many": {"sequential_wall_s": w_seq, "batch_wall_s": w_par,
                            "sequential_cpu_s": c_seq, "batch_cpu_s": c_par,
                            "points_per_s_sequential": a.points / w_seq, "points_per_s_batch": a.points / w_par,
                            "throughput_gain": w_seq / w_par, "identical_results": bool(same)},
           "sweep_batch": {"one_at_a_time_wall_s": w_one, "batch_wall_s": w_bat,
                           "one_at_a_time_cpu_s": c_one, "batch_cpu_s": c_bat,
                           "points_per_s_one_at_a_time": a.points / w_one, "points_per_s_batch": a.points / w_bat,
                           "throughput_gain": w_one / w_bat, "setup_wall_s_per_point": w_setup / a.points,
                           "setup_wall_s_per_point_shared_model": w_setup_shared / a.points,
                           "setup_cpu_s_per_point": c_setup / a.points,
                           "setup_cpu_s_per_point_shared_model": c_setup_shared / a.points,
                           "identical_results": bool(same_sweep)},
           "loadavg_1min": os.getloadavg()[0]}
    if a.json:
        print(json.dumps(out, indent=1))
    else:
        print(machine_line(out["machine"], clock="wall time, process CPU time (all threads) beside it"))
        print(f"control: {c0:.2f} / {c1:.2f} of {a.workers} cores free (before / after); "
              f"load {out['loadavg_1min']:.1f}")
        print(f"advance_many: {a.points} points x {a.t_sim:g} s: one after the other {w_seq:.2f} s "
              f"(CPU {c_seq:.2f} s), {a.workers} threads {w_par:.2f} s (CPU {c_par:.2f} s): {w_seq / w_par:.2f}x (identical: {same})")
        print(f"sweep batch (dynamic): one at a time {w_one:.2f} s (CPU {c_one:.2f} s), "
              f"batch {w_bat:.2f} s (CPU {c_bat:.2f} s): {w_one / w_bat:.2f}x "
              f"(identical: {same_sweep}); set-up {w_setup / a.points * 1e3:.0f} ms per point, "
              f"{w_setup_shared / a.points * 1e3:.0f} ms with the model constructed once per batch")
    return out


if __name__ == "__main__":
    main()
