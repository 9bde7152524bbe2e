"""SSP examples (ssp_examples/): the generated SSP archives are read by fmpy's SSP support and by libcosim (Open
Simulation Platform, C++, libcosimpy from PyPI); both masters run each example in fresh processes (exit status
checked, docs/fmu.md), agree with each other, and the systems are physically sound.

Short versions of the examples (the long run-ups are in ssp_examples/*/run.py): the rotor at constant speed
(0.15 s, 1500 steps of 1e-4 s), the drivetrain's first 0.3 s from rest (300 steps of 1e-3 s), the drive cycle
at fidelity 'map' compressed to 4 s (400 steps of 1e-2 s).
"""
import json
import math
import os
import sys
import time
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
SSP = ROOT / "ssp_examples"
for p in (str(ROOT), str(SSP), str(SSP / "rotor_bearings"), str(SSP / "drivetrain")):
    if p not in sys.path:
        sys.path.insert(0, p)

from masters import NS, run_subprocess, ssd_info  # noqa: E402


def _load(name, path):
    import importlib.util
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


rotor_make = _load("ssp_rotor_make", SSP / "rotor_bearings" / "make_ssp.py")
drive_make = _load("ssp_drive_make", SSP / "drivetrain" / "make_ssp.py")
drive_run = _load("ssp_drive_run", SSP / "drivetrain" / "run.py")


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    import build_examples
    d = tmp_path_factory.mktemp("ssp_build")
    fmus = build_examples.build_fmus(d)
    # the numba cache of the other FMU tests: the examples' bearing FMU has their code (plus an operating map,
    # which does not enter the code's hash), so its kernels are compiled once per session
    cache = tmp_path_factory.getbasetemp() / "fmu_numba_cache"
    cache.mkdir(exist_ok=True)
    env = dict(os.environ, BEARING_FMU_CACHE=str(cache))
    return {"dir": d, "fmus": fmus, "env": env}


def _both(build, ssp, tmp_path):
    R, wall = {}, {}
    for master in ("fmpy", "libcosim"):
        t0 = time.perf_counter()
        summary, R[master], code = run_subprocess(master, ssp, tmp_path / f"{master}.npz", env=build["env"],
                                                  timeout=900)
        wall[master] = time.perf_counter() - t0
        assert code == 0
        assert all(np.all(np.isfinite(v)) for v in R[master].values())
    print("wall times [s]:", {k: round(v, 1) for k, v in wall.items()})
    return R


def test_ssd_has_units_bindings_and_is_valid(build, tmp_path):
    """The generated SSD validates against the SSP 1.0 schema (fmpy's reader), every connector carries a type and
    its unit (defined in ssd:Units), every connected input is declared, bindings carry the bearing's choices
    (Enumerations, as Integer values) and the start values of the bearing inputs, and the OSP step annotation is there."""
    from fmpy.ssp.ssd import read_ssd
    ssp = rotor_make.make(tmp_path / "rotor.ssp", rotor_make.RotorDesign(stop_time=0.01), fmu_dir=build["fmus"])
    read_ssd(str(ssp))                                  # raises on a schema violation
    root = ET.fromstring(zipfile.ZipFile(ssp).read("SystemStructure.ssd"))
    units = {u.get("name") for u in root.findall("ssd:Units/ssc:Unit", NS)}
    for c in root.findall(".//ssd:Connector", NS):
        real = c.find("ssc:Real", NS)
        assert real is not None
        assert real.get("unit") is None or real.get("unit") in units
    info = ssd_info(ssp)
    a = info["components"]["bearing_A"]
    # the bearing's choices are Integer values of its Enumerations (settable by fmpy's stock simulate_ssp)
    from sspgen import enumeration_value
    fmu = build["fmus"] / "BearingFMU.fmu"
    assert a["parameters"]["coupling_choice"] == ("Integer", str(enumeration_value(fmu, "coupling_choice",
                                                                                 "displacement")))
    assert a["parameters"]["bearing_preset"] == ("Integer", str(enumeration_value(fmu, "bearing_preset", "7218B")))
    # ... and their String twins for libcosim (it does not handle FMI Enumerations)
    assert a["parameters"]["coupling"] == ("String", "displacement")
    assert a["parameters"]["bearing"] == ("String", "7218B")
    # every unit of a connector or a parameter binding is defined in ssd:Units
    for p in root.findall(".//ssv:Real", NS):
        assert p.get("unit") is None or p.get("unit") in units
    assert a["parameters"]["dz"][0] == "Real" and float(a["parameters"]["dz"][1]) > 0   # preloaded start pose
    assert info["step"] == 1e-4
    ends = {(c.get("endElement"), c.get("endConnector")) for c in root.findall(".//ssd:Connection", NS)}
    for name, comp in info["components"].items():
        for cn, kind in comp["connectors"]:
            if kind == "input":
                assert (name, cn) in ends
    # the reverse mapping of bearing B (mirrored frame) is in the rotor, not in connections
    assert not root.findall(".//ssc:LinearTransformation", NS)


