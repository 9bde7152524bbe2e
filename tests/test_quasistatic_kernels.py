"""numba kernels of the two-point quasi-static model (bearing_core.models.quasistatic_kernels), held against checks
computed here from the returned per-ball arrays with numpy, independently of the kernels."""
import math

import numpy as np
import pytest

from bearing_core.errors import ConvergenceError
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.quasistatic import FourPointQuasiStaticModel, QuasiStaticModel
from bearing_core.models.quasistatic_kernels import lstsq_svd

RPM = math.pi / 30

CASES = [
    ("7218B", 0.0, "outer", (0.0, 0.0, 3000.0, 0.0, 0.0)),
    ("7218B", 3000.0, "outer", (1000.0, 0.0, 3000.0, 0.0, 0.0)),
    ("7218B", 10000.0, "inner", (3000.0, 900.0, 900.0, 0.0, 0.0)),
    ("7218B", 20000.0, "hybrid", (600.0, 0.0, 3000.0, 40.0, -25.0)),
    ("7008-ma2023", 12000.0, "outer", (300.0, -200.0, 800.0, 3.0, 2.0)),
    ("wan-105", 15000.0, "hybrid", (0.0, 0.0, 889.84, 0.0, 0.0)),
]


@pytest.fixture(scope="module", params=CASES, ids=[f"{c[0]}-{c[1]:g}rpm-{c[2]}" for c in CASES])
def solved(request):
    name, rpm, control, loads = request.param
    g = load_preset(name)
    return g, QuasiStaticModel(g, control).solve(rpm * RPM, loads, stiffness=True)


def test_ball_and_ring_equilibrium(solved):
    """Newton's laws from the returned arrays (Jones 1960; Harris & Kotzalas 5th ed. Vol. 2 Ch. 3):
    (a) each ball: contact forces Q along the normals, the friction forces F resisting the gyroscopic
        moment along the tangents and the centrifugal force m dm omega_m^2 / 2 sum to zero, within 1e-9 of
        the largest contact load (plus 1e-7 N for the separated-contact spring, < 1e-8 N);
    (b) the inner ring: the ball forces on it (applied at the groove-centre locus of radius Ri, friction
        moment arm ri) balance the applied (Fx, Fy, Fz, Mx, My) within 1e-9 of the load (moments over dm/2);
    (c) Mg = J omega_m omega_R sin(beta) in magnitude, and the friction pair carries Mg / D (lambda_i +
        lambda_o = 2) where it is below the Coulomb limit."""
    g, r = solved
    ai, ao = r.alpha_i, r.alpha_o
    Fc = 0.5 * g.ball_mass * g.dm * r.omega_m ** 2
    assert np.allclose(r.Fc, Fc, rtol=1e-12, atol=0)
    # (a) ball: n_i = -(cos ai, sin ai), n_o = (cos ao, sin ao), tangents e = (n_z, -n_r)
    Rr = r.Q_i * np.cos(ai) - r.Q_o * np.cos(ao) - r.F_i * np.sin(ai) + r.F_o * np.sin(ao) + Fc
    Rz = r.Q_i * np.sin(ai) - r.Q_o * np.sin(ao) + r.F_i * np.cos(ai) - r.F_o * np.cos(ao)
    qmax = max(r.Q_i.max(), r.Q_o.max())
    assert np.max(np.hypot(Rr, Rz)) < 1e-9 * qmax + 1e-7
    # (b) ring
    fr = -r.Q_i * np.cos(ai) + r.F_i * np.sin(ai)
    fz = -r.Q_i * np.sin(ai) - r.F_i * np.cos(ai)
    c, s = np.cos(r.psi), np.sin(r.psi)
    F = np.array([np.sum(fr * c), np.sum(fr * s), np.sum(fz),
                  np.sum(g.Ri * s * fz + g.ri * r.F_i * s), np.sum(-g.Ri * c * fz - g.ri * r.F_i * c)])
    scale = np.array([1, 1, 1, 2 / g.dm, 2 / g.dm])
    ref = max(np.max(np.abs(r.loads * scale)), 1.0)
    assert np.max(np.abs((F + r.loads) * scale)) < 1e-9 * ref
    # (c) gyroscopic moment and its friction forces
    assert np.allclose(np.abs(r.Mg), np.abs(g.ball_inertia * r.omega_m * r.omega_R * np.sin(r.beta)),
                       rtol=1e-12, atol=1e-300)
    free = (np.abs(r.F_i) < 0.2 * 0.1 * r.Q_i) & (np.abs(r.F_o) < 0.2 * 0.1 * r.Q_o)
    if r.omega > 0:
        assert np.allclose((r.F_i + r.F_o)[free], 2.0 * r.Mg[free] / g.D, rtol=1e-4, atol=1e-12)


def test_stiffness_predicts_neighbouring_solutions(solved):
    """The stiffness kernel (central differences of the ring force at the solution) against two further
    full solves: K du = dF for a load step dF of 1e-4 of the load in each direction, du the
    change of the solved displacements. Tolerance 2e-3 relative (second-order terms and the solver's
    1e-10 tolerance)."""
    g, r = solved
    m = QuasiStaticModel(g, r.control)
    L = np.asarray(r.loads, dtype=float)
    step = 1e-4 * max(np.linalg.norm(L[:3]), 1.0)
    for k, dF in enumerate([step, step, step, step * 0.5 * g.dm, step * 0.5 * g.dm]):
        e = np.zeros(5)
        e[k] = dF
        up = m.solve(r.omega, L + e, u0=r.u, stiffness=False).u
        um = m.solve(r.omega, L - e, u0=r.u, stiffness=False).u
        pred = r.stiffness @ (up - um) / 2.0
        assert np.linalg.norm(pred - e) < 2e-3 * dF, (k, pred, e)


