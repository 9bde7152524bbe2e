"""Generate the drivetrain SSP: induction motor (InductionMotor.fmu) -> rigid shaft (ShaftInertia.fmu) -> fan load
(FanLoad.fmu), the shaft carried by two 7218B bearing FMUs (load-driven coupling, different loads) whose friction
torque brakes the shaft. The speed is a state of the shaft: nothing prescribes it.

    python ssp_examples/drivetrain/make_ssp.py [--out ssp_examples/build/drivetrain.ssp]

The bearings' loads are start values of their inputs Fx, Fz (ParameterBindings; not connectors, so no master
overwrites them). With a duty cycle (DrivetrainDesign.duty_cycle, e.g. CYCLE_60S) a DutyCycle FMU gives the
loads and the motor's supply frequency over time, connected to the bearings' Fx, Fz and the motor's
frequency_ratio. The bearing FMU is dist/BearingFMU.fmu as built (coupling = load is its default).
"""
from __future__ import annotations

import argparse
import json
import sys
from dataclasses import asdict, dataclass, replace
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from sspgen import Component, enumeration_value, ssd_xml, write_ssp  # noqa: E402

BEARING_OUT = [("friction_torque", "N.m"), ("heat_flux_total", "W"), ("cage_speed", "rad/s"),
               ("cage_shaft_ratio", "1"), ("cage_shaft_ratio_theory", "1"), ("reaction_Fx", "N"), ("reaction_Fz", "N"),
               ("heat_flux_race_inner", "W"), ("heat_flux_race_outer", "W"), ("heat_flux_pocket", "W"),
               ("heat_flux_land", "W"), ("heat_flux_drag", "W"), ("heat_flux_damping", "W")]


MAX_PHASES = 8                            # phase slots of fmus/duty_cycle.py


@dataclass
class Phase:
    """One phase of a duty cycle (fmus/duty_cycle.py): from `time` the outputs move linearly to the phase's values
    over `ramp` (0: a step). The first phase is the state at the start (its ramp is not used)."""
    name: str
    time: float                           # s
    ramp: float                           # s
    load_A: tuple                         # (Fx, Fz) N on bearing A
    load_B: tuple                         # (Fx, Fz) N on bearing B
    frequency_ratio: float                # motor supply frequency / rated; 0: supply off


def drive_cycle(t_runup=8.0, t_step1=20.0, t_step2=32.0, t_off=44.0, t_idle=47.0) -> tuple:
    """The drive cycle's phases, times in s: an inverter run-up from 20 % of the rated supply frequency (10 Hz)
    to the rated one (50 Hz) over [0, t_runup] under the base loads (A: Fx 1 kN, Fz 3 kN; B: 0.5 / 2 kN), running
    at them from t_runup, a step to full process load at t_step1 (A: 2.5 / 5 kN; B: 1.5 / 3.5 kN), a step to part
    load at t_step2 (A: 0.6 / 2.5 kN; B: 0.3 / 1.7 kN), the supply off at t_off (coast-down under fan and bearing
    friction) and back on at t_idle at 30 % of the rated frequency (15 Hz: idle near 890 rpm, above the 500 rpm
    floor of the 7218B maps; with the default inertia and fan the shaft would reach 500 rpm about 6 s after
    switching off)."""
    base, full, part = ((1000.0, 3000.0), (500.0, 2000.0)), ((2500.0, 5000.0), (1500.0, 3500.0)), \
        ((600.0, 2500.0), (300.0, 1700.0))
    return (Phase("start", 0.0, 0.0, *base, 0.2), Phase("run-up", 0.0, t_runup, *base, 1.0),
            Phase("base load", t_runup, 0.0, *base, 1.0), Phase("full load", t_step1, 0.0, *full, 1.0),
            Phase("part load", t_step2, 0.0, *part, 1.0), Phase("coast-down", t_off, 0.0, *part, 0.0),
            Phase("idle", t_idle, 0.0, *part, 0.3))


