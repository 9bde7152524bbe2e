"""Benchmark of the tribo-dynamic core on the seed 000 acceleration case (7218B, 1000 rpm to 0.5 s, then
10,000 rpm/s to 10,000 rpm at 1.4 s, held to 2 s), full 16-ball model.

Prints wall time, simulated time, real-time factor (wall / simulated; < 1 is faster than real time) of
the production integrator ('auto' by default: per 5 ms chunk the cheaper of the explicit adaptive RK4(3)
(FSAL error estimate) and the Rosenbrock-W ROS34PW2 with the arrow-structured ball/ring/cage Jacobian), and its speed-up
over the papers' fixed-step RK4 (dt = 1e-5 s) measured in the same run, with the relative difference of
the mean cage speed over the last 0.3 s between the two; also the explicit and implicit integrators alone.
``phases``: wall time, real-time factor, rhs calls, steps and speed-up over RK4 of each phase of the profile
(1000 rpm to 0.5 s, the ramp to 1.4 s, 10,000 rpm to 2 s).
``rtf_cpu``, ``speedup_vs_rk4_cpu`` and the phases' ``rtf_cpu``: the same from the thread's CPU time
(time.thread_time; the integration runs in the calling thread), the figures to compare on a shared machine
where other jobs stretch the wall time.
Numba compilation is done (or loaded from cache) before timing.

Right-hand-side cost: ``rhs_us`` is the mean wall time (``rhs_cpu_us`` the thread's CPU time beside it) of one call of the compiled right-hand side
(dynamics_kernels.rhs, all balls, both race contacts, cage) at the final state of the production run
(10,000 rpm when t_end = 2 s), averaged over --rhs-calls calls in one compiled loop; ``--rhs-only``
measures just that (after the production run to t_end) and skips the integrator timings.
All times: wall time (time.perf_counter) is the headline (``wall_s``, ``rtf``, ``speedup_vs_rk4``,
``<integrator>_wall_s``), thread CPU time beside it (``cpu_s``, ``rtf_cpu``, ``<integrator>_cpu_s``). The JSON output
carries the machine (bench/machine.py) under "machine"; the text output names it first.
Quickest check: ``--t-end 0.02 --no-others`` (or ``--rhs-only --t-end 0.02``).

    python bench/bench_dynamics.py [--t-end 2.0] [--json] [--fx 1000 --fz 3000] [--traction lubricated]
                                   [--integrator auto|adaptive|implicit|adaptive-rk4] [--no-others] [--rhs-only]
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from bearing_core.models.dynamics import (DynamicModel, DynamicsOptions, SEED000_PROFILE, records_to_dict,
                                   simulate_profile)
from bearing_core.bearing.geometry import load_preset
from bearing_core.models import dynamics_kernels as K
from numba import njit

sys.path.insert(0, str(Path(__file__).resolve().parent))
from machine import machine_info, machine_line  # noqa: E402


@njit(cache=True)
def _rhs_loop(n, t, y, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd):
    dy = np.zeros_like(y)
    acc = 0.0
    for _ in range(n):
        K.rhs(t, y, dy, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
        acc += dy[11]
    return acc


def rhs_cost_us(m, n=20000, cpu=False):
    """Mean wall time [us] of one right-hand-side call at the model's current state (the best of 3 loops of n
    calls); with cpu=True (wall, thread CPU) [us], each clock's best on its own."""
    diag = np.zeros(K.NOUT)
    bd = np.zeros((int(m.P[K.P_NB]), K.NBD))
    args = (m.t, m.y.copy(), m.P, m.U, m._tab_i, m._tab_o, m._ta0, m._tda, m._tp, *m._quad, diag, bd)
    _rhs_loop(10, *args)
    best = best_cpu = math.inf
    for _ in range(3):
        c0 = time.thread_time()
        t0 = time.perf_counter()
        _rhs_loop(n, *args)
        best = min(best, (time.perf_counter() - t0) / n * 1e6)
        best_cpu = min(best_cpu, (time.thread_time() - c0) / n * 1e6)
    return (best, best_cpu) if cpu else best


