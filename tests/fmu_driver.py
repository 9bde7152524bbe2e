"""Drive the bearing FMU with fmpy in a separate process (used by tests/test_fmu.py).

    python tests/fmu_driver.py SPEC.json   ->  prints one JSON line 'RESULT {...}' (FMU log lines before it)

A fresh process per run, which exits normally (C exit handlers run), so that the host's exit status is part
of what the tests check (docs/fmu.md). SPEC keys: fmu, mode ('run' | 'two' | 'rollback'), params,
start_inputs, steps ([[h, {inputs}], ...]), outputs (names).
"""
import json
import sys

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


def _open(spec, name, params, inputs0):
    md = read_model_description(spec["fmu"])
    vr = {v.name: v.valueReference for v in md.modelVariables}
    types = {v.name: v.type for v in md.modelVariables}
    enums = {v.name: v.declaredType for v in md.modelVariables if v.type == "Enumeration"}
    f = FMU2Slave(guid=md.guid, unzipDirectory=spec["_unzip"], modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=name)
    f.instantiate(loggingOn=True)
    f.setupExperiment(startTime=0.0)
    for k, v in params.items():
        if types[k] == "String":
            f.setString([vr[k]], [str(v)])
        elif types[k] == "Enumeration":   # by item name or value
            items = {it.name: int(it.value) for it in enums[k].items}
            f.setInteger([vr[k]], [items[v] if isinstance(v, str) else int(v)])
        elif types[k] == "Integer":
            f.setInteger([vr[k]], [int(v)])
        elif types[k] == "Boolean":
            f.setBoolean([vr[k]], [bool(v)])
        else:
            f.setReal([vr[k]], [float(v)])
    f.enterInitializationMode()
    f.setReal([vr[k] for k in inputs0], [float(v) for v in inputs0.values()])
    f.exitInitializationMode()
    return f, vr


def _step(f, vr, t, h, inputs, outputs):
    if inputs:
        f.setReal([vr[k] for k in inputs], [float(v) for v in inputs.values()])
    try:
        status = f.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        status = int(status) if status is not None else 0
    except Exception as e:  # fmpy raises for error statuses
        return {"status": "exception", "error": str(e)}
    return {"status": status, "values": f.getReal([vr[k] for k in outputs])}


def main():
    spec = json.load(open(sys.argv[1]))
    spec["_unzip"] = extract(spec["fmu"])
    out = {"rows": [], "init_error": None}
    try:
        f, vr = _open(spec, "bearing1", spec.get("params", {}), spec.get("start_inputs", {}))
    except Exception as e:
        out["init_error"] = str(e)
        print("RESULT " + json.dumps(out))
        return
    names = spec["outputs"]
    out["initial"] = f.getReal([vr[k] for k in names])
    mode = spec.get("mode", "run")
    t = 0.0
    if mode == "run":
        for h, inputs in spec["steps"]:
            r = _step(f, vr, t, h, inputs, names)
            out["rows"].append(r)
            if r["status"] == 0:
                t += h
    elif mode == "two":
        g, vr2 = _open(spec, "bearing2", spec.get("params", {}), spec["start_inputs_2"])
        rows2 = []
        for h, inputs in spec["steps"]:
            out["rows"].append(_step(f, vr, t, h, inputs, names))
            rows2.append(_step(g, vr2, t, h, spec["inputs_2"], names))
            t += h
        out["rows2"] = rows2
        g.terminate()
        g.freeInstance()
    elif mode == "rollback":
        (h, inputs) = spec["steps"][0]
        for _ in range(spec["n_before"]):
            _step(f, vr, t, h, inputs, names)
            t += h
        state = f.getFMUstate()
        a = [_step(f, vr, t + k * h, h, inputs, names) for k in range(spec["n_after"])]
        f.setFMUstate(state)
        b = [_step(f, vr, t + k * h, h, inputs, names) for k in range(spec["n_after"])]
        f.freeFMUstate(state)
        out["a"], out["b"] = a, b
    f.terminate()
    f.freeInstance()
    print("RESULT " + json.dumps(out))


if __name__ == "__main__":
    main()   # '--normal-exit' (bench/fmu_exit_check.py) is accepted: every exit is a normal one
