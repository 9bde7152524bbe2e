"""Linear algebra of the Rosenbrock-W integrator (dynamics_kernels.integrate_rosw): the arrow-structured
factorisation of I - h g W against a dense solve, the transformed stage form against the textbook
ROS34PW2 step, and the stability of the method with the scaled W that a kept factorisation amounts to."""
import math

import numpy as np
import pytest

from bearing_core.models import dynamics_kernels as K
NF, NSB = K.NSTATE_FIXED, K.NSB


def _arrow(nb, rng, outer_elastic=False):
    """Random arrow-structured W with the kernel's sparsity: Wfb non-zero only on the rows CB_ROWS that the
    balls' contributions enter (the outer-ring rows 18, 19 only with an elastic housing)."""
    ws = K.rosw_workspace(nb)
    Wff, Wbf, Wfb, Wbb = ws[:4]
    Wff[:] = rng.normal(size=Wff.shape) * 1e4
    Wbf[:] = rng.normal(size=Wbf.shape) * 1e4
    rows = K.CB_ROWS if outer_elastic else K.CB_ROWS[:8]
    Wfb[:] = 0.0
    Wfb[:, rows, :] = rng.normal(size=(nb, rows.size, NSB)) * 1e3
    Wbb[:] = rng.normal(size=Wbb.shape) * 1e5
    n = NF + nb * NSB
    W = np.zeros((n, n))
    W[:NF, :NF] = Wff
    for j in range(nb):
        o = NF + NSB * j
        W[o:o + NSB, o:o + NSB] = Wbb[j]
        W[o:o + NSB, :NF] = Wbf[j]
        W[:NF, o:o + NSB] = Wfb[j]
    return ws, W


@pytest.mark.parametrize("hg", [1e-6, 2e-5, 1e-3])
@pytest.mark.parametrize("outer_elastic", [False, True])
def test_arrow_factorisation_matches_dense_solve(hg, outer_elastic):
    """Block elimination (ball blocks, then the Schur complement on the fixed states; Golub & Van Loan,
    Matrix Computations, Sec. 3.2 and 4.5) gives the solution of the dense system (I - hg W) x = b to
    1e-11 relative (the systems' condition numbers reach 4e4 here; backward-stable LU with partial pivoting
    keeps the error near cond * 1e-16)."""
    rng = np.random.default_rng(7)
    nb = 16
    ws, W = _arrow(nb, rng, outer_elastic)
    Wff, Wbf, Wfb, Wbb, LUb, pivb, Minv, Z, S, pivs, _ = ws
    K._w_factor(hg, Wff, Wbf, Wfb, Wbb, LUb, pivb, Minv, Z, S, pivs)
    n = W.shape[0]
    for _ in range(3):
        b = rng.normal(size=n)
        ref = np.linalg.solve(np.eye(n) - hg * W, b)
        x = b.copy()
        K._w_solve(hg, x, Wbf, Minv, Z, S, pivs, np.empty(NSB))
        assert np.abs(x - ref).max() < 1e-11 * np.abs(ref).max()


def _step(f, W, y, h, h_lu, transformed):
    """One ROS34PW2 step with the matrix I - h_lu g W: the textbook form (Rang & Angermann 2005; stages k_s)
    or the kernel's transformed form (stages u_s, Hairer & Wanner II, Sec. IV.7)."""
    M = np.eye(y.size) - h_lu * K.ROSW_G * W
    st = []
    for s in range(4):
        if transformed:
            ys = y + h * sum((K.ROSW_TA[s, q] * st[q] for q in range(s)), np.zeros_like(y))
            r = K.ROSW_G * (f(ys) + sum((K.ROSW_TC[s, q] * st[q] for q in range(s)), np.zeros_like(y)))
        else:
            ys = y + h * sum((K.ROSW_A[s, q] * st[q] for q in range(s)), np.zeros_like(y))
            r = f(ys) + h_lu * W @ sum((K.ROSW_GAM[s, q] * st[q] for q in range(s)), np.zeros_like(y))
        st.append(np.linalg.solve(M, r))
    if transformed:
        return (y + h * sum(K.ROSW_TM[s] * st[s] for s in range(4)),
                h * sum(K.ROSW_TE[s] * st[s] for s in range(4)))
    return (y + h * sum(K.ROSW_B[s] * st[s] for s in range(4)),
            h * sum((K.ROSW_B[s] - K.ROSW_BH[s]) * st[s] for s in range(4)))


@pytest.mark.parametrize("ratio", [1.0, 0.8, 1.25])
def test_transformed_stages_equal_textbook_step(ratio):
    """The transformed stages u_s = sum_q Gamma_sq k_q (no product W sum gamma_sq k_q per stage) are an exact
    rewriting: solution and error estimate equal the textbook step to rounding (1e-13), also when the kept
    factorisation belongs to another step size (h_lu = ratio h), which both forms read as W' = (h_lu/h) W."""
    f = lambda y: np.array([y[1], -y[0] - 0.3 * y[1] ** 3 + np.sin(y[0]), -50.0 * (y[2] - y[0])])
    W = np.array([[0.0, 1.0, 0.0], [-3.0, -0.5, 0.0], [50.0, 0.0, -45.0]])
    y = np.array([1.0, 0.3, -0.2])
    h = 0.05
    y1, e1 = _step(f, W, y, h, ratio * h, transformed=False)
    y2, e2 = _step(f, W, y, h, ratio * h, transformed=True)
    assert np.abs(y1 - y2).max() < 1e-13 * np.abs(y1).max()
    assert np.abs(e1 - e2).max() < 1e-13 * max(np.abs(e1).max(), 1e-300) + 1e-16