def test_rotor_bearings_two_masters_statics(build, tmp_path):
    """Jeffcott rotor (100 kg disk, 7218B pair, fixed-position preload, 500 N axial load) at a constant 150 rad/s
    for 0.15 s, h = 1e-4 s, run by fmpy and by libcosim. Over the last two revolutions:
    * the radial reactions of the two bearings sum to the rotor's weight within 1% (the rotating unbalance force
      averages out over whole revolutions; the residue is the decaying start transient of the disk, ~8 N);
    * the axial reactions (bearing B's frame mirrored) sum to minus the axial load within 20 N (1% of bearing A's
      axial reaction);
    * each bearing's radial reaction equals its static load (system statics with bearing_core's quasi-static
      bearings, make_ssp.py) within 2%;
    * fmpy and libcosim agree: mean cage speeds within 0.1%, mean reactions within 0.5% (the masters differ only
      in fmpy's zero inputs during the first step and in time rounding)."""
    w = 150.0
    d = rotor_make.RotorDesign(speed_start=w, speed_end=w, ramp_start=0.0, ramp_end=0.0, stop_time=0.15)
    ssp = rotor_make.make(tmp_path / "rotor.ssp", d, fmu_dir=build["fmus"])
    meta = json.loads(Path(str(ssp) + ".json").read_text())
    R = _both(build, ssp, tmp_path)
    W = d.disk_mass * d.gravity
    for m, r in R.items():
        t = r["time"]
        assert abs(t[-1] - 0.15) < 2e-4 and len(t) >= 1499
        win = t > t[-1] - 2 * 2 * math.pi / w
        fy = (r["bearing_A.reaction_Fy"] + r["bearing_B.reaction_Fy"])[win].mean()
        fz = (r["bearing_A.reaction_Fz"] - r["bearing_B.reaction_Fz"])[win].mean()
        print(m, "sum Fy", fy, "W", W, "sum Fz", fz)
        assert abs(fy / W - 1) < 0.01, (m, fy, W)
        assert abs(fz + d.axial_load) < 20.0, (m, fz)
        for b in "AB":
            mean = r[f"bearing_{b}.reaction_Fy"][win].mean()
            assert abs(mean / meta[f"reaction_{b}"][1] - 1) < 0.02, (m, b, mean, meta[f"reaction_{b}"][1])
    f, l = R["fmpy"], R["libcosim"]
    win_f = f["time"] > 0.05
    win_l = l["time"] > 0.05
    for b in "AB":
        cf, cl = f[f"bearing_{b}.cage_speed"][win_f].mean(), l[f"bearing_{b}.cage_speed"][win_l].mean()
        assert abs(cf / cl - 1) < 1e-3, (b, cf, cl)
        for k in ("reaction_Fy", "reaction_Fz"):
            vf, vl = f[f"bearing_{b}.{k}"][win_f].mean(), l[f"bearing_{b}.{k}"][win_l].mean()
            assert abs(vf / vl - 1) < 5e-3, (b, k, vf, vl)


@pytest.mark.slow
def test_drivetrain_two_masters_energy(build, tmp_path):
    """Drivetrain from rest (induction motor, 0.3 kg.m2 shaft, fan, two 7218B bearings in load coupling with
    different loads), first 0.3 s, h = 1e-3 s, run by fmpy and by libcosim:
    * energy: motor work (motor FMU) = fan work (fan FMU) + bearing losses (time integral of the bearings'
      heat_flux_total) + kinetic energy of the shaft (shaft FMU) within 2% of the motor work; the residual holds
      the bearings' own kinetic energy (balls, cage) and the one-step lag of explicit coupling;
    * the shaft-side bookkeeping closes to 1e-9 of the motor work;
    * the masters agree: final speed within 1% (fmpy feeds 0 to every input in its first step, so its shaft
      starts one step later), mean bearing losses over the last 0.1 s within 10% (chaotic cage and pocket
      contacts at low speed: compare means)."""
    d = drive_make.DrivetrainDesign(stop_time=0.3)
    ssp = drive_make.make(tmp_path / "drivetrain.ssp", d, fmu_dir=build["fmus"])
    R = _both(build, ssp, tmp_path)
    for m, r in R.items():
        e = drive_run.energy_balance(r, d.step, drive_make.asdict(d))
        print(m, json.dumps(e))
        assert r["shaft.shaft_speed"][-1] > 5.0                     # it runs up on its own
        assert abs(e["residual_rel"]) < 0.02, (m, e)
        assert abs(e["shaft_side_residual_J"]) < 1e-9 * e["motor_work_J"] + 1e-9, (m, e)
    f, l = R["fmpy"], R["libcosim"]
    assert abs(f["shaft.shaft_speed"][-1] / l["shaft.shaft_speed"][-1] - 1) < 0.01
    qf = (f["bearing_A.heat_flux_total"] + f["bearing_B.heat_flux_total"])[f["time"] > 0.2].mean()
    ql = (l["bearing_A.heat_flux_total"] + l["bearing_B.heat_flux_total"])[l["time"] > 0.2].mean()
    assert abs(qf / ql - 1) < 0.10, (qf, ql)


