"""Run an SSP archive with two independent co-simulation masters, each in its own process:

    python ssp_examples/masters.py fmpy     SYSTEM.ssp OUT.npz [--stop-time T]
    python ssp_examples/masters.py libcosim SYSTEM.ssp OUT.npz [--stop-time T]

writes every connector's time series to OUT.npz (keys 'time' and 'component.connector', SI units) and prints
one line 'RESULT {json}' (wall time, number of samples), and exits normally. Every FMU of the examples, the
bearing and the helpers (speed ramp, rotor, motor, shaft, fan), runs on the bearing FMU's native FMI layer: the
model of each instance lives in a process of its own, so the master's process holds no Python of the FMUs and
nothing of theirs runs in its exit handlers (docs/fmu.md).

fmpy (0.3.32): fmpy.ssp.simulation.simulate_ssp, stock. It applies only its parameter_set argument (not the SSD's
ParameterBindings) and sets Real, Integer and Enumeration values (not String; bound Booleans would all become
true), so this runner reads the bindings with fmpy's own SSD reader (fmpy.ssp.ssd.read_ssd) and passes the Real and
Integer ones as simulate_ssp's parameter_set (names prefixed with the component, as it expects). The examples bind
the bearing's choices as Integer values of its Enumeration parameters (bearing_preset, coupling_choice) and, for
libcosim, also as their String twins; a String binding is accepted only if it equals the FMU's start value or the
item a bound Enumeration of the same component selects (so the FMU as built runs unchanged). Its loop is Jacobi (all FMUs step, then values are exchanged), its connector
values start at 0 (every connected input is 0 during the first step) and its result row k holds the values at
t_k + h under the label t_k: we relabel to t_k + h.

libcosim (libcosimpy 0.0.6, Open Simulation Platform, C++): CosimExecution.from_ssp_file; applies the bindings
(all types) as start values, takes the step from the OSP FixedStepAlgorithm annotation, propagates initial
outputs to connected inputs during initialisation (N iterations), then steps Jacobi-style.
"""
from __future__ import annotations

import json
import os
import sys
import tempfile
import time
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np

NS = {"ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
      "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
      "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
      "osp": "http://opensimulationplatform.com/SSP/OSPAnnotations"}


def ssd_info(ssp) -> dict:
    """Components (source, connectors, bound parameters), start/stop time and master step of an SSP archive."""
    with zipfile.ZipFile(ssp) as z:
        root = ET.fromstring(z.read("SystemStructure.ssd"))
    comps = {}
    for c in root.findall("ssd:System/ssd:Elements/ssd:Component", NS):
        conns = [(k.get("name"), k.get("kind")) for k in c.findall("ssd:Connectors/ssd:Connector", NS)]
        params = {}
        for p in c.findall(".//ssv:Parameter", NS):
            v = list(p)[0]
            params[p.get("name")] = (v.tag.split("}")[1], v.get("value"))
        comps[c.get("name")] = {"source": c.get("source"), "connectors": conns, "parameters": params}
    de = root.find("ssd:DefaultExperiment", NS)
    alg = root.find(".//osp:FixedStepAlgorithm", NS)
    return {"components": comps, "start": float(de.get("startTime", 0.0)), "stop": float(de.get("stopTime")),
            "step": float(alg.get("baseStepSize"))}


