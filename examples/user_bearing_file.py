"""A user bearing file: your own bearing from a JSON file (docs/bearing_files.md), solved quasi-statically over a
speed range, next to the preset it was made from (the 7218B with a 25 deg instead of a 39.9 deg contact angle).

    python examples/user_bearing_file.py [--bearing examples/my_7218_25deg.json] [--points 13] [--out out/examples]

Contact angles, cage speed and axial stiffness against speed under Fx = 1 kN, Fz = 3 kN. Writes
user_bearing.png to --out.
"""
from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

import bearing_core as bc  # noqa: E402

LOADS = (1000.0, 0.0, 3000.0, 0.0, 0.0)     # Fx, Fy, Fz [N], Mx, My [N m]


def sweep(bearing, speeds_rpm):
    g = bc.load_bearing(bearing)
    rows = []
    for n in speeds_rpm:
        r = bc.solve_quasistatic(g, n * math.pi / 30, LOADS, control="outer")
        loaded = np.asarray(r.Q_i) > 0
        rows.append((n, math.degrees(np.mean(np.asarray(r.alpha_i)[loaded])),
                     math.degrees(np.mean(np.asarray(r.alpha_o)[loaded])),
                     float(np.mean(np.asarray(r.omega_m)[loaded])) * 30 / math.pi, r.stiffness[2, 2]))
    return g, np.array(rows)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bearing", default=str(HERE / "my_7218_25deg.json"), help="bearing file (or preset, designation)")
    ap.add_argument("--compare", default="7218B", help="a second bearing drawn beside it")
    ap.add_argument("--points", type=int, default=13)
    ap.add_argument("--out", default="out/examples")
    a = ap.parse_args(argv)
    speeds = np.linspace(1000, 13000, a.points)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(14, 4))
    for b, ls in ((a.bearing, "-"), (a.compare, "--")):
        g, r = sweep(b, speeds)
        label = Path(b).name if b.endswith(".json") else b
        ax[0].plot(r[:, 0], r[:, 1], ls, color="C0", label=f"inner, {label}")
        ax[0].plot(r[:, 0], r[:, 2], ls, color="C1", label=f"outer, {label}")
        ax[1].plot(r[:, 0], r[:, 3], ls, label=label)
        ax[2].plot(r[:, 0], r[:, 4] / 1e6, ls, label=label)
        print(f"{label}: {g.Z} balls, at {r[-1, 0]:.0f} rpm alpha_i {r[-1, 1]:.1f} deg, alpha_o {r[-1, 2]:.1f} deg, "
              f"orbital speed {r[-1, 3]:.0f} rpm, axial stiffness {r[-1, 4] / 1e6:.0f} N/um")
    ax[0].set(xlabel="shaft speed [rpm]", ylabel="mean contact angle of the loaded balls [deg]")
    ax[1].set(xlabel="shaft speed [rpm]", ylabel="mean orbital (cage) speed, outer control [rpm]")
    ax[2].set(xlabel="shaft speed [rpm]", ylabel="axial stiffness dFz/dz [N/um]")
    for x in ax:
        x.grid(alpha=0.3)
        x.legend(fontsize=8)
    fig.suptitle("Quasi-static model, Fx = 1 kN, Fz = 3 kN: a user bearing file (solid) and a preset (dashed)")
    fig.tight_layout()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "user_bearing.png", dpi=100)
    print(f"wrote {out / 'user_bearing.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
