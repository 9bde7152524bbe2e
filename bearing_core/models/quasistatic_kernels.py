"""numba kernels of the two-point Jones-Harris quasi-static model (bearing_core.models.quasistatic, whose module
docstring states the equations and sources: Jones 1960; Harris & Kotzalas, Rolling Bearing Analysis 5th
ed., Vol. 2 Ch. 3; seed 003 Eqs. 1-19).

One ball:        _ball          contact deflections, Hertz loads (hertz.hertz_lookup_alpha on the
                                HertzTable arrays), raceway-control kinematics, centrifugal force,
                                gyroscopic moment and its Coulomb-bounded friction, equilibrium residual.
All balls:       _solve_balls   per-ball Newton (2x2 finite-difference Jacobian, step limit 1e-3 D,
                                per-ball backtracking) for the ball equilibrium at given ring displacement.
Ring:            ring_forces    force and moment of the balls on the inner ring.
5-DOF solve:     solve          Newton on the ring equilibrium (finite-difference 5x5 Jacobian, kept
                                with Broyden updates while it contracts the residual, least squares
                                step, growing step limits, backtracking line search), Harris's
                                hybrid-control criterion, and the 5x5 stiffness matrix by central
                                differences.

Geometry and parameters come in one float array ``geo`` (indices G_*); the raceway control as an int
(CTRL_*); the ball state of all balls as a (NS, Z) array (rows S_*).
"""
from __future__ import annotations

import math

import numpy as np

from ..contact.hertz import ROW_A_COEF, ROW_ELL_E, ROW_K_LOAD, hertz_lookup_alpha
from ..numerics.jit import hot

K_REG = 1e-3  # N/m, tension spring of separated contacts (quasistatic module docstring)
BALL_TOL = 1e-10       # ball equilibrium: max |R| < BALL_TOL (max(1, m dm omega^2 / 2) + max Q)
BALL_TOL_FINE = 1e-12  # the same near the ring solution (solve: max scaled ring residual < RING_FINE)
RING_FINE = 1e-6
STEP_GROW_MAX = 32.0   # ring step limits grow up to this factor while clipped full steps are accepted
REUSE_CONTRACTION = 0.1  # ring Jacobian kept (Broyden-updated) after full steps contracting |r| this much

CTRL_OUTER, CTRL_INNER, CTRL_HYBRID = 0, 1, 2
G_D, G_DM, G_FO, G_FI, G_A, G_ALPHA0, G_RI, G_RIG, G_MASS, G_INERTIA, G_MU, G_WOUT, N_GEO = range(13)
(S_RR, S_RZ, S_QI, S_QO, S_DI, S_DO, S_AI, S_AO, S_BETA, S_WM, S_WR, S_FC, S_MG, S_LAMI, S_OC, S_FI,
 S_FO, NS) = range(18)
STATE_NAMES = ("Rr", "Rz", "Qi", "Qo", "d_i", "d_o", "ai", "ao", "beta", "wm", "wR", "Fc", "Mg", "lam_i",
               "outer_ctrl", "Fi", "Fo")

# status codes of solve()
OK, LINE_SEARCH_FAILED, NOT_CONVERGED = 0, 1, 2


@hot(inline="always")
def _copy1(a, out):
    """out[:] = a (1-D), without numpy's shape-mismatch error path."""
    for i in range(a.shape[0]):
        out[i] = a[i]


@hot(inline="always")
def _copy2(a, out):
    """out[:, :] = a (2-D)."""
    for i in range(a.shape[0]):
        for k in range(a.shape[1]):
            out[i, k] = a[i, k]


@hot(inline="always")
def _sign(x):
    """sign of x (0 for 0 and NaN)."""
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)


@hot(inline="always")
def _norm5(r):
    """Euclidean norm of a 5-vector."""
    s = 0.0
    for k in range(5):
        s += r[k] * r[k]
    return math.sqrt(s)


@hot(inline="always")
def _dot_col(A, i, B, k):
    """Dot product of column i of A and column k of B."""
    s = 0.0
    for j in range(A.shape[0]):
        s += A[j, i] * B[j, k]
    return s


@hot(inline="always")
def _coulomb(F, Fmax):
    """Smooth |F| <= Fmax: F / (1 + (|F|/Fmax)^8)^(1/8); 0 where Fmax <= 0."""
    if Fmax > 0.0:
        x = F / Fmax
        x2 = x * x
        x4 = x2 * x2
        if abs(x4) < 3e-9:              # x^8 < 1e-17: 1 + x^8 rounds to 1, F itself without the roots
            return F
        return F / math.sqrt(math.sqrt(math.sqrt(1.0 + x4 * x4)))
    return 0.0