def test_helper_fmus_run_on_the_project_fmi_layer(build):
    """Every FMU of the examples carries the project's FMI layer and model process, none pythonfmu's exported
    native library."""
    for fmu in sorted(Path(build["fmus"]).glob("*.fmu")):
        with zipfile.ZipFile(fmu) as z:
            names = z.namelist()
            tool = ET.fromstring(z.read("modelDescription.xml")).get("generationTool")
        assert "resources/model_process.py" in names and "native FMI 2.0 layer" in tool, fmu.name
        assert not any("pythonfmu-export" in n for n in names), fmu.name


def test_examples_exit_normally_in_fresh_processes(build, tmp_path):
    """Each example briefly (10 steps) in a fresh master process, 3 times per example and master (12 runs; 200
    runs per host kind: bench/fmu_exit_check.py):
    every run exits with status 0 and prints its result, with nothing on stderr about a crash at exit."""
    ssps = {"rotor": rotor_make.make(tmp_path / "rotor.ssp", rotor_make.RotorDesign(stop_time=1e-3),
                                     fmu_dir=build["fmus"]),
            "drivetrain": drive_make.make(tmp_path / "drivetrain.ssp", drive_make.DrivetrainDesign(stop_time=0.01),
                                          fmu_dir=build["fmus"])}
    import subprocess
    codes = []
    for name, ssp in ssps.items():
        for master in ("fmpy", "libcosim"):
            for k in range(3):
                cmd = [sys.executable, str(SSP / "masters.py"), master, str(ssp), str(tmp_path / f"{name}{k}.npz")]
                r = subprocess.run(cmd, capture_output=True, text=True, env=build["env"], timeout=300)
                codes.append((name, master, r.returncode))
                assert r.returncode == 0, f"{name} / {master}: exit {r.returncode}\n{r.stderr[-2000:]}"
                assert "RESULT " in r.stdout
                for bad in ("corrupted", "double free", "Segmentation", "Aborted"):
                    assert bad not in r.stderr, f"{name} / {master}: {r.stderr[-2000:]}"
    assert len(codes) == 12 and all(c == 0 for _, _, c in codes)


def test_rotor_bearings_at_quasi_static_statics(build, tmp_path):
    """The rotor of test_rotor_bearings_two_masters_statics with both bearings at fidelity 'quasi-static'
    (displacement coupling: each bearing's steady forces at the pose the rotor gives), run by libcosim at a
    constant 150 rad/s for 0.12 s: the radial reactions sum to the weight within 1 %, the axial ones to minus the
    axial load within 20 N, each radial reaction within 2 % of the system statics (make_ssp.py)."""
    w = 150.0
    d = rotor_make.RotorDesign(speed_start=w, speed_end=w, ramp_start=0.0, ramp_end=0.0, stop_time=0.12,
                               fidelity="quasi-static")
    ssp = rotor_make.make(tmp_path / "rotor_qs.ssp", d, fmu_dir=build["fmus"])
    meta = json.loads(Path(str(ssp) + ".json").read_text())
    summary, r, code = run_subprocess("libcosim", ssp, tmp_path / "libcosim.npz", env=build["env"], timeout=900)
    assert code == 0 and all(np.all(np.isfinite(v)) for v in r.values())
    t = r["time"]
    assert abs(t[-1] - 0.12) < 2e-4
    win = t > t[-1] - 2 * 2 * math.pi / w
    W = d.disk_mass * d.gravity
    fy = (r["bearing_A.reaction_Fy"] + r["bearing_B.reaction_Fy"])[win].mean()
    fz = (r["bearing_A.reaction_Fz"] - r["bearing_B.reaction_Fz"])[win].mean()
    assert abs(fy / W - 1) < 0.01, (fy, W)
    assert abs(fz + d.axial_load) < 20.0, fz
    for b in "AB":
        mean = r[f"bearing_{b}.reaction_Fy"][win].mean()
        assert abs(mean / meta[f"reaction_{b}"][1] - 1) < 0.02, (b, mean, meta[f"reaction_{b}"][1])
        assert 0.35 < r[f"bearing_{b}.cage_speed"][win].mean() / w < 0.5


