"""The co-simulation session's output array and input handling (bearing_core.session.cosim).

The outputs are assembled in one numba call (bearing_core.session.session_kernels.assemble_outputs) from index maps;
these tests hold them against the library's own definitions computed independently in Python (the model's
output channels, DynamicModel.film, skid.classify_skid, the time integrals of the channels), and check that
inputs held from one step to the next are checked again as soon as they change."""
import math

import numpy as np
import pytest

from bearing_core.models import dynamics_kernels as K
from bearing_core.session.cosim import (ALL_OUTPUT_NAMES, CSR_MIN_SPEED, HEAT_CHANNELS, CoSimParameters, CoSimSession,
                                StepRejected)
from bearing_core.models.skid import classify_skid

INP = {"shaft_speed": 314.16, "Fx": 1000.0, "Fz": 3000.0}


@pytest.fixture(scope="module")
def session():
    s = CoSimSession(CoSimParameters())
    s.initialize(0.0, INP)
    return s


def test_outputs_equal_the_library_definitions(session):
    """Every output of a step against its definition in Python: channels of DynamicModel.outputs() at the
    communication point, cage/shaft ratios, films of DynamicModel.film(), the skid state of
    skid.classify_skid, and the step averages as (integral after - integral before) / h of
    DynamicModel.integrals(). Tolerance 1e-12 relative (the same doubles, summed in another order)."""
    s = session
    h = 1e-3
    q0 = s.model.integrals()
    o = s.step(s.t, h, dict(INP))
    q1 = s.model.integrals()
    c = s.model.outputs()
    fl = s.model.film()
    assert set(o) == set(ALL_OUTPUT_NAMES)
    near = dict(rel=1e-12, abs=1e-300)
    for name, ch in (("reaction_Fx", "Fx"), ("reaction_Fz", "Fz"), ("cage_speed", "cage_speed"),
                     ("max_contact_pressure", "p_max"), ("ball0_traction_i", "ball0_Ft_i"), ("ir_z", "ir_z"),
                     ("instantaneous_friction_torque", "friction_torque"),
                     ("cage_speed_pure_rolling_outer", "cage_speed_pure_rolling_outer")):
        assert o[name] == pytest.approx(c[ch], **near), name
    w = c["shaft_speed"]
    assert abs(w) >= CSR_MIN_SPEED
    assert o["cage_shaft_ratio"] == pytest.approx(c["cage_speed"] / w, **near)
    csr_t = c["pure_rolling_cage_speed"] / w
    assert o["skid_ratio"] == pytest.approx(1.0 - (c["cage_speed"] / w) / csr_t, rel=1e-9)
    state, slip = classify_skid(c["cage_speed"], c["cage_speed_pure_rolling_outer"], omega_outer=c["outer_ring_speed"])
    assert o["skid_state"] == state and isinstance(o["skid_state"], int)
    assert o["cage_slip_ratio"] == pytest.approx(slip, **near)
    assert o["film_min_inner"] == pytest.approx(fl["h_min_i"][fl["h_min_i"] > 0].min(), **near)
    assert o["film_min_outer"] == pytest.approx(fl["h_min_o"][fl["h_min_o"] > 0].min(), **near)
    assert o["film_parameter_min"] == pytest.approx(fl["Lambda_min"], **near)
    assert o["heat_flux_pocket"] == pytest.approx((q1["P_pocket"] - q0["P_pocket"]) / h, rel=1e-9)
    assert o["drive_power"] == pytest.approx((q1["P_drive"] - q0["P_drive"]) / h, rel=1e-9)
    assert o["heat_flux_total"] == pytest.approx(sum((q1[v] - q0[v]) / h for v in HEAT_CHANNELS.values()), rel=1e-9)
    assert o["instantaneous_heat_flux_total"] == pytest.approx(sum(c[v] for v in HEAT_CHANNELS.values()), rel=1e-12)
    assert o["temperature_oil"] == s.p.oil_temperature and o["thermal_runaway"] == 0
    assert all(math.isfinite(v) for v in o.values())
    # the live array and the snapshot agree; the snapshot does not change with later steps
    assert np.array_equal(s.values, [o[n] for n in ALL_OUTPUT_NAMES])
    s.step(s.t, h, INP)
    assert o["cage_speed"] == pytest.approx(c["cage_speed"], **near)


def test_held_inputs_are_checked_again_when_they_change(session):
    """The same input dictionary passed at every step and changed in place between steps: a reversed axial
    load, a NaN and an unknown name are refused (StepRejected naming the input, state unchanged); a new
    speed is applied at the start of the next step."""
    s = session
    u = dict(INP)
    s.step(s.t, 1e-3, u)
    before = s.values.copy()
    y, t = s.model.y.copy(), s.t
    for change, what in (({"Fz": -3000.0}, "Fz"), ({"Fx": float("nan")}, "Fx"), ({"bogus": 1.0}, "bogus")):
        u.update(change)
        with pytest.raises(StepRejected, match=what):
            s.step(s.t, 1e-3, u)
        assert s.t == t and np.array_equal(s.model.y, y) and np.array_equal(s.values, before)
        u = dict(INP)
    u["shaft_speed"] = 400.0
    s.step(s.t, 1e-3, u)
    assert s.model.U[K.U_W1] == 400.0
    assert s.step(s.t, 1e-3, u)["cage_shaft_ratio"] > 0.0
