"""Run the bearing FMU in libcosim (Open Simulation Platform's C++ co-simulation master, via libcosimpy):
constant inputs, fixed step, prints 'RESULT {json}' with every output's time series. With "speeds" in the
spec (one shaft speed per step, rad/s) the speed is overridden before every step (held over the step)."""
import json
import sys

from fmpy import read_model_description
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimEnums import CosimVariableType
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimManipulator import CosimManipulator
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimSlave import CosimLocalSlave


def main():
    spec = json.load(open(sys.argv[1]))
    log_output_level(CosimLogLevel.WARNING)
    md = read_model_description(spec["fmu"])
    vr = {v.name: v.valueReference for v in md.modelVariables}
    ex = CosimExecution.from_step_size(step_size=int(round(spec["h"] * 1e9)))
    idx = ex.add_local_slave(local_slave=CosimLocalSlave(fmu_path=spec["fmu"], instance_name="bearing"))
    n = int(round(spec["t_end"] / spec["h"]))
    obs = CosimObserver.create_time_series(buffer_size=n + 10)
    ex.add_observer(observer=obs)
    for name in spec["outputs"]:
        obs.start_time_series(slave_index=idx, value_reference=vr[name], variable_type=CosimVariableType.REAL)
    for k, v in spec["inputs"].items():
        ex.real_initial_value(slave_index=idx, variable_reference=vr[k], value=float(v))
    if "speeds" in spec:
        manip = CosimManipulator.create_override()
        ex.add_manipulator(manipulator=manip)
        ok = True
        for w in spec["speeds"]:
            manip.slave_real_values(idx, [vr["shaft_speed"]], [float(w)])
            ok = ex.step() and ok
    else:
        ok = ex.simulate_until(target_time=int(round(spec["t_end"] * 1e9)))
    series = {}
    for name in spec["outputs"]:
        samples = obs.time_series_real_samples(slave_index=idx, value_reference=vr[name], from_step=0,
                                               sample_count=n + 1)
        series[name] = [float(v) for v in samples[2]]   # (times [ns], steps, values)
    print("RESULT " + json.dumps({"ok": bool(ok), "series": series}))


if __name__ == "__main__":
    main()
