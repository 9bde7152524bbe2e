"""Cost and accuracy of one contact evaluation: FASTSIM (Kalker) variants against a fine reference grid, and
the ellipse-integrated Coulomb law, called from compiled code, for a 7218B-like contact (a = 1.15 mm,
b = 0.17 mm, Q = 300 N, steel, mu = 0.1).

  1. cost per call [us]: fastsim_traction at 8/12/20/40 square grids (parabolic and Hertz bound, as the
     dynamics calls it), fastsim_traction_fast (grid branch, full-slip branch, linear branch, defaults),
     ellipse_traction (Coulomb, 6 x 2 Gauss points);
  2. accuracy against a 200 x 200 grid of the same FASTSIM, over random creepage directions binned by the
     creepage level f (fastsim.creepage_level): max error of F_t, F_m over mu Q and of M_n over mu Q a;
  3. grid shape at equal cell count (n_x cells along the rolling direction x n_y strips);
  4. --dynamics: the 32 ball-race contacts of the 7218B Kalker model (dynamics traction 'kalker', 12 x 12,
     Hertz bound, mu = 0.1, Fx 1000 N, Fz 3000 N) 20 ms after its quasi-static start at 1000 rpm: branch
     taken per contact, cost per contact of fastsim_traction_fast (as the right-hand side calls it: strip-SIMD
     grid march) against the scalar march of fastsim_traction on the same grid, and of kalker_coefficients.
Costs are wall time (best of several loops; ``cost_us``, ``..._us_per_contact``) with the calling thread's CPU
time beside it (``cost_cpu_us``, ``..._us_per_contact_cpu``), which leaves out the time the thread spends
descheduled on a shared machine. Until the "machine" key was added the costs were thread CPU time. The JSON
output carries the machine (bench/machine.py) under "machine"; the text output names it first.
  --seed000: also the real-time factor (wall / simulated time) of the seed 000 case with Kalker traction
     (7218B, SEED000_PROFILE to 2 s, mu = 0.1, Fx 1000 N, Fz 3000 N; about 100 s).

    python bench/bench_fastsim.py [--json] [--seed000] [--dynamics]
"""
import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit

sys.path.insert(0, str(Path(__file__).resolve().parent))
from machine import machine_info, machine_line  # noqa: E402

from bearing_core.contact.contact_kernels import TRACTION_COULOMB, ellipse_quadrature, ellipse_traction, traction_params
from bearing_core.contact.fastsim import (PRESSURE_HERTZ, PRESSURE_PARABOLIC, combined_elastic, creepage_level,
                                  fastsim_traction, fastsim_traction_fast, kalker_coefficients)

A, B, Q, MU = 1.15e-3, 0.17e-3, 300.0, 0.1
G, NU = combined_elastic(206e9, 0.3, 206e9, 0.3)


@njit(cache=True)
def _loop_fastsim(n, a, b, Q, mu, G, nu, nx, ny, pr, vt, vm, w, u):
    s = 0.0
    for k in range(n):
        s += fastsim_traction(a, b, Q, mu, G, nu, vt + 1e-12 * k, vm, w, u, nx, ny, pr)[0]
    return s


@njit(cache=True)
def _loop_fast(n, a, b, Q, mu, G, nu, nx, ny, pr, vt, vm, w, u, flin, fslip):
    s = 0.0
    for k in range(n):
        s += fastsim_traction_fast(a, b, Q, mu, G, nu, vt + 1e-12 * k, vm, w, u, nx, ny, pr, flin, fslip)[0]
    return s


@njit(cache=True)
def _loop_ellipse(n, a, b, p, D, R, tp, qx, qwx, qy, qwy):
    s = 0.0
    for k in range(n):
        r = ellipse_traction(a, b, p, D, R, 3e-3 + 1e-9 * k, 1.4e-3, 16.5, 0.0, 0.0, -9.9, TRACTION_COULOMB, tp,
                             qx, qwx, qy, qwy)
        s += r[0]
    return s


