"""Benchmark of the tribo-dynamic core on the seed 000 acceleration case (7218B, 1000 rpm to 0.5 s, then
10,000 rpm/s to 10,000 rpm at 1.4 s, held to 2 s), full 16-ball model.

Prints wall time, simulated time, real-time factor (wall / simulated; < 1 is faster than real time) of
the production integrator ('auto' by default: per 5 ms chunk the cheaper of the explicit Dormand-Prince
5(4) and the Rosenbrock-W ROS34PW2 with the arrow-structured ball/ring/cage Jacobian), and its speed-up
over the papers' fixed-step RK4 (dt = 1e-5 s) measured in the same run, with the relative difference of
the mean cage speed over the last 0.3 s between the two; also the explicit and implicit integrators alone.
Numba compilation is done (or loaded from cache) before timing.

Right-hand-side cost: ``rhs_us`` is the mean wall time of one call of the compiled right-hand side
(dynamics_kernels.rhs, all balls, both race contacts, cage) at the final state of the production run
(10,000 rpm when t_end = 2 s), averaged over --rhs-calls calls in one compiled loop; ``--rhs-only``
measures just that (after the production run to t_end) and skips the integrator timings.

    python bench/bench_dynamics.py [--t-end 2.0] [--json] [--fx 1000 --fz 3000] [--traction lubricated]
                                   [--integrator auto|adaptive|implicit] [--no-others] [--rhs-only]
"""
from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np

from bearing_core.dynamics import (DynamicModel, DynamicsOptions, SEED000_PROFILE, records_to_dict,
                                   simulate_profile)
from bearing_core.geometry import load_preset
from bearing_core import dynamics_kernels as K
from numba import njit