@hot(inline="always")
def ball_kinematics(cai, sai, cao, sao, oc, control, omega, geo, Qi_pos, Qo_pos):
    """Kinematics and gyroscopic friction of one ball from cos / sin of its inner and outer contact angles
    and the compressive load on each race [N]: raceway control (kinematics.attitude_outer /
    attitude_inner; oc: the outer race controls under hybrid control) and pure rolling
    (kinematics.ball_speeds), centrifugal force and gyroscopic moment at the absolute orbital speed, the
    friction forces resisting the moment (lambda_i = 0 / 1, lambda_o = 2 - lambda_i, Coulomb-bounded by
    mu Q). Returns (bx, by, wm, wR, Fc, Mg, lam_i, Fi, Fo); beta = atan2(by, bx)."""
    D = geo[G_D]
    dm = geo[G_DM]
    gam = D / dm
    if control == CTRL_OUTER or (control == CTRL_HYBRID and oc):
        bx = cao + gam
        by = sao
    else:
        bx = cai - gam
        by = sai
    hb = math.sqrt(bx * bx + by * by)
    cb = bx / hb                           # cos(beta), sin(beta)
    sb = by / hb
    gi = D * cai / dm
    go = D * cao / dm
    ci = cai * cb + sai * sb               # cos(ai - beta)
    co = cao * cb + sao * sb               # cos(ao - beta)
    wm = omega * (1.0 - gi) / ((1.0 - gi) + (1.0 + go) * ci / co)
    wR = -wm * dm * (1.0 + go) / (D * co)
    wma = wm + geo[G_WOUT]                 # absolute orbital speed
    Fc = 0.5 * geo[G_MASS] * dm * wma * wma
    Mg = geo[G_INERTIA] * wma * wR * sb * -1.0
    lam_i = 0.0 if oc else 1.0
    lam_o = 2.0 - lam_i
    Fi = _coulomb(lam_i * Mg / D, geo[G_MU] * Qi_pos)
    Fo = _coulomb(lam_o * Mg / D, geo[G_MU] * Qo_pos)
    return bx, by, wm, wR, Fc, Mg, lam_i, Fi, Fo


@hot
def _ball(Xr, Xz, Cr, Cz, omega, oc_in, control, geo, tab_i, tab_o, dal):
    """State of one ball with centre (Xr, Xz) [m] relative to the outer groove centre and inner groove
    centre (Cr, Cz) [m]. Returns (Rr, Rz, Qi, Qo, d_i, d_o, ai, ao, bx, wm, wR, Fc, Mg, lam_i, oc, Fi, Fo,
    by): the quantities of QuasiStaticModel._ball_state (loads include the separated-contact spring; oc as
    1.0 / 0.0), the attitude angle as beta = atan2(by, bx) (ball_states; the Newton iterations do not
    need it)."""
    D = geo[G_D]
    lo = math.sqrt(Xr * Xr + Xz * Xz)
    nor = Xr / lo
    noz = Xz / lo
    dvr = Xr - Cr
    dvz = Xz - Cz
    li = math.sqrt(dvr * dvr + dvz * dvz)
    nir = dvr / li
    niz = dvz / li
    d_o = lo - (geo[G_FO] - 0.5) * D
    d_i = li - (geo[G_FI] - 0.5) * D
    ao = math.atan2(noz, nor)
    ai = math.atan2(-niz, -nir)
    if control == CTRL_INNER:
        oc = False
    elif control == CTRL_HYBRID:
        oc = oc_in or d_i <= 0.0        # balls without inner contact roll on the outer race only
    else:
        oc = oc_in
    Ki = hertz_lookup_alpha(tab_i, 0.0, dal, ai, ROW_K_LOAD)
    Ko = hertz_lookup_alpha(tab_o, 0.0, dal, ao, ROW_K_LOAD)
    Qi = Ki * d_i * math.sqrt(d_i) if d_i > 0.0 else K_REG * d_i       # K delta^1.5
    Qo = Ko * d_o * math.sqrt(d_o) if d_o > 0.0 else K_REG * d_o
    # raceway control (kinematics.attitude_outer / attitude_inner) and pure rolling (ball_speeds), with
    # cos / sin of the contact angles taken from the unit normals: (cos ao, sin ao) = n_o,
    # (cos ai, sin ai) = -n_i
    bx, by, wm, wR, Fc, Mg, lam_i, Fi, Fo = ball_kinematics(-nir, -niz, nor, noz, oc, control, omega, geo,
                                                            max(Qi, 0.0), max(Qo, 0.0))
    Rr = -Qi * nir - Qo * nor + Fi * niz + Fo * noz + Fc
    Rz = -Qi * niz - Qo * noz - Fi * nir - Fo * nor
    return Rr, Rz, Qi, Qo, d_i, d_o, ai, ao, bx, wm, wR, Fc, Mg, lam_i, 1.0 if oc else 0.0, Fi, Fo, by


@hot(inline="always")
def _centres(u, cpsi, spsi, geo, Cr, Cz):
    """Inner groove-centre position per ball (seed 003 Eqs. 3, 5, 6) into Cr, Cz [m]."""
    A = geo[G_A]
    cr0 = A * math.cos(geo[G_ALPHA0])
    cz0 = A * math.sin(geo[G_ALPHA0])
    for j in range(cpsi.shape[0]):
        dr = u[0] * cpsi[j] + u[1] * spsi[j]
        da = u[2] + geo[G_RI] * (u[3] * spsi[j] - u[4] * cpsi[j])
        Cr[j] = cr0 + dr
        Cz[j] = cz0 + da


