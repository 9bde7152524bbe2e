"""The session's fatigue outputs life_L10r_h [h] and fatigue_damage [-] (docs/life.md "In a co-simulation"): the
Palmgren-Miner sum at a held state, over a duty cycle of two levels, through a rollback, the life at the dynamic
level against bearing_core.models.life on the same per-ball state, finite values at standstill."""
import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest

from bearing_core.session.cosim import CoSimParameters, CoSimSession
from bearing_core.session.cosim_spec import LIFE_CAP_H, OUTPUT_NAMES, OUTPUT_SPEC
from bearing_core.session.fidelity import MAP_FATIGUE_RATE

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_fidelity_map import RPM, rate_field, synthetic_map  # noqa: E402


@pytest.fixture(scope="module")
def rate_map(tmp_path_factory):
    """The synthetic map of test_fidelity_map with its fatigue damage rate (rate_field)."""
    return synthetic_map(tmp_path_factory.mktemp("maps") / "life.nc")


def inputs(rpm, fx, fz, **kw):
    return dict({"shaft_speed": rpm * RPM, "Fx": fx, "Fz": fz}, **kw)


def test_outputs_are_last_with_their_units():
    assert OUTPUT_NAMES[-2:] == ("life_L10r_h", "fatigue_damage")
    assert [u for _, u, _ in OUTPUT_SPEC[-2:]] == ["h", "1"]


def test_map_damage_is_time_over_life_and_sums_over_a_duty_cycle(rate_map):
    s = CoSimSession(CoSimParameters(fidelity="map", map_file=rate_map))
    a, b = (2500.0, 1200.0, 2000.0), (3500.0, 500.0, 2800.0)
    s.initialize(0.0, inputs(*a))
    assert s.outputs["fatigue_damage"] == 0.0
    La = s.outputs["life_L10r_h"]
    assert La == pytest.approx(1.0 / (3600.0 * rate_field(*a)), rel=1e-12)
    t, h = 0.0, 0.5
    for _ in range(8):                 # 4 s at level a
        s.step(t, h, inputs(*a))
        t += h
    Da = s.outputs["fatigue_damage"]
    assert Da == pytest.approx(4.0 / (3600.0 * La), rel=1e-12)
    for _ in range(4):                 # then 2 s at level b
        s.step(t, h, inputs(*b))
        t += h
    Lb = s.outputs["life_L10r_h"]
    assert Lb == pytest.approx(1.0 / (3600.0 * rate_field(*b)), rel=1e-12) and Lb != pytest.approx(La)
    assert s.outputs["fatigue_damage"] == pytest.approx(4.0 / (3600.0 * La) + 2.0 / (3600.0 * Lb), rel=1e-12)


def test_map_rollback_restores_the_damage(rate_map):
    s = CoSimSession(CoSimParameters(fidelity="map", map_file=rate_map))
    s.initialize(0.0, inputs(2000.0, 1000.0, 2000.0))
    for k in range(3):
        s.step(0.1 * k, 0.1, inputs(2000.0, 1000.0, 2000.0))
    st, d0 = s.get_state(), s.outputs["fatigue_damage"]
    for k in range(3, 6):
        s.step(0.1 * k, 0.1, inputs(3000.0, 1500.0, 2500.0))
    assert s.outputs["fatigue_damage"] > d0
    s.set_state(st)
    assert s.outputs["fatigue_damage"] == d0
    s.step(0.3, 0.1, inputs(2000.0, 1000.0, 2000.0))
    assert s.outputs["fatigue_damage"] == pytest.approx(d0 * 4.0 / 3.0, rel=1e-12)


def test_map_without_the_rate_holds_zero_with_a_warning(tmp_path):
    path = synthetic_map(tmp_path / "plain.nc", fatigue_rate=False)
    s = CoSimSession(CoSimParameters(fidelity="map", map_file=path))
    assert any(MAP_FATIGUE_RATE in w for w in s.warnings)
    s.initialize(0.0, inputs(2000.0, 1000.0, 2000.0))
    s.step(0.0, 0.5, inputs(2000.0, 1000.0, 2000.0))
    assert s.outputs["life_L10r_h"] == 0.0 and s.outputs["fatigue_damage"] == 0.0


@pytest.fixture(scope="module")
def dyn():
    s = CoSimSession(CoSimParameters(bearing="7218B", traction_model="coulomb"))
    s.initialize(0.0, inputs(3000.0, 2000.0, 3000.0))
    return s


def test_dynamic_life_agrees_with_the_library_and_damage_accumulates(dyn):
    from bearing_core.models import life as LF
    s = dyn
    st = s.get_state()
    u = inputs(3000.0, 2000.0, 3000.0)
    h = 2e-3
    t = s.t
    lives = []
    for _ in range(3):
        s.step(t, h, u)
        t += h
        lives.append(s.outputs["life_L10r_h"])
    m = s.model
    _, bd = m.evaluate_point()
    par = LF.life_parameters(m.g, "inner")
    ref = LF.rating_life_hours_details_nb(bd, par, 3000.0)
    assert 1e2 < ref < 1e9 and s.outputs["life_L10r_h"] == pytest.approx(ref, rel=1e-9)
    # the quasi-static load distribution of the same loads gives nearly the same life (models.life.rating_life)
    qs = LF.life_at(m.g, 3000.0, (2000.0, 0.0, 3000.0, 0.0, 0.0))
    assert ref == pytest.approx(qs.rating.L10r_h, rel=0.1)
    # damage with the life at the end of each step
    assert s.outputs["fatigue_damage"] == pytest.approx(sum(h / (3600.0 * L) for L in lives), rel=1e-12)
    d3 = s.outputs["fatigue_damage"]
    s.set_state(st)
    assert s.outputs["fatigue_damage"] == 0.0
    s.step(s.t, h, u)
    assert 0.0 < s.outputs["fatigue_damage"] < d3


def test_dynamic_standstill_is_finite_and_adds_no_damage():
    s = CoSimSession(CoSimParameters(bearing="7218B", traction_model="coulomb"))
    s.initialize(0.0, inputs(0.0, 1000.0, 3000.0))
    s.step(0.0, 1e-3, inputs(0.0, 1000.0, 3000.0))
    assert s.outputs["life_L10r_h"] == LIFE_CAP_H and s.outputs["fatigue_damage"] == 0.0
    assert np.all(np.isfinite(s.values))


@pytest.mark.skipif(os.environ.get("BEARING_TEST_QS_CAGE") != "1", reason="solves with the quasi-static cage "
                    "kernels: set BEARING_TEST_QS_CAGE=1 (they compile for ~2 CPU minutes)")
def test_quasistatic_damage_is_time_over_held_life():
    s = CoSimSession(CoSimParameters(bearing="7218B", fidelity="quasi-static"))
    u = inputs(3000.0, 2000.0, 3000.0)
    s.initialize(0.0, u)
    L = s.outputs["life_L10r_h"]
    assert 1e2 < L < 1e9 and math.isfinite(L)
    for k in range(5):
        s.step(0.2 * k, 0.2, u)
    assert s.outputs["life_L10r_h"] == L
    assert s.outputs["fatigue_damage"] == pytest.approx(1.0 / (3600.0 * L), rel=1e-12)
