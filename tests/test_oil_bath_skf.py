"""SKF's (2004) oil-bath drag term and the oil supply built on it (bearing_core.lubrication.friction_models,
oil_supply): the digitised V_M(H/dm) curve, the drag moment by hand, the SKF-equivalent bath oil fraction,
and Parker's unit checked by the energy balance of the NASA jet runs."""
import math

import pytest

from bearing_core.bearing.geometry import load_preset
from bearing_core.errors import BearingInputError
from bearing_core.lubrication.churning import ball_drag_power
from bearing_core.lubrication.friction_models import (VM_BALL_CURVE, bearing_envelope_mm, drag_loss_variable,
                                                      skf_drag_torque, skf_friction)
from bearing_core.lubrication.oil_supply import (CD_BALL, RHO_OIL_NOMINAL, OilSupply, bath_fraction,
                                                 cavity_oil_fraction, parker_fraction, skf_bath_fraction)


def test_vm_curve_passes_its_points_rises_and_is_capped_at_1_2_dm():
    for x, y in (p for p in VM_BALL_CURVE if p[0] <= 1.2):
        assert drag_loss_variable(x)[0] == pytest.approx(y, rel=1e-12, abs=1e-15)
    xs = [0.01 * k for k in range(121)]
    v = [drag_loss_variable(x)[0] for x in xs]
    assert v[0] == 0.0 and all(b > a for a, b in zip(v, v[1:]))          # rises with the level up to 1.2 dm
    assert drag_loss_variable(1.2)[1] is False
    V, capped = drag_loss_variable(3.0)
    assert capped and V == drag_loss_variable(1.2)[0]
    with pytest.raises(BearingInputError):
        drag_loss_variable(-0.1)


def test_skf_drag_moment_by_hand_and_through_skf_friction():
    # 7218-size envelope 90 x 160 mm, level 10 mm, 2000 rpm: V_M K_ball dm^5 n^2 [N mm] by hand
    d, D, n, H = 90.0, 160.0, 2000.0, 10.0
    dm = 125.0
    V_M = drag_loss_variable(H / dm)[0]
    K_ball = 4.4 * (d + D) / (D - d) * 1e-12
    assert skf_drag_torque(d, D, n, H) == pytest.approx(V_M * K_ball * dm ** 5 * n * n * 1e-3, rel=1e-12)
    # quadratic in speed; skf_friction with oil_level_mm carries the same drag term
    assert skf_drag_torque(d, D, 2 * n, H) == pytest.approx(4 * skf_drag_torque(d, D, n, H), rel=1e-12)
    r = skf_friction(d, D, n, 32.0, 0.0, 5000.0, oil_level_mm=H, lubrication="oil-bath")
    assert r["M_drag"] == pytest.approx(skf_drag_torque(d, D, n, H), rel=1e-12)
    with pytest.raises(BearingInputError) as e:
        skf_friction(d, D, n, 32.0, 0.0, 5000.0, V_M=1e-4, oil_level_mm=H)
    assert e.value.parameter == "V_M"


def test_skf_bath_fraction_makes_the_ball_drag_equal_skfs_drag():
    g = load_preset("7218B")
    d, D, _ = bearing_envelope_mm(g)
    for H in (0.25 * g.D, 0.5 * g.D, g.D):
        X, ext, _ = skf_bath_fraction(H, g)
        assert 0.0 < X < 1.0 and not ext
        for rpm in (300.0, 3000.0):
            w = rpm * math.pi / 30.0
            w_m = 0.5 * w * (1.0 - g.D * math.cos(g.alpha0) / g.dm)
            rho = 1.2 + X * (RHO_OIL_NOMINAL - 1.2)
            P = ball_drag_power(rho, CD_BALL, w_m, g.dm, g.D, int(g.Z))
            assert P == pytest.approx(skf_drag_torque(d, D, rpm, H * 1e3) * w, rel=1e-9)
    # more oil, more drag; a deep bath needs more than flooded balls: capped at 1 and flagged
    assert skf_bath_fraction(0.5 * g.D, g)[0] < skf_bath_fraction(g.D, g)[0]
    X, ext, note = skf_bath_fraction(0.8 * g.dm, g)
    assert X == 1.0 and ext and "capped" in note


