"""The bearing FMU (FMI 2.0 co-simulation) built by build_fmu.py and driven by fmpy in fresh processes."""
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
RPM = math.pi / 30
OUT = ["reaction_Fx", "reaction_Fy", "reaction_Fz", "cage_speed", "cage_shaft_ratio", "cage_shaft_ratio_theory",
       "friction_torque", "heat_flux_total", "max_contact_pressure", "skid_ratio"]


@pytest.fixture(scope="session")
def fmu(tmp_path_factory):
    sys.path.insert(0, str(HERE.parent))
    from build_fmu import build
    d = tmp_path_factory.mktemp("dist")
    path = build(d)
    cache = tmp_path_factory.getbasetemp() / "fmu_numba_cache"   # shared with tests/test_native_host.py
    cache.mkdir(exist_ok=True)
    return {"path": str(path), "cache": str(cache)}


def drive(fmu, spec, tmp_path, name="spec.json"):
    spec = dict(spec, fmu=fmu["path"])
    spec.setdefault("outputs", OUT)
    p = tmp_path / name
    p.write_text(json.dumps(spec))
    env = dict(os.environ, BEARING_FMU_CACHE=fmu["cache"])
    r = subprocess.run([sys.executable, str(HERE / "fmu_driver.py"), str(p)], capture_output=True, text=True,
                       env=env, timeout=600)
    # the host process exits normally (C exit handlers run) and must exit cleanly (docs/fmu.md)
    assert r.returncode == 0, (r.returncode, r.stderr[-2000:])
    line = [ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")][-1]
    res = json.loads(line[7:])
    res["log"] = r.stdout
    return res


def _vals(rows, name):
    k = OUT.index(name)
    return np.array([r["values"][k] for r in rows if r["status"] == 0])


def steady_spec(n=300, h=1e-3, rpm=1000.0, fx=1000.0, fz=3000.0, **params):
    inp = {"shaft_speed": rpm * RPM, "Fx": fx, "Fz": fz}
    return {"params": params, "start_inputs": inp, "steps": [[h, inp]] * n}


def test_model_description_valid(fmu):
    """fmpy.validation.validate_fmu reports nothing; units and variabilities are declared."""
    from fmpy import read_model_description
    from fmpy.validation import validate_fmu
    assert validate_fmu(fmu["path"]) == []
    md = read_model_description(fmu["path"])
    v = {x.name: x for x in md.modelVariables}
    assert v["shaft_speed"].causality == "input" and v["shaft_speed"].unit == "rad/s"
    assert v["reaction_Fz"].causality == "output" and v["reaction_Fz"].unit == "N"
    assert v["friction_torque"].unit == "N.m" and v["heat_flux_total"].unit == "W"
    assert v["bearing"].causality == "parameter" and v["bearing"].variability == "fixed"
    assert md.coSimulation.canGetAndSetFMUstate


def test_steady_reactions_heat_and_finite_outputs(fmu, tmp_path):
    """Constant inputs (7218B, 1000 rpm, Fx 1000 N, Fz 3000 N): the FMU starts in equilibrium (the first
    outputs already carry the load), the mean reactions equal the applied loads (0.5%), the mean heat
    flux equals friction torque x speed within 2% (energy balance at steady state), all outputs finite,
    and the cage-shaft ratio sits within 2% of its spin-free theoretical value."""
    res = drive(fmu, steady_spec(), tmp_path)
    rows = res["rows"]
    assert all(r["status"] == 0 for r in rows)
    assert all(np.all(np.isfinite(r["values"])) for r in rows)
    assert abs(-res["initial"][OUT.index("reaction_Fz")] / 3000 - 1) < 0.01
    late = rows[100:]
    assert abs(-_vals(late, "reaction_Fz").mean() / 3000 - 1) < 0.005
    assert abs(-_vals(late, "reaction_Fx").mean() / 1000 - 1) < 0.005
    heat = _vals(late, "heat_flux_total").mean()
    drive_power = _vals(late, "friction_torque").mean() * 1000 * RPM
    assert abs(heat / drive_power - 1) < 0.02, (heat, drive_power)
    csr = _vals(late, "cage_shaft_ratio").mean()
    assert abs(csr / _vals(late, "cage_shaft_ratio_theory").mean() - 1) < 0.02


def test_outputs_equal_bearing_core(fmu, tmp_path):
    """The FMU only translates: its outputs equal bearing_core.session.cosim.CoSimSession's for the same inputs
    and steps (same numbers: relative 1e-9, and 1e-9 of the 2 kN load scale for values near zero such as
    reaction_Fy, where round-off of a different compilation of the same kernels shows)."""
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    # fixed-step RK4 on both sides: with adaptive steps, rounding differences between two compilations of
    # the same kernels (the FMU has its own numba cache) can flip a step decision, after which the runs
    # differ at the integrator's tolerance
    spec = steady_spec(n=40, rpm=2000.0, fx=500.0, fz=2000.0, integrator="rk4")
    res = drive(fmu, spec, tmp_path)
    s = CoSimSession(CoSimParameters(integrator="rk4"))
    s.initialize(0.0, spec["start_inputs"])
    t = 0.0
    for (h, inp), row in zip(spec["steps"], res["rows"]):
        o = s.step(t, h, inp)
        t += h
        assert np.allclose(row["values"], [o[k] for k in OUT], rtol=1e-9, atol=2e-6)


def test_communication_step_independence(fmu, tmp_path):
    """The FMU integrates exactly to t + h inside the compiled integrator: h = 1 ms and h = 0.1 ms give the
    same mean cage speed (0.2%) and reactions (0.5%) over 0.1-0.2 s."""
    a = drive(fmu, steady_spec(n=200, h=1e-3), tmp_path, "a.json")["rows"]
    b = drive(fmu, steady_spec(n=2000, h=1e-4), tmp_path, "b.json")["rows"]
    ca, cb = _vals(a[100:], "cage_speed").mean(), _vals(b[1000:], "cage_speed").mean()
    assert abs(ca / cb - 1) < 0.002
    assert abs(_vals(a[100:], "reaction_Fz").mean() / _vals(b[1000:], "reaction_Fz").mean() - 1) < 0.005


def test_bad_inputs_discard_and_recover(fmu, tmp_path):
    """NaN speed, a speed beyond the +-2e4 rad/s range (negative speeds are valid: reverse rotation) and a load beyond the 4.2 GPa contact-stress limit give fmi2Discard with a
    log message naming the cause, and the instance stays usable; an unknown preset fails initialisation
    with a message naming the parameter."""
    good = {"shaft_speed": 1000 * RPM, "Fx": 1000.0, "Fz": 3000.0}
    steps = [[1e-3, good]] * 3 + [[1e-3, dict(good, shaft_speed=float("nan"))],
                                  [1e-3, dict(good, shaft_speed=-3.0e4)],
                                  [1e-3, dict(good, Fz=5e5)]] + [[1e-3, good]] * 3
    res = drive(fmu, {"params": {}, "start_inputs": good, "steps": steps}, tmp_path)
    st = [r["status"] for r in res["rows"]]
    assert st[:3] == [0, 0, 0] and st[-3:] == [0, 0, 0]
    assert all(s != 0 for s in st[3:6])
    log = res["log"]
    assert "shaft_speed" in log and "contact pressure" in log
    bad = drive(fmu, {"params": {"bearing": "no-such"}, "start_inputs": good, "steps": []}, tmp_path, "bad.json")
    assert bad["init_error"] is not None
    assert "bearing" in bad["log"]


def test_two_instances_are_independent(fmu, tmp_path):
    """Two bearings in one process (two instances of the FMU) with different loads give exactly the
    results of each bearing run alone."""
    inp1 = {"shaft_speed": 1500 * RPM, "Fx": 800.0, "Fz": 2500.0}
    inp2 = {"shaft_speed": 1500 * RPM, "Fx": 0.0, "Fz": 4000.0}
    steps = [[1e-3, inp1]] * 30
    both = drive(fmu, {"mode": "two", "params": {}, "start_inputs": inp1, "start_inputs_2": inp2,
                       "inputs_2": inp2, "steps": steps}, tmp_path, "two.json")
    alone1 = drive(fmu, {"params": {}, "start_inputs": inp1, "steps": steps}, tmp_path, "one.json")
    alone2 = drive(fmu, {"params": {}, "start_inputs": inp2, "steps": [[1e-3, inp2]] * 30}, tmp_path, "one2.json")
    for x, y in zip(both["rows"], alone1["rows"]):
        assert x["values"] == y["values"]
    for x, y in zip(both["rows2"], alone2["rows"]):
        assert x["values"] == y["values"]


def test_get_set_state_rollback(fmu, tmp_path):
    """fmi2GetFMUstate / fmi2SetFMUstate: steps repeated after restoring a saved state reproduce the same
    outputs exactly (rollback for iterative masters)."""
    inp = {"shaft_speed": 1000 * RPM, "Fx": 500.0, "Fz": 2000.0}
    res = drive(fmu, {"mode": "rollback", "params": {}, "start_inputs": inp, "steps": [[1e-3, inp]],
                      "n_before": 5, "n_after": 5}, tmp_path)
    assert [r["values"] for r in res["a"]] == [r["values"] for r in res["b"]]


@pytest.mark.slow
def test_acceleration_profile_skidding(fmu, tmp_path):
    """Seed 000's ramp (10,000 rpm/s) from 1000 rpm, as 1 ms input steps, Coulomb traction with the cage
    friction equal to mu (solid lubricant): mu = 0.001 skids (cage-shaft ratio below 80% of its theoretical
    value at the end of a 0.3 s ramp) while mu = 0.1 tracks within 5%."""
    n0, rate, h = 1000.0, 10000.0, 1e-3
    steps = []
    for k in range(400):
        t = k * h
        n = n0 + rate * max(0.0, t - 0.1) if t < 0.4 else n0 + rate * 0.3
        steps.append([h, {"shaft_speed": n * RPM, "Fx": 1000.0, "Fz": 3000.0}])
    ratios = {}
    for mu in (0.001, 0.1):
        res = drive(fmu, {"params": {"traction_model": "coulomb", "friction_coefficient": mu,
                                     "cage_friction_coefficient": mu},
                          "start_inputs": steps[0][1], "steps": steps}, tmp_path, f"mu{mu}.json")
        rows = res["rows"]
        assert all(r["status"] == 0 for r in rows)
        ratios[mu] = _vals(rows[390:], "cage_shaft_ratio").mean() / _vals(rows[390:], "cage_shaft_ratio_theory").mean()
    assert ratios[0.001] < 0.8
    assert abs(ratios[0.1] - 1) < 0.05


def test_runs_in_libcosim_like_in_fmpy(fmu, tmp_path):
    """A second, independent FMI 2.0 master (libcosim, C++, via libcosimpy from PyPI) runs the FMU with the
    same constant inputs and 1 ms steps. The two masters round the communication points differently
    (libcosim: integer nanoseconds; fmpy: accumulated floats), which the chaotic cage motion amplifies, so
    the comparison is on means over 0.1-0.2 s: cage speed within 0.3%, reactions within 0.5%."""
    inp = {"shaft_speed": 1000 * RPM, "Fx": 1000.0, "Fz": 3000.0}
    spec = {"fmu": fmu["path"], "h": 1e-3, "t_end": 0.2, "inputs": inp, "outputs": OUT}
    p = tmp_path / "cosim.json"
    p.write_text(json.dumps(spec))
    env = dict(os.environ, BEARING_FMU_CACHE=fmu["cache"])
    r = subprocess.run([sys.executable, str(HERE / "libcosim_driver.py"), str(p)], capture_output=True,
                       text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    res = json.loads([ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")][-1][7:])
    assert res["ok"]
    ref = drive(fmu, steady_spec(n=200), tmp_path)["rows"][100:]
    for k, tol in (("cage_speed", 0.003), ("reaction_Fz", 0.005), ("reaction_Fx", 0.005)):
        a = np.mean(res["series"][k][-100:])
        b = _vals(ref, k).mean()
        assert abs(a / b - 1) < tol, (k, a, b)


def test_bearing_simulate_command(fmu, tmp_path):
    """`bearing simulate` drives the FMU with fmpy through a user's profile CSV (speed and load columns)
    and writes CSV (units in the header), plot and summary; bad arguments exit 2 with one line."""
    prof = tmp_path / "p.csv"
    prof.write_text("time_s,speed_rpm,Fz_N\n0,1000,2000\n0.02,1500,2000\n0.04,1500,2500\n")
    env = dict(os.environ, BEARING_FMU_CACHE=fmu["cache"])
    cmd = [sys.executable, "-m", "bearing_cosim.cli", "simulate", "--fmu", fmu["path"], "--profile", str(prof),
           "--fx", "300", "--out", str(tmp_path / "o")]
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    s = json.loads((tmp_path / "o" / "fmu_simulation_summary.json").read_text())
    assert s["simulated_s"] == pytest.approx(0.04)
    head = (tmp_path / "o" / "fmu_simulation.csv").read_text().splitlines()
    assert "cage_speed [rad/s]" in head[0] and "heat_flux_total [W]" in head[0]
    last = head[-1].split(",")
    assert abs(float(last[head[0].split(",").index("reaction_Fz [N]")]) + 2500) < 0.05 * 2500
    for bad in (["--profile", "/no/file.csv"], ["--step", "0"], ["--fmu", "/no.fmu"]):
        r = subprocess.run([sys.executable, "-m", "bearing_cosim.cli", "simulate", "--fmu", fmu["path"], *bad],
                           capture_output=True, text=True, env=env, timeout=120)
        assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, (bad, r.stderr)


def _profile_steps(points, h=1e-3, loads=None):
    """Held-per-step inputs sampled from piecewise-linear (t, rpm) points (and optional (t, Fz) loads)."""
    t_end = points[-1][0]
    steps = []
    for k in range(int(round(t_end / h))):
        t = k * h
        n = float(np.interp(t, [p[0] for p in points], [p[1] for p in points]))
        fz = 3000.0 if loads is None else float(np.interp(t, [p[0] for p in loads], [p[1] for p in loads]))
        steps.append([h, {"shaft_speed": n * RPM, "Fx": 1000.0, "Fz": fz}])
    return steps


@pytest.mark.slow
def test_deceleration_start_from_rest_and_load_step(fmu, tmp_path):
    """Three more profiles as input signals: a deceleration (3000 -> 1000 rpm in 0.2 s), a start from rest
    (0 -> 2000 rpm in 0.2 s) and a step of axial load during rotation (3000 -> 5000 N at 0.1 s). Every step
    is accepted with finite outputs; the cage follows the shaft (cage-shaft ratio within 5% of its
    theoretical value over the last 50 ms); after the load step the reaction settles on the new load
    (0.5%) and the heat flux rises with the load."""
    cases = {
        "decel": _profile_steps([(0.0, 3000.0), (0.05, 3000.0), (0.25, 1000.0), (0.35, 1000.0)]),
        "rest": _profile_steps([(0.0, 0.0), (0.05, 0.0), (0.25, 2000.0), (0.35, 2000.0)]),
        "load": _profile_steps([(0.0, 2000.0), (0.3, 2000.0)], loads=[(0.0, 3000.0), (0.1, 3000.0),
                                                                       (0.1 + 1e-9, 5000.0), (0.3, 5000.0)]),
    }
    out = {}
    for name, steps in cases.items():
        res = drive(fmu, {"params": {}, "start_inputs": steps[0][1], "steps": steps}, tmp_path, f"{name}.json")
        rows = res["rows"]
        assert all(r["status"] == 0 for r in rows), name
        assert all(np.all(np.isfinite(r["values"])) for r in rows), name
        out[name] = rows
        tail = rows[-50:]
        ratio = _vals(tail, "cage_shaft_ratio").mean() / _vals(tail, "cage_shaft_ratio_theory").mean()
        assert abs(ratio - 1) < 0.05, (name, ratio)
    rows = out["load"]
    assert abs(-_vals(rows[-100:], "reaction_Fz").mean() / 5000 - 1) < 0.005
    assert abs(-_vals(rows[50:100], "reaction_Fz").mean() / 3000 - 1) < 0.005
    assert _vals(rows[-100:], "heat_flux_total").mean() > _vals(rows[50:100], "heat_flux_total").mean()


def test_geometry_overrides(fmu, tmp_path):
    """Overriding the preset's free contact angle (40 -> 25 deg on the 7218B) gives the loaded contact angle
    that the quasi-static model predicts for the overridden bearing (0.5 deg); a negative angle fails
    initialisation with a message naming the parameter."""
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.models.quasistatic import solve_quasistatic
    inp = {"shaft_speed": 1000 * RPM, "Fx": 0.0, "Fz": 3000.0}
    outs = OUT + ["alpha_i_mean"]
    res = drive(fmu, {"params": {"free_contact_angle": math.radians(25.0)}, "start_inputs": inp,
                      "steps": [[1e-3, inp]] * 20, "outputs": outs}, tmp_path)
    ai = np.mean([r["values"][-1] for r in res["rows"]])
    qs = solve_quasistatic(load_preset("7218B", alpha0=math.radians(25.0)), 1000 * RPM, (0, 0, 3000, 0, 0),
                           stiffness=False)
    assert abs(math.degrees(ai - qs.alpha_i[0])) < 0.5
    bad = drive(fmu, {"params": {"free_contact_angle": -0.1}, "start_inputs": inp, "steps": []}, tmp_path, "b.json")
    assert bad["init_error"] is not None and "free_contact_angle" in bad["log"]


def test_fmpy_statuses(fmu, tmp_path):
    """Through fmpy (its exceptions carry the status): a failed initialisation (reversed axial load) is
    fmi2Error, not fatal, and getReal/doStep after it are fmi2Error; after a good initialisation a fixed
    parameter set is fmi2Error and reads back unchanged; a state serialized to bytes and deserialized (into a
    new instance's state too) repeats the step bit for bit; bytes that are no state are fmi2Error and the
    instance keeps stepping (OK); every refusal's reason reaches the logger."""
    code = r"""
import json, sys
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi1 import FMICallException
path = sys.argv[1]
md = read_model_description(path)
vr = {v.name: v.valueReference for v in md.modelVariables}
logs = []
from fmpy.fmi2 import fmi2CallbackFunctions, fmi2CallbackLoggerTYPE, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE
from fmpy import calloc, free
def logger(c, name, status, cat, msg):
    logs.append([status, cat.decode(), msg.decode()])
cb = fmi2CallbackFunctions()
cb.logger = fmi2CallbackLoggerTYPE(logger)
cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
out = {}
def st(name, fn):
    try:
        fn(); out[name] = 0
    except FMICallException as e:
        out[name] = e.status
unz = extract(path)
f = FMU2Slave(guid=md.guid, unzipDirectory=unz, modelIdentifier="BearingFMU", instanceName="a")
f.instantiate(callbacks=cb); f.setupExperiment(startTime=0.0); f.enterInitializationMode()
f.setReal([vr["Fz"]], [-2000.0])
st("exit_failed", f.exitInitializationMode)
st("get_after_failed", lambda: f.getReal([vr["cage_speed"]]))
st("step_after_failed", lambda: f.doStep(0.0, 1e-3))
f.terminate(); f.freeInstance()
g = FMU2Slave(guid=md.guid, unzipDirectory=unz, modelIdentifier="BearingFMU", instanceName="b")
g.instantiate(callbacks=cb); g.setupExperiment(startTime=0.0); g.enterInitializationMode()
st("exit_ok", g.exitInitializationMode)
st("set_fixed", lambda: g.setReal([vr["friction_coefficient"]], [0.3]))
out["fixed_value"] = g.getReal([vr["friction_coefficient"]])[0]
s = g.getFMUstate()
data = g.serializeFMUstate(s)
out["nbytes"] = len(data)
st("step_after_serialize", lambda: g.doStep(0.0, 1e-3))
a = g.getReal([vr["cage_speed"]])[0]
s2 = g.deSerializeFMUstate(data)
g.setFMUstate(s2)
st("step_from_bytes", lambda: g.doStep(0.0, 1e-3))
out["same"] = g.getReal([vr["cage_speed"]])[0] == a
st("deserialize_garbage", lambda: g.deSerializeFMUstate(b"not a state"))
st("step_after_garbage", lambda: g.doStep(1e-3, 1e-3))
g.terminate(); g.freeInstance()
print("RESULT", json.dumps({"status": out, "logs": logs}))
"""
    env = dict(os.environ, BEARING_FMU_CACHE=fmu["cache"])
    r = subprocess.run([sys.executable, "-c", code, fmu["path"]], capture_output=True, text=True, env=env,
                       timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    res = json.loads(r.stdout.split("RESULT", 1)[1])
    st, logs = res["status"], res["logs"]
    assert st["exit_failed"] == 3 and st["get_after_failed"] == 3 and st["step_after_failed"] == 3
    assert st["exit_ok"] == 0 and st["set_fixed"] == 3 and st["fixed_value"] == 0.1
    assert st["step_after_serialize"] == 0 and st["step_from_bytes"] == 0 and st["same"] is True
    assert st["deserialize_garbage"] == 3 and st["step_after_garbage"] == 0 and st["nbytes"] > 1000
    errs = [m for s, c, m in logs if s == 3 and c == "logError"]
    assert any("reversed axial load" in m for m in errs), logs
    assert any("friction_coefficient is a fixed parameter" in m for m in errs), logs
    assert any("fmi2DeSerializeFMUstate: not a serialized state of this FMU" in m for m in errs), logs