@njit(cache=True)
def _rhs_loop(n, t, y, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd):
    dy = np.zeros_like(y)
    acc = 0.0
    for _ in range(n):
        K.rhs(t, y, dy, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
        acc += dy[11]
    return acc


def rhs_cost_us(m, n=20000):
    """Mean wall time [us] of one right-hand-side call at the model's current state."""
    diag = np.zeros(K.NOUT)
    bd = np.zeros((int(m.P[K.P_NB]), K.NBD))
    args = (m.t, m.y.copy(), m.P, m.U, m._tab_i, m._tab_o, m._ta0, m._tda, m._tp, *m._quad, diag, bd)
    _rhs_loop(10, *args)
    best = math.inf
    for _ in range(3):
        t0 = time.perf_counter()
        _rhs_loop(n, *args)
        best = min(best, (time.perf_counter() - t0) / n * 1e6)
    return best


def run(integrator, t_end, loads, traction, mu, rtol):
    g = load_preset("7218B")
    m = DynamicModel(g, DynamicsOptions(integrator=integrator, reduced="full", traction=traction, mu=mu,
                                        rtol=rtol))
    m.initialize(1000 * math.pi / 30, loads)
    prof = [(t, n) for t, n in SEED000_PROFILE if t < t_end] + [(t_end, _speed_at(t_end))]
    t0 = time.perf_counter()
    rec = records_to_dict(simulate_profile(m, prof, record_dt=1e-3))
    wall = time.perf_counter() - t0
    return wall, rec, m.stats.copy(), m


def _speed_at(t):
    pts = SEED000_PROFILE
    return float(np.interp(t, [p[0] for p in pts], [p[1] for p in pts]))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t-end", type=float, default=2.0, help="simulated time [s] (<= 2 follows seed 000)")
    ap.add_argument("--fx", type=float, default=1000.0, help="radial load [N]")
    ap.add_argument("--fz", type=float, default=3000.0, help="axial load [N]")
    ap.add_argument("--traction", default="lubricated", choices=("lubricated", "coulomb", "kalker"))
    ap.add_argument("--mu", type=float, default=0.1)
    ap.add_argument("--rtol", type=float, default=1e-4)
    ap.add_argument("--integrator", default="auto", choices=("auto", "adaptive", "implicit"),
                    help="production integrator to time against RK4")
    ap.add_argument("--no-others", action="store_true", help="skip timing the other two integrators")
    ap.add_argument("--rhs-only", action="store_true", help="only the per-call right-hand-side cost")
    ap.add_argument("--rhs-calls", type=int, default=20000)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    loads = (a.fx, 0.0, a.fz, 0.0, 0.0)
    # warm-up: compile or load the numba cache for both integrators
    if a.rhs_only:
        _, _, _, m = run(a.integrator, a.t_end, loads, a.traction, a.mu, a.rtol)
        us = rhs_cost_us(m, a.rhs_calls)
        out = {"rhs_us": us, "t_state_s": m.t, "traction": a.traction, "loads_N": {"Fx": a.fx, "Fz": a.fz}}
        print(json.dumps(out) if a.json else
              f"7218B, state at t = {m.t:g} s, {a.traction}: {us:.2f} us per right-hand side")
        return out
    for integ in ("adaptive", "implicit", "auto", "rk4"):
        run(integ, 0.002, loads, a.traction, a.mu, a.rtol)
    wall, rec, st, m = run(a.integrator, a.t_end, loads, a.traction, a.mu, a.rtol)
    rhs_us = rhs_cost_us(m, a.rhs_calls)
    wall0, rec0, st0, _ = run("rk4", a.t_end, loads, a.traction, a.mu, a.rtol)
    tail = rec["t"] > a.t_end - 0.3
    tail0 = rec0["t"] > a.t_end - 0.3
    c1 = rec["cage_speed"][tail].mean()
    c0 = rec0["cage_speed"][tail0].mean()
    out = {
        "simulated_s": a.t_end,
        "wall_s": wall,
        "rtf": wall / a.t_end,
        "baseline_wall_s": wall0,
        "speedup_vs_rk4": wall0 / wall,
        "cage_speed_rel_diff": abs(c1 / c0 - 1.0),
        "cage_speed_rpm": c1 * 30 / math.pi,
        "baseline_cage_speed_rpm": c0 * 30 / math.pi,
        "steps": int(st[0]), "rejected": int(st[1]), "rhs_calls": int(st[2]),
        "baseline_rhs_calls": int(st0[2]),
        "rhs_us": rhs_us,
        "loads_N": {"Fx": a.fx, "Fz": a.fz}, "traction": a.traction, "integrator": a.integrator,
    }
    if not a.no_others:
        for integ in ("adaptive", "implicit", "auto"):
            if integ == a.integrator:
                continue
            w2, rec2, st2, _ = run(integ, a.t_end, loads, a.traction, a.mu, a.rtol)
            c2 = rec2["cage_speed"][rec2["t"] > a.t_end - 0.3].mean()
            out[f"{integ}_wall_s"] = w2
            out[f"{integ}_speedup_vs_rk4"] = wall0 / w2
            out[f"{integ}_cage_speed_rel_diff"] = abs(c2 / c0 - 1.0)
    if a.json:
        print(json.dumps(out))
    else:
        print(f"7218B seed-000 profile, {a.t_end:g} s simulated, Fx {a.fx:g} N, Fz {a.fz:g} N, {a.traction}")
        print(f"production ({a.integrator}, rtol {a.rtol:g}): wall {wall:.2f} s, real-time factor {wall / a.t_end:.2f}, "
              f"{int(st[2])} rhs calls ({int(st[0])} steps, {int(st[1])} rejected)")
        print(f"right-hand side: {rhs_us:.2f} us per call at the final state")
        print(f"baseline (RK4, dt 1e-5 s): wall {wall0:.2f} s, {int(st0[2])} rhs calls")
        print(f"speed-up vs RK4: {wall0 / wall:.2f}x; mean cage speed over the last 0.3 s: "
              f"{c1 * 30 / math.pi:.1f} vs {c0 * 30 / math.pi:.1f} rpm (rel. diff {abs(c1 / c0 - 1):.2e})")
        for integ in ("adaptive", "implicit", "auto"):
            if f"{integ}_wall_s" in out:
                print(f"  {integ}: wall {out[integ + '_wall_s']:.2f} s, speed-up vs RK4 "
                      f"{out[integ + '_speedup_vs_rk4']:.2f}x, cage rel. diff {out[integ + '_cage_speed_rel_diff']:.2e}")
    return out


if __name__ == "__main__":
    main()
