"""Drive the bearing FMU with fmpy through a speed profile with held loads; write CSV, plots and a
summary. Used by `bearing simulate` and the README's main job."""
from __future__ import annotations

import csv
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

RPM = math.pi / 30.0
from bearing_core.dynamics import PROFILE_LOAD_COLUMNS as LOAD_COLS, read_profile

def _clip_profile(t, n, loads, t_stop):
    """The profile on [t0, t_stop]: cut (interpolated at t_stop) or extended holding the last values."""
    keep = t < t_stop
    tt = np.append(t[keep], t_stop)
    f = lambda y: np.append(y[keep], np.interp(t_stop, t, y))
    return tt, f(n), ({k: f(v) for k, v in loads.items()} if loads else loads)


def enumeration_values(md, values: dict) -> dict:
    """``values`` with the item names of Enumeration variables replaced by their item values (what
    fmi2SetInteger takes); an unknown item name is an error naming the variable and its items."""
    from bearing_core.errors import BearingInputError
    out = dict(values)
    for v in md.modelVariables:
        if v.type == "Enumeration" and isinstance(out.get(v.name), str):
            items = {it.name: int(it.value) for it in v.declaredType.items}
            val = out[v.name]
            if val in items:
                out[v.name] = items[val]
            elif val.strip().lstrip("-").isdigit():
                out[v.name] = int(val)
            else:
                raise BearingInputError(v.name, val, " | ".join(items))
    return out


def simulate(fmu: str, profile: str, loads=(0.0, 0.0, 0.0, 0.0, 0.0), step: float = 1e-3, params=None,
             out: str = "out", progress: bool = True, stop_time: float | None = None) -> dict:
    """Run the FMU through the profile with fmpy; returns the summary dict (files written to out/).
    ``stop_time`` [s] ends the run early, or holds the profile's last values past its end."""
    import fmpy
    from fmpy import read_model_description

    t, n, prof_loads = read_profile(profile)
    if stop_time is not None:
        t, n, prof_loads = _clip_profile(t, n, prof_loads, float(stop_time))
    md = read_model_description(fmu)
    outputs = [v.name for v in md.modelVariables if v.causality == "output"]
    names = ["shaft_speed", "Fx", "Fy", "Fz", "Mx", "My"]
    cols = [n * RPM]
    for k, name in zip(LOAD_COLS, names[1:]):
        cols.append(prof_loads[k] if prof_loads and k in prof_loads else np.full_like(t, loads[names.index(name) - 1]))
    # the displacement-coupling inputs are unused in load-driven mode: held at zero
    for name in [v.name for v in md.modelVariables if v.causality == "input" and v.name not in names]:
        names.append(name)
        cols.append(np.zeros_like(t))
    sig = np.array(list(zip(t, *cols)), dtype=[("time", float)] + [(k, float) for k in names])
    t0 = time.perf_counter()
    last = [0.0]

    def step_finished(time_, recorder):
        if progress and time_ - last[0] >= 0.05 - 1e-12:
            last[0] = time_
            sys.stderr.write(f"\r  simulated {time_:7.3f} / {t[-1]:.3f} s   wall {time.perf_counter() - t0:6.1f} s")
            sys.stderr.flush()
        return True

    reasons = []

    def logger(component, instance_name, status, category, message):
        if status >= 2:   # discard, error, fatal: the FMU's reason, reported with the failure
            reasons.append(message.decode("utf-8", "replace") if isinstance(message, bytes) else str(message))

    start_values = enumeration_values(md, params or {})
    try:
        res = fmpy.simulate_fmu(fmu, start_time=float(t[0]), stop_time=float(t[-1]), step_size=step,
                                output_interval=step, input=sig, output=outputs, start_values=start_values,
                                step_finished=step_finished, logger=logger)
    except Exception as e:
        if progress:
            sys.stderr.write("\n")
        raise RuntimeError(f"{e}: " + ("; ".join(reasons[-3:]) if reasons else "the FMU gave no reason")) from None
    if progress:
        sys.stderr.write("\n")
    wall = time.perf_counter() - t0
    outd = Path(out)
    outd.mkdir(parents=True, exist_ok=True)
    from bearing_core.postprocess import plot_dynamics
    csv_path = outd / "fmu_simulation.csv"
    units = {v.name: (v.unit or "1") for v in md.modelVariables}
    with csv_path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["time [s]", "shaft_speed [rad/s]"] + [f"{k} [{units[k]}]" for k in outputs])
        speed = np.interp(res["time"], t, n * RPM)
        for i in range(len(res)):
            w.writerow([f"{res['time'][i]:.9g}", f"{speed[i]:.9g}"] + [f"{res[k][i]:.9g}" for k in outputs])
    speed = np.interp(res["time"], t, n * RPM)
    d = {"t": res["time"], "shaft_speed": speed, "cage_speed": res["cage_speed"],
         "pure_rolling_cage_speed": res["cage_shaft_ratio_theory"] * speed,
         "friction_torque": res["friction_torque"], "P_drive": res["friction_torque"] * speed,
         "P_race_inner": res["heat_flux_race_inner"], "P_race_outer": res["heat_flux_race_outer"],
         "P_pocket": res["heat_flux_pocket"], "P_land": res["heat_flux_land"], "P_drag": res["heat_flux_drag"],
         "P_damping": res["heat_flux_damping"], "Fx": res["reaction_Fx"], "Fy": res["reaction_Fy"],
         "Fz": res["reaction_Fz"], "ball0_wr": res["ball0_omega_r"], "ball0_wt": res["ball0_omega_t"],
         "ball0_wz": res["ball0_omega_z"]}
    png = plot_dynamics(d, outd / "fmu_simulation.png", title=f"bearing FMU via fmpy, profile {profile}, "
                                                              f"loads {tuple(loads)} N / N m, step {step:g} s")
    tail = res["time"] >= res["time"][-1] - 0.1
    summary = {"fmu": str(fmu), "profile": profile, "loads": dict(zip(LOAD_COLS, map(float, loads))),
               "step_s": step, "parameters": params or {}, "simulated_s": float(t[-1] - t[0]), "wall_s": wall,
               "final_cage_speed_rpm": float(res["cage_speed"][tail].mean() / RPM),
               "final_cage_shaft_ratio": float(res["cage_shaft_ratio"][tail].mean()),
               "final_cage_shaft_ratio_theory": float(res["cage_shaft_ratio_theory"][tail].mean()),
               "final_friction_torque_Nm": float(res["friction_torque"][tail].mean()),
               "final_heat_flux_W": float(res["heat_flux_total"][tail].mean()),
               "csv": str(csv_path), "plot": str(png)}
    (outd / "fmu_simulation_summary.json").write_text(json.dumps(summary, indent=1))
    return summary
