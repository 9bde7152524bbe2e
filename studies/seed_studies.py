"""Reproduce the seeds' transient studies with bearing_core.models.dynamics and write the figures and numbers
used in docs/model_checks.md. The seed 000 loads and the settle-time measure are those of the validation
case seed000-preload-trend (bearing_validation), so the study and `bearing validate` agree.

  seed 000 (Lubricants 2025 13(5) 218), 7218B through its acceleration profile:
    - friction study: Coulomb traction mu = 0.001 and 0.1 (pocket and land friction equal to mu, a solid
      lubricant film everywhere), Fx = 1000 N, Fz = 3000 N (the paper does not state its loads)
    - preload study: Fz = 750 / 1500 / 3000 N (25 / 50 / 100 % of our 3000 N 'MOL'), same Fx
  seed 002 (Lubricants 2023 11(3) 96), 7008-ma2023 at 5000 rpm: sliding velocity against axial load
  (reduced model), and a combined 100 N axial + 200 N radial case (unloaded zone).

    python studies/seed_studies.py [--out docs/figures] [--quick]
"""
from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import numpy as np

from bearing_core.models.dynamics import (DynamicModel, DynamicsOptions, SEED000_PROFILE, records_to_dict,
                                   simulate_profile)
from bearing_core.bearing.geometry import load_preset
from bearing_validation import load_cases
from bearing_validation.kinds import _settle_time

RPM = math.pi / 30


_CASE = load_cases(names=["seed000-preload-trend"])[0]["inputs"]
FX = _CASE["Fx_N"]                    # radial load held in the seed 000 runs [N]
FZ_LIST = tuple(sorted(_CASE["Fz_N"]))  # 25 / 50 / 100 % of our MOL [N]


def seed000_run(mu, fz, fx=FX, t_end=2.0):
    m = DynamicModel(load_preset("7218B"), DynamicsOptions(traction="coulomb", mu=mu, mu_pocket=mu, mu_land=mu,
                                                           reduced="full"))
    m.initialize(1000 * RPM, (fx, 0.0, fz, 0.0, 0.0))
    prof = [p for p in SEED000_PROFILE if p[0] < t_end] + [(t_end, float(np.interp(
        t_end, [p[0] for p in SEED000_PROFILE], [p[1] for p in SEED000_PROFILE])))]
    return records_to_dict(simulate_profile(m, prof, record_dt=2e-3))


def settle_time(d, tol=0.01):
    """First time after which the cage speed stays within tol of its mean over the last 0.1 s."""
    return _settle_time(d["t"], d["cage_speed"], tol)


def seed002_axial(fa, rpm=5000.0, T=0.08):
    m = DynamicModel(load_preset("7008-ma2023"), DynamicsOptions(traction="lubricated"))
    m.initialize(rpm * RPM, (0.0, 0.0, fa, 0.0, 0.0))
    d = records_to_dict(m.advance(T, record_dt=1e-4))
    late = d["t"] > T / 2
    bd = m.ball_details()
    return {"Fa_N": fa, "slip_inner_m_s": float(abs(bd["slip_i"][0])), "slip_outer_m_s": float(abs(bd["slip_o"][0])),
            "cage_over_theory": float(d["cage_speed"][late].mean() / d["pure_rolling_cage_speed"][late].mean())}


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="docs/figures")
    ap.add_argument("--quick", action="store_true", help="seed 002 part only")
    a = ap.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    res = {}
    if not a.quick:
        runs = {}
        for mu in (0.001, 0.1):
            for fz in FZ_LIST:
                d = seed000_run(mu, fz)
                runs[(mu, fz)] = d
                acc = d["t"] > 0.5
                tail = d["t"] > 1.9
                res[f"mu={mu},Fz={fz:g}"] = {
                    "cage_end_rpm": float(d["cage_speed"][tail].mean() / RPM),
                    "csr_end": float((d["cage_speed"] / d["shaft_speed"])[tail].mean()),
                    "csr_theory_end": float((d["pure_rolling_cage_speed"] / d["shaft_speed"])[tail].mean()),
                    "min_csr_over_theory_after_0.5s": float(np.min(d["cage_speed"][acc] / d["pure_rolling_cage_speed"][acc])),
                    "settle_time_s": settle_time(d),
                    "max_abs_ir_ax_m_s2_accel_phase": float(np.max(np.abs(d["ir_ax"][(d["t"] > 0.5) & (d["t"] < 1.4)]))),
                    "friction_torque_end_Nm": float(d["friction_torque"][tail].mean()),
                }
                print(f"mu={mu} Fz={fz:g}: {json.dumps(res[f'mu={mu},Fz={fz:g}'])}", flush=True)
        fig, ax = plt.subplots(1, 2, figsize=(12, 4.5), constrained_layout=True)
        for i, mu in enumerate((0.001, 0.1)):
            for fz in FZ_LIST:
                d = runs[(mu, fz)]
                ax[i].plot(d["t"], d["cage_speed"] / d["shaft_speed"], label=f"Fz {fz:g} N")
            d = runs[(mu, 3000.0)]
            ax[i].plot(d["t"], d["pure_rolling_cage_speed"] / d["shaft_speed"], "k--", label="theoretical (Eq. 26)")
            ax[i].set_title(f"7218B, seed 000 profile, Coulomb mu = {mu}")
            ax[i].set_xlabel("time [s]")
            ax[i].set_ylabel("cage / shaft speed ratio [-]")
            ax[i].grid(alpha=0.3)
            ax[i].legend()
        fig.savefig(out / "seed000_csr.png", dpi=90)
        plt.close(fig)
    sweep = [seed002_axial(fa) for fa in (10.0, 20.0, 40.0, 60.0, 80.0, 120.0, 200.0, 400.0)]
    res["seed002_axial_sweep_5000rpm"] = sweep
    for r in sweep:
        print(r, flush=True)
    fig, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
    ax.semilogy([r["Fa_N"] for r in sweep], [r["slip_inner_m_s"] for r in sweep], "o-", label="inner race")
    ax.semilogy([r["Fa_N"] for r in sweep], [r["slip_outer_m_s"] for r in sweep], "s-", label="outer race")
    ax.set_xlabel("axial load [N]")
    ax.set_ylabel("sliding velocity at contact centre [m/s]")
    ax.set_title("7008-ma2023, 5000 rpm, lubricated (seed 002 Fig. 13)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.savefig(out / "seed002_sliding_vs_axial_load.png", dpi=90)
    plt.close(fig)
    (out / "studies.json").write_text(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