@hot
def centres(u, cpsi, spsi, geo):
    """(Cr, Cz) [m] of every ball for ring displacement u (dx, dy, dz, tx, ty) [m, rad]."""
    Z = cpsi.shape[0]
    Cr = np.empty(Z)
    Cz = np.empty(Z)
    _centres(u, cpsi, spsi, geo, Cr, Cz)
    return Cr, Cz


@hot
def ball_states(X, Cr, Cz, omega, oc, control, geo, tab_i, tab_o, dal, S):
    """All balls' states into S (NS, Z). X (Z, 2) [m]; oc (Z,) bool: outer race controls."""
    for j in range(X.shape[0]):
        r = _ball(X[j, 0], X[j, 1], Cr[j], Cz[j], omega, oc[j], control, geo, tab_i, tab_o, dal)
        for k in range(NS):
            S[k, j] = r[k]
        S[S_BETA, j] = math.atan2(r[NS], r[S_BETA])      # attitude angle from (bx, by)


@hot(inline="always")
def rolling_fc(omega, geo):
    """Centrifugal force [N] of a ball at the pure-rolling orbital speed omega (1 - D/dm) / 2 (zero
    contact angle estimate, for starting positions)."""
    wm = 0.5 * omega * (1.0 - geo[G_D] / geo[G_DM])
    return 0.5 * geo[G_MASS] * geo[G_DM] * wm ** 2


@hot(inline="always")
def _x_start(Cr, Cz, omega, geo, tab_o, dal, X):
    """Initial ball positions: on the line of centres with equal deflections; at speed a ball whose
    equal deflection is below the outer deflection dc of the pure-rolling centrifugal force alone is
    put on the outer race with deflection dc along the line of centres (the inner contact then takes
    what is left, 2 d - dc; at d = dc both starts agree)."""
    D = geo[G_D]
    ro = (geo[G_FO] - 0.5) * D
    ri = (geo[G_FI] - 0.5) * D
    lo = 0.0
    ta = 0.0
    if omega > 0.0:
        K0 = hertz_lookup_alpha(tab_o, 0.0, dal, geo[G_ALPHA0], ROW_K_LOAD)
        lo = ro + (rolling_fc(omega, geo) / K0) ** (2.0 / 3.0)
    for j in range(Cr.shape[0]):
        L = math.hypot(Cr[j], Cz[j])
        d = 0.5 * (L - (ro + ri))
        t = (ro + d) / max(L, 1e-300)
        X[j, 0] = Cr[j] * t
        X[j, 1] = Cz[j] * t
        if omega > 0.0 and d < lo - ro:
            ta = math.atan2(Cz[j], Cr[j])
            X[j, 0] = lo * math.cos(ta)
            X[j, 1] = lo * math.sin(ta)


@hot
def x_start(u, omega, cpsi, spsi, geo, tab_o, dal):
    """Initial ball positions X (Z, 2) [m] for ring displacement u (see _x_start)."""
    Z = cpsi.shape[0]
    Cr = np.empty(Z)
    Cz = np.empty(Z)
    _centres(u, cpsi, spsi, geo, Cr, Cz)
    X = np.empty((Z, 2))
    _x_start(Cr, Cz, omega, geo, tab_o, dal, X)
    return X


@hot(inline="always")
def ball_newton_step(J00, J01, J10, J11, R0, R1, D, lim):
    """Newton step (d0, d1) [m] of one ball's 2x2 equilibrium J d = -R, a small steepest-descent step
    (1e-4 D) where J is singular, limited to lim in the max norm."""
    det = J00 * J11 - J01 * J10
    if not abs(det) > 0.0:
        det = 1e-300
    d0 = -(J11 * R0 - J01 * R1) / det
    d1 = -(-J10 * R0 + J00 * R1) / det
    if not (math.isfinite(d0) and math.isfinite(d1)):
        # singular 2x2 (e.g. degenerate kinematics): small steepest-descent step
        d0 = -1e-4 * D * _sign(R0)
        d1 = -1e-4 * D * _sign(R1)
    mag = max(abs(d0), abs(d1))
    if mag > lim:
        f = lim / max(mag, 1e-300)
        d0 *= f
        d1 *= f
    return d0, d1


