"""Oil and heat in the dynamics: churning torques, the thermal network on the slow time scale with temperature
feedback, film thickness per contact, and the energy bookkeeping of the coupled model."""
import math

import numpy as np
import pytest

from bearing_core.lubrication.churning import churning_losses
from bearing_core.session.cosim import CoSimParameters, CoSimSession, StepRejected
from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict
from bearing_core.bearing.geometry import load_preset
from bearing_core.heat.thermal import ThermalData

RPM = math.pi / 30
LOSSES = ("P_race_inner", "P_race_outer", "P_pocket", "P_land", "P_drag", "P_damping", "P_churn_cage",
          "P_churn_ring")


def _model(rpm=3000.0, loads=(1000.0, 0.0, 3000.0, 0.0, 0.0), **kw):
    m = DynamicModel(load_preset("7218B"), DynamicsOptions(**kw))
    m.initialize(rpm * RPM, loads)
    return m


def test_churning_power_balance_and_kernel_matches_library():
    """Churning enters the equations of motion as torques, so the energy balance (drive power =
    total heat flux + rate of kinetic and elastic energy, within 1% over windows) still closes; the inner
    ring's churning power equals seed 001 Eq. 17 evaluated by bearing_core.lubrication.churning at the same oil state
    (1e-9)."""
    m = _model(churning=True, oil_fraction=0.2, reduced="full")
    rec = records_to_dict(m.advance(0.1, record_dt=2e-4))
    t = rec["t"]
    E = rec["KE"] + rec["U_elastic"]
    diss = sum(rec[k] for k in LOSSES)
    for a in (0.02, 0.06):
        s = (t >= a) & (t <= a + 0.04)
        W_in = np.trapezoid((rec["P_drive"] + rec["P_ext"])[s], t[s])
        W_out = np.trapezoid(diss[s], t[s]) + E[s][-1] - E[s][0]
        assert abs(W_out / W_in - 1) < 0.01, (a, W_in, W_out)
    assert rec["P_churn_ring"].mean() > 0 and rec["P_churn_cage"].mean() > 0
    ref = churning_losses(m.g, m.oil_name, m.opt.oil_temperature, 3000 * RPM, rec["cage_speed"][-1],
                          oil_fraction=0.2)
    assert rec["P_churn_ring"][-1] == pytest.approx(ref["Q_ch_s"], rel=1e-9)
    assert rec["P_churn_cage"][-1] == pytest.approx(ref["Q_ch_c"], rel=1e-9)


def test_thermal_equilibrium_heat_generated_equals_rejected():
    """At thermal steady state the heat generated equals the heat rejected (ambient
    + oil flow) within 1%. The check is not the network's own identity: the losses are recomputed by the
    dynamics over a fresh window at the converged temperatures (the coupled fixed point). The feedback
    works in the expected direction: hotter oil is thinner, so the inner-ring churning loss falls below its
    isothermal value at the 35 degC supply temperature (seed 001 section 4.3: churning falls with
    temperature)."""
    kw = dict(churning=True, oil_fraction=0.05, reduced="auto")
    m = _model(rpm=5000.0, loads=(0.0, 0.0, 3000.0, 0.0, 0.0), thermal=True,
               thermal_data=ThermalData(T_amb=308.15, T_in=308.15, flow_rate=1e-5), oil_temperature=308.15, **kw)
    r = m.thermal_equilibrium(window=0.05, tol=0.05)
    assert abs(r["balance"]) < 0.01, r
    T = r["temperatures_K"]
    assert all(v > 308.15 + 1.0 for v in T.values())
    assert abs(r["drive_power_W"] / r["heat_generated_W"] - 1) < 0.01
    iso = _model(rpm=5000.0, loads=(0.0, 0.0, 3000.0, 0.0, 0.0), oil_temperature=308.15, **kw)
    rec_iso = records_to_dict(iso.advance(0.05, record_dt=1e-3))
    assert r["losses_W"]["Q_ch_s"] < 0.9 * rec_iso["P_churn_ring"].mean()


def test_film_thickness_per_contact():
    """Hamrock-Dowson minimum film per contact from the dynamics' contact state: it grows with the
    entrainment speed as h ~ U^0.68 (Hamrock & Dowson 1977), checked between 2000 and 4000 rpm under pure
    thrust within 3% (the loads change a little with the centrifugal force), and it thins when the oil is
    hotter (viscosity); Lambda is h_min over the composite roughness (ball and race Rq of the geometry)."""
    h = {}
    for rpm in (2000.0, 4000.0):
        m = _model(rpm=rpm, loads=(0.0, 0.0, 3000.0, 0.0, 0.0))
        f = m.film()
        bd = m.ball_details()
        h[rpm] = (f["h_min_i"][0], bd["u_i"][0], bd["Q_i"][0])
        assert f["Lambda_min"] == pytest.approx(min(f["h_min_i"].min(), f["h_min_o"].min())
                                                / math.hypot(*m.roughness_pair()), rel=1e-9)
    (h1, u1, q1), (h2, u2, q2) = h[2000.0], h[4000.0]
    expect = (u2 / u1) ** 0.68 * (q2 / q1) ** -0.073
    assert h2 / h1 == pytest.approx(expect, rel=0.03)
    hot = _model(rpm=2000.0, loads=(0.0, 0.0, 3000.0, 0.0, 0.0), oil_temperature=353.15)
    assert hot.film()["h_min_i"][0] < 0.6 * h1


def test_cosim_thermal_outputs_and_rollback():
    """Through the co-simulation session (what the FMU wraps): with the thermal network on, temperatures
    rise step by step from ambient, the total heat flux includes churning, and a rejected step leaves the
    temperatures where they were."""
    s = CoSimSession(CoSimParameters(bearing="7218B", thermal=True, churning=True, oil_fraction=0.05,
                                     thermal_time_scale=1000.0, oil_flow_rate=1e-5))
    inp = {"shaft_speed": 3000 * RPM, "Fz": 3000.0, "Fx": 500.0}
    s.initialize(0.0, inp)
    T0 = s.outputs["temperature_oil"]
    assert T0 == pytest.approx(308.15)
    t = 0.0
    for _ in range(5):
        out = s.step(t, 2e-3, inp)
        t += 2e-3
    assert out["temperature_oil"] > T0 + 0.1 and out["temperature_ball"] > T0 + 0.1
    parts = sum(out[k] for k in out if k.startswith("heat_flux_") and k not in (
        "heat_flux_total", "heat_flux_race_slide", "heat_flux_race_spin", "heat_flux_race_diffslip"))
    assert out["heat_flux_total"] == pytest.approx(parts, rel=1e-12)
    assert out["heat_flux_churn_ring"] > 0 and out["film_min_inner"] > 0 and out["film_parameter_min"] > 0
    before = dict(s.outputs)
    with pytest.raises(StepRejected):
        s.step(t, 2e-3, dict(inp, shaft_speed=float("nan")))
    assert s.outputs["temperature_oil"] == before["temperature_oil"]
    assert s.model.temperatures()["oil"] == pytest.approx(before["temperature_oil"])
