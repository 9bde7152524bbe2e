"""Speed of the operating-map FMU all in C (BearingMapFMU, bearing build-map-fmu): the median fmi2DoStep in a C
host, the FMU through fmpy at 1 ms steps against fmpy's own floor (a C FMU whose functions only copy values, in
the same run: bench/fmpy_floor.py), the instantiation (table read included) and the zipped size.

    python bench/bench_map_fmu.py [--map maps/7218B_oil.nc] [--steps 200000] [--t-end 2] [--repeat 3] [--json F]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(HERE))
from machine import machine_info, machine_line  # noqa: E402
import fmpy_floor  # noqa: E402

RPM = math.pi / 30.0
OUTPUTS = ("cage_speed", "friction_torque", "heat_flux_total", "reaction_Fx", "reaction_Fy", "reaction_Fz",
           "cage_shaft_ratio", "skid_ratio", "ir_z", "max_contact_pressure")
"""The 10 outputs read per step (as bench/fmpy_floor.py reads 10)."""


def host_timing(fmu: Path, d: Path, steps: int, cycles: int) -> dict:
    """Median fmi2DoStep [ns] over steps steps (shaft speed 4000 rpm, Fx 1500 N, Fz 3000 N) and mean instantiate +
    free [ns] over cycles, in the C host tests/c_host/host.c (-O2)."""
    from fmpy import read_model_description
    cc = os.environ.get("CC", "gcc")
    exe = d / "host"
    subprocess.run([cc, "-std=gnu99", "-O2", "-o", str(exe), str(ROOT / "tests" / "c_host" / "host.c"), "-ldl"],
                   check=True)
    unz = d / "unz"
    with zipfile.ZipFile(fmu) as z:
        z.extractall(unz)
    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    script = d / "s.txt"
    script.write_text("instantiate\nsetup 0\nenter\nexit\n"
                      f"inputs {vr['shaft_speed']} {vr['Fx']} {vr['Fz']}\n"
                      f"outputs {' '.join(str(vr[n]) for n in OUTPUTS)}\n"
                      f"repeat {steps} 0.001 {4000 * RPM!r} 1500 3000\nfree\ninstantiate\ncycles {cycles}\nfree\n")
    r = subprocess.run([str(exe), str(unz), md.coSimulation.modelIdentifier, md.guid, str(script)],
                       capture_output=True, text=True, check=True)
    step = [float(ln.split()[1]) for ln in r.stdout.splitlines() if ln.startswith("TIMING ")][0]
    inst = [float(ln.split()[1]) for ln in r.stdout.splitlines() if ln.startswith("TIMING_CYCLE ")][0]
    row = [ln for ln in r.stdout.splitlines() if ln.startswith("ROW ")][0].split()
    if int(row[1]) > 1:
        raise SystemExit(f"the host's steps failed: {r.stdout[-1000:]}")
    return {"doStep_median_ns": step, "instantiate_free_mean_ns": inst}


def fmpy_per_sim_s(fmu: Path, names, t_end: float) -> float:
    """fmpy's FMU2Slave at 1 ms steps through t_end, bench/fmpy_floor.step_loop (setReal of 3 inputs, doStep,
    getReal of 10 outputs; the first 0.1 s left out): wall time per simulated second."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    f = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(fmu)), modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="bench")
    f.instantiate()
    f.setupExperiment(startTime=0.0)
    f.enterInitializationMode()
    f.exitInitializationMode()
    ins, outs = names
    in_vr = [vr[n] for n in ins]
    out_vr = [vr[n] for n in outs]
    n = int(round(t_end / fmpy_floor.H))
    skip = int(round(0.1 / fmpy_floor.H))
    # a run-up from 1000 rpm at 2000 rpm/s (every step a new operating point), Fx 1500 N, Fz 3000 N
    inputs = [[(1000.0 + 2000.0 * k * fmpy_floor.H) * RPM, 1500.0, 3000.0] for k in range(n)]
    wall, _t_step, _t_io = fmpy_floor.step_loop(f, in_vr, out_vr, inputs, skip)
    f.terminate()
    f.freeInstance()
    return wall / ((n - skip) * fmpy_floor.H)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", default=str(ROOT / "maps" / "7218B_oil.nc"))
    ap.add_argument("--steps", type=int, default=200000, help="fmi2DoStep calls timed in the C host")
    ap.add_argument("--cycles", type=int, default=200, help="instantiate/free cycles timed in the C host")
    ap.add_argument("--t-end", type=float, default=2.0, help="simulated seconds per fmpy run")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    for name, v, ok, allowed in (("--steps", a.steps, 1 <= a.steps <= 10**8, "1 <= value <= 1e8"),
                                 ("--cycles", a.cycles, 1 <= a.cycles <= 10**6, "1 <= value <= 1e6"),
                                 ("--t-end", a.t_end, math.isfinite(a.t_end) and 0.2 <= a.t_end <= 3600.0,
                                  "0.2 <= value <= 3600 s"),
                                 ("--repeat", a.repeat, 1 <= a.repeat <= 100, "1 <= value <= 100")):
        if not ok:
            ap.error(f"{name} = {v!r} is invalid; allowed: {allowed}")
    if not Path(a.map).is_file():
        ap.error(f"--map = {a.map!r} is not a file")
    print(machine_line())
    from bearing_cosim.map_fmu import build_map_fmu
    from bearing_cosim.map_table import TABLE_NAME
    res = {"machine": machine_info(), "map": a.map}
    with tempfile.TemporaryDirectory(prefix="bench_map_fmu_") as td:
        d = Path(td)
        fmu = build_map_fmu(a.map, d / "dist", ["linux64"])
        with zipfile.ZipFile(fmu) as z:
            table = z.getinfo(f"resources/{TABLE_NAME}")
        res["zipped_bytes"] = fmu.stat().st_size
        res["zipped_table_bytes"] = table.compress_size
        res["table_bytes"] = table.file_size
        print(f"BearingMapFMU.fmu (linux64): {fmu.stat().st_size / 1024:.0f} KiB zipped, of which the table "
              f"{table.compress_size / 1024:.0f} KiB ({table.file_size / 1024:.0f} KiB unpacked)")
        h = host_timing(fmu, d, a.steps, a.cycles)
        res["host"] = h
        print(f"C host: fmi2DoStep median {h['doStep_median_ns'] / 1000:.3f} us over {a.steps} steps; "
              f"fmi2Instantiate + fmi2FreeInstance (table read and checked) {h['instantiate_free_mean_ns'] / 1e6:.3f} ms")
        floor = fmpy_floor.build(d)
        runs = {"floor": [], "map_fmu": []}
        for _ in range(a.repeat):       # alternating: the machine's state changes within a session
            runs["floor"].append(fmpy_per_sim_s(floor, (("u0", "u1", "u2"), tuple(f"y{k}" for k in range(3, 13))),
                                                a.t_end))
            runs["map_fmu"].append(fmpy_per_sim_s(fmu, (("shaft_speed", "Fx", "Fz"), OUTPUTS), a.t_end))
            print(f"fmpy at 1 ms steps: copy-only C FMU {runs['floor'][-1]:.4f}, BearingMapFMU "
                  f"{runs['map_fmu'][-1]:.4f} s per simulated s (ratio {runs['map_fmu'][-1] / runs['floor'][-1]:.2f})")
        res["fmpy"] = runs
        ratio = min(runs["map_fmu"]) / min(runs["floor"])
        res["fmpy_ratio_best"] = ratio
        print(f"best of {a.repeat}: ratio to fmpy's floor {ratio:.2f}")
    if a.json:
        Path(a.json).write_text(json.dumps(res, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
