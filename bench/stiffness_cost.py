"""What the stiffness outputs cost per communication step, in the co-simulation session (docs/fidelity.md
"Stiffness"): interleaved runs with and without them, medians.

  * map (maps/7218B_oil.nc, 2800 rpm, Fx 1 kN, Fy 600 N, Fz 3.5 kN, 1 ms steps): the one-call step with the stiffness
    (map_kernels.map_step_stiffness) against map_step alone, inputs held and loads moving; wall time per step;
  * dynamic (7218B, lubricated, 3000 rpm, Fx 1 kN, Fz 3 kN, 1 ms steps): the step with the tangent stiffness against
    the step with it replaced by zeros (process CPU time), and the tangent stiffness's own call.

    python bench/stiffness_cost.py [--json OUT]
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))

RPM = math.pi / 30.0


def map_cost(reps: int = 7, n: int = 5000) -> dict:
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    import bearing_core.session.map_kernels as MK
    s = CoSimSession(CoSimParameters(fidelity="map", map_file=str(HERE.parent / "maps" / "7218B_oil.nc")))
    inp = {"shaft_speed": 2800 * RPM, "Fx": 1000.0, "Fy": 600.0, "Fz": 3500.0}
    s.initialize(0.0, inp)
    lvl = s.steady.level
    args_on, args_off = lvl.step_args, lvl.step_args[:-3]     # map_step_stiffness's three arguments last

    def run(on, moving):
        lvl.step_kernel, lvl.step_args = (MK.map_step_stiffness, args_on) if on else (MK.map_step, args_off)
        s.steady._fast = lvl.step_kernel
        t, q = s.t, dict(inp)
        a = time.perf_counter()
        for k in range(n):
            if moving:
                q["Fx"] = 1000.0 + 100.0 * math.sin(k * 1e-2)
            s.step(t, 1e-3, q)
            t += 1e-3
        return (time.perf_counter() - a) / n

    out = {}
    for moving in (False, True):
        on, off = [], []
        for _ in range(reps):
            on.append(run(True, moving))
            off.append(run(False, moving))
        out["moving" if moving else "held"] = {"with_us": 1e6 * float(np.median(on)),
                                               "without_us": 1e6 * float(np.median(off))}
    return out


def dynamic_cost(reps: int = 5, n: int = 40) -> dict:
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    d = CoSimSession(CoSimParameters(bearing="7218B"))
    inp = {"shaft_speed": 3000 * RPM, "Fx": 1000.0, "Fz": 3000.0}
    d.initialize(0.0, inp)
    tangent = d._tangent
    zero = np.zeros((5, 5))

    def run(on):
        d._tangent = tangent if on else (lambda m, diag0=None: zero)
        t = d.t
        a = time.process_time()
        for _ in range(n):
            d.step(t, 1e-3, inp)
            t += 1e-3
        return (time.process_time() - a) / n

    on, off = [], []
    for _ in range(reps):
        on.append(run(True))
        off.append(run(False))
    d._tangent = tangent
    m = d.model
    diag0 = m.evaluate_point()[0]
    a = time.process_time()
    for _ in range(200):
        tangent(m, diag0)
    return {"step_with_ms_cpu": 1e3 * float(np.median(on)), "step_without_ms_cpu": 1e3 * float(np.median(off)),
            "tangent_ms_cpu": 1e3 * (time.process_time() - a) / 200}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    from machine import machine_info, machine_line
    info = machine_info()
    print(machine_line(info))
    res = {"machine": info, "map": map_cost(), "dynamic": dynamic_cost()}
    print(json.dumps({k: v for k, v in res.items() if k != "machine"}, indent=1))
    if a.json:
        Path(a.json).write_text(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