def _time(f, *args, n=20000, repeats=5):
    """(wall, thread CPU) [us] per call: the best of `repeats` loops of n calls, each clock's best on its own."""
    f(10, *args)
    best = best_cpu = 1e9
    for _ in range(repeats):
        c0 = time.thread_time()
        t0 = time.perf_counter()
        f(n, *args)
        best = min(best, (time.perf_counter() - t0) / n * 1e6)
        best_cpu = min(best_cpu, (time.thread_time() - c0) / n * 1e6)
    return best, best_cpu


@njit(cache=True)
def _loop_contacts(n, C, mu, G, nu, n_xy, fast):
    """n sweeps over the contacts C (rows a, b, Q, vs_t, vs_m, w_spin, u_roll), Hertz bound."""
    s = 0.0
    for k in range(n):
        for c in range(C.shape[0]):
            if fast:
                r = fastsim_traction_fast(C[c, 0], C[c, 1], C[c, 2], mu, G, nu, C[c, 3] + 1e-15 * k, C[c, 4], C[c, 5],
                                          C[c, 6], n_xy, n_xy, PRESSURE_HERTZ)
            else:
                r = fastsim_traction(C[c, 0], C[c, 1], C[c, 2], mu, G, nu, C[c, 3] + 1e-15 * k, C[c, 4], C[c, 5],
                                     C[c, 6], n_xy, n_xy, PRESSURE_HERTZ)
            s += r[0]
    return s


@njit(cache=True)
def _loop_coefficients(n, r, nu):
    s = 0.0
    for k in range(n):
        for c in range(r.shape[0]):
            s += kalker_coefficients(r[c] + 1e-12 * k, nu)[2]
    return s


def dynamics_contacts(settle=0.02):
    """The race contacts of the Kalker dynamics model after `settle` s from the quasi-static start at 1000 rpm:
    branch per contact, cost per contact of fastsim_traction_fast and of the scalar march (fastsim_traction)."""
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_traction import LOADS, RPM, race_contacts
    from bearing_core.models import dynamics_kernels as K
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions
    from bearing_core.contact.fastsim import SHORTCUT_LIN, SHORTCUT_SLIP, slip_level
    from bearing_core.bearing.geometry import load_preset
    m = DynamicModel(load_preset("7218B"), DynamicsOptions(integrator="auto", reduced="full", traction="kalker",
                                                           mu=MU))
    m.initialize(1000.0 * RPM, LOADS)
    m.advance(settle)
    R = race_contacts(m)
    Gc, nuc, n_xy = m.P[K.P_GCOMB], m.P[K.P_NUCOMB], int(m.P[K.P_FS_NX])
    Q = 2.0 / 3.0 * math.pi * R[:, 0] * R[:, 1] * R[:, 2]
    C = np.column_stack([R[:, 0], R[:, 1], Q, R[:, 7], R[:, 8], R[:, 9], R[:, 12]])
    branches = {"linear": 0, "grid": 0, "fullslip": 0}
    for a, b, q, vt, vm, w, u in C:
        ap, bp = b, a
        cf = kalker_coefficients(ap / bp, nuc)
        sg = -1.0 if u > 0 else 1.0
        cr = (sg * vt / abs(u), sg * vm / abs(u), w / abs(u))
        f = creepage_level(ap, bp, q, MU, Gc, *cf, *cr)
        if f <= SHORTCUT_LIN:
            branches["linear"] += 1
        elif f >= SHORTCUT_SLIP and slip_level(ap, bp, q, MU, Gc, *cf, *cr) >= SHORTCUT_SLIP:
            branches["fullslip"] += 1
        else:
            branches["grid"] += 1
    n = 300
    fast = [t / len(C) for t in _time(_loop_contacts, C, MU, Gc, nuc, n_xy, True, n=n, repeats=15)]
    scalar = [t / len(C) for t in _time(_loop_contacts, C, MU, Gc, nuc, n_xy, False, n=n, repeats=15)]
    coef = [t / len(C) for t in _time(_loop_coefficients, C[:, 1] / C[:, 0], nuc, n=3000, repeats=15)]
    return {"contacts": len(C), "grid": n_xy, "branches": branches,
            "fast_us_per_contact": fast[0], "fast_us_per_contact_cpu": fast[1],
            "scalar_march_us_per_contact": scalar[0], "scalar_march_us_per_contact_cpu": scalar[1],
            "kalker_coefficients_us": coef[0], "kalker_coefficients_us_cpu": coef[1]}