@hot
def _solve_balls(Cr, Cz, omega, X, oc, control, geo, tab_i, tab_o, dal, tol, maxit, S, Rr, Rz):
    """Newton per ball on the ball equilibrium, X (Z, 2) updated in place; 2x2 forward-difference
    Jacobians (step 1e-10 D), Newton step limited to 1e-3 D, per-ball backtracking on |R| (at most 12
    halvings, down to 1e-3). Converged when max |R| < tol (max(1, m dm omega^2 / 2) + max Q) over all
    balls. Leaves the final state in S; returns converged."""
    Z = X.shape[0]
    D = geo[G_D]
    scale = max(1.0, 0.5 * geo[G_MASS] * geo[G_DM] * omega ** 2)
    h = 1e-10 * D
    lim = 1e-3 * D
    # residual and loads of each ball at X, kept from its line search when that evaluated the accepted point
    Qi = np.empty(Z)
    Qo = np.empty(Z)
    known = np.zeros(Z, dtype=np.bool_)
    # a ball whose Newton update leaves X bit for bit unchanged is at a fixed point of the iteration (the
    # same X gives the same residual, Jacobian and step): it is skipped from then on, which changes nothing
    frozen = np.zeros(Z, dtype=np.bool_)
    for it in range(maxit):
        rmax = 0.0
        qmax = 0.0
        finite = True
        for j in range(Z):
            if not known[j]:
                r = _ball(X[j, 0], X[j, 1], Cr[j], Cz[j], omega, oc[j], control, geo, tab_i, tab_o, dal)
                Rr[j] = r[0]
                Rz[j] = r[1]
                Qi[j] = r[2]
                Qo[j] = r[3]
            if not (math.isfinite(Rr[j]) and math.isfinite(Rz[j]) and math.isfinite(Qi[j])
                    and math.isfinite(Qo[j])):
                finite = False
            rmax = max(rmax, abs(Rr[j]), abs(Rz[j]))
            qmax = max(qmax, Qi[j], Qo[j])
        if finite and rmax < tol * (scale + qmax):
            ball_states(X, Cr, Cz, omega, oc, control, geo, tab_i, tab_o, dal, S)
            return True
        for j in range(Z):
            if frozen[j]:
                continue
            x0 = X[j, 0]
            x1 = X[j, 1]
            R0 = Rr[j]
            R1 = Rz[j]
            p = _ball(x0 + h, x1, Cr[j], Cz[j], omega, oc[j], control, geo, tab_i, tab_o, dal)
            J00 = (p[0] - R0) / h
            J10 = (p[1] - R1) / h
            p = _ball(x0, x1 + h, Cr[j], Cz[j], omega, oc[j], control, geo, tab_i, tab_o, dal)
            J01 = (p[0] - R0) / h
            J11 = (p[1] - R1) / h
            d0, d1 = ball_newton_step(J00, J01, J10, J11, R0, R1, D, lim)
            n0 = math.hypot(R0, R1)
            lam = 1.0
            xn0 = x0 + d0
            xn1 = x1 + d1
            known[j] = False
            for _ in range(12):
                q = _ball(xn0, xn1, Cr[j], Cz[j], omega, oc[j], control, geo, tab_i, tab_o, dal)
                nn = math.hypot(q[0], q[1])
                if (nn <= n0 * (1.0 + 1e-9)) or not (lam > 1e-3):
                    known[j] = True
                    Rr[j] = q[0]
                    Rz[j] = q[1]
                    Qi[j] = q[2]
                    Qo[j] = q[3]
                    break
                lam *= 0.5
                xn0 = x0 + lam * d0
                xn1 = x1 + lam * d1
            X[j, 0] = xn0
            X[j, 1] = xn1
            if xn0 == x0 and xn1 == x1:
                frozen[j] = True
    ball_states(X, Cr, Cz, omega, oc, control, geo, tab_i, tab_o, dal, S)
    return False


@hot
def ring_forces(cpsi, spsi, ai, Qi, Fi, Ri, rig, F):
    """Force and moment (Fx, Fy, Fz, Mx, My) of the balls on the inner ring into F [N, N m]: contact
    force Qi (incl. regularisation) along the inner contact normal at angle ai, applied at the inner
    groove-centre locus of radius Ri, plus the gyroscopic friction force Fi with its moment arm rig about
    the groove centre (seed 003 Eqs. 18-19)."""
    for k in range(5):
        F[k] = 0.0
    for j in range(cpsi.shape[0]):
        nir = -math.cos(ai[j])
        niz = -math.sin(ai[j])
        fr = Qi[j] * nir - Fi[j] * niz
        fz = Qi[j] * niz + Fi[j] * nir
        c = cpsi[j]
        s = spsi[j]
        F[0] += fr * c
        F[1] += fr * s
        F[2] += fz
        F[3] += Ri * s * fz + rig * Fi[j] * s
        F[4] += -Ri * c * fz - rig * Fi[j] * c