CYCLE_60S = drive_cycle()


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
    duty_cycle: tuple = ()                # Phase rows: loads and motor supply over time (DutyCycle FMU); () constant
    bearing_fmu: str = "BearingFMU"       # the bearings' FMU: BearingFMU, or BearingMapFMU (the map level all in C,
    #                                       bearing build-map-fmu; its parameters are the map's: none are set)


MAP_CYCLE = DrivetrainDesign(fidelity="map", speed0=60.0, stop_time=60.0)
"""The drive at fidelity 'map' for 60 s: run-up from 573 rpm (the 7218B maps start at 500 rpm) to the fan's
operating speed and a minute of running; the bearing FMU must embed a map (bearing build-fmu --map)."""

MAP_DRIVE_CYCLE = DrivetrainDesign(fidelity="map", speed0=60.0, stop_time=60.0, duty_cycle=CYCLE_60S)
QS_DRIVE_CYCLE = replace(MAP_DRIVE_CYCLE, fidelity="quasi-static")
C_MAP_DRIVE_CYCLE = replace(MAP_DRIVE_CYCLE, bearing_fmu="BearingMapFMU")
"""The 60 s drive cycle with the bearings as BearingMapFMU: the map level in C, no Python beside the master."""
"""The 60 s drive cycle (drive_cycle) at fidelity 'map', from 573 rpm: run-up, two load steps, coast-down and
idle; the bearing FMU must embed a map."""


def _check_cycle(phases):
    if not 1 <= len(phases) <= MAX_PHASES:
        raise ValueError(f"duty_cycle: {len(phases)} phases; allowed 1 .. {MAX_PHASES}")
    for k in range(1, len(phases)):
        p, q = phases[k], phases[k - 1]
        start = q.time + (q.ramp if k > 1 else 0.0)
        if p.time < start or p.ramp < 0.0:
            raise ValueError(f"duty_cycle phase {k + 1}: time {p.time} s, ramp {p.ramp} s; allowed time >= "
                             f"{start} s (the previous phase's end) and ramp >= 0")


