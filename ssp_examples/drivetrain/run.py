"""Run the drivetrain SSP with fmpy and with libcosim, check the energy balance, compare, plot.

    python ssp_examples/drivetrain/run.py [--stop-time T] [--out out/ssp_drivetrain]

Builds the FMUs and the SSP first if ssp_examples/build/drivetrain.ssp is missing. Writes results_<master>.npz,
drivetrain.png (run-up, torques, bearing losses, energy) and summary.json.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SSP_DIR = HERE.parent
ROOT = SSP_DIR.parent
sys.path.insert(0, str(SSP_DIR))
from masters import run_subprocess  # noqa: E402

RPM = 30.0 / math.pi


def energy_balance(r, h, design):
    """Energies [J] at the end of the run, each from the component that owns it: motor work (motor FMU),
    load work (fan FMU), bearing losses (time integral of the bearings' heat_flux_total, one value per step),
    change of the shaft's kinetic energy (shaft FMU). residual = motor - load - losses - kinetic. The shaft-side
    balance uses the shaft FMU's own work integrals (exact by construction: a check of the bookkeeping)."""
    q = float(np.sum(r["bearing_A.heat_flux_total"] + r["bearing_B.heat_flux_total"]) * h)
    ke0 = 0.5 * design["inertia"] * design["speed0"] ** 2
    e = {"motor_work_J": float(r["motor.work"][-1]), "load_work_J": float(r["load.work"][-1]),
         "bearing_losses_J": q, "kinetic_energy_change_J": float(r["shaft.kinetic_energy"][-1] - ke0),
         "shaft_side_friction_work_J": float(r["shaft.work_friction"][-1]),
         "shaft_side_motor_work_J": float(r["shaft.work_motor"][-1]),
         "shaft_side_load_work_J": float(r["shaft.work_load"][-1])}
    e["residual_J"] = e["motor_work_J"] - e["load_work_J"] - q - e["kinetic_energy_change_J"]
    e["residual_rel"] = e["residual_J"] / e["motor_work_J"]
    e["shaft_side_residual_J"] = (e["shaft_side_motor_work_J"] - e["shaft_side_load_work_J"]
                                  - e["shaft_side_friction_work_J"] - e["kinetic_energy_change_J"])
    e["bearing_friction_work_vs_heat_rel"] = (e["shaft_side_friction_work_J"] - q) / q
    return e


def smooth(x, n):
    n = max(1, int(n))
    k = np.ones(n)
    return np.convolve(x, k, mode="same") / np.convolve(np.ones_like(x), k, mode="same")   # no edge dip


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ssp", default=str(SSP_DIR / "build" / "drivetrain.ssp"))
    ap.add_argument("--stop-time", type=float, default=None)
    ap.add_argument("--out", default=str(ROOT / "out" / "ssp_drivetrain"))
    ap.add_argument("--masters", default="fmpy,libcosim",
                    help="comma list (the drive at fidelity 'map', build/drivetrain_map.ssp, runs with libcosim only: "
                         "fmpy's simulate_ssp holds every connected input at 0 during the first step, and a shaft "
                         "speed of 0 is outside the map, which is never extrapolated)")
    a = ap.parse_args(argv)
    masters = tuple(m.strip() for m in a.masters.split(",") if m.strip())
    ssp = Path(a.ssp)
    if not ssp.exists():
        import subprocess
        subprocess.run([sys.executable, str(SSP_DIR / "build_examples.py")], check=True)
    d = json.loads(Path(str(ssp) + ".json").read_text())["design"]
    h = d["step"]
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    R, S = {}, {}
    for master in masters:
        print(f"running {ssp.name} with {master} ...", flush=True)
        S[master], R[master], _ = run_subprocess(master, ssp, out / f"results_{master}.npz", a.stop_time,
                                                 env=dict(os.environ))
        print(f"  {S[master]['samples']} steps to {S[master]['t_end']:.3f} s in {S[master]['wall_s']:.1f} s wall")
    summary = {"ssp": str(ssp), "step_s": h, "masters": S}
    for m, r in R.items():
        t = r["time"]
        late = t >= t[-1] - 0.2
        w = r["shaft.shaft_speed"]
        i95 = int(np.argmax(w >= 0.95 * w[-1]))
        summary[m] = {
            "energy": energy_balance(r, h, d), "final_speed_rpm": float(w[-1] * RPM),
            "time_to_95pct_speed_s": float(t[i95]),
            "last_0.2s_mean": {
                "shaft_speed_rpm": float(w[late].mean() * RPM), "motor_torque_Nm": float(r["motor.torque"][late].mean()),
                "load_power_W": float(r["load.power"][late].mean()),
                **{f"friction_torque_{b}_Nm": float(r[f"bearing_{b}.friction_torque"][late].mean()) for b in "AB"},
                **{f"heat_flux_{b}_W": float(r[f"bearing_{b}.heat_flux_total"][late].mean()) for b in "AB"},
                **{f"cage_shaft_ratio_{b}": float(r[f"bearing_{b}.cage_shaft_ratio"][late].mean()) for b in "AB"},
                **{f"cage_shaft_ratio_theory_{b}": float(r[f"bearing_{b}.cage_shaft_ratio_theory"][late].mean())
                   for b in "AB"}}}
        lm = summary[m]["last_0.2s_mean"]
        lm["bearing_loss_share_of_motor_power"] = (lm["heat_flux_A_W"] + lm["heat_flux_B_W"]) / (
            lm["motor_torque_Nm"] * lm["shaft_speed_rpm"] / RPM)
    if "fmpy" in R and "libcosim" in R:
        f, l = summary["fmpy"]["last_0.2s_mean"], summary["libcosim"]["last_0.2s_mean"]
        summary["agreement_rel"] = {k: abs(f[k] - l[k]) / max(abs(f[k]), abs(l[k]), 1e-12) for k in f}
    (out / "summary.json").write_text(json.dumps(summary, indent=1))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 2, figsize=(13, 9))
    n = int(round(0.02 / h))
    for m, ls in (("fmpy", "-"), ("libcosim", "--")):
        if m not in R:
            continue
        r = R[m]
        t = r["time"]
        ax[0, 0].plot(t, r["shaft.shaft_speed"] * RPM, ls, label=f"shaft ({m})")
        for b, col in (("A", "C0"), ("B", "C1")):
            ax[0, 0].plot(t, r[f"bearing_{b}.cage_speed"] * RPM, ls, color=col, lw=0.7, label=f"cage {b} ({m})")
            ax[1, 0].plot(t, smooth(r[f"bearing_{b}.heat_flux_total"], n), ls, color=col, label=f"bearing {b} ({m})")
        ax[0, 1].plot(t, r["motor.torque"], ls, color="C3", label=f"motor ({m})")
        ax[0, 1].plot(t, r["load.torque"], ls, color="C2", label=f"fan ({m})")
        ax[0, 1].plot(t, smooth(r["bearing_A.friction_torque"] + r["bearing_B.friction_torque"], n) * 10, ls,
                      color="C4", label=f"bearings A+B x10, 20 ms mean ({m})")
    m0 = masters[0]
    r, e = R[m0], summary[m0]["energy"]
    ax[1, 1].bar(["motor work", "fan work", "bearing losses", "kinetic energy", "residual"],
                 [e["motor_work_J"], e["load_work_J"], e["bearing_losses_J"], e["kinetic_energy_change_J"],
                  e["residual_J"]], color=["C3", "C2", "C4", "C0", "k"])
    for i, v in enumerate([e["motor_work_J"], e["load_work_J"], e["bearing_losses_J"], e["kinetic_energy_change_J"],
                           e["residual_J"]]):
        ax[1, 1].text(i, v, f"{v:.0f} J", ha="center", va="bottom", fontsize=8)
    ax[0, 0].set(xlabel="time [s]", ylabel="speed [rpm]", title="run-up: speed from the system (motor, inertia, "
                 "fan, bearing friction)")
    ax[0, 1].set(xlabel="time [s]", ylabel="torque [N.m]", title="torques")
    ax[1, 0].set(xlabel="time [s]", ylabel="heat flux [W] (20 ms mean)", title="bearing losses")
    ax[1, 1].set(ylabel="energy [J]", title=f"energy balance to t = {r['time'][-1]:.2f} s ({m0}; residual "
                 f"{100 * e['residual_rel']:.2f}% of motor work)")
    for x in ax.flat:
        x.grid(True, alpha=0.3)
    for x in (ax[0, 0], ax[0, 1], ax[1, 0]):
        x.legend(fontsize=7)
    fig.suptitle(f"Drivetrain with two {d['bearing']} bearing FMUs (fidelity {d.get('fidelity', 'dynamic')}), SSP run by "
                 f"{' and '.join(masters)} (fmpy solid, libcosim dashed), "
                 f"h = {h:g} s")
    fig.tight_layout()
    fig.savefig(out / "drivetrain.png", dpi=110)
    for m in R:
        print(m, json.dumps(summary[m], indent=1))
    if "agreement_rel" in summary:
        print("agreement", json.dumps(summary["agreement_rel"], indent=1))
    print(f"wrote {out}/drivetrain.png, summary.json")


if __name__ == "__main__":
    main()