@hot
def _residual_tol(u, omega, X0, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal, X, S, Cr, Cz, Rr, Rz, F,
                  btol):
    """Ring force F of the balls at displacement u, balls re-equilibrated from X0 (_solve_balls) to the
    ball tolerance btol where they reach it, else to BALL_TOL (a ball at the edge of contact may not
    reach a finer one), retried from the geometric start with 200 iterations if that fails; X, S: final
    ball positions and states. Returns whether the balls are in equilibrium to BALL_TOL at least."""
    _centres(u, cpsi, spsi, geo, Cr, Cz)
    _copy2(X0, X)
    n_it = max(60, Cr.shape[0] // 1000)          # 60 (typed int64, not a literal: one compilation)
    ok = _solve_balls(Cr, Cz, omega, X, oc, control, geo, tab_i, tab_o, dal, btol, n_it, S, Rr, Rz)
    if not ok and btol < BALL_TOL:
        ok = _solve_balls(Cr, Cz, omega, X, oc, control, geo, tab_i, tab_o, dal, BALL_TOL, n_it, S, Rr, Rz)
    if not ok:
        _x_start(Cr, Cz, omega, geo, tab_o, dal, X)
        ok = _solve_balls(Cr, Cz, omega, X, oc, control, geo, tab_i, tab_o, dal, BALL_TOL, n_it + 140, S,
                          Rr, Rz)
    ring_forces(cpsi, spsi, S[S_AI], S[S_QI], S[S_FI], geo[G_RI], geo[G_RIG], F)
    return ok


@hot
def _residual(u, omega, X0, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal, X, S, Cr, Cz, Rr, Rz, F):
    """_residual_tol at the ball tolerance BALL_TOL."""
    return _residual_tol(u, omega, X0, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal, X, S, Cr, Cz, Rr, Rz,
                         F, BALL_TOL)


@hot
def residual(u, omega, X0, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal):
    """(F (5,), X (Z, 2), S (NS, Z), ok): ring force of the balls at displacement u [N, N m] with the
    balls in equilibrium, started from X0."""
    Z = cpsi.shape[0]
    X = np.empty((Z, 2))
    S = np.empty((NS, Z))
    Cr = np.empty(Z)
    Cz = np.empty(Z)
    Rr = np.empty(Z)
    Rz = np.empty(Z)
    F = np.empty(5)
    ok = _residual(u, omega, X0, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal, X, S, Cr, Cz, Rr, Rz, F)
    return F, X, S, ok


@hot
def lstsq_svd(A, b, rcond):
    """Minimum-norm least-squares solution of A x = b (A n x n) through the singular value decomposition,
    singular values below rcond * s_max treated as zero: numpy.linalg.lstsq's definition, computed by
    one-sided Jacobi rotations (Demmel & Veselic 1992; Golub & Van Loan, Matrix Computations, 4th ed.,
    Sec. 8.6.3), which for a 5 x 5 matrix costs far less to compile than LAPACK's gelsd."""
    n = A.shape[1]
    U = A.copy()
    V = np.zeros((n, n))
    for i in range(n):
        V[i, i] = 1.0
    for sweep in range(60):
        rotated = False
        for p in range(n - 1):
            for q in range(p + 1, n):
                al = 0.0
                be = 0.0
                ga = 0.0
                for i in range(A.shape[0]):
                    al += U[i, p] * U[i, p]
                    be += U[i, q] * U[i, q]
                    ga += U[i, p] * U[i, q]
                if abs(ga) <= 1e-15 * math.sqrt(al * be) or ga == 0.0:
                    continue
                rotated = True
                zeta = (be - al) / (2.0 * ga)
                t = (1.0 if zeta >= 0.0 else -1.0) / (abs(zeta) + math.sqrt(1.0 + zeta * zeta))
                c = 1.0 / math.sqrt(1.0 + t * t)
                sn = c * t
                for i in range(A.shape[0]):
                    up = U[i, p]
                    U[i, p] = c * up - sn * U[i, q]
                    U[i, q] = sn * up + c * U[i, q]
                for i in range(n):
                    vp = V[i, p]
                    V[i, p] = c * vp - sn * V[i, q]
                    V[i, q] = sn * vp + c * V[i, q]
        if not rotated:
            break
    sv = np.empty(n)
    for k in range(n):
        sv[k] = math.sqrt(_dot_col(U, k, U, k))
    cut = 0.0
    for k in range(n):
        cut = max(cut, rcond * sv[k])
    x = np.zeros(n)
    for k in range(n):
        if sv[k] > cut:
            coef = 0.0
            for i in range(A.shape[0]):
                coef += U[i, k] * b[i]
            coef /= sv[k] * sv[k]                 # (u_k . b) / s_k with u_k = U[:, k] / s_k
            for i in range(n):
                x[i] += coef * V[i, k]
    return x


@hot
def _scaled(loads, F, fs, uu, us, fixed_tilt, r):
    """Scaled ring residual r = (loads + F) / fs; with a fixed tilt the tilt rows pin tx = ty = 0."""
    for k in range(5):
        r[k] = (loads[k] + F[k]) / fs[k]
    if fixed_tilt:
        r[3] = uu[3] / us[3]
        r[4] = uu[4] / us[4]


@hot
def _hybrid_oc(S, tab_i, tab_o, dal, oc):
    """Harris's criterion: the outer race controls where Q_o a_o E(k_o) cos(ai - ao) > Q_i a_i E(k_i)."""
    for j in range(S.shape[1]):
        ai = S[S_AI, j]
        ao = S[S_AO, j]
        Qi = max(S[S_QI, j], 0.0)
        Qo = max(S[S_QO, j], 0.0)
        a_i = hertz_lookup_alpha(tab_i, 0.0, dal, ai, ROW_A_COEF) * np.cbrt(Qi)
        a_o = hertz_lookup_alpha(tab_o, 0.0, dal, ao, ROW_A_COEF) * np.cbrt(Qo)
        Ei = hertz_lookup_alpha(tab_i, 0.0, dal, ai, ROW_ELL_E)
        Eo = hertz_lookup_alpha(tab_o, 0.0, dal, ao, ROW_ELL_E)
        oc[j] = Qo * a_o * Eo * math.cos(ai - ao) > Qi * a_i * Ei


@hot(inline="always")
def ring_scales(loads, geo, fixed_tilt, u, us, smax_div, fs):
    """Scales of the 5-DOF Newton solve: unknowns us (1 um, 1e-5 rad), step limits smax_div (20 um,
    1 mrad in units of us), residual scales fs (the load, moments over dm/2, at least 1 N); with a fixed
    tilt the start u gets tx = ty = 0."""
    for k in range(5):
        us[k] = 1e-6 if k < 3 else 1e-5
        smax_div[k] = 20.0 if k < 3 else 100.0
    n3 = math.sqrt(loads[0] ** 2 + loads[1] ** 2 + loads[2] ** 2)
    nm = math.sqrt(loads[3] ** 2 + loads[4] ** 2)
    Fscale = max(n3, nm / (0.5 * geo[G_DM]), 1.0)
    for k in range(5):
        fs[k] = Fscale if k < 3 else Fscale * 0.5 * geo[G_DM]
    if fixed_tilt:
        u[3] = 0.0
        u[4] = 0.0


@hot(inline="always")
def hybrid_update(S, tab_i, tab_o, dal, new_oc, oc):
    """Harris's criterion on the ball states S into oc; returns whether any ball changed its controlling
    race (new_oc: work array)."""
    _hybrid_oc(S, tab_i, tab_o, dal, new_oc)
    changed = False
    for j in range(oc.shape[0]):
        if new_oc[j] != oc[j]:
            changed = True
    if changed:
        _copy1(new_oc, oc)
    return changed


@hot(inline="always")
def ring_converged(r, tol):
    """max |r| < tol with every scaled residual finite."""
    rmax = 0.0
    rfin = True
    for k in range(5):
        if not math.isfinite(r[k]):
            rfin = False
        rmax = max(rmax, abs(r[k]))
    return rfin and rmax < tol


@hot(inline="always")
def ring_step(J, r, smax_div, step, grow):
    """Newton step of the 5-DOF solve into step (scaled units): least squares J step = -r (rcond 1e-12),
    scaled down to the limits grow * smax_div. Returns (ok, clipped); ok False (no step) where J or r is
    not finite."""
    fin = True
    for i in range(5):
        if not math.isfinite(r[i]):
            fin = False
        for k in range(5):
            if not math.isfinite(J[i, k]):
                fin = False
    if not fin:
        return False, False
    x = lstsq_svd(J, r, 1e-12)
    smax = 0.0
    for k in range(5):
        step[k] = -x[k]
        smax = max(smax, abs(step[k]) / (grow * smax_div[k]))
    if smax > 1.0:
        for k in range(5):
            step[k] /= smax
    return True, smax > 1.0


@hot(inline="always")
def step_growth(grow, clipped, lam, fast):
    """Factor on the ring step limits for the next iteration (a trust-region radius update, Nocedal &
    Wright, Numerical Optimization, 2nd ed., Alg. 4.1, with the line-search fraction lam standing for the
    agreement ratio): doubled after a clipped step accepted in full, cut to the accepted fraction (not
    below 1) after a backtracked one."""
    if lam < 1.0:
        return max(1.0, grow * lam)
    if clipped and fast:
        return min(2.0 * grow, STEP_GROW_MAX)
    return grow


@hot(inline="always")
def broyden_update(J, step, lam, rn, r):
    """Broyden's rank-one update of the ring Jacobian J (scaled units) for the accepted step s = lam step
    and residual change y = rn - r: J += (y - J s) s^T / (s^T s) (Broyden 1965; Dennis & Schnabel,
    Numerical Methods for Unconstrained Optimization and Nonlinear Equations, Eq. 8.1.5)."""
    ss = 0.0
    for k in range(5):
        ss += (lam * step[k]) ** 2
    if not ss > 0.0:
        return
    for i in range(5):
        js = 0.0
        for k in range(5):
            js += J[i, k] * lam * step[k]
        c = (rn[i] - r[i] - js) / ss
        for k in range(5):
            J[i, k] += c * lam * step[k]


@hot(inline="always")
def keep_jacobian(rn, n0, lam, fast):
    """Whether the next ring iteration reuses the (Broyden-updated) Jacobian instead of a new
    forward-difference one: after a full step that reduced |r| at least REUSE_CONTRACTION-fold (the
    Newton phase, where the difference Jacobian's own error, ~1e-3 for steps of 1e-8 m on deflections of
    ~1e-5 m, bounds the contraction anyway)."""
    return fast and lam == 1.0 and _norm5(rn) < REUSE_CONTRACTION * n0


@hot(inline="always")
def ball_tolerance(r, fast):
    """Ball tolerance of the ring-force evaluations at scaled ring residual r: BALL_TOL, and with fast
    BALL_TOL_FINE once max |r| < RING_FINE, so that the ball solves' residuals (at BALL_TOL up to
    1e-10 (m dm omega^2 / 2 + max Q) each, at 20,000 rpm several times the ring tolerance) do not hide
    the ring residual at its tolerance."""
    return BALL_TOL_FINE if fast and max_abs_or_nan(r) < RING_FINE else BALL_TOL


@hot(inline="always")
def max_abs_or_nan(r):
    """max |r_k| of a 5-vector, NaN if any r_k is not finite."""
    m = 0.0
    for k in range(5):
        m = max(m, abs(r[k])) if math.isfinite(r[k]) and math.isfinite(m) else np.nan
    return m


@hot(inline="always")
def shifted(u, k, du, out):
    """out = u with out[k] = u[k] + du."""
    _copy1(u, out)
    out[k] += du


@hot(inline="always")
def jacobian_column(J, k, rp, r):
    """Column k of the forward-difference Jacobian in scaled units (step 1e-2)."""
    for i in range(5):
        J[i, k] = (rp[i] - r[i]) / 1e-2


@hot(inline="always")
def trial_point(u, lam, step, us, un):
    """Line-search point un = u + lam step us [m, rad]."""
    for k in range(5):
        un[k] = u[k] + lam * step[k] * us[k]


@hot(inline="always")
def sufficient_decrease(rn, n0, lam):
    """Armijo-type acceptance of the line search: |rn| < (1 - 1e-4 lam) n0."""
    return _norm5(rn) < (1.0 - 1e-4 * lam) * n0


@hot(inline="always")
def accept(un, u, rn, r, Xn, X, Sn, S):
    """Take the accepted line-search point: u, r, ball positions X and states S."""
    _copy1(un, u)
    _copy1(rn, r)
    _copy2(Xn, X)
    _copy2(Sn, S)


@hot(inline="always")
def outer_controls(S):
    """Raceway control per ball (True: outer) from the state rows S_OC."""
    ocs = np.empty(S.shape[1], dtype=np.bool_)
    for j in range(S.shape[1]):
        ocs[j] = S[S_OC, j] != 0.0
    return ocs


@hot(inline="always")
def stiffness_steps():
    """Central-difference steps of the stiffness matrix: 1e-8 m, 1e-7 rad."""
    h = np.empty(5)
    for k in range(5):
        h[k] = 1e-8 if k < 3 else 1e-7
    return h


@hot(inline="always")
def stiffness_column(Kmat, k, Fp, Fm, hk):
    """Column k of K = -dF/du from the ring forces at u +- hk e_k."""
    for i in range(5):
        Kmat[i, k] = -(Fp[i] - Fm[i]) / (2.0 * hk)


@hot
def solve(omega, loads, u, fixed_tilt, control, tol, maxit, want_K, geo, cpsi, spsi, tab_i, tab_o, dal,
          X, S, Kmat, info, fast):
    """5-DOF inner-ring equilibrium F_ext + F_balls(u) = 0 by Newton's method, from u (updated in place;
    [m, rad]). Residual scaled by the load (moments by dm/2), unknowns by 1 um / 1e-5 rad; forward-difference
    Jacobian (step 1e-2 scaled units), least-squares step (rcond 1e-12) limited to 20 um / 1 mrad,
    backtracking line search (16 halvings, sufficient decrease 1e-4). Converged when every scaled ring
    residual is below tol with every ball in equilibrium (_solve_balls, ball tolerance BALL_TOL at
    least). Hybrid control: Harris's criterion re-evaluated in the
    first 15 iterations. fast: the step limits grow (step_growth) after clipped full steps once the
    raceway control is fixed, and after a full step that contracted |r| tenfold the next step uses the
    Broyden-updated Jacobian instead of a new one (keep_jacobian), and the ball tolerance tightens near
    the solution (ball_tolerance); a step from the kept Jacobian or grown limits that fails the
    line search is retried with a new Jacobian at the initial limits. fast=False: the plain Newton
    iteration. On success X (Z, 2), S (NS, Z) hold the balls and, if want_K, Kmat the 5x5 stiffness by
    central differences (steps 1e-8 m, 1e-7 rad). Returns (status, iterations); info[0] = |residual| at
    a failed line search, info[1] = max scaled residual."""
    Z = cpsi.shape[0]
    us = np.empty(5)
    smax_div = np.empty(5)
    fs = np.empty(5)
    ring_scales(loads, geo, fixed_tilt, u, us, smax_div, fs)
    oc = np.ones(Z, dtype=np.bool_)
    new_oc = np.ones(Z, dtype=np.bool_)
    Cr = np.empty(Z)
    Cz = np.empty(Z)
    Rr = np.empty(Z)
    Rz = np.empty(Z)
    F = np.empty(5)
    r = np.empty(5)
    rn = np.empty(5)
    rp = np.empty(5)
    Xn = np.empty((Z, 2))
    Sn = np.empty((NS, Z))
    Xp = np.empty((Z, 2))
    Sp = np.empty((NS, Z))
    up = np.empty(5)
    un = np.empty(5)
    J = np.empty((5, 5))
    step = np.empty(5)
    _centres(u, cpsi, spsi, geo, Cr, Cz)
    X0 = np.empty((Z, 2))
    _x_start(Cr, Cz, omega, geo, tab_o, dal, X0)
    # the balls from the geometric start: _residual's retry from that start, at once
    _copy2(X0, X)
    n_it = max(200, Z // 1000)
    ok = _solve_balls(Cr, Cz, omega, X, oc, control, geo, tab_i, tab_o, dal, BALL_TOL, n_it, S, Rr, Rz)
    ring_forces(cpsi, spsi, S[S_AI], S[S_QI], S[S_FI], geo[G_RI], geo[G_RIG], F)
    _scaled(loads, F, fs, u, us, fixed_tilt, r)
    it = 0
    converged = False
    grow = 1.0
    reuse = False
    for it in range(1, maxit + 1):
        if control == CTRL_HYBRID and it <= 15 and hybrid_update(S, tab_i, tab_o, dal, new_oc, oc):
            reuse = False
            _copy2(X, X0)
            ok = _residual(u, omega, X0, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal, X, S, Cr, Cz,
                           Rr, Rz, F)
            _scaled(loads, F, fs, u, us, fixed_tilt, r)
        if ok and ring_converged(r, tol):
            converged = True
            break
        btol = ball_tolerance(r, fast)
        if not reuse:
            for k in range(5):
                shifted(u, k, 1e-2 * us[k], up)
                _residual_tol(up, omega, X, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal, Xp, Sp, Cr, Cz, Rr,
                              Rz, F, btol)
                _scaled(loads, F, fs, up, us, fixed_tilt, rp)
                jacobian_column(J, k, rp, r)
        has_step, clipped = ring_step(J, r, smax_div, step, grow)
        if not has_step:
            break                   # no least-squares step
        lam = 1.0
        n0 = _norm5(r)
        accepted = False
        okn = False
        for _ in range(16):
            trial_point(u, lam, step, us, un)
            okn = _residual_tol(un, omega, X, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal, Xn, Sn, Cr, Cz,
                                Rr, Rz, F, btol)
            _scaled(loads, F, fs, un, us, fixed_tilt, rn)
            if okn and sufficient_decrease(rn, n0, lam):
                accepted = True
                break
            if reuse:
                break               # no decrease along the kept Jacobian's step: a new Jacobian
            lam *= 0.5
        if not accepted:
            if reuse or grow > 1.0:
                # a kept Jacobian's step, or one from grown limits, that does not decrease |r|: again
                # with a new Jacobian and the initial limits
                reuse = False
                grow = 1.0
                continue
            info[0] = n0
            return LINE_SEARCH_FAILED, it
        reuse = keep_jacobian(rn, n0, lam, fast)
        if reuse:
            broyden_update(J, step, lam, rn, r)
        accept(un, u, rn, r, Xn, X, Sn, S)
        ok = okn
        if not (control == CTRL_HYBRID and it < 15):
            grow = step_growth(grow, clipped, lam, fast)     # fixed limits while the raceway control may change
    if not converged:
        info[1] = max_abs_or_nan(r)
        return NOT_CONVERGED, it
    if want_K:
        _copy2(stiffness(u, omega, X, outer_controls(S), control, geo, cpsi, spsi, tab_i, tab_o, dal), Kmat)
    return OK, it


@hot
def stiffness(u, omega, X, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal):
    """5x5 bearing stiffness K_kl = d(load_k)/d(u_l) [N/m, N/rad, N m/m, N m/rad] at ring displacement u
    with balls X (Z, 2) and raceway control oc: central differences (steps 1e-8 m, 1e-7 rad) of the ring
    force, every ball re-equilibrated from X."""
    Z = cpsi.shape[0]
    h = stiffness_steps()
    Kmat = np.empty((5, 5))
    up = np.empty(5)
    Fp = np.empty(5)
    Fm = np.empty(5)
    Xp = np.empty((Z, 2))
    Sp = np.empty((NS, Z))
    Cr = np.empty(Z)
    Cz = np.empty(Z)
    Rr = np.empty(Z)
    Rz = np.empty(Z)
    for k in range(5):
        shifted(u, k, h[k], up)
        _residual(up, omega, X, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal, Xp, Sp, Cr, Cz, Rr, Rz, Fp)
        shifted(u, k, -h[k], up)
        _residual(up, omega, X, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal, Xp, Sp, Cr, Cz, Rr, Rz, Fm)
        stiffness_column(Kmat, k, Fp, Fm, h[k])
    return Kmat
