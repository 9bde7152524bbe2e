"""Rotation either way, a turning outer ring, and energy-consistent (step-averaged) co-simulation outputs.

Conventions (docs/reversal_and_outputs.md): speeds are signed about +z; a run at -omega is the run at +omega
reflected in the x-z plane (loads (Fx, Fy, Fz, Mx, My) -> (Fx, -Fy, Fz, -Mx, My)), so with Fy = Mx = 0 the
loads are the same and the outputs mirror: speeds and torques about z, Fy, Mx and the ball spin components
Omega_r, Omega_z change sign; powers, Fx, Fz, Omega_t do not.
"""
import math

import numpy as np
import pytest

from bearing_core.session.cosim import CoSimParameters, CoSimSession, HEAT_CHANNELS
from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict, simulate_profile
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.skid import SKID_TOL

RPM = math.pi / 30
HEAT = tuple(HEAT_CHANNELS.values())


def _model(**kw):
    return DynamicModel(load_preset("7218B"), DynamicsOptions(**kw))


@pytest.mark.parametrize("traction", ["lubricated", "coulomb"])
def test_mirrored_runs_give_mirrored_outputs(traction):
    """+omega and -omega from the quasi-static start, 16 balls, Fx 1 kN, Fz 3 kN, 3000 rpm, 5 ms. The kernels
    are written for signed speeds, the start is the mirrored state, so the two runs differ only by the
    rounding of sums taken in another ball order (ball j <-> ball Z - j), which the adaptive step control
    can amplify up to its tolerance (the fast build's re-associated sums, bearing_core.numerics.jit, add rounding of
    the same order): asserted to the integrator's relative tolerance, 1e-4 of each channel's scale
    (measured: ~1e-9 relative on the torques and forces, up to ~1e-5 on the pocket power once a step
    decision differs)."""
    runs = {}
    for sgn in (1.0, -1.0):
        m = _model(traction=traction, reduced="full")
        m.initialize(sgn * 3000 * RPM, (1000.0, 0.0, 3000.0, 0.0, 0.0))
        runs[sgn] = records_to_dict(m.advance(0.005, record_dt=1e-3))
    p, n = runs[1.0], runs[-1.0]
    odd = ("shaft_speed", "cage_speed", "friction_torque", "Fy", "ball0_wr", "ball0_wz", "ball0_orbit_speed",
           "cage_speed_pure_rolling_outer", "pure_rolling_cage_speed")
    even = ("Fx", "Fz", "P_drive", "P_race_inner", "P_race_outer", "P_pocket", "P_land", "P_damping", "KE",
            "Q_i_max", "alpha_i_mean")
    for k in odd + even:
        ref = p[k] if k in even else -p[k]
        scale = max(np.abs(p[k]).max(), 1e-30)
        if k == "Fy":
            scale = np.abs(p["Fx"]).max()      # ~0 by symmetry of the load: measured on the force scale
        assert np.all(np.isfinite(n[k]))
        assert np.abs(n[k] - ref).max() <= 1e-4 * scale, (k, p[k], n[k])
    assert np.all(p["cage_speed"] > 0) and np.all(n["cage_speed"] < 0)


