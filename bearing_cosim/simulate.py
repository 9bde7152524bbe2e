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
from bearing_core.models.dynamics import PROFILE_LOAD_COLUMNS as LOAD_COLS, read_profile

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
    # the profile's optional outer_speed_rpm column drives the outer ring (signed, rpm -> rad/s); the
    # displacement-coupling inputs are unused in load-driven mode: held at zero
    for name in [v.name for v in md.modelVariables if v.causality == "input" and v.name not in names]:
        names.append(name)
        if name == "outer_ring_speed" and prof_loads and "outer_speed_rpm" in prof_loads:
            cols.append(prof_loads["outer_speed_rpm"] * RPM)
        else:
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
    units = {v.name: (getattr(v, "unit", None) or "1") for v in md.modelVariables}
    with csv_path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["time [s]", "shaft_speed [rad/s]"] + [f"{k} [{units[k]}]" for k in outputs])
        speed = np.interp(res["time"], t, n * RPM)
        for i in range(len(res)):
            w.writerow([f"{res['time'][i]:.9g}", f"{speed[i]:.9g}"] + [f"{res[k][i]:.9g}" for k in outputs])
    speed = np.interp(res["time"], t, n * RPM)
    d = {"t": res["time"], "shaft_speed": speed, "cage_speed": res["cage_speed"],
         "pure_rolling_cage_speed": res["cage_shaft_ratio_theory"] * speed,
         # heat fluxes, friction torque and drive power are the FMU's step averages (energy-consistent,
         # free of the ball-pass aliasing of 1 ms samples); older FMUs without drive_power: torque x speed
         "friction_torque": res["friction_torque"],
         "P_drive": res["drive_power"] if "drive_power" in res.dtype.names else res["friction_torque"] * speed,
         "P_race_inner": res["heat_flux_race_inner"], "P_race_outer": res["heat_flux_race_outer"],
         "P_pocket": res["heat_flux_pocket"], "P_land": res["heat_flux_land"], "P_drag": res["heat_flux_drag"],
         "P_damping": res["heat_flux_damping"], "Fx": res["reaction_Fx"], "Fy": res["reaction_Fy"],
         "Fz": res["reaction_Fz"], "ball0_wr": res["ball0_omega_r"], "ball0_wt": res["ball0_omega_t"],
         "ball0_wz": res["ball0_omega_z"]}
    if "cage_speed_pure_rolling_outer" in res.dtype.names:
        d["cage_speed_pure_rolling_outer"] = res["cage_speed_pure_rolling_outer"]
        d["cage_speed_pure_rolling_inner"] = res["cage_speed_pure_rolling_inner"]
    png = plot_dynamics(d, outd / "fmu_simulation.png", title=f"bearing FMU via fmpy, profile {profile}, "
                                                              f"loads {tuple(loads)} N / N m, step {step:g} s "
                                                              "(powers, torque: step averages)")
    tail = res["time"] >= res["time"][-1] - 0.1
    fr_png, refs = plot_friction_references(res, speed, params or {}, outd / "fmu_friction.png", loads, prof_loads, t)
    summary = {"fmu": str(fmu), "profile": profile, "loads": dict(zip(LOAD_COLS, map(float, loads))),
               "step_s": step, "parameters": params or {}, "simulated_s": float(t[-1] - t[0]), "wall_s": wall,
               "final_window_s": 0.1,   # every final_* value is the mean over the run's last final_window_s
               "final_cage_speed_rpm": float(res["cage_speed"][tail].mean() / RPM),
               "final_cage_shaft_ratio": float(res["cage_shaft_ratio"][tail].mean()),
               "final_cage_shaft_ratio_theory": float(res["cage_shaft_ratio_theory"][tail].mean()),
               "final_friction_torque_Nm": float(res["friction_torque"][tail].mean()),
               "final_heat_flux_W": float(res["heat_flux_total"][tail].mean()),
               "csv": str(csv_path), "plot": str(png), "friction_plot": str(fr_png)}
    if "cage_speed_pure_rolling_outer" in res.dtype.names:
        from bearing_core.models.skid import SKID_LABELS, classify_skid
        wc = float(res["cage_speed"][tail].mean())
        wo = float(res["cage_speed_pure_rolling_outer"][tail].mean())
        st, slip = classify_skid(wc, wo)
        summary.update({"final_cage_speed_pure_rolling_outer_rpm": wo / RPM,
                        "final_cage_speed_pure_rolling_inner_rpm":
                            float(res["cage_speed_pure_rolling_inner"][tail].mean() / RPM),
                        "final_cage_slip_ratio": slip, "final_skid_state": SKID_LABELS[st]})
    if refs is not None:
        summary.update({"final_skf_friction_torque_Nm": float(refs["skf"][tail].mean()),
                        "final_palmgren_friction_torque_Nm": float(refs["palmgren"][tail].mean()),
                        "reference_viscosity_mm2_s": refs["nu_mm2s"], "reference_envelope": refs["envelope"]})
    if "thermal_runaway" in res.dtype.names:
        summary["thermal_runaway"] = bool(np.any(res["thermal_runaway"] > 0))
    (outd / "fmu_simulation_summary.json").write_text(json.dumps(summary, indent=1))
    return summary


