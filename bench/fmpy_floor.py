"""The master's own cost per communication step, and that of the FMU's model process with a model that does nothing
(docs/fidelity.md, "Speed").

A steady fidelity level's target through fmpy (wall time per simulated second at 1 ms steps) includes fmpy's own
calls. With the call pattern of bench/fidelity_speed.py (per step setReal of 3 inputs, doStep, getReal of
--outputs outputs, through fmpy's FMU2Slave) this bench drives

  * floor: an FMI 2.0 co-simulation FMU built here with the C compiler whose functions only copy values (fmi2DoStep
    returns at once; no model, no process): the floor no FMU goes below in that master on this machine;
  * model process: a pythonfmu slave whose do_step does nothing, built on the bearing FMU's own FMI layer
    (bearing_cosim.fmu_build: the native layer and a model process per instance): the floor of that layer, the
    exchange with the model process and its request loop included.

A target under the first cannot be met on the machine; one under the second not with the model process's loop.

    python bench/fmpy_floor.py [--t-end 2] [--outputs 10] [--repeat 3] [--no-model-process] [--json OUT]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))
from machine import machine_info, machine_line  # noqa: E402

H = 1e-3
N_IN = 3
N_VARS = 13         # 3 inputs and the 10 outputs bench/fidelity_speed.py reads
HEADER = HERE.parent / "bearing_cosim" / "fmu_src" / "native" / "fmi2_min.h"

# every FMI 2.0 co-simulation function (fmpy binds them all at instantiation); values live in one array indexed by
# value reference
_C = r"""
#include <stdlib.h>
#include <string.h>
#include "fmi2_min.h"
#define NV %(nv)d
typedef struct { double r[NV]; double t; } Inst;
#define E FMI2_EXPORT
#define OKV(x) ((x) < NV)
E const char *fmi2GetTypesPlatform(void) { return "default"; }
E const char *fmi2GetVersion(void) { return "2.0"; }
E fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String cat[]) {
    (void)c; (void)on; (void)n; (void)cat; return fmi2OK; }
E fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid, fmi2String res,
                                const fmi2CallbackFunctions *cb, fmi2Boolean vis, fmi2Boolean log) {
    (void)name; (void)type; (void)guid; (void)res; (void)cb; (void)vis; (void)log;
    return calloc(1, sizeof(Inst)); }
E void fmi2FreeInstance(fmi2Component c) { free(c); }
E fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean td, fmi2Real tol, fmi2Real t0, fmi2Boolean sd,
                                 fmi2Real t1) { (void)td; (void)tol; (void)sd; (void)t1; ((Inst *)c)->t = t0;
    return fmi2OK; }
E fmi2Status fmi2EnterInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }
E fmi2Status fmi2ExitInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }
E fmi2Status fmi2Terminate(fmi2Component c) { (void)c; return fmi2OK; }
E fmi2Status fmi2Reset(fmi2Component c) { memset(c, 0, sizeof(Inst)); return fmi2OK; }
E fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real v[]) {
    for (size_t k = 0; k < n; k++) { if (!OKV(vr[k])) return fmi2Error; v[k] = ((Inst *)c)->r[vr[k]]; }
    return fmi2OK; }
E fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real v[]) {
    for (size_t k = 0; k < n; k++) { if (!OKV(vr[k])) return fmi2Error; ((Inst *)c)->r[vr[k]] = v[k]; }
    return fmi2OK; }
E fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer v[]) {
    (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
E fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Boolean v[]) {
    (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
E fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2String v[]) {
    (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
E fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer v[]) {
    (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
E fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Boolean v[]) {
    (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
E fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2String v[]) {
    (void)c; (void)vr; (void)v; return n ? fmi2Error : fmi2OK; }
E fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)c; (void)s; return fmi2Error; }
E fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) { (void)c; (void)s; return fmi2Error; }
E fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)c; (void)s; return fmi2Error; }
E fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t *n) {
    (void)c; (void)s; (void)n; return fmi2Error; }
E fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n) {
    (void)c; (void)s; (void)b; (void)n; return fmi2Error; }
E fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *s) {
    (void)c; (void)s; (void)b; (void)n; return fmi2Error; }
E fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu,
                                          const fmi2ValueReference z[], size_t nz, const fmi2Real dv[],
                                          fmi2Real dz[]) {
    (void)c; (void)u; (void)nu; (void)z; (void)nz; (void)dv; (void)dz; return fmi2Error; }
E fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                         const fmi2Integer o[], const fmi2Real v[]) {
    (void)c; (void)vr; (void)n; (void)o; (void)v; return fmi2Error; }
E fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                          const fmi2Integer o[], fmi2Real v[]) {
    (void)c; (void)vr; (void)n; (void)o; (void)v; return fmi2Error; }
E fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean noprior) {
    (void)noprior; ((Inst *)c)->t = t + h; return fmi2OK; }
E fmi2Status fmi2CancelStep(fmi2Component c) { (void)c; return fmi2Error; }
E fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *v) {
    (void)c; (void)s; (void)v; return fmi2Discard; }
E fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *v) {
    if (s != fmi2LastSuccessfulTime) return fmi2Discard; *v = ((Inst *)c)->t; return fmi2OK; }
E fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *v) {
    (void)c; (void)s; (void)v; return fmi2Discard; }
E fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *v) {
    (void)c; (void)s; (void)v; return fmi2Discard; }
E fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *v) {
    (void)c; (void)s; (void)v; return fmi2Discard; }
"""

_MD = """<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="Floor" guid="{00000000-0000-0000-0000-00000000f100}"
  generationTool="bench/fmpy_floor.py" variableNamingConvention="flat" numberOfEventIndicators="0">
  <CoSimulation modelIdentifier="Floor" canHandleVariableCommunicationStepSize="true"/>
  <ModelVariables>
%s
  </ModelVariables>
  <ModelStructure>
    <Outputs>
%s
    </Outputs>
  </ModelStructure>
</fmiModelDescription>
"""


def build(dest: Path) -> Path:
    """The do-nothing FMU in dest (compiled with $CC or gcc, -O2)."""
    cc = os.environ.get("CC", "gcc")
    if shutil.which(cc) is None:
        raise SystemExit(f"no C compiler ({cc}) on this machine")
    src = dest / "floor.c"
    src.write_text(_C % {"nv": N_VARS})
    so = dest / "Floor.so"
    subprocess.run([cc, "-std=gnu99", "-O2", "-shared", "-fPIC", "-fvisibility=hidden", "-I", str(HEADER.parent),
                    "-o", str(so), str(src)], check=True)
    sv = []
    for k in range(N_VARS):
        if k < N_IN:
            sv.append(f'    <ScalarVariable name="u{k}" valueReference="{k}" causality="input" variability="continuous">'
                      '<Real start="0"/></ScalarVariable>')
        else:
            sv.append(f'    <ScalarVariable name="y{k}" valueReference="{k}" causality="output" variability="continuous">'
                      '<Real/></ScalarVariable>')
    outs = "\n".join(f'      <Unknown index="{k + 1}"/>' for k in range(N_IN, N_VARS))
    fmu = dest / "Floor.fmu"
    with zipfile.ZipFile(fmu, "w") as z:
        z.writestr("modelDescription.xml", _MD % ("\n".join(sv), outs))
        z.write(so, "binaries/linux64/Floor.so")
    return fmu


# a pythonfmu slave with N_IN Real inputs and N_VARS - N_IN Real outputs that does nothing per step
_SLAVE = f"""
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real
from pythonfmu.enums import Fmi2Initial


class Idle(Fmi2Slave):
    author = "bearing-tribodynamics bench"
    description = "does nothing per step: the floor of the FMI layer and its model process"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        for k in range({N_VARS}):
            setattr(self, f"v{{k}}", 0.0)
            if k < {N_IN}:
                self.register_variable(Real(f"v{{k}}", causality=Fmi2Causality.input,
                                            variability=Fmi2Variability.continuous))
            else:
                self.register_variable(Real(f"v{{k}}", causality=Fmi2Causality.output,
                                            variability=Fmi2Variability.continuous, initial=Fmi2Initial.calculated))

    def do_step(self, current_time, step_size):
        return True
"""


def build_idle(dest: Path) -> Path:
    """The do-nothing pythonfmu slave on the bearing FMU's FMI layer (native layer, model process) in dest."""
    from bearing_cosim import fmu_build
    return fmu_build._build("Idle", {"idle_slave": _SLAVE}, "idle_slave", dest)


