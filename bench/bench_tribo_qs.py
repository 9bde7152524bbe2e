"""Quasi-static tribological model (bearing_core.models.quasistatic_tribo): convergence and cost over a matrix of
cases, and a seed 000 Table 1 analogue (Jones-Harris vs quasi-static tribological vs tribo-dynamic model).

    python bench/bench_tribo_qs.py [--quick] [--out out/]
    python bench/bench_tribo_qs.py --speed [--repeat N] [--save ref.npz] [--compare ref.npz] [--only SUBSTR]
    python bench/bench_tribo_qs.py --sweep [--repeat N]

(a) matrix: 7218B; traction Kalker mu 0.1 and 0.001, Coulomb 0.1, lubricated; 1000 / 3000 / 10,000 rpm;
    loads (Fx, Fz) = (0, 3000), (1000, 3000), (3000, 2000) N: converged or not, residual evaluations, wall
    time, cage (mean orbital) speed against Jones-Harris.
(b) Table 1 analogue: seed 000 compares its J-H model, its quasi-static tribological model and its
    tribo-dynamic model (mean values) for one bearing and load. Its bearing and loads are not ours to
    reuse (refs. [37, 44], not given), so the same three columns are computed for 7218B, Kalker mu 0.1,
    Fx 1000 N, Fz 3000 N at 10,000 rpm; the dynamic column comes from a
    0.3 s run (full model, started from the tribological solution): inner-ring displacements and cage speed
    averaged over the last 0.1 s, ball quantities a snapshot at the end of the ball nearest azimuth 0.
Writes out/bench_tribo_qs.json.

--speed: cost per load case instead (wall time of solve_tribo_quasistatic, the whole call: model
set-up, Jones-Harris start and solve; median of --repeat warm runs; thread CPU time beside it) over 7218B and 7008-ma2023;
1000 / 3000 / 10,000 / 20,000 rpm; light (Fz = s / 3), combined (Fx = s / 3, Fz = s) and heavy combined
(Fx = s, Fz = 2 s) loads with s = Z (D / 22.2 mm)^2 200 N (3.2 kN for 7218B); traction 'lubricated' (oil
regime), 'lubricated-curve' (oil), 'kalker' mu 0.1 (solid) and 'coulomb' mu 0.1 (dry regime). --save
writes each converged case's solution (u, cage speed, ball loads, contact angles, ball speeds, friction
torque, drive power) to an .npz; --compare prints the largest difference from such a file (relative to
the largest value of each quantity in the case). --sweep: load sweeps, each case solved cold and from the
previous case's solution (docstring of sweep()).

Times: wall time is the headline, the thread's CPU time beside it (matrix: wall_s / cpu_s; --speed: ms, ms_min,
median_ms, max_ms, le_2ms wall and ms_cpu, ms_min_cpu, median_ms_cpu, max_ms_cpu CPU; --sweep: cold_ms, warm_ms
wall and cold_ms_cpu, warm_ms_cpu CPU). Until the "machine" key was added the --speed and --sweep figures were
thread CPU time. Every JSON file carries the machine (bench/machine.py) under "machine" (the --sweep file is now
an object {"machine", "rows"} instead of a list); the text output names the machine first.
Quickest check: ``--quick --out /tmp/x`` (about a minute), or ``--speed --repeat 1 --only 7008-ma2023|coulomb``.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict
from bearing_core.errors import ConvergenceError
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.quasistatic_tribo import TriboQuasiStaticModel, solve_tribo_quasistatic

sys.path.insert(0, str(Path(__file__).resolve().parent))
from machine import machine_info, machine_line  # noqa: E402

RPM = math.pi / 30


def matrix(g, quick):
    rows = []
    cases = [("kalker", 0.1), ("kalker", 0.001), ("coulomb", 0.1), ("lubricated", 0.1)]
    speeds = (3000,) if quick else (1000, 3000, 10000)
    loads = ((0, 3000), (1000, 3000)) if quick else ((0, 3000), (1000, 3000), (3000, 2000))
    for tr, mu in cases:
        for n in speeds:
            for fx, fz in loads:
                opt = DynamicsOptions(traction=tr, mu=mu)
                t0 = time.perf_counter()
                c0 = time.thread_time()
                try:
                    q = solve_tribo_quasistatic(g, n * RPM, (fx, 0, fz, 0, 0), opt)
                    row = dict(ok=True, evaluations=q.iterations, residual_N=q.residual,
                               cage_rpm=q.cage_speed / RPM, jh_cage_rpm=q.jones_harris.cage_speed / RPM)
                except ConvergenceError as e:
                    row = dict(ok=False, error=str(e)[-120:])
                row.update(traction=tr, mu=mu, speed_rpm=n, Fx_N=fx, Fz_N=fz, wall_s=time.perf_counter() - t0,
                           cpu_s=time.thread_time() - c0)
                rows.append(row)
                print(f"{tr:10s} mu {mu:<5g} {n:6d} rpm Fx {fx:5d} Fz {fz:5d}: "
                      + (f"ok  {row['evaluations']:5d} evals {row['wall_s']:6.3f} s ({1e3 * row['cpu_s']:7.1f} ms "
                         f"CPU)  cage {row['cage_rpm']:8.1f} "
                         f"(J-H {row['jh_cage_rpm']:8.1f}) rpm" if row["ok"] else f"FAIL {row['wall_s']:6.2f} s"),
                      flush=True)
    return rows


SPEED_PRESETS = ("7218B", "7008-ma2023")
SPEED_RPM = (1000.0, 3000.0, 10000.0, 20000.0)
SPEED_TRACTIONS = (("lubricated", "oil"), ("lubricated-curve", "oil"), ("kalker", "solid"), ("coulomb", "dry"))
SAVED = ("u", "cage_speed", "Q_i", "Q_o", "alpha_i", "alpha_o", "omega_ball", "orbit_speed", "friction_torque")


def speed_loads(g):
    """(name, loads) scaled to the bearing (s = 3.2 kN for 7218B)."""
    s = g.Z * (g.D / 0.0222) ** 2 * 200.0
    return (("light", (0.0, 0.0, s / 3, 0.0, 0.0)), ("combined", (s / 3, 0.0, s, 0.0, 0.0)),
            ("heavy", (s, 0.0, 2 * s, 0.0, 0.0)))


def speed_cases():
    for p in SPEED_PRESETS:
        g = load_preset(p)
        for tr, lub in SPEED_TRACTIONS:
            opt = DynamicsOptions(traction=tr, mu=0.1, lubrication=lub)
            for n in SPEED_RPM:
                for lname, loads in speed_loads(g):
                    yield f"{p}|{tr}|{n:g}|{lname}", g, opt, n * RPM, loads


def speed(repeat, save, compare, only):
    """Cost per load case (module docstring, --speed)."""
    ref = np.load(compare) if compare else None
    saved, rows, worst = {}, [], {}
    for key, g, opt, w, loads in speed_cases():
        if only and only not in key:
            continue
        c0 = time.thread_time()
        t0 = time.perf_counter()
        try:
            q = solve_tribo_quasistatic(g, w, loads, opt)
        except ConvergenceError:
            rows.append(dict(case=key, ok=False, ms=1e3 * (time.perf_counter() - t0),
                             ms_cpu=1e3 * (time.thread_time() - c0)))
            print(f"{key:40s} FAIL {rows[-1]['ms']:8.1f} ms", flush=True)
            continue
        ts, cs = [], []
        for _ in range(repeat):
            c0 = time.thread_time()
            t0 = time.perf_counter()
            solve_tribo_quasistatic(g, w, loads, opt)
            ts.append(time.perf_counter() - t0)
            cs.append(time.thread_time() - c0)
        row = dict(case=key, ok=True, ms=1e3 * float(np.median(ts)), ms_min=1e3 * float(np.min(ts)),
                   ms_cpu=1e3 * float(np.median(cs)), ms_min_cpu=1e3 * float(np.min(cs)),
                   evaluations=q.iterations)
        msg = ""
        for f in SAVED:
            v = np.asarray(getattr(q, f), dtype=float)
            saved[f"{key}|{f}"] = v
            if ref is not None and f"{key}|{f}" in ref:
                o = ref[f"{key}|{f}"]
                d = float(np.max(np.abs(v - o)) / max(np.max(np.abs(o)), 1e-300))
                row[f"diff_{f}"] = d
                worst[f] = max(worst.get(f, 0.0), d)
        if ref is not None:
            msg = "  max rel diff " + " ".join(f"{f} {row.get('diff_' + f, float('nan')):.1e}" for f in
                                              ("u", "cage_speed", "Q_i", "omega_ball"))
        rows.append(row)
        print(f"{key:40s} {row['ms']:8.2f} ms (min {row['ms_min']:6.2f}; thread CPU {row['ms_cpu']:8.2f})  "
              f"{q.iterations:5d} evals{msg}", flush=True)
    ok = [r for r in rows if r["ok"]]
    summ = dict(cases=len(rows), failed=len(rows) - len(ok))
    if ok:
        ms = np.array([r["ms"] for r in ok])
        mc = np.array([r["ms_cpu"] for r in ok])
        summ.update(median_ms=float(np.median(ms)), max_ms=float(ms.max()), le_2ms=int(np.sum(ms <= 2.0)),
                    median_ms_cpu=float(np.median(mc)), max_ms_cpu=float(mc.max()),
                    median_evaluations=float(np.median([r["evaluations"] for r in ok])))
    if worst:
        summ["max_rel_diff"] = worst
    if save:
        np.savez(save, **saved)
    print(json.dumps(summ, indent=1))
    return rows, summ


def sweep(repeat):
    """Load sweeps (--sweep): each preset, 'lubricated' (oil) and 'coulomb' (dry), 3000 and 10,000 rpm, the
    radial load from 0 to s in 9 steps at Fz = s (s as in --speed); every case solved cold
    (solve_tribo_quasistatic) and from the previous case's solution (TriboQuasiStaticModel.solve(start=)):
    wall time per case (median of --repeat sweeps; thread CPU time beside it), evaluations, failures and the largest difference of
    the warm-started solutions from the cold ones."""
    out = []
    for p in SPEED_PRESETS:
        g = load_preset(p)
        s = g.Z * (g.D / 0.0222) ** 2 * 200.0
        loads = [np.array((fx, 0.0, s, 0.0, 0.0)) for fx in np.linspace(0.0, s, 9)]
        for tr, lub in (("lubricated", "oil"), ("coulomb", "dry")):
            opt = DynamicsOptions(traction=tr, mu=0.1, lubrication=lub)
            for n in (3000.0, 10000.0):
                w = n * RPM
                res = {}
                for mode in ("cold", "warm"):
                    ts, cs, ev, fail, sols = [], [], [], 0, []
                    for k in range(repeat + 1):
                        prev, c0, t0, ev, fail, sols = None, time.thread_time(), time.perf_counter(), [], 0, []
                        m = TriboQuasiStaticModel(g, opt)
                        for L in loads:
                            try:
                                q = (solve_tribo_quasistatic(g, w, L, opt) if mode == "cold" or prev is None
                                     else m.solve(w, L, start=prev))
                                ev.append(q.iterations)
                                sols.append(q)
                                prev = q
                            except ConvergenceError:
                                fail += 1
                                sols.append(None)
                                prev = None
                        if k > 0:        # the first sweep warms up
                            ts.append((time.perf_counter() - t0) / len(loads))
                            cs.append((time.thread_time() - c0) / len(loads))
                    res[mode] = dict(ms_per_case=1e3 * float(np.median(ts)), ms_per_case_cpu=1e3 * float(np.median(cs)),
                                     evaluations=ev, failed=fail, sols=sols)
                dc = max((abs(a.cage_speed / b.cage_speed - 1) for a, b in zip(res["warm"]["sols"], res["cold"]["sols"])
                          if a is not None and b is not None), default=float("nan"))
                dq = max((np.max(np.abs(a.Q_i - b.Q_i)) / np.max(b.Q_i) for a, b in
                          zip(res["warm"]["sols"], res["cold"]["sols"]) if a is not None and b is not None),
                         default=float("nan"))
                row = dict(case=f"{p}|{tr}|{n:g}", cold_ms=res["cold"]["ms_per_case"], warm_ms=res["warm"]["ms_per_case"],
                           cold_ms_cpu=res["cold"]["ms_per_case_cpu"], warm_ms_cpu=res["warm"]["ms_per_case_cpu"],
                           cold_evaluations=res["cold"]["evaluations"], warm_evaluations=res["warm"]["evaluations"],
                           cold_failed=res["cold"]["failed"], warm_failed=res["warm"]["failed"],
                           cage_speed_rel_diff=dc, Q_i_rel_diff=dq)
                out.append(row)
                print(f"{row['case']:30s} cold {row['cold_ms']:6.2f} ms/case ({row['cold_failed']} failed)  warm "
                      f"{row['warm_ms']:6.2f} ms/case ({row['warm_failed']} failed)  evaluations cold "
                      f"{np.median(row['cold_evaluations'] or [0]):.0f} warm {np.median(row['warm_evaluations'] or [0]):.0f}"
                      f"  warm-cold: cage {dc:.1e}, Q_i {dq:.1e}", flush=True)
    return out


def table1(g, quick):
    n, loads = 10000.0, (1000.0, 0.0, 3000.0, 0.0, 0.0)
    opt = DynamicsOptions(traction="kalker", mu=0.1, mu_pocket=0.1, mu_land=0.1, reduced="full", integrator="auto")
    m = DynamicModel(g, opt)
    c0 = time.thread_time()
    t0 = time.perf_counter()
    m.initialize(n * RPM, loads, start="tribological")
    t_qs = time.perf_counter() - t0
    c_qs = time.thread_time() - c0
    q, jh = m.tribo_qs, m.qs
    t_end = 0.1 if quick else 0.3
    c0 = time.thread_time()
    t0 = time.perf_counter()
    d = records_to_dict(m.advance(t_end, record_dt=1e-4))
    t_dyn = time.perf_counter() - t0
    c_dyn = time.thread_time() - c0
    tail = d["t"] >= t_end - (0.03 if quick else 0.1)

    def deg(x):
        return float(np.degrees(x))

    # ball rows of the dynamic column: snapshot at t_end of the ball nearest azimuth 0 (ball 0 of the
    # quasi-static models sits at the radial load); ring displacements: mean over the tail
    bd = m.ball_details()
    th = (bd["theta"] + math.pi) % (2 * math.pi) - math.pi
    j = int(np.argmin(np.abs(th)))
    Wd = bd["omega"][j]

    # J-H: omega_R about the spin axis at attitude beta in the cage frame -> local (r, t, z) absolute
    W_jh = (-jh.omega_R[0] * math.sin(jh.beta[0]), 0.0, jh.omega_R[0] * math.cos(jh.beta[0]) + jh.omega_m[0])
    rows = {
        "inner ring radial displacement dx [m]": (jh.u[0], q.u[0], d["ir_x"][tail].mean()),
        "inner ring axial displacement dz [m]": (jh.u[2], q.u[2], d["ir_z"][tail].mean()),
        "inner contact angle, ball at psi = 0 [deg]": (deg(jh.alpha_i[0]), deg(q.alpha_i[0]), deg(bd["alpha_i"][j])),
        "outer contact angle, ball at psi = 0 [deg]": (deg(jh.alpha_o[0]), deg(q.alpha_o[0]), deg(bd["alpha_o"][j])),
        "attitude angle, ball at psi = 0 [deg]": (deg(jh.beta[0]), deg(q.attitude[0]), deg(bd["attitude"][j])),
        "yaw angle, ball at psi = 0 [deg]": (0.0, deg(q.yaw[0]), deg(bd["yaw"][j])),
        "Omega_t (paper's w_bx), psi = 0 [rpm]": (W_jh[1] / RPM, q.omega_ball[0, 1] / RPM, Wd[1] / RPM),
        "Omega_r (paper's w_by), psi = 0 [rpm]": (W_jh[0] / RPM, q.omega_ball[0, 0] / RPM, Wd[0] / RPM),
        "Omega_z (paper's w_bz), psi = 0 [rpm]": (W_jh[2] / RPM, q.omega_ball[0, 2] / RPM, Wd[2] / RPM),
        "orbital speed, ball at psi = 0 [rpm]": (jh.omega_m[0] / RPM, q.orbit_speed[0] / RPM, bd["orbit_speed"][j] / RPM),
        "cage speed (mean orbit / cage) [rpm]": (jh.cage_speed / RPM, q.cage_speed / RPM, d["cage_speed"][tail].mean() / RPM),
    }
    print(f"\nTable 1 analogue: 7218B, Kalker mu 0.1, Fx 1000 N, Fz 3000 N, 10,000 rpm "
          f"(QS {t_qs:.1f} s, dynamics {t_end} s in {t_dyn:.1f} s wall, {c_dyn:.1f} s thread CPU)")
    print(f"{'item':45s} {'J-H (outer control)':>20s} {'QS tribological':>16s} {'tribo-dynamic':>14s}")
    for k, (a, b, c) in rows.items():
        fmt = "{:>20.4e} {:>16.4e} {:>14s}" if "[m]" in k else "{:>20.3f} {:>16.3f} {:>14s}"
        cs = "n/a" if c is None else (f"{c:.4e}" if "[m]" in k else f"{c:.3f}")
        print(f"{k:45s} " + fmt.format(a, b, cs))
    print(f"(dynamic column: ball {j} at psi = {math.degrees(th[j]):.1f} deg at t = {t_end} s)")
    return {"case": "7218B kalker mu 0.1 Fx 1000 N Fz 3000 N 10000 rpm", "qs_wall_s": t_qs, "dyn_wall_s": t_dyn,
            "qs_cpu_s": c_qs, "dyn_cpu_s": c_dyn,
            "dyn_simulated_s": t_end,
            "rows": {k: [None if v is None else float(v) for v in r] for k, r in rows.items()}}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="a few cases only")
    ap.add_argument("--out", default="out")
    ap.add_argument("--speed", action="store_true", help="cost per load case over a matrix (docstring)")
    ap.add_argument("--sweep", action="store_true", help="load sweeps solved cold and from the previous case")
    ap.add_argument("--repeat", type=int, default=5, help="--speed, --sweep: warm runs per case (median)")
    ap.add_argument("--save", help="--speed: write the solutions to this .npz")
    ap.add_argument("--compare", help="--speed: compare the solutions with this .npz")
    ap.add_argument("--only", help="--speed: cases whose key contains this string")
    a = ap.parse_args()
    mach = machine_info()
    print(machine_line(mach), flush=True)
    if a.sweep:
        rows = sweep(a.repeat)
        out = Path(a.out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "bench_tribo_qs_sweep.json").write_text(json.dumps(dict(machine=mach, rows=rows), indent=1))
        return
    if a.speed:
        rows, summ = speed(a.repeat, a.save, a.compare, a.only)
        out = Path(a.out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "bench_tribo_qs_speed.json").write_text(json.dumps(dict(machine=mach, summary=summ, cases=rows),
                                                                  indent=1))
        return
    g = load_preset("7218B")
    res = {"machine": mach, "matrix": matrix(g, a.quick), "table1": table1(g, a.quick)}
    ok = sum(r["ok"] for r in res["matrix"])
    print(f"\nconverged {ok} of {len(res['matrix'])}")
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "bench_tribo_qs.json").write_text(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