HEAT_SOURCES = (("heat_flux_race_inner", "ball-inner race"), ("heat_flux_race_outer", "ball-outer race"),
                ("heat_flux_pocket", "ball-pocket"), ("heat_flux_land", "cage land"), ("heat_flux_drag", "ball drag"),
                ("heat_flux_churn_cage", "churning, cage"), ("heat_flux_churn_ring", "churning, inner ring"),
                ("heat_flux_damping", "contact damping"))


def plot_friction_references(res, speed, params, path, loads, prof_loads, t_prof):
    """Friction torque of the run next to the SKF (2004) and Palmgren estimates at the same speed, loads and
    oil viscosity (bearing_core.lubrication.friction_models; oil at the oil_temperature parameter), and the heat by
    source (stacked). Returns (png path, reference dict or None when the run is not oil-lubricated)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.lubrication.lubricants import TRACTION_OIL, get_oil
    from bearing_core.lubrication.friction_models import reference_torques

    tt = res["time"]
    lub = params.get("lubrication", "auto")
    oil_run = lub == "oil" or (lub == "auto" and params.get("traction_model", "lubricated") == "lubricated")
    refs = None
    fig, ax = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    ax[0].plot(tt, res["friction_torque"], lw=1, label="dynamics (FMU)")
    if oil_run:
        g = load_preset(params.get("bearing", "7218B"))
        oil = params.get("oil") or TRACTION_OIL.get(params.get("lubricant", "generic-mineral-oil"), "iso-vg32-mineral")
        T = float(params.get("oil_temperature", 313.15))
        nu = get_oil(oil).nu(T) * 1e6
        Fr = np.hypot(res["reaction_Fx"], res["reaction_Fy"])
        Fa = np.abs(res["reaction_Fz"])
        refs = reference_torques(g, speed / RPM, nu, Fr, Fa)
        refs["nu_mm2s"] = nu
        ax[0].plot(tt, refs["skf"], "--", lw=1.2, label="SKF model (2004), 72 B constants")
        ax[0].plot(tt, refs["palmgren"], ":", lw=1.5, label="Palmgren (f0 = 2)")
        ax[0].set_title(f"friction torque, {oil} at {T - 273.15:.0f} degC (nu = {nu:.1f} mm^2/s); "
                        f"d x D {refs['d_mm']:.0f} x {refs['D_mm']:.0f} mm ({refs['envelope']})", fontsize=8)
    else:
        ax[0].set_title(f"friction torque ({lub} lubrication: the oil-film references do not apply)", fontsize=8)
    ax[0].set_ylabel("torque [N m]")
    ax[0].legend(fontsize=8)
    base = np.zeros_like(tt)
    for k, lab in HEAT_SOURCES:
        if k in res.dtype.names:
            v = np.clip(res[k], 0.0, None)
            ax[1].fill_between(tt, base, base + v, label=lab, lw=0)
            base = base + v
    ax[1].set_ylabel("heat by source [W]")
    ax[1].set_xlabel("time [s]")
    ax[1].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path, refs
