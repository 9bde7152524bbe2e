"""Wall time per simulated second of a steady fidelity level ('map' or 'quasi-static') at 1 ms communication steps
(docs/fidelity.md).

  * session: bearing_core.session.cosim.CoSimSession at the level (--fidelity, default map) in this process, through the seed 000
    profile (the speed input changes every step) and with held inputs;
  * fmu: the FMU with the map embedded (bearing build-fmu --map, or --fmu) driven by fmpy's FMU2Slave: per step
    setReal of the inputs, doStep, getReal of --outputs outputs (the master's own calls included), the first
    0.1 s left out (start-up); the time in doStep and in the get/set calls reported apart.

    python bench/fidelity_speed.py --map maps/7218B_oil.nc [--fidelity quasi-static] [--fmu dist/BearingFMU.fmu]
        [--t-end 2] [--json OUT]

At --fidelity quasi-static the map gives only the parameters (the level solves at them; an FMU built here embeds
the map all the same)."""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))
from machine import machine_info, machine_line  # noqa: E402
from fmpy_floor import step_loop  # noqa: E402  (the same master loop as the floor it is compared with)

RPM = math.pi / 30.0
H = 1e-3
OUTPUTS = ("cage_speed", "friction_torque", "heat_flux_total", "reaction_Fx", "reaction_Fy", "reaction_Fz",
           "reaction_Mx", "reaction_My", "cage_slip_ratio", "temperature_oil")


def profile_speed(t):
    from bearing_core.models.dynamics import SEED000_PROFILE
    tp = [p[0] for p in SEED000_PROFILE]
    n = [p[1] for p in SEED000_PROFILE]
    return float(np.interp(t, tp, n)) * RPM


def session_speed(map_file, params, t_end, fx=1000.0, fz=3000.0, fidelity="map"):
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    s = CoSimSession(CoSimParameters(**dict(params, fidelity=fidelity,
                                            map_file=map_file if fidelity == "map" else "")))
    s.initialize(0.0, {"shaft_speed": profile_speed(0.0), "Fx": fx, "Fz": fz})
    n = int(round(t_end / H))
    speeds = [profile_speed(k * H) for k in range(n)]
    out = {}
    for label, varying in (("ramp", True), ("held", False)):
        s.initialize(0.0, {"shaft_speed": speeds[0], "Fx": fx, "Fz": fz})
        held = {"shaft_speed": speeds[0], "Fx": fx, "Fz": fz}
        us = [{"shaft_speed": speeds[k], "Fx": fx, "Fz": fz} if varying else held for k in range(n)]
        steps = np.empty(n)
        t0, c0 = time.perf_counter(), time.thread_time()
        for k in range(n):
            a = time.perf_counter()
            s.step(k * H, H, us[k])
            steps[k] = time.perf_counter() - a
        out[label] = {"wall_per_sim_s": (time.perf_counter() - t0) / (n * H),
                      "cpu_per_sim_s": (time.thread_time() - c0) / (n * H),
                      # the median step: robust against the host's preemptions, which the mean carries
                      "median_step_us": float(np.median(steps) * 1e6)}
    return out


