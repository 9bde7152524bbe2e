"""Seed 003 wear study on the wan-105 bearing: wear coefficient and film against speed and load (seed 003
Figs. 5-10), sliding speed over a contact ellipse (Fig. 12), sliding at the ellipse centre against speed
(Fig. 13), and raceway wear depth over hours (not in the seed). Writes the figures docs/figures/seed003_wear_*.png and the numbers to
out/seed003_wear_study.json (quoted in docs/wear.md), with a summary on stdout.

    python studies/wear_study.py [--out docs/figures] [--json out/seed003_wear_study.json]

Loads the seed does not state: the axial preload of Figs. 5-10 (Fz = 500 N, the preload the seed names for
Fig. 12) and the load levels of Figs. 6-10 (ours: Fx 100/300/500 N, M 1/3/5 N m). Speed 10000 rpm for
Figs. 6-10 (the seed's Fig. 12 speed). Azimuth: ours, psi from +x towards +y; the seed's phi
(f_d = dx sin(phi) + dy cos(phi), Eq. 3) is phi = 90 deg - psi.
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

from bearing_core.bearing.geometry import load_preset
from bearing_core.models.wear import SEED003, SEED003_AS_PRINTED, operating_point_wear, wear_rates, wear_report

RPM = math.pi / 30.0
FZ_PRELOAD = 500.0          # N, seed 003 Fig. 12 "preload 500 N"; assumed for Figs. 5-10
SPEED_FIGS_6_10 = 10000.0   # rpm, seed 003 Fig. 12 speed; assumed for Figs. 6-10


def op(g, rpm, loads, params=SEED003):
    return operating_point_wear(g, rpm * RPM, loads, params)


def per_ball(o):
    """Per-ball arrays of an operating point: k, h_min, Lambda, Q, centre sliding speed, wear rate."""
    out = {"psi_deg": np.degrees(o["qs"].psi).tolist()}
    for race in ("inner", "outer"):
        r = o[race]
        s = r.states
        out[f"k_{race}_per_Pa"] = r.k.tolist()
        out[f"h_min_{race}_m"] = np.nan_to_num(r.h_min).tolist()
        out[f"lambda_{race}"] = np.nan_to_num(r.Lambda).tolist()
        out[f"Q_{race}_N"] = s.Q.tolist()
        out[f"v_centre_{race}_m_s"] = np.hypot(s.vs_t, s.vs_m).tolist()
        out[f"V_dot_{race}_m3_s"] = r.V_dot.tolist()
        out[f"mean_sliding_{race}_m_s"] = np.where(s.Q > 0, r.P_pv / np.where(s.Q > 0, s.Q, 1.0), 0.0).tolist()
    return out


def zones(Q_lo, Q_hi):
    """Bearing zone: balls whose inner load grows with the applied load; non-bearing zone: the others."""
    Q_lo, Q_hi = np.asarray(Q_lo), np.asarray(Q_hi)
    return Q_hi > Q_lo, Q_hi <= Q_lo


def count_local_minima(y):
    """Interior local minima of a periodic sequence (a 'W' has two)."""
    y = np.asarray(y)
    return int(np.sum((y < np.roll(y, 1)) & (y < np.roll(y, -1))))


def load_sweep(g, label, loads_list):
    runs = [per_ball(op(g, SPEED_FIGS_6_10, L)) for L in loads_list]
    lo, hi = runs[0], runs[-1]
    bz, nbz = zones(lo["Q_inner_N"], hi["Q_inner_N"])
    summ = {"label": label, "loads": [list(map(float, L)) for L in loads_list], "runs": runs,
            "bearing_zone_balls": np.where(bz)[0].tolist()}
    for race in ("inner", "outer"):
        K = np.array([r[f"k_{race}_per_Pa"] for r in runs])
        dk = np.diff(K, axis=0)
        summ[f"k_{race}_increasing_in_bearing_zone"] = bool(np.all(dk[:, bz] > 0))
        summ[f"k_{race}_decreasing_in_non_bearing_zone"] = bool(np.all(dk[:, nbz] < 0)) if nbz.any() else None
        summ[f"k_{race}_argmax_psi_deg"] = [float(runs[0]["psi_deg"][int(np.argmax(k))]) for k in K]
        summ[f"k_{race}_local_minima"] = [count_local_minima(k) for k in K]
    return summ


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="docs/figures")
    ap.add_argument("--json", default="out/seed003_wear_study.json")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t0 = time.time()
    g = load_preset("wan-105")
    res = {"bearing": "wan-105", "preload_Fz_N": FZ_PRELOAD, "speed_figs_6_10_rpm": SPEED_FIGS_6_10}

    # ---- Fig. 5: speed, Fx = Fy = 300 N, Mx = My = 3 N m -------------------------------------------------
    speeds = [2000.0, 4000.0, 6000.0, 8000.0, 10000.0, 12000.0, 14000.0, 16000.0]
    L5 = (300.0, 300.0, FZ_PRELOAD, 3.0, 3.0)
    sp = [per_ball(op(g, n, L5)) for n in speeds]
    sp_printed = [per_ball(op(g, n, L5, SEED003_AS_PRINTED)) for n in speeds]
    f5 = {"speeds_rpm": speeds, "loads": list(L5), "runs": sp}
    for race in ("inner", "outer"):
        K = np.array([r[f"k_{race}_per_Pa"] for r in sp])
        H = np.array([r[f"h_min_{race}_m"] for r in sp])
        loaded = np.all(np.array([r[f"Q_{race}_N"] for r in sp]) > 0, axis=0)
        f5[f"k_{race}_decreasing_with_speed_all_balls"] = bool(np.all(np.diff(K[:, loaded], axis=0) < 0))
        f5[f"h_min_{race}_increasing_with_speed_all_balls"] = bool(np.all(np.diff(H[:, loaded], axis=0) > 0))
        f5[f"k_{race}_mean_per_Pa"] = K[:, loaded].mean(axis=1).tolist()
        f5[f"h_min_{race}_mean_m"] = H[:, loaded].mean(axis=1).tolist()
        Hp = np.array([r[f"h_min_{race}_m"] for r in sp_printed])
        f5[f"h_min_{race}_as_printed_over_ours"] = float(np.mean(Hp[:, loaded] / H[:, loaded]))
        V = np.array([r[f"v_centre_{race}_m_s"] for r in sp])
        f5[f"v_centre_{race}_max_m_s"] = V.max(axis=1).tolist()
        M = np.array([r[f"mean_sliding_{race}_m_s"] for r in sp])
        f5[f"mean_sliding_{race}_max_m_s"] = M.max(axis=1).tolist()
    res["fig5_speed"] = f5

    # ---- Figs. 6-10: loads at 10000 rpm --------------------------------------------------------------
    Fs = (100.0, 300.0, 500.0)
    Ms = (1.0, 3.0, 5.0)
    sweeps = {
        "fig6_Fx": [(F, 0.0, FZ_PRELOAD, 0.0, 0.0) for F in Fs],
        "fig6_Fy": [(0.0, F, FZ_PRELOAD, 0.0, 0.0) for F in Fs],
        "fig7_Mx": [(0.0, 0.0, FZ_PRELOAD, M, 0.0) for M in Ms],
        "fig7_My": [(0.0, 0.0, FZ_PRELOAD, 0.0, M) for M in Ms],
    }
    for k_, L in sweeps.items():
        res[k_] = load_sweep(g, k_, L)
    # which sign of My loads the same side as +Fx (seed Figs. 8-9: "same" / "opposite" direction)
    psi_fx = res["fig6_Fx"]["k_inner_argmax_psi_deg"][-1]
    q_my = np.array(res["fig7_My"]["runs"][-1]["Q_inner_N"])
    psi = np.array(res["fig7_My"]["runs"][-1]["psi_deg"])
    sgn = 1.0 if abs(((psi[int(np.argmax(q_my))] - psi_fx) + 180) % 360 - 180) < 90 else -1.0
    res["my_sign_same_side_as_fx"] = sgn
    res["fig8_same_direction"] = load_sweep(g, "fig8", [(F, 0.0, FZ_PRELOAD, 0.0, sgn * M) for F, M in zip(Fs, Ms)])
    res["fig9_opposite_direction"] = load_sweep(g, "fig9", [(F, 0.0, FZ_PRELOAD, 0.0, -sgn * M)
                                                            for F, M in zip(Fs, Ms)])
    res["fig10_all_combined"] = load_sweep(g, "fig10", [(F, F, FZ_PRELOAD, M, sgn * M) for F, M in zip(Fs, Ms)])

    # ---- Fig. 12: sliding speed over the ellipse, Fx = Fy = 300 N, preload 500 N, 10000 rpm, ball at 135 deg
    # in the seed's azimuth = our psi = 90 - 135 = -45 deg (nearest ball)
    o12 = op(g, 10000.0, (300.0, 300.0, FZ_PRELOAD, 0.0, 0.0))
    psi = np.degrees(o12["qs"].psi)
    j12 = int(np.argmin(np.abs(((psi - (-45.0)) + 180) % 360 - 180)))
    f12 = {"ball": j12, "psi_deg": float(psi[j12])}
    maps = {}
    for race in ("inner", "outer"):
        s = o12[race].states
        a, b = s.a[j12], s.b[j12]
        X, Y = np.meshgrid(np.linspace(-1, 1, 81), np.linspace(-1, 1, 81), indexing="ij")
        inside = X ** 2 + Y ** 2 <= 1.0
        h = 0.5 * s.D
        R = s.R_def
        x, y = a * X, b * Y
        d = np.sqrt(R * R - x * x) - np.sqrt(R * R - a * a) + np.sqrt(h * h - a * a) - h
        vt = s.vs_t[j12] - s.w_spin[j12] * x + s.w_roll_m[j12] * d
        vm = s.vs_m[j12] + s.w_spin[j12] * y - s.w_roll_t[j12] * d
        v = np.where(inside, np.hypot(vt, vm), np.nan)
        maps[race] = (X, Y, v)
        vx = v[:, 40]                    # along the major axis (y = 0)
        vy = v[40, :]                    # along the minor axis (x = 0)
        f12[f"{race}_major_axis_asymmetry"] = float(np.nanmax(np.abs(vx - vx[::-1])) / np.nanmax(vx))
        f12[f"{race}_minor_axis_variation"] = float((np.nanmax(vy) - np.nanmin(vy)) / np.nanmax(v))
        f12[f"{race}_centre_is_min_along_minor_axis"] = bool(np.nanargmin(vy) == 40)
        f12[f"{race}_v_max_m_s"] = float(np.nanmax(v))
        f12[f"{race}_spin_rad_s"] = float(s.w_spin[j12])
    res["fig12_ellipse_sliding"] = f12

    # ---- wear depth over hours (our extension: the seed gives no depths) --------------------------------
    rep = [wear_report("wan-105", n, fx=300.0, fy=300.0, fz=FZ_PRELOAD, mx=3.0, my=3.0, hours=1000.0)
           for n in speeds]
    res["depth_1000h_vs_speed"] = {
        "speeds_rpm": speeds,
        "inner_wear_depth_m": [r["inner_wear_depth_m"] for r in rep],
        "outer_wear_depth_m": [r["outer_wear_depth_m"] for r in rep],
        "inner_wear_volume_m3": [r["inner_wear_volume_m3"] for r in rep],
        "outer_wear_volume_m3": [r["outer_wear_volume_m3"] for r in rep]}
    repF = [wear_report("wan-105", SPEED_FIGS_6_10, fx=F, fz=FZ_PRELOAD, hours=1000.0) for F in (0.0, 100.0, 300.0, 500.0, 1000.0)]
    res["depth_1000h_vs_Fx"] = {
        "Fx_N": [0.0, 100.0, 300.0, 500.0, 1000.0],
        "inner_wear_depth_m": [r["inner_wear_depth_m"] for r in repF],
        "outer_wear_depth_m": [r["outer_wear_depth_m"] for r in repF],
        "inner_wear_volume_m3": [r["inner_wear_volume_m3"] for r in repF],
        "outer_wear_volume_m3": [r["outer_wear_volume_m3"] for r in repF]}
    # quadrature convergence of the ellipse integral on the Fig. 5 case at 10000 rpm
    o = op(g, 10000.0, L5)
    conv = {}
    for n in (8, 16, 32, 48, 96):
        conv[str(n)] = [wear_rates(o[r].states, n_major=n, n_minor=n // 2 if n > 8 else 4).V_dot_total
                        for r in ("inner", "outer")]
    res["quadrature_convergence_V_dot_m3_s"] = conv
    res["runtime_s"] = time.time() - t0

    jpath = Path(args.json)
    jpath.parent.mkdir(parents=True, exist_ok=True)
    jpath.write_text(json.dumps(res, indent=1))

    # ---- figures -------------------------------------------------------------------------------------
    psi = np.array(sp[0]["psi_deg"])
    fig, ax = plt.subplots(2, 2, figsize=(10, 7))
    cm = plt.get_cmap("viridis")
    for i, (n, r) in enumerate(zip(speeds, sp)):
        c = cm(i / (len(speeds) - 1))
        ax[0, 0].plot(psi, r["k_inner_per_Pa"], "-o", ms=3, color=c, label=f"{n:.0f} rpm")
        ax[0, 1].plot(psi, r["k_outer_per_Pa"], "-o", ms=3, color=c)
        ax[1, 0].plot(psi, np.array(r["h_min_inner_m"]) * 1e6, "-o", ms=3, color=c)
        ax[1, 1].plot(psi, np.array(r["h_min_outer_m"]) * 1e6, "-o", ms=3, color=c)
    ax[0, 0].set_ylabel("k_i [m^3/(N m)]"); ax[0, 1].set_ylabel("k_o [m^3/(N m)]")
    ax[1, 0].set_ylabel("h_min,i [um]"); ax[1, 1].set_ylabel("h_min,o [um]")
    for x in ax.ravel():
        x.set_xlabel("ball azimuth psi [deg] (ours; seed phi = 90 - psi)")
        x.grid(alpha=0.3)
    ax[0, 0].legend(fontsize=7)
    fig.suptitle("wan-105, Fx = Fy = 300 N, Mx = My = 3 N m, Fz = 500 N: wear coefficient and film vs speed "
                 "(seed 003 Fig. 5)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out / "seed003_wear_speed.png", dpi=90)
    plt.close(fig)

    keys = ["fig6_Fx", "fig7_Mx", "fig7_My", "fig8_same_direction", "fig9_opposite_direction", "fig10_all_combined"]
    fig, ax = plt.subplots(len(keys), 2, figsize=(10, 2.3 * len(keys)), sharex=True)
    for i, k_ in enumerate(keys):
        sw = res[k_]
        for lvl, (L, r) in enumerate(zip(sw["loads"], sw["runs"])):
            lab = f"Fx {L[0]:.0f} Fy {L[1]:.0f} N, Mx {L[3]:.0f} My {L[4]:.0f} N m"
            ax[i, 0].plot(psi, r["k_inner_per_Pa"], "-o", ms=2, label=lab)
            ax[i, 1].plot(psi, r["k_outer_per_Pa"], "-o", ms=2)
        ax[i, 0].set_ylabel(f"{k_}\nk_i [1/Pa]", fontsize=7)
        ax[i, 1].set_ylabel("k_o [1/Pa]", fontsize=7)
        ax[i, 0].legend(fontsize=6)
        for x in ax[i]:
            x.grid(alpha=0.3)
    for x in ax[-1]:
        x.set_xlabel("ball azimuth psi [deg] (ours; seed phi = 90 - psi)")
    fig.suptitle(f"wan-105, {SPEED_FIGS_6_10:.0f} rpm, Fz = 500 N: wear coefficient vs load (seed 003 Figs. 6-10)",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(out / "seed003_wear_loads.png", dpi=90)
    plt.close(fig)

    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for x, race in zip(ax, ("inner", "outer")):
        X, Y, v = maps[race]
        cs = x.contourf(X, Y, v, 20)
        fig.colorbar(cs, ax=x, label="sliding speed [m/s]")
        x.set_xlabel("x / a (major axis, across the groove)")
        x.set_ylabel("y / b (rolling direction)")
        x.set_title(f"{race} race, ball at psi = {f12['psi_deg']:.0f} deg", fontsize=9)
        x.set_aspect("equal")
    fig.suptitle("Sliding speed over the contact ellipse, Fx = Fy = 300 N, Fz = 500 N, 10000 rpm "
                 "(seed 003 Fig. 12)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out / "seed003_wear_ellipse_sliding.png", dpi=90)
    plt.close(fig)

    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    dv = res["depth_1000h_vs_speed"]
    ax[0].plot(speeds, np.array(dv["inner_wear_depth_m"]) * 1e6, "-o", label="inner")
    ax[0].plot(speeds, np.array(dv["outer_wear_depth_m"]) * 1e6, "-s", label="outer")
    ax[0].set_xlabel("speed [rpm]"); ax[0].set_ylabel("max raceway wear depth after 1000 h [um]")
    ax[0].set_title("Fx = Fy = 300 N, Mx = My = 3 N m, Fz = 500 N", fontsize=9)
    dF = res["depth_1000h_vs_Fx"]
    ax[1].plot(dF["Fx_N"], np.array(dF["inner_wear_depth_m"]) * 1e6, "-o", label="inner")
    ax[1].plot(dF["Fx_N"], np.array(dF["outer_wear_depth_m"]) * 1e6, "-s", label="outer")
    ax[1].set_xlabel("Fx [N]"); ax[1].set_title("10000 rpm, Fz = 500 N", fontsize=9)
    for x in ax:
        x.grid(alpha=0.3); x.legend()
    fig.suptitle("Raceway wear depth (seed 003 model, our extension: the seed gives no depths)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out / "seed003_wear_depth.png", dpi=90)
    plt.close(fig)

    print(json.dumps({k: v for k, v in res["fig5_speed"].items() if k != "runs"}, indent=1))
    for k_ in ["fig6_Fx", "fig6_Fy", "fig7_Mx", "fig7_My", "fig8_same_direction", "fig9_opposite_direction",
               "fig10_all_combined"]:
        print(k_, json.dumps({k: v for k, v in res[k_].items() if k not in ("runs",)}))
    print("fig12", json.dumps(f12))
    print("depth vs speed", json.dumps(res["depth_1000h_vs_speed"]))
    print("depth vs Fx", json.dumps(res["depth_1000h_vs_Fx"]))
    print("quadrature", json.dumps(conv))
    print(f"runtime {res['runtime_s']:.1f} s")


if __name__ == "__main__":
    main()