# a ball-race state from the dynamics (7218B outer contact, 3000 rpm): partial slip, spin dominated
STATE = (3e-3, 1.4e-3, 16.5, -9.9)


def costs():
    """(wall, thread CPU) dicts of the costs [us] per call."""
    out = {}
    for pr, name in ((PRESSURE_PARABOLIC, "parabolic"), (PRESSURE_HERTZ, "hertz")):
        for n in (8, 12, 20, 40):
            out[f"fastsim_traction_{n}x{n}_{name}_us"] = _time(_loop_fastsim, A, B, Q, MU, G, NU, n, n, pr, *STATE)
        out[f"fast_grid_12x12_{name}_us"] = _time(_loop_fast, A, B, Q, MU, G, NU, 12, 12, pr, *STATE, 0.0, 1e300)
        out[f"fast_fullslip_12x12_{name}_us"] = _time(_loop_fast, A, B, Q, MU, G, NU, 12, 12, pr, *STATE, 0.0, 0.0)
        out[f"fast_linear_{name}_us"] = _time(_loop_fast, A, B, Q, MU, G, NU, 12, 12, pr, *STATE, 1e300, 1e300)
    q = ellipse_quadrature(6, 2)
    tp = traction_params(0.1, 0.02)
    p = 1.5 * Q / (np.pi * A * B)
    out["ellipse_coulomb_6x2_us"] = _time(_loop_ellipse, A, B, p, 0.02223, 0.0116, tp, *q)
    return {k: v[0] for k, v in out.items()}, {k: v[1] for k, v in out.items()}


def _cases(n_dir, f_values, seed=1):
    """Random creepage directions at given creepage levels (fastsim.creepage_level), rolling speed 10 m/s."""
    rng = np.random.default_rng(seed)
    ap, bp = B, A
    C = kalker_coefficients(ap / bp, NU)
    u = 10.0
    out = []
    for f in f_values:
        for _ in range(n_dir):
            d = rng.normal(size=3)
            d /= np.linalg.norm(d)
            # scale so that creepage_level == f exactly
            f1 = creepage_level(ap, bp, Q, MU, G, *C, d[0], d[1], d[2])
            xi, eta, phi = d * f / f1
            out.append((f, (-xi * u, -eta * u, phi * u, u)))       # contact frame, u > 0: xi_K = -vs_t / u
    return out


def accuracy(pressure, f_values=(0.003, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0), n_dir=16, n_ref=200):
    """Max error per creepage level of: the 12 x 12 grid, the full-slip branch (12 x 12), the linear branch."""
    rows = []
    cases = _cases(n_dir, f_values)
    for f in f_values:
        e = {"grid12": 0.0, "grid20": 0.0, "fullslip12": 0.0, "linear": 0.0, "fast_default_12": 0.0}
        for fc, args in cases:
            if fc != f:
                continue
            ref = np.array(fastsim_traction(A, B, Q, MU, G, NU, *args, n_ref, n_ref, pressure)[:3])

            def err(r):
                r = np.asarray(r[:3])
                return max(abs(r[0] - ref[0]) / (MU * Q), abs(r[1] - ref[1]) / (MU * Q), abs(r[2] - ref[2]) / (MU * Q * A))
            e["grid12"] = max(e["grid12"], err(fastsim_traction(A, B, Q, MU, G, NU, *args, 12, 12, pressure)))
            e["grid20"] = max(e["grid20"], err(fastsim_traction(A, B, Q, MU, G, NU, *args, 20, 20, pressure)))
            e["fullslip12"] = max(e["fullslip12"], err(fastsim_traction_fast(A, B, Q, MU, G, NU, *args, 12, 12, pressure, 0.0, 0.0)))
            e["linear"] = max(e["linear"], err(fastsim_traction_fast(A, B, Q, MU, G, NU, *args, 12, 12, pressure, 1e300, 1e300)))
            e["fast_default_12"] = max(e["fast_default_12"], err(fastsim_traction_fast(A, B, Q, MU, G, NU, *args, 12, 12, pressure)))
        rows.append({"f": f, **{k + "_pct": 100 * v for k, v in e.items()}})
    return rows


