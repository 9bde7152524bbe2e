"""Work of the rotating parts on the supply oil (oil_supply.supply_oil_work) and its place in the thermal
network (source 'Q_oil_work' -> oil node)."""
import math

import pytest

from bearing_core.bearing.geometry import load_preset
from bearing_core.errors import BearingInputError
from bearing_core.heat.thermal import I_OIL, ThermalData, ThermalNetwork
from bearing_core.lubrication.oil_supply import OilSupply, supply_oil_work

JET = OilSupply("jet", 1.0e-5, 394.0)


def test_euler_work_by_hand_and_its_bounds():
    rho, w, wc, ri, rc = 920.0, 7540.0, 3510.0, 0.0208, 0.0258
    m_dot = rho * JET.flow_rate
    P = supply_oil_work(JET, rho, w, wc, ri, rc)
    # inner ring's work w * m_dot w ri^2, the cage's wc * m_dot (wc rc^2 - w ri^2)
    assert P == pytest.approx(w * m_dot * w * ri ** 2 + wc * m_dot * (wc * rc ** 2 - w * ri ** 2), rel=1e-12)
    # between the cage-only acceleration and the oil leaving with the inner ring's speed
    assert m_dot * (wc * rc) ** 2 < P < m_dot * (w * ri) ** 2
    # a cage at the ring's angular speed (rigid rotation): the oil leaves with w rc, work m_dot (w rc)^2
    assert supply_oil_work(JET, rho, w, w, ri, rc) == pytest.approx(m_dot * (w * rc) ** 2, rel=1e-12)
    # linear in the flow, sign of the rotation irrelevant
    assert supply_oil_work(OilSupply("jet", 2e-5, 394.0), rho, w, wc, ri, rc) == pytest.approx(2 * P, rel=1e-12)
    assert supply_oil_work(JET, rho, -w, -wc, ri, rc) == pytest.approx(P, rel=1e-12)


def test_no_through_flow_no_work_and_errors():
    assert supply_oil_work(OilSupply("bath", 0.0, 313.15, oil_level=0.01), 870.0, 1000.0, 420.0, 0.05, 0.07) == 0.0
    assert supply_oil_work(OilSupply("grease", 0.0, 313.15), 870.0, 1000.0, 420.0, 0.05, 0.07) == 0.0
    assert supply_oil_work(JET, 870.0, 0.0, 0.0, 0.05, 0.07) == 0.0
    with pytest.raises(BearingInputError, match="r_cage"):
        supply_oil_work(JET, 870.0, 1000.0, 420.0, 0.05, 0.0)
    with pytest.raises(BearingInputError, match="rho_oil"):
        supply_oil_work(JET, 50.0, 1000.0, 420.0, 0.05, 0.07)


def test_network_puts_it_in_the_oil_node_and_rejects_it():
    g = load_preset("7218B")
    net = ThermalNetwork(g, data=ThermalData(flow_rate=1e-5, shaft_speed=500.0))
    q = net.node_heat({"Q_oil_work": 80.0})
    assert q[I_OIL] == pytest.approx(80.0) and q.sum() == pytest.approx(80.0)
    T = net.steady_state({"Q_oil_work": 80.0, "Q_br_i": 20.0})
    assert net.heat_to_ambient(T) + net.heat_to_oil_flow(T) == pytest.approx(100.0, rel=1e-9)
    assert math.isfinite(T[I_OIL])
