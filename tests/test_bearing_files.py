"""User bearing definitions: bearing JSON files, catalogue designations, and their validation."""
import json
import math
import subprocess
import sys

import numpy as np
import pytest

from bearing_core.bearing.catalogue import catalogue_definition, list_catalogue, SERIES
from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import from_dict, load_bearing, load_preset, preset_data
from bearing_core.models.quasistatic import solve_quasistatic


def _write(tmp_path, d, name="my_bearing.json"):
    p = tmp_path / name
    p.write_text(json.dumps(d))
    return p


def test_bearing_file_equals_the_equivalent_preset(tmp_path):
    """A file holding the 7218B preset's fields gives the same geometry and the same quasi-static
    solution (Fz 3 kN, Fx 1 kN, 5000 rpm) as the preset, to round-off (rel 1e-12)."""
    d = preset_data("7218B")
    d["name"] = "my-218"
    path = _write(tmp_path, d)
    g_file, g_pre = load_bearing(str(path)), load_preset("7218B")
    for f in ("Z", "D", "dm", "fi", "fo", "alpha0", "inner_ring_mass", "width"):
        assert getattr(g_file, f) == pytest.approx(getattr(g_pre, f), rel=1e-12)
    r1 = solve_quasistatic(g_file, 5000 * math.pi / 30, (1000.0, 0, 3000.0, 0, 0))
    r2 = solve_quasistatic(g_pre, 5000 * math.pi / 30, (1000.0, 0, 3000.0, 0, 0))
    assert np.allclose(r1.Q_i, r2.Q_i, rtol=1e-12, atol=1e-9)
    assert np.allclose(r1.u, r2.u, rtol=1e-12, atol=1e-15)


def test_file_name_is_the_default_name(tmp_path):
    d = preset_data("wan-105")
    del d["name"]
    assert load_bearing(_write(tmp_path, d, "spindle_A.json")).name == "spindle_A"


@pytest.mark.parametrize("series,code,dims", [
    # ISO 15 boundary dimensions stated by the seed papers' own bearings: seed 000 Table 2's 7218 B on
    # the 90 x 160 x 30 mm envelope of ISO 15 series 02; seed 002 Table 2's 7008 on 40 x 68 x 15 mm.
    ("72", 18, (90, 160, 30)),
    ("70", 8, (40, 68, 15)),
])
def test_catalogue_boundary_dimensions(series, code, dims):
    assert SERIES[series][1][code] == dims


def test_catalogue_rule_reproduces_harris_218_internal_geometry():
    """Harris & Kotzalas' 218 angular-contact bearing (the 7218B preset, from the book): 16 balls of
    22.23 mm (7/8 in) on dm 125.26 mm. The series 02 rule was calibrated on it, so this checks the
    implementation of the rule, exactly for Z and within 0.01 mm for the ball and 0.5 % for dm."""
    d = catalogue_definition("7218B")
    assert d["number_of_balls"] == 16
    assert d["ball_diameter_mm"] == pytest.approx(22.23, abs=0.01)
    assert d["pitch_diameter_mm"] == pytest.approx(125.26, rel=5e-3)
    assert d["estimated"] is True and "ESTIMATED" in d["source"]


def test_every_catalogue_bearing_is_physical():
    """Every designation builds and is geometrically possible: balls fit between bore and outside
    diameter with material left for both rings, balls fit on the pitch circle, contact angle as the suffix."""
    names = list_catalogue()
    assert len(names) == 3 * 21 * 4
    for n in names:
        d = catalogue_definition(n)
        g = from_dict(d)
        series, code = n[:2], int(n[2:4])
        bore, od, width = SERIES[series][1][code]
        assert bore * 1e-3 < g.inner_raceway_diameter < g.outer_raceway_diameter < od * 1e-3
        assert g.dm * math.sin(math.pi / g.Z) > g.D
        suffix = n[4:]
        assert math.degrees(g.alpha0) == pytest.approx({"C": 15, "AC": 25, "A": 30, "B": 40}[suffix], abs=1e-9)
        assert d["width_mm"] == width


def test_presets_take_precedence_over_catalogue():
    assert load_bearing("7218B").source == preset_data("7218B")["source"]
    assert "Harris" in load_bearing("7218B").source


def _bad(tmp_path, mutate):
    d = preset_data("7218B")
    mutate(d)
    return _write(tmp_path, d)


@pytest.mark.parametrize("mutate,field", [
    (lambda d: d.pop("ball_diameter_mm"), "ball_diameter_mm"),                     # missing field
    (lambda d: d.update(number_of_balls=30), "number_of_balls"),                   # balls do not fit
    (lambda d: d.update(outer_raceway_diameter_mm=140.0), "outer_raceway_diameter_mm"),  # negative clearance
    (lambda d: d.update(fi=float("nan")), "fi"),                                   # NaN
    (lambda d: d.update(width_mm=-3.0), "width_mm"),
    (lambda d: d.update(inner_ring_mass_kg="heavy"), "inner_ring_mass_kg"),
    (lambda d: d["cage"].update(mass_kg=float("inf")), "cage.mass_kg"),
    (lambda d: d["cage"].pop("inertia_kg_mm2"), "cage.inertia_kg_mm2"),
    (lambda d: d["cage"].update(pocket_clearance_mm=-0.1), "cage.pocket_clearance_mm"),
    (lambda d: d.update(ball_diamter_mm=22.0), "ball_diamter_mm"),                  # misspelt field
    (lambda d: d.update(free_contact_angle_deg=95.0, pitch_diameter_mm=125.0) or d.pop("inner_raceway_diameter_mm"),
     "free_contact_angle_deg"),
])
def test_bad_bearing_files_name_the_field(tmp_path, mutate, field):
    path = _bad(tmp_path, mutate)
    with pytest.raises(BearingInputError) as e:
        load_bearing(str(path))
    assert e.value.parameter.startswith(field) or field in str(e.value)
    assert "allowed" in str(e.value)


def test_misspelt_field_suggests_the_right_one(tmp_path):
    path = _bad(tmp_path, lambda d: d.update(ball_diamter_mm=22.0))
    with pytest.raises(BearingInputError, match="did you mean 'ball_diameter_mm'"):
        load_bearing(path)


def test_unreadable_or_missing_files(tmp_path):
    p = tmp_path / "broken.json"
    p.write_text("{not json")
    with pytest.raises(BearingInputError, match="bearing"):
        load_bearing(str(p))
    with pytest.raises(BearingInputError, match="file not found"):
        load_bearing(str(tmp_path / "absent.json"))
    with pytest.raises(BearingInputError, match="catalogue designation"):
        load_bearing("7299B")


def test_cli_accepts_bearing_file_and_designation(tmp_path):
    """`bearing quasistatic --bearing FILE` gives the preset's numbers; a designation works too; a bad
    file exits with the field named, not a traceback."""
    d = preset_data("7218B")
    path = _write(tmp_path, d)
    run = lambda b: subprocess.run([sys.executable, "-m", "bearing_core.cli", "quasistatic", "--bearing", b,
                                    "--speed-rpm", "3000", "--fz", "3000", "--json"],
                                   capture_output=True, text=True, timeout=300)
    a, b = run(str(path)), run("7218B")
    assert a.returncode == 0 and b.returncode == 0, a.stderr + b.stderr
    assert json.loads(a.stdout)["Q_i_N"] == json.loads(b.stdout)["Q_i_N"]
    assert run("7210C").returncode == 0
    bad = _bad(tmp_path, lambda d: d.update(fo=0.4))
    r = run(str(bad))
    assert r.returncode != 0 and "fo" in r.stderr and "Traceback" not in r.stderr
