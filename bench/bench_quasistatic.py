"""Warm wall time of one Jones-Harris quasi-static solve (bearing_core.models.quasistatic) over a matrix of cases,
with and without the 5x5 stiffness matrix, and of the tribological quasi-static solve
(bearing_core.models.quasistatic_tribo), which starts from it (7218B, lubricated, 3000 rpm, Fx 1 kN, Fz 3 kN;
tribo_jones_harris_start_ms: the Jones-Harris start inside it, without stiffness, to the start's tolerance).

    python bench/bench_quasistatic.py [--quick] [--repeat N] [--matrix all|two-point|four-point]
                                      [--clock wall|thread] [--save ref.npz] [--compare ref.npz] [--json]

Matrix: the two-point presets 7218B, 7008-ma2023, wan-105; speeds 0, 3000, 10,000, 20,000 rpm; loads pure
axial, combined, radial-heavy, with moments; raceway control outer / inner / hybrid. Four-point matrix
(FourPointQuasiStaticModel, preset QJ1044, outer control): 0, 3000, 10,000 rpm; loads radial (Fx 10 kN),
combined (Fx 2 kN, Fz 10 kN) and light combined (Fx 1 kN, Fz 3 kN); its summary keys start with
'fourpoint_', the other summary keys cover the two-point matrix only. Each solve is run once to compile
and warm up, then timed as the best of --repeat runs (the machine is shared: the best run is the cost of
the solve, the others add other jobs' time slices). Wall time is the headline (``ms_without``,
``ms_with_stiffness``, ``median_ms_*``, ``tribo_*_s``, ``first_solve_s``); the thread's CPU time of the same runs
is beside it under the same names with ``_cpu`` (``ms_without_cpu``, ``median_ms_without_cpu``,
``tribo_lubricated_cpu_s``, ...). --clock thread makes the headline keys thread CPU time as before (kept for
old scripts). The JSON summary carries the machine (bench/machine.py) under "machine"; the text output names
it first. Quickest check: ``--quick --repeat 1 --matrix two-point``.

--save writes every case's results (u, ball loads, contact angles, deflections, orbital speed, stiffness)
to an .npz file; --compare reads such a file (e.g. written by another version of the code) and prints the
largest relative difference of each quantity over the matrix (|new - old| / max|old| per array).
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from bearing_core.errors import ConvergenceError
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.quasistatic import FourPointQuasiStaticModel, QuasiStaticModel

sys.path.insert(0, str(Path(__file__).resolve().parent))
from machine import machine_info, machine_line  # noqa: E402

RPM = math.pi / 30
PRESETS = ("7218B", "7008-ma2023", "wan-105")
SPEEDS_RPM = (0.0, 3000.0, 10000.0, 20000.0)
FIELDS = ("u", "Q_i", "Q_o", "alpha_i", "alpha_o", "delta_i", "delta_o", "omega_m", "omega_R", "beta", "F_i",
          "F_o", "p_i", "stiffness")
FIELDS4 = FIELDS + ("Q_c", "alpha_c", "delta_c", "F_c")
FOURPOINT_PRESET = "QJ1044"
FOURPOINT_SPEEDS_RPM = (0.0, 3000.0, 10000.0)
FOURPOINT_LOADS = (("radial", (10000.0, 0.0, 0.0, 0.0, 0.0)),
                   ("combined", (2000.0, 0.0, 10000.0, 0.0, 0.0)),
                   ("light-combined", (1000.0, 0.0, 3000.0, 0.0, 0.0)))


def load_cases(g):
    """(name, loads) scaled to the bearing's size: C0-like scale from Z and D."""
    s = g.Z * (g.D / 0.0222) ** 2 * 200.0          # ~3 kN for 7218B
    ra = 0.5 * g.dm
    return [("axial", (0.0, 0.0, s, 0.0, 0.0)),
            ("combined", (s / 3, 0.0, s, 0.0, 0.0)),
            ("radial-heavy", (s, 0.3 * s, 0.3 * s, 0.0, 0.0)),
            ("moment", (0.2 * s, 0.0, s, 0.05 * s * ra, -0.03 * s * ra))]