@pytest.mark.parametrize("bearing_fmu", ["BearingFMU", "BearingMapFMU"])
def test_drivetrain_drive_cycle_at_map(build, tmp_path, bearing_fmu):
    """The drive cycle (make_ssp.drive_cycle) compressed to 4 s, both bearings at fidelity 'map' (the shipped
    7218B oil map: embedded in BearingFMU, or BearingMapFMU, the level all in C), h = 1e-2 s, run by libcosim:
    inverter run-up 0-1 s from 573 rpm, base load, full
    load at 1.5 s, part load at 2 s, supply off at 2.5 s, idle at 15 Hz from 3.5 s.
    * every bearing's reaction equals minus the load the duty cycle commanded one step earlier within 0.5 % at
      every step (the map interpolates steady states that balance the load; measured 0.04 %), and the
      commanded loads are the phases' values;
    * the shaft runs at the rated speed after the run-up, falls monotonically while the supply is off, and
      idles just below the 15 Hz synchronous speed (900 rpm), above the map's 500 rpm;
    * the friction torque of each bearing is larger under full load than under part load;
    * energy: motor work = fan work + bearing heat + kinetic energy change within 2 % of the motor work. At
      h = 1e-2 s the explicit coupling's one-step lag makes the residual (run.coupling_lag): h w dT at each
      torque change (137 J for switching off 45 N.m at 305 rad/s, ~300 J for re-energising into generator
      braking) and -(J h / 2) a^2 h per step, together -1.4 % of the motor work here (-0.002 % in the 60 s
      cycle at h = 1e-3 s). With that estimate taken out the balance closes within 0.2 % (measured 0.04 %:
      the map's heat against the work of its friction torque, separate window means of the dynamic model)."""
    if not (ROOT / "maps" / "7218B_oil.nc").is_file():
        pytest.skip("no shipped map maps/7218B_oil.nc")
    cycle = drive_make.drive_cycle(t_runup=1.0, t_step1=1.5, t_step2=2.0, t_off=2.5, t_idle=3.5)
    d = drive_make.DrivetrainDesign(fidelity="map", speed0=60.0, stop_time=4.0, step=1e-2, duty_cycle=cycle,
                                    bearing_fmu=bearing_fmu)
    ssp = drive_make.make(tmp_path / "cycle.ssp", d, fmu_dir=build["fmus"])
    t0 = time.perf_counter()
    summary, r, code = run_subprocess("libcosim", ssp, tmp_path / "libcosim.npz", env=build["env"], timeout=900)
    print("wall time [s]:", round(time.perf_counter() - t0, 1))
    assert code == 0 and all(np.all(np.isfinite(v)) for v in r.values())
    t, w = r["time"], r["shaft.shaft_speed"]
    assert len(t) == 400 and abs(t[-1] - 4.0) < 1e-9
    # loads: the bearings' step i runs with the duty cycle's output of step i - 1
    ph_in = np.round(np.concatenate([r["duty.phase"][:1], r["duty.phase"][:-1]])).astype(int)
    k = {p.name: i for i, p in enumerate(cycle, 1)}
    assert set(ph_in) == set(range(2, len(cycle) + 1))
    for b in "AB":
        for j, f in enumerate(("Fx", "Fz")):
            cmd = np.concatenate([r[f"duty.{f}_{b}"][:1], r[f"duty.{f}_{b}"][:-1]])
            for p in range(3, len(cycle) + 1):
                assert np.all(cmd[ph_in == p] == getattr(cycle[p - 1], f"load_{b}")[j]), (b, f, p)
            dev = np.abs(r[f"bearing_{b}.reaction_{f}"] + cmd) / cmd
            assert dev.max() < 5e-3, (b, f, dev.max(), t[np.argmax(dev)])
    # speed: rated in the run-up, monotonic coast-down without supply, idle near 15 Hz
    rpm = w * drive_run.RPM
    rated = (ph_in == k["full load"]) | (ph_in == k["part load"])
    assert 2890.0 < rpm[rated].min() and rpm[rated].max() < 3000.0
    off = ph_in == k["coast-down"]
    assert np.all(r["motor.torque"][off] == 0.0)
    assert np.all(np.diff(w[off]) < 0.0) and rpm[off][-1] < 0.8 * rpm[off][0]
    assert 850.0 < rpm[-1] < 900.0 and rpm.min() > 500.0
    for b in "AB":
        tq = r[f"bearing_{b}.friction_torque"]
        assert tq[ph_in == k["full load"]].mean() > 1.3 * tq[ph_in == k["part load"]].mean(), b
    e = drive_run.energy_balance(r, d.step, drive_make.asdict(d))
    print(json.dumps(e))
    assert abs(e["residual_rel"]) < 0.02, e
    assert abs(e["residual_after_lag_rel"]) < 2e-3, e
    assert abs(e["shaft_side_residual_J"]) < 1e-9 * e["motor_work_J"], e
