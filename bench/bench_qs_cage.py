"""Quasi-static cage model (bearing_core.models.quasistatic_cage) against the dynamic model's window means.

    python bench/bench_qs_cage.py --reference [--n 32] [--seed 31] [--regime oil|solid|both]
        dynamic window means at the random operating points (and the two published check points), cached
        in bench/qs_cage_reference.json (points already there are kept; run once, in the background)
    python bench/bench_qs_cage.py --accuracy [--json out.json]
        the quasi-static cage model at the same points: errors against the references, solve times
    python bench/bench_qs_cage.py --convergence [--json out.json]
        convergence over bench_tribo_qs.py --speed's case set (presets x traction laws x speeds x loads)
    python bench/bench_qs_cage.py --ramp --regime oil [--json out.json]
        seed 000's speed profile stepped at 1 ms (re-solve beyond the sensitivity's input tolerance, linear
        update otherwise, cage speed through its first-order lag) against the dynamic model

Operating points: 7218B, speed uniform in 500-12,000 rpm, Fx uniform in 0-3 kN, Fz uniform in 0.5-8 kN
(numpy default_rng(seed)), oil-lubricated (EHL race traction, lubricated pocket, flooded land) and
solid-lubricated (Kalker traction, mu 0.1, dry Coulomb cage, mu 0.1). Dynamic reference: DynamicModel
started from Jones-Harris, integrator 'auto', run for 0.06 s, then advanced in 0.04 s windows until the window
means of the cage speed move less than 0.2 % and the friction torque less than 5 % between windows
(maps.sweep.DynamicWindow's criterion), at most 0.6 s; the reference values are the means over the last
window (records every 1 ms).
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from machine import machine_info, machine_line  # noqa: E402

from bearing_core import load_bearing  # noqa: E402
from bearing_core.models.dynamics import DynamicModel, DynamicsOptions  # noqa: E402
from bearing_core.models import dynamics_kernels as K  # noqa: E402

RPM = math.pi / 30.0
REF_FILE = Path(__file__).resolve().parent / "qs_cage_reference.json"
REGIMES = {"oil": dict(traction="lubricated", lubrication="oil"),
           "solid": dict(traction="kalker", mu=0.1, lubrication="solid")}
HEAT = ("P_race_inner", "P_race_outer", "P_pocket", "P_land", "P_drag", "P_churn_cage", "P_churn_ring",
        "P_damping")
MEANS = ("cage_speed", "friction_torque", "P_drive", "Fx", "Fy", "Fz", "Mx", "My", "ir_x", "ir_y", "ir_z",
         "ir_tx", "ir_ty", "alpha_i_mean", "alpha_o_mean", "Q_i_max", "Q_o_max", "p_max") + HEAT


def random_points(n, seed):
    """n operating points (speed rpm, Fx N, Fz N) uniform in the validity range."""
    rng = np.random.default_rng(seed)
    return [(float(rng.uniform(500.0, 12000.0)), float(rng.uniform(0.0, 3000.0)), float(rng.uniform(500.0, 8000.0)))
            for _ in range(n)]


def options(regime):
    return DynamicsOptions(integrator="auto", **REGIMES[regime])


def dynamic_window(g, regime, rpm, fx, fz, window=0.04, min_time=0.1, max_time=0.6, steady_tol=2e-3,
                   torque_tol=0.05):
    """Window means of the dynamic model at held speed and loads (module docstring), after at least
    min_time [s]."""
    m = DynamicModel(g, options(regime))
    m.initialize(rpm * RPM, (fx, 0.0, fz, 0.0, 0.0))
    m.advance(min_time - window, record_dt=window / 20.0)
    prev = None
    steady = False
    I = K.OUT_INDEX
    while m.t < max_time - 1e-12:
        rec = m.advance(min(m.t + window, max_time), record_dt=window / 40.0)
        s = {k: float(np.mean(rec[:, I[k]])) for k in MEANS}
        s["cage_speed_std"] = float(np.std(rec[:, I["cage_speed"]]))
        s["cage_x_mean"] = float(np.mean(rec[:, I["cage_x"]]))
        s["cage_y_mean"] = float(np.mean(rec[:, I["cage_y"]]))
        s["cage_e_mean"] = float(np.mean(np.hypot(rec[:, I["cage_x"]], rec[:, I["cage_y"]])))
        dc = prev is not None and abs(s["cage_speed"] - prev["cage_speed"]) <= steady_tol * abs(s["cage_speed"])
        if dc and abs(s["friction_torque"] - prev["friction_torque"]) <= torque_tol * abs(s["friction_torque"]) + 1e-6:
            steady = True
            break
        prev = s
    s["steady"] = steady
    s["settle_time_s"] = m.t
    return s


def reference(n, seed, regimes):
    g = load_bearing("7218B")
    data = json.loads(REF_FILE.read_text()) if REF_FILE.exists() else {"points": []}
    done = {(p["regime"], round(p["speed_rpm"], 6), round(p["load_Fx"], 6), round(p["load_Fz"], 6))
            for p in data["points"]}
    pts = []
    for regime in regimes:
        if regime == "oil":
            pts += [("oil", 3000.0, 1000.0, 3000.0, "check"), ("oil", 10000.0, 1000.0, 3000.0, "check")]
        pts += [(regime, *p, "random") for p in random_points(n, seed + (0 if regime == "oil" else 1))]
    for regime, rpm, fx, fz, kind in pts:
        if (regime, round(rpm, 6), round(fx, 6), round(fz, 6)) in done:
            continue
        t0 = time.perf_counter()
        try:
            s = dynamic_window(g, regime, rpm, fx, fz)
            err = None
        except Exception as e:   # noqa: BLE001 (recorded with the point)
            s, err = {}, f"{type(e).__name__}: {e}"
        s.update(regime=regime, speed_rpm=rpm, load_Fx=fx, load_Fz=fz, kind=kind, wall_s=time.perf_counter() - t0,
                 error=err)
        data["points"].append(s)
        data["machine"] = machine_info()
        data["seed"] = seed
        REF_FILE.write_text(json.dumps(data, indent=1))
        print(f"{regime} {rpm:7.0f} rpm Fx {fx:6.0f} Fz {fz:6.0f}: cage {s.get('cage_speed', 0) / RPM:7.1f} rpm "
              f"torque {s.get('friction_torque', 0):6.3f} N m steady {s.get('steady')} "
              f"({s['wall_s']:.0f} s) {err or ''}", flush=True)


TOL = {"cage_speed": 0.01, "friction_torque": 0.05, "heat": 0.05, "reaction": 0.005, "alpha_deg": 0.5}


def qs_model(regime):
    from bearing_core.models.quasistatic_cage import QuasiStaticCageModel
    return QuasiStaticCageModel(load_bearing("7218B"), options(regime))


def accuracy(regimes, out_json=None):
    """The quasi-static cage model at the reference points: errors against the dynamic window means (relative
    for cage speed, friction torque, heat; reactions relative to the largest load component; contact angles
    absolute in degrees), cold solve time, warm re-solve time at +0.5 % speed, and the linear update's
    error there."""
    data = json.loads(REF_FILE.read_text())
    rows = []
    models = {r: qs_model(r) for r in regimes}
    for p in data["points"]:
        if p["regime"] not in regimes or p.get("error"):
            continue
        m = models[p["regime"]]
        w = p["speed_rpm"] * RPM
        loads = (p["load_Fx"], 0.0, p["load_Fz"], 0.0, 0.0)
        row = dict(regime=p["regime"], speed_rpm=p["speed_rpm"], Fx=p["load_Fx"], Fz=p["load_Fz"], kind=p["kind"],
                   dyn_steady=p["steady"])
        t0 = time.perf_counter()
        try:
            m.forget()                  # each point solved cold on its own (no state from the point before)
            r = m.solve(w, loads)
        except Exception as e:   # noqa: BLE001 (reported per point)
            row.update(converged=False, error=str(e)[:300], cold_s=time.perf_counter() - t0)
            rows.append(row)
            print(f"{p['regime']:5s} {p['speed_rpm']:6.0f} rpm Fx {p['load_Fx']:5.0f} Fz {p['load_Fz']:5.0f}: "
                  f"NOT CONVERGED {row['error'][:120]}", flush=True)
            continue
        row["cold_s"] = time.perf_counter() - t0
        heat_dyn = sum(p[k] for k in HEAT)
        react_dyn = np.array([p[k] for k in ("Fx", "Fy", "Fz", "Mx", "My")])
        hdm = 0.5 * m.g.dm
        scale = max(abs(p["load_Fx"]), abs(p["load_Fz"]))
        dre = np.abs(r.reaction - react_dyn)
        dre[3:] /= hdm
        row.update(converged=True, iterations=r.iterations,
                   cage_rpm=r.cage_speed / RPM, cage_rpm_dyn=p["cage_speed"] / RPM,
                   torque=r.friction_torque, torque_dyn=p["friction_torque"],
                   heat=r.heat["total"], heat_dyn=heat_dyn, P_drive=r.P_drive,
                   err_cage=r.cage_speed / p["cage_speed"] - 1.0,
                   err_torque=r.friction_torque / p["friction_torque"] - 1.0,
                   err_heat=r.heat["total"] / heat_dyn - 1.0,
                   err_reaction=float(np.max(dre)) / scale,
                   err_alpha_i_deg=math.degrees(r.output("alpha_i_mean") - p["alpha_i_mean"]),
                   err_alpha_o_deg=math.degrees(r.output("alpha_o_mean") - p["alpha_o_mean"]),
                   power_balance=r.heat["total"] / r.P_drive - 1.0, tau_cage_s=r.tau_cage,
                   heat_by_source={k: r.heat[k] for k in r.heat}, heat_by_source_dyn={k: p[k] for k in HEAT})
        w2 = w * 1.005
        t0 = time.perf_counter()
        try:
            r2 = m.solve(w2, loads, start=r, sensitivity=False)
            row["warm_s"] = time.perf_counter() - t0
            pred = r.predict(w2, loads)
            row["update_err_cage"] = pred[0] / r2.cage_speed - 1.0
            row["update_err_torque"] = pred[1] / r2.friction_torque - 1.0
        except Exception as e:   # noqa: BLE001
            row["warm_error"] = str(e)[:200]
        rows.append(row)
        print(f"{p['regime']:5s} {p['speed_rpm']:6.0f} rpm Fx {p['load_Fx']:5.0f} Fz {p['load_Fz']:5.0f}: cage "
              f"{row['err_cage'] * 100:+6.2f} % torque {row['err_torque'] * 100:+6.1f} % "
              f"heat {row['err_heat'] * 100:+6.1f} % react {row['err_reaction'] * 100:5.2f} % "
              f"ai {row['err_alpha_i_deg']:+5.2f} ao {row['err_alpha_o_deg']:+5.2f} deg "
              f"({row['cold_s']:.2f} s, warm {row.get('warm_s', float('nan')) * 1e3:.1f} ms)", flush=True)
    summ = {}
    for regime in regimes:
        rr = [r for r in rows if r["regime"] == regime]
        ok = [r for r in rr if r["converged"]]
        s = dict(points=len(rr), converged=len(ok))
        for k, tol in (("err_cage", TOL["cage_speed"]), ("err_torque", TOL["friction_torque"]),
                       ("err_heat", TOL["heat"]), ("err_reaction", TOL["reaction"]),
                       ("err_alpha_i_deg", TOL["alpha_deg"]), ("err_alpha_o_deg", TOL["alpha_deg"])):
            e = np.abs([r[k] for r in ok])
            if e.size:
                s[k] = dict(within=int(np.sum(e <= tol)), max=float(e.max()), median=float(np.median(e)),
                            mean_signed=float(np.mean([r[k] for r in ok])))
        if ok:
            s["cold_s_median"] = float(np.median([r["cold_s"] for r in ok]))
            ws = [r["warm_s"] for r in ok if "warm_s" in r]
            s["warm_ms_median"] = 1e3 * float(np.median(ws)) if ws else None
        summ[regime] = s
    print(json.dumps(summ, indent=1))
    if out_json:
        Path(out_json).write_text(json.dumps(dict(machine=machine_info(), tolerances=TOL, summary=summ, rows=rows),
                                             indent=1))
    return summ


def convergence(out_json=None):
    """The quasi-static cage model over bench_tribo_qs.py --speed's case set (presets, traction laws, speeds,
    loads): converged or not, cold solve time."""
    from bench_tribo_qs import speed_cases
    from bearing_core.models.quasistatic_cage import QuasiStaticCageModel
    rows = []
    models = {}
    for key, g, opt, w, loads in speed_cases():
        k2 = (key.split("|")[0], key.split("|")[1])
        if k2 not in models:
            models[k2] = QuasiStaticCageModel(g, opt)
        models[k2].forget()             # each case solved cold on its own
        t0 = time.perf_counter()
        try:
            r = models[k2].solve(w, loads, sensitivity=False)
            rows.append(dict(case=key, converged=True, s=time.perf_counter() - t0, cage_rpm=r.cage_speed / RPM,
                             torque=r.friction_torque))
        except Exception as e:   # noqa: BLE001
            rows.append(dict(case=key, converged=False, s=time.perf_counter() - t0, error=str(e)[:300]))
        print(f"{key:40s} {'ok ' if rows[-1]['converged'] else 'FAIL'} {rows[-1]['s']:.2f} s", flush=True)
    n_ok = sum(r["converged"] for r in rows)
    print(f"converged {n_ok} of {len(rows)}")
    if out_json:
        Path(out_json).write_text(json.dumps(dict(machine=machine_info(), converged=n_ok, cases=len(rows), rows=rows),
                                             indent=1))


def ramp(regime, out_json=None, rel=2e-3, dt=1e-3):  # noqa: C901
    """Seed 000's speed profile (dynamics.SEED000_PROFILE; Fx 1 kN, Fz 3 kN) at dt steps the way a
    co-simulation step would use the model: a warm re-solve when an input has moved by more than half its
    input_tolerance(rel) since the last solve, else the linear update predict(); at a re-solve the derivatives
    are recomputed only where they did not predict its cage speed and torque to rel; the cage speed
    through the first-order lag with the solution's tau_cage. Against the dynamic model run through the same
    profile (records every dt): the cage speed's largest deviation after the first 0.05 s, and the wall time
    per simulated second of the quasi-static stepping."""
    from bearing_core.models.dynamics import SEED000_PROFILE, simulate_profile
    g = load_bearing("7218B")
    loads = (1000.0, 0.0, 3000.0, 0.0, 0.0)
    tp, npf = np.array([p[0] for p in SEED000_PROFILE]), np.array([p[1] for p in SEED000_PROFILE])
    m = qs_model(regime)
    # derivatives by the implicit function theorem at each re-solve: the secants (the solver's default) cost
    # 14 warm solves per re-solve, hours over the 900-odd re-solves of this profile
    m.sensitivity_method = "implicit"
    t = np.arange(0.0, tp[-1] + 0.5 * dt, dt)
    w = np.interp(t, tp, npf) * RPM
    r0 = m.solve(w[0], loads)
    tol = r0.input_tolerance(rel)
    wc = r0.cage_speed
    out = np.empty((t.size, 3))
    n_solve = 0
    n_sens = 0
    t_solve, t_sens = [], []
    t0 = time.perf_counter()
    for k in range(t.size):
        p = np.concatenate([[w[k]], loads, [r0.T_oil]])
        if np.any(np.abs(p - r0.inputs()) > 0.5 * tol):
            ts = time.perf_counter()
            r1 = m.solve(w[k], loads, start=r0, sensitivity=False)
            t_solve.append(time.perf_counter() - ts)
            ts = time.perf_counter()
            pred = r0.predict(w[k], loads)
            # the derivatives are kept while they predicted this re-solve's cage speed and torque to rel
            if abs(pred[0] / r1.cage_speed - 1.0) < rel and abs(pred[1] / r1.friction_torque - 1.0) < rel:
                r1.sensitivity, r1.tau_cage = r0.sensitivity, r0.tau_cage
            else:
                r1.sensitivity = r0.sensitivity
                m.update_sensitivity(r1, columns=(0,))     # only the shaft speed moves here
                n_sens += 1
                t_sens.append(time.perf_counter() - ts)
            r0 = r1
            tol = r0.input_tolerance(rel)
            n_solve += 1
            y = r0.outputs
        else:
            y = r0.predict(w[k], loads)
        a = 1.0 - math.exp(-dt / r0.tau_cage) if math.isfinite(r0.tau_cage) and r0.tau_cage > 0 else 1.0
        wc += (y[0] - wc) * a
        out[k] = (wc, y[0], y[1])
    wall = time.perf_counter() - t0
    d = DynamicModel(g, options(regime))
    d.initialize(w[0], loads)
    rec = simulate_profile(d, SEED000_PROFILE, record_dt=dt)
    I = K.OUT_INDEX
    td, wcd = rec[:, I["t"]], rec[:, I["cage_speed"]]
    wq = np.interp(td, t, out[:, 0])
    sel = td > 0.05
    dev = wq[sel] / wcd[sel] - 1.0
    res = dict(regime=regime, dt=dt, rel=rel, wall_s_per_sim_s=wall / t[-1], resolves=n_solve, sensitivity_updates=n_sens, steps=int(t.size),
               resolve_ms=dict(median=1e3 * float(np.median(t_solve)), p90=1e3 * float(np.percentile(t_solve, 90)),
                               total_s=float(np.sum(t_solve))),
               sensitivity_ms=dict(median=1e3 * float(np.median(t_sens)) if t_sens else None,
                                   total_s=float(np.sum(t_sens))),
               cage_dev_max=float(np.max(np.abs(dev))), cage_dev_mean=float(np.mean(dev)),
               cage_dev_at_end=float(dev[-1]), torque_end_qs=float(out[-1, 2]),
               torque_end_dyn=float(np.mean(rec[-100:, I["friction_torque"]])))
    print(json.dumps(res, indent=1))
    if out_json:
        Path(out_json).write_text(json.dumps(dict(machine=machine_info(), **res), indent=1))
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference", action="store_true")
    ap.add_argument("--n", type=int, default=32)
    ap.add_argument("--seed", type=int, default=31)
    ap.add_argument("--regime", default="both", choices=("oil", "solid", "both"))
    ap.add_argument("--accuracy", action="store_true")
    ap.add_argument("--convergence", action="store_true")
    ap.add_argument("--ramp", action="store_true")
    ap.add_argument("--rel", type=float, default=2e-3, help="--ramp: re-solve tolerance (input_tolerance(rel))")
    ap.add_argument("--json", help="write the results to this JSON file")
    a = ap.parse_args()
    print(machine_line(), flush=True)
    regimes = ("oil", "solid") if a.regime == "both" else (a.regime,)
    if a.reference:
        reference(a.n, a.seed, regimes)
    if a.accuracy:
        accuracy(regimes, a.json)
    if a.convergence:
        convergence(a.json)
    if a.ramp:
        ramp(regimes[0], a.json, rel=a.rel)


if __name__ == "__main__":
    main()
