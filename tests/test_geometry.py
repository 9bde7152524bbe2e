"""Bearing definition, presets and input validation."""
import math

import pytest

from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import list_presets, load_preset, from_dict, preset_data


def test_presets_listed_and_cited():
    names = list_presets()
    for n in ("7218B", "7008-ma2023", "7008-rivera2021", "wan-105"):
        assert n in names
        assert preset_data(n)["source"], f"preset {n} must cite its source"


def test_7218B_derived_contact_angle():
    """Harris 218 ACBB: Pd = 147.73 - 102.79 - 2*22.23 = 0.48 mm, A = 0.0464 D, alpha0 = 39.9 deg
    (Harris & Kotzalas' worked 218 example rounds it to 40 deg; seed 000 Table 2 gives 40 deg). Tol 0.2 deg."""
    g = load_preset("7218B")
    assert g.Z == 16
    assert math.isclose(g.D, 22.23e-3)
    assert math.isclose(g.dm, 0.5 * (102.79e-3 + 147.73e-3))
    assert math.isclose(g.Pd, 0.48e-3, rel_tol=1e-9)
    assert abs(math.degrees(g.alpha0) - 40.0) < 0.2
    # inverse relation reproduces the raceway diameters
    assert math.isclose(g.inner_raceway_diameter, 102.79e-3, rel_tol=1e-12)
    assert math.isclose(g.outer_raceway_diameter, 147.73e-3, rel_tol=1e-12)


def test_groove_radii_to_conformity():
    """seed 003 Table 1: groove radius 7.8421 mm on a 15.081 mm ball gives f = 0.5200."""
    g = load_preset("wan-105")
    assert abs(g.fi - 0.52) < 1e-4 and abs(g.fo - 0.52) < 1e-4
    g2 = load_preset("7008-ma2023")  # seed 002 Table 2: ri 3.990, ro 3.780, D 7.000 mm
    assert math.isclose(g2.fi, 0.57) and math.isclose(g2.fo, 0.54)


def test_ball_mass_and_inertia():
    g = load_preset("7218B")
    m = 7800 * math.pi * 0.02223 ** 3 / 6
    assert math.isclose(g.ball_mass, m)
    assert math.isclose(g.ball_inertia, 7800 * math.pi * 0.02223 ** 5 / 60)


def _base():
    return dict(preset_data("7218B"))


@pytest.mark.parametrize("field,value,fragment", [
    ("fi", 0.5, "fi"),
    ("fo", 0.45, "fo"),
    ("number_of_balls", 2, "Z"),
    ("ball_diameter_mm", -1.0, "ball_diameter_mm"),
    ("number_of_balls", 40, "Z"),          # 40 balls of 22 mm do not fit on a 125 mm pitch circle
])
def test_validation_names_the_field(field, value, fragment):
    d = _base()
    d[field] = value
    with pytest.raises(BearingInputError) as e:
        from_dict(d)
    assert fragment in str(e.value)
    assert "allowed" in str(e.value)


def test_overrides_are_validated():
    g = load_preset("7008-rivera2021", alpha0=math.radians(40))
    assert math.isclose(math.degrees(g.alpha0), 40.0)
    with pytest.raises(BearingInputError, match="alpha0"):
        load_preset("7008-rivera2021", alpha0=float("nan"))
    with pytest.raises(BearingInputError, match="bearing"):
        load_preset("no-such-bearing")