def cases(quick):
    presets = PRESETS[:1] if quick else PRESETS
    speeds = (0.0, 3000.0) if quick else SPEEDS_RPM
    controls = ("outer",) if quick else ("outer", "inner", "hybrid")
    for p in presets:
        g = load_preset(p)
        for ctrl in controls:
            for n in speeds:
                for lname, loads in load_cases(g):
                    yield p, g, ctrl, n, lname, loads


def fourpoint_cases():
    g = load_preset(FOURPOINT_PRESET)
    for n in FOURPOINT_SPEEDS_RPM:
        for lname, loads in FOURPOINT_LOADS:
            yield FOURPOINT_PRESET, g, "outer", n, lname, loads


CLOCK = {"wall": time.perf_counter, "thread": time.thread_time}


def timed(fn, repeat, clock=time.perf_counter, cpu=False):
    """Best of `repeat` runs of fn() on `clock` [s]; with cpu=True (that, the best thread CPU time)."""
    ts, cs = [], []
    for _ in range(repeat):
        c0 = time.thread_time()
        t0 = clock()
        fn()
        ts.append(clock() - t0)
        cs.append(time.thread_time() - c0)
    return (float(np.min(ts)), float(np.min(cs))) if cpu else float(np.min(ts))


def _summary(rows, prefix=""):
    ok = [r for r in rows if r["ok"]]
    out = {f"{prefix}cases": len(rows), f"{prefix}failed": len(rows) - len(ok)}
    if ok:
        out.update({f"{prefix}median_ms_without": float(np.median([r["ms_without"] for r in ok])),
                    f"{prefix}max_ms_without": float(np.max([r["ms_without"] for r in ok])),
                    f"{prefix}median_ms_with_stiffness": float(np.median([r["ms_with_stiffness"] for r in ok])),
                    f"{prefix}max_ms_with_stiffness": float(np.max([r["ms_with_stiffness"] for r in ok])),
                    f"{prefix}median_ms_without_cpu": float(np.median([r["ms_without_cpu"] for r in ok])),
                    f"{prefix}max_ms_without_cpu": float(np.max([r["ms_without_cpu"] for r in ok])),
                    f"{prefix}median_ms_with_stiffness_cpu": float(np.median([r["ms_with_stiffness_cpu"] for r in ok])),
                    f"{prefix}max_ms_with_stiffness_cpu": float(np.max([r["ms_with_stiffness_cpu"] for r in ok]))})
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--save")
    ap.add_argument("--compare")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--no-tribo", action="store_true", help="skip the tribological solve timing")
    ap.add_argument("--matrix", choices=("all", "two-point", "four-point"), default="all",
                    help="which matrix of cases to time (default: both)")
    ap.add_argument("--clock", choices=tuple(CLOCK), default="wall",
                    help="headline keys: wall time (perf_counter, default) or the thread's CPU time (thread_time); "
                         "the *_cpu keys are thread CPU time either way")
    a = ap.parse_args()
    clock = CLOCK[a.clock]
    mach = machine_info()
    if not a.json:
        print(machine_line(mach, clock="wall time, thread CPU time beside it" if a.clock == "wall"
                           else "thread CPU time (--clock thread)"), flush=True)
    c0 = time.thread_time()
    t0 = time.perf_counter()
    if a.matrix != "four-point":
        m0 = QuasiStaticModel(load_preset("7218B"))
        m0.solve(3000 * RPM, (1000.0, 0, 3000.0, 0, 0))
    first_s = time.perf_counter() - t0
    summary = dict(machine=mach, clock=a.clock, first_solve_s=first_s, first_solve_cpu_s=time.thread_time() - c0)
    if a.matrix != "two-point":
        c0 = time.thread_time()
        t0 = time.perf_counter()
        FourPointQuasiStaticModel(load_preset(FOURPOINT_PRESET)).solve(3000 * RPM, (1000.0, 0, 3000.0, 0, 0))
        summary["fourpoint_first_solve_s"] = time.perf_counter() - t0
        summary["fourpoint_first_solve_cpu_s"] = time.thread_time() - c0
    rows, rows4, saved = [], [], {}
    ref = np.load(a.compare) if a.compare else None
    worst = {}
    matrix = []
    if a.matrix != "four-point":
        matrix += [(c, QuasiStaticModel, FIELDS, rows) for c in cases(a.quick)]
    if a.matrix != "two-point":
        matrix += [(c, FourPointQuasiStaticModel, FIELDS4, rows4) for c in fourpoint_cases()]
    for (p, g, ctrl, n, lname, loads), cls, fields, out in matrix:
        key = f"{p}|{ctrl}|{n:g}|{lname}"
        m = cls(g, ctrl)
        w = n * RPM
        try:
            r = m.solve(w, loads, stiffness=True)
        except ConvergenceError as e:
            print(f"{key:40s} FAIL {str(e)[:100]}")
            out.append(dict(case=key, ok=False))
            continue
        t_k, c_k = timed(lambda: m.solve(w, loads, stiffness=True), a.repeat, clock, cpu=True)
        t_n, c_n = timed(lambda: m.solve(w, loads, stiffness=False), a.repeat, clock, cpu=True)
        out.append(dict(case=key, ok=True, ms_with_stiffness=1e3 * t_k, ms_without=1e3 * t_n,
                        ms_with_stiffness_cpu=1e3 * c_k, ms_without_cpu=1e3 * c_n, iterations=r.iterations))
        msg = ""
        for f in fields:
            v = np.asarray(getattr(r, f), dtype=float)
            saved[f"{key}|{f}"] = v
            if ref is not None and f"{key}|{f}" in ref:
                o = ref[f"{key}|{f}"]
                d = float(np.max(np.abs(v - o)) / max(np.max(np.abs(o)), 1e-300))
                worst[f] = max(worst.get(f, 0.0), d)
                msg = f"  max rel diff {max(worst.get(f, 0) for f in fields):.1e}"
        print(f"{key:40s} {1e3 * t_n:8.2f} ms ({1e3 * c_n:6.2f} CPU)  {1e3 * t_k:8.2f} ms with stiffness "
              f"({1e3 * c_k:6.2f} CPU)  it {r.iterations:3d}{msg}",
              flush=True)
    if a.matrix != "four-point":
        summary.update(_summary(rows))
    if a.matrix != "two-point":
        summary.update(_summary(rows4, "fourpoint_"))
    if not a.no_tribo and a.matrix != "four-point":
        from bearing_core.models.dynamics import DynamicsOptions
        from bearing_core.models.quasistatic_tribo import TriboQuasiStaticModel, solve_tribo_quasistatic
        g = load_preset("7218B")
        for tr in ("lubricated",):
            opt = DynamicsOptions(traction=tr, mu=0.1)
            solve_tribo_quasistatic(g, 3000 * RPM, (1000.0, 0, 3000.0, 0, 0), opt)
            summary[f"tribo_{tr}_s"], summary[f"tribo_{tr}_cpu_s"] = timed(
                lambda: solve_tribo_quasistatic(g, 3000 * RPM, (1000.0, 0, 3000.0, 0, 0), opt), 2, cpu=True)
            m7 = QuasiStaticModel(g)
            w7, c7 = timed(lambda: m7.solve(3000 * RPM, (1000.0, 0, 3000.0, 0, 0), stiffness=False,
                                            tol=TriboQuasiStaticModel.jones_harris_tol), a.repeat, cpu=True)
            summary["tribo_jones_harris_start_ms"], summary["tribo_jones_harris_start_cpu_ms"] = 1e3 * w7, 1e3 * c7
    if worst:
        summary["max_rel_diff"] = worst
    if a.save:
        np.savez(a.save, **saved)
    print(json.dumps(summary, indent=1) if a.json else
          "\n".join(f"{k}: {v}" for k, v in summary.items() if k != "machine"))
    if a.json:
        print(json.dumps(rows + rows4))


if __name__ == "__main__":
    main()
