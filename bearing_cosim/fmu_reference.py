"""Reference results of the bearing FMU, laid out as the FMI cross-check rules ask (modelica/fmi-cross-check:
<id>_in.csv input signals, <id>_ref.opt experiment options, <id>_ref.csv results, first column "time"):

    python -m bearing_cosim.fmu_reference FMU OUTDIR      (run by `bearing build-fmu --with-reference`)

The reference experiment is the FMU's default experiment (0 to 1 s, 1 ms communication steps) driven by the
seed 000 acceleration profile (1000 rpm to 0.5 s, then 10,000 rpm/s; bearing_core.models.dynamics.SEED000_PROFILE) with
Fx = 1 kN, Fz = 3 kN held, run by fmpy's simulate_fmu (inputs sampled at each communication point and held over
the step). Also writes <id>_ref.png, a plot of the run. Runs in its own process and leaves with os._exit after
writing (docs/fmu.md: exit of processes that hosted the FMU).
"""
from __future__ import annotations

import csv
import math
import os
import sys
from pathlib import Path

import numpy as np

REF_OUTPUTS = ("cage_speed", "cage_shaft_ratio", "skid_ratio", "friction_torque", "heat_flux_total", "reaction_Fx",
               "reaction_Fz", "ir_x", "ir_z", "max_contact_pressure")
LOADS = {"Fx": 1000.0, "Fz": 3000.0}


def input_signal(start: float, stop: float):
    """The cross-check input table: time [s], shaft_speed [rad/s], Fx, Fz [N] at the profile's corners on
    [start, stop] (linear in between)."""
    from bearing_core.models.dynamics import SEED000_PROFILE
    t, n = (np.array(v, dtype=float) for v in zip(*SEED000_PROFILE))
    tt = np.unique(np.concatenate(([start, stop], t[(t > start) & (t < stop)])))
    w = np.interp(tt, t, n) * math.pi / 30.0
    return np.array(list(zip(tt, w, *[np.full_like(tt, v) for v in LOADS.values()])),
                    dtype=[("time", float), ("shaft_speed", float)] + [(k, float) for k in LOADS])


def write_csv(path: Path, arr, names):
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, quoting=csv.QUOTE_NONNUMERIC)
        w.writerow(names)
        for row in arr:
            w.writerow([float(row[k]) for k in names])


def reference(fmu: str, outdir: str) -> dict:
    import fmpy
    from fmpy import read_model_description
    md = read_model_description(fmu)
    mid = md.coSimulation.modelIdentifier
    de = md.defaultExperiment
    start, stop, h = float(de.startTime), float(de.stopTime), float(de.stepSize)
    tol = float(de.tolerance) if de.tolerance else 1e-4
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    sig = input_signal(start, stop)
    write_csv(out / f"{mid}_in.csv", sig, sig.dtype.names)
    (out / f"{mid}_ref.opt").write_text(f"StartTime, {start!r}\nStopTime, {stop!r}\nStepSize, {h!r}\n"
                                        f"RelTol, {tol!r}\n")
    res = simulate_reference(fmu, out / f"{mid}_in.csv", out / f"{mid}_ref.opt")
    write_csv(out / f"{mid}_ref.csv", res, ("time",) + REF_OUTPUTS)
    plot(res, out / f"{mid}_ref.png", mid)
    return {"in": out / f"{mid}_in.csv", "opt": out / f"{mid}_ref.opt", "ref": out / f"{mid}_ref.csv",
            "png": out / f"{mid}_ref.png"}


def read_opt(path) -> dict:
    return {k.strip(): float(v) for k, v in (ln.split(",", 1) for ln in Path(path).read_text().splitlines() if ln)}


def simulate_reference(fmu, in_csv, opt):
    """Run the cross-check experiment (in_csv, opt) with fmpy; returns the structured result array."""
    import fmpy
    from fmpy.util import read_csv
    o = read_opt(opt)
    return fmpy.simulate_fmu(str(fmu), start_time=o["StartTime"], stop_time=o["StopTime"], step_size=o["StepSize"],
                             output_interval=o["StepSize"], input=read_csv(str(in_csv)), output=list(REF_OUTPUTS))


def plot(res, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(3, 1, figsize=(7, 7), sharex=True)
    t = res["time"]
    ax[0].plot(t, res["cage_speed"] * 30 / math.pi, label="cage speed")
    ax[0].set_ylabel("cage speed [rpm]")
    ax[1].plot(t, res["cage_shaft_ratio"], label="cage / shaft speed")
    ax[1].set_ylabel("cage / shaft speed [-]")
    ax[2].plot(t, res["friction_torque"], label="friction torque")
    ax[2].set_ylabel("friction torque [N.m]")
    ax[2].set_xlabel("time [s]")
    fig.suptitle(f"{title}: default experiment, seed 000 acceleration profile, Fx 1 kN, Fz 3 kN")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


if __name__ == "__main__":
    files = reference(sys.argv[1], sys.argv[2])
    print("wrote " + ", ".join(str(p) for p in files.values()))
    sys.stdout.flush()
    os._exit(0)
