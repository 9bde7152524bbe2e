"""Build the FMUs of the SSP examples and generate the SSP archives.

    python ssp_examples/build_examples.py [--dest ssp_examples/build]

-> build/fmus/BearingFMU.fmu (= dist/BearingFMU.fmu, with the 7218B oil map maps/7218B_oil.nc embedded for
fidelity 'map' when this checkout has it; the SSDs choose bearing preset and coupling through its Enumeration
parameters, so every master that sets Integer values can run them), the helper FMUs (JeffcottRotor, SpeedRamp,
InductionMotor, ShaftInertia, FanLoad, DutyCycle; pythonfmu slaves in <example>/fmus/) built on the bearing FMU's own
FMI layer (each instance's model in a process of its own, so no master hosts their Python), and
build/rotor_bearings.ssp, build/drivetrain.ssp (by each example's make_ssp.py), build/drivetrain_map.ssp (the
drivetrain for 60 s at fidelity 'map', with the map) and build/drivetrain_cycle_map.ssp (the 60 s drive cycle:
run-up, load steps, coast-down, idle, at fidelity 'map'; build/drivetrain_cycle_qs.ssp the same at
'quasi-static'). Nothing here is committed.
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(HERE))

HELPERS = {"rotor_bearings": ("jeffcott_rotor.py", "speed_ramp.py"),
           "drivetrain": ("induction_motor.py", "shaft_inertia.py", "fan_load.py", "duty_cycle.py")}


def slave_class(source: str) -> str:
    """Name of the pythonfmu Fmi2Slave subclass a helper's source defines (one per file)."""
    names = re.findall(r"(?m)^class (\w+)\(Fmi2Slave\)", source)
    if len(names) != 1:
        raise ValueError(f"expected one Fmi2Slave subclass, found {names}")
    return names[0]


SHIPPED_MAP = ROOT / "maps" / "7218B_oil.nc"
"""The operating map the bearing FMU embeds (fidelity 'map', docs/fidelity.md), when this checkout has it."""


def build_fmus(dest: Path) -> Path:
    from bearing_cosim import fmu_build

    fmus = Path(dest) / "fmus"
    fmus.mkdir(parents=True, exist_ok=True)
    fmu_build.build(fmus, map_file=SHIPPED_MAP if SHIPPED_MAP.is_file() else None)
    if SHIPPED_MAP.is_file():     # the same map's level all in C (BearingMapFMU.fmu)
        from bearing_cosim.map_fmu import build_map_fmu
        build_map_fmu(SHIPPED_MAP, fmus)
    for example, scripts in HELPERS.items():
        for s in scripts:
            src = (HERE / example / "fmus" / s).read_text()
            module = Path(s).stem
            fmu_build._build(slave_class(src), {module: src}, module, fmus)
    return fmus


def make_ssps(dest: Path, fmus: Path) -> list:
    import importlib.util

    out = []
    for example in HELPERS:
        spec = importlib.util.spec_from_file_location(f"make_ssp_{example}", HERE / example / "make_ssp.py")
        mod = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = mod
        spec.loader.exec_module(mod)
        out.append(mod.make(Path(dest) / f"{example}.ssp", fmu_dir=fmus))
        if example == "rotor_bearings":
            out.append(mod.make(Path(dest) / "rotor_bearings_qs.ssp", mod.QS_RUNUP, fmu_dir=fmus))
        if example == "drivetrain" and SHIPPED_MAP.is_file():
            out.append(mod.make(Path(dest) / "drivetrain_map.ssp", mod.MAP_CYCLE, fmu_dir=fmus))
            out.append(mod.make(Path(dest) / "drivetrain_cycle_map.ssp", mod.MAP_DRIVE_CYCLE, fmu_dir=fmus))
            out.append(mod.make(Path(dest) / "drivetrain_cycle_qs.ssp", mod.QS_DRIVE_CYCLE, fmu_dir=fmus))
            out.append(mod.make(Path(dest) / "drivetrain_cycle_cmap.ssp", mod.C_MAP_DRIVE_CYCLE, fmu_dir=fmus))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dest", default=str(HERE / "build"))
    a = ap.parse_args(argv)
    fmus = build_fmus(Path(a.dest))
    for f in sorted(fmus.glob("*.fmu")):
        print(f"built {f} ({f.stat().st_size / 1024:.0f} KiB)")
    for p in make_ssps(Path(a.dest), fmus):
        print(f"wrote {p}")
    return 0


if __name__ == "__main__":
    import scipy.linalg  # noqa: F401  (before numba: docs/fmu.md)
    sys.exit(main())
