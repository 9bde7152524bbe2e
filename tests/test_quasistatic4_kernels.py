"""numba kernels of the four-point-contact quasi-static model (bearing_core.models.quasistatic4_kernels) against the
model's equations evaluated here with numpy (FourPointQuasiStaticModel docstring; Jones 1960; Harris &
Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2 Ch. 3), and the solution against Newton's laws
computed from the returned per-contact arrays."""
import math

import numpy as np
import pytest

from bearing_core.contact import kinematics as kin
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.quasistatic import FourPointQuasiStaticModel, quasistatic_model

RPM = math.pi / 30
QJ = load_preset("QJ1044")

# (rpm, control, loads [N, N m], outer-ring speed [rad/s]): radial, combined and light combined loads of
# the benchmark, a moment load, all three raceway controls; 3000 rpm light combined restarts balls from
# their potential minimum, 1800 rpm turns the outer ring too
CASES = [
    (0.0, "outer", (2000.0, 0.0, 10000.0, 0.0, 0.0), 0.0),
    (3000.0, "hybrid", (1000.0, 0.0, 3000.0, 0.0, 0.0), 0.0),
    (10000.0, "inner", (10000.0, 0.0, 0.0, 0.0, 0.0), 0.0),
    (1800.0, "outer", (500.0, 300.0, 20000.0, 200.0, -100.0), 30.0),
]


@pytest.fixture(scope="module", params=CASES, ids=[f"{c[0]:g}rpm-{c[1]}-{c[3]:g}" for c in CASES])
def solved(request):
    rpm, control, loads, w_out = request.param
    m = FourPointQuasiStaticModel(QJ, control)
    m.omega_outer = w_out
    return m, m.solve(rpm * RPM, loads, stiffness=True)


def _numpy_ball_state(m, u, X, omega, outer_ctrl):
    """The four-point ball state of FourPointQuasiStaticModel's docstring, with numpy: arc centres, per-arc
    deflections, validity, contact angles and Hertz loads (K interpolated by numpy.interp), load weights,
    the two-point kinematics at the weighted angles, centrifugal force, Coulomb-bounded gyroscopic
    friction shared by the weights, and the force residual of each ball."""
    g = m.g
    psi = 2 * np.pi * np.arange(g.Z) / g.Z
    c, s = np.cos(psi), np.sin(psi)
    tilt = u[3] * s - u[4] * c
    dr, da = u[0] * c + u[1] * s, u[2] + g.Ri * tilt
    ei, eo = g.inner_groove_offset, g.outer_groove_offset
    Cr = np.stack([g.A * math.cos(g.alpha0) + dr - ei * tilt, g.A * math.cos(g.alpha0) + dr + ei * tilt], axis=1)
    Cz = np.stack([g.A * math.sin(g.alpha0) + da, g.A * math.sin(g.alpha0) + da - 2 * ei], axis=1)
    Xr, Xz = X[:, 0:1], X[:, 1:2]
    vz = np.concatenate([Xz, Xz - 2 * eo], axis=1)
    vr = np.broadcast_to(Xr, vz.shape)
    lo = np.hypot(vr, vz)
    nor, noz = vr / lo, vz / lo
    do = lo - (g.fo - 0.5) * g.D
    ao = np.arctan2(noz, nor)
    val_o = np.stack([g.fo * g.D * noz[:, 0] >= eo, g.fo * g.D * noz[:, 1] < -eo], axis=1)
    li = np.hypot(Xr - Cr, Xz - Cz)
    nir, niz = (Xr - Cr) / li, (Xz - Cz) / li
    di = li - (g.fi - 0.5) * g.D
    ai = np.arctan2(-niz, -nir)
    val_i = np.stack([-g.fi * g.D * niz[:, 0] >= ei, -g.fi * g.D * niz[:, 1] < -ei], axis=1)
    Qi = np.where(val_i, np.where(di > 0, m.hz.K(ai, True) * np.abs(di) ** 1.5, 1e-3 * di), 0.0)
    Qo = np.where(val_o, np.where(do > 0, m.hz.K(ao, False) * np.abs(do) ** 1.5, 1e-3 * do), 0.0)

    def weights(Q, d, valid):
        dmax = np.max(np.where(valid, d, -np.inf), axis=1, keepdims=True)
        w = np.where(valid, np.maximum(Q, 0) + 1e-9 * np.exp(np.minimum(0, d - dmax) / (1e-6 * g.D)), 0.0)
        return w / w.sum(axis=1, keepdims=True)

    wi, wo = weights(Qi, di, val_i), weights(Qo, do, val_o)
    ai_e, ao_e = np.sum(wi * ai, axis=1), np.sum(wo * ao, axis=1)
    oc = np.asarray(outer_ctrl, dtype=bool).copy()
    if m.control == "inner":
        oc[:] = False
    elif m.control == "hybrid":
        oc |= np.max(np.where(val_i, di, -np.inf), axis=1) <= 0
    beta, wm, wR = kin.kinematics(omega, ai_e, ao_e, g.D, g.dm, m.control, oc)
    wma = wm + m.omega_outer
    Fc = 0.5 * g.ball_mass * g.dm * wma ** 2
    Mg = -g.ball_inertia * wma * wR * np.sin(beta)
    lam_i = np.where(oc, 0.0, 1.0)

    def coulomb(F, Fmax):
        x = np.abs(F) / np.where(Fmax > 0, Fmax, 1.0)
        return np.where(Fmax > 0, F / (1 + x ** 8) ** 0.125, 0.0)

    Fi = coulomb(lam_i * Mg / g.D, m.mu_gyro * np.maximum(Qi, 0).sum(axis=1))[:, None] * wi
    Fo = coulomb((2 - lam_i) * Mg / g.D, m.mu_gyro * np.maximum(Qo, 0).sum(axis=1))[:, None] * wo
    Rr = np.sum(-Qi * nir + Fi * niz, axis=1) + np.sum(-Qo * nor + Fo * noz, axis=1) + Fc
    Rz = np.sum(-Qi * niz - Fi * nir, axis=1) + np.sum(-Qo * noz - Fo * nor, axis=1)
    return dict(Cr=Cr, Cz=Cz, Qi4=Qi, Qo4=Qo, ai4=ai, ao4=ao, di4=di, do4=do, wi=wi, wo=wo, Fi4=Fi, Fo4=Fo,
                ai=ai_e, ao=ao_e, beta=beta, wm=wm, wR=wR, Fc=Fc, Mg=Mg, Rr=Rr, Rz=Rz)


