"""Paired comparison of two builds of the bearing FMU in one fmpy master: the per-step overhead of B against A.

Both FMUs are instantiated in the same master process with the default parameters and inputs (7218B, 3000 rpm,
Fx 1000 N, Fz 3000 N, lubricated, integrator 'auto') and stepped alternately at 1 ms communication steps, in the
order A B B A A B B A ... so that neither always goes first (--block N: N steps of one, then N of the other, so
that each steps back to back as when alone; the first step of each block is left out). Both integrate the same model with the same
arithmetic, so the time integration costs each the same at every step, and the difference of their wall times at
the same step (doStep plus a getReal of three outputs) is the difference of their per-step overheads: the FMI
layer, the exchange with a model process, the session's Python. Host noise that drifts over seconds (other
virtual machines, frequency changes) hits both members of a pair alike and cancels in the difference, which a
comparison of separate runs cannot do on a shared machine.

Reports per run the median wall time per step of each FMU and the median of the paired differences B - A with a
bootstrap 95 % interval; with --repeat, fresh master processes, and the pooled figures. The outputs of A and B
are compared at the end of each run (they integrate the same model; a difference means the builds differ in
physics, and the comparison is then of different work).

    python bench/bench_fmu_ab.py --fmu-a OLD.fmu --fmu-b NEW.fmu [--a-path DIR] [--cache DIR] [--t-end 0.2]
        [--block 1] [--repeat 5] [--json]

--a-path DIR puts DIR first on the master's sys.path, for an FMU whose layer runs Python in the master's
interpreter and imports our package from there (the in-process layer of earlier builds).
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from machine import machine_info, machine_line  # noqa: E402

H = 1e-3


def _open(fmu: str, name: str):
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(fmu)
    unz = extract(fmu)
    f = FMU2Slave(guid=md.guid, unzipDirectory=unz, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName=name)
    f.instantiate()
    f.setupExperiment(startTime=0.0)
    f.enterInitializationMode()
    f.exitInitializationMode()
    vr = {v.name: v.valueReference for v in md.modelVariables}
    return f, [vr["cage_speed"], vr["reaction_Fx"], vr["heat_flux_total"]]


def _timed_kernels_in_master(box):
    """If an FMU runs our package in this (the master's) interpreter, wrap its numba integration kernels with a
    timer adding to box[0]; returns whether it does."""
    # the package, possibly under a content-named alias (bearing_core_<hash>) as earlier in-process layers load it
    dyn = next((m for name, m in list(sys.modules.items())
                if name.startswith("bearing_core") and name.endswith(".dynamics") and hasattr(m, "K")), None)
    if dyn is None:
        return False
    K = dyn.K
    for name in ("integrate", "integrate_rosw"):
        f = getattr(K, name)

        def timed(*a, _f=f):
            t1 = time.perf_counter()
            try:
                return _f(*a)
            finally:
                box[0] += time.perf_counter() - t1
        setattr(K, name, timed)
    return True


def worker(fmu_a: str, fmu_b: str, t_end: float, block: int = 1) -> dict:
    """Step A and B alternately in this process; wall time of doStep + getReal per step for each, and the time
    of the numba integration kernels in each step where it can be measured: in this process for an FMU that runs
    our package in the master's interpreter (A, with --a-path), from the model process's profile
    (BEARING_FMU_PROFILE) for the out-of-process layer."""
    fa, outs_a = _open(fmu_a, "a")
    box = [0.0]
    a_in_master = _timed_kernels_in_master(box)
    fb, outs_b = _open(fmu_b, "b")
    kern_a = []
    n = int(round(t_end / H))
    walls = {"a": [], "b": []}
    pair = (("a", fa, outs_a), ("b", fb, outs_b))
    first = {"a": [], "b": []}   # whether a step is the first of its block (the switch from the other FMU)
    for k0 in range(0, n, block):
        order = pair if (k0 // block) % 2 == 0 else pair[::-1]   # blocks A B, B A, A B, ...
        for key, f, outs in order:
            for k in range(k0, min(k0 + block, n)):
                box[0] = 0.0
                s = time.perf_counter()
                f.doStep(currentCommunicationPoint=k * H, communicationStepSize=H)
                f.getReal(outs)
                walls[key].append(time.perf_counter() - s)
                first[key].append(k == k0)
                if key == "a":
                    kern_a.append(box[0])
    end_a, end_b = fa.getReal(outs_a), fb.getReal(outs_b)
    for f in (fa, fb):
        f.terminate()
        f.freeInstance()
    res = {"walls_a": walls["a"], "walls_b": walls["b"], "end_a": list(end_a), "end_b": list(end_b),
           "block_first": first["a"]}
    prof = Path(os.environ["BEARING_FMU_PROFILE"])
    if a_in_master and prof.exists():   # B's model process wrote its per-step kernel times at fmi2FreeInstance
        res["kernel_a"] = kern_a
        res["kernel_b"] = json.loads(prof.read_text())["bare_kernel"][:n]
    return res


def _bootstrap_median(x, n=2000, seed=1):
    rng = np.random.default_rng(seed)
    meds = np.median(rng.choice(x, size=(n, len(x)), replace=True), axis=1)
    return [float(np.percentile(meds, 2.5)), float(np.percentile(meds, 97.5))]


def _summary(wa, wb, ka=None, kb=None) -> dict:
    """Medians of the step walls and of the paired differences B - A [us]; with the kernel times, the same for
    the overheads (wall less kernel), in which the kernels' own variation (code placement, cache state) is gone."""
    wa, wb = np.asarray(wa), np.asarray(wb)
    d = (wb - wa) * 1e6
    lo, hi = _bootstrap_median(d)
    out = {"steps": int(len(d)), "a_median_us": float(np.median(wa) * 1e6), "b_median_us": float(np.median(wb) * 1e6),
           "diff_median_us": float(np.median(d)), "diff_ci95_us": [lo, hi],
           "diff_p25_p75_us": [float(np.percentile(d, 25)), float(np.percentile(d, 75))],
           "b_faster_fraction": float(np.mean(d < 0))}
    if ka is not None and kb is not None:
        oa, ob = (wa - np.asarray(ka)) * 1e6, (wb - np.asarray(kb)) * 1e6
        do = ob - oa
        lo, hi = _bootstrap_median(do)
        out.update({"overhead_a_median_us": float(np.median(oa)), "overhead_b_median_us": float(np.median(ob)),
                    "overhead_diff_median_us": float(np.median(do)), "overhead_diff_ci95_us": [lo, hi],
                    "overhead_b_le_a_fraction": float(np.mean(do <= 0))})
    return out


def _ovh_text(s) -> str:
    if "overhead_diff_median_us" not in s:
        return ""
    return (f"; overhead (wall less integration kernels) A {s['overhead_a_median_us']:.0f} us, B "
            f"{s['overhead_b_median_us']:.0f} us, B - A median {s['overhead_diff_median_us']:+.1f} us (95 % "
            f"{s['overhead_diff_ci95_us'][0]:+.1f} .. {s['overhead_diff_ci95_us'][1]:+.1f}), B <= A in "
            f"{100 * s['overhead_b_le_a_fraction']:.0f} % of the pairs")


def _run(args, cache) -> dict:
    env = dict(os.environ, BEARING_FMU_CACHE=str(cache), BEARING_FMU_PROFILE=str(Path(cache) / "ab_profile.json"))
    if args.a_path:
        env["BEARING_AB_A_PATH"] = args.a_path
    p = subprocess.run([sys.executable, __file__, "--worker", "--fmu-a", args.fmu_a, "--fmu-b", args.fmu_b,
                        "--t-end", str(args.t_end), "--block", str(args.block)], capture_output=True, text=True, env=env)
    lines = [ln for ln in p.stdout.splitlines() if ln.startswith("RESULT ")]
    if p.returncode != 0 or not lines:
        raise RuntimeError(f"worker failed ({p.returncode}): {p.stderr[-2000:]}")
    return json.loads(lines[-1][7:])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fmu-a", required=True, help="the reference FMU")
    ap.add_argument("--fmu-b", required=True, help="the FMU compared with it")
    ap.add_argument("--a-path", default=None, help="a folder put first on the master's sys.path (see above)")
    ap.add_argument("--cache", default=None, help="FMU cache folder (BEARING_FMU_CACHE); default a new one, "
                                                  "warmed by a first run that is not counted")
    ap.add_argument("--t-end", type=float, default=0.2, help="simulated time [s] per run")
    ap.add_argument("--block", type=int, default=1,
                    help="steps of one FMU before switching to the other (1: every step alternates; larger: each "
                         "FMU steps back to back as when alone, and the first step of each block is left out)")
    ap.add_argument("--repeat", type=int, default=5, help="fresh master processes")
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    if args.worker:
        a_path = os.environ.get("BEARING_AB_A_PATH")
        if a_path:
            sys.path.insert(0, a_path)
        print("RESULT " + json.dumps(worker(args.fmu_a, args.fmu_b, args.t_end, args.block)))
        return 0
    cache = args.cache or tempfile.mkdtemp(prefix="bench_fmu_ab_")
    if not args.cache:
        _run(argparse.Namespace(**{**vars(args), "t_end": 0.01}), cache)   # compile / load the kernels
    runs, wa, wb, ka, kb = [], [], [], [], []
    for i in range(args.repeat):
        r = _run(args, cache)
        # the first step includes first-call costs in the master, and with blocks the first step of each block
        # the switch between the FMUs: left out
        keep = [i for i, f in enumerate(r["block_first"]) if i > 0 and not (args.block > 1 and f)]
        for key in ("walls_a", "walls_b", "kernel_a", "kernel_b"):
            if key in r:
                r[key] = [r[key][0]] + [r[key][i] for i in keep]
        has_k = "kernel_a" in r
        s = _summary(r["walls_a"][1:], r["walls_b"][1:], r.get("kernel_a", [None])[1:] if has_k else None,
                     r.get("kernel_b", [None])[1:] if has_k else None)
        s["outputs_equal"] = r["end_a"] == r["end_b"]
        s["end_a"], s["end_b"] = r["end_a"], r["end_b"]
        runs.append(s)
        wa += r["walls_a"][1:]
        wb += r["walls_b"][1:]
        if has_k:
            ka += r["kernel_a"][1:]
            kb += r["kernel_b"][1:]
        if not args.json:
            print(f"run {i + 1}: A {s['a_median_us']:.0f} us, B {s['b_median_us']:.0f} us per step; "
                  f"B - A median {s['diff_median_us']:+.1f} us (95 % {s['diff_ci95_us'][0]:+.1f} .. "
                  f"{s['diff_ci95_us'][1]:+.1f}); outputs equal: {s['outputs_equal']}" + _ovh_text(s), flush=True)
    pooled = _summary(wa, wb, ka or None, kb or None)
    res = {"machine": machine_info(), "fmu_a": args.fmu_a, "fmu_b": args.fmu_b, "t_end": args.t_end,
           "step": H, "runs": runs, "pooled": pooled,
           "run_diff_medians_us": [r["diff_median_us"] for r in runs]}
    if args.json:
        print(json.dumps(res, indent=1))
    else:
        print(machine_line())
        print(f"pooled over {args.repeat} runs ({pooled['steps']} paired steps): A {pooled['a_median_us']:.0f} us, "
              f"B {pooled['b_median_us']:.0f} us per step; B - A median {pooled['diff_median_us']:+.1f} us "
              f"(95 % {pooled['diff_ci95_us'][0]:+.1f} .. {pooled['diff_ci95_us'][1]:+.1f}); "
              f"B faster in {100 * pooled['b_faster_fraction']:.0f} % of the pairs" + _ovh_text(pooled))
    return 0


if __name__ == "__main__":
    sys.exit(main())
