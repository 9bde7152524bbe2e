"""Run the drivetrain SSP with fmpy and with libcosim, check the energy balance, compare, plot.

    python ssp_examples/drivetrain/run.py [--ssp SSP] [--masters fmpy,libcosim] [--stop-time T]
                                          [--out out/ssp_drivetrain]

Builds the FMUs and the SSPs first if the archive is missing. Writes results_<master>.npz, drivetrain.png
(run-up, torques, bearing losses, energy) and summary.json; for a drive cycle (build/drivetrain_cycle_*.ssp)
also phases_<master>.csv (per phase: speeds, loads, torques, heat) and a plot of the cycle
(speed, loads and reactions, friction torque and heat of both bearings, energy).
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
    e["coupling_lag_estimate_J"] = coupling_lag(r, h, design)
    e["residual_after_lag_rel"] = (e["residual_J"] - e["coupling_lag_estimate_J"]) / e["motor_work_J"]
    return e


def coupling_lag(r, h, design):
    """First-order estimate [J] of the energy residual that the explicit (Jacobi) coupling itself makes: every
    torque reaches the shaft one step after its source computed it at the speed it was given, so each change dT
    of a torque shifts h w dT between the source's work and the shaft's, and a torque held over a step meets the
    shaft's mean speed rather than the step's start speed, -(J h / 2) a^2 h per step. Both vanish as h -> 0 and
    are computed from the recorded torques, speed and acceleration (row i holds the values at the end of step
    i; the components computed it with the speed of row i - 1)."""
    w = r["shaft.shaft_speed"]
    w_in = np.concatenate([[design["speed0"]], w[:-1]])
    net = r["motor.torque"] - r["load.torque"] - r["bearing_A.friction_torque"] - r["bearing_B.friction_torque"]
    d_net = np.diff(np.concatenate([net[:1], net]))
    a = r["shaft.shaft_accel"]
    return float(h * np.sum(d_net * w_in) - 0.5 * design["inertia"] * h * h * np.sum(a * a))


def load_tracking(r):
    """Largest relative deviation of each bearing's reaction from minus the load the duty cycle commanded (the
    bearing sees the duty cycle's output one step later: reaction row i against load row i - 1)."""
    out = {}
    for b in "AB":
        for k in ("Fx", "Fz"):
            cmd = r[f"duty.{k}_{b}"][:-1]
            out[f"{k}_{b}"] = float(np.max(np.abs(r[f"bearing_{b}.reaction_{k}"][1:] + cmd) / np.abs(cmd)))
    return out


def phase_table(r, h, design):
    """Per phase of the duty cycle in force: start and end time [s], shaft speed at its start and end and mean
    [rpm], mean motor and fan torque [N.m], commanded loads [N], mean friction torque [N.m] and heat [W] of each
    bearing."""
    names = [p["name"] for p in design["duty_cycle"]]
    t, ph, w = r["time"], r["duty.phase"], r["shaft.shaft_speed"] * RPM
    # the bearings' and shaft's row i ran with the duty cycle's row i - 1
    ph_in = np.concatenate([ph[:1], ph[:-1]])
    rows = []
    for k in sorted({int(round(x)) for x in ph_in}):
        m = np.round(ph_in) == k
        i = np.flatnonzero(m)
        row = {"phase": k, "name": names[k - 1], "t_start_s": float(t[i[0]] - h), "t_end_s": float(t[i[-1]]),
               "speed_start_rpm": float(w[i[0] - 1] if i[0] > 0 else design["speed0"] * RPM),
               "speed_end_rpm": float(w[i[-1]]), "speed_mean_rpm": float(w[m].mean()),
               "motor_torque_Nm": float(r["motor.torque"][m].mean()),
               "fan_torque_Nm": float(r["load.torque"][m].mean())}
        for b in "AB":
            row[f"Fx_{b}_N"] = float(r[f"duty.Fx_{b}"][i[-1] - 1] if i[-1] > 0 else r[f"duty.Fx_{b}"][0])
            row[f"Fz_{b}_N"] = float(r[f"duty.Fz_{b}"][i[-1] - 1] if i[-1] > 0 else r[f"duty.Fz_{b}"][0])
            row[f"friction_torque_{b}_Nm"] = float(r[f"bearing_{b}.friction_torque"][m].mean())
            row[f"heat_{b}_W"] = float(r[f"bearing_{b}.heat_flux_total"][m].mean())
        rows.append(row)
    return rows


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
                    help="comma list (the drives at fidelity 'map' or 'quasi-static', build/drivetrain_map.ssp and "
                         "build/drivetrain_cycle_*.ssp, run with libcosim only: "
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
        if d.get("duty_cycle"):
            rows = phase_table(r, h, d)
            summary[m]["phases"] = rows
            summary[m]["reaction_vs_load_max_rel"] = load_tracking(r)
            summary[m]["min_speed_after_run_up_rpm"] = float(w[t >= d["duty_cycle"][1]["time"]
                                                              + d["duty_cycle"][1]["ramp"]].min() * RPM)
            with open(out / f"phases_{m}.csv", "w") as f:
                f.write(",".join(rows[0]) + "\n")
                for row in rows:
                    f.write(",".join(f"{v:.6g}" if isinstance(v, float) else str(v) for v in row.values()) + "\n")
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
    if d.get("duty_cycle"):
        plot_cycle(R, summary, d, h, out / "drivetrain_cycle.png")
    for m in R:
        print(m, json.dumps(summary[m], indent=1))
    if "agreement_rel" in summary:
        print("agreement", json.dumps(summary["agreement_rel"], indent=1))
    print(f"wrote {out}/drivetrain.png, summary.json" + (", drivetrain_cycle.png, phases_*.csv"
                                                          if d.get("duty_cycle") else ""))


