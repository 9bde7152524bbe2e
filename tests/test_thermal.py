"""Checks of bearing_core.heat.thermal (seed 001 Eqs. 21-29) against analytic solutions and conservation."""
import math

import numpy as np
import pytest
from scipy.linalg import expm

from bearing_core.heat import thermal as th
from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import load_preset

Q = dict(Q_br_i=50.0, Q_br_o=40.0, Q_bp=10.0, Q_cg=5.0, Q_ch_c=20.0, Q_ch_b=30.0, Q_ch_s=15.0)


def net(**kw):
    return th.ThermalNetwork(load_preset("7218B"), "iso-vg32-mineral", th.ThermalData(**kw))


def _be(C, L, g, Tout, q, T0, t_end, n):
    T = np.array(T0, float)
    for _ in range(n):
        T = th.thermal_be_step(C, L, g, Tout, q, T, t_end / n)
    return T


def test_one_node_exponential_and_first_order():
    # C dT/dt = q - g (T - T_out): T = T_out + q/g + (T0 - T_out - q/g) exp(-g t / C) (exact). Backward
    # Euler is first order: the error halves with dt (ratio 2 +- 0.1), and is < 1e-3 K at 800 steps.
    C, g, q, Tout, T0, t = np.array([500.0]), np.array([2.0]), np.array([40.0]), np.array([300.0]), [310.0], 400.0
    L = np.zeros((1, 1))
    exact = Tout[0] + q[0] / g[0] + (T0[0] - Tout[0] - q[0] / g[0]) * math.exp(-g[0] * t / C[0])
    errs = [abs(_be(C, L, g, Tout, q, T0, t, n)[0] - exact) for n in (100, 200, 400, 800)]
    for a, b in zip(errs, errs[1:]):
        assert a / b == pytest.approx(2.0, abs=0.1)
    assert errs[-1] < 1e-3 * abs(exact - T0[0]) + 1e-12


def test_two_node_against_matrix_exponential():
    # two nodes, G between them, node 0 to outside: dT/dt = -C^-1 (L + diag g)(T - T_s), T_s the steady
    # state; exact T(t) = T_s + expm(-A t)(T0 - T_s). BE error first order (ratio 2 +- 0.15).
    C = np.array([300.0, 1200.0])
    G = 3.0
    L = np.array([[G, -G], [-G, G]])
    g = np.array([1.5, 0.0])
    Tout = np.array([295.0, 295.0])
    q = np.array([10.0, 25.0])
    T0 = np.array([300.0, 320.0])
    Ts = np.linalg.solve(L + np.diag(g), q + g * Tout)
    A = (L + np.diag(g)) / C[:, None]
    t = 600.0
    exact = Ts + expm(-A * t) @ (T0 - Ts)
    errs = [np.max(np.abs(_be(C, L, g, Tout, q, T0, t, n) - exact)) for n in (200, 400, 800)]
    for a, b in zip(errs, errs[1:]):
        assert a / b == pytest.approx(2.0, abs=0.15)
    assert np.allclose(th.thermal_steady(L, g, Tout, q), Ts, rtol=1e-14)
    # steady state: generated = rejected, within 1e-12 relative
    assert np.dot(g, Ts - Tout) == pytest.approx(q.sum(), rel=1e-12)


@pytest.mark.parametrize("flow", [0.0, 2e-5])
def test_steady_state_balance(flow):
    # at thermal steady state heat generated = heat rejected (ambient + oil flow) within 1e-9
    n = net(flow_rate=flow)
    T = n.steady_state(Q)
    rejected = n.heat_to_ambient(T) + n.heat_to_oil_flow(T)
    assert rejected == pytest.approx(sum(Q.values()), rel=1e-9)
    assert np.all(T > n.data.T_amb)
    if flow > 0:
        assert n.heat_to_oil_flow(T) > 0


