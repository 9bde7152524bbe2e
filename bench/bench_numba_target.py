"""Precompiled targets against host-tuned numba kernels: the FMU's precompiled kernels are built for x86-64-v3
(AVX2, FMA) and for numba's generic target (any x86-64 processor; bearing_cosim.fmu_build.PRECOMPILE_TARGETS);
this measures what each costs against kernels compiled for the processor at hand.

Each target runs in fresh processes with its own numba cache (warmed by a first process): a CoSimSession with
default parameters and inputs (7218B, 3000 rpm, Fx 1 kN, Fz 3 kN, lubricated, integrator 'auto') steps
--steps x 1 ms; reported is the median wall time per step and each target's ratio to host (> 1: slower). The
targets alternate --repeat times so that load on a shared machine affects them alike.

    python bench/bench_numba_target.py [--steps 200] [--repeat 3] [--json]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

WORKER = r"""
import json, sys, time
import numpy as np
sys.path.insert(0, sys.argv[2])
from bearing_core.session.cosim import CoSimParameters, CoSimSession
from bearing_core.session.cosim_spec import INPUT_NAMES
sys.path.insert(0, sys.argv[3])
from bearing_fmu import INPUT_START
n = int(sys.argv[1])
inputs = {k: INPUT_START.get(k, 0.0) for k in INPUT_NAMES}
s = CoSimSession(CoSimParameters())
s.initialize(0.0, inputs)
s.step(0.0, 1e-3, inputs)
walls = []
for k in range(1, n + 1):
    a = time.perf_counter()
    s.step(k * 1e-3, 1e-3, inputs)
    walls.append(time.perf_counter() - a)
print("RESULT", json.dumps({"median_step_s": float(np.median(walls)), "cage": float(s.outputs["cage_speed"])}))
"""


def run(target: str, cache: Path, steps: int) -> dict:
    from bearing_cosim.fmu_build import PRECOMPILE_TARGETS
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env["NUMBA_CACHE_DIR"] = str(cache)
    for t in PRECOMPILE_TARGETS:
        if t["name"] == target:
            env.update(NUMBA_CPU_NAME=t["name"], NUMBA_CPU_FEATURES=t["features"])
    r = subprocess.run([sys.executable, "-c", WORKER, str(steps), str(ROOT), str(ROOT / "bearing_cosim" / "fmu_src")],
                       capture_output=True, text=True, env=env)
    if r.returncode != 0:
        raise RuntimeError(r.stderr[-2000:])
    return json.loads(r.stdout.split("RESULT", 1)[1])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    targets = ("host", "x86-64-v3", "generic")
    with tempfile.TemporaryDirectory(prefix="bench_target_") as td:
        caches = {t: Path(td) / t for t in targets}
        for t, c in caches.items():
            run(t, c, 2)                                   # compile into this target's cache
        res = {t: [] for t in targets}
        for _ in range(a.repeat):
            for t in targets:
                res[t].append(run(t, caches[t], a.steps)["median_step_s"])
    best = {t: min(v) for t, v in res.items()}
    out = {f"{t}_step_ms": best[t] * 1e3 for t in targets}
    out.update({f"{t}_over_host": best[t] / best["host"] for t in targets[1:]}, runs=res)
    if a.json:
        print(json.dumps(out))
    else:
        print(f"median wall per 1 ms step (best of {a.repeat}): " + ", ".join(f"{t} {best[t] * 1e3:.3f} ms"
                                                                           for t in targets)
              + "; " + ", ".join(f"{t} / host {out[f'{t}_over_host']:.3f}" for t in targets[1:]))
    return out


if __name__ == "__main__":
    main()
