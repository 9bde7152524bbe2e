"""An operating map built and used: `bearing build-map` on a small grid, the map FMU in C built from it
(`bearing build-map-fmu`), and that FMU driven through a speed ramp by fmpy.

    python examples/map_build_and_use.py [--level tribological] [--out out/examples]

The grid is 2 x 2 x 2 (speed 1000 and 3000 rpm, Fx 0 and 1 kN, Fz 2 and 4 kN). The default level,
tribological (the quasi-static tribological model: free balls, centred cage), takes about 10 s once the kernels
are compiled; --level dynamic holds the dynamic model at each point until steady (minutes). The map is never
extrapolated: the profile stays inside the grid. Writes map_7218B.nc, BearingMapFMU.fmu and map_fmu.png to --out.
"""
from __future__ import annotations

import argparse
import math
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
RPM = math.pi / 30
GRID = ["speed_rpm=1000,3000", "fx_N=0,1000", "fz_N=2000,4000"]


def build_map(out: Path, level: str) -> Path:
    nc = out / "map_7218B.nc"
    cmd = [sys.executable, "-m", "bearing_cosim.cli", "build-map", "--bearing", "7218B", "--level", level,
           "--workers", "1", "--no-progress", "--no-cache", "--out", str(nc)]
    for g in GRID:
        cmd += ["--grid", g]
    subprocess.run(cmd, check=True, cwd=ROOT)
    return nc


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--level", default="tribological", choices=("tribological", "dynamic"))
    ap.add_argument("--out", default="out/examples")
    a = ap.parse_args(argv)
    out = Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    nc = build_map(out, a.level)
    sys.path.insert(0, str(ROOT))
    from bearing_cosim.map_fmu import build_map_fmu
    fmu = build_map_fmu(nc, out, ["linux64"])

    from fmpy import simulate_fmu
    # 1200 rpm to 2800 rpm from 0.2 to 0.6 s; Fx 500 N, Fz 3000 N (inside the grid)
    speed = np.array([(0.0, 1200 * RPM), (0.2, 1200 * RPM), (0.6, 2800 * RPM), (1.0, 2800 * RPM)],
                     dtype=[("time", float), ("shaft_speed", float)])
    res = simulate_fmu(str(fmu), stop_time=1.0, step_size=1e-3, input=speed,
                       start_values={"shaft_speed": 1200 * RPM, "Fx": 500.0, "Fz": 3000.0},
                       output=["cage_speed", "friction_torque", "heat_flux_total"])

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    t = res["time"]
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    ax[0].plot(speed["time"], speed["shaft_speed"] / RPM, "k--", lw=0.8, label="shaft")
    ax[0].plot(t, res["cage_speed"] / RPM, label="cage (first-order lag towards the map)")
    ax[0].set(xlabel="time [s]", ylabel="speed [rpm]")
    ax[1].plot(t, res["friction_torque"], label="friction torque [N m]")
    ax[1].plot(t, res["heat_flux_total"] / 100, label="heat [100 W]")
    ax[1].set(xlabel="time [s]")
    for x in ax:
        x.grid(alpha=0.3)
        x.legend(fontsize=8)
    fig.suptitle(f"BearingMapFMU (C) from a 2x2x2 {a.level} map of the 7218B, Fx 500 N, Fz 3 kN, in fmpy")
    fig.tight_layout()
    fig.savefig(out / "map_fmu.png", dpi=100)
    print(f"map {nc.name}, {fmu.name}: cage {res['cage_speed'][-1] / RPM:.0f} rpm, friction torque "
          f"{res['friction_torque'][-1]:.3f} N m at 2800 rpm; wrote {out / 'map_fmu.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