def run_fmpy(ssp, stop_time=None) -> dict:
    from fmpy import read_model_description
    from fmpy.ssp.simulation import simulate_ssp
    from fmpy.ssp.ssd import Parameter, ParameterSet, find_components, read_ssd

    info = ssd_info(ssp)
    ssd = read_ssd(str(ssp))                       # validates against the SSP 1.0 schema
    params = []
    with tempfile.TemporaryDirectory() as td:
        zipfile.ZipFile(ssp).extractall(td)
        for comp in find_components(ssd.system):
            md = read_model_description(os.path.join(td, comp.source), validate=False)
            start = {v.name: v.start for v in md.modelVariables}
            mv = {v.name: v for v in md.modelVariables}
            bound = [p for b in comp.parameterBindings for ps in b.parameterValues for p in ps.parameters]
            chosen = {it.name for p in bound if p.name in mv and mv[p.name].type == "Enumeration"
                      for it in mv[p.name].declaredType.items if str(it.value) == str(p.value)}
            for binding in comp.parameterBindings:
                for pset in binding.parameterValues:
                    for p in pset.parameters:
                        if p.type in ("Real", "Integer"):
                            params.append(Parameter(name=f"{comp.name}.{p.name}", type=p.type, value=p.value))
                        elif str(start.get(p.name)) != str(p.value) and str(p.value) not in chosen:
                            raise ValueError(f"{comp.name}.{p.name} = {p.value!r} ({p.type}) cannot be set by "
                                             f"fmpy's simulate_ssp and differs from the FMU's start value "
                                             f"{start.get(p.name)!r}")
    h = info["step"]
    t_end = info["stop"] if stop_time is None else float(stop_time)
    res = simulate_ssp(str(ssp), start_time=info["start"], stop_time=t_end - 0.5 * h, step_size=h,
                       parameter_set=ParameterSet(parameters=params))
    out = {"time": np.asarray(res["time"]) + h}
    for name in res.dtype.names[1:]:
        out[name] = np.asarray(res[name], dtype=float)
    return out


def run_libcosim(ssp, stop_time=None) -> dict:
    from libcosimpy.CosimEnums import CosimVariableType
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    info = ssd_info(ssp)
    log_output_level(CosimLogLevel.WARNING)
    ex = CosimExecution.from_ssp_file(str(ssp))
    h = info["step"]
    t_end = info["stop"] if stop_time is None else float(stop_time)
    n = int(round((t_end - info["start"]) / h))
    obs = CosimObserver.create_time_series(buffer_size=n + 10)
    ex.add_observer(observer=obs)
    watch = []
    for cname, comp in info["components"].items():
        idx = ex.slave_index_from_instance_name(cname)
        refs = {v.name.decode(): v.reference for v in ex.slave_variables(idx)}
        for name, kind in comp["connectors"]:
            if kind == "output":
                obs.start_time_series(slave_index=idx, value_reference=refs[name],
                                      variable_type=CosimVariableType.REAL)
                watch.append((f"{cname}.{name}", idx, refs[name]))
    ok = ex.simulate_until(target_time=int(round(t_end * 1e9)))
    if not ok:
        raise RuntimeError("libcosim: simulate_until failed")
    out = {}
    for key, idx, ref in watch:
        # from step 1: libcosimpy 0.0.6 trims its sample lists by counting zero step numbers, so a step-0 sample
        # would cost the last sample
        tp, steps, vals = obs.time_series_real_samples(slave_index=idx, value_reference=ref, from_step=1,
                                                       sample_count=n + 5)
        t = np.asarray(tp, dtype=float) * 1e-9
        keep = t > info["start"] + 0.5 * h           # step results only (from t0 + h), like the fmpy rows
        out.setdefault("time", t[keep])
        out[key] = np.asarray(vals, dtype=float)[keep]
    m = min(len(v) for v in out.values())
    return {k: v[:m] for k, v in out.items()}


def run_subprocess(master, ssp, dest, stop_time=None, env=None, timeout=900):
    """Run one master on one SSP in a fresh Python process; returns (summary dict, arrays dict, exit status).
    The process's exit status is part of what callers check (docs/fmu.md)."""
    import subprocess
    cmd = [sys.executable, str(Path(__file__).resolve()), master, str(ssp), str(dest)]
    if stop_time is not None:
        cmd += ["--stop-time", repr(float(stop_time))]
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=timeout)
    lines = [ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")]
    if r.returncode != 0 or not lines:
        raise RuntimeError(f"{master} on {ssp} failed (exit {r.returncode}):\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    data = np.load(dest)
    return json.loads(lines[-1][7:]), {k: data[k] for k in data.files}, r.returncode


def main(argv):
    master, ssp, dest = argv[0], argv[1], argv[2]
    stop = float(argv[argv.index("--stop-time") + 1]) if "--stop-time" in argv else None
    t0 = time.perf_counter()
    res = {"fmpy": run_fmpy, "libcosim": run_libcosim}[master](ssp, stop)
    wall = time.perf_counter() - t0
    np.savez(dest, **res)
    print("RESULT " + json.dumps({"master": master, "wall_s": wall, "samples": int(len(res["time"])),
                                  "t_end": float(res["time"][-1])}))


if __name__ == "__main__":
    main(sys.argv[1:])
