"""Generate the rotor-bearing SSP: a Jeffcott rotor (JeffcottRotor.fmu) on two 7218B bearing FMUs in
displacement-driven coupling, driven by a run-up speed profile (SpeedRamp.fmu).

    python ssp_examples/rotor_bearings/make_ssp.py [--out ssp_examples/build/rotor_bearings.ssp]

The FMUs come from ssp_examples/build/fmus (python ssp_examples/build_examples.py builds them). The static
equilibrium of the system (journal positions, disk sag) and the bearings' stiffness at it are solved here with
bearing_core's quasi-static model, and written into the SSD as start values (rotor parameters, bearing inputs)
and as the rotor's interface stiffness estimates.
"""
from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass, asdict
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(HERE.parent))

import scipy.linalg  # noqa: E402,F401  (before numba: docs/fmu.md)
from sspgen import Component, enumeration_value, ssd_xml, write_ssp  # noqa: E402

MIRROR = np.array([1.0, 1.0, -1.0, -1.0, -1.0])
BEARING_OUT = [("reaction_Fx", "N"), ("reaction_Fy", "N"), ("reaction_Fz", "N"), ("reaction_Mx", "N.m"),
               ("reaction_My", "N.m"), ("cage_speed", "rad/s"), ("cage_shaft_ratio_theory", "1"),
               ("friction_torque", "N.m"), ("heat_flux_total", "W"), ("max_contact_pressure", "Pa")]
POSE = ("dx", "dy", "dz", "tx", "ty")
RATE = ("vx", "vy", "vz", "wx", "wy")
REAC = ("Fx", "Fy", "Fz", "Mx", "My")


@dataclass
class RotorDesign:
    bearing: str = "7218B"
    disk_mass: float = 100.0            # kg
    shaft_diameter: float = 0.06        # m (between the journals)
    young: float = 2.1e11               # Pa
    span: float = 1.0                   # m, bearing centre to bearing centre
    disk_position: float = 0.4          # m from bearing A: A carries the larger radial load
    damping_ratio: float = 0.02         # external damping of the disk mode, fraction of critical
    unbalance_eccentricity: float = 20e-6   # m (disk mass eccentricity)
    axial_load: float = 500.0           # N along +z (loads bearing A, unloads bearing B)
    preload_force: float = 1500.0       # N axial preload of each bearing alone (fixed-position preload)
    gravity: float = 9.81
    speed_start: float = 60.0           # rad/s
    speed_end: float = 420.0            # rad/s
    ramp_start: float = 0.05            # s
    ramp_end: float = 2.05              # s
    stop_time: float = 2.2              # s
    step: float = 1e-4                  # s, communication step
    interface_stiffness_factor: float = 2.0   # rotor's interface stiffness / quasi-static bearing stiffness
    fidelity: str = "dynamic"           # the bearings' fidelity level (docs/fidelity.md)

    @property
    def shaft_stiffness(self):
        a, L = self.disk_position, self.span
        b = L - a
        EI = self.young * math.pi * self.shaft_diameter ** 4 / 64.0
        return 3.0 * EI * L / (a * a * b * b)


def _T(L):
    TA = np.zeros((5, 5)); TB = np.zeros((5, 5))
    for T, ix, iy in ((TA, 0, 1), (TB, 2, 3)):
        T[0, ix] = 1.0; T[1, iy] = 1.0; T[2, 4] = 1.0
        T[3, 1] = 1.0 / L; T[3, 3] = -1.0 / L
        T[4, 0] = -1.0 / L; T[4, 2] = 1.0 / L
    return TA, TB


