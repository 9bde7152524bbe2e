"""Sweep throughput on Dask: points per minute with 1 and 2 local workers, and how the wall time grows with the
number of points.

    PYTHONPATH=$PWD python bench/bench_sweep.py [--models quasistatic,tribo] [--sizes 8,16,32,64]
                                                 [--workers 1,2] [--json docs/figures/bench_sweep.json]
                                                 [--png docs/figures/bench_sweep.png]
    PYTHONPATH=$PWD python bench/bench_sweep.py --plot-only docs/figures/bench_sweep.json --png FILE
    PYTHONPATH=$PWD python bench/bench_sweep.py --batch [--models dynamic] [--sizes 16] [--batch-json FILE]

Per model and worker count: one LocalCluster of single-threaded processes (its start-up is timed apart), one
warm-up sweep (workers import bearing_core and load the compiled kernels), then sweeps of N points (no cache),
one task per point (batch_size=1; --batch compares batched tasks), each point solved from scratch. Points:
7008-ma2023, speeds evenly spaced over 3000-18,000 rpm, preload 100 N, lubricated traction with ball drag (oil
fraction 0.5). Reported: wall time, points per minute, the mean cost of one point inside the worker
(eval_wall_s) and the per-point overhead (wall x workers / N - mean point cost). The load average is printed: on
a shared machine other processes take cores from the workers.

--batch: per-point tasks against batched tasks (sweep.run_sweep batch_size / threads_per_worker), points per wall
second, in one run: 'per-point' (2 single-threaded workers, one task per point), 'batched' (2 single-threaded
workers, automatic batches), 'batched-threads' (1 worker whose batches advance their points on 2 threads with
dynamics.advance_many; dynamic and profile models only). The clusters of all configurations stay up and the
configurations take turns for --repeats rounds; medians are compared. The 'dynamic' model on 7008-ma2023 at
--sizes points (3000-12,000 rpm, Fz 300-900 N, lubricated; windows of 0.01 s, 0.03 s simulated, steadiness off
so every point costs the same simulated time); 'quasistatic' and 'tribo' as in the scaling run. The results of
all configurations are checked equal. Control (the machine may be shared): bench_batch.free_cores, a trivial
nogil numba loop alone and in two threads at once, before the run and after each model; it gives the cores this
run actually had.

Times are wall time only: the points are solved in Dask worker processes, whose CPU time this process cannot
see (eval_wall_s, the cost of a point inside its worker, is wall time too). The JSON files carry the machine
(bench/machine.py) under "machine" (an object; it was the string "<n> CPUs", now under "cpus" as a number); the
text output names the machine first. Quickest check: ``--models quasistatic --sizes 4 --workers 1``.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))
from machine import machine_info, machine_line  # noqa: E402

CLOCK_NOTE = "wall time only (the points run in Dask worker processes)"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--models", default="quasistatic,tribo")
    ap.add_argument("--sizes", default="8,16,32,64")
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--json", default=None)
    ap.add_argument("--png", default=None, help="plot of wall time against points")
    ap.add_argument("--plot-only", default=None, metavar="JSON", help="only plot a previous run's JSON")
    ap.add_argument("--batch", action="store_true", help="per-point against batched tasks (see above)")
    ap.add_argument("--batch-json", default=None, help="--batch: write the rows here")
    ap.add_argument("--repeats", type=int, default=3, help="--batch: rounds (medians are compared)")
    a = ap.parse_args()
    if a.plot_only:
        plot(json.loads(Path(a.plot_only).read_text())["rows"], a.png)
        return
    mach = machine_info()
    print(machine_line(mach, clock=CLOCK_NOTE), flush=True)
    if a.batch:
        return batch_compare(a.models if a.models != "quasistatic,tribo" else "dynamic",
                             [int(s) for s in a.sizes.split(",")] if a.sizes != "8,16,32,64" else [16], a.batch_json,
                             a.repeats, mach)
    from distributed import Client, LocalCluster
    import numpy as np
    from bearing_core.maps import sweep as S
    sizes = [int(s) for s in a.sizes.split(",")]
    rows = []
    for model in a.models.split(","):
        base = {"bearing": "7008-ma2023", "preload_N": 100.0}
        if model != "quasistatic":
            base.update(traction="lubricated", oil_fraction=0.5)
        for nw in [int(w) for w in a.workers.split(",")]:
            t0 = time.perf_counter()
            with LocalCluster(n_workers=nw, threads_per_worker=1, processes=True, dashboard_address=":0",
                              host="127.0.0.1") as cl, Client(cl) as c:
                t_start = time.perf_counter() - t0
                warm = S.SweepSpec(model=model, base=base, grid={"speed_rpm": [5000.0] * 1 + [7000.0] * (nw > 1)})
                S.run_sweep(warm, client=c, progress=False, batch_size=1)
                for n in sizes:
                    spec = S.SweepSpec(model=model, base=base, grid={"speed_rpm": np.linspace(3000, 18000, n).tolist()})
                    la = os.getloadavg()[0]
                    t1 = time.perf_counter()
                    df = S.run_sweep(spec, client=c, progress=False, batch_size=1)
                    wall = time.perf_counter() - t1
                    cost = float(df["eval_wall_s"].mean())
                    r = {"model": model, "workers": nw, "points": n, "wall_s": wall, "points_per_min": 60 * n / wall,
                         "mean_point_s": cost, "overhead_per_point_s": wall * nw / n - cost,
                         "failed": int((df["status"] != "ok").sum()), "cluster_start_s": t_start, "loadavg_1min": la}
                    rows.append(r)
                    print(f"{model:12s} workers {nw}  N {n:4d}  wall {wall:7.2f} s  {r['points_per_min']:8.1f} pt/min  "
                          f"point {cost:6.3f} s  overhead {r['overhead_per_point_s']:+.3f} s/pt  "
                          f"(cluster start {t_start:.1f} s, load {la:.1f})", flush=True)
    if a.json:
        Path(a.json).write_text(json.dumps({"machine": mach, "cpus": os.cpu_count(), "clock": CLOCK_NOTE,
                                            "rows": rows}, indent=1))
    if a.png:
        plot(rows, a.png)


# name, workers, threads per worker, batch size (None: automatic)
BATCH_CONFIGS = (("per-point", 2, 1, 1), ("batched", 2, 1, None), ("batched-threads", 1, 2, None))
THREADED = ("dynamic", "profile")     # the models whose batches advance their points on several threads


def batch_compare(models: str, sizes, json_path=None, repeats: int = 3, mach=None):
    """Points per wall second of per-point and batched tasks (BATCH_CONFIGS; 'batched-threads' for the
    models in THREADED only), with the free-core control. The clusters of all configurations stay up and
    the configurations take turns (repeats rounds, rotated order), so that a change of the machine's load
    during the run hits them alike; medians over the rounds are compared."""
    import contextlib
    import statistics
    from distributed import Client, LocalCluster
    import numpy as np
    import pandas as pd
    from bearing_core.maps import sweep as S
    sys.path.insert(0, str(ROOT / "bench"))
    from bench_batch import free_cores

    def spec(model, n):
        if model == "dynamic":
            rpm = np.linspace(3000.0, 12000.0, n).tolist()
            pts = [{"speed_rpm": r, "fz_N": 300.0 + 300.0 * (k % 3)} for k, r in enumerate(rpm)]
            return S.SweepSpec(model=model, base={"bearing": "7008-ma2023"}, points_list=pts,
                               options={"window_s": 0.01, "max_time_s": 0.03, "steady_tol": 1e-8,
                                        "torque_tol": 1e-8})
        base = {"bearing": "7008-ma2023", "preload_N": 100.0}
        if model != "quasistatic":
            base.update(traction="lubricated", oil_fraction=0.5)
        return S.SweepSpec(model=model, base=base, grid={"speed_rpm": np.linspace(3000, 18000, n).tolist()})

    controls = [free_cores(2)]
    print(f"control before: {controls[0]:.2f} of 2 cores free (load {os.getloadavg()[0]:.1f})", flush=True)
    rows, ref = [], {}
    for model in models.split(","):
        configs = [c for c in BATCH_CONFIGS if c[2] == 1 or model in THREADED]
        with contextlib.ExitStack() as stack:
            clients = {}
            for name, nw, th, bs in configs:
                t0 = time.perf_counter()
                cl = stack.enter_context(LocalCluster(n_workers=nw, threads_per_worker=1, processes=True,
                                                      dashboard_address=":0", host="127.0.0.1"))
                c = stack.enter_context(Client(cl))
                t_start = time.perf_counter() - t0
                t0 = time.perf_counter()
                S.run_sweep(spec(model, 2 * nw * th), client=c, progress=False, batch_size=bs,
                            threads_per_worker=th)                    # warm-up: kernels loaded in every worker
                clients[name] = (c, t_start, time.perf_counter() - t0)
            for rep in range(repeats):
                for k in range(len(configs)):
                    name, nw, th, bs = configs[(k + rep) % len(configs)]
                    c, t_start, t_warm = clients[name]
                    for n in sizes:
                        la = os.getloadavg()[0]
                        t1 = time.perf_counter()
                        df = S.run_sweep(spec(model, n), client=c, progress=False, batch_size=bs,
                                         threads_per_worker=th)
                        wall = time.perf_counter() - t1
                        vals = df.drop(columns=["eval_wall_s", "cached"])
                        if (model, n) in ref:
                            pd.testing.assert_frame_equal(ref[(model, n)], vals, check_exact=True)
                        ref.setdefault((model, n), vals)
                        r = {"model": model, "config": name, "round": rep, "workers": nw, "threads_per_worker": th,
                             "batch_size": bs or S.auto_batch_size(n, nw, th), "points": n, "wall_s": wall,
                             "points_per_s": n / wall, "failed": int((df["status"] != "ok").sum()),
                             "cluster_start_s": t_start, "warmup_sweep_s": t_warm, "loadavg_1min": la}
                        rows.append(r)
                        print(f"{model:12s} {name:16s} workers {nw} x {th} threads, batch {r['batch_size']:3d}  "
                              f"N {n:4d}  wall {wall:7.2f} s  {r['points_per_s']:7.2f} pt/s  (warm-up sweep "
                              f"{t_warm:.1f} s, load {la:.1f})", flush=True)
            controls.append(free_cores(2))
            print(f"control: {controls[-1]:.2f} of 2 cores free (load {os.getloadavg()[0]:.1f})", flush=True)
    summary = []
    for model in models.split(","):
        for n in sizes:
            med = {}
            for r in rows:
                if r["model"] == model and r["points"] == n:
                    med.setdefault(r["config"], []).append(r["points_per_s"])
            med = {k: statistics.median(v) for k, v in med.items()}
            base = med["per-point"]
            summary += [{"model": model, "points": n, "config": k, "median_points_per_s": v,
                         "gain_vs_per_point": v / base} for k, v in med.items()]
            print(f"{model} N {n} (median of {repeats}): " +
                  ", ".join(f"{k} {v:.2f} pt/s ({v / base:.2f}x)" for k, v in med.items()))
    out = {"machine": mach or machine_info(), "cpus": os.cpu_count(), "clock": CLOCK_NOTE,
           "control_free_cores": controls,
           "results_identical_across_configs": True, "summary": summary, "rows": rows}
    if json_path:
        Path(json_path).write_text(json.dumps(out, indent=1))
    return out


def plot(rows, path):
    """Wall time against the number of points, per model and worker count."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
    keys = sorted({(r["model"], r["workers"]) for r in rows})
    for (m, w) in keys:
        rr = [r for r in rows if r["model"] == m and r["workers"] == w]
        ax.plot([r["points"] for r in rr], [r["wall_s"] for r in rr], "o-" if w == 1 else "s--",
                label=f"{m}, {w} worker{'s' if w > 1 else ''}")
    ax.set_xlabel("points")
    ax.set_ylabel("wall time [s]")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    la = [r["loadavg_1min"] for r in rows]
    ax.set_title(f"sweep wall time (2-core machine, load average {min(la):.0f}-{max(la):.0f} during the run)",
                 fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()
