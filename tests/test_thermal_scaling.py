"""The thermal network's speed- and size-dependent elements (bearing_core.heat.thermal): moving-source contact
resistance (Tian & Kennedy 1994) against its classical limits, Blok's heat partition, flat-plate
convection (Incropera & DeWitt Eqs. 7.30 / 7.38), and the energy ledger when the speed changes."""
import math

import numpy as np
import pytest

from bearing_core.heat import thermal as th
from bearing_core.bearing.geometry import load_preset


def test_moving_source_limits():
    k, kappa, a = 46.6, 1.26e-5, 2e-4
    # Pe -> 0: the mean rise of a stationary uniform circular flux, 8 q a / (3 pi k) (Carslaw & Jaeger,
    # Conduction of Heat in Solids, Sec. 8.2), within 2 %; Holm's isothermal disc 1/(4 k a) within 7 %
    R0 = th.moving_source_resistance(k, kappa, a, 0.0)
    assert R0 == pytest.approx(8.0 / (3.0 * math.pi ** 2 * k * a), rel=0.02)
    assert R0 == pytest.approx(1.0 / (4.0 * k * a), rel=0.07)
    # Pe >> 1: Jaeger's moving-source asymptote, resistance ~ Pe^-1/2 (4x the speed halves it, within 0.1 %)
    R1 = th.moving_source_resistance(k, kappa, a, 100.0)
    R4 = th.moving_source_resistance(k, kappa, a, 400.0)
    assert R1 / R4 == pytest.approx(2.0, rel=1e-3)


def test_flat_plate_continuous_at_transition_and_laminar_exponent():
    # the laminar (Eq. 7.30) and mixed (Eq. 7.38) averages meet at Re = 5e5 within 0.2 %
    k, nu, Pr, L = 0.14, 5e-6, 60.0, 0.01
    u_t = th.RE_TRANSITION * nu / L
    lo, hi = th.flat_plate_h(u_t * (1 - 1e-9), L, k, nu, Pr), th.flat_plate_h(u_t * (1 + 1e-9), L, k, nu, Pr)
    assert hi == pytest.approx(lo, rel=2e-3)
    assert th.flat_plate_h(4.0, L, k, nu, Pr) / th.flat_plate_h(1.0, L, k, nu, Pr) == pytest.approx(2.0, rel=1e-12)


def _net(name="7218B", **kw):
    return th.ThermalNetwork(load_preset(name), "mil-prf-23699-ester",
                             th.ThermalData(T_amb=300.0, T_in=394.0, flow_rate=1.27e-5, **kw))


def test_conductances_grow_with_speed():
    n = _net()
    G0 = dict(n.conductances)
    n.set_speed(20000 * math.pi / 30)
    G1 = dict(n.conductances)
    for key in ("G_bh", "G_bs", "G_boil", "G_hoil", "G_soil"):
        assert G1[key] > 3.0 * G0[key], key
    # the stationary contact conductance is of the order of Holm's (Z contacts, two bodies in series)
    d = n.dims
    holm = load_preset("7218B").Z / (2.0 / (4.0 * 46.6 * math.sqrt(d["a_o"] * d["b_o"])))
    assert G0["G_bh"] == pytest.approx(holm, rel=0.07)


def test_blok_partition_ceramic_ball_takes_less():
    # silicon nitride (k 30) against steel (k 46.6): the ball's resistance is higher, so it takes less
    from bearing_core.bearing.materials import get_material
    g = load_preset("7218B", ball_material=get_material("silicon_nitride"))
    n = th.ThermalNetwork(g, "mil-prf-23699-ester", th.ThermalData(shaft_speed=1000.0))
    assert 0.3 < n.split_i < 0.5 and 0.3 < n.split_o < 0.5


def test_ledger_closes_across_speed_changes():
    n = _net()
    Q = dict(Q_br_i=80.0, Q_br_o=60.0, drag=200.0, Q_ch_c=30.0)
    for w in (500.0, 1500.0, 3000.0, 800.0):
        n.set_speed(w)
        for _ in range(5):
            n.step(Q, 20.0)
    assert abs(n.energy_residual()) <= 1e-9 * n.E_generated
    T = n.steady_state(Q)
    assert n.heat_to_ambient(T) + n.heat_to_oil_flow(T) == pytest.approx(sum(Q.values()), rel=1e-9)
    assert np.all(T > 300.0)


def test_runaway_names_node_and_cause():
    # 5 kW of ball drag with no oil flow and still air: the steady state passes the mineral oil's limit; the
    # error names the ball node, drag as its main source and its paths out
    n = th.ThermalNetwork(load_preset("7218B"), "iso-vg32-mineral", th.ThermalData(shaft_speed=100.0))
    n.steady_state({"drag": 5000.0, "Q_br_i": 50.0}, set_state=True)
    with pytest.raises(th.ThermalRunaway) as e:
        n.check_runaway("at test")
    assert e.value.node == "ball"
    assert "node 'ball'" in e.value.cause and "(drag 100 %)" in e.value.cause and "oil" in e.value.cause
    assert "cause:" in str(e.value)


def test_ring_to_housing_and_shaft_paths_through_the_fits():
    """The outer and inner ring nodes reject to ambient through the fit contact, the housing wall (cylindrical
    conduction) or the shaft (axial conduction) and the convection, in series; fit_contact_resistance None
    gives back seed 001's convection-only paths."""
    import math
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.heat.thermal import ThermalData, ThermalNetwork
    g = load_preset("7218B")
    td = ThermalData(L_shaft=0.1)
    net = ThermalNetwork(g, data=td)
    seed = ThermalNetwork(g, data=ThermalData(L_shaft=0.1, fit_contact_resistance=None))
    r, k = net.dims, 46.6
    R_o = (6e-4 / (math.pi * r["D_o"] * g.width) + math.log(r["D_h"] / r["D_o"]) / (2 * math.pi * k * r["L_h"])
           + 1.0 / seed.g_amb[1])
    R_i = 6e-4 / (math.pi * r["D_s"] * g.width) + 0.5 * r["L_h"] / (k * math.pi * r["D_s"] ** 2 / 4) + 1.0 / seed.g_amb[2]
    assert net.g_amb[1] == pytest.approx(1.0 / R_o, rel=1e-12)
    assert net.g_amb[2] == pytest.approx(1.0 / R_i, rel=1e-12)
    assert net.g_amb[1] < seed.g_amb[1] and net.g_amb[2] < seed.g_amb[2]
    assert net.g_amb[3] == seed.g_amb[3]
    with pytest.raises(Exception):
        ThermalNetwork(g, data=ThermalData(fit_contact_resistance=-1.0))