def statics(d: RotorDesign) -> dict:
    """Static equilibrium at speed_start with bearing_core's quasi-static bearing model (same physics as the
    FMU's initialisation): journal coordinates q, disk position, bearing poses and reactions, preload
    displacement, and the bearings' stiffness diagonal at the equilibrium (own frames)."""
    from scipy.optimize import brentq, fsolve
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.models.quasistatic import QuasiStaticModel

    qsm = QuasiStaticModel(load_preset(d.bearing), "outer")
    w = d.speed_start
    F = lambda p: qsm.residual(np.asarray(p, float), w)[0]          # reaction on the shaft, own frame
    delta = brentq(lambda z: -F([0, 0, z, 0, 0])[2] - d.preload_force, 1e-9, 2e-4, xtol=1e-14)
    TA, TB = _T(d.span)
    L, a = d.span, d.disk_position
    bx = np.array([(L - a) / L, 0, a / L, 0, 0]); by = np.array([0, (L - a) / L, 0, a / L, 0])
    ks = d.shaft_stiffness
    c = np.array([0, 0, delta, 0, 0.0])

    def poses(q):
        return TA @ q + c, MIRROR * (TB @ q) + c

    def res(u):
        q, xd, yd = u[:5] * 1e-6, u[5] * 1e-6, u[6] * 1e-6
        pA, pB = poses(q)
        RA, RB = F(pA), MIRROR * F(pB)
        rx, ry = xd - bx @ q, yd - by @ q
        Q = TA.T @ RA + TB.T @ RB + ks * (bx * rx + by * ry) + np.array([0, 0, 0, 0, d.axial_load])
        return np.concatenate([Q, [-ks * rx, -ks * ry - d.disk_mass * d.gravity]]) / 1e3

    u, info, ier, msg = fsolve(res, np.zeros(7), full_output=True, xtol=1e-12)
    if ier != 1 or np.max(np.abs(res(u))) > 1e-6:
        raise RuntimeError(f"no static equilibrium: {msg}")
    q, xd, yd = u[:5] * 1e-6, u[5] * 1e-6, u[6] * 1e-6
    pA, pB = poses(q)
    out = {"q": q, "disk": (xd, yd), "delta": delta, "pose_A": pA, "pose_B": pB,
           "reaction_A": F(pA), "reaction_B": F(pB)}
    for name, p in (("A", pA), ("B", pB)):
        k = []
        for j in range(3):
            e = np.zeros(5); e[j] = 2e-7
            k.append(-(F(p + e)[j] - F(p - e)[j]) / (2 * 2e-7))
        out["k_" + name] = np.array(k)
    return out


QS_RUNUP = RotorDesign(fidelity="quasi-static")
"""The same run-up with both bearings at fidelity 'quasi-static' (the map level takes no displacement coupling)."""


