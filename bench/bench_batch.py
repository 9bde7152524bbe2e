"""Throughput of independent operating points in one process (bearing_core.dynamics.advance_many: a
thread pool over models whose integration kernels release the GIL) against running them one after the
other: 7218B, full 16-ball model, lubricated, 'auto' integrator, n points at different loads and speeds,
each simulated for --t-sim seconds after a compiled warm-up.

    python bench/bench_batch.py [--points 4] [--t-sim 0.02] [--workers 2] [--json]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import time

from bearing_core.dynamics import DynamicModel, DynamicsOptions, advance_many
from bearing_core.geometry import load_preset


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


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=4)
    ap.add_argument("--t-sim", type=float, default=0.02, help="simulated time per point [s]")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    seq = _models(a.points)
    t0 = time.perf_counter()
    for m in seq:
        m.advance(m.t + a.t_sim)
    w_seq = time.perf_counter() - t0
    par = _models(a.points)
    t0 = time.perf_counter()
    advance_many(par, [m.t + a.t_sim for m in par], workers=a.workers)
    w_par = time.perf_counter() - t0
    same = all(abs(p.y - s.y).max() == 0.0 for p, s in zip(par, seq))
    out = {"points": a.points, "simulated_s_per_point": a.t_sim, "workers": a.workers,
           "sequential_wall_s": w_seq, "batch_wall_s": w_par, "throughput_gain": w_seq / w_par,
           "identical_results": bool(same), "cpus": os.cpu_count()}
    if a.json:
        print(json.dumps(out))
    else:
        print(f"{a.points} points x {a.t_sim:g} s simulated: one after the other {w_seq:.2f} s, "
              f"advance_many ({a.workers} threads) {w_par:.2f} s: {w_seq / w_par:.2f}x throughput "
              f"(results identical: {same})")
    return out


if __name__ == "__main__":
    main()