def make(dest, design: DrivetrainDesign | None = None, fmu_dir=None) -> Path:
    d = design or DrivetrainDesign()
    fmu_dir = Path(fmu_dir or HERE.parent / "build" / "fmus")
    if d.bearing_fmu not in ("BearingFMU", "BearingMapFMU"):
        raise ValueError(f"bearing_fmu = {d.bearing_fmu!r}; allowed: 'BearingFMU', 'BearingMapFMU'")
    if d.bearing_fmu == "BearingMapFMU" and d.fidelity != "map":
        raise ValueError(f"fidelity = {d.fidelity!r} with BearingMapFMU; allowed: 'map'")
    bfmu = fmu_dir / f"{d.bearing_fmu}.fmu"
    cyc = tuple(d.duty_cycle)
    if cyc:
        _check_cycle(cyc)
    comps = [
        Component("motor", "resources/InductionMotor.fmu",
                  [("shaft_speed", "input", "rad/s"), ("torque", "output", "N.m"), ("power", "output", "W"),
                   ("work", "output", "J")] + ([("frequency_ratio", "input", "1")] if cyc else []),
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
    loads = {"A": d.load_A, "B": d.load_B}
    if cyc:
        loads = {"A": cyc[0].load_A, "B": cyc[0].load_B}
        par = [("phases", len(cyc), None)]
        for k, p in enumerate(cyc, 1):
            par += [(f"phase{k}_time", p.time, "s"), (f"phase{k}_ramp", p.ramp, "s"),
                    (f"phase{k}_Fx_A", p.load_A[0], "N"), (f"phase{k}_Fz_A", p.load_A[1], "N"),
                    (f"phase{k}_Fx_B", p.load_B[0], "N"), (f"phase{k}_Fz_B", p.load_B[1], "N"),
                    (f"phase{k}_frequency_ratio", p.frequency_ratio, "1")]
        comps.append(Component("duty", "resources/DutyCycle.fmu",
                               [(n, "output", u) for n, u in (("Fx_A", "N"), ("Fz_A", "N"), ("Fx_B", "N"),
                                                               ("Fz_B", "N"), ("frequency_ratio", "1"),
                                                               ("phase", "1"))], par))
        conns.append(("duty", "frequency_ratio", "motor", "frequency_ratio"))
        comps[0].parameters.append(("frequency_ratio", cyc[0].frequency_ratio, "1"))
    for b, (fx, fz) in loads.items():
        if cyc:
            conns += [("duty", f"Fx_{b}", f"bearing_{b}", "Fx"), ("duty", f"Fz_{b}", f"bearing_{b}", "Fz")]
        starts = [("shaft_speed", d.speed0, "rad/s"), ("Fx", fx, "N"), ("Fz", fz, "N")]
        if d.bearing_fmu == "BearingFMU":
            # choices as Enumeration (fmpy) and String twin (libcosim); they agree
            starts = [("bearing_preset", enumeration_value(bfmu, "bearing_preset", d.bearing), None),
                      ("bearing", d.bearing, None),
                      ("coupling_choice", enumeration_value(bfmu, "coupling_choice", "load"), None),
                      ("coupling", "load", None)] + starts + (
                [] if d.fidelity == "dynamic" else
                [("fidelity_choice", enumeration_value(bfmu, "fidelity_choice", d.fidelity), None),
                 ("fidelity", d.fidelity, None)])
        comps.append(Component(f"bearing_{b}", f"resources/{d.bearing_fmu}.fmu",
                               [("shaft_speed", "input", "rad/s")]
                               + ([("Fx", "input", "N"), ("Fz", "input", "N")] if cyc else [])
                               + [(n, "output", u) for n, u in BEARING_OUT], starts))
        conns += [("shaft", "shaft_speed", f"bearing_{b}", "shaft_speed"),
                  (f"bearing_{b}", "friction_torque", "shaft", f"friction_torque_{b}")]
    desc = (f"Induction motor, shaft inertia {d.inertia:g} kg.m2 and fan load on two {d.bearing} bearings " +
            (f"(loads and motor supply from a {len(cyc)}-phase duty cycle)" if cyc else
             f"(A: Fx {d.load_A[0]:g} N, Fz {d.load_A[1]:g} N; B: Fx {d.load_B[0]:g} N, Fz {d.load_B[1]:g} N)"))
    ssd = ssd_xml("drivetrain", desc, comps, conns, 0.0, d.stop_time, d.step, "ssp_examples/drivetrain/make_ssp.py")
    fmus = {n: fmu_dir / n for n in ("InductionMotor.fmu", "ShaftInertia.fmu", "FanLoad.fmu", f"{d.bearing_fmu}.fmu")
            + (("DutyCycle.fmu",) if cyc else ())}
    path = write_ssp(dest, ssd, fmus)
    Path(str(path) + ".json").write_text(json.dumps({"design": asdict(d)}, indent=1))
    return path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(HERE.parent / "build" / "drivetrain.ssp"))
    ap.add_argument("--map-cycle", action="store_true",
                    help="the 60 s drive at fidelity 'map' (MAP_CYCLE) instead of the 3 s run-up from rest")
    ap.add_argument("--drive-cycle", choices=("map", "quasi-static", "c-map"),
                    help="the 60 s drive cycle (MAP_DRIVE_CYCLE) with the bearings at this fidelity")
    a = ap.parse_args(argv)
    design = MAP_CYCLE if a.map_cycle else None
    if a.drive_cycle:
        design = (C_MAP_DRIVE_CYCLE if a.drive_cycle == "c-map" else replace(MAP_DRIVE_CYCLE, fidelity=a.drive_cycle))
    print(f"wrote {make(a.out, design)}")


if __name__ == "__main__":
    main()
