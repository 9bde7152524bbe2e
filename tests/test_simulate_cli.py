"""`bearing simulate`: any FMU parameter by name (--param), --stop-time, negative numbers as values, a
user bearing file as the FMU's bearing, and `bearing --version`."""
import csv
import json
import subprocess
import sys

import pytest

from bearing_core.bearing.geometry import preset_data


def _cli(*args, timeout=600):
    return subprocess.run([sys.executable, "-m", "bearing_cosim.cli", *args], capture_output=True, text=True,
                          timeout=timeout)


@pytest.fixture(scope="module")
def fmu(tmp_path_factory):
    from build_fmu import build

    return str(build(tmp_path_factory.mktemp("fmu")))


def test_version():
    r = _cli("--version")
    assert r.returncode == 0 and r.stdout.startswith("bearing-tribodynamics ")


def test_negative_number_is_a_value_not_an_option(fmu):
    r = _cli("simulate", "--fmu", fmu, "--step", "-1e-3")
    assert r.returncode == 2
    assert "--step = -0.001 is invalid" in r.stderr and "expected one argument" not in r.stderr


def test_param_errors_name_the_parameter(fmu):
    r = _cli("simulate", "--fmu", fmu, "--param", "no_such_parameter=1")
    assert r.returncode == 2 and "no_such_parameter is not a parameter" in r.stderr and "integrator" in r.stderr
    r = _cli("simulate", "--fmu", fmu, "--param", "oil_temperature=warm")
    assert r.returncode == 2 and "oil_temperature" in r.stderr and "Real" in r.stderr
    r = _cli("simulate", "--fmu", fmu, "--param", "integrator")
    assert r.returncode == 2 and "NAME=VALUE" in r.stderr


@pytest.mark.slow
def test_bearing_file_params_and_stop_time(fmu, tmp_path):
    """A user bearing file (the 7218B preset's fields) as the FMU's bearing, the fixed-step integrator
    set by --param, and a run cut at --stop-time before the profile's end: the CSV ends at the stop time
    and the cage turns (speed between 0 and the shaft's)."""
    bfile = tmp_path / "my218.json"
    bfile.write_text(json.dumps(preset_data("7218B")))
    prof = tmp_path / "p.csv"
    prof.write_text("time_s,speed_rpm\n0,2000\n1,2000\n")
    out = tmp_path / "out"
    r = _cli("simulate", "--fmu", fmu, "--profile", str(prof), "--fz", "3000", "--fx", "-500",
             "--bearing", str(bfile), "--param", "integrator=rk4", "--stop-time", "0.02", "--out", str(out))
    assert r.returncode == 0, r.stderr
    summ = json.loads((out / "fmu_simulation_summary.json").read_text())
    assert summ["parameters"]["integrator"] == "rk4" and summ["parameters"]["bearing"] == str(bfile)
    rows = list(csv.reader((out / "fmu_simulation.csv").open()))
    assert float(rows[-1][0]) == pytest.approx(0.02, abs=1e-9)
    assert 0.0 < summ["final_cage_speed_rpm"] < 2000.0