def test_ball_state_kernel_matches_numpy(solved):
    """The kernel's ball state (centres, per-arc loads, angles, deflections, weights, friction forces,
    kinematics, residual) equals the numpy evaluation of the same equations to round-off: at the
    solution and at ball positions moved by up to +-20 um (balls off equilibrium, other arcs engaged).
    Tolerance 1e-11 of each array's largest value; for the residuals of the largest contact load Q_max,
    for the friction forces of mu_gyro Q_max (and D times that for the gyroscopic moment: under a pure
    radial load the attitude angle is zero by symmetry, so these are round-off there); for angles 1e-11
    rad (the kernel takes cos / sin of a contact angle from the contact normal, numpy from the angle)."""
    m, r = solved
    rng = np.random.default_rng(7)
    for X in (r.X, r.X + rng.uniform(-2e-5, 2e-5, r.X.shape)):
        ref = _numpy_ball_state(m, r.u, X, r.omega, r.outer_control)
        Cr, Cz = m._centres(r.u)
        np.testing.assert_allclose(Cr, ref["Cr"], rtol=0, atol=1e-15)
        np.testing.assert_allclose(Cz, ref["Cz"], rtol=0, atol=1e-15)
        st = m._ball_state(X, Cr, Cz, r.omega, r.outer_control)
        for k, v in ref.items():
            if k in ("Cr", "Cz"):
                continue
            scale = max(np.max(np.abs(v)), 1e-300)
            qmax = max(np.max(np.abs(ref["Qi4"])), np.max(np.abs(ref["Qo4"])))
            if k in ("Rr", "Rz"):
                scale = qmax
            elif k in ("Fi4", "Fo4"):
                scale = max(scale, m.mu_gyro * qmax)
            elif k == "Mg":
                scale = max(scale, m.mu_gyro * qmax * m.g.D)
            atol = 1e-11 * (max(scale, 1.0) if k in ("ai4", "ao4", "ai", "ao", "beta") else scale)
            np.testing.assert_allclose(st[k], v, rtol=0, atol=atol, err_msg=k)