def step_loop(f, in_vr, out_vr, inputs, skip: int):
    """The master's loop of the speed benches (this one and bench/fidelity_speed.py) on fmpy's FMU2Slave f: per 1 ms
    step setReal of in_vr to inputs[k], doStep, getReal of out_vr. Returns the wall time [s] from step skip on (the
    start-up left out) and the times in doStep and in setReal + getReal over the same steps."""
    t_step = t_io = 0.0
    tw = time.perf_counter()
    for k in range(len(inputs)):
        if k == skip:
            t_step = t_io = 0.0
            tw = time.perf_counter()
        a = time.perf_counter()
        f.setReal(in_vr, inputs[k])
        b = time.perf_counter()
        f.doStep(currentCommunicationPoint=k * H, communicationStepSize=H)
        c = time.perf_counter()
        f.getReal(out_vr)
        d = time.perf_counter()
        t_step += c - b
        t_io += (b - a) + (d - c)
    return time.perf_counter() - tw, t_step, t_io


def floor_per_sim_s(fmu: Path, t_end: float, n_out: int) -> dict:
    """fmpy's FMU2Slave through t_end at 1 ms steps, the loop of bench/fidelity_speed.py (the first 0.1 s left
    out): wall time per simulated second, in doStep and in setReal + getReal apart. The inputs are the first N_IN
    variables and the outputs read the next n_out, by the model description's order."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(str(fmu))
    f = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(fmu)), modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="floor")
    f.instantiate()
    f.setupExperiment(startTime=0.0)
    f.enterInitializationMode()
    f.exitInitializationMode()
    ins = [v.valueReference for v in md.modelVariables if v.causality == "input"][:N_IN]
    outs = [v.valueReference for v in md.modelVariables if v.causality == "output"]
    in_vr = ins
    out_vr = [outs[k % len(outs)] for k in range(n_out)]
    n = int(round(t_end / H))
    skip = int(round(0.1 / H))
    inputs = [[1000.0 + k, 1000.0, 3000.0] for k in range(n)]
    wall, t_step, t_io = step_loop(f, in_vr, out_vr, inputs, skip)
    sim = (n - skip) * H
    f.terminate()
    f.freeInstance()
    return {"wall_per_sim_s": wall / sim, "doStep_per_sim_s": t_step / sim, "get_set_per_sim_s": t_io / sim,
            "outputs_read": n_out}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t-end", type=float, default=2.0)
    ap.add_argument("--outputs", type=int, default=10, help="outputs read per step through getReal")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-model-process", action="store_true", help="only the C FMU's floor")
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    # the first 0.1 s are left out (start-up): a shorter run measures nothing
    for name, v, ok, allowed in (("--t-end", a.t_end, math.isfinite(a.t_end) and 0.2 <= a.t_end <= 3600.0,
                                  "0.2 <= value <= 3600 s"),
                                 ("--outputs", a.outputs, 1 <= a.outputs <= 10000, "1 <= value <= 10000"),
                                 ("--repeat", a.repeat, 1 <= a.repeat <= 100, "1 <= value <= 100")):
        if not ok:
            ap.error(f"{name} = {v!r} is invalid; allowed: {allowed}")
    print(machine_line())
    runs = {"floor": [], "model_process": []}
    with tempfile.TemporaryDirectory(prefix="fmpy_floor_") as d:
        fmus = {"floor": build(Path(d))}
        if not a.no_model_process:
            os.environ.setdefault("BEARING_FMU_CACHE", str(Path(d) / "cache"))
            fmus["model_process"] = build_idle(Path(d))
        for _ in range(a.repeat):       # the two alternating: the machine's state changes within a session
            for key, fmu in fmus.items():
                r = floor_per_sim_s(fmu, a.t_end, a.outputs)
                runs[key].append(r)
                what = ("do-nothing C FMU" if key == "floor" else
                        "do-nothing slave on the bearing FMU's FMI layer and model process")
                print(f"fmpy, {what}: {r['wall_per_sim_s']:.4f} s per simulated s at 1 ms steps (doStep "
                      f"{r['doStep_per_sim_s']:.4f}, setReal of {N_IN} + getReal of {a.outputs} "
                      f"{r['get_set_per_sim_s']:.4f})")
    if a.json:
        Path(a.json).write_text(json.dumps({"machine": machine_info(), "runs": runs}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