def _stability(z, w):
    """Stability function R(z, w) of the W-method on y' = lambda y with W = alpha lambda (z = h lambda,
    w = h alpha lambda): one step of the k-form."""
    ks = []
    for s in range(4):
        r = z + sum(z * K.ROSW_A[s, q] * ks[q] + w * K.ROSW_GAM[s, q] * ks[q] for q in range(s))
        ks.append(r / (1.0 - K.ROSW_G * w))
    return 1.0 + sum(K.ROSW_B[s] * ks[s] for s in range(4))


def test_kept_factorisation_band_is_a_stable():
    """The kernel keeps the factorisation of I - h_lu g W for 0.8 <= h_lu / h <= 1.25, i.e. it runs the
    W-method with W = alpha J, alpha in [0.8, 1.25]. On a polar grid of the left half-plane (|z| from 1e-3
    to 1e7) |R(z, alpha z)| <= 1 + 1e-12 at the band's ends and inside (A-stability, Hairer & Wanner II,
    Sec. IV.3 and IV.7), and at alpha = 1 the method is L-stable (|R(-1e9)| < 1e-6) (Rang & Angermann 2005:
    ROS34PW2 is L-stable with the exact Jacobian); alpha = 0.5 is not A-stable (|R| > 1), which is why the
    band stops at 0.8."""
    assert K.ROSW_REUSE_LO == 0.8 and K.ROSW_REUSE_HI == 1.25
    th = np.linspace(math.pi / 2, math.pi, 61)
    r = np.logspace(-3, 7, 301)
    z = (r[:, None] * np.exp(1j * th)[None, :]).ravel()
    for alpha in (0.8, 0.9, 1.0, 1.1, 1.25):
        assert np.abs(_stability(z, alpha * z)).max() <= 1.0 + 1e-12, alpha
    assert abs(_stability(-1e9, -1e9)) < 1e-6
    assert np.abs(_stability(z, 0.5 * z)).max() > 1.1


@pytest.mark.parametrize("opts", [dict(), dict(fixed_tilt=True), dict(outer_mount="elastic"),
                                  dict(coupling="displacement"), dict(reduced="axisymmetric")])
def test_frozen_fixed_states_have_zero_derivative(opts):
    """The Jacobian skips the columns of the fixed states that _frozen_fixed declares frozen; that is exact
    only if the right-hand side sets their derivatives to zero whatever the state. Checked on 7218B at
    random perturbations of the quasi-static state (every state moved by up to 1e-6 of its scale), for each
    configuration that freezes states, and the frozen set is what the configuration implies (rigid outer
    ring: its 4 states; elastic: none of them)."""
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions
    from bearing_core.bearing.geometry import load_preset
    o = dict(reduced="full", traction="lubricated")
    o.update(opts)
    m = DynamicModel(load_preset("7218B"), DynamicsOptions(**o))
    axisym = o["reduced"] == "axisymmetric"
    loads = (0.0, 0.0, 3000.0, 0.0, 0.0) if axisym else (1000.0, 0.0, 3000.0, 0.0, 0.0)
    kw = {"displacement": np.zeros(10)} if o.get("coupling") == "displacement" else {}
    m.initialize(3000 * math.pi / 30, loads, **kw)
    fr = K._frozen_fixed(m.P)
    rigid = o.get("outer_mount", "fixed") != "elastic" or axisym
    assert fr[16:20].all() if rigid else not fr[16:20].any()
    if opts.get("fixed_tilt"):
        assert fr[[3, 4, 8, 9]].all()
    if opts.get("coupling") == "displacement":
        assert fr[:10].all()
    if axisym:
        assert fr[[0, 1, 3, 4, 5, 6, 8, 9]].all() and fr[12:16].all() and not fr[[2, 7, 10, 11]].any()
    rng = np.random.default_rng(3)
    nb = int(m.P[K.P_NB])
    dy = np.empty_like(m.y)
    for _ in range(5):
        y = m.y * (1.0 + 1e-6 * rng.normal(size=m.y.size)) + 1e-9 * rng.normal(size=m.y.size)
        K.rhs(0.0, y, dy, m.P, m.U, m._tab_i, m._tab_o, m._ta0, m._tda, m._tp, *m._quad, np.zeros(K.NOUT),
              np.zeros((nb, K.NBD)), False)
        assert np.all(dy[:K.NSTATE_FIXED][fr] == 0.0), np.nonzero(dy[:K.NSTATE_FIXED][fr])
