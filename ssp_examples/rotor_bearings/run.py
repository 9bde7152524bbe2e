"""Run the rotor-bearing SSP with fmpy and with libcosim, compare, plot.

    python ssp_examples/rotor_bearings/run.py [--stop-time T] [--out out/ssp_rotor_bearings]

Builds the FMUs and the SSP first if ssp_examples/build/rotor_bearings.ssp is missing. Writes
results_<master>.npz, rotor_bearings.png (unbalance response vs speed with the steady-state Jeffcott curve, cage
speeds of both bearings, reactions) and summary.json.
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


def envelope(speed, whirl, bin_rpm=25.0):
    """Largest whirl radius in each speed bin: the unbalance response amplitude vs speed."""
    rpm = speed * RPM
    edges = np.arange(rpm.min(), rpm.max() + bin_rpm, bin_rpm)
    idx = np.digitize(rpm, edges)
    c, a = [], []
    for k in np.unique(idx):
        m = idx == k
        c.append(rpm[m].mean()); a.append(whirl[m].max())
    return np.array(c), np.array(a)


def steady_response(meta, rpm):
    """Steady-state unbalance response of the Jeffcott disk (supports with the bearings' quasi-static
    stiffness in series): a = e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2)."""
    d = meta["design"]
    a, L = d["disk_position"], d["span"]
    b = L - a
    kA, kB = meta["k_A"][1], meta["k_B"][1]
    k = 1.0 / (1.0 / meta["shaft_stiffness"] + (b / L) ** 2 / kA + (a / L) ** 2 / kB)
    m = d["disk_mass"]
    wn = math.sqrt(k / m)
    zeta = meta["disk_damping"] / (2 * math.sqrt(k * m))
    r = np.asarray(rpm) / RPM / wn
    return d["unbalance_eccentricity"] * r * r / np.sqrt((1 - r * r) ** 2 + (2 * zeta * r) ** 2), wn, zeta


def compare(R, t0):
    """fmpy vs libcosim: means over t >= t0 of cage speeds and reactions, relative differences."""
    out = {}
    for key in ("bearing_A.cage_speed", "bearing_B.cage_speed", "bearing_A.reaction_Fy", "bearing_B.reaction_Fy",
                "bearing_A.reaction_Fz", "bearing_B.reaction_Fz"):
        mf = float(R["fmpy"][key][R["fmpy"]["time"] >= t0].mean())
        ml = float(R["libcosim"][key][R["libcosim"]["time"] >= t0].mean())
        out[key] = {"fmpy": mf, "libcosim": ml, "rel_diff": abs(mf - ml) / max(abs(mf), abs(ml), 1e-12)}
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ssp", default=str(SSP_DIR / "build" / "rotor_bearings.ssp"))
    ap.add_argument("--stop-time", type=float, default=None)
    ap.add_argument("--out", default=str(ROOT / "out" / "ssp_rotor_bearings"))
    ap.add_argument("--masters", default="fmpy,libcosim",
                    help="comma-separated; fmpy holds every connected input at 0 in the first step, which a steady "
                         "fidelity level refuses (a shaft speed of 0): libcosim only there")
    a = ap.parse_args(argv)
    masters = tuple(m.strip() for m in a.masters.split(",") if m.strip())
    ssp = Path(a.ssp)
    if not ssp.exists():
        import subprocess
        subprocess.run([sys.executable, str(SSP_DIR / "build_examples.py")], check=True)
    meta = json.loads(Path(str(ssp) + ".json").read_text())
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    R, S = {}, {}
    for master in masters:
        print(f"running {ssp.name} with {master} ...", flush=True)
        S[master], R[master], _ = run_subprocess(master, ssp, out / f"results_{master}.npz", a.stop_time,
                                                 env=dict(os.environ))
        print(f"  {S[master]['samples']} steps to {S[master]['t_end']:.3f} s in {S[master]['wall_s']:.1f} s wall")

    d = meta["design"]
    W = d["disk_mass"] * d["gravity"]
    summary = {"ssp": str(ssp), "step_s": d["step"], "masters": S, "static": {
        "weight_N": W, "reaction_A_Fy_N": meta["reaction_A"][1], "reaction_B_Fy_N": meta["reaction_B"][1],
        "reaction_A_Fz_N": meta["reaction_A"][2], "reaction_B_Fz_N": meta["reaction_B"][2],
        "preload_displacement_m": meta["delta"]}}
    # steady window before the ramp: reactions vs statics
    for m, r in R.items():
        win = (r["time"] > 0.005) & (r["time"] <= d["ramp_start"])
        summary[m] = {"mean_before_ramp": {k: float(r[k][win].mean()) for k in
                                           ("bearing_A.reaction_Fy", "bearing_B.reaction_Fy",
                                            "bearing_A.reaction_Fz", "bearing_B.reaction_Fz")}}
        speed = r["speed.shaft_speed"]
        c, env = envelope(speed, r["rotor.disk_whirl"])
        k = int(np.argmax(env))
        summary[m]["peak_whirl_m"] = float(env[k])
        summary[m]["peak_speed_rpm"] = float(c[k])
        summary[m]["final_cage_speed_rpm"] = {b: float(r[f"bearing_{b}.cage_speed"][-1] * RPM) for b in "AB"}
        summary[m]["final_shaft_speed_rpm"] = float(speed[-1] * RPM)
        summary[m]["max_contact_pressure_GPa"] = float(max(r["bearing_A.max_contact_pressure"].max(),
                                                           r["bearing_B.max_contact_pressure"].max()) / 1e9)
    _, wn, zeta = steady_response(meta, [0.0])
    summary["jeffcott"] = {"natural_frequency_rpm": wn * RPM, "damping_ratio": zeta,
                           "steady_peak_m": d["unbalance_eccentricity"] / (2 * zeta)}
    if len(R) == 2:
        summary["agreement"] = compare(R, 0.01)
    (out / "summary.json").write_text(json.dumps(summary, indent=1))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 2, figsize=(13, 9))
    for m, ls in (("fmpy", "-"), ("libcosim", "--")):
        if m not in R:
            continue
        r = R[m]
        c, env = envelope(r["speed.shaft_speed"], r["rotor.disk_whirl"])
        ax[0, 0].plot(c, env * 1e6, ls, label=f"run-up ({m})")
        t = r["time"]
        for b, col in (("A", "C0"), ("B", "C1")):
            ax[0, 1].plot(t, r[f"bearing_{b}.cage_speed"] * RPM, ls, color=col, lw=0.8, label=f"cage {b} ({m})")
            ax[1, 0].plot(t, r[f"bearing_{b}.reaction_Fy"], ls, color=col, lw=0.6, label=f"{b} Fy ({m})")
            ax[1, 1].plot(t, r[f"bearing_{b}.reaction_Fz"], ls, color=col, lw=0.6, label=f"{b} Fz ({m})")
    r = R[masters[0]]
    for b, col in (("A", "C0"), ("B", "C1")):
        ax[0, 1].plot(r["time"], r[f"bearing_{b}.cage_shaft_ratio_theory"] * r["speed.shaft_speed"] * RPM, ":",
                      color=col, lw=1.0, label=f"pure rolling {b}")
    rpm = np.linspace(c.min(), c.max(), 400)
    ax[0, 0].plot(rpm, steady_response(meta, rpm)[0] * 1e6, "k:", label="steady state (Jeffcott, same damping)")
    ax[0, 0].set(xlabel="shaft speed [rpm]", ylabel="disk whirl radius [um]", title="unbalance response in the run-up")
    ax[0, 1].set(xlabel="time [s]", ylabel="cage speed [rpm]", title="cage speeds")
    ax[1, 0].set(xlabel="time [s]", ylabel="reaction Fy [N] (bearing frame)", title="radial reactions (static: "
                 f"A {meta['reaction_A'][1]:.0f} N, B {meta['reaction_B'][1]:.0f} N)")
    ax[1, 1].set(xlabel="time [s]", ylabel="reaction Fz [N] (bearing frame)", title="axial reactions")
    for x in ax.flat:
        x.grid(True, alpha=0.3); x.legend(fontsize=7)
    fig.suptitle(f"Jeffcott rotor on two {d['bearing']} bearing FMUs (fidelity {d.get('fidelity', 'dynamic')}), SSP "
                 f"run by {' and '.join(masters)} (fmpy solid, libcosim dashed), h = {d['step']:g} s")
    fig.tight_layout()
    fig.savefig(out / "rotor_bearings.png", dpi=110)
    print(json.dumps({k: summary[k] for k in ("jeffcott", "agreement") if k in summary}, indent=1))
    for m in R:
        print(m, json.dumps(summary[m]))
    print(f"wrote {out}/rotor_bearings.png, summary.json")


if __name__ == "__main__":
    main()
