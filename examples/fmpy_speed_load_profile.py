"""A custom speed and load profile through fmpy: the bearing FMU (BearingFMU, fidelity dynamic) driven by a
table of shaft speed and loads over time.

    python examples/fmpy_speed_load_profile.py [--fmu dist/BearingFMU.fmu] [--stop-time 0.4] [--out out/examples]

The profile: 2000 rpm held, a ramp to 4000 rpm from 0.1 to 0.3 s, the axial load stepped from 3 to 4 kN at 0.2 s
(Fx = 1 kN throughout). fmpy interpolates the table linearly between its rows (a step is two rows at one time).
Builds the FMU into a temporary folder when --fmu is not given. Writes profile.png and profile.csv to --out.
"""
from __future__ import annotations

import argparse
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
RPM = math.pi / 30      # rpm -> rad/s

#           time [s]  speed [rpm]  Fx [N]   Fz [N]
PROFILE = [(0.00, 2000.0, 1000.0, 3000.0),
           (0.10, 2000.0, 1000.0, 3000.0),
           (0.20, 3000.0, 1000.0, 3000.0),
           (0.20, 3000.0, 1000.0, 4000.0),
           (0.30, 4000.0, 1000.0, 4000.0),
           (1.00, 4000.0, 1000.0, 4000.0)]
OUTPUTS = ["cage_speed", "cage_speed_pure_rolling_outer", "friction_torque", "heat_flux_total", "reaction_Fz",
           "skid_ratio"]


def run(fmu: Path, stop_time: float, step: float = 1e-3) -> np.ndarray:
    from fmpy import simulate_fmu
    signals = np.array([(t, n * RPM, fx, fz) for t, n, fx, fz in PROFILE],
                       dtype=[("time", float), ("shaft_speed", float), ("Fx", float), ("Fz", float)])
    return simulate_fmu(str(fmu), stop_time=stop_time, step_size=step, input=signals, output=OUTPUTS,
                        start_values={"bearing": "7218B", "fidelity": "dynamic", "shaft_speed": PROFILE[0][1] * RPM,
                                      "Fx": PROFILE[0][2], "Fz": PROFILE[0][3]})


def plot(res, out: Path) -> Path:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    t = res["time"]
    prof = np.array(PROFILE)
    fig, ax = plt.subplots(1, 3, figsize=(14, 4))
    ax[0].plot(prof[:, 0], prof[:, 1], "k--", lw=0.8, label="shaft (profile)")
    ax[0].plot(t, res["cage_speed"] / RPM, label="cage")
    ax[0].plot(t, res["cage_speed_pure_rolling_outer"] / RPM, ":", label="cage, pure rolling (outer control)")
    ax[0].set(xlabel="time [s]", ylabel="speed [rpm]")
    ax[1].plot(t, res["friction_torque"], label="friction torque [N m]")
    ax[1].plot(t, res["heat_flux_total"] / 100, label="heat [100 W]")
    ax[1].set(xlabel="time [s]")
    ax[2].plot(prof[:, 0], prof[:, 3], "k--", lw=0.8, label="Fz (profile)")
    ax[2].plot(t, -res["reaction_Fz"], label="-reaction Fz")
    ax[2].set(xlabel="time [s]", ylabel="axial force [N]")
    for a in ax:
        a.set_xlim(0, t[-1])
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.suptitle("7218B through a speed and load profile (BearingFMU in fmpy, fidelity dynamic, 1 ms steps)")
    fig.tight_layout()
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "profile.png", dpi=100)
    np.savetxt(out / "profile.csv", np.column_stack([res[k] for k in ["time"] + OUTPUTS]), delimiter=",",
               header=",".join(["time"] + OUTPUTS), comments="")
    return out / "profile.png"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fmu", default=None, help="BearingFMU.fmu (default: build one into a temporary folder)")
    ap.add_argument("--stop-time", type=float, default=0.4)
    ap.add_argument("--out", default="out/examples")
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as td:
        fmu = Path(a.fmu) if a.fmu else _build(td)
        res = run(fmu, a.stop_time)
    png = plot(res, Path(a.out))
    print(f"cage {res['cage_speed'][-1] / RPM:.0f} rpm, friction torque {res['friction_torque'][-1]:.3f} N m at "
          f"{res['time'][-1]:.3f} s; wrote {png}")
    return 0


def _build(dest) -> Path:
    sys.path.insert(0, str(ROOT))
    from bearing_cosim.fmu_build import build
    return build(dest)


if __name__ == "__main__":
    sys.exit(main())
