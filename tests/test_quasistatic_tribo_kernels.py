"""numba kernels of the quasi-static tribological model (bearing_core.models.quasistatic_tribo_kernels): the
block-arrow linear solve against LAPACK's dense solve, the arrow Jacobian against the residual change it
predicts, and the kept-Jacobian continuation against the per-step one."""
import math

import numpy as np
import pytest

import bearing_core.models.dynamics_kernels as K
import bearing_core.models.quasistatic_tribo_kernels as TK
from bearing_core.models.dynamics import DynamicModel, DynamicsOptions
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.quasistatic_tribo import TriboQuasiStaticModel

RPM = math.pi / 30
G = load_preset("7218B")


def _arrow(rng, Z, act):
    A = rng.normal(size=(Z, 6, 6)) - 8.0 * np.eye(6)
    B = rng.normal(size=(Z, 6, 6))
    C = rng.normal(size=(Z, 6, 6))
    Dg = rng.normal(size=(6, 6)) - 8.0 * Z * np.eye(6)
    B[:, :, ~act] = 0.0
    C[:, ~act, :] = 0.0
    Dg[~act, :] = 0.0
    Dg[:, ~act] = 0.0
    Dg[~act, ~act] = -1.0
    return A, B, C, Dg


@pytest.mark.parametrize("singular_block", [False, True])
def test_arrow_solve_equals_dense_lapack_solve(singular_block):
    """(diag(d)/dtau - J) dv = R by block elimination (and by the kernel's dense fallback when a ball block is
    singular) must equal numpy.linalg.solve (LAPACK gesv) of the assembled matrix to 1e-10 relative."""
    rng = np.random.default_rng(3)
    Z = 16
    act = np.array([True, True, True, True, True, False])
    A, B, C, Dg = _arrow(rng, Z, act)
    xs_l = np.array([1e-6, 1e-6, 300.0, 300.0, 300.0, 300.0])
    xs_g = np.array([1e-6, 1e-6, 1e-6, 1e-5, 1e-5, 300.0])
    d = np.empty(6 * Z + 6)
    TK.jacobian_diagonal(A, Dg, xs_l, xs_g, d)
    dtau = 3.0
    if singular_block:     # ball 5's block loses row 0 (the ring columns keep the whole matrix regular)
        A[5, 0, :] = 0.0
        d[30] = 0.0
        B[5, 0, :3] = 1e6
    J = np.empty((6 * Z + 6, 6 * Z + 6))
    TK.assemble(A, B, C, Dg, xs_l, xs_g, J)
    M = np.diag(d / dtau) - J
    R = rng.normal(size=6 * Z + 6)
    ref = np.linalg.solve(M, R)
    dv = np.empty_like(R)
    assert TK.arrow_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv)
    assert np.max(np.abs(dv - ref)) < 1e-10 * np.max(np.abs(ref))


def test_arrow_solve_reports_a_singular_matrix():
    """An exactly singular system (a ball block and its ring coupling both zero in one row) is reported, not
    solved into NaN."""
    rng = np.random.default_rng(4)
    act = np.ones(6, dtype=bool)
    act[5] = False
    A, B, C, Dg = _arrow(rng, 4, act)
    A[2, 1, :] = 0.0
    B[2, 1, :] = 0.0
    d = np.ones(30)
    d[13] = 0.0
    dv = np.empty(30)
    assert not TK.arrow_solve(A, B, C, Dg, np.ones(6), np.ones(6), d, 1.0, np.ones(30), dv)


def test_arrow_jacobian_predicts_the_residual_change():
    """The arrow Jacobian (balls coupled only through the ring) applied to a small change of ALL unknowns
    at once must predict the residual change of the full right-hand side: relative error < 2e-3 at random
    steps up to 0.3 nm and 3e-6 omega (first-order Taylor, measured 5e-4; an index or coupling error gives
    O(1); Coulomb 0.1, 3000 rpm, Fx 1 kN, Fz 3 kN, Jones-Harris state)."""
    w = 3000 * RPM
    m = DynamicModel(G, DynamicsOptions(traction="coulomb", mu=0.1, reduced="full"))
    m.initialize(w, (1000.0, 0.0, 3000.0, 0.0, 0.0))
    P, U = m.P, m.U
    P[K.P_LUBE] = 0.0
    P[K.P_ETA_LAND] = 0.0
    y = m.y.copy()
    y[5:11] = 0.0
    y[12:20] = 0.0
    Z = G.Z
    b = K.NSTATE_FIXED + K.NSB * np.arange(Z)
    y[b + 4] = 0.0
    y[b + 5] = 0.0
    xl = np.stack([y[b + 1], y[b + 2], y[b + 6], y[b + 7], y[b + 8], y[b + 3]], axis=1)
    xg = np.append(y[0:5], y[11])
    act = np.array([True] * 5 + [False])
    tabs = (m._tab_i, m._tab_o, m._ta0, m._tda, m._tp, *m._quad)
    iF, iM = K.OUT_INDEX["Fx"], K.OUT_INDEX["Mx"]
    ws = (np.empty(y.size), np.empty(y.size), np.zeros(K.NOUT), np.zeros((Z, K.NBD)))

    def res(xl_, xg_):
        Rl, Rg, sh = np.empty((Z, 6)), np.empty(6), np.empty((Z, 6))
        TK.residual(0.0, y, xl_, xg_, act, iF, iM, P, U, *tabs, *ws, Rl, Rg, sh)
        return Rl, Rg, sh

    Rl, Rg, sh = res(xl, xg)
    A, B, C, Dg = (np.empty((Z, 6, 6)), np.empty((Z, 6, 6)), np.empty((Z, 6, 6)), np.empty((6, 6)))
    TK.jacobian(0.0, y, xl, xg, Rl, Rg, sh, act, w, iF, iM, P, U, *tabs, *ws, A, B, C, Dg)
    rng = np.random.default_rng(5)
    el = rng.uniform(-1, 1, size=(Z, 6)) * np.array([3e-10, 3e-10, 3e-6 * w, 3e-6 * w, 3e-6 * w, 3e-6 * w])
    eg = rng.uniform(-1, 1, size=6) * np.array([3e-10, 3e-10, 3e-10, 3e-9, 3e-9, 0.0])
    Rl2, Rg2, _ = res(xl + el, xg + eg)
    pred_l = np.einsum("jik,jk->ji", A, el) + np.einsum("jik,k->ji", B, eg)
    pred_g = np.einsum("jik,jk->i", C, el) + Dg @ eg
    pred_g[~act] = 0.0
    assert np.max(np.abs(Rl2 - Rl - pred_l)) < 2e-3 * np.max(np.abs(Rl2 - Rl))
    assert np.max(np.abs(Rg2 - Rg - pred_g)) < 2e-3 * np.max(np.abs(Rg2 - Rg))


