"""The bearing FMU as a sweep model (`bearing sweep --model fmu --fmu FILE`), driven by fmpy.

One FMU instance per worker process: the FMU is unpacked once per process (the first point that needs it) and
instantiated once (again only after a point failed inside the FMU); between points it is reset with fmi2Reset, its parameters are set again, and it is
initialised at the point's speed and loads. The run then steps (communication step options['step_s'], default
1e-3 s) in windows of options['window_s'] until steady by the criterion of bearing_core.maps.sweep.DynamicWindow:
between two consecutive windows the window mean of the cage speed changes by less than options['steady_tol'] and
that of the friction torque by less than options['torque_tol'] (relative; torque plus 1e-6 N m), at most options['max_time_s']
simulated. The pure-rolling cage speed is the FMU's output cage_speed_pure_rolling_outer (outer raceway control at
each loaded ball's contact angles), as for the other models (bearing_core.models.skid).

Registered in bearing_core.maps.sweep.PLUGINS as 'fmu' -> 'bearing_cosim.fmu_sweep:FMUEvaluator'.
"""
from __future__ import annotations

import hashlib
import math
import shutil
import tempfile
import threading
from pathlib import Path

from bearing_core.errors import BearingInputError
from bearing_core.maps.sweep import RPM, DynamicWindow, _CAGE, _COMMON, _TRIBO, _ratio

# per-process FMU instances, keyed by the FMU file's content hash (one worker process = one instance)
_INSTANCES: dict = {}
_LOCK = threading.Lock()


class _Instance:
    """An unpacked, instantiated FMU (fmpy FMU2Slave) reused for every point this process evaluates."""

    def __init__(self, path: str):
        from fmpy import extract, read_model_description
        from fmpy.fmi2 import FMU2Slave
        self.md = read_model_description(path)
        self.unzipdir = extract(path, unzipdir=tempfile.mkdtemp(prefix="bearing_fmu_sweep_"))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.types = {v.name: v.type for v in self.md.modelVariables}
        self.fmu = FMU2Slave(guid=self.md.guid, unzipDirectory=self.unzipdir,
                             modelIdentifier=self.md.coSimulation.modelIdentifier, instanceName="sweep")
        self.fmu.instantiate(loggingOn=False)
        self.used = False
        self.points = 0
        self.unpacks = 1

    def close(self):
        try:
            self.fmu.terminate()
            self.fmu.freeInstance()
        finally:
            shutil.rmtree(self.unzipdir, ignore_errors=True)

    def _set(self, name, value):
        t = self.types[name]
        if t == "String":
            self.fmu.setString([self.vr[name]], [str(value)])
        elif t == "Boolean":
            self.fmu.setBoolean([self.vr[name]], [bool(value)])
        else:
            self.fmu.setReal([self.vr[name]], [float(value)])

    def run(self, point: dict, options: dict) -> dict:
        f = self.fmu
        b = str(point["bearing"])
        if b.lower().endswith(".json"):
            raise BearingInputError("bearing", b, "a preset name for the FMU model (it takes no bearing file)")
        if self.used:
            f.reset()                      # fmi2Reset: back to the instantiated state, parameters settable
        self.used = True
        self.points += 1
        pc, lc = point["pocket_clearance_mm"], point["land_clearance_mm"]
        params = {"bearing": b, "traction_model": point["traction"], "friction_coefficient": point["mu"],
                  "cage_friction_coefficient": point["mu_cage"], "oil": point["oil"],
                  "oil_fraction": point["oil_fraction"], "oil_temperature": point["oil_temperature_C"] + 273.15,
                  "pocket_clearance": 0.0 if math.isnan(pc) else pc * 1e-3,
                  "land_clearance": 0.0 if math.isnan(lc) else lc * 1e-3}
        if "integrator" in options:
            params["integrator"] = options["integrator"]
        for k, v in params.items():
            self._set(k, v)
        f.setupExperiment(startTime=0.0)
        f.enterInitializationMode()
        w = point["speed_rpm"] * RPM
        loads = (point["fx_N"], point["fy_N"], point["fz_N"] + point["preload_N"], point["mx_Nm"], point["my_Nm"])
        names = ("shaft_speed", "Fx", "Fy", "Fz", "Mx", "My")
        f.setReal([self.vr[n] for n in names], [w, *map(float, loads)])
        f.exitInitializationMode()
        h = float(options.get("step_s", 1e-3))
        win = float(options.get("window_s", 0.02))
        t_max = float(options.get("max_time_s", 1.0))
        tol = float(options.get("steady_tol", 2e-3))
        ttol = float(options.get("torque_tol", 0.05))
        outs = ("cage_speed", "friction_torque", "heat_flux_total", "alpha_i_mean", "alpha_o_mean", "Q_i_max",
                "max_contact_pressure", "cage_speed_pure_rolling_outer")
        ovr = [self.vr[n] for n in outs]
        n_win = max(1, round(win / h))
        t, prev, steady = 0.0, None, False
        while t < t_max - 1e-12:
            acc = [0.0] * len(outs)
            for _ in range(n_win):
                f.doStep(currentCommunicationPoint=t, communicationStepSize=h)
                t += h
                for k, v in enumerate(f.getReal(ovr)):
                    acc[k] += v / n_win
            s = dict(zip(outs, acc))
            if prev is not None:
                dc = abs(s["cage_speed"] - prev["cage_speed"]) <= tol * abs(s["cage_speed"])
                dt = abs(s["friction_torque"] - prev["friction_torque"]) <= ttol * abs(s["friction_torque"]) + 1e-6
                if dc and dt:
                    steady = True
                    break
            prev = s
        pure = s["cage_speed_pure_rolling_outer"]
        return {"cage_speed_rpm": s["cage_speed"] / RPM, "pure_rolling_cage_speed_rpm": pure / RPM,
                "cage_speed_ratio": _ratio(s["cage_speed"], pure), "friction_torque_Nm": s["friction_torque"],
                "heat_W": s["heat_flux_total"], "alpha_i_deg": math.degrees(s["alpha_i_mean"]),
                "alpha_o_deg": math.degrees(s["alpha_o_mean"]), "Q_i_N": s["Q_i_max"],
                "p_max_Pa": s["max_contact_pressure"], "steady": steady, "settle_time_s": t}


