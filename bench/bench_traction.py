"""Cost of the ball-race traction laws and of the dynamics right-hand side.

The 32 race contacts (16 balls x inner / outer) of the 7218B under Fx = 1000 N, Fz = 3000 N at
10,000 rpm, taken from the lubricated (rheology-based EHL) model after --settle seconds of simulation,
are fed to dynamics_kernels._race_traction (the entry point the right-hand side uses) with each law:
  coulomb  ellipse-integrated mu0 tanh(v / v_reg)
  curve    ellipse-integrated illustrative traction curve (traction 'lubricated-curve')
  ehl      rheology-based EHL traction with rolling resistance (traction 'lubricated', the default)
  kalker   Kalker's FASTSIM (traction 'kalker')
and the cost per contact is the best mean over --repeats timed loops of --calls sweeps over all 32: wall
time (us_per_contact) and, beside it, the calling thread's CPU time (us_per_contact_cpu; time the thread
spends descheduled on a shared machine is not counted). The right-hand side (dynamics_kernels.rhs,
lubricated, all balls and the cage) is timed the same way at the same state (rhs_us wall, rhs_cpu_us CPU).
Until the "machine" key was added, us_per_contact and rhs_us were thread CPU time; they are wall time now.
The JSON output carries the machine (bench/machine.py) under "machine"; the text output names it first.

The build follows bearing_core.numerics.jit: run once as is (fast build) and once with BEARING_PLAIN_MATH=1 (strict
IEEE, error_model='python') to compare; --both runs the two builds back to back in subprocesses.

    python bench/bench_traction.py [--json] [--both] [--quick] [--settle 0.02] [--quad 6 2]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np
from numba import njit

from bearing_core.models import dynamics_kernels as K
from bearing_core.contact.contact_kernels import (TRACTION_COULOMB, ball_race_contact, contact_kinematics,
                                          ellipse_quadrature)
from bearing_core.models.dynamics import DynamicModel, DynamicsOptions
from bearing_core.lubrication.ehl_traction import ehl_scratch
from bearing_core.bearing.geometry import load_preset

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_dynamics import _rhs_loop  # noqa: E402  (the right-hand-side timing loop, shared)
from machine import machine_info, machine_line  # noqa: E402

try:
    from bearing_core.numerics.jit import build_info
except ImportError:          # trees without bearing_core.numerics.jit: numba defaults
    def build_info():
        return {"plain_math": None, "fastmath": [], "error_model": "python"}

RPM = math.pi / 30.0
LOADS = (1000.0, 0.0, 3000.0, 0.0, 0.0)


def race_contacts(m):
    """Arguments of the 2 nb race contacts at the model's state, as dynamics_kernels.rhs forms them:
    rows (a, b, p_max, D, R_def, Rx, Ry, vs_t, vs_m, w_spin, w_roll_m, w_roll_t, u_roll)."""
    P, U, y = m.P, m.U, m.y
    D, dm, fi, fo, a0 = P[K.P_D], P[K.P_DM], P[K.P_FI], P[K.P_FO], P[K.P_A0]
    Aa = (fi + fo - 1.0) * D
    Ri = 0.5 * dm + (fi - 0.5) * D * math.cos(a0)
    Roo = 0.5 * dm - (fo - 0.5) * D * math.cos(a0)
    Zoo = -(fo - 0.5) * D * math.sin(a0)
    Rdi, Rdo = 2.0 * fi * D / (2.0 * fi + 1.0), 2.0 * fo * D / (2.0 * fo + 1.0)
    Ryi, Ryo = fi * D / (2.0 * fi - 1.0), fo * D / (2.0 * fo - 1.0)
    w, _ = K._shaft(U, m.t)
    wo = U[K.U_WO]
    xi_, yi_, zi_, txi, tyi, vxi, vyi, vzi, wxi, wyi = y[:10]
    xo, yo = y[16], y[17]
    vxo, vyo = y[18], y[19]
    rows = []
    for j in range(int(P[K.P_NB])):
        o = K.NSTATE_FIXED + K.NSB * j
        th, rb, zb, thd, rd, zd, Wr, Wt, Wz = y[o:o + 9]
        c, s = math.cos(th), math.sin(th)
        Cr = Aa * math.cos(a0) + xi_ * c + yi_ * s
        Cz = Aa * math.sin(a0) + zi_ + Ri * (txi * s - tyi * c)
        vrr, vrt, vrz = vxi * c + vyi * s, -vxi * s + vyi * c, vzi + Ri * (wxi * s - wyi * c)
        Xr, Xz = rb - Roo - (xo * c + yo * s), zb - Zoo
        vor, vot = vxo * c + vyo * s, -vxo * s + vyo * c
        (_, nor, noz, ao, _, ao_s, bo_s, po, _, nir, niz, ai, _, ai_s, bi_s, pi_) = ball_race_contact(
            Xr, Xz, Cr, Cz, (fo - 0.5) * D, (fi - 0.5) * D, m._tab_i, m._tab_o, m._ta0, m._tda)
        kin = contact_kinematics(rb, rd, rb * thd, zd, Wr, Wt, Wz, w, vrr, vrt, vrz, nir, niz, D)
        rows.append((ai_s, bi_s, pi_, D, Rdi, 0.5 * D * (1.0 - D * math.cos(ai) / dm), Ryi) + tuple(kin))
        kin = contact_kinematics(rb, rd, rb * thd, zd, Wr, Wt, Wz, wo, vor, vot, 0.0, nor, noz, D)
        rows.append((ao_s, bo_s, po, D, Rdo, 0.5 * D * (1.0 + D * math.cos(ao) / dm), Ryo) + tuple(kin))
    return np.array(rows)


@njit(cache=True)
def _traction_loop(n, C, kalker, tmodel, tp, Gc, nuc, fnx, fny, qx, qwx, qy, qwy):
    acc = 0.0
    sc = ehl_scratch(qx, qwx, qy, qwy)        # one scratch for all contacts, as in dynamics_kernels.rhs
    for _ in range(n):
        for k in range(C.shape[0]):
            a, b, p = C[k, 0], C[k, 1], C[k, 2]
            Q = 2.0 / 3.0 * math.pi * a * b * p
            r = K._race_traction(kalker, a, b, Q, p, C[k, 3], C[k, 4], C[k, 5], C[k, 6], C[k, 7], C[k, 8],
                                 C[k, 9], C[k, 10], C[k, 11], C[k, 12], tmodel, tp, Gc, nuc, fnx, fny,
                                 qx, qwx, qy, qwy, sc)
            acc += r[0] + r[5]
    return acc


def _best_us(fn, args, n, repeats, per):
    """(wall, thread CPU) [us] per unit: the smallest of `repeats` timed loops of n calls, each clock's
    minimum on its own."""
    fn(1, *args)
    best = best_cpu = math.inf
    for _ in range(repeats):
        c0 = time.thread_time()
        t0 = time.perf_counter()
        fn(n, *args)
        best = min(best, time.perf_counter() - t0)
        best_cpu = min(best_cpu, time.thread_time() - c0)
    return best / (n * per) * 1e6, best_cpu / (n * per) * 1e6


def _model(traction, quad, kalker_grid=None):
    kw = dict(integrator="auto", reduced="full", traction=traction, n_major=quad[0], n_minor=quad[1])
    return DynamicModel(load_preset("7218B"), DynamicsOptions(**kw))


def measure(settle=0.02, quad=(6, 2), calls=200, repeats=25):
    m = _model("lubricated", quad)
    m.initialize(10000.0 * RPM, LOADS)
    m.advance(settle)
    C = race_contacts(m)
    q = ellipse_quadrature(*quad)
    Gc, nuc = m.P[K.P_GCOMB], m.P[K.P_NUCOMB]
    fnx, fny = int(m.P[K.P_FS_NX]), int(m.P[K.P_FS_NY])
    curve = _model("lubricated-curve", quad)
    curve.initialize(10000.0 * RPM, LOADS)
    laws = {
        "coulomb": (False, TRACTION_COULOMB, m._tp),
        "curve": (False, int(curve._tp[K.P_LUBMODEL]), curve._tp),
        "ehl": (False, int(m._tp[K.P_LUBMODEL]), m._tp),
        "kalker": (True, TRACTION_COULOMB, m._tp),
    }
    out = {"machine": machine_info(), "build": build_info(), "quadrature": list(quad), "state_t_s": m.t,
           "contacts": len(C), "us_per_contact": {}, "us_per_contact_cpu": {}}
    for name, (kal, tmodel, tp) in laws.items():
        w, c = _best_us(_traction_loop, (C, kal, tmodel, tp, Gc, nuc, fnx, fny, *q), calls, repeats, len(C))
        out["us_per_contact"][name] = w
        out["us_per_contact_cpu"][name] = c
    diag = np.zeros(K.NOUT)
    bd = np.zeros((int(m.P[K.P_NB]), K.NBD))
    out["rhs_us"], out["rhs_cpu_us"] = _best_us(
        _rhs_loop, (m.t, m.y.copy(), m.P, m.U, m._tab_i, m._tab_o, m._ta0, m._tda, m._tp, *m._quad, diag, bd),
        calls, repeats, 1)
    return out


def quadrature_check(settle=0.04, window=0.02, rules=((6, 2), (8, 2), (8, 4), (12, 6), (24, 12), (48, 24)),
                     rpms=(10000.0, 1000.0)):
    """Window means of the friction torque (torque to drive the inner ring) and of the race power losses
    of the lubricated model run with each quadrature rule (from its quasi-static start, `settle` seconds,
    then the mean over `window` seconds), relative to the finest rule's."""
    out = {}
    names = ("friction_torque", "P_race_inner", "P_race_outer")
    for rpm in rpms:
        vals = {}
        for quad in rules:
            m = _model("lubricated", (6, 2))
            m.initialize(rpm * RPM, LOADS)
            m._quad = ellipse_quadrature(*quad)        # beyond the options' 32-node limit for the reference
            m.advance(settle)
            rec = m.advance(settle + window, record_dt=1e-4)
            vals[quad] = {n: float(rec[:, K.OUT_INDEX[n]].mean()) for n in names}
        ref = vals[rules[-1]]
        out[f"{rpm:g} rpm"] = {f"{qa}x{qb}": dict(**{n: v / ref[n] - 1.0 for n, v in d.items()},
                                                  friction_torque_Nm=d["friction_torque"])
                               for (qa, qb), d in vals.items()}
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--settle", type=float, default=0.02, help="simulated time before sampling [s]")
    ap.add_argument("--quad", type=int, nargs=2, default=(6, 2), help="quadrature nodes (major, minor)")
    ap.add_argument("--calls", type=int, default=200, help="sweeps per timed loop")
    ap.add_argument("--repeats", type=int, default=25, help="timed loops (the best is kept)")
    ap.add_argument("--both", action="store_true",
                    help="run the fast and the plain (BEARING_PLAIN_MATH=1) builds back to back")
    ap.add_argument("--quad-check", action="store_true",
                    help="friction torque and race losses of each quadrature rule against 48 x 24 instead")
    ap.add_argument("--rules", default="6x2,8x2,8x4,12x6,24x12,48x24",
                    help="quadrature rules of --quad-check, the last one the reference")
    ap.add_argument("--rpm", default="10000,1000", help="shaft speeds of --quad-check [rpm]")
    ap.add_argument("--settle-qc", type=float, default=0.04, help="--quad-check: time before the window [s]")
    ap.add_argument("--window", type=float, default=0.02, help="--quad-check: averaging window [s]")
    ap.add_argument("--quick", action="store_true", help="20 sweeps x 5 loops (--calls 20 --repeats 5)")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    if a.quick:
        a.calls, a.repeats = 20, 5
    if a.quad_check:
        rules = tuple(tuple(int(v) for v in r.split("x")) for r in a.rules.split(","))
        out = quadrature_check(settle=a.settle_qc, window=a.window, rules=rules,
                               rpms=tuple(float(v) for v in a.rpm.split(",")))
        if a.json:
            print(json.dumps(dict(out, machine=machine_info())))
        else:
            print(machine_line(clock="no timings"))
            print("\n".join(f"{sp} {rule}: " + ", ".join(f"{n} {v:+.2e}" for n, v in d.items())
                            for sp, rules in out.items() for rule, d in rules.items()))
        return out
    if a.both:
        res = {}
        for name, plain in (("fast", "0"), ("plain", "1")):
            env = dict(os.environ, BEARING_PLAIN_MATH=plain)
            cmd = [sys.executable, os.path.abspath(__file__), "--json", "--settle", str(a.settle), "--quad",
                   str(a.quad[0]), str(a.quad[1]), "--calls", str(a.calls), "--repeats", str(a.repeats)]
            r = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
            res[name] = json.loads(r.stdout.strip().splitlines()[-1])
        out = dict(res, machine=machine_info())     # each build's own "machine" stays in it (its plain-math flag)
    else:
        out = measure(a.settle, tuple(a.quad), a.calls, a.repeats)
    if a.json:
        print(json.dumps(out))
        return out
    print(machine_line(out["machine"]))
    for name, r in ([(k, v) for k, v in out.items() if k != "machine"] if a.both else [("this build", out)]):
        print(f"{name}: {r['build']}")
        print("  us per contact, wall (thread CPU): " + ", ".join(
            f"{k} {v:.3f} ({r['us_per_contact_cpu'][k]:.3f})" for k, v in r["us_per_contact"].items()))
        print(f"  right-hand side: {r['rhs_us']:.2f} us wall ({r['rhs_cpu_us']:.2f} us thread CPU)")
    return out


if __name__ == "__main__":
    main()
