"""Dynamics of four-point-contact (gothic-arch) ball bearings: up to four raceway contacts per ball."""
import math

import numpy as np
import pytest

from bearing_core.models import dynamics_kernels as K
from bearing_core.session.cosim import CoSimParameters, CoSimSession
from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict
from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.quasistatic import FourPointQuasiStaticModel

RPM = math.pi / 30
QJ = load_preset("QJ1044")


SYMMETRIC_ZERO = ("Fx", "Fy", "Mx", "My", "ir_x", "ir_y", "ir_tx", "ir_ty")
COMPARED = ("cage_speed", "Fz", "ir_z", "friction_torque", "P_drive", "P_race_inner", "P_race_outer", "P_pocket",
            "P_race_slide", "P_race_spin", "KE", "U_elastic", "alpha_i_mean", "alpha_o_mean", "Q_i_max", "Q_o_max",
            "Q_i_min", "p_max", "ball0_wr", "ball0_wz", "ball0_orbit_speed", "ball0_slide_roll_i",
            "ball0_spin_roll_o", "ball0_Ft_i", "ball0_Ft_o", "cage_speed_pure_rolling_outer")


def test_gothic_arch_with_unloaded_second_arcs_is_its_two_point_bearing():
    """Exact reduction (geometry, no fitted number): a gothic-arch bearing whose second arcs never touch is
    the two-point bearing of its loaded diagonal pair (same D, dm, fi, fo, alpha0; Harris & Kotzalas Vol. 1,
    the free contact angle of a four-point bearing is that of one diagonal pair). QJ1044 under a pure axial
    20 kN at 1,200 rpm (full 23-ball model, lubricated EHL traction) against the same geometry with zero
    groove offsets, both started from the same state: speeds, forces, losses, contact loads and angles,
    ball 0's motion and the final ball states agree to 1e-6 of each channel's scale (measured: <= 7e-8;
    rounding only: the four-point ring's moment arms +-e_i leave a 1e-13 rad tilt noise that the stiff
    traction amplifies); the channels zero by symmetry stay at
    rounding noise in both; no second arc is loaded."""
    loads = (0.0, 0.0, 20000.0, 0.0, 0.0)
    twin = QJ.with_overrides(inner_groove_offset=0.0, outer_groove_offset=0.0)
    assert not twin.is_four_point
    opt = DynamicsOptions(traction="lubricated", integrator="auto", reduced="full")
    m4 = DynamicModel(QJ, opt).initialize(1200 * RPM, loads)
    m2 = DynamicModel(twin, opt).initialize(1200 * RPM, loads)
    # the four-point quasi-static start equals the two-point one (one contact per ring)
    assert np.allclose(m4.y, m2.y, rtol=1e-9, atol=1e-13)
    m2.y[:] = m4.y
    m2.P[K.P_CRX:K.P_CRTY + 1] = m4.P[K.P_CRX:K.P_CRTY + 1]
    r4 = m4.advance(0.01, record_dt=5e-4)
    r2 = m2.advance(0.01, record_dt=5e-4)
    assert r4.shape == r2.shape
    for name in SYMMETRIC_ZERO:          # zero by symmetry, up to the rounding noise of both models
        k = K.OUT_INDEX[name]
        # tilts: 1e-10 rad, rounding noise growing linearly over the run (1e-12 rad after 10 ms measured)
        tol = 1e-3 if name in ("Fx", "Fy") else 1e-4 if name in ("Mx", "My") else 1e-10
        assert np.abs(r4[:, k]).max() < tol and np.abs(r2[:, k]).max() < tol, name
    for name in COMPARED:
        k = K.OUT_INDEX[name]
        assert np.abs(r4[:, k] - r2[:, k]).max() <= 1e-6 * np.abs(r2[:, k]).max(), name
    b4 = m4.y[K.NSTATE_FIXED:].reshape(-1, K.NSB)
    b2 = m2.y[K.NSTATE_FIXED:].reshape(-1, K.NSB)
    for k in (0, 1, 2, 3, 6, 7, 8):      # ball angle, position, orbit speed, spin vector
        assert np.allclose(b4[:, k], b2[:, k], rtol=1e-6, atol=0.0), k
    assert np.allclose(b4[:, 4:6], b2[:, 4:6], rtol=0.0, atol=1e-8)     # ball radial / axial velocity [m/s]
    assert m4.y[2] == pytest.approx(m2.y[2], rel=1e-8) and m4.y[11] == pytest.approx(m2.y[11], rel=1e-6)
    bd = m4.ball_details()
    assert np.all(bd["Q_i2"] == 0.0) and np.all(bd["Q_o2"] == 0.0) and np.all(bd["Q_i"] > 1000.0)


