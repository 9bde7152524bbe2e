"""Benchmark of the bearing FMU driven through fmpy with default parameters and inputs (7218B, 3000 rpm,
Fx 1000 N, Fz 3000 N, lubricated, integrator 'auto') at 1 ms communication steps.

Builds the FMU (bearing_cosim.fmu_build.build, as ``bearing build-fmu``) into a temporary folder, or takes
--fmu, and runs it in fresh processes:
  * cold: an empty FMU cache folder (BEARING_FMU_CACHE), so numba compiles every kernel;
  * warm: the same folder again (compiled kernels loaded from numba's cache).
The model runs in its own process, which times its integration kernels and its own share of each doStep
(BEARING_FMU_PROFILE). Reports per run the wall time of instantiate + initialisation, of the first doStep, and the marginal wall
time per simulated second over the steps after the first (``wall_per_sim_s``; < 1 is faster than real
time). The per-step overhead is the wall time per doStep that is not time integration: the same steps are
run in process through bearing_core.session.cosim.CoSimSession (same arithmetic, same integrator choices) with the
integration kernels timed, and their time per step is subtracted from the FMU's wall time per step
(``fmu_overhead_us``: FMI layer + session; ``session_overhead_us``: the session alone; medians over the
steps). The ``*_vs_kernels_us`` figures subtract only the numba integration kernels, i.e. they also count the
Python of DynamicModel.advance as overhead. The ``*_short_step_us`` figures are the same medians over
SHORT_N steps of SHORT_H = 10 us after the 1 ms steps: there the processor caches stay warm, so they show the
overhead's own cost without the cache misses that other processes on a shared machine cause during a long
integration. On a loaded machine the wall times vary from run to run; the overheads are the robust figures.

    python bench/bench_fmu.py [--t-end 0.2] [--fmu dist/BearingFMU.fmu] [--cache DIR] [--json]

``--transport``: the model server's TCP transport against the shared memory. The C host (tests/c_host/host.c,
its ``repeat`` command: the median wall time of fmi2DoStep) runs the do-nothing slave of bench/fmpy_floor.py
(the round trip per step) and the bearing FMU at fidelity 'dynamic', 1 ms steps (the step the transport is
measured against), each with its local model process (shared memory), through `bearing serve` on 127.0.0.1
(BEARING_FMU_SERVER, the Linux .so) and, where wine64 and mingw-w64 are installed, the win64 DLL in the host
cross-compiled for win64 under wine (Winsock through wine). Runs alternated ``--repeat`` times.

    python bench/bench_fmu.py --transport [--t-end 0.1] [--rtt-steps 2000] [--repeat 3] [--json]
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
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
from machine import machine_info, machine_line  # noqa: E402
H = 1e-3
SHORT_H, SHORT_N = 1e-5, 300


def _time_kernels(dyn_module, acc, bare):
    """Wrap DynamicModel._integrate (acc[0]) and the numba integration kernels (bare[0]) of a dynamics
    module with timers; returns a function undoing it."""
    K = dyn_module.K
    undo = [(dyn_module.DynamicModel, "_integrate", dyn_module.DynamicModel._integrate)]
    undo += [(K, n, getattr(K, n)) for n in ("integrate", "integrate_rosw")]

    def timer(f, box):
        def timed(*a):
            t1 = time.perf_counter()
            try:
                return f(*a)
            finally:
                box[0] += time.perf_counter() - t1
        return timed
    for obj, name, f in undo:
        setattr(obj, name, timer(f, acc if name == "_integrate" else bare))
    return lambda: [setattr(obj, name, f) for obj, name, f in undo]


def _median_us(walls, subtract):
    return float(np.median(np.subtract(walls, subtract))) * 1e6


def worker(fmu: str, t_end: float) -> dict:
    """Drive the FMU with fmpy (in this process) and time it."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    t0 = time.perf_counter()
    md = read_model_description(fmu)
    unz = extract(fmu)
    f = FMU2Slave(guid=md.guid, unzipDirectory=unz, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="bench")
    f.instantiate()
    f.setupExperiment(startTime=0.0)
    f.enterInitializationMode()
    f.exitInitializationMode()
    t_init = time.perf_counter() - t0
    vr = {v.name: v.valueReference for v in md.modelVariables}
    outs = [vr["cage_speed"], vr["reaction_Fx"], vr["heat_flux_total"]]
    n = int(round(t_end / H))
    walls, gets, gets_again = [], [], []
    t = 0.0
    for k in range(n):
        a = time.perf_counter()
        f.doStep(currentCommunicationPoint=t, communicationStepSize=H)
        b = time.perf_counter()
        f.getReal(outs)
        c = time.perf_counter()
        walls.append(c - a)
        # the same call again: the master's own code with warm caches (the first follows the wait)
        f.getReal(outs)
        gets.append(c - b)
        gets_again.append(time.perf_counter() - c)
        t = (k + 1) * H
    last = f.getReal(outs)
    short = []
    for k in range(SHORT_N):
        a = time.perf_counter()
        f.doStep(currentCommunicationPoint=t, communicationStepSize=SHORT_H)
        f.getReal(outs)
        short.append(time.perf_counter() - a)
        t = n * H + (k + 1) * SHORT_H
    f.terminate()
    f.freeInstance()
    # the model process's own timings of every fmi2DoStep (BEARING_FMU_PROFILE, written at fmi2FreeInstance)
    prof = json.loads(Path(os.environ["BEARING_FMU_PROFILE"]).read_text())
    busy, kerns, bares = prof["busy"], prof["kernel"], prof["bare_kernel"]
    return {"init_s": t_init, "first_step_s": walls[0], "step_walls": walls, "kernel_walls": kerns[:n],
            "bare_kernel_walls": bares[:n], "busy": busy[:n], "slave_step": prof.get("slave_step", [])[:n],
            "short_step_overheads": [w - b for w, b in zip(short, bares[n:])],
            "short_step_exchange": [w - b for w, b in zip(short, busy[n:])], "cage_speed_end": last[0],
            "get_real": gets, "get_real_again": gets_again}