PHASES = (("1000rpm", 0.0, 0.5), ("ramp", 0.5, 1.4), ("10000rpm", 1.4, 2.0))


def run(integrator, t_end, loads, traction, mu, rtol, phases=None):
    """Run the profile to t_end; returns wall time [s], records, integrator stats, the model and thread CPU
    time [s]. phases (dict) receives per phase of PHASES its wall and CPU time [s], simulated time [s], rhs
    calls, accepted and rejected steps."""
    g = load_preset("7218B")
    m = DynamicModel(g, DynamicsOptions(integrator=integrator, reduced="full", traction=traction, mu=mu,
                                        rtol=rtol))
    m.initialize(1000 * math.pi / 30, loads)
    prof = [(t, n) for t, n in SEED000_PROFILE if t < t_end] + [(t_end, _speed_at(t_end))]
    out = []
    wall = cpu = 0.0
    for name, ta, tb in PHASES:
        tb = min(tb, t_end)
        if tb <= ta:
            continue
        seg = [(t, n) for t, n in prof if ta < t < tb]
        seg = [(ta, _speed_at(ta))] + seg + [(tb, _speed_at(tb))]
        s0 = m.stats[:3].copy()
        c0 = time.thread_time()
        t0 = time.perf_counter()
        out.append(simulate_profile(m, seg, record_dt=1e-3))
        w = time.perf_counter() - t0
        c = time.thread_time() - c0
        wall += w
        cpu += c
        if phases is not None:
            d = m.stats[:3] - s0
            phases[name] = {"wall_s": w, "simulated_s": tb - ta, "rtf": w / (tb - ta), "cpu_s": c,
                            "rtf_cpu": c / (tb - ta), "rhs_calls": int(d[2]),
                            "steps": int(d[0]), "rejected": int(d[1]), "mean_step_s": (tb - ta) / max(d[0], 1)}
    rec = records_to_dict(np.concatenate(out))
    return wall, rec, m.stats.copy(), m, cpu


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
    ap.add_argument("--integrator", default="auto", choices=("auto", "adaptive", "implicit", "adaptive-rk4"),
                    help="production integrator to time against RK4")
    ap.add_argument("--no-others", action="store_true", help="skip timing the other two integrators")
    ap.add_argument("--rhs-only", action="store_true", help="only the per-call right-hand-side cost")
    ap.add_argument("--rhs-calls", type=int, default=20000)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    loads = (a.fx, 0.0, a.fz, 0.0, 0.0)
    # warm-up: compile or load the numba cache for both integrators
    if a.rhs_only:
        _, _, _, m, _ = run(a.integrator, a.t_end, loads, a.traction, a.mu, a.rtol)
        us, us_cpu = rhs_cost_us(m, a.rhs_calls, cpu=True)
        out = {"machine": machine_info(), "rhs_us": us, "rhs_cpu_us": us_cpu, "t_state_s": m.t,
               "traction": a.traction, "loads_N": {"Fx": a.fx, "Fz": a.fz}}
        if a.json:
            print(json.dumps(out))
        else:
            print(machine_line(out["machine"]))
            print(f"7218B, state at t = {m.t:g} s, {a.traction}: {us:.2f} us per right-hand side, wall "
                  f"({us_cpu:.2f} us thread CPU)")
        return out
    for integ in ("adaptive", "implicit", "auto", "rk4", "adaptive-rk4"):
        run(integ, 0.002, loads, a.traction, a.mu, a.rtol)
    ph = {}
    wall, rec, st, m, cpu = run(a.integrator, a.t_end, loads, a.traction, a.mu, a.rtol, ph)
    rhs_us, rhs_cpu_us = rhs_cost_us(m, a.rhs_calls, cpu=True)
    ph0 = {}
    wall0, rec0, st0, _, cpu0 = run("rk4", a.t_end, loads, a.traction, a.mu, a.rtol, ph0)
    for k, v in ph.items():
        v["speedup_vs_rk4"] = ph0[k]["wall_s"] / v["wall_s"]
        v["speedup_vs_rk4_cpu"] = ph0[k]["cpu_s"] / v["cpu_s"]
    tail = rec["t"] > a.t_end - 0.3
    tail0 = rec0["t"] > a.t_end - 0.3
    c1 = rec["cage_speed"][tail].mean()
    c0 = rec0["cage_speed"][tail0].mean()
    out = {
        "machine": machine_info(),
        "simulated_s": a.t_end,
        "wall_s": wall,
        "rtf": wall / a.t_end,
        "cpu_s": cpu,
        "rtf_cpu": cpu / a.t_end,
        "baseline_wall_s": wall0,
        "baseline_cpu_s": cpu0,
        "speedup_vs_rk4": wall0 / wall,
        "speedup_vs_rk4_cpu": cpu0 / cpu,
        "cage_speed_rel_diff": abs(c1 / c0 - 1.0),
        "cage_speed_rpm": c1 * 30 / math.pi,
        "baseline_cage_speed_rpm": c0 * 30 / math.pi,
        "steps": int(st[0]), "rejected": int(st[1]), "rhs_calls": int(st[2]),
        "baseline_rhs_calls": int(st0[2]),
        "rhs_us": rhs_us,
        "rhs_cpu_us": rhs_cpu_us,
        "phases": ph,
        "loads_N": {"Fx": a.fx, "Fz": a.fz}, "traction": a.traction, "integrator": a.integrator,
    }
    if not a.no_others:
        for integ in ("adaptive", "implicit", "auto", "adaptive-rk4"):
            if integ == a.integrator:
                continue
            w2, rec2, st2, _, cpu2 = run(integ, a.t_end, loads, a.traction, a.mu, a.rtol)
            c2 = rec2["cage_speed"][rec2["t"] > a.t_end - 0.3].mean()
            out[f"{integ}_wall_s"] = w2
            out[f"{integ}_cpu_s"] = cpu2
            out[f"{integ}_speedup_vs_rk4"] = wall0 / w2
            out[f"{integ}_cage_speed_rel_diff"] = abs(c2 / c0 - 1.0)
    if a.json:
        print(json.dumps(out))
    else:
        print(machine_line(out["machine"]))
        print(f"7218B seed-000 profile, {a.t_end:g} s simulated, Fx {a.fx:g} N, Fz {a.fz:g} N, {a.traction}")
        print(f"production ({a.integrator}, rtol {a.rtol:g}): wall {wall:.2f} s, real-time factor {wall / a.t_end:.2f} "
              f"(thread CPU {cpu / a.t_end:.2f}), "
              f"{int(st[2])} rhs calls ({int(st[0])} steps, {int(st[1])} rejected)")
        print(f"right-hand side: {rhs_us:.2f} us per call at the final state ({rhs_cpu_us:.2f} us thread CPU)")
        for k, v in ph.items():
            print(f"  {k}: real-time factor {v['rtf']:.2f} (thread CPU {v['rtf_cpu']:.2f}), {v['rhs_calls'] / v['simulated_s']:.0f} rhs calls per "
                  f"simulated s, mean step {v['mean_step_s']:.2e} s ({v['rejected']} rejected), "
                  f"speed-up vs RK4 {v['speedup_vs_rk4']:.2f}x")
        print(f"baseline (RK4, dt 1e-5 s): wall {wall0:.2f} s (thread CPU {cpu0:.2f} s), {int(st0[2])} rhs calls")
        print(f"speed-up vs RK4: {wall0 / wall:.2f}x (thread CPU {cpu0 / cpu:.2f}x); mean cage speed over the last 0.3 s: "
              f"{c1 * 30 / math.pi:.1f} vs {c0 * 30 / math.pi:.1f} rpm (rel. diff {abs(c1 / c0 - 1):.2e})")
        for integ in ("adaptive", "implicit", "auto", "adaptive-rk4"):
            if f"{integ}_wall_s" in out:
                print(f"  {integ}: wall {out[integ + '_wall_s']:.2f} s (thread CPU {out[integ + '_cpu_s']:.2f} s), speed-up vs RK4 "
                      f"{out[integ + '_speedup_vs_rk4']:.2f}x, cage rel. diff {out[integ + '_cage_speed_rel_diff']:.2e}")
    return out


if __name__ == "__main__":
    main()
