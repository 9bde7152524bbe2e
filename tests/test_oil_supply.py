"""bearing_core.lubrication.oil_supply: the cavity oil fraction from the supply (Parker's correlation for jet / oil-air,
the submerged share of the cavity for a bath, none for channelled grease) and its input errors."""
import math

import pytest

from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import load_preset
from bearing_core.lubrication.oil_supply import OilSupply, bath_fraction, cavity_oil_fraction, parker_fraction

LPM = 1.0 / 60000.0


def test_parker_exponents_and_one_value_by_hand():
    # X[%] = 1e5 W^0.37 / (n dm^1.7): doubling the flow multiplies X by 2^0.37, doubling the speed halves it,
    # doubling dm divides it by 2^1.7
    X0, _, _ = parker_fraction(1.0 * LPM, 20000.0, 0.05)
    assert parker_fraction(2.0 * LPM, 20000.0, 0.05)[0] / X0 == pytest.approx(2 ** 0.37, rel=1e-12)
    assert parker_fraction(1.0 * LPM, 40000.0, 0.05)[0] / X0 == pytest.approx(0.5, rel=1e-12)
    assert parker_fraction(1.0 * LPM, 20000.0, 0.10)[0] / X0 == pytest.approx(2 ** -1.7, rel=1e-12)
    # by hand: W = 1000 cm^3/min, n = 20000 rpm, dm = 50 mm: 1e5 * 12.882 / (2e4 * 772.9) % = 0.0833 %
    assert X0 == pytest.approx(1e5 * 1000 ** 0.37 / (2e4 * 50 ** 1.7) / 100, rel=1e-12)
    assert X0 == pytest.approx(8.33e-4, rel=2e-3)


def test_parker_validity_flag():
    assert parker_fraction(1.0 * LPM, 20000.0, 0.05)[1] is False          # n dm 1e6, 1000 cm^3/min
    X, ext, note = parker_fraction(1.0 * LPM, 1000.0, 0.05)               # n dm 5e4: outside
    assert ext and "n dm" in note


def test_bath_fraction_geometry():
    # no oil, full, and the level at the centre (half of the annulus by symmetry)
    assert bath_fraction(0.0, 0.04, 0.06) == 0.0
    assert bath_fraction(0.12, 0.04, 0.06) == pytest.approx(1.0, rel=1e-12)
    assert bath_fraction(0.06, 0.04, 0.06) == pytest.approx(0.5, rel=1e-12)
    # level at the inner radius' lowest point: only the segment of the outer disc below it
    r, R = 0.04, 0.06
    y = -r
    seg = R * R * math.acos(-y / R) + y * math.sqrt(R * R - y * y)
    assert bath_fraction(R - r, r, R) == pytest.approx(seg / (math.pi * (R * R - r * r)), rel=1e-12)


def test_methods():
    g = load_preset("7218B")
    jet = cavity_oil_fraction(OilSupply("jet", 2.0 * LPM, 350.0), g, 10000.0)
    assert 0.0 < jet.fraction < 0.01 and jet.method == "jet"
    mist = cavity_oil_fraction(OilSupply("oil-air", 1e-3 * LPM, 300.0), g, 10000.0)
    assert mist.fraction < jet.fraction and mist.extrapolated
    bath = cavity_oil_fraction(OilSupply("bath", 0.0, 320.0, oil_level=0.5 * g.D), g, 3000.0)
    assert 0.0 < bath.fraction < 0.5
    assert cavity_oil_fraction(OilSupply("grease", 0.0, 320.0), g, 3000.0).fraction == 0.0


@pytest.mark.parametrize("kw, param", [
    (dict(method="splash", flow_rate=1e-5), "lubrication method"),
    (dict(method="jet", flow_rate=0.0), "oil flow_rate"),
    (dict(method="jet", flow_rate=-1e-5), "oil flow_rate"),
    (dict(method="jet", flow_rate=float("nan")), "oil flow_rate"),
    (dict(method="bath", flow_rate=0.0), "oil_level"),
    (dict(method="bath", flow_rate=0.0, oil_level=-0.01), "oil_level"),
    (dict(method="jet", flow_rate=1e-5, oil_level=0.01), "oil_level"),
    (dict(method="grease", flow_rate=1e-5), "oil flow_rate"),
    (dict(method="jet", flow_rate=1e-5, T_in=600.0), "oil inlet temperature T_in"),
])
def test_errors_name_parameter_value_and_range(kw, param):
    with pytest.raises(BearingInputError) as e:
        OilSupply(**kw).validate()
    assert e.value.parameter == param
    assert "allowed" in str(e.value)


def test_cosim_takes_the_supply_and_follows_the_speed():
    """Through the co-simulation session (what the FMU wraps): with oil_fraction 0 and a jet flow the cavity
    oil content is the supply's at the running speed -- it falls as 1/n when the shaft speed doubles -- and
    an explicit oil_fraction overrides it. Bad method / level name the parameter."""
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    rpm = math.pi / 30.0
    flow = 1e-5
    s = CoSimSession(CoSimParameters(bearing="7218B", churning=True, oil_flow_rate=flow, lubrication_method="jet"))
    inp = {"shaft_speed": 3000 * rpm, "Fz": 3000.0}
    s.initialize(0.0, inp)
    g = s.model.g
    X1 = s.model.oil_fraction_used()
    assert X1 == pytest.approx(parker_fraction(flow, 3000.0, g.dm)[0], rel=1e-9)
    s.step(0.0, 1e-3, dict(inp, shaft_speed=6000 * rpm))
    assert s.model.oil_fraction_used() == pytest.approx(0.5 * X1, rel=1e-6)
    s2 = CoSimSession(CoSimParameters(bearing="7218B", oil_flow_rate=flow, oil_fraction=0.02))
    s2.initialize(0.0, inp)
    assert s2.model.oil_fraction_used() == 0.02
    for kw, param in ((dict(lubrication_method="splash"), "lubrication_method"), (dict(oil_level=-1.0), "oil_level")):
        with pytest.raises(BearingInputError) as e:
            CoSimSession(CoSimParameters(bearing="7218B", oil_flow_rate=flow, **kw)).initialize(0.0, inp)
        assert e.value.parameter == param


def test_cosim_output_oil_fraction_used():
    """The session (FMU) output oil_fraction_used is the oil content the model uses: the jet supply's at the
    running speed, the explicit oil_fraction when given."""
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    rpm = math.pi / 30.0
    inp = {"shaft_speed": 3000 * rpm, "Fz": 3000.0}
    s = CoSimSession(CoSimParameters(bearing="7218B", oil_flow_rate=1e-5, lubrication_method="jet"))
    s.initialize(0.0, inp)
    o = s.outputs
    assert o["oil_fraction_used"] == s.model.oil_fraction_used() == pytest.approx(
        parker_fraction(1e-5, 3000.0, s.model.g.dm)[0], rel=1e-9)
    s2 = CoSimSession(CoSimParameters(bearing="7218B", oil_fraction=0.02))
    s2.initialize(0.0, inp)
    assert s2.outputs["oil_fraction_used"] == 0.02