def shapes(pressure, n_ref=200):
    """Max error over creepage levels 0.01 ... 100 (same cases) of grids with about 144 cells."""
    cases = _cases(8, (0.01, 0.1, 1.0, 10.0, 100.0), seed=2)
    refs = [np.array(fastsim_traction(A, B, Q, MU, G, NU, *args, n_ref, n_ref, pressure)[:3]) for _, args in cases]
    rows = []
    for nx, ny in ((12, 12), (8, 18), (6, 24), (4, 36), (16, 9), (24, 6)):
        ef = 0.0
        for (_, args), ref in zip(cases, refs):
            r = np.array(fastsim_traction(A, B, Q, MU, G, NU, *args, nx, ny, pressure)[:3])
            ef = max(ef, abs(r[0] - ref[0]) / (MU * Q), abs(r[1] - ref[1]) / (MU * Q), abs(r[2] - ref[2]) / (MU * Q * A))
        rows.append({"n_x": nx, "n_y": ny, "max_err_pct": 100 * ef})
    return rows


def seed000_rtf():
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "studies"))
    from kalker_studies import run
    d, wall = run(0.1, 3000.0, t_end=2.0, grid=12)
    return {"seed000_kalker_mu0.1_wall_s": wall,     # wall time only (kalker_studies.run times the wall)
            "seed000_kalker_mu0.1_real_time_factor": wall / 2.0}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--seed000", action="store_true", help="also time the seed 000 Kalker case (about 100 s)")
    ap.add_argument("--dynamics", action="store_true",
                    help="also the contacts of the Kalker dynamics model at 1000 rpm (about 20 s)")
    a = ap.parse_args()
    wall, cpu = costs()
    out = {"machine": machine_info(), "cost_us": wall, "cost_cpu_us": cpu}
    if a.dynamics:
        out["dynamics"] = dynamics_contacts()
    for pr, name in ((PRESSURE_HERTZ, "hertz"), (PRESSURE_PARABOLIC, "parabolic")):
        out[f"accuracy_{name}"] = accuracy(pr)
        out[f"shapes_{name}"] = shapes(pr)
    if a.seed000:
        out["seed000"] = seed000_rtf()
    if a.json:
        print(json.dumps(out, indent=1))
        return
    print(machine_line(out["machine"]))
    print("cost per contact evaluation, from compiled code [us], wall (thread CPU):")
    for k, v in out["cost_us"].items():
        print(f"  {k}: {v:.2f} ({out['cost_cpu_us'][k]:.2f})")
    for name in ("hertz", "parabolic"):
        print(f"\naccuracy against a 200 x 200 grid, {name} bound, b/a = {B / A:.3f} (max error, % of mu Q and mu Q a):")
        print("  f        grid12   grid20   fullslip12   linear     fast(default, 12x12)")
        for r in out[f"accuracy_{name}"]:
            print(f"  {r['f']:<8g} {r['grid12_pct']:7.3f}  {r['grid20_pct']:7.3f}  {r['fullslip12_pct']:9.3f}  "
                  f"{r['linear_pct']:10.3f}  {r['fast_default_12_pct']:9.3f}")
        print(f"  grid shape at ~144 cells ({name}):", ", ".join(f"{r['n_x']}x{r['n_y']}: {r['max_err_pct']:.2f}%"
                                                             for r in out[f"shapes_{name}"]))
    if a.dynamics:
        d = out["dynamics"]
        print(f"\ndynamics state (7218B, Kalker {d['grid']}x{d['grid']} Hertz, 1000 rpm, 20 ms): branches {d['branches']}; "
              f"per contact, wall (thread CPU): fastsim_traction_fast {d['fast_us_per_contact']:.3f} "
              f"({d['fast_us_per_contact_cpu']:.3f}) us, scalar march {d['scalar_march_us_per_contact']:.3f} "
              f"({d['scalar_march_us_per_contact_cpu']:.3f}) us, kalker_coefficients "
              f"{d['kalker_coefficients_us']:.4f} ({d['kalker_coefficients_us_cpu']:.4f}) us")
    if a.seed000:
        print("\n" + "\n".join(f"{k}: {v:.2f}" for k, v in out["seed000"].items()) + " (wall time)")


if __name__ == "__main__":
    main()