def make(dest, design: RotorDesign | None = None, fmu_dir=None) -> Path:
    d = design or RotorDesign()
    fmu_dir = Path(fmu_dir or HERE.parent / "build" / "fmus")
    bfmu = fmu_dir / "BearingFMU.fmu"
    st = statics(d)
    L = d.span
    ks = d.shaft_stiffness
    c_disk = 2.0 * d.damping_ratio * math.sqrt(ks * d.disk_mass)
    q = st["q"]
    # interface stiffness: twice the quasi-static stiffness (under-relaxed fixed point). Measured with 7218B at
    # h = 1e-4 s: the bearing's reaction one step after a pose step overshoots its static value 1.4x (ball
    # inertia and contact damping), and with the estimate = static stiffness the coupled loop oscillated at
    # ~550 Hz and grew; 1.5x, 2x and 3x are stable and give the same steady result.
    kf = d.interface_stiffness_factor
    rotor_params = [
        ("disk_mass", d.disk_mass, "kg"), ("unbalance_eccentricity", d.unbalance_eccentricity, "m"),
        ("shaft_stiffness", ks, "N/m"), ("disk_damping", c_disk, "N.s/m"), ("span", L, "m"),
        ("disk_position", d.disk_position, "m"), ("gravity", d.gravity, "m/s2"),
        ("axial_load", d.axial_load, "N"), ("preload_A", st["delta"], "m"), ("preload_B", st["delta"], "m"),
        ("A_kxx", kf * st["k_A"][0], "N/m"), ("A_kyy", kf * st["k_A"][1], "N/m"),
        ("A_kzz", kf * st["k_A"][2], "N/m"), ("B_kxx", kf * st["k_B"][0], "N/m"),
        ("B_kyy", kf * st["k_B"][1], "N/m"), ("B_kzz", kf * st["k_B"][2], "N/m"),
        ("x_A0", q[0], "m"), ("y_A0", q[1], "m"), ("x_B0", q[2], "m"), ("y_B0", q[3], "m"), ("z0", q[4], "m"),
        ("disk_x0", st["disk"][0], "m"), ("disk_y0", st["disk"][1], "m"), ("max_substep", 2.5e-5, "s")]
    rotor_conn = [("shaft_speed", "input", "rad/s"), ("shaft_accel", "input", "rad/s2")]
    rotor_conn += [(f"{b}_{r}", "input", "N.m" if r[0] == "M" else "N") for b in "AB" for r in REAC]
    rotor_conn += [(f"{b}_{p}", "output", "rad" if p[0] == "t" else "m") for b in "AB" for p in POSE]
    rotor_conn += [(f"{b}_{p}", "output", "rad/s" if p[0] == "w" else "m/s") for b in "AB" for p in RATE]
    rotor_conn += [("disk_x", "output", "m"), ("disk_y", "output", "m"), ("disk_whirl", "output", "m"),
                   ("rotor_angle", "output", "rad")]
    comps = [
        Component("speed", "resources/SpeedRamp.fmu",
                  [("shaft_speed", "output", "rad/s"), ("shaft_accel", "output", "rad/s2")],
                  [("speed_start", d.speed_start, "rad/s"), ("speed_end", d.speed_end, "rad/s"),
                   ("ramp_start", d.ramp_start, "s"), ("ramp_end", d.ramp_end, "s")]),
        Component("rotor", "resources/JeffcottRotor.fmu", rotor_conn, rotor_params)]
    conns = [("speed", "shaft_speed", "rotor", "shaft_speed"), ("speed", "shaft_accel", "rotor", "shaft_accel")]
    for b in "AB":
        bc = [("shaft_speed", "input", "rad/s")]
        bc += [(p, "input", "rad" if p[0] == "t" else "m") for p in POSE]
        bc += [(p, "input", "rad/s" if p[0] == "w" else "m/s") for p in RATE]
        bc += [(n, "output", u) for n, u in BEARING_OUT]
        pose = st["pose_" + b]
        # each choice twice: the Enumeration (Integer value; fmpy's simulate_ssp sets no Strings) and its String
        # twin (libcosim 0.x does not handle FMI Enumerations); the FMU requires both to agree
        bp = [("bearing_preset", enumeration_value(bfmu, "bearing_preset", d.bearing), None), ("bearing", d.bearing, None),
              ("coupling_choice", enumeration_value(bfmu, "coupling_choice", "displacement"), None),
              ("coupling", "displacement", None),
              ("shaft_speed", d.speed_start, "rad/s")]
        if d.fidelity != "dynamic":
            bp += [("fidelity_choice", enumeration_value(bfmu, "fidelity_choice", d.fidelity), None),
                   ("fidelity", d.fidelity, None)]
        bp += [(p, float(v), "rad" if p[0] == "t" else "m") for p, v in zip(POSE, pose)]
        comps.append(Component(f"bearing_{b}", "resources/BearingFMU.fmu", bc, bp))
        conns.append(("speed", "shaft_speed", f"bearing_{b}", "shaft_speed"))
        conns += [("rotor", f"{b}_{p}", f"bearing_{b}", p) for p in POSE + RATE]
        conns += [(f"bearing_{b}", f"reaction_{r}", "rotor", f"{b}_{r}") for r in REAC]
    desc = (f"Jeffcott rotor ({d.disk_mass:g} kg disk at {d.disk_position:g} m of a {L:g} m span) on two {d.bearing} "
            f"bearings (displacement-driven, B mirrored, fidelity {d.fidelity}), run-up {d.speed_start * 30 / math.pi:.0f} -> "
            f"{d.speed_end * 30 / math.pi:.0f} rpm")
    ssd = ssd_xml("rotor_bearings", desc, comps, conns, 0.0, d.stop_time, d.step,
                  "ssp_examples/rotor_bearings/make_ssp.py")
    fmus = {n: fmu_dir / n for n in ("SpeedRamp.fmu", "JeffcottRotor.fmu", "BearingFMU.fmu")}
    path = write_ssp(dest, ssd, fmus)
    meta = {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in st.items()}
    meta.update(design=asdict(d), shaft_stiffness=ks, disk_damping=c_disk,
                static_load_N=d.disk_mass * d.gravity)
    Path(str(path) + ".json").write_text(__import__("json").dumps(meta, indent=1, default=float))
    return path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(HERE.parent / "build" / "rotor_bearings.ssp"))
    ap.add_argument("--quasi-static", action="store_true", help="both bearings at fidelity 'quasi-static' (QS_RUNUP)")
    a = ap.parse_args(argv)
    p = make(a.out, QS_RUNUP if a.quasi_static else None)
    print(f"wrote {p}")


if __name__ == "__main__":
    main()