def test_reversal_through_zero_and_coast_down():
    """+2000 rpm -> -2000 rpm in 0.1 s, held 0.1 s, then coasting down to 0 in 0.1 s and held (EHL traction,
    Fz 3 kN, one representative ball). Every output finite (the pure-rolling references are linear in the
    ring speeds, no 0/0); the cage follows the shaft: after each hold the cage speed is within SKID_TOL of
    the pure-rolling (spin-free, seed 000 Eq. 26) reference, with the shaft's sign, and it stops with it."""
    m = _model()
    m.initialize(2000 * RPM, (0.0, 0.0, 3000.0, 0.0, 0.0))
    prof = [(0.0, 2000.0), (0.05, 2000.0), (0.15, -2000.0), (0.25, -2000.0), (0.35, 0.0), (0.45, 0.0)]
    rec = simulate_profile(m, prof, record_dt=1e-3)
    assert np.all(np.isfinite(rec))
    d = records_to_dict(rec)
    t, wc, ref = d["t"], d["cage_speed"], d["pure_rolling_cage_speed"]
    for ta in (0.049, 0.249):
        k = np.searchsorted(t, ta)
        assert abs(wc[k] / ref[k] - 1) < SKID_TOL, (ta, wc[k], ref[k])
    assert wc[np.searchsorted(t, 0.049)] > 0 > wc[np.searchsorted(t, 0.249)]
    stop = t > 0.44
    assert np.all(np.abs(wc[stop]) < 0.01 * 2000 * RPM * 0.45)      # < 1 % of the cage speed at 2000 rpm
    assert np.all(np.abs(d["shaft_speed"][stop]) < 1e-9)   # the profile interpolation leaves ~1e-15 rad/s


def test_session_through_zero_speed_finite_outputs():
    """Co-simulation session passing through zero shaft speed in 1 ms steps (+5, +0.5, 0, -0.5, -5 rad/s):
    every output finite, cage/shaft ratios 0 below CSR_MIN_SPEED (their 0/0), the skid state defined."""
    s = CoSimSession(CoSimParameters(traction_model="coulomb"))
    u = {"shaft_speed": 5.0, "Fz": 3000.0}
    s.initialize(0.0, u)
    t = 0.0
    for w in (5.0, 0.5, 0.0, -0.5, -5.0):
        u["shaft_speed"] = w
        o = s.step(t, 1e-3, u)
        t += 1e-3
        assert all(math.isfinite(v) for v in o.values())
        if abs(w) < 1.0:
            assert o["cage_shaft_ratio"] == 0.0 and o["cage_shaft_ratio_theory"] == 0.0


def _gammas(d, g, late):
    gi = g.D * np.cos(d["alpha_i_mean"][late].mean()) / g.dm
    go = g.D * np.cos(d["alpha_o_mean"][late].mean()) / g.dm
    return gi, go


@pytest.mark.parametrize("wi_rpm, wo_rpm", [(0.0, 3000.0), (3000.0, -1500.0)])
def test_outer_ring_rotation_kinematics(wi_rpm, wo_rpm):
    """Rotating outer ring (inner fixed) and counter-rotation, Fz 3 kN (moderate load, 7218B), EHL traction.
    Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 1 Ch. 8 (cage speed with both rings
    rotating, spin neglected): omega_c = [omega_i (1 - gamma_i) + omega_o (1 + gamma_o)] / 2 with gamma =
    D cos(alpha) / dm; with equal angles and the inner ring fixed, omega_o (1 + gamma) / 2. Written with the
    model's mean contact angles, (w_i (1 - g_i) + w_o (1 + g_o)) / (2 - g_i + g_o). The cage must turn at that
    speed within the skid tolerance SKID_TOL (1 %) of the ring speed difference seen from the cage,
    |w_i - w_o| / 2 (the relative measure stays meaningful where the reference is near zero)."""
    g = load_preset("7218B")
    m = _model()
    m.initialize(wi_rpm * RPM, (0.0, 0.0, 3000.0, 0.0, 0.0), omega_outer=wo_rpm * RPM)
    d = records_to_dict(m.advance(0.1, record_dt=1e-3))
    assert np.all(np.isfinite(np.column_stack(list(d.values()))))
    late = d["t"] > 0.05
    gi, go = _gammas(d, g, late)
    wi, wo = wi_rpm * RPM, wo_rpm * RPM
    ref = (wi * (1 - gi) + wo * (1 + go)) / (2 - gi + go)
    wc = d["cage_speed"][late].mean()
    assert abs(wc - ref) < SKID_TOL * abs(wi - wo) / 2, (wc / RPM, ref / RPM)
    if wi == 0.0:    # Harris' outer-rotation form at the mean of the two angles
        gm = 0.5 * (gi + go)
        assert abs(wc / (wo * (1 + gm) / 2) - 1) < 2 * SKID_TOL
    # the outer drive supplies power when the outer ring turns; the held inner ring needs a torque
    assert np.all(d["outer_ring_speed"] == wo)
    assert abs(d["friction_torque_outer"][late].mean()) > 0


