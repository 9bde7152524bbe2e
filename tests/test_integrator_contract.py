"""Accuracy contract of the production integrator (DynamicsOptions(integrator='auto'), the FMU default):
window-mean cage speed and inner-ring reactions within 0.5 % of classical RK4 at a fine fixed step (1e-6 s,
ten times finer than the seed 000 papers' 1e-5 s, so its own error is far below the tolerance), and the
energy balance closed within 1 % (work in = dissipation + change of kinetic and elastic energy, a
conservation law independent of any reference run). Full 16-ball 7218B model, EHL traction, at the two
ends of the seed 000 speed profile, where 'auto' runs different methods (Rosenbrock-W where the traction
is stiff at 1000 rpm, the explicit adaptive RK4(3) at 10,000 rpm), and with Kalker's FASTSIM traction at
1000 rpm."""
import math

import numpy as np
import pytest

from bearing_core.models import dynamics_kernels as K
from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict
from bearing_core.bearing.geometry import load_preset

LOADS = (1000.0, 0.0, 3000.0, 0.0, 0.0)
T_SETTLE, T_WIN = 4e-3, 8e-3       # [s] start-up from the quasi-static state, then the compared window
DISS = ("P_race_inner", "P_race_outer", "P_pocket", "P_land", "P_drag", "P_damping", "P_churn_cage",
        "P_churn_ring")


def _window(rpm, traction="lubricated", **opt):
    m = DynamicModel(load_preset("7218B"), DynamicsOptions(reduced="full", traction=traction, **opt))
    m.initialize(rpm * math.pi / 30.0, LOADS)
    m.advance(T_SETTLE)
    o0 = m.outputs()
    m.reset_integrals()
    rec = records_to_dict(m.advance(T_SETTLE + T_WIN, record_dt=1e-4))
    o1 = m.outputs()
    q = m.integrals()
    means = {k: q[k] / T_WIN for k in ("cage_speed", "Fx", "Fz")}
    diss = sum(q[k] for k in DISS)
    # energy residual: work in - dissipation - change of stored energy, relative to the dissipation (the
    # work in alone can be near zero while the balls spin down from the quasi-static start)
    res = (q["P_drive"] + q["P_ext"] - diss - (o1["KE"] + o1["U_elastic"]) + (o0["KE"] + o0["U_elastic"])) / diss
    return m, rec, means, res


@pytest.mark.slow
@pytest.mark.parametrize("rpm", [1000.0, 10000.0])
def test_production_integrator_contract(rpm):
    """'auto' against RK4 at dt = 1e-6 s over an 8 ms window: mean cage speed and mean reactions Fx, Fz
    within 0.5 %, energy residual within 1 % of the dissipated energy (both runs); tolerances: the production integrator's accuracy contract."""
    _, _, ref, res0 = _window(rpm, integrator="rk4", dt=1e-6)
    m, rec, got, res = _window(rpm, integrator="auto")
    assert np.all(np.isfinite(rec["cage_speed"]))
    for k in ("cage_speed", "Fx", "Fz"):
        assert abs(got[k] / ref[k] - 1.0) < 5e-3, (k, got[k], ref[k])
    assert abs(res0) < 0.01
    assert abs(res) < 0.01, res
    # the run stayed on the production path: far fewer right-hand sides than the reference's 4 per 1e-6 s
    assert m.stats[2] < 0.25 * 4 * (T_SETTLE + T_WIN) / 1e-6


@pytest.mark.slow
def test_production_integrator_contract_kalker():
    """Kalker's FASTSIM race traction (mu = 0.1, 12 x 12 grid) at 1000 rpm, where the creep forces are stiff
    and 'auto' runs the Rosenbrock-W method from the start: the same contract against RK4 at dt = 1e-6 s
    (mean cage speed, Fx, Fz within 0.5 %, energy residual within 1 % of the dissipated energy), and the run
    stayed on the implicit method (well under a tenth of the reference's right-hand sides; the explicit
    method needs about a quarter at this speed)."""
    from bearing_core.models.dynamics import ST_CUR
    _, _, ref, res0 = _window(1000.0, traction="kalker", mu=0.1, integrator="rk4", dt=1e-6)
    m, rec, got, res = _window(1000.0, traction="kalker", mu=0.1, integrator="auto")
    assert np.all(np.isfinite(rec["cage_speed"]))
    for k in ("cage_speed", "Fx", "Fz"):
        assert abs(got[k] / ref[k] - 1.0) < 5e-3, (k, got[k], ref[k])
    assert abs(res0) < 0.01
    assert abs(res) < 0.01, res
    assert m.stats[ST_CUR] == 2
    assert m.stats[2] < 0.1 * 4 * (T_SETTLE + T_WIN) / 1e-6


def test_advance_many_matches_one_at_a_time():
    """Batch runs (dynamics.advance_many: threads over models, GIL released in the kernels) give
    bit-identical states and records to running the same models one after the other (no shared state);
    mismatched argument lengths are refused naming the parameter."""
    from bearing_core.models.dynamics import advance_many
    from bearing_core.errors import BearingInputError

    def models():
        out = []
        for k, rpm in enumerate((1000.0, 4000.0, 8000.0)):
            m = DynamicModel(load_preset("7218B"), DynamicsOptions(reduced="axisymmetric", integrator="auto"))
            m.initialize(rpm * math.pi / 30.0, (0.0, 0.0, 2000.0 + 500.0 * k, 0.0, 0.0))
            out.append(m)
        return out
    seq, par = models(), models()
    r_seq = [m.advance(0.01) for m in seq]
    r_par = advance_many(par, 0.01, workers=3)
    for a, b, ra, rb in zip(seq, par, r_seq, r_par):
        assert np.array_equal(a.y, b.y) and np.array_equal(ra, rb)
    with pytest.raises(BearingInputError, match="t_end"):
        advance_many(par, [0.02, 0.02])