def _arcs(bd):
    """Dynamics per-ball contacts as (Z, 4) loads and angles in FourPointResult order (inner 1, inner 2,
    outer 1, outer 2: arcs 1 have positive contact angles)."""
    Q = np.zeros((bd["Q_i"].size, 4))
    A = np.zeros_like(Q)
    for first, second, col in (("i", "i2", 0), ("o", "o2", 2)):
        for nm in (first, second):
            q, a = bd["Q_" + nm], bd["alpha_" + nm]
            for j in np.flatnonzero(q > 0):
                c = col if a[j] > 0 else col + 1
                Q[j, c], A[j, c] = q[j], a[j]
    return Q, A


@pytest.mark.parametrize("loads, tol_q, tol_deg", [((10000.0, 0.0, 0.0, 0.0, 0.0), 0.015, 0.05),
                                                     ((2000.0, 0.0, 10000.0, 0.0, 0.0), 0.03, 1.0)])
def test_contacts_consistent_with_four_point_quasistatic(loads, tol_q, tol_deg):
    """Consistency check between two models of this library (NOT a published reference): QJ1044 at 600 rpm
    under a pure radial 10 kN (the balls of the loaded zone touch all four arcs) and under 2 kN radial +
    10 kN axial (two to four contacts per ball). After 0.04 s the dynamics' mean ring displacement is
    within 0.5 % of FourPointQuasiStaticModel's and, at the final instant, the four contact loads of every
    ball are within tol_q of the largest load and the loaded contacts' angles within tol_deg of the
    quasi-static solution at the same ball azimuths. Measured: 0.6 % / 0.004 deg (radial), 2.1 % / 0.63 deg
    (combined). The combined case differs more because the dynamics resolves the traction of a ball on
    three or four arcs, which the quasi-static model replaces by its kinematic estimate (gyroscopic friction
    shared by load weights), and carries the ball's orbital ripple."""
    w = 600 * RPM
    m = DynamicModel(QJ, DynamicsOptions(traction="lubricated", integrator="auto", reduced="full"))
    m.initialize(w, loads)
    rec = records_to_dict(m.advance(0.04, record_dt=1e-3))
    late = rec["t"] >= 0.02
    qsm = FourPointQuasiStaticModel(QJ)
    bd = m.ball_details()
    qsm.psi = np.mod(bd["theta"], 2 * math.pi)
    qs = qsm.solve(w, loads, stiffness=False)
    assert rec["ir_x"][late].mean() == pytest.approx(qs.u[0], rel=5e-3)
    assert abs(rec["ir_z"][late].mean() - qs.u[2]) < 5e-3 * abs(qs.u[0])
    assert -rec["Fx"][late].mean() == pytest.approx(loads[0], rel=5e-3)
    Qd, Ad = _arcs(bd)
    assert np.sum(Qd > 0, axis=1).max() == 4 and np.sum(qs.Q_c > 0, axis=1).max() == 4
    scale = qs.Q_c.max()
    assert np.abs(Qd - qs.Q_c).max() < tol_q * scale
    both = (Qd > 0.02 * scale) & (qs.Q_c > 0.02 * scale)
    assert both.sum() >= 8
    assert np.degrees(np.abs(Ad - qs.alpha_c)[both]).max() < tol_deg


def test_qj1044_runs_through_the_cosimulation_session():
    """The FMU's session (bearing_core.session.cosim, used by fmu_src/bearing_fmu.py and `bearing simulate`) runs the
    four-point QJ1044 under 1 kN radial + 3 kN axial at 900 rpm: finite outputs, the applied loads carried,
    the cage turning; a four-point bearing needs no seating axial load, but refuses no load at all."""
    s = CoSimSession(CoSimParameters(bearing="QJ1044", oil_fraction=0.05, churning=True))
    u = dict(shaft_speed=900 * RPM, Fx=1000.0, Fz=3000.0)
    s.initialize(0.0, u)
    for k in range(4):
        out = s.step(k * 2.5e-3, 2.5e-3, u)
    assert all(math.isfinite(v) for v in out.values())
    assert 0.3 < out["cage_speed"] / (900 * RPM) < 0.6
    assert out["reaction_Fz"] == pytest.approx(-3000.0, rel=0.05)
    assert out["reaction_Fx"] == pytest.approx(-1000.0, rel=0.1)
    s2 = CoSimSession(CoSimParameters(bearing="QJ1044"))
    s2.initialize(0.0, dict(shaft_speed=900 * RPM, Fx=2000.0, Fz=0.0))   # radial only: fine for four-point
    with pytest.raises(BearingInputError, match="Fx, Fy, Fz"):
        CoSimSession(CoSimParameters(bearing="QJ1044")).initialize(0.0, dict(shaft_speed=100.0))
