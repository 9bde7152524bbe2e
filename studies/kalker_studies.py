"""Seed 000 (Lubricants 2025 13(5) 218) studies with Kalker (FASTSIM) traction in the dynamics, 7218B,
SEED000_PROFILE (1000 rpm to 0.5 s, 10,000 rpm/s to 10,000 rpm at 1.4 s, held to 2 s). Writes the
figures docs/figures/seed000_kalker_*.png and the numbers (JSON) used in docs/kalker.md.

  (a) preload study (seed 000 Sec. 5.2, Fig. 14, Table 3): axial preload 25 / 50 / 100 % of our 'maximum
      of loading' (MOL) Fz = 3000 N, i.e. Fz = 750 / 1500 / 3000 N, radial Fx = 1000 N held at all
      preloads; mu = 0.001 and 0.1 (pocket and land friction equal to mu: a solid film everywhere).
      Vibration measure as Table 3: maximum |inner-ring x acceleration| during the acceleration phase
      (0.5 - 1.4 s), plus its RMS in that window (the paper's table has no unit; ours is m/s^2).
  (b) friction study (Sec. 5.1, Figs. 12-13; Figs. 15-16 for the preloads): slide-to-roll ratio
      (vs_t / |u_roll|, centre slip along rolling over the entrainment speed) and spin-to-roll ratio
      (w_spin (D/2) / |u_roll|) of ball 0 at the inner and outer contacts; set to 0 while the contact is
      open (as the paper does: "the spinning ratio is therefore considered zero").

    python studies/kalker_studies.py [--quick] [--out docs/figures] [--cache out/kalker_studies] [--grid 12]

--quick: 0.7 s of the profile, Fz = 3000 N only (a check that everything runs, ~30 s). Full: six 2 s runs,
about 30-70 s wall each on one core; raw records are cached (npz) and reused unless --rerun.
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

from bearing_core.models.dynamics import (DynamicModel, DynamicsOptions, SEED000_PROFILE, records_to_dict,
                                   simulate_profile)
from bearing_core.bearing.geometry import load_preset

RPM = math.pi / 30
MOL = 3000.0                  # our 100 % axial preload [N] (the paper does not state its MOL)
FX = 1000.0                   # radial load [N], held at every preload
PRELOADS = (0.25, 0.5, 1.0)
MUS = (0.001, 0.1)


def _profile(t_end):
    ts = [p[0] for p in SEED000_PROFILE]
    ns = [p[1] for p in SEED000_PROFILE]
    return [p for p in SEED000_PROFILE if p[0] < t_end] + [(t_end, float(np.interp(t_end, ts, ns)))]


def run(mu, fz, t_end=2.0, grid=12, record_dt=2e-4):
    """One seed 000 run with Kalker traction; returns (records dict, wall time [s])."""
    m = DynamicModel(load_preset("7218B"), DynamicsOptions(traction="kalker", mu=mu, mu_pocket=mu, mu_land=mu,
                                                           reduced="full", kalker_grid=grid))
    m.initialize(1000 * RPM, (FX, 0.0, fz, 0.0, 0.0))
    t0 = time.perf_counter()
    d = records_to_dict(simulate_profile(m, _profile(t_end), record_dt=record_dt))
    return d, time.perf_counter() - t0


def cached_run(cache: Path, mu, fz, t_end, grid, rerun=False):
    f = cache / f"mu{mu:g}_fz{fz:g}_t{t_end:g}_g{grid}.npz"
    if f.exists() and not rerun:
        z = np.load(f)
        return {k: z[k] for k in z.files if k != "_wall"}, float(z["_wall"])
    d, wall = run(mu, fz, t_end, grid)
    cache.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(f, _wall=wall, **d)
    return d, wall


def ratios(d):
    """Ball 0 slide-to-roll and spin-to-roll ratios, zero while the contact is open (paper's convention)."""
    r = {}
    for k, q in (("slide_roll_i", "ball0_Q_i"), ("slide_roll_o", "ball0_Q_o"),
                 ("spin_roll_i", "ball0_Q_i"), ("spin_roll_o", "ball0_Q_o")):
        r[k] = np.where(d[q] > 0.0, d["ball0_" + k], 0.0)
    return r


def settle_time(d, tol=0.01):
    """First time after which the cage speed stays within tol of its mean over the last 0.1 s."""
    t = d["t"]
    final = d["cage_speed"][t > t[-1] - 0.1].mean()
    bad = np.where(np.abs(d["cage_speed"] / final - 1) > tol)[0]
    return float(t[bad[-1]]) if len(bad) else float(t[0])


WINDOWS = {"1000rpm_0.3-0.5s": (0.3, 0.5), "ramp_0.9-1.4s": (0.9, 1.4), "after_ramp_1.4-1.7s": (1.4, 1.7),
           "end_1.85-2.0s": (1.85, 2.0)}


def summarize(d, wall):
    t = d["t"]
    t_end = float(t[-1])
    acc = (t >= 0.5) & (t <= min(1.4, t_end))
    tail = t > t_end - 0.1
    csr = d["cage_speed"] / d["shaft_speed"]
    th = d["pure_rolling_cage_speed"] / d["shaft_speed"]
    ax = d["ir_ax"][acc]
    s = {
        "wall_s": wall, "sim_s": t_end - float(t[0]), "real_time_factor": wall / (t_end - float(t[0])),
        "cage_end_rpm": float(d["cage_speed"][tail].mean() / RPM),
        "csr_end": float(csr[tail].mean()), "csr_theory_end": float(th[tail].mean()),
        "min_csr_over_theory_after_0.5s": float(np.min((csr / th)[t > 0.5])) if t_end > 0.5 else float("nan"),
        "settle_time_s": settle_time(d),
        "max_abs_ir_ax_accel_m_s2": float(np.max(np.abs(ax))) if ax.size else float("nan"),
        "rms_ir_ax_accel_m_s2": float(np.sqrt(np.mean((ax - ax.mean()) ** 2))) if ax.size else float("nan"),
        "ptp_ir_x_accel_um": float(np.ptp(d["ir_x"][acc]) * 1e6) if ax.size else float("nan"),
        "min_Q_i_accel_N": float(np.min(d["Q_i_min"][acc])) if ax.size else float("nan"),
        "friction_torque_end_Nm": float(d["friction_torque"][tail].mean()),
    }
    r = ratios(d)
    for w, (a, b) in WINDOWS.items():
        sel = (t >= a) & (t <= b)
        if not sel.any():
            continue
        for k, v in r.items():
            s[f"{k}_mean_{w}"] = float(v[sel].mean())
            s[f"{k}_absmax_{w}"] = float(np.max(np.abs(v[sel])))
    # outer spin: time of the peak |ratio| and sign reversals after 0.5 s (seed 000 Fig. 13b)
    after = t > 0.5
    so = r["spin_roll_o"][after]
    s["spin_roll_o_peak_time_s"] = float(t[after][np.argmax(np.abs(so))]) if so.size else float("nan")
    sgn = np.sign(so[np.abs(so) > 1e-6])
    s["spin_roll_o_sign_changes_after_0.5s"] = int(np.count_nonzero(np.diff(sgn))) if sgn.size else 0
    s["inner_contact_open_fraction_accel"] = float(np.mean(d["ball0_Q_i"][acc] <= 0.0)) if ax.size else 0.0
    return s


def smooth(x, n):
    if n <= 1:
        return x
    k = np.ones(n) / n
    return np.convolve(x, k, mode="same")


def plots(runs, out: Path, t_end):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # Fig. 14 analogue: CSR for three preloads, both mu
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5), constrained_layout=True)
    for i, mu in enumerate(MUS):
        for p in PRELOADS:
            if (mu, p) not in runs:
                continue
            d = runs[(mu, p)][0]
            ax[i].plot(d["t"], d["cage_speed"] / d["shaft_speed"], lw=1, label=f"{p:.0%} MOL (Fz {p * MOL:g} N)")
        if (mu, 1.0) in runs:
            d = runs[(mu, 1.0)][0]
            ax[i].plot(d["t"], d["pure_rolling_cage_speed"] / d["shaft_speed"], "k--", lw=1,
                       label="theoretical (Eq. 26)")
        ax[i].set_title(f"7218B, seed 000 profile, Kalker traction mu = {mu}, Fx = {FX:g} N")
        ax[i].set_xlabel("time [s]")
        ax[i].set_ylabel("cage / shaft speed ratio (CSR) [-]")
        ax[i].set_xlim(0, t_end)
        ax[i].grid(alpha=0.3)
        ax[i].legend(fontsize=8)
    fig.savefig(out / "seed000_kalker_csr.png", dpi=90)
    plt.close(fig)
    # Figs. 12-13 analogue: ratios at 100 % preload for both mu
    fig, ax = plt.subplots(2, 2, figsize=(12, 7.5), constrained_layout=True, sharex=True)
    for mu, col in zip(MUS, ("C3", "C0")):
        if (mu, 1.0) not in runs:
            continue
        d = runs[(mu, 1.0)][0]
        r = ratios(d)
        for (i, j), k, lab in (((0, 0), "slide_roll_i", "inner slide-to-roll"), ((0, 1), "slide_roll_o", "outer slide-to-roll"),
                               ((1, 0), "spin_roll_i", "inner spin-to-roll"), ((1, 1), "spin_roll_o", "outer spin-to-roll")):
            ax[i, j].plot(d["t"], r[k], color=col, lw=0.6, label=f"mu = {mu}")
            ax[i, j].set_title(f"{lab} (ball 0), Fz = {MOL:g} N, Fx = {FX:g} N")
            ax[i, j].grid(alpha=0.3)
            ax[i, j].legend(fontsize=8)
    for j in range(2):
        ax[1, j].set_xlabel("time [s]")
    fig.savefig(out / "seed000_kalker_ratios_mu.png", dpi=90)
    plt.close(fig)
    # Figs. 15-16 analogue: ratios against preload, mu = 0.001
    fig, ax = plt.subplots(2, 2, figsize=(12, 7.5), constrained_layout=True, sharex=True)
    for p, col in zip(PRELOADS, ("C1", "C2", "C0")):
        if (0.001, p) not in runs:
            continue
        d = runs[(0.001, p)][0]
        r = ratios(d)
        for (i, j), k, lab in (((0, 0), "slide_roll_i", "inner slide-to-roll"), ((0, 1), "slide_roll_o", "outer slide-to-roll"),
                               ((1, 0), "spin_roll_i", "inner spin-to-roll"), ((1, 1), "spin_roll_o", "outer spin-to-roll")):
            ax[i, j].plot(d["t"], r[k], color=col, lw=0.6, label=f"{p:.0%} MOL")
            ax[i, j].set_title(f"{lab} (ball 0), mu = 0.001")
            ax[i, j].grid(alpha=0.3)
            ax[i, j].legend(fontsize=8)
    for j in range(2):
        ax[1, j].set_xlabel("time [s]")
    fig.savefig(out / "seed000_kalker_ratios_preload.png", dpi=90)
    plt.close(fig)
    # Table 3 analogue: inner-ring x acceleration
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.2), constrained_layout=True, sharey=True)
    for i, mu in enumerate(MUS):
        for p in PRELOADS[::-1]:
            if (mu, p) not in runs:
                continue
            d = runs[(mu, p)][0]
            ax[i].plot(d["t"], d["ir_ax"], lw=0.5, label=f"{p:.0%} MOL")
        ax[i].axvspan(0.5, 1.4, color="0.9", zorder=0)
        ax[i].set_title(f"inner-ring x acceleration, mu = {mu} (shaded: acceleration phase)")
        ax[i].set_xlabel("time [s]")
        ax[i].set_ylabel("a_x [m/s^2]")
        ax[i].grid(alpha=0.3)
        ax[i].legend(fontsize=8)
    fig.savefig(out / "seed000_kalker_vibration.png", dpi=90)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="docs/figures")
    ap.add_argument("--cache", default="out/kalker_studies")
    ap.add_argument("--quick", action="store_true", help="0.7 s, Fz = 3000 N only")
    ap.add_argument("--grid", type=int, default=12)
    ap.add_argument("--rerun", action="store_true")
    a = ap.parse_args(argv)
    out, cache = Path(a.out), Path(a.cache)
    t_end = 0.7 if a.quick else 2.0
    if a.quick:
        out = cache / "quick_figures"
    out.mkdir(parents=True, exist_ok=True)
    pre = (1.0,) if a.quick else PRELOADS
    runs, res = {}, {}
    for mu in MUS:
        for p in pre[::-1]:
            d, wall = cached_run(cache, mu, p * MOL, t_end, a.grid, a.rerun)
            runs[(mu, p)] = (d, wall)
            s = summarize(d, wall)
            res[f"mu={mu},preload={p:.0%},Fz={p * MOL:g}"] = s
            print(f"mu={mu} Fz={p * MOL:g} N: wall {wall:.1f} s (RTF {s['real_time_factor']:.1f}), cage end "
                  f"{s['cage_end_rpm']:.0f} rpm, CSR {s['csr_end']:.3f} (theory {s['csr_theory_end']:.3f}), "
                  f"min CSR/theory {s['min_csr_over_theory_after_0.5s']:.3f}, settle {s['settle_time_s']:.2f} s, "
                  f"max|ax| {s['max_abs_ir_ax_accel_m_s2']:.2f} m/s2, rms {s['rms_ir_ax_accel_m_s2']:.3f}", flush=True)
    plots(runs, out, t_end)
    (cache / ("kalker_studies_quick.json" if a.quick else "kalker_studies.json")).write_text(json.dumps(res, indent=1))
    print(f"figures in {out}, numbers in {cache}")


if __name__ == "__main__":
    main()
