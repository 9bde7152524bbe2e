"""Throughput of two bearing FMU instances stepped from two threads of one fmpy master, against one instance
stepped alone (each instance runs its model in its own process, so two instances can use two cores).

    python bench/bench_fmu_parallel.py [--fmu dist/BearingFMU.fmu] [--steps 150] [--repeat 3] [--json]

Each repetition runs in a fresh fmpy process: a warm-up instance steps once through the same steps (kernels
compiled into the FMU cache), then instance c alone (time t_one), then instances a and b from two threads at
once (time t_two), default parameters and inputs at 1 ms steps. Throughput ratio = 2 t_one / t_two (2 = two
cores fully used, 1 = serialised). Wall time; the machine (bench/machine.py) is printed and under "machine".
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
from machine import machine_info, machine_line  # noqa: E402

WORKER = r"""
import json, sys, threading, time
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
path, n = sys.argv[1], int(sys.argv[2])
md = read_model_description(path)
vr = {v.name: v.valueReference for v in md.modelVariables}
unz = extract(path)
def make(name):
    f = FMU2Slave(guid=md.guid, unzipDirectory=unz, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=name)
    f.instantiate(); f.setupExperiment(startTime=0.0); f.enterInitializationMode(); f.exitInitializationMode()
    for k in range(5):
        f.doStep(k * 1e-3, 1e-3)
    return f
def run(f, out):
    for k in range(5, 5 + n):
        f.doStep(k * 1e-3, 1e-3)
        out.append(f.getReal([vr["cage_speed"]])[0])
w = make("w"); run(w, []); w.terminate(); w.freeInstance()
fs = [make("a"), make("b")]
c = make("c")
one = []
t0 = time.perf_counter(); run(c, one); t_one = time.perf_counter() - t0
c.terminate(); c.freeInstance()
res = [[], []]
th = [threading.Thread(target=run, args=(f, r)) for f, r in zip(fs, res)]
t0 = time.perf_counter()
for t in th: t.start()
for t in th: t.join()
t_two = time.perf_counter() - t0
for f in fs: f.terminate(); f.freeInstance()
print("RESULT", json.dumps({"t_one": t_one, "t_two": t_two, "same": res[0] == res[1] == one}))
"""


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fmu", default=None, help="FMU to drive (default: build one into a temporary folder)")
    ap.add_argument("--steps", type=int, default=150, help="1 ms steps per instance")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cache", default=None, help="FMU cache folder (BEARING_FMU_CACHE; default: a new one)")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="bench_fmu_par_") as tmp:
        fmu = a.fmu
        if fmu is None:
            from bearing_cosim.fmu_build import build
            fmu = str(build(Path(tmp) / "dist"))
        env = dict(os.environ, BEARING_FMU_CACHE=a.cache or str(Path(tmp) / "cache"))
        runs = []
        for _ in range(a.repeat):
            p = subprocess.run([sys.executable, "-c", WORKER, fmu, str(a.steps)], capture_output=True, text=True,
                               env=env, timeout=1800)
            if p.returncode != 0 or "RESULT" not in p.stdout:
                raise RuntimeError(f"worker failed ({p.returncode}): {p.stderr[-2000:]}")
            r = json.loads(p.stdout.split("RESULT", 1)[1])
            r["ratio"] = 2 * r["t_one"] / r["t_two"]
            runs.append(r)
    out = {"machine": machine_info(), "steps": a.steps, "runs": runs,
           "ratio_median": statistics.median(r["ratio"] for r in runs),
           "identical_results": all(r["same"] for r in runs)}
    if a.json:
        print(json.dumps(out))
    else:
        print(machine_line())
        for r in runs:
            print(f"one instance {r['t_one']:.3f} s, two from two threads {r['t_two']:.3f} s: ratio {r['ratio']:.2f}")
        print(f"median ratio {out['ratio_median']:.2f}; identical results: {out['identical_results']}")
    return out


if __name__ == "__main__":
    main()