def test_ball_and_ring_equilibrium(solved):
    """Newton's laws from the returned per-contact arrays (Jones 1960; Harris & Kotzalas 5th ed. Vol. 2
    Ch. 3): (a) each ball: the four contact forces Q along their normals, the friction forces F resisting
    the gyroscopic moment along the tangents and the centrifugal force m dm omega_m^2 / 2 (absolute orbital
    speed) sum to zero within 1e-9 of the largest contact load (plus 1e-7 N for the separated-contact
    spring, < 1e-8 N); (b) the inner ring: the inner-arc forces, each acting through its arc centre at
    height +-e_i from the ring mid-plane, balance the applied loads within 1e-9 of the load (moments over
    dm / 2) plus 1e-6 N."""
    m, r = solved
    g = m.g
    Q, a, F = r.Q_c, r.alpha_c, r.F_c
    Fc = 0.5 * g.ball_mass * g.dm * (r.omega_m + m.omega_outer) ** 2
    np.testing.assert_allclose(r.Fc, Fc, rtol=1e-12, atol=0)
    Rr = (np.sum(Q[:, :2] * np.cos(a[:, :2]) - F[:, :2] * np.sin(a[:, :2]), axis=1)
          + np.sum(-Q[:, 2:] * np.cos(a[:, 2:]) + F[:, 2:] * np.sin(a[:, 2:]), axis=1) + Fc)
    Rz = (np.sum(Q[:, :2] * np.sin(a[:, :2]) + F[:, :2] * np.cos(a[:, :2]), axis=1)
          + np.sum(-Q[:, 2:] * np.sin(a[:, 2:]) - F[:, 2:] * np.cos(a[:, 2:]), axis=1))
    assert np.max(np.hypot(Rr, Rz)) < 1e-9 * Q.max() + 1e-7
    ai = a[:, :2]
    fr = -Q[:, :2] * np.cos(ai) + F[:, :2] * np.sin(ai)
    fz = -Q[:, :2] * np.sin(ai) - F[:, :2] * np.cos(ai)
    zc = np.array([g.inner_groove_offset, -g.inner_groove_offset])
    mom = g.Ri * fz.sum(axis=1) - (fr * zc).sum(axis=1) + g.ri * F[:, :2].sum(axis=1)
    c, s = np.cos(r.psi), np.sin(r.psi)
    Fb = np.array([np.sum(fr.sum(axis=1) * c), np.sum(fr.sum(axis=1) * s), np.sum(fz), np.sum(mom * s),
                   -np.sum(mom * c)])
    scale = np.array([1, 1, 1, 2 / g.dm, 2 / g.dm])
    ref = max(np.max(np.abs(r.loads * scale)), 1.0)
    assert np.max(np.abs((Fb + r.loads) * scale)) < 1e-9 * ref + 1e-6


def test_stiffness_predicts_neighbouring_solutions(solved):
    """The stiffness kernel (central differences of the ring force at the solution) against two further
    full solves per direction: K du = dF for load steps dF of 1e-4 of the load (moments 1e-4 of the load
    times dm / 2), du the change of the solved displacements. Tolerance 2e-3 of |dF| (second-order
    terms, the solver's 1e-10 tolerance)."""
    m, r = solved
    L = np.asarray(r.loads, dtype=float)
    step = 1e-4 * max(np.linalg.norm(L[:3]), 1.0)
    for k, dF in enumerate([step] * 3 + [step * 0.5 * QJ.dm] * 2):
        e = np.zeros(5)
        e[k] = dF
        up = m.solve(r.omega, L + e, u0=r.u, stiffness=False).u
        um = m.solve(r.omega, L - e, u0=r.u, stiffness=False).u
        pred = r.stiffness @ (up - um) / 2.0
        scale = np.array([1, 1, 1, 2 / QJ.dm, 2 / QJ.dm])
        assert np.max(np.abs((pred - e) * scale)) < 2e-3 * step, (k, pred, e)


@pytest.mark.parametrize("name", ["7218B", "QJ1044"])
def test_set_ball_azimuths_are_solved(name):
    """Ball azimuths set on a model (psi, e.g. the balls of a dynamic state) are the ones the kernels
    solve with: with the ball set turned by 0.37 of a ball spacing under a combined load, the ring
    reaction computed from the returned arrays at the returned azimuths balances the loads within 1e-9
    (moments over dm / 2), and the displacement differs from the unturned set's (variable compliance,
    Harris & Kotzalas 5th ed. Vol. 1 Ch. 7: the radial deflection varies as the balls pass the load)."""
    g = load_preset(name)
    m = quasistatic_model(g)
    loads = np.array([3000.0, 0.0, 6000.0, 0.0, 0.0])
    r0 = m.solve(3000 * RPM, loads, stiffness=False)
    m.psi = m.psi + 0.37 * 2 * np.pi / g.Z
    r = m.solve(3000 * RPM, loads, stiffness=False)
    np.testing.assert_array_equal(r.psi, m.psi)
    scale = np.array([1, 1, 1, 2 / g.dm, 2 / g.dm])
    assert np.max(np.abs((r.ring_reaction() + loads) * scale)) < 1e-9 * np.max(np.abs(loads))
    assert abs(r.u[0] - r0.u[0]) > 1e-6 * abs(r0.u[0])
