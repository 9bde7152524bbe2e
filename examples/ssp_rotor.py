"""The rotor SSP system, short: a Jeffcott rotor on two 7218B bearing FMUs (ssp_examples/rotor_bearings/, the SSP
archive generated here) run by fmpy's or libcosim's SSP master for a short time from its static equilibrium.

    python examples/ssp_rotor.py [--master fmpy|libcosim] [--stop-time 0.05] [--out out/examples]

Builds BearingFMU and the rotor's helper FMUs into --out/fmus, writes --out/rotor_bearings.ssp, runs it
(1e-4 s steps, every instance's model in a process of its own) and draws the disk whirl, the cage speeds and the
bearings' reactions: ssp_rotor.png. The whole 2.2 s run-up with both masters: ssp_examples/README.md.
"""
from __future__ import annotations

import argparse
import importlib.util
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SSP = ROOT / "ssp_examples"
for p in (str(ROOT), str(SSP)):
    if p not in sys.path:
        sys.path.insert(0, p)

RPM = 30 / math.pi


def build(out: Path) -> Path:
    import build_examples as be
    from bearing_cosim import fmu_build
    fmus = out / "fmus"
    fmus.mkdir(parents=True, exist_ok=True)
    fmu_build.build(fmus)
    for s in be.HELPERS["rotor_bearings"]:
        src = (SSP / "rotor_bearings" / "fmus" / s).read_text()
        fmu_build._build(be.slave_class(src), {Path(s).stem: src}, Path(s).stem, fmus)
    spec = importlib.util.spec_from_file_location("rotor_make_ssp", SSP / "rotor_bearings" / "make_ssp.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod.make(out / "rotor_bearings.ssp", fmu_dir=fmus)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--master", default="libcosim", choices=("fmpy", "libcosim"))
    ap.add_argument("--stop-time", type=float, default=0.05)
    ap.add_argument("--out", default="out/examples")
    a = ap.parse_args(argv)
    out = Path(a.out).resolve()
    ssp = build(out)
    from masters import run_subprocess
    summary, r, _ = run_subprocess(a.master, ssp, out / f"ssp_rotor_{a.master}.npz", a.stop_time)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    t = r["time"]
    fig, ax = plt.subplots(1, 3, figsize=(14, 4))
    ax[0].plot(t, r["rotor.disk_whirl"] * 1e6)
    ax[0].set(xlabel="time [s]", ylabel="disk whirl radius [um]")
    for b, col in (("A", "C0"), ("B", "C1")):
        ax[1].plot(t, r[f"bearing_{b}.cage_speed"] * RPM, color=col, label=f"cage {b}")
        ax[2].plot(t, r[f"bearing_{b}.reaction_Fy"], color=col, label=f"{b} Fy")
        ax[2].plot(t, r[f"bearing_{b}.reaction_Fz"], "--", color=col, label=f"{b} Fz")
    ax[1].plot(t, r["speed.shaft_speed"] * RPM, "k--", lw=0.8, label="shaft")
    ax[1].set(xlabel="time [s]", ylabel="speed [rpm]")
    ax[2].set(xlabel="time [s]", ylabel="reaction [N] (bearing frame)")
    for x in ax:
        x.grid(alpha=0.3)
    ax[1].legend(fontsize=8)
    ax[2].legend(fontsize=8)
    fig.suptitle(f"Jeffcott rotor on two 7218B bearing FMUs, SSP run by {a.master}, first {t[-1]:.3f} s "
                 f"({summary['samples']} steps in {summary['wall_s']:.1f} s wall)")
    fig.tight_layout()
    fig.savefig(out / "ssp_rotor.png", dpi=100)
    print(f"{a.master}: {summary['samples']} steps to {summary['t_end']:.3f} s in {summary['wall_s']:.1f} s; cage A "
          f"{r['bearing_A.cage_speed'][-1] * RPM:.0f} rpm, reaction A Fy {r['bearing_A.reaction_Fy'][-1]:.0f} N; "
          f"wrote {out / 'ssp_rotor.png'}")
    return 0


if __name__ == "__main__":
    import scipy.linalg  # noqa: F401  (before numba, as ssp_examples/build_examples.py)
    sys.exit(main())
