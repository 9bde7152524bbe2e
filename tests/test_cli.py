"""The `bearing` console script contract."""
import json
import subprocess
import sys

import pytest

from bearing_core.cli import main


def test_quasistatic_json_keys(capsys):
    rc = main(["quasistatic", "--bearing", "wan-105", "--speed-rpm", "15000", "--fz", "889.84", "--json"])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    for k in ("alpha_i_deg", "alpha_o_deg", "Q_i_N", "Q_o_N", "omega_m_rpm", "omega_R_rpm",
              "spin_roll_i", "spin_roll_o"):
        assert isinstance(d[k], list) and len(d[k]) == 19
    assert set(d["displacement"]) == {"dx_m", "dy_m", "dz_m", "tx_rad", "ty_rad"}
    assert len(d["stiffness"]) == 5 and all(len(r) == 5 for r in d["stiffness"])
    assert 7000 < d["cage_speed_rpm"] < 7500
    assert abs(d["alpha_i_deg"][0] - 37.7) < 0.4   # seed 003 Table 2


def test_human_table(capsys):
    rc = main(["quasistatic", "--bearing", "7218B", "--speed-rpm", "1000", "--fz", "1000", "--fx", "200"])
    assert rc == 0
    out = capsys.readouterr().out
    assert "cage speed" in out and "stiffness" in out


@pytest.mark.parametrize("args", [
    ["quasistatic", "--bearing", "7218B", "--speed-rpm", "abc"],
    ["quasistatic", "--bearing", "nope", "--speed-rpm", "100"],
    ["quasistatic", "--bearing", "7218B", "--speed-rpm", "-2e5"],
    ["quasistatic", "--bearing", "7218B", "--speed-rpm", "1e9", "--fz", "100"],
    ["quasistatic", "--bearing", "7218B", "--speed-rpm", "100", "--fz", "nan"],
    ["quasistatic", "--bearing", "7218B", "--speed-rpm", "100", "--control", "diagonal"],
])
def test_bad_arguments_exit_2_one_line(args):
    p = subprocess.run([sys.executable, "-m", "bearing_core.cli", *args], capture_output=True, text=True)
    assert p.returncode == 2
    assert len(p.stderr.strip().splitlines()) == 1
    assert p.stdout == ""
    if args[3] == "1e9":      # the user's parameter and unit, not the library's rad/s
        assert "--speed-rpm" in p.stderr and "rpm" in p.stderr


def test_dynamics_subcommand_writes_outputs(tmp_path, capsys):
    prof = tmp_path / "prof.csv"
    prof.write_text("time_s,speed_rpm\n0,1000\n0.01,1200\n0.02,1200\n")
    rc = main(["dynamics", "--bearing", "7218B", "--profile", str(prof), "--fz", "2000", "--fx", "300",
               "--out", str(tmp_path / "o"), "--record-dt", "1e-3"])
    assert rc == 0
    d = json.loads((tmp_path / "o" / "dynamics_7218B_summary.json").read_text())
    assert abs(d["final_speed_rpm"] - 1200) < 1e-6
    assert abs(d["final_reaction_N"]["Fz"] + 2000) < 0.05 * 2000
    head = (tmp_path / "o" / "dynamics_7218B.csv").read_text().splitlines()[0]
    assert "cage_speed [rad/s]" in head and "friction_torque [Nm]" in head
    assert (tmp_path / "o" / "dynamics_7218B.png").stat().st_size > 10000


@pytest.mark.parametrize("args", [
    ["dynamics", "--bearing", "7218B", "--profile", "/no/such.csv"],
    ["dynamics", "--bearing", "7218B", "--mu", "nan"],
    ["dynamics", "--bearing", "7218B", "--mu", "3"],
])
def test_dynamics_bad_arguments(args):
    p = subprocess.run([sys.executable, "-m", "bearing_core.cli", *args], capture_output=True, text=True)
    assert p.returncode == 2, p.stderr
    assert len(p.stderr.strip().splitlines()) == 1


def test_microslip_subcommand(tmp_path, capsys):
    rc = main(["microslip", "--bearing", "7218B", "--speed-rpm", "3000", "--fz", "3000", "--time", "0.005",
               "--race", "outer", "--out", str(tmp_path)])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert 0.0 <= d["adhesion_fraction"] <= 1.0 and d["Q"] > 0
    assert (tmp_path / "microslip_7218B_outer_ball0.png").is_file()
    for bad in (["--time", "0"], ["--race", "middle"], ["--ball", "99"]):
        p = subprocess.run([sys.executable, "-m", "bearing_core.cli", "microslip", "--bearing", "7218B",
                            "--speed-rpm", "3000", "--fz", "3000", *bad, "--out", str(tmp_path)],
                           capture_output=True, text=True)
        assert p.returncode == 2, (bad, p.stderr)
        assert len(p.stderr.strip().splitlines()) == 1


def test_thermal_command_json(capsys):
    """`bearing thermal`: coupled dynamic-thermal steady state; heat generated = rejected within 1%
    and the drive power equals the heat generated within 1% (energy bookkeeping)."""
    rc = main(["thermal", "--bearing", "7218B", "--speed-rpm", "4000", "--fz", "3000", "--oil-flow-lpm", "0.5",
               "--json"])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert abs(d["heat_balance"]) < 0.01
    assert abs(d["drive_power_W"] / d["heat_generated_W"] - 1) < 0.01
    assert set(d["temperatures_K"]) == {"ball", "outer", "inner", "oil"}
    assert all(T > d["ambient_temperature_K"] for T in d["temperatures_K"].values())
    assert d["film_parameter_min"] > 0


def test_wear_command_json_and_bad_input(capsys):
    rc = main(["wear", "--bearing", "wan-105", "--speed-rpm", "10000", "--fx", "300", "--fz", "500",
               "--hours", "100", "--json"])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert d["inner_wear_depth_m"] > 0 and d["outer_wear_volume_m3"] > 0
    rc = main(["wear", "--bearing", "wan-105", "--speed-rpm", "10000", "--fz", "500", "--hours", "-1"])
    assert rc == 2
    assert "hours" in capsys.readouterr().err