def in_process(t_end: float) -> dict:
    """The same steps through CoSimSession in this process, with the integration kernels timed."""
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    from bearing_core.session.cosim_spec import INPUT_NAMES
    from bearing_core.models import dynamics
    sys.path.insert(0, str(ROOT / "bearing_cosim" / "fmu_src"))
    from bearing_fmu import INPUT_START
    inputs = {k: INPUT_START.get(k, 0.0) for k in INPUT_NAMES}
    # compile / load every integration kernel before timing ('auto' probes both of its methods)
    w = CoSimSession(CoSimParameters())
    w.initialize(0.0, inputs)
    for integ in ("implicit", "adaptive-rk4", "adaptive"):
        w.model.opt = dynamics.replace(w.model.opt, integrator=integ)
        w.model.advance(w.model.t + 2e-4)
    s = CoSimSession(CoSimParameters())
    s.initialize(0.0, inputs)
    kern, bare = [0.0], [0.0]
    ev = [0.0]
    orig_ev = dynamics.DynamicModel.evaluate_point

    def timed_ev(self):
        t0 = time.perf_counter()
        try:
            return orig_ev(self)
        finally:
            ev[0] += time.perf_counter() - t0
    undo = _time_kernels(dynamics, kern, bare)
    dynamics.DynamicModel.evaluate_point = timed_ev
    n = int(round(t_end / H))
    walls, kerns, bares, evs, short = [], [], [], [], []
    try:
        for k in range(n):
            kern[0] = bare[0] = ev[0] = 0.0
            a = time.perf_counter()
            s.step(k * H, H, inputs)
            walls.append(time.perf_counter() - a)
            kerns.append(kern[0])
            bares.append(bare[0])
            evs.append(ev[0])
        end = s.outputs["cage_speed"]
        for k in range(SHORT_N):
            bare[0] = 0.0
            a = time.perf_counter()
            s.step(s.t, SHORT_H, inputs)
            short.append(time.perf_counter() - a - bare[0])
    finally:
        undo()
        dynamics.DynamicModel.evaluate_point = orig_ev
    return {"step_walls": walls, "kernel_walls": kerns, "bare_kernel_walls": bares, "eval_walls": evs,
            "short_step_overheads": short, "cage_speed_end": end}