def test_wan105_seed003_table2_through_kernels():
    """Seed 003 (Liu et al. 2026) Table 2, literature column (Wan Changsen 1987): wan-105, Fz 889.84 N,
    15,000 rpm, outer control: orbital speed 7255 rpm, ball spin 57,670 rpm, contact angles 37.7 / 4.074
    deg, loads 76.57 / 488.97 N, within 1 %; and the model instance re-solved many times returns the same
    numbers bit for bit (no state carried between solves)."""
    g = load_preset("wan-105")
    m = QuasiStaticModel(g, "outer")
    r = m.solve(15000 * RPM, (0, 0, 889.84, 0, 0), stiffness=False)
    got = (r.omega_m[0] / RPM, abs(r.omega_R[0]) / RPM, math.degrees(r.alpha_i[0]), math.degrees(r.alpha_o[0]),
           r.Q_i[0], r.Q_o[0])
    for x, ref in zip(got, (7255, 57670, 37.7, 4.074, 76.57, 488.97)):
        assert abs(x / ref - 1) < 0.01, (x, ref)
    m.solve(1000 * RPM, (500, 0, 889.84, 0, 0), stiffness=True)
    r2 = m.solve(15000 * RPM, (0, 0, 889.84, 0, 0), stiffness=False)
    assert np.array_equal(r.u, r2.u) and np.array_equal(r.Q_o, r2.Q_o)


@pytest.mark.parametrize("name, rpm, control, loads", [
    ("7218B", 20000.0, "outer", (3200.0, 960.0, 960.0, 0.0, 0.0)),
    ("7218B", 20000.0, "outer", (600.0, 0.0, 3000.0, 40.0, -25.0)),
    ("wan-105", 20000.0, "hybrid", (1500.0, 450.0, 450.0, 0.0, 0.0)),
    ("QJ1044", 3000.0, "outer", (1000.0, 0.0, 3000.0, 0.0, 0.0)),
])
def test_fast_and_plain_newton_reach_the_same_equilibrium(name, rpm, control, loads):
    """The ring equilibrium does not depend on the iteration: the fast solve (growing step limits, kept
    Broyden Jacobian, finer ball tolerance near the solution) and the plain Newton iteration (fixed
    limits, a new difference Jacobian every iteration) end at the same displacements and ball loads within
    what the convergence criterion allows (scaled ring residual < 1e-10, condition numbers of the scaled
    Jacobian < 1e3: 1e-7 of the largest displacement / load); the four-point case covers
    quasistatic4_kernels.solve."""
    g = load_preset(name)
    m = (FourPointQuasiStaticModel if g.is_four_point else QuasiStaticModel)(g, control)
    loads = np.asarray(loads, dtype=float)
    fast = m._solve(rpm * RPM, loads, None, 1e-10, 30, False, fast=True)
    plain = m._solve(rpm * RPM, loads, None, 1e-10, 100, False, fast=False)
    assert np.max(np.abs(fast.u - plain.u)) < 1e-7 * np.max(np.abs(plain.u))
    qmax = max(plain.Q_i.max(), plain.Q_o.max())
    assert np.max(np.abs(fast.Q_i - plain.Q_i)) < 1e-7 * qmax
    assert np.max(np.abs(fast.Q_o - plain.Q_o)) < 1e-7 * qmax
    for r in (fast, plain):
        assert r.residual < 1e-9


def test_convergence_error_message():
    """A solve that cannot converge in the allowed iterations raises ConvergenceError naming the speed,
    the loads and the control, with the reason of both attempts (direct and speed continuation)."""
    m = QuasiStaticModel(load_preset("7218B"), "inner")
    with pytest.raises(ConvergenceError, match=r"no quasi-static equilibrium found for omega = 314\.159.*"
                                               r"'inner'.*did not converge in 1 iterations"):
        m.solve(3000 * RPM, (1000.0, 0.0, 3000.0, 0.0, 0.0), maxit=1)


def test_lstsq_svd_matches_numpy():
    """The Jacobi-SVD least-squares step equals numpy.linalg.lstsq (LAPACK gelsd) with the same rcond:
    full-rank matrices within 10 cond(A) eps relative, rank-deficient ones (minimum-norm solution) within
    1e-9."""
    rng = np.random.default_rng(1)
    for k in range(200):
        A = rng.normal(size=(5, 5)) * np.exp(2 * rng.normal(size=5))[None, :] * np.exp(2 * rng.normal(size=5))[:, None]
        if k % 2:
            A[:, 3] = -1.5 * A[:, 0]
        b = rng.normal(size=5)
        x = np.linalg.lstsq(A, b, rcond=1e-12)[0]
        y = lstsq_svd(A, b, 1e-12)
        tol = 1e-9 if k % 2 else 10 * np.linalg.cond(A) * np.finfo(float).eps
        assert np.linalg.norm(x - y) <= tol * np.linalg.norm(x)