def _assert_same_steady_state(a, b, rel=1e-7):
    """Two solves of the same case agree to rel in cage speed, contact loads (relative to the largest) and
    drive power."""
    assert abs(a.cage_speed / b.cage_speed - 1) < rel
    assert np.max(np.abs(a.Q_i - b.Q_i)) < rel * np.max(b.Q_i)
    assert np.max(np.abs(a.Q_o - b.Q_o)) < rel * np.max(b.Q_o)
    assert abs(a.losses["P_drive"] / b.losses["P_drive"] - 1) < rel


@pytest.mark.parametrize("traction", ["lubricated", "coulomb"])
def test_kept_jacobian_reaches_the_same_steady_state(traction):
    """The kept-Jacobian continuation and the per-step-Jacobian continuation solve the same equations: at a
    tolerance of 1e-10 of the load both steady states must agree to 1e-7 in cage speed, contact loads
    (relative to the largest) and drive power (3000 rpm, Fx 1 kN, Fz 3 kN; 7218B)."""
    opt = DynamicsOptions(traction=traction, mu=0.1)
    out = []
    for lazy in (True, False):
        m = TriboQuasiStaticModel(G, opt)
        m.lazy_jacobian = lazy
        out.append(m.solve(3000 * RPM, (1000.0, 0.0, 3000.0, 0.0, 0.0), tol=1e-10))
    a, b = out
    _assert_same_steady_state(a, b)
    assert a.iterations < b.iterations


@pytest.mark.parametrize("traction", ["lubricated", "coulomb"])
def test_near_newton_stage_reaches_the_same_steady_state(traction):
    """The near-Newton first stage (large initial pseudo-time step, chord polishing) and the continuation
    from dtau 1 solve the same equations: at a tolerance of 1e-10 of the load both steady states must agree
    to 1e-7 in cage speed, contact loads (relative to the largest) and drive power, and the near-Newton stage
    must be the one that converged (fewer evaluations than the continuation alone; 3000 rpm, Fx 1 kN,
    Fz 3 kN; 7218B)."""
    opt = DynamicsOptions(traction=traction, mu=0.1)
    out = []
    for budget in (TriboQuasiStaticModel.fast_budget, 0):
        m = TriboQuasiStaticModel(G, opt)
        m.fast_budget = budget
        out.append(m.solve(3000 * RPM, (1000.0, 0.0, 3000.0, 0.0, 0.0), tol=1e-10))
    a, b = out
    _assert_same_steady_state(a, b)
    assert a.iterations <= TriboQuasiStaticModel.fast_budget < b.iterations


@pytest.mark.parametrize("traction", ["lubricated", "coulomb"])
def test_start_with_a_stopped_ball_returns_the_axisymmetric_steady_state(traction):
    """Under pure thrust every ball carries the same load and orbits at the same speed (Harris & Kotzalas,
    Vol. 1, pure axial load: Q = Fa / (Z sin alpha)). Started from a steady state in which ball 3 is stopped
    (no spin, no orbit) and pulled 20 um off both raceways -- next to the spurious root of a ball without
    contact load and orbital speed, whose residuals are zero -- the solve must return the axisymmetric state:
    orbital speeds and contact loads of all balls equal to 1e-6 (7218B, 3000 rpm, Fz 3 kN)."""
    import copy
    m = TriboQuasiStaticModel(G, DynamicsOptions(traction=traction, mu=0.1))
    w = 3000 * RPM
    q = m.solve(w, (0.0, 0.0, 3000.0, 0.0, 0.0))
    s = copy.copy(q)
    s.y, s.omega_ball, s.orbit_speed = q.y.copy(), q.omega_ball.copy(), q.orbit_speed.copy()
    s.omega_ball[3] = 0.0
    s.orbit_speed[3] = 0.0
    s.y[K.NSTATE_FIXED + K.NSB * 3 + 1] -= 20e-6
    r = m.solve(w, (0.0, 0.0, 3000.0, 0.0, 0.0), start=s)
    assert np.ptp(r.orbit_speed) < 1e-6 * np.max(r.orbit_speed)
    assert np.ptp(r.Q_i) < 1e-6 * np.max(r.Q_i)
    assert np.ptp(r.Q_o) < 1e-6 * np.max(r.Q_o)