def _run_worker(fmu, t_end, cache):
    env = dict(os.environ, BEARING_FMU_CACHE=str(cache), BEARING_FMU_PROFILE=str(Path(cache) / "profile.json"),
               BEARING_FMU_WAIT_STATS="1")
    env.pop("NUMBA_CACHE_DIR", None)
    p = subprocess.run([sys.executable, __file__, "--worker", "--fmu", str(fmu), "--t-end", str(t_end)],
                       capture_output=True, text=True, env=env)
    lines = [ln for ln in p.stdout.splitlines() if ln.startswith("RESULT ")]
    if p.returncode != 0 or not lines:
        raise RuntimeError(f"FMU worker failed ({p.returncode}): {p.stderr[-2000:]}")
    res = json.loads(lines[-1][7:])
    # how the native layer saw the step answers (its counters, printed at fmi2FreeInstance)
    stats = [ln.split()[1:] for ln in p.stderr.splitlines() if ln.startswith("BEARING_FMU_WAIT_STATS ")]
    if stats:
        res["wait_stats"] = {k: float(v) for k, v in (kv.split("=") for kv in stats[-1])}
        # the native layer's own exchange time (request sent to answer seen, less the model's busy time) per
        # way the answer was seen, in bins < 10, < 20, < 40, < 80, >= 80 us
        kinds = ("first_spin", "predicted_spin", "asleep", "spun_through")
        hist = [ln.split() for ln in p.stderr.splitlines() if ln.startswith("BEARING_FMU_EXCHANGE_HIST ")][-4:]
        res["exchange_hist"] = {kinds[int(w[1])]: [int(x) for x in w[2:]] for w in hist}
    return res


def _wine():
    import shutil
    for w in (shutil.which("wine64"), "/usr/lib/wine/wine64", shutil.which("wine")):
        if w and os.path.exists(w):
            return w
    return None


