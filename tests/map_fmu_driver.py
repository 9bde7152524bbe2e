"""Drive an FMU step by step with fmpy's FMU2Slave (the statuses of every call kept, never raised) and the input
sequences of the map FMU's equality tests: ramps, rotating radial loads, the map's range edges and refusals."""
from __future__ import annotations

import math
import re
import shutil
import tempfile

import numpy as np

RPM = math.pi / 30.0


def run_fmu(fmu: str, start: dict, rows: list, h: float = 1e-3, outputs=None, t0: float = 0.0):
    """Instantiate fmu, set the start values (by type), initialise at rows[0]'s inputs and step once per later row.
    rows: list of {input name: value}. Returns {'init': status, 'status': [per step], 'out': array (steps + 1, n),
    'names': output names, 'logs': [(status, message)] per call index (-1 init), 'ints': integer output names}."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(fmu)
    vars_ = {v.name: v for v in md.modelVariables}
    outs = outputs or [v.name for v in md.modelVariables if v.causality == "output"]
    real_out = [vars_[n].valueReference for n in outs if vars_[n].type == "Real"]
    int_out = [vars_[n].valueReference for n in outs if vars_[n].type == "Integer"]
    order = [n for n in outs if vars_[n].type == "Real"] + [n for n in outs if vars_[n].type == "Integer"]
    logs = []
    where = [-1]

    def logger(env, name, status, category, message):
        logs.append((where[0], int(status), message.decode("utf-8", "replace")))

    from ctypes import c_char_p, c_double, c_int, c_uint
    from fmpy.fmi2 import (fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE, fmi2CallbackFunctions,
                           fmi2CallbackLoggerTYPE, fmi2StepFinishedTYPE, calloc, free)
    unz = extract(fmu, tempfile.mkdtemp(prefix="mapfmu_drv_"))
    s = FMU2Slave(guid=md.guid, unzipDirectory=unz, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="drv")
    cb = fmi2CallbackFunctions()
    cb.logger = fmi2CallbackLoggerTYPE(logger)
    cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
    cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
    cb.stepFinished = fmi2StepFinishedTYPE()
    s.instantiate(callbacks=cb)

    from ctypes import c_void_p
    comp = c_void_p(s.component)

    def call(fn, *a):     # the raw C function: fmpy's wrappers raise on a status above Warning
        return int(getattr(s.dll, fn)(comp, *a))

    inp = [v.name for v in md.modelVariables if v.causality == "input"]
    in_vr = (c_uint * len(inp))(*[vars_[n].valueReference for n in inp])

    def set_inputs(row):
        vals = (c_double * len(inp))(*[float(row.get(n, 0.0)) for n in inp])
        return call("fmi2SetReal", in_vr, len(inp), vals)

    def read():
        a = (c_double * len(real_out))()
        b = (c_int * max(1, len(int_out)))()
        st1 = call("fmi2GetReal", (c_uint * len(real_out))(*real_out), len(real_out), a)
        st2 = call("fmi2GetInteger", (c_uint * len(int_out))(*int_out), len(int_out), b) if int_out else 0
        return max(st1, st2), list(a) + list(b)[:len(int_out)]

    st = call("fmi2SetupExperiment", 0, c_double(0.0), c_double(t0), 0, c_double(0.0))
    st = max(st, call("fmi2EnterInitializationMode"))
    for k, v in start.items():
        vr = (c_uint * 1)(vars_[k].valueReference)
        t = vars_[k].type
        if t == "Real":
            st = max(st, call("fmi2SetReal", vr, 1, (c_double * 1)(float(v))))
        elif t in ("Integer", "Enumeration"):
            st = max(st, call("fmi2SetInteger", vr, 1, (c_int * 1)(int(v))))
        elif t == "Boolean":
            st = max(st, call("fmi2SetBoolean", vr, 1, (c_int * 1)(int(bool(v)))))
        else:
            st = max(st, call("fmi2SetString", vr, 1, (c_char_p * 1)(str(v).encode())))
    set_inputs(rows[0])
    init = call("fmi2ExitInitializationMode")
    statuses, out = [], []
    if init <= 1:
        out.append(read()[1])
        t = t0
        for i, row in enumerate(rows[1:]):
            where[0] = i
            set_inputs(row)
            stt = call("fmi2DoStep", c_double(t), c_double(h), 1)
            statuses.append(stt)
            if stt <= 1:
                t += h
            out.append(read()[1])
    call("fmi2Terminate")
    s.freeInstance()
    shutil.rmtree(unz, ignore_errors=True)
    return {"init": init, "status": statuses, "out": np.array(out), "names": order, "logs": logs}


def scenario(ranges: dict, n: int = 320, seed: int = 0, rotate: bool = True, extra_axes=None) -> list:
    """Input rows inside and at the edges of the map's ranges {input: (lo, hi)}, with ramps of the shaft speed,
    rotating radial loads, exact range edges and refused inputs (outside the map, NaN, a moment the map does not
    vary, a turning outer ring), then back inside."""
    rng = np.random.default_rng(seed)
    w_lo, w_hi = ranges["shaft_speed"]
    fx_lo, fx_hi = ranges["Fx"]
    fz_lo, fz_hi = ranges["Fz"]
    rows = []
    mid = {"shaft_speed": 0.5 * (w_lo + w_hi), "Fx": 0.5 * (fx_lo + fx_hi), "Fz": 0.5 * (fz_lo + fz_hi)}
    rows.append(dict(mid))
    for k in range(n):
        phase = k % 8
        r = dict(rows[-1]) if rows else dict(mid)
        for key in ("Mx", "outer_ring_speed"):
            r.pop(key, None)
        if phase in (0, 1, 2):      # a ramp of the shaft speed
            r["shaft_speed"] = float(np.clip(r.get("shaft_speed", mid["shaft_speed"])
                                             + rng.normal(0.0, 0.08) * (w_hi - w_lo), w_lo, w_hi))
        elif phase == 3:            # a rotating radial load
            fr = rng.uniform(fx_lo, fx_hi)
            th = rng.uniform(0, 2 * math.pi)
            if rotate:
                r["Fx"], r["Fy"] = fr * math.cos(th), fr * math.sin(th)
            else:
                r["Fx"] = fr
            r["Fz"] = rng.uniform(fz_lo, fz_hi)
        elif phase == 4:            # range edges exactly
            r["shaft_speed"] = float(rng.choice([w_lo, w_hi]))
            r["Fz"] = float(rng.choice([fz_lo, fz_hi]))
            r["Fx"], r["Fy"] = float(rng.choice([fx_lo, fx_hi])), 0.0
        elif phase == 5:            # refusals
            kind = k // 8 % 6
            if kind == 0:
                r["shaft_speed"] = w_hi * 1.05 + 1.0
            elif kind == 1:
                r["Fz"] = float("nan")
            elif kind == 2:
                r["Mx"] = 12.5
            elif kind == 3:
                r["outer_ring_speed"] = 3.0
            elif kind == 4:
                r["Fz"] = fz_lo - 0.1 * (fz_hi - fz_lo) - 1.0
            else:
                r["Fx"], r["Fy"] = fx_hi * 0.9, fx_hi * 0.9     # radial load above the map
        else:                       # random point inside
            r["shaft_speed"] = rng.uniform(w_lo, w_hi)
            r["Fz"] = rng.uniform(fz_lo, fz_hi)
            if extra_axes:
                for name, (lo, hi) in extra_axes.items():
                    r[name] = rng.uniform(lo, hi)
        rows.append(r)
    return rows


_PATH = re.compile(r"(operating map|the map|the map's range,) (\S+?)(;| \(| was| has|$)")


def normalise(msg: str) -> str:
    """A message with the map's file path replaced (the two FMUs read the map from different files)."""
    return _PATH.sub(lambda m: f"{m.group(1)} <map>{m.group(3)}", msg)