def _instance(path: str) -> _Instance:
    key = hashlib.sha256(Path(path).read_bytes()).hexdigest()
    inst = _INSTANCES.get(key)
    if inst is None:
        inst = _INSTANCES[key] = _Instance(path)
    return inst


class FMUEvaluator(DynamicWindow):
    """The FMU at held speed and loads until steady (module docstring). options: fmu (file), step_s, window_s,
    max_time_s, steady_tol, integrator."""

    name = "fmu"
    uses = ("speed_rpm",) + _COMMON + _TRIBO + _CAGE
    min_speed_rpm = 10.0
    option_names = ("fmu", "step_s", "window_s", "max_time_s", "steady_tol", "torque_tol", "integrator")

    def validate_options(self, o):
        from bearing_core.errors import check_range
        super().validate_options(o)
        f = o.get("fmu")
        if not f or not Path(f).is_file():
            raise BearingInputError("fmu", f, "an existing FMU file (build it with: python build_fmu.py)")
        h = check_range("step_s", o.get("step_s", 1e-3), 1e-5, 0.1, unit="s")
        if h > o.get("window_s", 0.02):
            raise BearingInputError("step_s", h, f"<= window_s = {o.get('window_s', 0.02)} s")
        try:
            import fmpy  # noqa: F401
        except ImportError as e:
            raise BearingInputError("model", "fmu", "a host with fmpy installed", str(e))

    def __call__(self, point, options):
        with _LOCK:
            inst = _instance(options["fmu"])
            try:
                return inst.run(point, options)
            except BearingInputError:
                raise                      # refused before the FMU was touched
            except Exception:
                # an FMU left in an error state is not reused: the next point unpacks a fresh one
                for k, v in list(_INSTANCES.items()):
                    if v is inst:
                        del _INSTANCES[k]
                try:
                    inst.close()
                except Exception:
                    pass
                raise