def test_bath_model_choice_and_its_error():
    g = load_preset("7218B")
    s = OilSupply("bath", 0.0, 330.0, oil_level=0.5 * g.D)
    skf = cavity_oil_fraction(s, g, 2000.0)
    geo = cavity_oil_fraction(s, g, 2000.0, bath_model="geometric")
    assert skf.fraction == skf_bath_fraction(0.5 * g.D, g)[0] and "SKF" in skf.formula
    assert geo.fraction == bath_fraction(0.5 * g.D, 0.5 * g.inner_raceway_diameter, 0.5 * g.outer_raceway_diameter)
    assert cavity_oil_fraction(s, g, 500.0).fraction == skf.fraction          # speed-independent
    assert cavity_oil_fraction(OilSupply("bath", 0.0, 330.0, oil_level=0.5 * g.D, bath_model="geometric"),
                               g, 2000.0).fraction == geo.fraction       # the supply carries its bath model
    with pytest.raises(BearingInputError) as e:
        cavity_oil_fraction(s, g, 2000.0, bath_model="sump")
    assert e.value.parameter == "bath_model"
    with pytest.raises(BearingInputError) as e:
        OilSupply("bath", 0.0, 330.0, oil_level=0.01, bath_model="sump").validate()
    assert e.value.parameter == "bath_model"


def test_bearing_thermal_bath_models(capsys):
    """`bearing thermal` with a bath: the oil content from SKF's drag term by default, the geometric share with
    --bath-model geometric; --bath-model without a bath is refused, naming the flag."""
    import json
    from bearing_core.cli import main
    g = load_preset("7218B")
    base = ["thermal", "--bearing", "7218B", "--speed-rpm", "1500", "--fz", "3000", "--oil", "iso-vg68-mineral",
            "--lubrication-method", "bath", "--oil-level-mm", "11", "--oil-inlet-c", "40", "--json"]
    got = {}
    for model in ("skf", "geometric"):
        assert main(base + ["--bath-model", model]) == 0
        got[model] = json.loads(capsys.readouterr().out)["oil_fraction"]
    assert got["skf"] == pytest.approx(skf_bath_fraction(0.011, g)[0], rel=1e-12)
    assert got["geometric"] == pytest.approx(
        bath_fraction(0.011, 0.5 * g.inner_raceway_diameter, 0.5 * g.outer_raceway_diameter), rel=1e-12)
    assert main(["thermal", "--bearing", "7218B", "--speed-rpm", "1500", "--fz", "3000", "--oil-flow-lpm", "1",
                 "--bath-model", "skf"]) == 2
    assert "--bath-model" in capsys.readouterr().err


@pytest.mark.parametrize("flow_cm3_min", [303.0, 758.0])
def test_parker_percent_reading_passes_the_energy_balance_of_the_nasa_runs(flow_cm3_min):
    """NASA ran the jet-lubricated 35-mm bearing successfully at 72,000 rpm with 303-1894 cm^3/min of ester at
    394 K (TP-1732). At the lower flows, read as percent, Parker's cavity oil gives a ball drag the oil flow
    carries away with a rise of a few tens of K; read as a fraction (100x more oil) the oil would have to
    leave above the 473 K limit of the ester (at 1894 cm^3/min it would stay just below: 469 K)."""
    n, dm, D, Z, alpha = 72000.0, 0.0535, 0.0119, 12, math.radians(24.0)
    w = n * math.pi / 30.0
    w_m = 0.5 * w * (1.0 - D * math.cos(alpha) / dm)
    flow = flow_cm3_min / 6.0e7
    X, _, _ = parker_fraction(flow, n, dm)
    m_cp = flow * 900.0 * 2000.0                         # ester: ~900 kg/m^3, ~2000 J/(kg K)
    rise_percent = ball_drag_power(1.2 + X * 898.8, 0.5, w_m, dm, D, Z) / m_cp
    rise_fraction = ball_drag_power(1.2 + 100.0 * X * 898.8, 0.5, w_m, dm, D, Z) / m_cp
    assert rise_percent < 40.0
    assert 394.0 + rise_fraction > 473.15