def plot_cycle(R, summary, d, h, path):
    """The drive cycle over time: speed and supply frequency, commanded loads and the bearings' reactions,
    friction torque and heat of both bearings (50 ms means), motor and fan torque, energy per phase."""
    import matplotlib.pyplot as plt
    m = "libcosim" if "libcosim" in R else next(iter(R))
    r = R[m]
    t = r["time"]
    n = int(round(0.05 / h))
    fig, ax = plt.subplots(3, 2, figsize=(14, 11), sharex=True)
    ax[0, 0].plot(t, r["shaft.shaft_speed"] * RPM, color="k", label="shaft")
    for b, col in (("A", "C0"), ("B", "C1")):
        ax[0, 0].plot(t, r[f"bearing_{b}.cage_speed"] * RPM, color=col, lw=0.8, label=f"cage {b}")
    if d["fidelity"] == "map":
        ax[0, 0].axhline(500.0, color="r", lw=0.7, ls=":", label="lowest shaft speed of the map, 500 rpm")
    tw = ax[0, 0].twinx()
    tw.plot(t, r["duty.frequency_ratio"] * 50.0, color="C3", lw=0.8, ls="--")
    tw.set_ylabel("supply frequency [Hz] (dashed, 50 Hz rated)", color="C3")
    for b, col in (("A", "C0"), ("B", "C1")):
        for k, ls in (("Fx", "-"), ("Fz", "--")):
            ax[0, 1].plot(t, r[f"duty.{k}_{b}"] / 1e3, ls, color=col, lw=1.5, alpha=0.5, label=f"{k} {b} commanded")
            ax[0, 1].plot(t, -r[f"bearing_{b}.reaction_{k}"] / 1e3, ls, color=col, lw=0.7,
                          label=f"-reaction {k} {b}")
    ax[1, 0].plot(t, r["motor.torque"], color="C3", label="motor")
    ax[1, 0].plot(t, r["load.torque"], color="C2", label="fan")
    for b, col in (("A", "C0"), ("B", "C1")):
        ax[1, 1].plot(t, smooth(r[f"bearing_{b}.friction_torque"], n), color=col, label=f"bearing {b}")
        ax[2, 0].plot(t, smooth(r[f"bearing_{b}.heat_flux_total"], n), color=col, label=f"bearing {b}")
    rows = summary[m]["phases"]
    for x in ax.flat[:5]:
        for row in rows[1:]:
            x.axvline(row["t_start_s"], color="0.6", lw=0.6)
    for row in rows:
        ax[0, 1].text(0.5 * (row["t_start_s"] + row["t_end_s"]), 1.02, row["name"], fontsize=8, ha="center",
                      va="bottom", transform=ax[0, 1].get_xaxis_transform())
    e = summary[m]["energy"]
    names = ["motor work", "fan work", "bearing heat", "kinetic energy", "residual"]
    vals = [e["motor_work_J"] / 1e3, e["load_work_J"] / 1e3, e["bearing_losses_J"] / 1e3,
            e["kinetic_energy_change_J"] / 1e3, e["residual_J"] / 1e3]
    ea = fig.add_subplot(3, 2, 6)
    ax[2, 1].set_visible(False)
    ea.bar(names, vals, color=["C3", "C2", "C4", "C0", "k"])
    for i, v in enumerate(vals):
        ea.text(i, v, f"{v:.2f} kJ", ha="center", va="bottom", fontsize=8)
    ea.set(ylabel="energy [kJ]", title=f"energy over the cycle: residual {100 * e['residual_rel']:.3f}% of the motor "
           f"work\n({100 * e['residual_after_lag_rel']:.3f}% after the coupling lag estimate)")
    ax[0, 0].set(ylabel="speed [rpm]", title="shaft and cage speeds")
    ax[0, 1].set(ylabel="load [kN]", title="loads: commanded (thick) and bearing reactions (thin)\n")
    ax[1, 0].set(ylabel="torque [N.m]", title="motor and fan torque")
    ax[1, 1].set(ylabel="friction torque [N.m] (50 ms mean)", title="bearing friction torque")
    ax[2, 0].set(xlabel="time [s]", ylabel="heat flux [W] (50 ms mean)", title="bearing heat")
    for x in list(ax.flat[:5]) + [ea]:
        x.grid(True, alpha=0.3)
    for x in ax.flat[:5]:
        x.legend(fontsize=7, loc="lower center" if x is ax[0, 0] else "upper right")
    ax[1, 1].tick_params(labelbottom=True)
    ax[1, 1].set_xlabel("time [s]")
    fig.suptitle(f"Drive cycle: induction motor, fan, two {d['bearing']} bearings at fidelity {d['fidelity']} "
                 f"({m}, h = {h:g} s)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()