def fmu_speed(fmu, params, t_end, n_out, fx=1000.0, fz=3000.0, profile=None, fidelity="map"):
    """profile: a file for the model process's own time per doStep (BEARING_FMU_PROFILE of the native layer)."""
    from fmpy import extract, read_model_description
    if profile:
        os.environ["BEARING_FMU_PROFILE"] = str(profile)
    else:
        os.environ.pop("BEARING_FMU_PROFILE", None)
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    unzip = extract(fmu)
    f = FMU2Slave(guid=md.guid, unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="bearing")
    t0 = time.perf_counter()
    f.instantiate()
    f.setupExperiment(startTime=0.0)
    f.setString([vr["fidelity"]], [fidelity])
    for k, v in params.items():
        if k in vr and isinstance(v, str) and k not in ("fidelity", "map_file"):
            f.setString([vr[k]], [v])
    f.enterInitializationMode()
    in_vr = [vr["shaft_speed"], vr["Fx"], vr["Fz"]]
    f.setReal(in_vr, [profile_speed(0.0), fx, fz])
    f.exitInitializationMode()
    init_s = time.perf_counter() - t0
    out_vr = [vr[n] for n in (list(OUTPUTS) * 10)[:n_out]]
    n = int(round(t_end / H))
    skip = int(round(0.1 / H))
    # the inputs computed before the loop: the master's own model is not the FMU's cost
    inputs = [[profile_speed(k * H), fx, fz] for k in range(n)]
    wall, t_step, t_io = step_loop(f, in_vr, out_vr, inputs, skip)
    sim = (n - skip) * H
    f.terminate()
    f.freeInstance()
    out = {"init_wall_s": init_s, "wall_per_sim_s": wall / sim, "doStep_per_sim_s": t_step / sim,
           "get_set_per_sim_s": t_io / sim, "outputs_read": n_out}
    if profile and Path(profile).is_file():
        busy = np.array(json.loads(Path(profile).read_text())["busy"][skip:])
        out["model_process_per_sim_s"] = float(busy.sum() / sim)
        out["model_process_median_step_us"] = float(np.median(busy) * 1e6)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", required=True)
    ap.add_argument("--fidelity", default="map", choices=("map", "quasi-static"))
    ap.add_argument("--fmu", default=None, help="an FMU embedding the map (default: built here with --map)")
    ap.add_argument("--t-end", type=float, default=2.0)
    ap.add_argument("--outputs", type=int, default=10, help="outputs read per step through getReal")
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    print(machine_line())
    import xarray as xr
    with xr.open_dataset(a.map, engine="scipy") as ds:
        params = json.loads(ds.attrs["parameters"])
    params = {k: v for k, v in params.items()}
    res = {"machine": machine_info(), "step_s": H, "t_end_s": a.t_end, "fidelity": a.fidelity}
    res["session"] = session_speed(a.map, params, a.t_end, fidelity=a.fidelity)
    print(f"session, fidelity {a.fidelity}: {res['session']['ramp']['wall_per_sim_s']:.4f} s per simulated s (speed ramp), "
          f"{res['session']['held']['wall_per_sim_s']:.4f} (held inputs); median step "
          f"{res['session']['ramp']['median_step_us']:.1f} us (ramp), {res['session']['held']['median_step_us']:.1f} us (held)")
    fmu = a.fmu
    if fmu is None:
        from bearing_cosim.fmu_build import build
        fmu = str(build(Path(tempfile.mkdtemp(prefix="fidelity_speed_")), map_file=a.map))
    os.environ.setdefault("BEARING_FMU_CACHE", str(Path(tempfile.gettempdir()) / "fidelity_speed_fmu_cache"))
    fmu_speed(fmu, params, 0.3, a.outputs, fidelity=a.fidelity)   # warm-up: the code copy and its compiled kernels
    res["fmu"] = fmu_speed(fmu, params, a.t_end, a.outputs, fidelity=a.fidelity,
                           profile=Path(tempfile.mkdtemp(prefix="fidelity_speed_")) / "profile.json")
    r = res["fmu"]
    print(f"FMU through fmpy, fidelity {a.fidelity}: {r['wall_per_sim_s']:.4f} s per simulated s (doStep "
          f"{r['doStep_per_sim_s']:.4f}, setReal + getReal of {r['outputs_read']} outputs "
          f"{r['get_set_per_sim_s']:.4f}); initialisation {r['init_wall_s']:.2f} s")
    if "model_process_per_sim_s" in r:
        print(f"  of which in the model process: {r['model_process_per_sim_s']:.4f} s per simulated s (median "
              f"{r['model_process_median_step_us']:.1f} us per step); the rest is the process exchange")
    if a.json:
        Path(a.json).parent.mkdir(parents=True, exist_ok=True)
        Path(a.json).write_text(json.dumps(res, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
