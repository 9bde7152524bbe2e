"""Sweeps on Dask (bearing_core.maps.sweep, `bearing sweep`): determinism across worker counts and schedulers, failing
points, worker loss, resume from the cache, the minimum-preload bisection, and spec validation.

Most tests use the Jones-Harris quasi-static model on 7008-ma2023 and tiny grids (cheap); the preload bisection
uses the quasi-static tribological model."""
import math
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("distributed")
import pandas as pd  # noqa: E402

from bearing_core.maps import sweep as S  # noqa: E402
from bearing_core.cli import main  # noqa: E402
from bearing_core.errors import BearingInputError  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
BEARING = "7008-ma2023"
META = ["eval_wall_s", "cached"]


def _grid_spec(model="quasistatic", **opts):
    return S.SweepSpec(model=model, base={"bearing": BEARING},
                       grid={"speed_rpm": [2000.0, 12000.0], "fz_N": [300.0, 1200.0], "fx_N": [0.0, 400.0]},
                       options=dict(control="outer", **opts))


def _values(df):
    return df.drop(columns=META)


@pytest.fixture(scope="module")
def client2():
    from distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                      host="127.0.0.1") as cl, Client(cl) as c:
        yield c


class ExternalCluster:
    """`dask scheduler` and two `dask worker` processes (no nanny) on 127.0.0.1, started as subprocesses. The
    processes start in the background; ready() waits for them."""

    def __init__(self, tmp: Path, n_workers: int = 2):
        env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), str(HERE)]))
        bindir = Path(sys.executable).parent
        self.n = n_workers
        self.sfile = tmp / "scheduler.json"
        self.procs = [subprocess.Popen([str(bindir / "dask"), "scheduler", "--host", "127.0.0.1", "--port", "0",
                                        "--no-dashboard", "--scheduler-file", str(self.sfile)], env=env,
                                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
        self.workers = [subprocess.Popen([str(bindir / "dask"), "worker", "--scheduler-file", str(self.sfile),
                                          "--nthreads", "1", "--no-nanny", "--host", "127.0.0.1", "--no-dashboard"],
                                         env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                        for _ in range(n_workers)]
        self.procs += self.workers
        self.address = None

    def ready(self):
        import json
        from distributed import Client
        t0 = time.time()
        while not self.sfile.is_file():
            if time.time() - t0 > 90:
                raise RuntimeError("dask scheduler did not start")
            time.sleep(0.1)
        self.address = json.loads(self.sfile.read_text())["address"]
        with Client(self.address, timeout="60s") as c:
            c.wait_for_workers(self.n, timeout=90)
        return self

    def close(self):
        for p in reversed(self.procs):
            if p.poll() is None:
                p.terminate()
        for p in self.procs:
            try:
                p.wait(10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


@pytest.fixture(scope="module")
def external(tmp_path_factory):
    """One external cluster for the module: the determinism test uses both workers, the worker-loss test (after
    it in this file) kills one."""
    ext = ExternalCluster(tmp_path_factory.mktemp("dask"))
    yield ext
    ext.close()


def test_identical_results_on_1_and_2_workers_and_an_external_scheduler(client2, external):
    """The same 8-point grid (speed x Fz x Fx) on a 1-worker and a 2-worker local cluster and on a scheduler
    with two worker processes started separately: identical values (bit for bit), in point order."""
    spec = _grid_spec()
    d1 = S.run_sweep(spec, workers=1, progress=False)      # while the external cluster starts
    d2 = S.run_sweep(spec, client=client2, progress=False)
    assert len(client2.scheduler_info()["workers"]) == 2
    d3 = S.run_sweep(spec, scheduler=external.ready().address, progress=False)
    assert len(d1) == 8 and (d1["status"] == "ok").all()
    assert list(d1["point_index"]) == list(range(8))
    pd.testing.assert_frame_equal(_values(d1), _values(d2), check_exact=True)
    pd.testing.assert_frame_equal(_values(d1), _values(d3), check_exact=True)
    # grid order: the last grid dimension varies fastest
    assert list(d1["fx_N"][:2]) == [0.0, 400.0] and list(d1["speed_rpm"][:4]) == [2000.0] * 4


def test_failing_point_is_recorded_and_the_others_complete(client2):
    spec = S.SweepSpec(model="sweep_helpers:RaisingQuasiStatic", base={"bearing": BEARING, "speed_rpm": 6000.0},
                       grid={"fz_N": [200.0, 666.0, 900.0]})
    df = S.run_sweep(spec, client=client2, progress=False)
    assert list(df["status"]) == ["ok", "failed", "ok"]
    assert "deliberate failure" in df["error"][1]
    assert df["cage_speed_rpm"][0] > 0 and df["cage_speed_rpm"][2] > 0 and math.isnan(df["cage_speed_rpm"][1])


def test_killing_a_worker_mid_sweep_still_completes(external, tmp_path):
    """10 points of 0.3 s each on the two external workers; one worker is killed (SIGKILL) after the first
    results arrive: the scheduler re-runs its tasks on the other worker and every point completes."""
    ext = external.ready()
    spec = S.SweepSpec(model="sweep_helpers:SlowQuasiStatic", base={"bearing": BEARING, "fz_N": 500.0},
                       grid={"speed_rpm": np.linspace(1000, 12000, 10).tolist()}, options={"sleep_s": 0.3})
    cache = tmp_path / "cache"
    box = {}
    th = threading.Thread(target=lambda: box.update(df=S.run_sweep(spec, scheduler=ext.address, cache_dir=cache,
                                                                   retries=2, progress=False)))
    th.start()
    t0 = time.time()
    while len(list(cache.glob("*.json"))) < 2 and time.time() - t0 < 60:
        time.sleep(0.05)
    ext.workers[0].send_signal(signal.SIGKILL)
    th.join(120)
    assert not th.is_alive()
    df = box["df"]
    assert ext.workers[0].wait(5) == -signal.SIGKILL
    assert (df["status"] == "ok").all(), df[["status", "error"]]
    ref = S.run_point("quasistatic", {}, spec.points()[-1])
    assert df["cage_speed_rpm"].iloc[-1] == ref["cage_speed_rpm"]


def test_resumed_sweep_recomputes_nothing_that_finished(client2, tmp_path):
    spec = _grid_spec()
    cache = tmp_path / "cache"
    first = S.run_sweep(spec, client=client2, cache_dir=cache, progress=False)
    assert first.attrs["computed"] == 8 and len(list(cache.glob("*.json"))) == 8
    # an interrupted sweep: three finished points lost
    for f in sorted(cache.glob("*.json"))[:3]:
        f.unlink()
    again = S.run_sweep(spec, client=client2, cache_dir=cache, progress=False)
    assert again.attrs["computed"] == 3 and int((~again["cached"]).sum()) == 3
    pd.testing.assert_frame_equal(_values(first), _values(again), check_exact=True)
    third = S.run_sweep(spec, client=client2, cache_dir=cache, progress=False)
    assert third.attrs["computed"] == 0 and third["cached"].all()
    # another model option is another point
    other = S.run_sweep(_grid_spec().__class__(model="quasistatic", base=spec.base, grid=spec.grid,
                                               options={"control": "inner"}),
                        client=client2, cache_dir=cache, progress=False)
    assert other.attrs["computed"] == 8


def test_min_preload_brackets_a_directly_checked_point(client2):
    """Quasi-static tribological model, 7008-ma2023 at 15,000 rpm, the smooth illustrative traction curve
    ('lubricated-curve': cheap, well-conditioned solves; the bisection is what is tested here) with ball drag in an
    oil-air mixture of oil fraction 0.5 (the drag the traction must overcome): the bisection's minimum preload
    P is checked directly, outside the bisection: at 0.9 P the bearing skids (cage speed ratio < 0.95), at
    1.03 P it does not. Also: the curve's bracket ratios straddle the criterion."""
    base = {"bearing": BEARING, "traction": "lubricated-curve", "oil_fraction": 0.5}
    spec = S.SweepSpec(model="tribo", base=base)
    df = S.min_preload_curve(spec, [15000.0], lo=20.0, hi=200.0, rtol=0.03, client=client2, progress=False)
    r = df.iloc[0]
    assert r["status"] == "ok", r["error"]
    P = r["min_preload_N"]
    assert 20.0 < r["preload_skidding_N"] < P < 200.0 and P - r["preload_skidding_N"] <= 0.03 * P
    assert r["ratio_at_skidding_preload"] < 0.95 <= r["ratio_at_min_preload"]
    pt = dict(S.SweepSpec(base=dict(base, speed_rpm=15000.0)).points()[0])
    # direct checks, on the same workers (their compiled kernels are loaded already)
    below, above = (client2.submit(S.run_point, "tribo", {}, dict(pt, preload_N=f * P), pure=False).result()
                    ["cage_speed_ratio"] for f in (0.9, 1.03))
    assert S.skid_state(below) == "skidding" and S.skid_state(above) != "skidding", (below, above)


def test_pure_rolling_cage_speed_equal_angles_is_the_textbook_formula():
    """Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 1, the chapter on rolling-bearing kinematics
    (cage speed with the outer ring fixed; chapter recalled from memory, the formula is the standard epicyclic
    result): omega_c = omega_i / 2 (1 - D cos(alpha) / dm) when both contact angles equal alpha. 7008-ma2023
    geometry, alpha = 15 and 40 deg; tolerance 1e-12 relative."""
    from bearing_core.bearing.geometry import load_preset
    g = load_preset(BEARING)
    for a in (math.radians(15.0), math.radians(40.0)):
        w = 1000.0
        ref = 0.5 * w * (1.0 - g.D * math.cos(a) / g.dm)
        assert S.pure_rolling_cage_speed(w, [a] * 3, [a] * 3, g.D, g.dm) == pytest.approx(ref, rel=1e-12)
    assert S.skid_state(0.94) == "skidding" and S.skid_state(1.06) == "over-skidding"
    assert S.skid_state(0.97) == "pure rolling" and S.skid_state(float("nan")) == ""


@pytest.mark.parametrize("args, words", [
    (["--grid", "speed_rmp=0:100:3"], ["speed_rmp", "speed_rpm"]),                    # unknown variable
    (["--grid", "speed_rpm=0:1000:0"], ["speed_rpm", "empty"]),                       # empty range
    (["--grid", "fz_N=100,nan"], ["fz_N", "finite"]),                                 # NaN
    (["--grid", "speed_rpm=-500,1000"], ["speed_rpm", "-500"]),                       # negative speed
    (["--model", "tribo", "--grid", "speed_rpm=0,1000"], ["speed_rpm", "tribo"]),     # zero speed, needs rolling
    (["--grid", "speed_rpm=1000,2000", "--grid", "mu=0.1,0.2"], ["mu", "quasistatic"]),  # no effect on the model
    (["--set", "bearing=nope", "--grid", "fz_N=100,200"], ["bearing", "nope"]),        # unknown preset
    (["--min-preload", "1000,2000", "--preload-range", "50:10", "--model", "tribo"], ["preload"]),
    (["--grid", "fz_N=100,200", "--batch-size", "0"], ["--batch-size", "0"]),
    (["--grid", "fz_N=100,200", "--threads-per-worker", "0"], ["--threads-per-worker", "0"]),
])
def test_bad_specs_fail_before_any_work(args, words, tmp_path, capsys):
    out = tmp_path / "o"
    t0 = time.perf_counter()
    rc = main(["sweep", "--out", str(out), "--no-progress", *args])
    err = capsys.readouterr().err
    assert rc == 2, err
    assert all(w in err for w in words), err
    assert not out.exists()            # nothing written, no cluster started
    assert time.perf_counter() - t0 < 5.0


def test_points_file_errors(tmp_path):
    f = tmp_path / "p.csv"
    f.write_text("speed_rpm,fz_N\n")
    with pytest.raises(BearingInputError, match="no points"):
        S.read_points_csv(f)
    f.write_text("speed_rpm,fz_N,colour\n1000,100,red\n")
    with pytest.raises(BearingInputError, match="colour"):
        S.read_points_csv(f)


def test_cli_legacy_speed_sweep_and_point_list(client2, tmp_path, capsys):
    """Today's flags still give quasistatic_sweep_<bearing>.csv (same columns) and the tidy table; a CSV list of
    points runs with the same engine; a grid over speed x preload writes the NetCDF and the maps."""
    out = tmp_path / "o"
    addr = client2.scheduler.address
    rc = main(["sweep", "--bearing", BEARING, "--fz", "500", "--speed-max-rpm", "12000", "--points", "3",
               "--out", str(out), "--scheduler", addr, "--no-progress"])
    assert rc == 0, capsys.readouterr().err
    legacy = pd.read_csv(out / f"quasistatic_sweep_{BEARING}.csv")
    assert list(legacy.columns) == ["speed_rpm", "cage_speed_rpm", "cage_shaft_ratio", "alpha_i_deg", "alpha_o_deg",
                                    "Q_i_N", "Q_o_N", "omega_R_rpm", "spin_roll_i", "spin_roll_o", "p_max_i_Pa",
                                    "dz_m", "dx_m"]
    assert list(legacy["speed_rpm"]) == [0.0, 6000.0, 12000.0]
    tidy = pd.read_parquet(out / "sweep.parquet")
    assert np.allclose(tidy["cage_speed_rpm"], legacy["cage_speed_rpm"], rtol=1e-12)
    assert (out / f"quasistatic_sweep_{BEARING}.png").is_file() and (out / "sweep.nc").is_file()

    pts = tmp_path / "points.csv"
    pts.write_text("speed_rpm,fz_N,bearing\n3000,400,7008-ma2023\n9000,800,7218B\n")
    rc = main(["sweep", "--points-file", str(pts), "--out", str(tmp_path / "p"), "--scheduler", addr, "--no-progress"])
    assert rc == 0
    d = pd.read_csv(tmp_path / "p" / "sweep.csv")
    assert list(d["bearing"]) == ["7008-ma2023", "7218B"] and (d["status"] == "ok").all()

    import xarray as xr
    rc = main(["sweep", "--bearing", BEARING, "--grid", "speed_rpm=2000:12000:3", "--grid", "preload_N=100,400",
               "--out", str(tmp_path / "g"), "--scheduler", addr, "--no-progress"])
    assert rc == 0
    ds = xr.open_dataset(tmp_path / "g" / "sweep.nc", engine="scipy")
    assert ds["cage_speed_rpm"].dims == ("speed_rpm", "preload_N") and ds["cage_speed_rpm"].shape == (3, 2)
    assert (tmp_path / "g" / "sweep_skid_map.png").is_file()


@pytest.mark.slow
def test_fmu_sweep_one_instance_per_worker_and_agrees_with_the_dynamic_model(client2, tmp_path):
    """The FMU model: 4 points on 2 workers; each worker unpacks and instantiates the FMU once and resets it
    between its points (pigeonhole: one worker runs >= 2). Its steady cage speed agrees with the dynamic
    model's at the same points within 0.5 % (the same physics, stepped through FMI instead of directly; the
    window means differ by the sampling: communication points vs records)."""
    pytest.importorskip("fmpy")
    sys.path.insert(0, str(ROOT))
    from build_fmu import build
    fmu = build(tmp_path / "dist")
    base = {"bearing": BEARING, "fz_N": 500.0}
    grid = {"speed_rpm": [3000.0, 5000.0, 7000.0, 9000.0]}
    opts = {"window_s": 0.02, "max_time_s": 0.1, "steady_tol": 2e-3}
    df = S.run_sweep(S.SweepSpec(model="fmu", base=base, grid=grid, options=dict(opts, fmu=str(fmu))),
                     client=client2, progress=False)
    assert (df["status"] == "ok").all(), df["error"].tolist()

    def instances():
        from bearing_cosim import fmu_sweep as F
        return [(i.points, i.unpacks) for i in F._INSTANCES.values()]

    per_worker = [v for v in client2.run(instances).values() if v]
    assert all(len(v) == 1 and v[0][1] == 1 for v in per_worker)          # one instance, unpacked once
    assert sum(v[0][0] for v in per_worker) == 4 and max(v[0][0] for v in per_worker) >= 2
    dyn = S.run_sweep(S.SweepSpec(model="dynamic", base=base, grid=grid, options=opts), client=client2,
                      progress=False)
    assert (dyn["status"] == "ok").all() and dyn["steady"].all()
    assert np.allclose(df["cage_speed_rpm"], dyn["cage_speed_rpm"], rtol=5e-3)
    assert np.allclose(df["cage_speed_ratio"], dyn["cage_speed_ratio"], rtol=5e-3)


def test_profile_model_ends_where_the_dynamic_window_settles(client2, tmp_path):
    """The profile model (1000 rpm held, ramp to 3000 rpm, held to 0.3 s) at Fz 500 N: its final speed is the
    profile's, its final cage speed ratio lies within the ratio range it reports, and its final cage speed agrees
    within 0.5 % with the dynamic model held at 3000 rpm (the same steady state reached two ways)."""
    prof = tmp_path / "profile.csv"
    prof.write_text("time_s,speed_rpm\n0,1000\n0.05,1000\n0.15,3000\n0.3,3000\n")
    base = {"bearing": BEARING, "fz_N": 500.0}
    p = S.run_sweep(S.SweepSpec(model="profile", base=base, options={"profile": str(prof)}), client=client2,
                    progress=False).iloc[0]
    assert p["status"] == "ok", p["error"]
    assert p["final_speed_rpm"] == pytest.approx(3000.0, rel=1e-9)
    assert p["cage_speed_ratio_min"] <= p["cage_speed_ratio"] <= p["cage_speed_ratio_max"]
    d = S.run_sweep(S.SweepSpec(model="dynamic", base=dict(base, speed_rpm=3000.0),
                                options={"window_s": 0.02, "max_time_s": 0.2}), client=client2, progress=False).iloc[0]
    assert d["status"] == "ok" and d["steady"]
    assert p["cage_speed_rpm"] == pytest.approx(d["cage_speed_rpm"], rel=5e-3)


def test_batched_dynamic_and_profile_sweeps_equal_one_point_per_task(client2, tmp_path):
    """The dynamic model (three 2 ms windows) over speed x oil temperature x Fz on 7008-ma2023, one point per
    task against batches of 3 points advanced together on 2 threads (dynamics.advance_many; a batch constructs
    one model per oil temperature and copies it) and the automatic batching: identical tables (bit for bit). In
    the same batches one point fails at its start and one inside the integration: both are reported for that
    point only, the others complete. The profile model likewise (two points, tiny profile). Batched results go
    to the cache point by point, and a re-run computes only the failed points."""
    from sweep_helpers import FAIL_ADVANCE_FZ_N, FAIL_FZ_N
    spec = S.SweepSpec(model="sweep_helpers:FailingDynamic", base={"bearing": BEARING},
                       grid={"speed_rpm": [3000.0, 6000.0], "oil_temperature_C": [40.0, 80.0],
                             "fz_N": [300.0, FAIL_FZ_N, FAIL_ADVANCE_FZ_N]},
                       options={"window_s": 0.002, "max_time_s": 0.006})
    one = S.run_sweep(spec, client=client2, progress=False, batch_size=1)
    cache = tmp_path / "cache"
    three = S.run_sweep(spec, client=client2, progress=False, batch_size=3, threads_per_worker=2, cache_dir=cache)
    auto = S.run_sweep(spec, client=client2, progress=False, threads_per_worker=2)
    assert list(one["status"]) == ["ok", "failed", "failed"] * 4
    assert all("deliberate failure at fz_N" in e for e in one["error"][1::3])
    assert all("FloatingPointError: deliberate failure in the integration" in e for e in one["error"][2::3])
    assert (one["cage_speed_rpm"][::3] > 0).all() and one["settle_time_s"][0] == pytest.approx(0.006)
    assert one["friction_torque_Nm"][0] != one["friction_torque_Nm"][3]        # the oil temperature matters
    pd.testing.assert_frame_equal(_values(one), _values(three), check_exact=True)
    pd.testing.assert_frame_equal(_values(one), _values(auto), check_exact=True)
    assert three.attrs["computed"] == 12 and len(list(cache.glob("*.json"))) == 4    # failed points not cached
    again = S.run_sweep(spec, client=client2, progress=False, batch_size=3, threads_per_worker=2, cache_dir=cache)
    assert again.attrs["computed"] == 8 and again["cached"].sum() == 4
    pd.testing.assert_frame_equal(_values(one), _values(again), check_exact=True)

    prof = tmp_path / "profile.csv"
    prof.write_text("time_s,speed_rpm\n0,1000\n0.004,1000\n0.008,3000\n0.012,3000\n")
    pspec = S.SweepSpec(model="profile", base={"bearing": BEARING}, grid={"fz_N": [300.0, 900.0]},
                        options={"profile": str(prof)})
    p1 = S.run_sweep(pspec, client=client2, progress=False, batch_size=1)
    p2 = S.run_sweep(pspec, client=client2, progress=False, batch_size=2, threads_per_worker=2)
    assert (p1["status"] == "ok").all(), p1["error"].tolist()
    pd.testing.assert_frame_equal(_values(p1), _values(p2), check_exact=True)


def test_batch_progress_reports_each_point_when_it_finishes(client2, capsys):
    """Inside a batch of the dynamic model each point is reported when it finishes: the point failing at its start
    first, the one failing in its second window next, the two that run all three windows last; the sweep's progress
    bar follows these events and ends at the number of points."""
    from sweep_helpers import FAIL_ADVANCE_FZ_N, FAIL_FZ_N
    spec = S.SweepSpec(model="sweep_helpers:FailingDynamic", base={"bearing": BEARING, "speed_rpm": 4000.0},
                       grid={"fz_N": [300.0, FAIL_ADVANCE_FZ_N, FAIL_FZ_N, 600.0]},
                       options={"window_s": 0.002, "max_time_s": 0.006})
    events = []
    client2.subscribe_topic("test-batch-progress", lambda ev: events.append(ev[1]))
    try:
        res = client2.submit(S.run_point_batch, spec.model, spec.options, spec.points(), (0.05, 0.05), 2,
                             ("test-batch-progress", 7), pure=False).result()
        t0 = time.time()
        while len(events) < 4 and time.time() - t0 < 10:
            time.sleep(0.05)
    finally:
        client2.unsubscribe_topic("test-batch-progress")
    assert [r["status"] for r in res] == ["ok", "failed", "failed", "ok"]
    assert [e[0] for e in events] == [7] * 4
    assert [e[1] for e in events[:2]] == [2, 1] and sorted(e[1] for e in events[2:]) == [0, 3]
    df = S.run_sweep(spec, client=client2, progress=True, batch_size=4, threads_per_worker=2)
    assert list(df["status"]) == ["ok", "failed", "failed", "ok"]
    assert "4/4" in capsys.readouterr().err


def test_automatic_batch_size():
    """About four tasks per task slot, at least one point per advance_many thread, at most MAX_AUTO_BATCH, never
    more points than there are; a bad batch size or thread count is refused before any work."""
    assert S.auto_batch_size(8, 2) == 1 and S.auto_batch_size(64, 2) == 8 and S.auto_batch_size(10, 2) == 2
    assert S.auto_batch_size(8, 2, threads=2) == 2 and S.auto_batch_size(1, 4, threads=2) == 1
    assert S.auto_batch_size(100000, 2) == S.MAX_AUTO_BATCH
    for kw in ({"batch_size": 0}, {"batch_size": 2.5}, {"threads_per_worker": 0}):
        with pytest.raises(BearingInputError, match=list(kw)[0]):
            S.run_sweep(_grid_spec(), client=object(), progress=False, **kw)


def test_cache_key_follows_content_of_a_bearing_file(tmp_path):
    """A bearing given as a file is keyed by its content: the same content under another name gives the same key,
    an edited file another key; the code version and the model options are part of the key."""
    import json
    from bearing_core.bearing.geometry import preset_data
    d = preset_data(BEARING)
    f1, f2 = tmp_path / "a.json", tmp_path / "b.json"
    f1.write_text(json.dumps(d))
    f2.write_text(json.dumps(d))
    p1, p2 = (S.SweepSpec(base={"bearing": str(f), "speed_rpm": 1000.0}).validate()[0] for f in (f1, f2))
    k = S.point_key(p1, "quasistatic", {}, "v1")
    assert k == S.point_key(p2, "quasistatic", {}, "v1")
    assert k != S.point_key(p1, "quasistatic", {}, "v2") and k != S.point_key(p1, "quasistatic", {"control": "inner"}, "v1")
    f1.write_text(json.dumps(dict(d, number_of_balls=d["number_of_balls"] - 1)))
    assert k != S.point_key(p1, "quasistatic", {}, "v1")
    assert S.resolve_geometry(p1).Z == d["number_of_balls"] - 1