def transport(a) -> dict:
    """Round trip per fmi2DoStep over the shared memory, over localhost TCP (Linux .so) and under wine (win64
    DLL), for the do-nothing slave and the bearing FMU at 'dynamic' (see the module's docstring)."""
    import re
    import signal
    import zipfile
    from bearing_cosim import fmu_build
    import fmpy_floor
    out = {"machine": machine_info(), "step_s": H}
    with tempfile.TemporaryDirectory(prefix="bench_transport_") as td:
        tmp = Path(td)
        win = fmu_build.win64_compiler() is not None and _wine() is not None
        plats = ("linux64", "win64") if win else ("linux64",)
        fmus = {"idle": fmu_build._build("Idle", {"idle_slave": fmpy_floor._SLAVE}, "idle_slave", tmp / "idle",
                                         platforms=plats),
                "bearing": Path(a.fmu) if a.fmu else fmu_build.build(tmp / "dist", platforms=plats)}
        info = {}
        for tag, f in fmus.items():
            unz = tmp / f"unz_{tag}"
            with zipfile.ZipFile(f) as z:
                z.extractall(unz)
            md = (unz / "modelDescription.xml").read_text()
            mid = re.search(r'modelIdentifier="([^"]+)"', md).group(1)
            out_name = "cage_speed" if tag == "bearing" else "v3"
            vr = re.search(rf'name="{out_name}" valueReference="(\d+)"', md).group(1)
            info[tag] = {"unz": unz, "guid": re.search(r'guid="([^"]+)"', md).group(1), "id": mid, "vr": vr}
        host_c = ROOT / "tests" / "c_host" / "host.c"
        host = tmp / "host"
        subprocess.run([os.environ.get("CC", "gcc"), "-std=gnu99", "-O2", "-o", str(host), str(host_c), "-ldl"],
                       check=True)
        if win:
            subprocess.run([*fmu_build.win64_compiler(), "-std=gnu99", "-O2", "-o", str(tmp / "host.exe"), str(host_c)],
                           check=True)
        cache = Path(a.cache) if a.cache else tmp / "cache"
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "NUMBA_CACHE_DIR")}
        env["BEARING_FMU_CACHE"] = str(cache)
        srv = subprocess.Popen([sys.executable, "-m", "bearing_cosim.cli", "serve", "--port", "0", "--fmu",
                                str(fmus["idle"]), "--fmu", str(fmus["bearing"])], stdout=subprocess.PIPE,
                               stderr=subprocess.DEVNULL, text=True, env=dict(env, PYTHONPATH=str(ROOT)))
        port = int(srv.stdout.readline().rsplit(":", 1)[1])

        def run(tag, mode, steps):
            """The median wall time of fmi2DoStep [us] over steps steps of H."""
            i = info[tag]
            script = tmp / f"{tag}_{mode}.txt"
            script.write_text(f"instantiate 0\nsetup 0\nenter\nexit\noutputs {i['vr']}\nrepeat {steps} {H!r}\nfree\n")
            e = dict(env)
            cmd = [str(host), str(i["unz"]), i["id"], i["guid"], str(script)]
            if mode != "shm":
                e["BEARING_FMU_SERVER"] = f"127.0.0.1:{port}"
            if mode == "wine":
                e["WINEDEBUG"] = "-all"
                cmd = [_wine(), str(tmp / "host.exe"), "Z:" + str(i["unz"]), i["id"], i["guid"], str(script)]
            r = subprocess.run(cmd, capture_output=True, text=True, env=e, timeout=3600)
            line = next((ln for ln in r.stdout.splitlines() if ln.startswith("TIMING ")), None)
            row = next((ln for ln in r.stdout.splitlines() if ln.startswith("ROW ")), "ROW 3")
            if r.returncode != 0 or line is None or row.split()[1] != "0":
                raise RuntimeError(f"{tag} over {mode} failed ({r.returncode}): {r.stdout[-1500:]} {r.stderr[-1500:]}")
            return float(line.split()[1]) * 1e-3

        try:
            modes = ("shm", "tcp", "wine") if win else ("shm", "tcp")
            run("bearing", "shm", 5)      # numba's cache filled (a cold cache compiles here)
            res = {(t, m): [] for t in ("idle", "bearing") for m in modes}
            n_dyn = int(round(a.t_end / H))
            for _ in range(a.repeat):
                for m in modes:
                    res[("idle", m)].append(run("idle", m, a.rtt_steps))
                    res[("bearing", m)].append(run("bearing", m, n_dyn))
        finally:
            srv.send_signal(signal.SIGINT)
            srv.wait(30)
    for (t, m), v in res.items():
        out[f"{t}_{m}_us"] = v
    for m in modes:
        idle = float(np.median(res[("idle", m)]))
        out[f"idle_{m}_median_us"] = idle
        out[f"bearing_{m}_median_us"] = float(np.median(res[("bearing", m)]))
        if m != "shm":
            cost = idle - float(np.median(res[("idle", "shm")]))
            out[f"transport_{m}_us"] = cost
            out[f"transport_{m}_share_of_dynamic_step"] = cost / out["bearing_shm_median_us"]
    out["wine"] = win
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t-end", type=float, default=0.2, help="simulated time [s] per run")
    ap.add_argument("--fmu", default=None, help="an FMU to drive (default: build one into a temporary folder)")
    ap.add_argument("--cache", default=None, help="FMU cache folder (default: a new, empty one: the first run "
                                                  "is cold)")
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--transport", action="store_true",
                    help="the model server's TCP transport against the shared memory (see the docstring)")
    ap.add_argument("--rtt-steps", type=int, default=2000, help="steps of the do-nothing slave per run (--transport)")
    ap.add_argument("--repeat", type=int, default=3, help="alternated runs per transport (--transport)")
    a = ap.parse_args(argv)
    if a.transport:
        if not 0.005 <= a.t_end <= 10.0 or not 20 <= a.rtt_steps <= 10 ** 6 or not 1 <= a.repeat <= 100:
            ap.error(f"--t-end = {a.t_end}, --rtt-steps = {a.rtt_steps}, --repeat = {a.repeat}: allowed 0.005..10 s, "
                     "20..1e6, 1..100")
        out = transport(a)
        if a.json:
            print(json.dumps(out))
        else:
            print(machine_line(out["machine"]))
            for m in ("shm", "tcp", "wine"):
                if f"idle_{m}_median_us" in out:
                    print(f"{m:5s}: do-nothing slave {out[f'idle_{m}_median_us']:8.1f} us per step (runs "
                          + ", ".join(f"{x:.1f}" for x in out[f"idle_{m}_us"]) + f"); bearing FMU at 'dynamic', 1 ms "
                          f"steps {out[f'bearing_{m}_median_us'] / 1e3:.3f} ms per step (runs "
                          + ", ".join(f"{x / 1e3:.3f}" for x in out[f"bearing_{m}_us"]) + ")")
                if f"transport_{m}_us" in out:
                    print(f"       transport over the shared memory: {out[f'transport_{m}_us']:.1f} us per step, "
                          f"{100 * out[f'transport_{m}_share_of_dynamic_step']:.2f} % of a dynamic 1 ms step")
        return out
    if a.worker:
        print("RESULT " + json.dumps(worker(a.fmu, a.t_end)))
        return None
    with tempfile.TemporaryDirectory(prefix="bench_fmu_") as tmp:
        fmu = a.fmu
        if fmu is None:
            from bearing_cosim.fmu_build import build
            fmu = str(build(Path(tmp) / "dist"))
        cache = Path(a.cache) if a.cache else Path(tmp) / "cache"
        cold = _run_worker(fmu, min(a.t_end, 0.01), cache)     # cold if the cache folder was empty
        warm = _run_worker(fmu, a.t_end, cache)
    ip = in_process(a.t_end)
    sw = warm["step_walls"][1:]
    n = len(sw)
    kw = ip["kernel_walls"][1:]
    kern = sum(kw) / n
    # overheads: medians over the steps of (step wall - the same step's integration time), robust to the
    # noise of a shared machine
    out = {
        "machine": machine_info(),
        "step_s": H, "simulated_s": a.t_end,
        "wall_per_sim_s": sum(sw) / (n * H),
        "wall_per_step_ms": sum(sw) / n * 1e3,
        "fmu_overhead_us": (float(np.median(np.subtract(sw, warm["kernel_walls"][1:]))) * 1e6
                            if any(warm["kernel_walls"]) else float(np.median(np.subtract(sw, kw))) * 1e6),
        "session_overhead_us": float(np.median(np.subtract(ip["step_walls"][1:], kw))) * 1e6,
        "fmu_overhead_vs_kernels_us": _median_us(sw, warm["bare_kernel_walls"][1:]),
        "session_overhead_vs_kernels_us": _median_us(ip["step_walls"][1:], ip["bare_kernel_walls"][1:]),
        "fmu_overhead_short_step_us": float(np.median(warm["short_step_overheads"])) * 1e6,
        # the FMI layer alone: fmpy + native layer + exchange with the model process (step wall - model's time)
        "exchange_us": _median_us(sw, warm["busy"][1:]),
        "exchange_short_step_us": float(np.median(warm["short_step_exchange"])) * 1e6,
        # the model process's own loop around the slave's do_step (request, outputs into the shared segment)
        "model_loop_us": (_median_us(warm["busy"][1:], warm["slave_step"][1:]) if warm["slave_step"] else None),
        # steps whose answer the master saw in its first spin, in a predicted spin, or asleep (futex)
        "wait_stats": warm.get("wait_stats"), "exchange_hist": warm.get("exchange_hist"),
        # fmpy's getReal of 3 outputs right after doStep, and the same call repeated at once (warm caches)
        "get_real_after_step_us": _median_us(warm["get_real"][1:], 0.0) if "get_real" in warm else None,
        "get_real_again_us": _median_us(warm["get_real_again"][1:], 0.0) if "get_real" in warm else None,
        "session_overhead_short_step_us": float(np.median(ip["short_step_overheads"])) * 1e6,
        # of which the one right-hand-side call for the outputs and films at the communication point
        "output_eval_us": float(np.median(ip["eval_walls"][1:])) * 1e6,
        "kernel_per_step_ms": kern * 1e3,
        "in_process_wall_per_sim_s": sum(ip["step_walls"][1:]) / (n * H),
        "warm_init_s": warm["init_s"], "warm_first_step_s": warm["first_step_s"],
        "cold_init_s": cold["init_s"], "cold_first_step_s": cold["first_step_s"],
        "cage_speed_end_fmu": warm["cage_speed_end"], "cage_speed_end_in_process": ip["cage_speed_end"],
    }
    if a.json:
        print(json.dumps(out))
    else:
        print(machine_line(out["machine"]))
        print(f"BearingFMU, default parameters and inputs, {H * 1e3:g} ms steps, {a.t_end:g} s simulated (fmpy)")
        print(f"marginal wall time per simulated second: {out['wall_per_sim_s']:.2f} "
              f"({out['wall_per_step_ms']:.3f} ms per step, of which integration {out['kernel_per_step_ms']:.3f} ms)")
        print(f"per-step overhead: {out['fmu_overhead_us']:.0f} us through the FMU, "
              f"{out['session_overhead_us']:.0f} us in the session alone (of which {out['output_eval_us']:.0f} us "
              "the right-hand-side call for outputs and films)")
        print(f"  counting the Python of DynamicModel.advance too: {out['fmu_overhead_vs_kernels_us']:.0f} us through "
              f"the FMU, {out['session_overhead_vs_kernels_us']:.0f} us in the session; at {SHORT_H * 1e6:g} us steps "
              f"(warm caches): {out['fmu_overhead_short_step_us']:.0f} us / "
              f"{out['session_overhead_short_step_us']:.0f} us")
        print(f"of which the FMI layer and the exchange with the model process: {out['exchange_us']:.0f} us "
              f"({out['exchange_short_step_us']:.0f} us at {SHORT_H * 1e6:g} us steps); the model process's own "
              f"loop: {out['model_loop_us']:.0f} us")
        if out["exchange_hist"]:
            print("  the native layer's exchange (request to answer seen, less the model's time), steps per bin "
                  "<10 / <20 / <40 / <80 / >=80 us: " + "; ".join(f"{k} {v}" for k, v in out["exchange_hist"].items()))
        print(f"  fmpy getReal right after doStep {out['get_real_after_step_us']:.1f} us, the same call repeated "
              f"{out['get_real_again_us']:.1f} us (the master's code on cold caches after the wait)")
        print(f"warm: initialisation {out['warm_init_s']:.2f} s, first step {out['warm_first_step_s']:.3f} s")
        print(f"first run (cold if the cache folder was empty): initialisation {out['cold_init_s']:.2f} s, "
              f"first step {out['cold_first_step_s']:.3f} s")
    return out


if __name__ == "__main__":
    main()
