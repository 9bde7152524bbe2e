"""Quasi-static cage model (bearing_core.models.quasistatic_cage) against the dynamic model's window means.

    python bench/bench_qs_cage.py --reference [--n 32] [--seed 31] [--regime oil|solid|both]
        dynamic window means at the random operating points (and the two published check points), cached
        in bench/qs_cage_reference.json (points already there are kept; run once, in the background)
    python bench/bench_qs_cage.py --accuracy [--json out.json]
        the quasi-static cage model at the same points: errors against the references, solve times
    python bench/bench_qs_cage.py --convergence
        convergence over bench_tribo_qs.py --speed's case set (presets x traction laws x speeds x loads)

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
        if prev is not None and abs(s["cage_speed"] - prev["cage_speed"]) <= steady_tol * abs(s["cage_speed"]) \
                and abs(s["friction_torque"] - prev["friction_torque"]) <= torque_tol * abs(s["friction_torque"]) + 1e-6:
            steady = True
            break
        prev = s
    s["steady"] = steady
    s["settle_time_s"] = m.t
    return s


def reference(n, seed, regimes):
    g = load_bearing("7218B")
    data = json.loads(REF_FILE.read_text()) if REF_FILE.exists() else {"points": []}
    done = {(p["regime"], round(p["speed_rpm"], 6), round(p["Fx"], 6), round(p["Fz"], 6)) for p in data["points"]}
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
        s.update(regime=regime, speed_rpm=rpm, Fx=fx, Fz=fz, kind=kind, wall_s=time.perf_counter() - t0, error=err)
        data["points"].append(s)
        data["machine"] = machine_info()
        data["seed"] = seed
        REF_FILE.write_text(json.dumps(data, indent=1))
        print(f"{regime} {rpm:7.0f} rpm Fx {fx:6.0f} Fz {fz:6.0f}: cage {s.get('cage_speed', 0) / RPM:7.1f} rpm "
              f"torque {s.get('friction_torque', 0):6.3f} N m steady {s.get('steady')} "
              f"({s['wall_s']:.0f} s) {err or ''}", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference", action="store_true")
    ap.add_argument("--n", type=int, default=32)
    ap.add_argument("--seed", type=int, default=31)
    ap.add_argument("--regime", default="both", choices=("oil", "solid", "both"))
    a = ap.parse_args()
    print(machine_line(), flush=True)
    regimes = ("oil", "solid") if a.regime == "both" else (a.regime,)
    if a.reference:
        reference(a.n, a.seed, regimes)


if __name__ == "__main__":
    main()
