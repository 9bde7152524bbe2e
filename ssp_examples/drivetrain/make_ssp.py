"""Generate the drivetrain SSP: induction motor (InductionMotor.fmu) -> rigid shaft (ShaftInertia.fmu) -> fan load
(FanLoad.fmu), the shaft carried by two 7218B bearing FMUs (load-driven coupling, different loads) whose friction
torque brakes the shaft. The speed is a state of the shaft: nothing prescribes it.

    python ssp_examples/drivetrain/make_ssp.py [--out ssp_examples/build/drivetrain.ssp]

The bearings' loads are start values of their inputs Fx, Fz (ParameterBindings; not connectors, so no master
overwrites them). The bearing FMU is dist/BearingFMU.fmu as built (coupling = load is its default).
"""
from __future__ import annotations

import argparse
import json
import sys
from dataclasses import asdict, dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from sspgen import Component, enumeration_value, ssd_xml, write_ssp  # noqa: E402

BEARING_OUT = [("friction_torque", "N.m"), ("heat_flux_total", "W"), ("cage_speed", "rad/s"),
               ("cage_shaft_ratio", "1"), ("cage_shaft_ratio_theory", "1"), ("reaction_Fx", "N"), ("reaction_Fz", "N"),
               ("heat_flux_race_inner", "W"), ("heat_flux_race_outer", "W"), ("heat_flux_pocket", "W"),
               ("heat_flux_land", "W"), ("heat_flux_drag", "W"), ("heat_flux_damping", "W")]


@dataclass
class DrivetrainDesign:
    bearing: str = "7218B"
    load_A: tuple = (1000.0, 3000.0)      # (Fx, Fz) N on bearing A: radial + axial (seed 000 case)
    load_B: tuple = (500.0, 2000.0)       # (Fx, Fz) N on bearing B
    breakdown_torque: float = 120.0       # N.m
    breakdown_slip: float = 0.15
    sync_speed: float = 314.159265        # rad/s (2-pole, 50 Hz)
    inertia: float = 0.3                  # kg.m2 (motor rotor + shaft + fan)
    fan_rated_torque: float = 40.0        # N.m at fan_rated_speed
    fan_rated_speed: float = 300.0        # rad/s
    breakaway_torque: float = 2.0         # N.m
    speed0: float = 0.0                   # rad/s: start from rest
    stop_time: float = 3.0                # s
    step: float = 1e-3                    # s
    fidelity: str = "dynamic"             # the bearings' fidelity level (docs/fidelity.md); map: the FMU's embedded map


MAP_CYCLE = DrivetrainDesign(fidelity="map", speed0=60.0, stop_time=60.0)
"""The drive at fidelity 'map' for 60 s: run-up from 573 rpm (the 7218B maps start at 500 rpm) to the fan's
operating speed and a minute of running; the bearing FMU must embed a map (bearing build-fmu --map)."""


def make(dest, design: DrivetrainDesign | None = None, fmu_dir=None) -> Path:
    d = design or DrivetrainDesign()
    fmu_dir = Path(fmu_dir or HERE.parent / "build" / "fmus")
    bfmu = fmu_dir / "BearingFMU.fmu"
    comps = [
        Component("motor", "resources/InductionMotor.fmu",
                  [("shaft_speed", "input", "rad/s"), ("torque", "output", "N.m"), ("power", "output", "W"),
                   ("work", "output", "J")],
                  [("breakdown_torque", d.breakdown_torque, "N.m"), ("breakdown_slip", d.breakdown_slip, "1"),
                   ("sync_speed", d.sync_speed, "rad/s")]),
        Component("shaft", "resources/ShaftInertia.fmu",
                  [("motor_torque", "input", "N.m"), ("load_torque", "input", "N.m"),
                   ("friction_torque_A", "input", "N.m"), ("friction_torque_B", "input", "N.m"),
                   ("shaft_speed", "output", "rad/s"), ("shaft_accel", "output", "rad/s2"),
                   ("kinetic_energy", "output", "J"), ("work_motor", "output", "J"), ("work_load", "output", "J"),
                   ("work_friction", "output", "J")],
                  [("inertia", d.inertia, "kg.m2"), ("speed0", d.speed0, "rad/s")]),
        Component("load", "resources/FanLoad.fmu",
                  [("shaft_speed", "input", "rad/s"), ("torque", "output", "N.m"), ("power", "output", "W"),
                   ("work", "output", "J")],
                  [("rated_torque", d.fan_rated_torque, "N.m"), ("rated_speed", d.fan_rated_speed, "rad/s"),
                   ("breakaway_torque", d.breakaway_torque, "N.m")]),
    ]
    conns = [("shaft", "shaft_speed", "motor", "shaft_speed"), ("shaft", "shaft_speed", "load", "shaft_speed"),
             ("motor", "torque", "shaft", "motor_torque"), ("load", "torque", "shaft", "load_torque")]
    for b, (fx, fz) in (("A", d.load_A), ("B", d.load_B)):
        comps.append(Component(f"bearing_{b}", "resources/BearingFMU.fmu",
                               [("shaft_speed", "input", "rad/s")] + [(n, "output", u) for n, u in BEARING_OUT],
                               # choices as Enumeration (fmpy) and String twin (libcosim); they agree
                               [("bearing_preset", enumeration_value(bfmu, "bearing_preset", d.bearing), None),
                                ("bearing", d.bearing, None),
                                ("coupling_choice", enumeration_value(bfmu, "coupling_choice", "load"), None),
                                ("coupling", "load", None),
                                ("shaft_speed", d.speed0, "rad/s"), ("Fx", fx, "N"), ("Fz", fz, "N")]
                               + ([] if d.fidelity == "dynamic" else
                                  [("fidelity_choice", enumeration_value(bfmu, "fidelity_choice", d.fidelity), None),
                                   ("fidelity", d.fidelity, None)])))
        conns += [("shaft", "shaft_speed", f"bearing_{b}", "shaft_speed"),
                  (f"bearing_{b}", "friction_torque", "shaft", f"friction_torque_{b}")]
    desc = (f"Induction motor, shaft inertia {d.inertia:g} kg.m2 and fan load on two {d.bearing} bearings "
            f"(A: Fx {d.load_A[0]:g} N, Fz {d.load_A[1]:g} N; B: Fx {d.load_B[0]:g} N, Fz {d.load_B[1]:g} N)")
    ssd = ssd_xml("drivetrain", desc, comps, conns, 0.0, d.stop_time, d.step, "ssp_examples/drivetrain/make_ssp.py")
    fmus = {n: fmu_dir / n for n in ("InductionMotor.fmu", "ShaftInertia.fmu", "FanLoad.fmu", "BearingFMU.fmu")}
    path = write_ssp(dest, ssd, fmus)
    Path(str(path) + ".json").write_text(json.dumps({"design": asdict(d)}, indent=1))
    return path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(HERE.parent / "build" / "drivetrain.ssp"))
    ap.add_argument("--map-cycle", action="store_true",
                    help="the 60 s drive at fidelity 'map' (MAP_CYCLE) instead of the 3 s run-up from rest")
    a = ap.parse_args(argv)
    print(f"wrote {make(a.out, MAP_CYCLE if a.map_cycle else None)}")


if __name__ == "__main__":
    main()