def test_large_steps_reach_steady_state_and_ledger_closes():
    # backward Euler is unconditionally stable: dt = 1e5 s (>> all time constants) lands on the steady
    # state without overshoot; the ledger generated = rejected + stored closes to 1e-9 relative
    n = net(flow_rate=1e-5)
    tau = n.time_constants()
    assert np.all(tau > 0)
    Ts = n.steady_state(Q)
    prev = n.T.copy()
    for _ in range(30):
        T = n.step(Q, 1e5)
        assert np.all(T >= prev - 1e-9) and np.all(T <= Ts + 1e-9)   # monotone approach from ambient
        prev = T
    assert np.allclose(T, Ts, atol=1e-6)
    assert abs(n.energy_residual()) <= 1e-9 * n.E_generated
    # variable sources and steps
    m = net(flow_rate=1e-5)
    rng = np.random.default_rng(1)
    for _ in range(50):
        m.step({k: v * rng.uniform(0, 3) for k, v in Q.items()}, rng.uniform(0.1, 500.0))
    assert abs(m.energy_residual()) <= 1e-9 * m.E_generated


def test_source_mapping():
    # every watt goes to exactly one node (seed 001 Eqs. 22-25 with the double-counted race / pocket heat
    # split); check the documented nodes
    n = net()
    q = n.node_heat(Q)
    assert q.sum() == pytest.approx(sum(Q.values()), rel=1e-15)
    # Blok's partition between a steel ball and a steel ring at the same rolling speed: one half each
    assert n.split_i == pytest.approx(0.5, rel=1e-12) and n.split_o == pytest.approx(0.5, rel=1e-12)
    s = 0.5
    assert q[th.I_BALL] == pytest.approx(s * 90.0 + 0.5 * 10.0 + 30.0)
    assert q[th.I_OUTER] == pytest.approx((1 - s) * 40.0 + 5.0)      # 7218B cage is outer-ring guided
    assert q[th.I_INNER] == pytest.approx((1 - s) * 50.0 + 15.0)
    assert q[th.I_OIL] == pytest.approx(0.5 * 10.0 + 20.0)
    assert np.allclose(n.node_heat({"drag": 7.0}), n.node_heat({"Q_ch_b": 7.0}))


def test_areas_and_capacities_follow_seed():
    # seed 001 Eqs. 28-29 recomputed by hand from the resolved dimensions; Eq. 21 C = c_p rho V for the balls
    g = load_preset("7218B")
    n = net()
    d = n.dims
    Lh = d["L_h"]
    assert n.areas["A_boil"] == pytest.approx(g.Z * math.pi * g.D ** 2)
    assert n.areas["A_hatm"] == pytest.approx(math.pi * (d["D_h"] ** 2 - d["D_Lo"] ** 2) / 2 + math.pi * d["D_h"] * Lh)
    assert n.areas["A_oilatm"] == pytest.approx(n.areas["A_boil"] + math.pi * d["D_Lo"] * Lh + math.pi * d["D_Li"] * Lh)
    assert n.C[th.I_BALL] == pytest.approx(g.Z * 7800.0 * math.pi * g.D ** 3 / 6 * 475.0)
    # contact_model 'seed001': Eq. 26 with N_b parallel contacts, G = N K pi a b / (2 a)
    s = net(contact_model="seed001")
    assert s.conductances["G_bh"] == pytest.approx(g.Z * 46.6 * math.pi * s.dims["b_o"] / 2)


def test_input_errors_name_parameter():
    with pytest.raises(BearingInputError) as e:
        net(h_b_oil=-5.0)
    assert e.value.parameter == "h_b_oil"
    with pytest.raises(BearingInputError) as e:
        net(D_h=0.1)                                     # smaller than the bearing
    assert "D_h" in e.value.parameter
    n = net()
    with pytest.raises(BearingInputError) as e:
        n.step({"Q_unknown": 1.0}, 1.0)
    assert e.value.parameter == "Q_sources key"
    with pytest.raises(BearingInputError) as e:
        n.step({"Q_bp": -1.0}, 1.0)
    assert e.value.parameter == "Q_bp"
    with pytest.raises(BearingInputError) as e:
        n.step(Q, 0.0)
    assert e.value.parameter == "dt"
    with pytest.raises(BearingInputError):
        net(h_h_atm=0.0, h_s_atm=0.0, h_oil_atm=0.0, flow_rate=0.0)