def test_power_balance_both_rings_turning():
    """Conservation with both rings turning (counter-rotation 3000 / -1500 rpm, Fx 1 kN, Fz 3 kN, 16 balls,
    EHL traction): drive power of both rings + external-load power = dissipated power + d(KE + U)/dt over
    0.02 s windows within 1 % (the energy-balance test of tests/test_dynamics.py). The integrals are the
    ones accumulated inside the integrator (DynamicModel.integrals)."""
    m = _model(reduced="full")
    m.initialize(3000 * RPM, (1000.0, 0.0, 3000.0, 0.0, 0.0), omega_outer=-1500 * RPM)
    m.advance(0.02, record_dt=1e-3)
    for _ in range(2):
        o0 = m.outputs()
        m.reset_integrals()
        m.advance(m.t + 0.02, record_dt=1e-3)
        o1 = m.outputs()
        I = m.integrals()
        dE = (o1["KE"] + o1["U_elastic"]) - (o0["KE"] + o0["U_elastic"])
        W_in = I["P_drive"] + I["P_ext"]
        W_out = sum(I[k] for k in HEAT) + dE
        assert abs(W_out / W_in - 1) < 0.01, (W_in, W_out)
        # both drives do work: the outer ring's share is not negligible
        assert abs(I["friction_torque_outer"] * -1500 * RPM) > 0.05 * abs(W_in)


def test_step_averaged_heat_closes_the_energy_sum():
    """Co-simulation, 7218B, 3000 rpm, Fx 1 kN, Fz 3 kN, EHL traction, 25 steps of 1 ms. (a) The step-averaged
    heat passed on, sum(heat_flux_total h), equals the dissipation integrated from the instantaneous values
    sampled every 1e-5 s in an identical run within 0.5 %. (b) With the averaged drive power it closes the
    energy balance drive + external work = heat + change of KE + elastic energy within 0.5 % after the
    start transient. The coarse sum of the 1 ms samples (the instantaneous_* outputs) aliases the
    ball-pass oscillation: it is printed, not asserted."""
    u = {"shaft_speed": 3000 * RPM, "Fx": 1000.0, "Fz": 3000.0}
    s = CoSimSession(CoSimParameters())
    s.initialize(0.0, u)
    t, h = 0.0, 1e-3
    for _ in range(5):           # start transient
        s.step(t, h, u)
        t += h
    m = s.model
    o0 = m.outputs()
    m.reset_integrals()
    Q = W = Qi = 0.0
    for _ in range(20):
        o = s.step(t, h, u)
        t += h
        Q += o["heat_flux_total"] * h
        W += o["drive_power"] * h
        Qi += o["instantaneous_heat_flux_total"] * h
    o1 = m.outputs()
    dE = (o1["KE"] + o1["U_elastic"]) - (o0["KE"] + o0["U_elastic"])
    assert abs((W + m.integrals()["P_ext"] - dE) / Q - 1) < 0.005
    # fine sampling of the same run, instantaneous values
    s2 = CoSimSession(CoSimParameters())
    s2.initialize(0.0, u)
    d = records_to_dict(s2.model.advance(0.005, record_dt=1e-5))
    d = records_to_dict(s2.model.advance(0.025, record_dt=1e-5))
    o_end = s2.model.outputs()
    tt = np.append(d["t"], 0.025)
    diss = np.append(sum(d[k] for k in HEAT), sum(o_end[k] for k in HEAT))
    Q_fine = np.trapezoid(diss, tt)
    print(f"heat over 20 ms: step-averaged {Q:.5f} J, fine instantaneous {Q_fine:.5f} J, "
          f"1 ms samples {Qi:.5f} J")
    assert abs(Q / Q_fine - 1) < 0.005
